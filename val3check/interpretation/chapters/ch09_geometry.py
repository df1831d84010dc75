"""Chapter 9: the geometry (`val3check.geometry`) behind the trsf, frame, tool, point, joint
and config instructions and operators, and the arm behind herej(), here(), jointToPoint(),
pointToJoint(), config(joint) and isInRange().

The arm is read through the `Arm` port (arm_port.py: the commanded joints at the current
simulated time, the kinematics in the unit of the application or library executing the line).
Without an arm model (no `--robot`, no arm.cfx), what needs one stops the task with R002
after the checks that need no arm (160-165); the pure geometry always works.

Values (values.py): trsf, frame, tool and point are the geometry's objects; joint and config
stay dicts of their fields (`j.j1 = 5` and `c.shoulder = lefty` are plain writes) and are
converted here, at the instruction boundary, to the tuples the geometry takes (`jt`, `ct`) and
back (`jd`, `cd`). A point's `config` is such a dict: every point this module returns gets its
own.
"""

from __future__ import annotations

from ...geometry import arm as geo_arm
from ...geometry import frames as geo_frames
from ...geometry import jointops
from ...geometry import points as geo_points
from ...geometry import trsf as geo_trsf
from ...geometry.frames import Frame, Tool
from ...geometry.points import Point
from ...geometry.trsf import Trsf
from ...language.runtime_errors import Val3RuntimeError
from ..arm_port import KinematicsUnsupported
from ..not_simulated import ARM_LIMIT, NO_ARM, SimLimit
from ..values import copy_local
from ..waiting import DELAY, WAIT
from .ch03_simple_types import IOW

E = Val3RuntimeError


# ---- conversions: joint and config dicts <-> geometry tuples ----------------------------------------


def jt(j: dict) -> tuple[float, ...]:
    """A joint dict {j1, j2, ...} (in field order) -> tuple."""
    return tuple(j.values())


def jd(j) -> dict[str, float]:
    return {f"j{i}": float(v) + 0.0 for i, v in enumerate(j, 1)}


def ct(c: dict) -> tuple[str, ...]:
    """A config dict -> ("lefty", "epositive", "wsame") (RS arms: only the shoulder)."""
    if len(c) == 3 and "shoulder" in c and "elbow" in c and "wrist" in c:  # (each motion command: no generator)
        return (c["shoulder"], c["elbow"], c["wrist"])
    return tuple(c[f] for f in ("shoulder", "elbow", "wrist") if f in c)


def cd(c) -> dict[str, str]:
    return dict(zip(("shoulder", "elbow", "wrist"), c))


def _point(p: Point, config: dict | tuple) -> Point:
    """A point the geometry returned, with an interpreter config (a dict of its own)."""
    p.config = dict(config) if type(config) is dict else cd(config)
    return p


def _geo_point(p: Point) -> Point:
    """The same point with the geometry's config tuple (for the functions that read it)."""
    return Point(p.trsf, ct(p.config), p.ref, name=p.name, local=p.local)


# ---- the arm -------------------------------------------------------------------------------------


def millimeter_unit(unit) -> bool:
    """The length unit of the application or library executing the line (2.1.4.1)."""
    return getattr(unit.model, "millimeter_unit", True)


def arm_of(task, what: str):
    """The arm port, with a model (else the task stops with R002, saying how to give one)."""
    arm = task.machine.arm
    if not arm.has_model:
        raise SimLimit(ARM_LIMIT, what, f"instruction {what} {NO_ARM}")
    return arm


def check_axes(arm, j: tuple, what: str) -> None:
    if len(j) != arm.axes:
        raise E(81, f"{what}: a joint value with {len(j)} axes for the {arm.axes}-axis arm {arm.name}")


def unsupported(what: str, arm, exc: Exception) -> SimLimit:
    return SimLimit(ARM_LIMIT, what, f"instruction {what} needs the closed-form kinematics (configurations, inverse) "
                                     f"of the arm model {arm.name}, which it does not have ({exc})")


