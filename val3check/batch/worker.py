"""One case, run where it lands: a child process under the watchdog (runner.py), here or on a Dask worker.

The case's files are written under a private temporary folder that mirrors their absolute
paths, and the run happens with the current folder set to the mirror of the folder the batch
was started from: display paths in the report are then those of a single `val3check sim`, and
the mirror's prefix is taken out of everything that comes back (absolute paths read as on the
machine that made the case). The steps are the single run's: both run `simulation.case.run_case`.
Any exception is the case's result ("crash"), never the batch's."""

from __future__ import annotations

import copy
import os
import shutil
import statistics
import tempfile
import time
import traceback
import zlib
from dataclasses import dataclass, field

from .cases import Case
from .outputs import case_outputs

MAX_CAUSES = 8
VERDICTS = ("pass", "fail", "not-run", "crash", "over-budget", "skipped")
STEP = None  # step(name) as a case goes on ("lint", "run", "report"): set by runner.py for its watchdog


@dataclass(frozen=True)
class CaseSummary:
    """What the summary shows of a case: small, picklable, deterministic (no wall time)."""

    key: tuple
    name: str  # file stem of the case's outputs (Case.name)
    app: str
    app_name: str
    arm: str  # --robot as given ("" for the default)
    model: str  # the arm model run ("none" without one)
    scenario: str
    cell: str
    overrides: tuple  # ((key, value), ...)
    verdict: str  # one of VERDICTS
    errors: int = 0  # runtime diagnostics of severity error
    warnings: int = 0
    cycle_time: float | None = None  # s: median of the verdict's cycle (arm_record.main_cycle)
    cycles: int = 0
    cycle_range: tuple | None = None  # s: (lowest, highest) cycle_time if the assumed accelerations are off by 2×
    end: str = ""  # how the run ended (SimResult end reason)
    reason: str = ""  # why the verdict is not "pass": the first failing diagnostic, the error, the crash
    # each failing diagnostic: (code, severity, path, line, col, time_us, task, message), at most
    # MAX_CAUSES (sim --explore groups failures by them; not in the summary's JSON)
    causes: tuple = ()
    cycle_max: float | None = None  # s: the longest of the verdict's cycles

    def as_dict(self) -> dict:
        return {"application": self.app, "name": self.app_name, "arm": self.arm or None, "model": self.model,
                "scenario": self.scenario or None, "cell": self.cell or None, "overrides": dict(self.overrides),
                "verdict": self.verdict, "errors": self.errors, "warnings": self.warnings,
                "cycle_time": self.cycle_time, "cycles": self.cycles,
                "cycle_time_range": None if self.cycle_range is None else list(self.cycle_range), "end": self.end or None,
                "reason": self.reason or None, "report": self.name}


@dataclass
class CaseOutcome:
    summary: CaseSummary
    # file suffix (".json") -> the file's bytes, zlib-compressed for the way back (a 60 s run's JSON
    # report is about 1.2 MB, 0.35 MB compressed at level 1, in about 10 ms)
    outputs: dict[str, bytes] = field(default_factory=dict)
    wall_s: float = 0.0  # for benchmarks; never in the summary
    cpu_s: float = 0.0  # CPU time of the process that ran the case, for benchmarks

    def files(self) -> dict[str, bytes]:
        return {suffix: zlib.decompress(data) for suffix, data in self.outputs.items()}


def summary_of(case: Case, verdict: str, reason: str = "", **kw) -> CaseSummary:  # noqa: ANN003
    return CaseSummary(key=case.key(), name=case.name(), app=case.app, app_name=case.app_name, arm=case.arm,
                       model=kw.pop("model", "none"), scenario=case.scenario, cell=case.cell,
                       overrides=tuple(sorted(case.overrides.as_dict().items())), verdict=verdict, reason=reason, **kw)


def run_case(case: Case) -> CaseOutcome:
    start, cpu = time.perf_counter(), time.process_time()
    here = os.getcwd()
    tmp = tempfile.mkdtemp(prefix="val3check-case-")
    mirror = os.path.join(tmp, "m")
    try:
        _write_mirror(case, mirror)
        cwd = _mirrored(mirror, case.cwd)
        os.makedirs(cwd, exist_ok=True)
        os.chdir(cwd)
        outcome = _run(case, mirror)
    except Exception as exc:  # noqa: BLE001 - a crashing case is reported, the batch goes on
        last = traceback.extract_tb(exc.__traceback__)[-1:]
        where = f" (at {os.path.basename(last[0].filename)}:{last[0].lineno})" if last else ""
        outcome = CaseOutcome(summary_of(case, "crash", f"{type(exc).__name__}: {exc}{where}"))
    finally:
        os.chdir(here)
        shutil.rmtree(tmp, ignore_errors=True)
    outcome = _unmirrored(outcome, mirror)
    outcome.wall_s = time.perf_counter() - start
    outcome.cpu_s = time.process_time() - cpu
    return outcome


def _write_mirror(case: Case, mirror: str) -> None:
    """The case's files under `mirror`, then the stand-ins of the files its run finds and refuses
    (a size, no content), then its symbolic links, their absolute targets mirrored too (not those
    under /proc, /sys or /dev: the gate refuses them by name, and they are the same everywhere)."""
    from ..confine import is_special

    for path, data in case.files:
        target = _mirrored(mirror, path)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        with open(target, "wb") as fh:
            fh.write(data)
    for path, size in case.stubs:
        target = _mirrored(mirror, path)
        if not os.path.lexists(target):
            os.makedirs(os.path.dirname(target), exist_ok=True)
            with open(target, "wb") as fh:
                fh.truncate(size)  # sparse: no byte of the refused file travels
    for path, to in case.links:
        where = _mirrored(mirror, path)
        if os.path.lexists(where):
            continue  # the loader took this path as a folder: files were written below it
        os.makedirs(os.path.dirname(where), exist_ok=True)
        os.symlink(_mirrored(mirror, to) if os.path.isabs(to) and not is_special(to) else to, where)


