"""What the checker returns: typed records, in millimetres and seconds of simulated time.

`source` fields carry whatever the caller attached to a motion or a gripper event (the program
line that commanded it); the checker never looks inside.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from ..light_dataclass import dataclass, field


@dataclass(frozen=True)
class MotionSpan:
    """One commanded motion: `id` (the caller's), `source` (its program line), `label` (text)."""

    id: int
    source: Any = None
    label: str = ""


@dataclass(frozen=True)
class Contact:
    """Two bodies in contact: penetration deeper than the cell's touch tolerance.

    time (s); body_a, body_b: labels ("link_4 (forearm)", "tool tGripper 'jaw'", "part 'brick'",
    "obstacle 'table'"); point: a contact point in world (mm); depth_mm: penetration depth as fcl
    reports it (for a solid inside a closed mesh: the depth is not known, None)."""

    time: float
    body_a: str
    body_b: str
    point: tuple[float, float, float]
    depth_mm: float | None
    kind: str = "contact"  # "contact", "self" (two parts of the arm and its tool), "inside" (contained)


@dataclass(frozen=True)
class Clearance:
    """The smallest distance between two bodies that may not touch: `mm`, at `time` (s), between
    body_a and body_b, at point_a and point_b (world, mm)."""

    mm: float
    time: float
    body_a: str
    body_b: str
    point_a: tuple[float, float, float]
    point_b: tuple[float, float, float]


@dataclass
class MotionReport:
    """The check of one motion.

    starts_in_collision  a contact at the motion's first sample (then first_contact is the first
                         contact with another pair, if any)
    first_contact        the first contact during the motion (time within 1/256 of a sample)
    min_clearance        the smallest clearance to the cell over the motion (within 0.05 mm + 2 %,
                         at most 0.4 mm below 50 mm; 5 % beyond), or None when nothing was measured
    too_close            min_clearance below the safety margin (and no contact)
    times                the motion's sample times (s)
    clearance            per sample, a certified lower bound of the clearance to the cell (mm): never above
                         the true clearance; equal to it (within tolerance_mm) where `exact`
                         is True, which is every sample closer than the margin, and the minimum
    exact                per sample: clearance is the true value
    checks               how many times a pair of bodies was measured (work done)
    """

    motion: MotionSpan
    times: np.ndarray = field(repr=False)
    clearance: np.ndarray = field(repr=False)
    exact: np.ndarray = field(repr=False)
    starts_in_collision: Contact | None = None
    first_contact: Contact | None = None
    min_clearance: Clearance | None = None
    too_close: bool = False
    margin_mm: float = 0.0
    tolerance_mm: float = 0.05
    checks: int = 0
    contacts: list[Contact] = field(default_factory=list)  # first contact of each pair of solid groups, by time

    @property
    def start(self) -> float:
        return float(self.times[0]) if len(self.times) else 0.0

    @property
    def end(self) -> float:
        return float(self.times[-1]) if len(self.times) else 0.0


class ShiftedReport:
    """A motion's report kept as the report on its own clock (shared by every motion that repeats
    it) and the motion's start: what `MotionReport` gives, computed when read, bit for bit what
    the shifted copy was (a long run keeps one small object per motion, not its sample times)."""

    __slots__ = ("motion", "own", "offset")

    def __init__(self, motion: MotionSpan, own: MotionReport, offset: float) -> None:
        self.motion = motion
        self.own = own
        self.offset = offset

    def _at(self, c):
        return None if c is None else replace(c, time=self.offset + c.time)

    @property
    def times(self) -> np.ndarray:
        return self.offset + self.own.times

    @property
    def clearance(self) -> np.ndarray:
        return self.own.clearance

    @property
    def exact(self) -> np.ndarray:
        return self.own.exact

    @property
    def starts_in_collision(self) -> Contact | None:
        return self._at(self.own.starts_in_collision)

    @property
    def first_contact(self) -> Contact | None:
        return self._at(self.own.first_contact)

    @property
    def min_clearance(self) -> Clearance | None:
        return self._at(self.own.min_clearance)

    @property
    def contacts(self) -> list[Contact]:
        return [self._at(c) for c in self.own.contacts]

    @property
    def too_close(self) -> bool:
        return self.own.too_close

    @property
    def margin_mm(self) -> float:
        return self.own.margin_mm

    @property
    def tolerance_mm(self) -> float:
        return self.own.tolerance_mm

    @property
    def checks(self) -> int:
        return self.own.checks

    @property
    def start(self) -> float:
        t = self.own.times
        return float(self.offset + t[0]) if len(t) else 0.0

    @property
    def end(self) -> float:
        t = self.own.times
        return float(self.offset + t[-1]) if len(t) else 0.0


@dataclass(frozen=True)
class PartDrop:
    """A part left (on open/close) inside an obstacle or another part."""

    time: float
    part: str
    obstacle: str
    point: tuple[float, float, float]
    depth_mm: float | None
    source: Any = None


@dataclass(frozen=True)
class CellProblem:
    """Something of the cell the run could not place: an obstacle whose frame has no position,
    a tool variable the program does not have. The solid is left out until it can be placed."""

    time: float
    what: str
    message: str
    where: Any = None  # the cell file position (cell.Where)