# ---- values made by the compiled code --------------------------------------------------------------


def TRSF(x: float = 0.0, y: float = 0.0, z: float = 0.0, rx: float = 0.0, ry: float = 0.0, rz: float = 0.0) -> Trsf:
    """A `{x, y, z, rx, ry, rz}` literal (2.4.2)."""
    return Trsf(x, y, z, rx, ry, rz)


def FRAMELIT(tr: Trsf) -> Frame:
    """A frame literal `{x, y, z, rx, ry, rz}`: its trsf; no reference (a new local value)."""
    return Frame(tr, None, local=True)


def TOOLLIT(tr: Trsf, gripper, otime: float, ctime: float) -> Tool:
    return Tool(tr, None, gripper=gripper, otime=otime, ctime=ctime, local=True)


def POINTLIT(tr: Trsf, config: dict) -> Point:
    p = Point(tr, (), None, local=True)
    p.config = config
    return p


def NASG(dst, src):
    """`=` for frame, tool and point (9.4.3, 9.5.3, 9.6.2): position, reference (and config,
    gripper, times) copied INTO the variable's node, which keeps its identity; 165 when a
    global would get a local reference. Returns the variable's value."""
    if type(dst) is Point:
        geo_points.assign(dst, src)
        if dst is not src:
            dst.config = dict(src.config)
    else:
        geo_frames.assign(dst, src)
    return dst


def NSET(dst, lit):
    """`p = {{x, ...}, {sfree, ...}}` (2.4.2): the literal's fields are written into the
    variable, which keeps its reference frame/tool."""
    dst.trsf = lit.trsf.copy()  # the literal's fields may be variables ({trA, cA}): copies
    tl = type(lit)
    if tl is Point:
        dst.config = dict(lit.config)
    elif tl is Tool:
        dst.gripper, dst.otime, dst.ctime = lit.gripper, lit.otime, lit.ctime
    return dst


def TINV(tr: Trsf) -> Trsf:
    """trsf `!` (9.3.3)."""
    return tr.inverse()


# ---- joint operators (9.2.2, 9.2.3): field by field, 81 when the axis counts differ ----------------


def JADD(a: dict, b: dict) -> dict:
    return jd(jointops.add(jt(a), jt(b)))


def JSUB(a: dict, b: dict) -> dict:
    return jd(jointops.sub(jt(a), jt(b)))


def JGT(a: dict, b: dict) -> bool:
    """9.2.2: true when EVERY field is strictly greater (not the negation of <)."""
    return jointops.gt(jt(a), jt(b))


def JLT(a: dict, b: dict) -> bool:
    return jointops.lt(jt(a), jt(b))


def JEQ(a: dict, b: dict) -> bool:
    """9.2.2: every field equal "à la précision du robot près" (geometry.jointops.JOINT_EPS)."""
    return jointops.eq(jt(a), jt(b))


def JNE(a: dict, b: dict) -> bool:
    return jointops.ne(jt(a), jt(b))


def JABS(a: dict) -> dict:
    return jd(jointops.abs_(jt(a)))


# ---- instructions of chapter 9 ---------------------------------------------------------------------


def I_herej(task, unit) -> dict:
    """9.2.3 herej(): the commanded joint position."""
    return jd(arm_of(task, "herej").joints_at(task.machine.clock.time_of(task), millimeter_unit(unit)))


def I_isinrange(task, unit, j: dict) -> bool:
    """9.2.3 isInRange(joint): within the model's software joint limits, bounds included."""
    arm = arm_of(task, "isInRange")
    jj = jt(j)
    check_axes(arm, jj, "isInRange")
    return jointops.is_in_range(jj, arm.joint_limits_in(millimeter_unit(unit)))


def I_distance(task, unit, a, b) -> float:
    """9.3.4 distance(trsf, trsf), 9.6.3 distance(point, point)."""
    if type(a) is Point:
        return geo_points.distance(a, b)
    return geo_trsf.distance(a, b)


