"""Chapter 9 in the virtual controller: the geometry (`val3check.geometry`) and the arm model
(`val3check.robot`) behind the VAL 3 instructions and operators.

Values (values.py): trsf, frame, tool and point are the geometry's objects; joint and config
stay dicts of their fields (`j.j1 = 5` and `c.shoulder = lefty` are plain writes) and are
converted here, at the instruction boundary, to the tuples the geometry takes (`jt`, `ct`) and
back (`jd`, `cd`). A point's `config` is such a dict: every point this module returns gets its
own.

Without an arm model (no `--robot`, no arm.cfx), what needs one (herej, here, jointToPoint,
pointToJoint, config(joint), isInRange) stops the task with R002 after the checks that need no
arm (160-165); the pure geometry (trsf operators, compose, appro, position, distance, link,
setFrame, interpolateL/C, align, joint operators) always works. With one, the arm stands at its
initial joint position (zeros, or the scenario's ``[robot] joints``): motion is not simulated in
this version, so the commanded position never changes.

Lengths: the arm model works in millimetres, the application in its unit (2.1.4.1): `Arm.kin`
gives the geometry a `Kinematics` in the unit of the application or library executing the line.
"""

from __future__ import annotations

from typing import Any

from ..geometry import arm as GA
from ..geometry import frames as GF
from ..geometry import jointops as GJ
from ..geometry import points as GP
from ..geometry import rotation as R
from ..geometry import trsf as GT
from ..geometry.frames import Frame, Tool
from ..geometry.points import Point
from ..geometry.trsf import Trsf
from ..language.runtime_errors import Val3RuntimeError
from .instructions import async_, sync
from .runtime import DELAY, IOW, SimLimit

E = Val3RuntimeError
INCH_MM = 25.4

NO_ARM = ("needs the arm model: pass --robot NAME (a catalogue arm such as tx2-60, listed by `val3check robots`), "
          "--robot path/to/arm.urdf, or run the application from a controller tree whose usr/configs/arm.cfx "
          "names the arm")


# ---- conversions: joint and config dicts <-> geometry tuples ----------------------------------------


def jt(j: dict) -> tuple[float, ...]:
    """A joint dict {j1, j2, ...} (in field order) -> tuple."""
    return tuple(j.values())


def jd(j) -> dict[str, float]:
    return {f"j{i}": float(v) + 0.0 for i, v in enumerate(j, 1)}


def ct(c: dict) -> tuple[str, ...]:
    """A config dict -> ("lefty", "epositive", "wsame") (RS arms: only the shoulder)."""
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


class UnitKinematics:
    """A `RobotModel` seen by the geometry (`geometry.arm.Kinematics`) in the application's
    length unit: poses in and out are scaled by `scale` (millimetres per unit)."""

    def __init__(self, model: Any, scale: float) -> None:
        self.model = model
        self.scale = scale

    def fk(self, joints):
        x, y, z, rx, ry, rz = self.model.fk(joints)
        s = self.scale
        if s != 1.0:
            x, y, z = x / s, y / s, z / s
        return (x, y, z, rx, ry, rz)

    def ik(self, pose, config, near):
        x, y, z, rx, ry, rz = pose
        s = self.scale
        return self.model.ik((x * s, y * s, z * s, rx, ry, rz), config=tuple(config), near=near)

    def config_of(self, joints):
        return self.model.config_of(joints)

    def in_limits(self, joints) -> bool:
        return self.model.in_limits(joints)


class Arm:
    """The arm of a simulation: its model and its commanded joint position (degrees). Motion is
    not simulated in this version: the position stays the initial one (all zeros, or the
    scenario's ``[robot] joints``)."""

    def __init__(self, model: Any, joints=None) -> None:
        self.model = model
        self.name = model.name
        n = len(model.joint_limits)
        self.joints: tuple[float, ...] = tuple(float(v) for v in joints) if joints is not None else (0.0,) * n
        self.initial = self.joints
        self._kin: dict[bool, UnitKinematics] = {}

    def start_at(self, joints) -> None:
        """The initial commanded position (scenario ``[robot] joints``)."""
        self.joints = self.initial = tuple(float(v) + 0.0 for v in joints)

    @property
    def axes(self) -> int:
        return len(self.model.joint_limits)

    def kin(self, A) -> UnitKinematics:
        """The kinematics in the length unit of the unit `A` (application or library)."""
        mm = getattr(A.model, "millimeter_unit", True)
        k = self._kin.get(mm)
        if k is None:
            k = self._kin[mm] = UnitKinematics(self.model, 1.0 if mm else INCH_MM)
        return k

    def check_axes(self, j: tuple, what: str) -> None:
        if len(j) != self.axes:
            raise E(81, f"{what}: a joint value with {len(j)} axes for the {self.axes}-axis arm {self.name}")


