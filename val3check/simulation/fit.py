"""Accelerations fitted to a cycle time measured on the real cell: `val3check robots fit` (issue 23).

Stäubli publishes no joint accelerations (docs/motion.md, "Accelerations"): the models assume
them, and the reports give the cycle time with the range it takes if they are off by 2×. A user
who measured the cycle of the application on the cell fixes them: the run's path is re-timed
with every acceleration and deceleration times a factor f (motion/retime.py, as for the range)
until the cycle time is the measured one, then the application is run again with the fitted
model to check it (and f corrected from that run when the re-timing was off by more than
CHECK_TOL). One number measured fixes one number: f is the same for every axis, the speeds are
unchanged. The result is a robot file (robot/overrides.py) whose `accelerations` are the fitted
values: measured, so the reports give no range with it.

    fit = fit_accelerations(ws, app, model, scenario, measured_s, options)
    text = robot_file(fit, arm_spec, base_values)
    code = command(app_path, robot_spec, measured_s, ...)   # `val3check robots fit`: an exit code
"""

from __future__ import annotations

import math
import os
import statistics
import sys
from dataclasses import dataclass

from ..motion.retime import Stretches, retimed
from .collect import task_cycles
from .moving_arm import MovingArm
from .run import SimOptions, run_machine

F_MIN, F_MAX = 1.0 / 64.0, 64.0  # the factors tried: accelerations from 1/64 to 64 times the model's
CHECK_TOL = 1e-3  # the fitted model's own run within this (relative) of the measured cycle
MAX_RUNS = 4  # runs of the application, the first one included


class FitError(ValueError):
    """The measured cycle cannot be fitted (no cycle in the run, or out of the accelerations' reach)."""


@dataclass
class Fit:
    """A fitted model: `factor` times the accelerations of `base`; `simulated` the cycle time of
    the fitted model's own run (the task `task`, loop at `marker`); `runs` of the application."""

    base: object  # robot.RobotModel as given
    model: object  # the fitted RobotModel (accelerations measured: no range)
    factor: float
    measured: float
    simulated: float
    task: str
    marker: tuple
    runs: int


def _run(ws, app, model, scenario, options: SimOptions):
    """Run the application with `model`: (its machine, motion queue and motion records) or a FitError."""
    opts = SimOptions(duration=options.duration, max_wall=options.max_wall, max_lines=options.max_lines,
                      max_memory_mb=options.max_memory_mb, disk_roots=options.disk_roots, robot=model,
                      cycles=options.cycles)
    machine, _ = run_machine(ws, app, opts, scenario)
    arm = machine.arm
    queue = arm.queue_in_use if isinstance(arm, MovingArm) else None
    if queue is None:
        raise FitError("the application moves no arm: there is no cycle to fit")
    return machine, queue, arm.live.records(arm, queue, arm.queue_time(machine.end_time))  # (collect's: the same)


def _cycle(machine, records, task: str | None = None):
    """(task, loop marker, median cycle time) of `task` in the run of `machine` (its records, or
    the same re-timed), or of the task with the most complete cycles (the verdict's); None when
    it has none."""
    stats = task_cycles(machine, records)
    if task is None:
        looping = [st for st in stats.values() if st.count]
        if not looping:
            return None
        best = min(looping, key=lambda st: (-st.count, st.task))
        task = best.task
    st = stats.get(task)
    if st is None or not st.times:
        return None
    return task, st.marker, statistics.median(st.times)


