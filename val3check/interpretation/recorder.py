"""What a run records besides its diagnostics: the user page transcript and the I/O log.

Both are typed records shared by every renderer (text and JSON reports, tests). Each has a
budget (docs/sim.md "Budgets"): past it, the run goes on without recording, and one R006
diagnostic says so.
"""

from __future__ import annotations

from typing import Any, Callable, NamedTuple


class TranscriptEntry(NamedTuple):
    """One action on the user page (chapter 4) or the system log."""

    time_us: int
    task: str  # "" when no task did it
    kind: str  # put, putln, title, cls, gotoxy, userPage, popUpMsg, logMsg, get, power, disk
    text: str
    screen: str | None  # the `screen` variable's name; None for the default page


class IOEvent(NamedTuple):
    """A change of an input/output of the cell, or data sent or received on a sio."""

    time_us: int
    kind: str  # dio, aio, sio
    link: str  # the physical link
    value: Any  # bool (dio), float (aio), text or list of byte values (sio)
    source: str  # the task that wrote it, or "scenario"


class ToolEvent(NamedTuple):
    """open() or close() of a tool (9.5.4), when the gripper output is set (after the end of
    the motion it waited for): the tool's name, its gripper's link, and its centre point in the
    flange (x, y, z in millimetres, rx, ry, rz in degrees, 9.5): for collision checking (what the
    gripper holds) and traces."""

    time_us: int
    task: str
    action: str  # "open" | "close"
    tool: str  # the tool variable's name ("" for a local or an anonymous value)
    gripper: str  # the link of its dio
    tcp_in_flange: tuple  # (x, y, z, rx, ry, rz), mm and degrees
    position: tuple  # (path, line, col, program) of the instruction


class TaskStateChange(NamedTuple):
    """A task's state from `time_us` on, for the task timelines of the HTML report and the
    traces. Sampled once per 4 ms cycle of the scheduler: a task that ran a line in a cycle is
    `running` over that cycle, then in the state it was left in (docs/html-report.md, tasks)."""

    time_us: int
    task: str
    state: str  # running | waiting | blocked | stopped | ended
    detail: str  # what it waits for or is blocked on ("" when running)


# What a waiting task waits for (task.waiting_for, as waiting.py's callers name it) that makes it
# `blocked` rather than `waiting`: the arm (end of motion, a full motion queue), a mutex, a key
# (get), a serial line. Anything else (wait(...), watch, delay) is waiting.
_BLOCKED_EXACT = ("setMutex", "get", "sio read", "sioGet")
_BLOCKED_SUFFIX = ("(end of motion)", "(the motion queue is full)")


def task_state_of(state: str, waiting_for: str) -> str:
    """The timeline state of a scheduler state (scheduler.TaskState values)."""
    if state in ("ready", "run", "preempted", "yield"):
        return "running"
    if state == "delay":
        return "waiting"
    if state == "wait":
        blocked = waiting_for in _BLOCKED_EXACT or waiting_for.endswith(_BLOCKED_SUFFIX)
        return "blocked" if blocked else "waiting"
    if state in ("killed", "ended"):
        return "ended"
    return "stopped"  # suspended, error, held (not simulated)


def sio_text(data: bytes) -> Any:
    """How the I/O log shows bytes sent or received on a sio: the text when they are UTF-8,
    else the list of the byte values."""
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return list(data)


class Recorder:
    """The transcript and the I/O log of a run, within their budgets. `full(message, task)` is
    called once per record that reaches its budget, with the message of the R006 diagnostic
    and the task that was recording."""

    def __init__(self, max_transcript: int, max_io_log: int, full: Callable[[str, Any], None]) -> None:
        self.transcript: list[TranscriptEntry] = []
        self.io_log: list[IOEvent] = []
        self.tool_events: list[ToolEvent] = []  # bounded by the I/O log's budget (each sets an output)
        self.task_states: list[TaskStateChange] = []
        self.max_task_states = 10 * max_io_log
        self._last_state: dict[str, TaskStateChange] = {}  # by task name: its last change kept
        self._pending_state: dict[str, TaskStateChange] = {}  # by task name: its last note
        self.max_transcript = max_transcript
        self.max_io_log = max_io_log
        self._full = full
        self._reported: set[str] = set()

    def _budget(self, which: str, message: str, task: Any) -> None:
        if which not in self._reported:
            self._reported.add(which)
            self._full(message, task)

    def transcript_room(self, task: Any) -> bool:
        """Whether one more transcript entry fits (if not, said once)."""
        if len(self.transcript) < self.max_transcript:
            return True
        self._budget("transcript", f"the user page transcript is full ({self.max_transcript} entries): "
                                   "later entries are not recorded (the page itself is still kept)", task)
        return False

    def io_room(self, task: Any) -> bool:
        """Whether one more I/O event fits (if not, said once)."""
        if len(self.io_log) < self.max_io_log:
            return True
        self._budget("io_log", f"the I/O log is full ({self.max_io_log} events): later events are not recorded", task)
        return False

    def task_state(self, time_us: int, task: str, state: str, detail: str = "", who: Any = None) -> None:
        """`task` is in `state` from `time_us` on. A note at the same time as the task's previous
        one replaces it; only changes are kept (`finish_task_states` flushes the last ones)."""
        pending = self._pending_state.get(task)
        if pending is not None and pending.time_us != time_us:
            self._commit_state(pending, who)
        self._pending_state[task] = TaskStateChange(time_us, task, state, detail)

    def _commit_state(self, change: TaskStateChange, who: Any) -> None:
        last = self._last_state.get(change.task)
        if last is not None and last.state == change.state and last.detail == change.detail:
            return
        if len(self.task_states) >= self.max_task_states:
            self._budget("task_states", f"the task timeline is full ({self.max_task_states} changes): later changes "
                                        "are not recorded", who)
            return
        self._last_state[change.task] = change
        self.task_states.append(change)

    def finish_task_states(self) -> list[TaskStateChange]:
        """Flush the last notes; the changes sorted by time (stable: in the order noted)."""
        for change in list(self._pending_state.values()):
            self._commit_state(change, None)
        self._pending_state.clear()
        self.task_states.sort(key=lambda c: c.time_us)
        return self.task_states