def _arm(T, what: str) -> Arm:
    arm = T.M.arm
    if arm is None:
        raise SimLimit("arm", what, f"instruction {what} {NO_ARM}")
    return arm


def _ik_unsupported(what: str, arm: Arm, exc: Exception):
    return SimLimit("arm", what, f"instruction {what} needs the closed-form kinematics (configurations, inverse) "
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
        GP.assign(dst, src)
        if dst is not src:
            dst.config = dict(src.config)
    else:
        GF.assign(dst, src)
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


def CPL(v):
    from .values import copy_local

    return copy_local(v)


# ---- joint operators (9.2.2, 9.2.3): field by field, 81 when the axis counts differ ----------------


def JADD(a: dict, b: dict) -> dict:
    return jd(GJ.add(jt(a), jt(b)))


def JSUB(a: dict, b: dict) -> dict:
    return jd(GJ.sub(jt(a), jt(b)))


def JGT(a: dict, b: dict) -> bool:
    """9.2.2: true when EVERY field is strictly greater (not the negation of <)."""
    return GJ.gt(jt(a), jt(b))


def JLT(a: dict, b: dict) -> bool:
    return GJ.lt(jt(a), jt(b))


def JEQ(a: dict, b: dict) -> bool:
    """9.2.2: every field equal "à la précision du robot près" (geometry.jointops.JOINT_EPS)."""
    return GJ.eq(jt(a), jt(b))


def JNE(a: dict, b: dict) -> bool:
    return GJ.ne(jt(a), jt(b))


def JABS(a: dict) -> dict:
    return jd(GJ.abs_(jt(a)))


# ---- instructions of chapter 9 ---------------------------------------------------------------------


@sync
def I_herej(T, A) -> dict:
    """9.2.3 herej(): the commanded joint position."""
    return jd(_arm(T, "herej").joints)


@sync
def I_isinrange(T, A, j: dict) -> bool:
    """9.2.3 isInRange(joint): within the model's software joint limits, bounds included."""
    arm = _arm(T, "isInRange")
    return GJ.is_in_range(jt(j), arm.model.joint_limits)


@sync
def I_distance(T, A, a, b) -> float:
    """9.3.4 distance(trsf, trsf), 9.6.3 distance(point, point)."""
    if type(a) is Point:
        return GP.distance(a, b)
    return GT.distance(a, b)


@sync
def I_interpolatel(T, A, start: Trsf, end: Trsf, s: float) -> Trsf:
    return GT.interpolate_l(start, end, s)


@sync
def I_interpolatec(T, A, start: Trsf, mid: Trsf, end: Trsf, s: float) -> Trsf:
    return GT.interpolate_c(start, mid, end, s)


@sync
def I_align(T, A, tr: Trsf, ref: Trsf) -> Trsf:
    return GT.align(tr, ref)


@sync
def I_setframe(T, A, origin: Point, on_x: Point, in_xy: Point, result) -> float:
    """9.4.4 setFrame: 0, 1 (pAxeOx too close to pOrigine), 2 (pPlanOxy too close to (Ox))."""
    c, k = result
    return float(GP.set_frame(origin, on_x, in_xy, c[k]))


@sync
def I_position(T, A, obj, ref) -> Trsf:
    """9.4.4 / 9.5.4 / 9.6.3 position(frame|tool|point, reference)."""
    if type(obj) is Point:
        return GP.position(obj, ref)
    return GF.position(obj, ref)


@sync
def I_link(T, A, obj, ref) -> None:
    """9.4.4 / 9.5.4 / 9.6.3 link(frame|tool|point, reference)."""
    if type(obj) is Point:
        GP.link(obj, ref)
    else:
        GF.link(obj, ref)


@sync
def I_compose(T, A, p: Point, ref: Frame, tr: Trsf) -> Point:
    """9.6.3 compose: reference frame and configuration of the result are those of p."""
    return _point(GP.compose(p, ref, tr), p.config)


@sync
def I_appro(T, A, p: Point, tr: Trsf) -> Point:
    return _point(GP.appro(p, tr), p.config)


@sync
def I_here(T, A, tool: Tool, ref: Frame) -> Point:
    """9.6.3 here(tool, frame): jointToPoint at the commanded position."""
    GF.check_defined(tool)
    GF.check_defined(ref)
    arm = _arm(T, "here")
    try:
        p = GA.here(arm.kin(A), arm.joints, tool, ref)
    except _robot_errors() as exc:
        raise _ik_unsupported("here", arm, exc) from None
    return _point(p, p.config)


@sync
def I_jointtopoint(T, A, tool: Tool, ref: Frame, j: dict) -> Point:
    GF.check_defined(tool)
    GF.check_defined(ref)
    arm = _arm(T, "jointToPoint")
    jj = jt(j)
    arm.check_axes(jj, "jointToPoint")
    try:
        p = GA.joint_to_point(arm.kin(A), tool, ref, jj)
    except _robot_errors() as exc:
        raise _ik_unsupported("jointToPoint", arm, exc) from None
    return _point(p, p.config)


@sync
def I_pointtojoint(T, A, tool: Tool, initial: dict, p: Point, result) -> bool:
    """9.6.3 pointToJoint: true and jResult set to the solution nearest jInitial in the point's
    configuration (free/same resolved against jInitial); false, jResult unchanged, when no joint
    position of the model reaches the point within the joint limits."""
    GF.check_defined(tool)
    GP.check_defined(p)
    arm = _arm(T, "pointToJoint")
    ji = jt(initial)
    arm.check_axes(ji, "pointToJoint")
    try:
        ok, j = GA.point_to_joint(arm.kin(A), tool, ji, _geo_point(p))
    except _robot_errors() as exc:
        raise _ik_unsupported("pointToJoint", arm, exc) from None
    if ok:
        c, k = result
        c[k] = jd(j)
    return ok


@sync
def I_config(T, A, j: dict) -> dict:
    """9.7.6 config(joint): the configuration of the arm at that joint position (9.7.4)."""
    arm = _arm(T, "config")
    jj = jt(j)
    arm.check_axes(jj, "config")
    try:
        return cd(GA.config_of(arm.kin(A), jj))
    except _robot_errors() as exc:
        raise _ik_unsupported("config", arm, exc) from None


@sync
def I_movej(T, A, target, tool: Tool, mdesc: dict) -> float:
    """10.6 movej: motion is not simulated in this version (R002), but a target that the arm
    model shows no joint position can reach (out of reach, outside the joint limits, or not in
    the point's configuration from the commanded position) is error 154 (12.1: "cible hors de
    portée"), as the manual says movej raises it. Errors 160-165 of the tool and point first."""
    GF.check_defined(tool)
    arm = T.M.arm
    if type(target) is dict:  # a joint position
        if arm is not None:
            j = jt(target)
            arm.check_axes(j, "movej")
            if not GJ.is_in_range(j, arm.model.joint_limits):
                raise E(154, f"movej: the joint position is outside the software joint limits of {arm.name}")
    else:
        flange = R.pose_mul(GP.world_pose(target), R.pose_inv(GF.root_pose(tool)))
        if arm is not None:
            from ..robot.errors import Unreachable

            x, y, z, rx, ry, rz = Trsf.from_pose(flange).as_tuple()
            s = arm.kin(A).scale
            try:
                arm.model.solve((x * s, y * s, z * s, rx, ry, rz), ct(target.config), initial=arm.joints)
            except Unreachable as exc:
                raise E(154, f"movej: no joint position of {arm.name} reaches the point ({exc})") from None
            except _robot_errors() as exc:
                raise _ik_unsupported("movej", arm, exc) from None
    raise SimLimit("arm", "movej")


@async_
def I_open(T, A, tool: Tool):
    """9.5.4 open(tool): waitEndMove(), gripper = true, delay(otime). No motion command is ever
    accepted in this version (movej/movel/movec stop the task), so there is no motion to wait
    for: the output is set at once."""
    IOW(T, tool.gripper, True)
    yield from DELAY(T, tool.otime)


@async_
def I_close(T, A, tool: Tool):
    """9.5.4 close(tool): waitEndMove(), gripper = false, delay(ctime) (see open)."""
    IOW(T, tool.gripper, False)
    yield from DELAY(T, tool.ctime)


def _robot_errors() -> tuple[type[Exception], ...]:
    from ..robot.errors import IKUnsupported

    return (IKUnsupported,)


NAMESPACE = {name: globals()[name] for name in (
    "TRSF", "FRAMELIT", "TOOLLIT", "POINTLIT", "NASG", "NSET", "TINV", "CPL", "JADD", "JSUB", "JGT", "JLT", "JEQ",
    "JNE", "JABS")}
