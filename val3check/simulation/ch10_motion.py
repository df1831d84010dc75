"""Chapter 10: the motion instructions, on the arm of the run (moving_arm.MovingArm): where the
interpreter's values meet the motion queue (motion/queue.py).

Each handler converts the VAL 3 values (points and tools with their references, joints,
mdesc) at the instruction, as the controller does when it records a command, and hands them to
the arm, which converts units and records the command in its motion queue (docs/motion.md).
The position of the instruction (file, line, column, program, task) goes with the command: the
motion diagnostics (R010-R019) point at it.

Errors (12.1; the table of docs/motion.md, "Runtime errors of 10.6"): what is known when the
command is recorded stops the task at the instruction, nothing recorded: an invalid mdesc field
with 100-106 (R017); a target outside the software limits, out of reach, or only in another
configuration than a line or a circle allows, and a movec intermediate point it cannot pass, with
154 (R010-R012); an arc that movec cannot define with 154 (R015); a joint or point of the other
arm family (Rx on an RS/TS arm or the reverse) with 81 (R001). A command whose path the arm cannot
follow (a joint limit, the workspace's edge or a singularity on the way) is recorded, reported at
its line, and the next motion instruction, waitEndMove(), open() or close() stops with 150.

Without an arm model the arm is idle: isEmpty(), isSettled(), resetMotion(), waitEndMove(),
stopMove(), restartMove(), autoConnectMove(), getMoveId(), setMoveId() and getSpeed() act on it
(issue 11 item 14); movej, movel, movec, resetMotion(joint), getPositionErr and getJointForce
stop the task with R002, saying how to name the arm.
"""

from __future__ import annotations

import operator
import re
import struct

import numpy as np

from ..geometry import frames as geo_frames
from ..geometry import points as geo_points
from ..geometry.frames import Tool, held_chain, same_chain
from ..geometry.points import Point
from ..interpretation.chapters.ch09_geometry import ct, jd, jt, millimeter_unit, wait_end_of_motion
from ..interpretation.not_simulated import ARM_LIMIT, NO_ARM, SimLimit
from ..interpretation.waiting import WAIT
from ..language.runtime_errors import Val3RuntimeError
from ..lengths import INCH_MM
from ..loading.types import arm_family
from ..motion.commands import Target
from ..motion.findings import MotionError, Source
from ..motion.queue import QueueFull

E = Val3RuntimeError
US = 1_000_000


# ---- conversions ---------------------------------------------------------------------------------


def _matrix(pose) -> np.ndarray:
    """A geometry pose (R, p, angles) as a 4x4 matrix (the caller's length unit)."""
    r, p, _ = pose  # r: the 9 values of the rotation, by rows
    return np.array(((r[0], r[1], r[2], p[0]), (r[3], r[4], r[5], p[1]), (r[6], r[7], r[8], p[2]),
                     (0.0, 0.0, 0.0, 1.0)), dtype=float)


_SOURCES: dict[tuple, Source] = {}  # `_source`, by its values (a frozen value: one object serves)


def _source(task) -> Source:
    """Where the task's running instruction is written (the motion diagnostics point at it)."""
    w = task.machine.line_running()
    if w is None:
        return Source(task.machine.app.path, 0, 0, task.program, task.name)
    key = (w, task.name)
    hit = _SOURCES.get(key)
    if hit is None:
        path, line, col, program = w
        hit = Source(path, line, col, program, task.name)
        if len(_SOURCES) >= 256:
            _SOURCES.clear()
        _SOURCES[key] = hit
    return hit


def _arm(task, what: str):
    """The arm with its model; without one the task stops with R002, saying how to name it."""
    arm = task.machine.arm
    if not arm.has_model:
        raise SimLimit(ARM_LIMIT, what, f"{what} {NO_ARM}")
    return arm


def _check_family(arm, value, what: str) -> None:
    """81 (12.1: "point/joint/config incompatible avec le bras"): a joint with another number
    of axes, or a point whose configuration has the fields of the other arm family (RX/TX:
    shoulder, elbow, wrist; RS/TS: shoulder only, 9.7.2)."""
    if type(value) is dict:
        if len(value) != arm.axes:
            raise E(81, f"{what}: a joint value with {len(value)} axes for the {arm.axes}-axis arm {arm.name}")
        return
    fields = len(value.config)
    want = len(getattr(arm.model, "config_fields", ("shoulder", "elbow", "wrist")))
    if fields != want:
        fam = "RS/TS (pointRs)" if fields == 1 else "RX/TX (pointRx)"
        raise E(81, f"{what}: {value.name or 'the point'} is a point of an {fam} arm, not of the {arm.name}")


