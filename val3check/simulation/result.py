"""What a run hands to the reports: `SimResult` (reporting/sim_report.py, sim_text.py,
sim_json.py; docs/sim-report.md), with `MotionRun`, what the arm did (motion table, cycle
times, the trajectory, the tools' open/close events): the interface the HTML/MCAP traces and
the collision checks read (docs/sim-report.md, "For developers")."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from ..diagnostics import Diagnostic
from ..interpretation.machine import Machine
from ..interpretation.recorder import IOEvent, TaskStateChange, ToolEvent, TranscriptEntry

END_REASONS = {
    "ended": "the application ended (its last task ended, then stop() ran)",
    "duration": "the simulated duration was reached",
    "deadlock": "deadlock: every task waits for something that no scheduled event can change",
    "stalled": "no task can run any more: each one is stopped (runtime error, instruction not simulated)",
    "wall-clock": "the wall-clock budget was reached",
    "steps": "the budget of executed lines was reached",
    "no-start": "the application has no start() program",
    "cycles": "the arm started the cycle after the last one asked for (--cycles)",
}


@dataclass(frozen=True)
class TaskSummary:
    """One task of the run, as the reports show it. Times in simulated microseconds."""

    name: str
    program: str
    library: str | None  # the library whose program it runs, None for the application
    priority: int | None  # asynchronous tasks
    period: float | None  # synchronous tasks, seconds
    created: int
    ended: int | None
    end: str  # ended, killed, destroyed, alive
    state_at_end_of_run: str  # what it was doing when the run ended
    error: int | None  # the VAL 3 code it stopped on
    error_text: str | None
    blocked_on: str | None  # what it waited for, when waiting at the end
    position: tuple | None  # (path, line, col, program)
    lines: int  # VAL 3 lines executed


@dataclass
class MotionRun:
    """What the arm did in a run (docs/sim-report.md, "For developers"). Times in simulated
    seconds, joints in degrees (a SCARA's axis 3 in mm), lengths in mm.

    - `records`: one `motion.records.MotionRecord` per command recorded (connection moves
      included), in recording order: id, source position and task, kind, state, record, start
      and end times, TCP length and peak speed, the limit active most of the time, target and
      tool names; `commands[i]` is the queue's command behind `records[i]` (its `tool`: the TCP
      in the flange as a 4x4 matrix in mm, None for the flange; `geom`: its joint path);
    - `trajectory`: the arm's joint trajectory (`motion.trajectory.Trajectory`: `position(t)`,
      `velocity(t)`, `sample(t0, t1, dt=0.004)` on the controller's 4 ms clock);
    - `tool_events`: every open()/close() with its time, task, tool name, gripper link and the
      tool's centre point in the flange (mm, degrees);
    - `cycles`: per task that moves the arm in a loop, `motion.cycle.CycleStats` (the loop's
      first motion instruction, the start of each pass, min/median/max cycle time);
    - `busy_s`, `idle_s`: the arm's moving and standing time over the run.
    """

    model: object  # the val3check.robot.RobotModel
    records: list
    commands: list
    trajectory: object
    tool_events: list[ToolEvent]
    cycles: dict
    busy_s: float
    idle_s: float
    end_s: float

    def sample(self, t0: float = 0.0, t1: float | None = None, dt: float = 0.004):
        """(times (N,), joint positions (N, axes), joint velocities (N, axes)) every `dt` s."""
        return self.trajectory.sample(t0, self.end_s if t1 is None else t1, dt)


@dataclass
class SimResult:
    application: str
    app_path: str
    end_reason: str
    end_message: str
    sim_time_us: int
    lines: int
    tasks: list[TaskSummary]
    diagnostics: list[Diagnostic]
    transcript: list[TranscriptEntry]
    io_log: list[IOEvent]
    screen: dict
    destroyed: list[str]
    link_names: dict = field(default_factory=dict)  # (kind, link) -> sorted variable names
    # the arm model of the run: {"name": "TX2-60", "initial_joints": [...]} or None
    robot: dict | None = None
    # The application's globals at the end of the run (name -> Arr/Coll of run-time values,
    # interpretation/values.py): for tests and tools; not part of the reports.
    globals: dict = field(default_factory=dict, repr=False)
    motion: MotionRun | None = None  # what the arm did (None without an arm model)
    # the collision checks (simulation.collision_run.CollisionRun): None when the run did not check
    # collisions (no arm model, an arm without collision solids, or not asked: SimOptions.collisions)
    collision: Any = None
    tool_events: list[ToolEvent] = field(default_factory=list)
    # every task's state over time (running, waiting, blocked, stopped, ended), sampled per 4 ms
    # cycle (interpretation/recorder.py): the task timelines of the HTML report and the traces
    task_states: list[TaskStateChange] = field(default_factory=list)


def collect(machine: Machine) -> SimResult:
    reason = machine.end_reason
    message = END_REASONS.get(reason, reason)
    if reason.startswith("budget:"):
        message = reason[len("budget:"):]
        reason = "budget"
    diags = list(machine.diags)
    if reason == "deadlock" and any(d.code == "R009" for d in diags) and not any(d.code == "R003" for d in diags):
        # no task waits only for variables: the cell, not the program, would go on (R009)
        message = ("every task waits for the cell (inputs, serial or socket peers, keys, the controller's state), "
                   "which nothing in the run plays (a scenario can: docs/scenario.md)")
    if reason == "duration":
        running = [t.name for t in machine.scheduler.history if t.final is not None]
        diags.append(Diagnostic("R007", f"run stopped at --duration {machine.end_time / 1e6:g} s; tasks still alive: "
                                + (", ".join(running) or "none"), machine.app.path, 0, 0,
                                time_us=machine.end_time, task="", program=""))
    elif reason in ("wall-clock", "steps", "budget"):
        diags.append(Diagnostic("R006", f"run cut short: {message}", machine.app.path, 0, 0, time_us=machine.end_time,
                                task="", program=""))
    tasks = []
    for t in machine.scheduler.history:
        final = t.final
        where = (final.where if final is not None else None) or t.errpos
        stopped_on_error = t.state.value == "error" or (final is not None and final.state == "error")
        tasks.append(TaskSummary(
            name=t.name,
            program=t.program,
            library=t.unit.name if t.unit is not machine.main else None,
            priority=t.prio if not t.period else None,
            period=t.period / 1e6 if t.period else None,
            created=t.created,
            ended=t.ended,
            end=t.end_state or "alive",
            state_at_end_of_run=final.state if final is not None else t.end_state or "ended",
            error=t.error if stopped_on_error else None,
            error_text=t.errdetail or None,
            blocked_on=final.blocked_on if final is not None else None,
            position=where,
            lines=t.lines,
        ))
    motion = _motion(machine, diags)
    diags.sort(key=lambda d: d.time_us if d.time_us is not None else 0)  # stable: by time, then as recorded
    page = machine.user_page.default
    screen = {"title": page.title, "lines": page.text()}
    arm = machine.arm
    robot = {"name": arm.name, "initial_joints": list(arm.initial_joints)} if arm.has_model else None
    return SimResult(machine.app.name, machine.app.path, reason, message, machine.end_time,
                     machine.scheduler.total_lines, tasks, diags, machine.recorder.transcript, machine.recorder.io_log,
                     screen, list(machine.destroyed), {k: sorted(v) for k, v in machine.link_names.items()},
                     robot=robot, globals=dict(machine.main.globals) if machine.main is not None else {},
                     motion=motion, tool_events=list(machine.recorder.tool_events),
                     task_states=list(machine.recorder.finish_task_states()))


def _motion(machine: Machine, diags: list[Diagnostic]) -> MotionRun | None:
    """The arm's findings as diagnostics (added to `diags`), and its MotionRun."""
    arm = machine.arm
    q = getattr(arm, "_queue", None)
    if q is None:
        return None
    from ..motion.cycle import cycle_stats
    from ..motion.records import busy_time, motion_records

    end_s = machine.end_time / 1_000_000
    q.advance(end_s)
    for f in q.findings:
        src = f.source
        diags.append(Diagnostic(f.code, f.message, src.path, src.line, src.col, time_us=int(round(f.time * 1e6)),
                                task=src.task, program=src.program, error=f.error))
    records = motion_records(q)
    busy, idle = busy_time(q.trajectory.profile, end_s)
    return MotionRun(arm.model, records, list(q.history), q.trajectory, list(machine.recorder.tool_events),
                     cycle_stats(records), busy, idle, end_s)
