"""The cell around the controller: its inputs/outputs and what drives them.

- `Cell`: one `IOPoint` per physical link (every variable linked to it shares it, 3.5.1), and
  the roots of the frame and tool trees, `world` and `flange` (9.4.1, 9.5.1), one each for the
  whole controller;
- `CellSubsystem`: the first `Subsystem` of the scheduler. It holds the timeline of what the
  scenario schedules (inputs changing, serial data, key presses, controller changes) and what
  the cell does in return to the application's outputs (reactions, serial replies), and the
  arm power coming on after `enablePower()`.
"""

from __future__ import annotations

from typing import Any, Callable

from ..diagnostics import Diagnostic
from ..geometry.frames import new_flange, new_world
from ..language.runtime_errors import Val3RuntimeError
from ..light_dataclass import dataclass  # (frozen record classes made without dataclasses' cost)
from ..rules import codes
from .events import ControllerChange, Event, InputsChange, KeyPress, PowerChange, SerialData, Timeline
from .recorder import sio_text
from .scheduler import EndRun
from .values import IOPoint


class Cell:
    def __init__(self) -> None:
        self.points: dict[tuple[str, str], IOPoint] = {}
        self.world = new_world()
        self.flange = new_flange(self.io("dio", "valve1"))
        # (node or point, "fPallet[0]"): data-file references waiting for every global to exist
        self.pending: list[tuple[Any, str]] = []
        self.budget = None  # memory_budget.MemoryBudget: containers are priced before they are built
        self.nesting = 0  # user-type values being built inside each other
        self.arm_family = "Rx"  # "Rs" on a SCARA arm: joint values j1..j4, config the shoulder only

    def io(self, kind: str, link: str) -> IOPoint:
        if not link:
            return IOPoint(kind, "")  # 3.5.1: an undefined link
        key = (kind, link)
        p = self.points.get(key)
        if p is None:
            p = self.points[key] = IOPoint(kind, link)
        return p


@dataclass(frozen=True, slots=True)
class Reaction:
    """The scenario's `[[reactions]]`: when `output` takes `value`, set inputs `delay_us` later."""

    output: IOPoint
    value: Any
    delay_us: int
    settings: tuple  # ((IOPoint, value), ...)
    line: int = 0  # its line in the scenario file (R008)


@dataclass(frozen=True, slots=True)
class SerialReply:
    """The scenario's `[[serial]] when_sent`: when the program has sent `pattern` on `io`, the
    peer answers `data` `delay_us` later."""

    io: IOPoint
    pattern: bytes
    delay_us: int
    data: bytes


# A scenario reaction firing more often within one 4 ms cycle is a loop (R008).
MAX_REACTIONS_PER_CYCLE = 10_000


class CellSubsystem:
    """See the module docstring. `log_io(time_us, io, value, source)` records I/O changes;
    `controller` is the chapter 8 state the scenario and enablePower() change;
    `report(diagnostic)` records a finding of the cell (R008)."""

    def __init__(self, controller: Any, log_io: Callable[[int, IOPoint, Any, str], None],
                 report: Callable[[Diagnostic], None]) -> None:
        self.timeline = Timeline()
        self.reactions: list[Reaction] = []
        self.serial_replies: list[SerialReply] = []
        self.controller = controller
        self.log_io = log_io
        self.report = report
        self.scenario_path = ""  # for R008's position
        self._fired: dict[int, int] | None = None  # reactions fired in the cycle being advanced

    # ---- Subsystem -----------------------------------------------------------------------------

    def next_time(self, now_us: int) -> int | None:
        heap = self.timeline.heap
        return heap[0][0] if heap else None

    def advance(self, to_us: int) -> None:
        timeline = self.timeline
        heap = timeline.heap
        if not heap or heap[0][0] > to_us:  # nothing due: the common case, every 4 ms
            return
        self._fired = {}
        try:
            while True:
                due = timeline.pop_due(to_us)
                if due is None:
                    return
                self._apply(*due)
        finally:
            self._fired = None

    def schedule(self, at: int, event: Event) -> None:
        self.timeline.push(at, event)

    def _apply(self, at: int, event: Event) -> None:
        te = type(event)
        if te is InputsChange:
            for io, value in event.settings:
                if io.value != value:
                    io.value = value
                    self.log_io(at, io, value, "scenario")
                    self._react(io, at)
        elif te is SerialData:
            event.io.rx.extend(event.data)
            self.log_io(at, event.io, sio_text(event.data), "scenario")
        elif te is PowerChange:
            ctl = self.controller
            if ctl.working_mode == 4 and ctl.es_status == 0:
                ctl.powered = event.on
        elif te is ControllerChange:
            for k, v in event.changes:
                setattr(self.controller, k, v)
        # KeyPress: the keys are in the user page's queue; the event only stops the clock
        elif te is not KeyPress:  # pragma: no cover - every event type is handled above
            raise TypeError(te)

    # ---- what the application does to the cell --------------------------------------------------

    def _react(self, io: IOPoint, at: int) -> None:
        fired = self._fired  # counted while the scenario's events are applied (advance)
        for k, r in enumerate(self.reactions):
            if r.output is io and io.value == r.value:
                if fired is not None:
                    fired[k] = fired.get(k, 0) + 1
                    if fired[k] > MAX_REACTIONS_PER_CYCLE:
                        self._reaction_loop(at, fired)
                self.timeline.push(at + r.delay_us, InputsChange(r.settings))

    def _reaction_loop(self, at: int, fired: dict[int, int]) -> None:
        """Scenario reactions that set each other's inputs without delay never let time move on:
        said once (R008) at the first reaction of the loop, and the run ends."""
        looping = [k for k in sorted(fired) if fired[k] > MAX_REACTIONS_PER_CYCLE // 2]
        lines = [self.reactions[k].line for k in looping]
        names = sorted({self.reactions[k].output.link for k in looping})
        where = ", ".join(f"line {n}" for n in lines if n) or "see [[reactions]]"
        self.report(
            Diagnostic(
                codes.SCENARIO_REACTION_LOOP,
                f"the scenario's reactions to {', '.join(names)} set each other's inputs again and again at"
                f" {at / 1e6:g} s ({MAX_REACTIONS_PER_CYCLE} times within one 4 ms cycle; {where}): time cannot move on",
                self.scenario_path,
                min((n for n in lines if n), default=0),
                1 if any(lines) else 0,
                time_us=at,
                task="",
                program="",
            )
        )
        raise EndRun(f"budget:the scenario's reactions loop at {at / 1e6:g} s (R008)")

    def output_changed(self, io: IOPoint, at: int, source: str) -> None:
        """An output written by a task at `at`: logged, and the cell's reactions scheduled."""
        self.log_io(at, io, io.value, source)
        self._react(io, at)

    def sio_sent(self, io: IOPoint, data: bytes, at: int, source: str) -> None:
        """Bytes sent on a sio: logged; a peer whose pattern has been sent answers."""
        if io.closed:
            raise Val3RuntimeError(125, f"{io.link} is closed")
        io.tx.extend(data)
        self.log_io(at, io, sio_text(data), source)
        for reply in self.serial_replies:
            if reply.io is io and reply.pattern in bytes(io.tx):
                del io.tx[: bytes(io.tx).index(reply.pattern) + len(reply.pattern)]
                self.timeline.push(at + reply.delay_us, SerialData(io, reply.data))