_SIX = operator.attrgetter("x", "y", "z", "rx", "ry", "rz")
_PACK6 = struct.Struct("6d")
_FLOATS6 = (float,) * 6


def _point(task, p: Point, what: str) -> Target:
    """A point as the queue's target: its TCP pose in world through its frames, configuration and
    names. One Target (its pose read-only) for a point of the same coordinates (their bits) in
    the very same frame objects, with the same configuration and names: a cycle records the same
    few targets again and again, most from points made anew (appro, compose)."""
    ref = p.ref
    key = None
    kept = getattr(task.machine.arm, "targets", None)  # (the run's own: MovingArm.targets)
    try:  # (what cannot be keyed goes the plain way, in its order: the point's errors first)
        config, name = ct(p.config), p.name or ""
        frame = getattr(ref, "name", "") or ("world" if ref is not None and ref.is_root else "")
        note = _other_family_note(task, p)
        six = _SIX(p.trsf)
        if kept is not None and tuple(map(type, six)) == _FLOATS6:
            key = (id(ref), _PACK6.pack(*six), config, name, frame, note)
            hit = kept.get(key)
            if hit is not None and same_chain(ref, hit[0]):
                return hit[1]
    except Exception:  # noqa: BLE001
        key = None
    pose = geo_points.world_pose(p)  # (what check_defined raises: computed once)
    if key is None:
        frame = getattr(ref, "name", "") or ("world" if ref is not None and ref.is_root else "")
        config, name, note = ct(p.config), p.name or "", _other_family_note(task, p)
    target = Target.point(_matrix(pose), config, name, frame, note=note)
    target.pose.flags.writeable = False  # (shared by the commands of the same target)
    held = held_chain(ref)
    if key is not None and held is not None:
        if len(kept) >= 256:
            kept.clear()
        kept[key] = (held, target)
    return target


_ELEMENT = re.compile(r"^(\w+)(?:\[([^\]]*)\])?$")  # pPick (a one-element array), pSlot[2]


def _other_family_note(task, p: Point) -> str:
    """What a failure at point `p` adds when its data imposes an elbow or a wrist (a six-axis
    arm's configuration) and the arm is a SCARA, whose points have a shoulder only (9.7.2): a
    `point` of the data file written for another arm (a `pointRx` stops with 81 before)."""
    arm = task.machine.arm
    if tuple(getattr(arm.model, "config_fields", ())) != ("shoulder",):  # (first: the cheaper test)
        return ""
    m = _ELEMENT.match(p.name or "")
    if m is None:
        return ""
    data = task.machine.app.data.get(m.group(1))
    if data is None or arm_family(data.type) is not None:
        return ""
    value = next((v for v in data.values if v.key == (m.group(2) or "0")), None)
    imposed = [f"{k} {value.fields[k]}" for k in ("elbow", "wrist") if value is not None and k in value.fields
               and not str(value.fields[k]).lower().endswith(("same", "free"))]
    if not imposed:
        return ""
    return (f"its data gives it a six-axis arm's configuration ({', '.join(imposed)}), not a SCARA's: the "
            f"{arm.name}'s points have a shoulder only (9.7.2); written for another arm family?")


def _tool(tool: Tool, kept: dict | None = None) -> np.ndarray | None:
    """A tool as its TCP in the flange through its base tools (4x4, read-only), None for the
    flange. The same matrix object again while the tool and its base tools are the very objects
    its pose was computed from (geometry.frames.kept: the same floats, so the same pose): a
    program records most of its commands with one tool, and moving_arm.record then knows it.
    `kept`: the run's table (MovingArm.tools; a table of the module would hold a finished run's
    tool, its gripper's output and what that links to)."""
    return _tool_matrix(tool) if kept is None else geo_frames.kept(kept, tool, _tool_matrix)


def _tool_matrix(tool: Tool) -> np.ndarray | None:
    pose = geo_frames.root_pose(tool)
    if tool.is_root:
        return None
    m = _matrix(pose)
    m.flags.writeable = False
    return m


