"""Assemble a run of the virtual controller and run it.

    result = simulate(workspace, app, SimOptions(duration=10.0, robot=model), scenario)

The application must have been loaded and its programs parsed (the `sim` command lints it
first, in-process). Assembling a run means, in this order: the registry of instructions (the
interpreter's chapters, then motion's), the arm (a `motion` arm on the chosen model), the
machine, its subsystems (the cell and its scenario first, then the arm's motion), the
scenario's settings. Nothing here writes files: reports are `val3check.reporting`.
"""

from __future__ import annotations

import time
from typing import Any

from ..interpretation import code_support, not_simulated, waiting
from ..interpretation.chapters import (
    ch02_variables,
    ch03_simple_types,
    ch04_user_page,
    ch05_tasks,
    ch06_libraries,
    ch08_controller,
    ch09_geometry,
)
from ..interpretation.machine import Budgets, Machine
from ..interpretation.registry import Registry
from ..interpretation.scheduler import EndRun
from ..lengths import INCH_MM
from ..light_dataclass import dataclass, field
from ..loading.model import Application, Workspace
from ..motion import history
from ..rules import codes
from . import ch09_latch, ch10_motion, ch11_absolute, ch11_alter, ch11_compliance, ch11_continuous, ch11_licences
from .budget import RUN_SHARE, RunBudget
from .collect import collect
from .folding import fold
from .moving_arm import MovingArm
from .result import SimResult
from .retention import release
from .scenario import Scenario, apply_scenario

# What the generated code calls, then the chapters of the manual, in order.
INTERPRETER_MODULES = (code_support, waiting, not_simulated, ch02_variables, ch03_simple_types, ch04_user_page,
                       ch05_tasks, ch06_libraries, ch08_controller, ch09_geometry)
MOTION_MODULES = (ch10_motion, ch09_latch, ch11_licences, ch11_absolute, ch11_continuous, ch11_compliance,
                  ch11_alter)


@dataclass
class SimOptions:
    """How to run a simulation: budgets, the arm model, --cycles, progress, the collision checks."""
    duration: float = 60.0  # simulated seconds
    max_wall: float = 60.0  # wall-clock seconds
    max_lines: int = 50_000_000
    max_transcript: int = 10_000
    max_memory_mb: float = 512.0  # growth of the process, loading included (interpretation/memory_budget.py)
    wall_clock: Any = time.monotonic  # what max_wall is measured with (tests: a clock of their own)
    # the share of max_wall the simulation may take; the collision checks and reports have the rest
    # (budget.py: the budgets cover every phase)
    run_share: float = RUN_SHARE
    # when the command started, on wall_clock (None: when the machine is made): --max-wall then
    # covers the lint and the arm's loading too
    started: float | None = None
    # the budgets also cover the reports written from the result (SimResult.budget): the `sim`
    # command and a batch's case write them at once; a caller of the API who writes them later
    # leaves this off
    reports_in_budget: bool = False
    disk_roots: list[str] = field(default_factory=list)
    # the arm model (val3check.robot.RobotModel) or None: see robot_choice.choose_sim_robot
    robot: Any = None
    cycles: int | None = None  # --cycles N: end the run when the arm starts cycle N + 1
    # progress(simulated seconds, motions_done()), called now and then while the run goes (the
    # progress display of `sim` on a terminal: reporting/progress.py)
    progress: Any = None
    # collision checks (docs/cell.md): `collisions` checks every motion of the arm (against itself
    # without a cell); `cell` the cell file (implies collisions), `cell_found` how it was chosen
    # ("option", "found", "disabled": collision_run.choose_cell)
    collisions: bool = False
    cell: str | None = None
    cell_found: str = "option"


def build_registry() -> Registry:
    """The registry of every instruction the virtual controller runs: the interpreter's chapters, then chapter 10."""
    registry = Registry()
    for module in INTERPRETER_MODULES + MOTION_MODULES:
        module.register(registry)
    return registry


def build_machine(ws: Workspace, app: Application, options: SimOptions, *, registry: Registry | None = None,
                  arm: Any = None) -> Machine:
    """A machine ready to load the application. `registry` and `arm` (an `Arm` port that is also
    a `Subsystem`) replace the standard ones (tests, tools)."""
    budgets = Budgets(duration_us=int(round(options.duration * 1_000_000)), wall_s=options.max_wall,
                      max_lines=options.max_lines, max_transcript=options.max_transcript,
                      max_memory_mb=options.max_memory_mb, wall_clock=options.wall_clock,
                      run_share=options.run_share)
    arm = arm if arm is not None else MovingArm(options.robot, cycles=options.cycles)
    if isinstance(arm, MovingArm) and arm.has_model and ch11_continuous.uses_reset_turn(ws, app):
        ch11_continuous.set_continuous(arm, True)  # the continuous axis option is in use (11.5)
    machine = Machine(ws, app, registry or build_registry(), arm, budgets=budgets, disk_roots=options.disk_roots)
    if options.started is not None:
        machine.wall_start = options.started
    if hasattr(arm, "bind"):
        arm.bind(machine.controller)  # its power and monitor speed (chapter 8)
    machine.add_subsystem(arm)  # after the cell: inputs are refreshed before the arm moves
    machine.cell.budget.also.append(history.over)  # the profile's temporary file (motion/history.py)
    if options.progress is not None:
        report = options.progress

        def motions_done() -> int:
            """Commands of the program the arm completed so far."""
            queue = arm.queue_in_use if isinstance(arm, MovingArm) else None
            return queue.completed if queue is not None else 0

        def progress(now_us: int) -> None:
            """The progress line at simulated time now_us."""
            report(now_us / 1e6, motions_done)

        machine.progress = progress
    return machine