def I_interpolatel(task, unit, start: Trsf, end: Trsf, s: float) -> Trsf:
    return geo_trsf.interpolate_l(start, end, s)


def I_interpolatec(task, unit, start: Trsf, mid: Trsf, end: Trsf, s: float) -> Trsf:
    return geo_trsf.interpolate_c(start, mid, end, s)


def I_align(task, unit, tr: Trsf, ref: Trsf) -> Trsf:
    return geo_trsf.align(tr, ref)


def I_setframe(task, unit, origin: Point, on_x: Point, in_xy: Point, result) -> float:
    """9.4.4 setFrame: 0, 1 (pAxeOx too close to pOrigine), 2 (pPlanOxy too close to (Ox))."""
    c, k = result
    return float(geo_points.set_frame(origin, on_x, in_xy, c[k]))


def I_position(task, unit, obj, ref) -> Trsf:
    """9.4.4 / 9.5.4 / 9.6.3 position(frame|tool|point, reference)."""
    if type(obj) is Point:
        return geo_points.position(obj, ref)
    return geo_frames.position(obj, ref)


def I_link(task, unit, obj, ref) -> None:
    """9.4.4 / 9.5.4 / 9.6.3 link(frame|tool|point, reference)."""
    if type(obj) is Point:
        geo_points.link(obj, ref)
    else:
        geo_frames.link(obj, ref)


def I_compose(task, unit, p: Point, ref: Frame, tr: Trsf) -> Point:
    """9.6.3 compose: reference frame and configuration of the result are those of p."""
    return _point(geo_points.compose(p, ref, tr), p.config)


def I_appro(task, unit, p: Point, tr: Trsf) -> Point:
    return _point(geo_points.appro(p, tr), p.config)


def I_here(task, unit, tool: Tool, ref: Frame) -> Point:
    """9.6.3 here(tool, frame): jointToPoint at the commanded position."""
    geo_frames.check_defined(tool)
    geo_frames.check_defined(ref)
    arm = arm_of(task, "here")
    try:
        mm = millimeter_unit(unit)
        p = geo_arm.here(arm.kinematics(mm), arm.joints_at(task.machine.clock.time_of(task), mm), tool, ref)
    except KinematicsUnsupported as exc:
        raise unsupported("here", arm, exc) from None
    return _point(p, p.config)


def I_jointtopoint(task, unit, tool: Tool, ref: Frame, j: dict) -> Point:
    geo_frames.check_defined(tool)
    geo_frames.check_defined(ref)
    arm = arm_of(task, "jointToPoint")
    jj = jt(j)
    check_axes(arm, jj, "jointToPoint")
    try:
        p = geo_arm.joint_to_point(arm.kinematics(millimeter_unit(unit)), tool, ref, jj)
    except KinematicsUnsupported as exc:
        raise unsupported("jointToPoint", arm, exc) from None
    return _point(p, p.config)


def I_pointtojoint(task, unit, tool: Tool, initial: dict, p: Point, result) -> bool:
    """9.6.3 pointToJoint: true and jResult set to the solution nearest jInitial in the point's
    configuration (free/same resolved against jInitial); false, jResult unchanged, when no joint
    position of the model reaches the point within the joint limits."""
    geo_frames.check_defined(tool)
    geo_points.check_defined(p)
    arm = arm_of(task, "pointToJoint")
    ji = jt(initial)
    check_axes(arm, ji, "pointToJoint")
    try:
        ok, j = geo_arm.point_to_joint(arm.kinematics(millimeter_unit(unit)), tool, ji, _geo_point(p))
    except KinematicsUnsupported as exc:
        raise unsupported("pointToJoint", arm, exc) from None
    if ok:
        c, k = result
        c[k] = jd(j)
    return ok


def I_config(task, unit, j: dict) -> dict:
    """9.7.6 config(joint): the configuration of the arm at that joint position (9.7.4)."""
    arm = arm_of(task, "config")
    jj = jt(j)
    check_axes(arm, jj, "config")
    try:
        return cd(geo_arm.config_of(arm.kinematics(millimeter_unit(unit)), jj))
    except KinematicsUnsupported as exc:
        raise unsupported("config", arm, exc) from None