def _record(task, unit, kind: str, target: Target, via: Target | None, tool: Tool, tool_m, mdesc: dict):
    """Record the command (10.2.1) with the tool `tool`, whose TCP in the flange is `tool_m`
    (`_tool`); a full queue: wait until the arm completes the command it is executing, then
    record (the instruction waits, as the manual says)."""
    arm = task.machine.arm
    clock = task.machine.clock
    source = _source(task)
    mm = millimeter_unit(unit)
    name = tool.name or ("flange" if tool.is_root else "")
    loops = task.machine.loop_passes()  # which pass of which loops records it (the cycle)
    while True:
        try:
            r = arm.record(kind, target, tool_m, mdesc, via, source, name, mm, clock.time_of(task), loops)
        except MotionError as exc:
            rule = exc.finding.code if exc.finding is not None else None
            raise E(exc.code, exc.message, rule=rule) from None
        if not isinstance(r, QueueFull):
            return float(r)
        room = lambda: arm.has_room(clock.now)
        room.motion = True
        yield from WAIT(task, room, False, f"{kind} (the motion queue is full)")


# ---- instructions of 10.6 --------------------------------------------------------------------------


def I_movej(task, unit, target, tool: Tool, mdesc: dict):
    """10.6 movej(joint|point, tool, mdesc): records a joint move; returns its identifier."""
    arm = _arm(task, "movej")
    tool_m = _tool(tool, getattr(arm, "tools", None))  # (raises what check_defined would: the tool's pose computed once)
    _check_family(arm, target, "movej")
    if type(target) is dict:
        tg = Target.joint(jt(target))
    else:
        tg = _point(task, target, "movej")
    return (yield from _record(task, unit, "movej", tg, None, tool, tool_m, mdesc))


def I_movel(task, unit, target: Point, tool: Tool, mdesc: dict):
    """10.6 movel(point, tool, mdesc): records a straight line of the tool centre point."""
    arm = _arm(task, "movel")
    tool_m = _tool(tool, getattr(arm, "tools", None))
    _check_family(arm, target, "movel")
    return (yield from _record(task, unit, "movel", _point(task, target, "movel"), None, tool, tool_m, mdesc))


def I_movec(task, unit, via: Point, target: Point, tool: Tool, mdesc: dict):
    """10.6 movec(intermediate, target, tool, mdesc): records an arc."""
    arm = _arm(task, "movec")
    tool_m = _tool(tool, getattr(arm, "tools", None))
    _check_family(arm, via, "movec")
    _check_family(arm, target, "movec")
    tg = _point(task, target, "movec")
    return (yield from _record(task, unit, "movec", tg, _point(task, via, "movec"), tool, tool_m, mdesc))


def I_waitendmove(task, unit):
    """10.6 waitEndMove(): cancels the blend of the last command and waits until the commanded
    position reaches its target; 150 when a recorded command cannot be executed."""
    yield from wait_end_of_motion(task, "waitEndMove")


def _now(task) -> int:
    """The task's simulated time (microseconds)."""
    return task.machine.clock.time_of(task)


def I_isempty(task, unit) -> bool:
    """10.6 isEmpty(): every recorded command has been executed."""
    return task.machine.arm.motion_done(_now(task))


def I_issettled(task, unit) -> bool:
    """10.6 isSettled(): the arm is at rest for 50 ms (the commanded position: no following
    error in the simulation)."""
    arm = task.machine.arm
    q = arm.sync(_now(task)) if arm.has_model else None
    return True if q is None else q.is_settled(_now(task) / US)


def I_stopmove(task, unit) -> None:
    """10.6 stopMove(): stops the arm on its path (the current command's deceleration) and
    holds the motion; returns at once."""
    arm = task.machine.arm
    q = arm.sync(_now(task)) if arm.has_model else None
    if q is not None:
        q.stop_move(_now(task) / US)


def I_restartmove(task, unit) -> None:
    """10.6 restartMove(): resumes a motion held by stopMove()."""
    arm = task.machine.arm
    q = arm.sync(_now(task)) if arm.has_model else None
    if q is not None:
        q.restart_move(_now(task) / US)