def _mirrored(mirror: str, path: str) -> str:
    drive, rest = os.path.splitdrive(os.path.abspath(path))
    return os.path.join(mirror, drive.replace(":", ""), rest.lstrip("\\/"))


def _unmirrored(outcome: CaseOutcome, mirror: str) -> CaseOutcome:
    """Absolute paths as on the machine that made the case."""
    s = outcome.summary
    fix = {f: getattr(s, f).replace(mirror, "") for f in ("reason", "model", "end")}
    fix["causes"] = tuple(c[:2] + (c[2].replace(mirror, ""),) + c[3:] for c in s.causes)
    summary = CaseSummary(**{**s.__dict__, **fix})
    prefix = mirror.encode("utf-8")
    return CaseOutcome(summary, {k: zlib.compress(v.replace(prefix, b""), 1) for k, v in outcome.outputs.items()})


def _run(case: Case, mirror: str) -> CaseOutcome:
    """The case as the single run runs it (simulation/case.py), its files read from the mirror."""
    from .. import __version__
    from ..diagnostics import Severity
    from ..lint import display_path
    from ..reporting.sim_report import build_report
    from ..rules.catalogue import catalogue
    from ..simulation import case as sim_case

    settings = copy.deepcopy(case.settings)
    settings.disk_roots = [_mirrored(mirror, d) for d in settings.disk_roots]
    if settings.root:
        settings.root = _mirrored(mirror, settings.root)
    ov, opts = case.overrides, case.options
    spec = sim_case.CaseSpec(
        _mirrored(mirror, case.app_path), settings, exact=True,
        robot=display_path(_mirrored(mirror, case.robot_path)) if case.robot_path else (case.arm or None),
        scenario=display_path(_mirrored(mirror, case.scenario_path)) if case.scenario_path else None,
        # the cell as `sim --cell` chooses it: the case's file, none, or the one beside the application
        cell=display_path(_mirrored(mirror, case.cell_path)) if case.cell_path else (case.cell or None),
        monitor_speed=ov.monitor_speed, duration=ov.duration or opts.duration, cycles=ov.cycles or opts.cycles,
        max_wall=opts.max_wall, max_lines=opts.max_lines, max_memory_mb=opts.max_memory_mb, step=STEP)
    done = sim_case.run_case(spec)
    model = getattr(done.model, "name", None) or "none"
    if done.refused is not None:
        d = done.errors[0] if done.errors else None
        where = f"{d.path}:{d.line}:{d.col}: {d.code} {d.message}" if d is not None else ""
        reason = {sim_case.UNREADABLE: "the application could not be read" + (f": {where}" if where else ""),
                  sim_case.LINT_ERRORS: f"{len(done.errors)} lint error(s), the first: {where}",
                  sim_case.ROBOT: f"--robot: {done.message}",
                  sim_case.SCENARIO: f"bad scenario: {done.message}"}.get(done.refused, done.message)
        return CaseOutcome(summary_of(case, "not-run", reason, **({"model": model} if done.refused == sim_case.SCENARIO
                                                                  else {})))
    result = done.result
    if STEP is not None:
        STEP("report")
    report = build_report(result, settings, catalogue(), __version__)
    errors_n = sum(1 for d in report.diagnostics if d.severity >= Severity.ERROR)
    warnings_n = sum(1 for d in report.diagnostics if d.severity == Severity.WARNING)
    failing = [] if opts.fail_on == "never" else [d for d in report.diagnostics
                                                  if d.severity >= Severity.parse(opts.fail_on)]
    reason = ""
    if failing:
        d = failing[0]
        loc = f"{d.path}:{d.line}:{d.col}" if d.line else d.path
        reason = f"{loc}: {d.code} {d.severity.label}: {d.message}"
    cycle_time, cycles, spread = _cycle(result.motion)
    causes = tuple((d.code, d.severity.label, d.path, d.line, d.col, d.time_us, d.task or "", d.message)
                   for d in failing[:MAX_CAUSES])
    summary = summary_of(case, "fail" if failing else "pass", reason, model=model, errors=errors_n,
                         warnings=warnings_n, cycle_time=cycle_time, cycles=cycles, cycle_range=spread,
                         end=result.end_reason, causes=causes, cycle_max=_longest(result.motion))
    return CaseOutcome(summary, case_outputs(report, opts.case_reports, opts.fail_on) if opts.reports else {})


def _longest(motion) -> float | None:  # noqa: ANN001
    """The longest of the verdict's cycles (sim --explore's bound, [explore] max_cycle_time)."""
    if motion is None:
        return None
    from ..simulation.arm_record import main_cycle

    st = main_cycle(motion.cycles)
    return None if st is None or not st.times else round(max(st.times), 6)


def _cycle(motion) -> tuple[float | None, int, tuple | None]:  # noqa: ANN001
    """The median of the verdict's cycle (arm_record.main_cycle), its count, and its range if the
    assumed accelerations are off (ArmRun.acceleration_range; None when measured)."""
    if motion is None:
        return None, 0, None
    from ..simulation.arm_record import main_cycle

    st = main_cycle(motion.cycles)  # the verdict's (reporting/html/from_run.py, sim_junit.py)
    if st is None:
        return None, 0, None
    spread = motion.acceleration_range.cycle_time(st.task) if motion.acceleration_range is not None else None
    return (round(statistics.median(st.times), 6), st.count,
            None if spread is None else (round(spread[0], 6), round(spread[1], 6)))