def fit_accelerations(ws, app, model, scenario, measured: float, options: SimOptions) -> Fit:
    """The model whose accelerations (all × one factor) give the measured cycle (module docstring)."""
    if not (measured > 0 and math.isfinite(measured)):
        raise FitError("the measured cycle must be a positive number of seconds")
    machine, queue, records = _run(ws, app, model, scenario, options)
    found = _cycle(machine, records)
    if found is None:
        raise FitError(f"no complete cycle in the run ({options.duration:g} s simulated): a longer --duration, or "
                       "an application whose task loops on its motions (docs/motion.md, \"Cycle time\")")
    task, marker, _ = found
    log_m = math.log(measured)
    stretches = Stretches(queue)  # the same for every factor tried: the run's profile no longer changes

    def g(log_f: float) -> float:
        """log(cycle time at accelerations × e^log_f) - log(measured), by re-timing the run."""
        c = _cycle(machine, retimed(queue, records, math.exp(log_f), stretches=stretches)[0], task)
        if c is None:
            raise FitError("the re-timed run has no complete cycle")
        return math.log(c[2]) - log_m

    lo, hi = math.log(F_MIN), math.log(F_MAX)
    g_lo, g_hi = g(lo), g(hi)
    if g_hi > 0:
        raise FitError(f"the measured {measured:g} s is shorter than the run's cycle with accelerations {F_MAX:g} times "
                       f"the model's ({measured * math.exp(g_hi):.4g} s): the speeds or the waits are too slow for it")
    if g_lo < 0:
        raise FitError(f"the measured {measured:g} s is longer than the run's cycle with accelerations {F_MAX:g} times "
                       f"smaller ({measured * math.exp(g_lo):.4g} s): the waits, not the arm, make the cycle")
    log_f = _solve(g, lo, hi, g_lo, g_hi)
    slope = _slope(g, log_f)
    runs, factor, simulated = 1, math.exp(log_f), math.nan
    while runs < MAX_RUNS:  # the fitted model's own run (the program may wait differently)
        fitted = _fitted(model, factor, measured)
        run, _, recs = _run(ws, app, fitted, scenario, options)
        runs += 1
        c = _cycle(run, recs, task)
        if c is None:
            raise FitError("the fitted model's run has no complete cycle of the task")
        simulated = c[2]
        err = math.log(simulated) - log_m
        if abs(err) <= CHECK_TOL or slope >= 0:
            break
        log_f -= err / slope
        factor = math.exp(log_f)
    return Fit(model, _fitted(model, factor, measured), factor, measured, simulated, task, marker, runs)


def _solve(g, lo: float, hi: float, g_lo: float, g_hi: float) -> float:
    """The root of the decreasing g on [lo, hi] (regula falsi, Illinois): log f."""
    x = lo
    side = 0
    for _ in range(60):
        x = (lo * g_hi - hi * g_lo) / (g_hi - g_lo) if g_hi != g_lo else (lo + hi) / 2
        gx = g(x)
        if abs(gx) < 1e-7 or hi - lo < 1e-9:
            return x
        if gx > 0:
            lo, g_lo = x, gx
            if side == -1:
                g_hi /= 2
            side = -1
        else:
            hi, g_hi = x, gx
            if side == 1:
                g_lo /= 2
            side = 1
    return x


def _slope(g, log_f: float, h: float = 0.05) -> float:
    """d log(cycle) / d log(f) around log_f (negative: more acceleration, a shorter cycle)."""
    return (g(log_f + h) - g(log_f - h)) / (2 * h)


def _fitted(model, factor: float, measured: float):
    """`model` with every acceleration × factor, given as measured values."""
    acc = [round(a * factor, 6) for a in model.accelerations]
    return model.with_accelerations(acc, note=f"fitted to a measured cycle of {measured:g} s (val3check robots fit): "
                                              f"the model's × {factor:.6g}")


def robot_file(fit: Fit, arm: str, base: dict | None = None, where: str = "") -> str:
    """The robot file (robot/overrides.py) of the fitted model: `arm` as the file names it, the
    base robot file's values (`base`: its name and [assume], when the model came from one) with
    the fitted accelerations in place of theirs; `where` says what was measured."""
    base = base or {}
    assume = {k: v for k, v in (base.get("assume") or {}).items() if k not in ("accelerations", "ramp_s")}
    assume["accelerations"] = [round(a, 6) for a in fit.model.accelerations]
    units = ", ".join(f"j{i + 1} {a:g} {'mm/s²' if u == 'mm' else '°/s²'}"
                      for i, (a, u) in enumerate(zip(fit.model.accelerations, fit.model.joint_units)))
    lines = [
        f"# Accelerations fitted by `val3check robots fit` to a cycle of {fit.measured:g} s measured on the cell{where}.",
        f"# Every axis's acceleration and deceleration is the model's ({fit.base.name}) × {fit.factor:.6g}: {units};",
        f"# the fitted model runs the cycle (task {fit.task}) in {fit.simulated:.6g} s. One measured cycle fixes one",
        "# number, not each axis (docs/motion.md, \"Accelerations\"). Measured values: the reports give no range.",
        f"arm = {_toml(arm)}",
    ]
    if base.get("name") is not None:
        lines.append(f"name = {_toml(base['name'])}")
    lines.append("")
    lines.append("[assume]")
    lines += [f"{k} = {_toml(v)}" for k, v in assume.items()]
    return "\n".join(lines) + "\n"