def I_resetmotion(task, unit, start: dict | None = None) -> None:
    """10.6 resetMotion() / resetMotion(jStart): stops the arm on its path, cancels every
    command, identifiers back to 0; with jStart the next command first connects to it."""
    arm = task.machine.arm
    if start is not None:
        arm = _arm(task, "resetMotion")
        _check_family(arm, start, "resetMotion")
    q = arm.sync(_now(task)) if arm.has_model else None
    if q is None:
        return
    joints = None if start is None else arm.joints_in(jt(start), millimeter_unit(unit))
    try:
        q.reset_motion(_now(task) / US, joints)
    except MotionError as exc:
        raise E(exc.code, exc.message) from None


def I_autoconnectmove(task, unit, active: bool | None = None):
    """10.6 autoConnectMove(bool) / autoConnectMove(): the setting is kept and returned; the
    connection move is always made automatically (no operator in the simulation)."""
    arm = task.machine.arm
    if active is None:
        return bool(arm.auto_connect)
    arm.auto_connect = bool(active)
    if arm.has_model and arm.queue is not None:
        arm.queue.auto_connect = bool(active)
    return None


def I_getspeed(task, unit, tool: Tool) -> float:
    """10.6 getSpeed(tool): the TCP translation speed from the commanded joint speeds, in the
    application's length unit per second."""
    geo_frames.check_defined(tool)
    arm = task.machine.arm
    q = arm.sync(_now(task)) if arm.has_model else None
    if q is None:
        return 0.0
    m = _tool(tool)
    mm = millimeter_unit(unit)
    s = 1.0 if mm else INCH_MM
    if m is not None:
        m = m.copy()
        m[:3, 3] *= s
    return q.get_speed(m, _now(task) / US) / s


def I_getpositionerr(task, unit) -> dict:
    """10.6 getPositionErr(): zero on every axis (the simulated arm follows its command exactly)."""
    arm = _arm(task, "getPositionErr")
    return jd((0.0,) * arm.axes)


def I_getjointforce(task, unit, forces) -> None:
    """10.6 getJointForce(nForce[]): the inverse dynamics of the commanded motion, when the arm
    model has masses; the Stäubli models have none (not public): R002. An array too small for
    the arm's axes is error 70 first (10.6: "si le paramètre n'est pas un tableau de valeurs
    numériques d'une taille suffisante"), whatever the model knows."""
    arm = _arm(task, "getJointForce")
    if forces.size() < arm.axes:
        raise E(70, f"getJointForce: the array holds {forces.size()} values for {arm.axes} axes")
    q = arm.sync(_now(task))
    f = q.joint_force(_now(task) / US)
    if f is None:
        raise SimLimit(ARM_LIMIT, "getJointForce", f"getJointForce needs the masses and inertias of the arm, which the "
                                                   f"model {arm.name} does not have (Stäubli does not publish them)")
    for i, v in enumerate(f):
        forces.data[forces.off + i] = float(v)


def I_getmoveid(task, unit) -> float:
    """10.6 getMoveId(): the command being executed (integer part) and its progress."""
    arm = task.machine.arm
    q = arm.sync(_now(task)) if arm.has_model else None
    return 0.0 if q is None else float(q.get_move_id(_now(task) / US))


def I_setmoveid(task, unit, n: float) -> float:
    """10.6 setMoveId(n): the identifier of the next command. The manual does not say what it
    returns: the identifier set."""
    arm = task.machine.arm
    q = arm.sync(_now(task)) if arm.has_model else None
    if q is not None:
        q.set_move_id(n)
    return float(n)


def register(registry) -> None:
    """The instructions of chapter 10 (nothing registers on import)."""
    for name, func in (("movej", I_movej), ("movel", I_movel), ("movec", I_movec), ("waitEndMove", I_waitendmove)):
        registry.instruction(name, func, blocking=True)
    for name, func in (("isEmpty", I_isempty), ("isSettled", I_issettled), ("stopMove", I_stopmove),
                       ("restartMove", I_restartmove), ("resetMotion", I_resetmotion),
                       ("autoConnectMove", I_autoconnectmove), ("getSpeed", I_getspeed),
                       ("getPositionErr", I_getpositionerr), ("getJointForce", I_getjointforce),
                       ("getMoveId", I_getmoveid), ("setMoveId", I_setmoveid)):
        registry.instruction(name, func)
