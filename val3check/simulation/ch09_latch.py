"""9.2.3 setLatch/getLatch: the position capture of the CS8C on a rising edge of an input.

The manual (9.2.3): setLatch "active la capture de position du robot sur le flanc ascendant
suivant du signal d'entrée"; getLatch "lit la dernière position capturée du robot", "renvoie
true si une capture de position valide peut être lue. Si une capture est en attente, ou si la
capture n'a jamais été activée, la fonction renvoie false et la position n'est pas mise à jour",
and "renvoie la même capture de position tant qu'une nouvelle capture n'est pas activée par
l'instruction setLatch".

In the simulation the edge is an input the scenario (or the cell's reactions) sets from false to
true, at the exact time the scenario gives (not the 4 ms cycle at which the program sees it: the
capture is electronic). The position captured is the arm's commanded position at that instant,
interpolated linearly between the two 4 ms setpoints around it (the controller sends the
amplifiers a position every 4 ms, 11.2.3), altered or not: what the arm does.

What is a model: the capture is armed at once (the manual: "entre 0 et 0.2 ms" after setLatch),
every rising edge counts (the manual guarantees detection only for an input low 0.2 ms before and
high 0.2 ms after the edge), and the capture is the commanded position (the simulated arm has no
following error). Only the CS8C's fast inputs capture (fIn0, fIn1: "Une erreur d'exécution 70
... si l'entrée digitale spécifiée ne supporte pas la capture"): the simulation cannot tell a
fast input from its link alone, so an input whose link does not name one is captured all the
same, with a warning (R051), never error 70.
"""

from __future__ import annotations

import re
from typing import Any

import numpy as np

from ..interpretation.chapters.ch03_simple_types import linked
from ..interpretation.chapters.ch09_geometry import arm_of, jd, millimeter_unit
from ..rules import codes
from .runtime_notes import note

US = 1_000_000
TICK_US = 4000  # the controller's setpoints (interpretation/clock.py)
FAST_INPUT = re.compile(r"(^|[^A-Za-z0-9])fIn[01]$", re.IGNORECASE)  # CS8C fast inputs (9.2.3)


class Latch:
    """The position capture of one controller: the input it is armed on, since when, and the
    capture (joint values of the model, degrees and mm), or None."""

    def __init__(self, arm: Any) -> None:
        self.arm = arm
        self.io: Any = None  # the input armed (an IOPoint), None when nothing is armed
        self.since_us = 0
        self.joints: tuple[float, ...] | None = None  # the last capture
        self.captured_us: int | None = None
        self._cell_log: Any = None

    def attach(self, cell: Any) -> None:
        """Watch the cell's input changes (its log of I/O changes carries their exact time)."""
        if self._cell_log is not None:
            return
        self._cell_log = cell.log_io

        def log_io(at: int, io: Any, value: Any, source: str) -> None:
            self._cell_log(at, io, value, source)
            if io is self.io and value is True:
                self._capture(at)

        cell.log_io = log_io

    def arm_on(self, io: Any, now_us: int) -> None:
        """setLatch: the next rising edge of `io` at or after `now_us` captures the position."""
        self.io = io
        self.since_us = now_us
        self.joints = None
        self.captured_us = None

    def _capture(self, at: int) -> None:
        """The rising edge at `at` (µs): the arm's position between its 4 ms setpoints."""
        if at < self.since_us:
            return
        self.joints = tuple(float(v) for v in setpoint_position(self.arm, at))
        self.captured_us = at
        self.io = None  # one capture per setLatch


def setpoint_position(arm: Any, at_us: int) -> np.ndarray:
    """The arm's commanded joints at `at_us`, linear between the 4 ms setpoints around it
    (model units: degrees, mm)."""
    k0 = (at_us // TICK_US) * TICK_US
    q0 = np.asarray(arm.actual_position(k0 / US), dtype=float)
    if k0 == at_us:
        return q0
    q1 = np.asarray(arm.actual_position((k0 + TICK_US) / US), dtype=float)
    f = (at_us - k0) / TICK_US
    return q0 + f * (q1 - q0)


def latch_of(task) -> Latch:
    """The run's latch (made at the first setLatch/getLatch)."""
    machine = task.machine
    latch = machine.__dict__.get("latch")
    if latch is None:
        latch = machine.__dict__["latch"] = Latch(machine.arm)
        latch.attach(machine.cell_subsystem)
    return latch


def I_setlatch(task, unit, io) -> None:
    """9.2.3 setLatch(dio): arm the capture on the next rising edge of the input."""
    arm_of(task, "setLatch")
    io = linked(io, "dio")
    if not FAST_INPUT.search(io.link):
        note(task, codes.LATCH_NOT_FAST_INPUT, f"setLatch on {io.link!r}: only the CS8C's fast inputs (fIn0, fIn1) capture the arm's "
                           "position (9.2.3); if this input is not one of them the controller stops the task with "
                           "error 70 here. The simulation captures on it all the same", once=f"latch:{io.link}")
    latch_of(task).arm_on(io, task.machine.clock.time_of(task))


def I_getlatch(task, unit, result) -> bool:
    """9.2.3 getLatch(joint& jPosition): true and the captured position when a capture was made
    since the last setLatch; false (jPosition unchanged) while it waits or when never armed."""
    arm = arm_of(task, "getLatch")
    latch = latch_of(task)
    if latch.joints is None:
        return False
    c, k = result
    c[k] = jd(arm.joints_out(latch.joints, millimeter_unit(unit)))
    return True


def register(registry) -> None:
    """The position capture of 9.2.3."""
    registry.instruction("setLatch", I_setlatch)
    registry.instruction("getLatch", I_getlatch)

