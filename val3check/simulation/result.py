"""What a run hands to the reports: `SimResult` (reporting/sim_report.py, sim_text.py,
sim_json.py; docs/sim-report.md), with `motion`, the record of what the arm did and of the scene
(arm_record.ArmRun: the motion table, cycle times, the trajectory, the tools' open/close
events), and `collision`, the collision checks (collision_run.CollisionRun). The reports read
these records and nothing else (docs/sim-report.md, "For developers"); collect.py builds them at
the end of a run."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ..diagnostics import Diagnostic
from ..light_dataclass import dataclass, field
from .arm_record import ArmRun

if TYPE_CHECKING:
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
class SimResult:
    """What a run hands to the reports (module docstring, docs/sim-report.md)."""
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
    motion: ArmRun | None = None  # what the arm did, and the scene (None without an arm model)
    # the collision checks (simulation.collision_run.CollisionRun): None when the run did not check
    # collisions (no arm model, an arm without collision solids, or not asked: SimOptions.collisions)
    collision: Any = None
    tool_events: list[ToolEvent] = field(default_factory=list)
    # every task's state over time (running, waiting, blocked, stopped, ended), sampled per 4 ms
    # cycle (interpretation/recorder.py): the task timelines of the HTML report and the traces
    task_states: list[TaskStateChange] = field(default_factory=list)
    # the run's budgets, which also cover the reports (simulation/budget.py RunBudget): a writer
    # leaves out what grows with the run once they are spent
    budget: Any = field(default=None, repr=False, compare=False)