def _toml(v) -> str:
    """A TOML value: strings, numbers, booleans, lists and inline tables of them."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v) if isinstance(v, int) else f"{v:.10g}" if math.isfinite(v) else "nan"
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{k} = {_toml(x)}" for k, x in v.items()) + " }"
    raise TypeError(f"no TOML form for {v!r}")


def command(app_path: str, robot_spec: str | None, measured: float | None, scenario_path: str | None,
            duration: float, cycles: int | None, output: str | None) -> int:
    """`val3check robots fit APP --robot ROBOT --measured-cycle S [--scenario FILE] [-o FILE]`: the
    exit code (0, or 2 for a usage error, said on standard error)."""
    from ..config import Settings
    from ..diagnostics import Severity
    from ..lint import printable_path, run
    from ..robot import RobotError
    from .robot_choice import choose_sim_robot
    from .scenario import ScenarioError, load_scenario

    def fail(message: str) -> int:
        print(f"val3check robots fit: error: {printable_path(message)}", file=sys.stderr)
        return 2

    if measured is None:
        return fail("--measured-cycle SECONDS is needed: the cycle time measured on the cell")
    if not 0 < duration <= 86400.0 or (cycles is not None and cycles < 1):
        return fail("--duration must be a positive number of seconds, --cycles a positive number")
    outcome = run([app_path], Settings())
    apps = [outcome.workspace.apps[k] for k in outcome.workspace.targets]
    if len(apps) != 1:
        return fail(f"{app_path}: one application is needed ({len(apps)} found)")
    app = apps[0]
    errors = [d for d in outcome.result.diagnostics if d.severity is not None and d.severity >= Severity.ERROR]
    if errors:
        return fail(f"{app.name}: not run: {len(errors)} error(s) (val3check lint); fix them first")
    try:
        model, _ = choose_sim_robot(robot_spec, app.path)
        if model is None:
            return fail("--robot ROBOT is needed (no arm model for the application)")
        scenario = load_scenario(scenario_path) if scenario_path else None
    except (RobotError, ScenarioError) as exc:
        return fail(str(exc))
    options = SimOptions(duration=duration, max_wall=max(60.0, 10 * duration), cycles=cycles)
    try:
        fit = fit_accelerations(outcome.workspace, app, model, scenario, measured, options)
    except FitError as exc:
        return fail(str(exc))
    base, arm = _base_file(robot_spec, output)
    where = f" (application {app.name}" + (f", scenario {os.path.basename(scenario_path)}" if scenario_path else "") + ")"
    text = robot_file(fit, arm or model.name, base, where)
    if output:
        with open(output, "w", encoding="utf-8") as fh:
            fh.write(text)
    else:
        sys.stdout.write(text)
    print(f"val3check robots fit: {model.name}: a cycle of {measured:g} s (task {fit.task}) with every acceleration "
          f"× {fit.factor:.4g}; the fitted model's run: {fit.simulated:.4f} s ({fit.runs} runs)"
          + (f"; wrote {printable_path(output)} (`val3check sim APP --robot {printable_path(output)}`)" if output else ""),
          file=sys.stderr)
    return 0


def _base_file(robot_spec: str | None, output: str | None) -> tuple[dict, str | None]:
    """The robot file named by --robot (its values, and its arm as the new file must name it), or
    ({}, the spec as the new file must name it: a path relative to the new file)."""
    import tomllib

    if not robot_spec:
        return {}, None
    out_dir = os.path.dirname(os.path.abspath(output)) if output else os.getcwd()
    spec, base = robot_spec, {}
    if robot_spec.lower().endswith(".toml"):
        with open(robot_spec, "rb") as fh:
            base = tomllib.load(fh)
        spec = str(base.get("arm", ""))
        if spec.lower().endswith((".urdf", ".xml", ".cfx")) and not os.path.isabs(spec):
            spec = os.path.join(os.path.dirname(os.path.abspath(robot_spec)), spec)
    if spec.lower().endswith((".urdf", ".xml", ".cfx")):
        spec = os.path.relpath(os.path.abspath(spec), out_dir)
    return base, spec