def wait_end_of_motion(task, what: str):
    """waitEndMove() (10.6), and open()/close() before they act (9.5.4): the blend of the last
    command is cancelled (error 150 when a motion recorded before cannot be executed), then the
    task waits on the arm's motion queue; the clock jumps to the end of the motion. (A function
    that returns the wait, called at the first step of its caller: one generator less to make
    and to pass through at each resumption.)"""
    machine = task.machine
    machine.arm.end_motion(machine.clock.time_of(task))
    return WAIT(task, machine.motion_done, False, _END_OF_MOTION.get(what) or f"{what} (end of motion)")


_END_OF_MOTION = {w: f"{w} (end of motion)" for w in ("open", "close", "waitEndMove")}


def _tool_action(task, unit, tool: Tool, action: str, value: bool, seconds: float):
    yield from wait_end_of_motion(task, action)
    machine = task.machine
    machine.tool_action(task, action, tool, millimeter_unit(unit))
    IOW(task, tool.gripper, value)
    yield from DELAY(task, seconds)


def I_open(task, unit, tool: Tool):
    """9.5.4 open(tool): waitEndMove(), gripper = true, delay(otime). (Returns the action's
    generator, for `yield from`: not a generator of its own.)"""
    return _tool_action(task, unit, tool, "open", True, tool.otime)


def I_close(task, unit, tool: Tool):
    """9.5.4 close(tool): waitEndMove(), gripper = false, delay(ctime)."""
    return _tool_action(task, unit, tool, "close", False, tool.ctime)


# ---- what s8 (CS9) adds, language/s8.toml ---------------------------------------------------------


def I_getjntref(task, unit, name: str) -> dict:
    """joint getJntRef(sName): a joint reference of the arm's configuration (arm.cfx
    <JntReferences>), which the simulator does not read: the arm's position at the start of the
    run (the scenario's [robot] joints), with R041."""
    arm = task.machine.arm
    task.machine.note_outside(task, f'getJntRef("{name}"): the arm configuration\'s joint references are not read: '
                                    "the value is the arm's position at the start of the run")
    j = tuple(arm.initial_joints) if arm.has_model else (0.0,) * 6
    return jd(j)


def I_setpayload(task, unit, tool, mass: float, center, inertia) -> None:
    """setPayload(tool, nMass, trCenter, nInertia[]): the payload carried by a tool; the
    simulated motion does not depend on masses (docs/motion.md): recorded, with R041."""
    task.machine.transcript_add(task, "setPayload", f"{getattr(tool, 'name', '') or 'tool'}: {mass:g} kg", None)
    task.machine.note_outside(task, "setPayload: the simulated motion does not depend on the payload: recorded in the "
                                    "transcript")


def register(registry) -> None:
    registry.instruction("getJntRef", I_getjntref)
    registry.instruction("setPayload", I_setpayload)
    registry.helpers(TRSF=TRSF, FRAMELIT=FRAMELIT, TOOLLIT=TOOLLIT, POINTLIT=POINTLIT, NASG=NASG, NSET=NSET,
                     TINV=TINV, CPL=copy_local, JADD=JADD, JSUB=JSUB, JGT=JGT, JLT=JLT, JEQ=JEQ, JNE=JNE, JABS=JABS)
    for name, func in (("herej", I_herej), ("isInRange", I_isinrange), ("distance", I_distance),
                       ("interpolateL", I_interpolatel), ("interpolateC", I_interpolatec), ("align", I_align),
                       ("setFrame", I_setframe), ("position", I_position), ("link", I_link), ("compose", I_compose),
                       ("appro", I_appro), ("here", I_here), ("jointToPoint", I_jointtopoint),
                       ("pointToJoint", I_pointtojoint), ("config", I_config)):
        registry.instruction(name, func)
    registry.instruction("open", I_open, blocking=True)
    registry.instruction("close", I_close, blocking=True)

