"""11.2 ALTER: alterMovej/alterMovel/alterMovec, alterBegin, alter, alterEnd, alterStopTime on the
arm of the run (alteration.py applies the alteration on the 4 ms setpoints; docs/motion.md, "ALTER").

11.2.6: alterMovej/L/C behave "exactement comme l'instruction movej [movel, movec], à ceci près
qu'elle[s] autorise[nt] le mode alter pour le mouvement". alterBegin(frame|tool, mdesc) returns 1
(started), 0 (waits for the alterable move), -1 (alter mode already started), -2 (the alter option
is not installed), -3 (the motion is in error: resetMotion is needed); alter(trsf) 1, 0 (locked
by a stop condition), -1 (alter mode not started, or over), -2, -3; alterEnd 1, -1, -3 (the text
of the manual lost the minus signs of alterEnd's and alter's codes: they are those of alterBegin);
alterStopTime the time left before a stop condition locks the alteration, negative without one, 0
when alter mode is not active.
"""

from __future__ import annotations

from ..geometry import frames as geo_frames
from ..geometry.frames import Tool
from ..interpretation.chapters.ch09_geometry import millimeter_unit
from ..language.runtime_errors import Val3RuntimeError
from ..lengths import INCH_MM
from ..motion.findings import MDESC
from ..motion.mdesc import MDesc
from .alteration import AlterMode, trsf4
from .ch10_motion import I_movec, I_movej, I_movel, _arm, _matrix, _source
from .ch11_licences import licensed, require

E = Val3RuntimeError
US = 1_000_000


def _alterable(task, name: str, handler, *args):
    """Record the command as its chapter 10 instruction does, marked alterable."""
    arm = _arm(task, name)
    require(task, "alter", name)
    arm.alteration.next_alterable = True
    try:
        return (yield from handler(task, *args))
    finally:
        arm.alteration.next_alterable = False


def I_altermovej(task, unit, target, tool, mdesc: dict):
    """11.2.6 alterMovej(joint|point, tool, mdesc): movej, alterable."""
    return (yield from _alterable(task, "alterMovej", I_movej, unit, target, tool, mdesc))


def I_altermovel(task, unit, target, tool, mdesc: dict):
    """11.2.6 alterMovel(point, tool, mdesc): movel, alterable."""
    return (yield from _alterable(task, "alterMovel", I_movel, unit, target, tool, mdesc))


def I_altermovec(task, unit, via, target, tool, mdesc: dict):
    """11.2.6 alterMovec(point, point, tool, mdesc): movec, alterable."""
    return (yield from _alterable(task, "alterMovec", I_movec, unit, via, target, tool, mdesc))


def _state(task, name: str):
    """(arm, its queue at the task's time, now in s): the arm with its model (R002 without)."""
    arm = _arm(task, name)
    now = task.machine.clock.time_of(task)
    q = arm._sync(now)
    arm.layers.before(now / US)
    return arm, q, now / US


def I_alterbegin(task, unit, reference, mdesc: dict) -> float:
    """11.2.6 alterBegin(frame|tool, mdesc): 1, 0, -1, -2 or -3."""
    arm, q, now = _state(task, "alterBegin")
    if not licensed(task, "alter", "alterBegin"):
        return -2.0
    geo_frames.check_defined(reference)
    mm = millimeter_unit(unit)
    s = 1.0 if mm else INCH_MM
    md = MDesc.from_fields(mdesc, s)
    bad = md.check()
    if bad is not None:
        raise E(bad[0], f"alterBegin: {bad[1]}", rule=MDESC)
    ref = _matrix(geo_frames.root_pose(reference))
    ref[:3, 3] *= s
    mode = AlterMode(isinstance(reference, Tool), ref, md.vel, md.tvel, md.rvel, md.decel, _source(task))
    alteration = arm.alteration
    alteration.report = task.machine.diags.append
    arm.layers.altered = alteration
    if q.failure is not None and alteration.state != "error":
        return -3.0  # a recorded command cannot be executed: the motion is in error
    return float(alteration.begin(mode, q, now))


def I_alter(task, unit, trsf) -> float:
    """11.2.6 alter(trsf): the new alteration, from the next 4 ms setpoint: 1, 0, -1, -2 or -3."""
    arm, q, now = _state(task, "alter")
    if not licensed(task, "alter", "alter"):
        return -2.0
    if q.failure is not None and arm.alteration.state in ("active", "ending"):
        return -3.0  # "alter a été refusé parce que le mouvement est en erreur"
    s = 1.0 if millimeter_unit(unit) else INCH_MM
    A = trsf4(trsf.as_tuple(), s)
    return float(arm.alteration.alter(A, now, _source(task)))


def I_alterend(task, unit) -> float:
    """11.2.6 alterEnd(): 1, -1 or -3; the moves that waited for it are recorded."""
    arm, q, now = _state(task, "alterEnd")
    if q.failure is not None and arm.alteration.state == "active":
        return -3.0  # "alterEnd a été refusé parce que le mouvement est en erreur"
    return float(arm.alteration.end(q, now, arm.queue_time(round(now * US))))


def I_alterstoptime(task, unit) -> float:
    """11.2.6 alterStopTime(): seconds before a stop condition locks the alteration."""
    arm = task.machine.arm
    if not arm.has_model or arm.queue_in_use is None:
        return 0.0
    arm, _, now = _state(task, "alterStopTime")
    return float(arm.alteration.stop_time(now))


def register(registry) -> None:
    """11.2."""
    for name, func in (("alterMovej", I_altermovej), ("alterMovel", I_altermovel), ("alterMovec", I_altermovec)):
        registry.instruction(name, func, blocking=True)
    for name, func in (("alterBegin", I_alterbegin), ("alter", I_alter), ("alterEnd", I_alterend),
                       ("alterStopTime", I_alterstoptime)):
        registry.instruction(name, func)

