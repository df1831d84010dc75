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
