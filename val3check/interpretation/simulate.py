"""Run an application in the virtual controller and collect what happened (`SimResult`).

    result = simulate(workspace, app, SimOptions(duration=10.0, scenario="cell.toml"))

The application must have been loaded and its programs parsed (the `sim` command lints it
first, in-process). Nothing here writes files: reporting is `val3check.reporting.sim_text` /
`sim_json`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from ..loading.model import Application, Workspace
from .machine import Budgets, Diag, EndRun, Machine

END_REASONS = {
    "ended": "the application ended (its last task ended, then stop() ran)",
    "duration": "the simulated duration was reached",
    "deadlock": "deadlock: every task waits for something that no scheduled event can change",
    "stalled": "no task can run any more: each one is stopped (runtime error, instruction not simulated)",
    "wall-clock": "the wall-clock budget was reached",
    "steps": "the budget of executed lines was reached",
    "no-start": "the application has no start() program",
}


@dataclass
class SimOptions:
    duration: float = 60.0  # simulated seconds
    max_wall: float = 60.0  # wall-clock seconds
    max_lines: int = 50_000_000
    max_transcript: int = 10_000
    max_memory_mb: float = 512.0  # growth of the process, loading included (memory_budget.py)
    scenario: str | None = None
    disk_roots: list[str] = field(default_factory=list)
    # the arm model (val3check.robot.RobotModel) or None: see `choose_sim_robot`
    robot: Any = None


@dataclass
class SimResult:
    application: str
    app_path: str
    end_reason: str
    end_message: str
    sim_time_us: int
    lines: int
    tasks: list[dict]
    diagnostics: list[Diag]
    transcript: list[tuple]
    io_log: list[tuple]
    screen: dict
    destroyed: list[str]
    link_names: dict = field(default_factory=dict)
    # the arm model of the run: {"name": "TX2-60", "initial_joints": [...]} or None
    robot: dict | None = None
    # The application's globals at the end of the run (name -> Arr/Coll of run-time values,
    # values.py): for tests and tools; not part of the reports.
    globals: dict = field(default_factory=dict, repr=False)


def simulate(ws: Workspace, app: Application, options: SimOptions | None = None, scenario: Any = None) -> SimResult:
    options = options or SimOptions()
    budgets = Budgets(duration_us=int(round(options.duration * 1_000_000)), wall_s=options.max_wall,
                      max_lines=options.max_lines, max_transcript=options.max_transcript,
                      max_memory_mb=options.max_memory_mb)
    M = Machine(ws, app, budgets=budgets, disk_roots=options.disk_roots, robot=options.robot)
    try:
        M.load_main()
        if scenario is not None:
            from .scenario import apply_scenario

            apply_scenario(M, scenario)
    except (EndRun, MemoryError, RecursionError) as stop:  # a budget reached before the first line ran
        M.end_reason = (stop.reason if isinstance(stop, EndRun) else f"budget:{stop}" if isinstance(stop, MemoryError)
                        else "budget:the application's values are nested too deeply for the simulator")
        return collect(M)
    M.run()
    return collect(M)


def collect(M: Machine) -> SimResult:
    reason = M.end_reason
    message = END_REASONS.get(reason, reason)
    if reason.startswith("budget:"):
        message = reason[len("budget:"):]
        reason = "budget"
    diags = list(M.diags)
    if reason in ("duration",):
        running = [t.name for t in M.history if t.final is not None]
        diags.append(Diag("R007", f"run stopped at --duration {M.end_time / 1e6:g} s; tasks still alive: "
                          + (", ".join(running) or "none"), M.app.path, 0, 0, M.end_time, "", ""))
    elif reason in ("wall-clock", "steps", "budget"):
        diags.append(Diag("R006", f"run cut short: {message}", M.app.path, 0, 0, M.end_time, "", ""))
    tasks = []
    for T in M.history:
        final = T.final or {}
        where = final.get("where") or T.errpos
        entry = {
            "name": T.name,
            "program": T.program,
            "library": T.unit.name if T.unit is not M.main else None,
            "priority": T.prio if not T.period else None,
            "period": T.period / 1e6 if T.period else None,
            "created": T.created,
            "ended": T.ended,
            "end": T.end_state or "alive",
            "state_at_end_of_run": final.get("state") if T.final is not None else T.end_state or "ended",
            "error": T.error if T.state == "error" or (final.get("state") == "error") else None,
            "error_text": T.errdetail or None,
            "blocked_on": final.get("blocked_on"),
            "position": where,
            "lines": T.lines,
        }
        tasks.append(entry)
    screen = {"title": M.default_page.title, "lines": M.default_page.text()}
    robot = None if M.arm is None else {"name": M.arm.name, "initial_joints": list(M.arm.initial)}
    return SimResult(M.app.name, M.app.path, reason, message, M.end_time, M.total_lines, tasks, diags, M.transcript,
                     M.io_log, screen, list(M.destroyed), {k: sorted(v) for k, v in M.link_names.items()},
                     robot=robot, globals=dict(M.main.globals) if M.main is not None else {})


def choose_sim_robot(spec: str | None, app_path: str) -> tuple[Any, str]:
    """The arm model of `val3check sim`: (RobotModel or None, a note for the user or "").

    `spec`: --robot's value: a catalogue name (case-insensitive), a URDF path, an arm.cfx, or
    "none" (no arm model). Without it, the usr/configs/arm.cfx of the controller tree that holds
    the application, if any. Raises `val3check.robot.RobotError` for a --robot that names no
    model; an arm.cfx found by itself whose arm has no model gives None and a note."""
    if spec is not None and spec.strip().lower() == "none":
        return None, ""
    from ..robot import RobotError, choose_robot
    from ..robot.catalog import find_arm_cfx

    if spec:
        return choose_robot(spec, app_path), ""
    cfx = find_arm_cfx(app_path)
    if cfx is None:
        return None, ""
    try:
        return choose_robot(str(cfx), app_path), ""
    except RobotError as exc:
        return None, f"{cfx}: {exc}; running without an arm model (name one with --robot)"
