"""Assemble a run of the virtual controller and run it.

    result = simulate(workspace, app, SimOptions(duration=10.0, robot=model), scenario)

The application must have been loaded and its programs parsed (the `sim` command lints it
first, in-process). Assembling a run means, in this order: the registry of instructions (the
interpreter's chapters, then motion's), the arm (a `motion` arm on the chosen model), the
machine, its subsystems (the cell and its scenario first, then the arm's motion), the
scenario's settings. Nothing here writes files: reports are `val3check.reporting`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
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
from ..loading.model import Application, Workspace
from ..motion import ch10_motion
from ..motion.arm import MovingArm
from .result import SimResult, collect
from .scenario import Scenario, apply_scenario

# What the generated code calls, then the chapters of the manual, in order.
INTERPRETER_MODULES = (code_support, waiting, not_simulated, ch02_variables, ch03_simple_types, ch04_user_page,
                       ch05_tasks, ch06_libraries, ch08_controller, ch09_geometry)
MOTION_MODULES = (ch10_motion,)


@dataclass
class SimOptions:
    duration: float = 60.0  # simulated seconds
    max_wall: float = 60.0  # wall-clock seconds
    max_lines: int = 50_000_000
    max_transcript: int = 10_000
    max_memory_mb: float = 512.0  # growth of the process, loading included (interpretation/memory_budget.py)
    disk_roots: list[str] = field(default_factory=list)
    # the arm model (val3check.robot.RobotModel) or None: see robot_choice.choose_sim_robot
    robot: Any = None
    cycles: int | None = None  # --cycles N: end the run when the arm starts cycle N + 1
    # progress(simulated seconds, motions_done()), called now and then while the run goes (the
    # progress display of `sim` on a terminal: reporting/progress.py)
    progress: Any = None


def build_registry() -> Registry:
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
                      max_memory_mb=options.max_memory_mb)
    arm = arm if arm is not None else MovingArm(options.robot, cycles=options.cycles)
    machine = Machine(ws, app, registry or build_registry(), arm, budgets=budgets, disk_roots=options.disk_roots)
    if hasattr(arm, "bind"):
        arm.bind(machine.controller)  # its power and monitor speed (chapter 8)
    machine.add_subsystem(arm)  # after the cell: inputs are refreshed before the arm moves
    if options.progress is not None:
        report = options.progress

        def motions_done() -> int:
            queue = getattr(arm, "_queue", None)
            return sum(1 for c in queue.history if c.state == "done" and c.id is not None) if queue is not None else 0

        def progress(now_us: int) -> None:
            report(now_us / 1e6, motions_done)

        machine.progress = progress
    return machine


def simulate(ws: Workspace, app: Application, options: SimOptions | None = None,
             scenario: Scenario | None = None) -> SimResult:
    options = options or SimOptions()
    machine = build_machine(ws, app, options)
    try:
        machine.load_main()
        if scenario is not None:
            apply_scenario(machine, scenario)
    except (EndRun, MemoryError, RecursionError) as stop:  # a budget reached before the first line ran
        machine.end_reason = (stop.reason if isinstance(stop, EndRun) else f"budget:{stop}"
                              if isinstance(stop, MemoryError)
                              else "budget:the application's values are nested too deeply for the simulator")
        return collect(machine)
    machine.run()
    return collect(machine)