def simulate(ws: Workspace, app: Application, options: SimOptions | None = None,
             scenario: Scenario | None = None) -> SimResult:
    """Run the application `app` of `ws` (loaded and parsed) with `options` and `scenario`: its SimResult."""
    machine, result = run_machine(ws, app, options, scenario)
    release(machine)  # what it kept per command, now that the record is taken (retention.py)
    return result


def run_machine(ws: Workspace, app: Application, options: SimOptions | None = None,
                scenario: Scenario | None = None) -> tuple[Machine, SimResult]:
    """`simulate`, and the machine that ran (for the tools that look at its arm: fit.py)."""
    options = options or SimOptions()
    machine = build_machine(ws, app, options)
    checks = _collision_setup(app, options, machine)
    try:
        machine.load_main()
        if scenario is not None:
            apply_scenario(machine, scenario)
    except (EndRun, MemoryError, RecursionError) as stop:  # a budget reached before the first line ran
        machine.end_reason = (stop.reason if isinstance(stop, EndRun) else f"budget:{stop}"
                              if isinstance(stop, MemoryError)
                              else "budget:the application's values are nested too deeply for the simulator")
        return machine, _finish(machine, app, options, checks)
    machine.run()
    return machine, _finish(machine, app, options, checks)


def _finish(machine: Machine, app: Application, options: SimOptions, checks) -> SimResult:
    """The run's record, its collision checks within what is left of its budgets, its findings
    folded (folding.py)."""
    budget = RunBudget.of(machine)
    result = _collisions(collect(machine), app, options, checks, budget)
    result.diagnostics = fold(result.diagnostics, app.path, result.sim_time_us)
    result.budget = budget if options.reports_in_budget else None
    return result


def _collision_setup(app: Application, options: SimOptions, machine: Machine):
    """(cell, R030 diagnostics, value watch, arm model) when the run checks collisions, else None;
    the watch reads the cell's frames and tools as the run goes (at each motion instruction, each
    time the arm advances)."""
    arm = machine.arm
    if not (options.collisions or options.cell) or not getattr(arm, "has_model", False):
        return None
    from . import collision_run

    # the cell's meshes are read within the run's budgets (memory priced before trimesh builds them)
    budgets = machine.budgets

    def out_of_time() -> bool:  # --max-wall, on the run's own clock
        return budgets.wall_clock() > machine.wall_start + budgets.wall_s

    cell, diags = (collision_run.load_cell(options.cell, app, found=options.cell_found == "found",
                                           budget=machine.cell.budget, out_of_time=out_of_time) if options.cell
                   else (None, []))
    watch = collision_run.ValueWatch(cell, machine)
    if isinstance(arm, MovingArm):
        arm.watch(watch)
    return cell, diags, watch, arm.model, arm


def _phase(progress: Any):
    """The collision checks' `on_motion` for a progress display that shows phases, else None."""
    phase = getattr(progress, "phase", None)
    if phase is None:
        return None
    return lambda done, total: phase(f"checking collisions: motion {done + 1} of {total}")


def _collisions(result: SimResult, app: Application, options: SimOptions, checks, budget: RunBudget) -> SimResult:
    """Check the motions of the run (SimResult.collision) and add the findings."""
    if checks is None:
        if options.cell and result.motion is None:  # said, not silently ignored
            from ..diagnostics import Diagnostic

            result.diagnostics.append(Diagnostic(
                codes.COLLISIONS_NOT_CHECKED, f"the cell {options.cell} is not checked: the run has no arm model (--robot NAME)",
                app.path, 0, 0, time_us=result.sim_time_us, task="", program=""))
        return result
    from . import collision_run

    cell, diags, watch, model, arm = checks
    found = list(diags)
    if result.motion is not None:
        unit_mm = 1.0 if getattr(app, "millimeter_unit", True) else INCH_MM
        how = options.cell_found if options.cell or options.cell_found == "disabled" else "none"
        run, more = collision_run.check_run(result.motion, cell, watch, model, cell_path=options.cell, cell_found=how,
                                            app_unit_mm=unit_mm, io_log=result.io_log,
                                            link_names=result.link_names, app_path=app.path,
                                            max_wall=options.max_wall, geometries=getattr(arm, "geometries", ()),
                                            on_motion=_phase(options.progress),
                                            out_of_budget=budget.spent)
        result.collision = run
        if run is not None:
            for index, report in run.by_motion.items():  # each motion's clearances slot
                result.motion.motions[index].clearance = report
        found.extend(more)
    if found:
        result.diagnostics = sorted([*result.diagnostics, *found],
                                    key=lambda d: d.time_us if d.time_us is not None else 0)
    return result
