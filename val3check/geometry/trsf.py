"""The `trsf` type (manual 9.3): value type, operators of 9.3.3 and instructions of 9.3.4.

`Trsf(x, y, z, rx, ry, rz)`: x, y, z in the application's length unit (mm or inch, 2.1.4.1:
the geometry never converts, a length is just a number), rx, ry, rz in degrees about x, y', z''
(9.3.2). A `Trsf` is mutable (the interpreter assigns fields: ``tr.x = 5``); every operation
returns a new object and never returns or keeps one of its arguments.

Angles written by the program are kept as written; angles that an operation computes are in
the canonical form of 9.3.2 (`rotation.py`).
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence

from ..language.runtime_errors import Val3RuntimeError

from . import rotation as R

FIELDS = ("x", "y", "z", "rx", "ry", "rz")

# interpolateC: positions closer than this (length unit) do not define an arc; three positions
# whose triangle has a relative area below COLLINEAR_EPS are aligned. The manual states no value.
ARC_MIN_DISTANCE = 1e-6
COLLINEAR_EPS = 1e-9
# 10.1.4.1: an arc or an orientation change of 180 degrees "or more" between the intermediate
# position and the start or the end is ambiguous; this is the tolerance on "180" (degrees).
AMBIGUITY_EPS = 1e-6


class Trsf:
    """A geometric transformation {x, y, z, rx, ry, rz} (9.3.1); default {0,0,0,0,0,0}."""

    __slots__ = FIELDS

    def __init__(self, x: float = 0.0, y: float = 0.0, z: float = 0.0,
                 rx: float = 0.0, ry: float = 0.0, rz: float = 0.0) -> None:
        self.x = float(x)
        self.y = float(y)
        self.z = float(z)
        self.rx = float(rx)
        self.ry = float(ry)
        self.rz = float(rz)

    # --- construction and conversion ------------------------------------------------------

    @classmethod
    def of(cls, values: Sequence[float]) -> Trsf:
        """From a 6-sequence (x, y, z, rx, ry, rz), e.g. the result of `Kinematics.fk`."""
        return cls(*values)

    @classmethod
    def from_dict(cls, d: dict) -> Trsf:
        """From the interpreter's dict shape {"x": .., "y": .., ..., "rz": ..}."""
        return cls(d["x"], d["y"], d["z"], d["rx"], d["ry"], d["rz"])

    def to_dict(self) -> dict[str, float]:
        return {"x": self.x, "y": self.y, "z": self.z, "rx": self.rx, "ry": self.ry, "rz": self.rz}

    def as_tuple(self) -> tuple[float, float, float, float, float, float]:
        return (self.x, self.y, self.z, self.rx, self.ry, self.rz)

    def __iter__(self) -> Iterator[float]:
        return iter((self.x, self.y, self.z, self.rx, self.ry, self.rz))

    # Field access by name (``tr["x"]``): the interpreter's (container, key) places, e.g. a
    # field passed by reference, ``call f(tr.x)`` (2.6.2).
    def __getitem__(self, name: str) -> float:
        return getattr(self, name)

    def __setitem__(self, name: str, value: float) -> None:
        setattr(self, name, value)

    def copy(self) -> Trsf:
        return Trsf(self.x, self.y, self.z, self.rx, self.ry, self.rz)

    def rotation(self) -> R.Mat:
        """Row-major 3x3 rotation matrix Rx(rx) Ry(ry) Rz(rz)."""
        return R.matrix(self.rx, self.ry, self.rz)

    def matrix4(self) -> tuple[tuple[float, float, float, float], ...]:
        """Homogeneous 4x4 matrix (rows)."""
        m = self.rotation()
        return ((m[0], m[1], m[2], self.x), (m[3], m[4], m[5], self.y), (m[6], m[7], m[8], self.z),
                (0.0, 0.0, 0.0, 1.0))

    @classmethod
    def from_rotation(cls, m: R.Mat, p: Sequence[float] = (0.0, 0.0, 0.0)) -> Trsf:
        """From a row-major 3x3 rotation and a translation; angles in canonical form."""
        rx, ry, rz = R.angles_of(tuple(m))  # type: ignore[arg-type]
        return cls(p[0], p[1], p[2], rx, ry, rz)

    @classmethod
    def from_matrix4(cls, m: Sequence[Sequence[float]]) -> Trsf:
        """From a homogeneous 4x4 matrix (rows); angles in canonical form."""
        rot = (m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2])
        return cls.from_rotation(rot, (m[0][3], m[1][3], m[2][3]))

    def pose(self) -> R.Pose:
        return R.pose(self.x, self.y, self.z, self.rx, self.ry, self.rz)

    @classmethod
    def from_pose(cls, p: R.Pose) -> Trsf:
        rx, ry, rz = R.pose_angles(p)
        t = p[1]
        return cls(t[0] + 0.0, t[1] + 0.0, t[2] + 0.0, rx, ry, rz)

    def canonical(self) -> Trsf:
        """Same transformation, angles in the canonical form of 9.3.2."""
        rx, ry, rz = R.canonical_angles(self.rx, self.ry, self.rz)
        return Trsf(self.x, self.y, self.z, rx, ry, rz)

    def is_identity(self) -> bool:
        return self.x == self.y == self.z == self.rx == self.ry == self.rz == 0.0

    # --- operators of 9.3.3 ---------------------------------------------------------------

    def __eq__(self, other: object) -> bool:
        """9.3.3: true when every field equals the corresponding field (exactly, as `num` ==:
        the manual states no tolerance for trsf, unlike joint)."""
        if not isinstance(other, Trsf):
            return NotImplemented
        return (self.x == other.x and self.y == other.y and self.z == other.z
                and self.rx == other.rx and self.ry == other.ry and self.rz == other.rz)

    def __ne__(self, other: object) -> bool:
        r = self.__eq__(other)
        return r if r is NotImplemented else not r

    __hash__ = None  # type: ignore[assignment]  # mutable

    def __mul__(self, other: Trsf) -> Trsf:
        """9.3.3 `*`: geometric composition (other expressed in self's frame)."""
        if not isinstance(other, Trsf):
            return NotImplemented
        return Trsf.from_pose(R.pose_mul(self.pose(), other.pose()))

    def inverse(self) -> Trsf:
        """9.3.3 `!`: the inverse transformation."""
        return Trsf.from_pose(R.pose_inv(self.pose()))

    __invert__ = inverse  # ~tr in Python stands for !tr in VAL 3

    def __repr__(self) -> str:
        return "Trsf({:g}, {:g}, {:g}, {:g}, {:g}, {:g})".format(*self.as_tuple())


def close(a: Trsf, b: Trsf, length_tol: float = 1e-9, angle_tol: float = 1e-9) -> bool:
    """Same transformation up to tolerances (translation distance, rotation angle in degrees),
    whatever the angle triples (180,0,0) vs (-180,0,0). Not a VAL 3 operator: for tests/tools."""
    if math.dist((a.x, a.y, a.z), (b.x, b.y, b.z)) > length_tol:
        return False
    angle, _ = R.rotation_between(a.rotation(), b.rotation())
    return angle <= angle_tol


# --- instructions of 9.3.4 --------------------------------------------------------------------


def distance(a: Trsf, b: Trsf) -> float:
    """9.3.4 distance(trsf, trsf): distance between the two positions (translations); valid
    when both are expressed in the same reference frame. Orientation is not used."""
    return math.sqrt((a.x - b.x) ** 2 + (a.y - b.y) ** 2 + (a.z - b.z) ** 2)


def _lerp(a: float, b: float, s: float) -> float:
    # a + (b - a) * s, arranged to give exactly a at s = 0 and exactly b at s = 1
    return a + (b - a) * s if s < 0.5 else b - (b - a) * (1.0 - s)


def interpolate_l(start: Trsf, end: Trsf, s: float) -> Trsf:
    """9.3.4 interpolateL(trStart, trEnd, nPosition).

    x = start.x + (end.x - start.x) * s, the same for y and z; the orientation turns by the
    fraction s of the smallest rotation from start to end (10.1.4.1: the trajectory generator
    minimises the amplitude of rotations). s outside ]-1, 2[: error 70. At a 180-degree
    orientation change, both senses are as short: the sense is arbitrary (no error: the manual
    states the ambiguity error for circles only)."""
    s = float(s)
    if not (-1.0 < s < 2.0):
        raise Val3RuntimeError(70, f"interpolateL: nPosition {s:g} is outside ]-1, 2[")
    x, y, z = _lerp(start.x, end.x, s), _lerp(start.y, end.y, s), _lerp(start.z, end.z, s)
    if s == 0.0:
        return Trsf(x, y, z, *R.canonical_angles(start.rx, start.ry, start.rz))
    if s == 1.0:
        return Trsf(x, y, z, *R.canonical_angles(end.rx, end.ry, end.rz))
    m = R.slerp(start.rotation(), end.rotation(), s)
    return Trsf(x, y, z, *R.angles_of(m))


def arc(p1: R.Vec, p2: R.Vec, p3: R.Vec) -> tuple[R.Vec, float, R.Vec, R.Vec, float, float]:
    """The circle through p1, p2, p3 travelled from p1 through p2 to p3:
    (centre, radius, e1, e2, angle of p2, angle of p3) with e1 = (p1 - centre)/radius,
    e2 = normal x e1, angles in radians measured from p1 in the sense of travel, so that
    0 < angle(p2) < angle(p3) < 2 pi. Error 70 when the positions are too close or aligned."""
    u = R.sub(p2, p1)
    v = R.sub(p3, p1)
    lu, lv, lw = R.length(u), R.length(v), R.length(R.sub(p3, p2))
    if min(lu, lv, lw) < ARC_MIN_DISTANCE:
        raise Val3RuntimeError(70, "interpolateC: the positions are too close to define an arc")
    w = R.cross(u, v)
    nw = R.length(w)
    if nw < COLLINEAR_EPS * lu * lv:
        raise Val3RuntimeError(70, "interpolateC: the positions are aligned, they define no arc")
    k = 1.0 / (2.0 * nw * nw)
    d = R.cross(R.sub(R.scale(v, R.dot(u, u)), R.scale(u, R.dot(v, v))), w)
    centre = R.add(p1, R.scale(d, k))
    r1 = R.sub(p1, centre)
    radius = R.length(r1)
    e1 = R.scale(r1, 1.0 / radius)
    n = R.scale(w, 1.0 / nw)
    e2 = R.cross(n, e1)

    def ang(p: R.Vec) -> float:
        q = R.sub(p, centre)
        t = math.atan2(R.dot(q, e2), R.dot(q, e1))
        return t + 2.0 * math.pi if t < 0.0 else t

    return centre, radius, e1, e2, ang(p2), ang(p3)


def interpolate_c(start: Trsf, mid: Trsf, end: Trsf, s: float) -> Trsf:
    """9.3.4 interpolateC(trStart, trIntermediate, trEnd, nPosition).

    Position: on the arc of circle from start through mid to end, at the fraction s of the arc
    angle (0 gives start, 1 gives end, 0.5 the middle of the arc; s < 0 before start, s > 1
    after end). Orientation: the smallest rotation from start to mid is spread over the arc
    from start to mid, then the smallest rotation from mid to end over the rest of the arc (so
    a constant orientation stays constant, and an orientation constant relative to the
    trajectory stays so: 10.1.4.1).

    Error 70 (invalid parameter value) when the arc is not defined (positions too close or
    aligned) or when the orientation interpolation is ambiguous (10.1.4.1): mid makes an angle
    of 180 degrees or more with start or end, on the arc or in orientation."""
    s = float(s)
    p1, p2, p3 = (start.x, start.y, start.z), (mid.x, mid.y, mid.z), (end.x, end.y, end.z)
    centre, radius, e1, e2, a2, a3 = arc(p1, p2, p3)
    limit = 180.0 - AMBIGUITY_EPS
    if math.degrees(a2) >= limit or math.degrees(a3 - a2) >= limit:
        raise Val3RuntimeError(
            70, "interpolateC: the intermediate position makes an angle of 180 degrees or more with "
            "the start or the end position: the orientation interpolation is ambiguous (10.1.4.1)")
    m1, m2, m3 = start.rotation(), mid.rotation(), end.rotation()
    ang12, axis12 = R.rotation_between(m1, m2)
    ang23, axis23 = R.rotation_between(m2, m3)
    if ang12 >= limit or ang23 >= limit:
        raise Val3RuntimeError(
            70, "interpolateC: the intermediate orientation is turned by 180 degrees from the start or "
            "the end orientation: the orientation interpolation is ambiguous (10.1.4.1)")
    if s == 0.0:
        return Trsf(start.x, start.y, start.z, *R.canonical_angles(start.rx, start.ry, start.rz))
    if s == 1.0:
        return Trsf(end.x, end.y, end.z, *R.canonical_angles(end.rx, end.ry, end.rz))
    t = s * a3
    c, sn = math.cos(t), math.sin(t)
    p = R.add(centre, R.add(R.scale(e1, radius * c), R.scale(e2, radius * sn)))
    u2 = a2 / a3
    if s <= u2:
        m = R.mat_mul(m1, R.axis_angle(axis12, ang12 * (s / u2))) if ang12 else m1
    else:
        m = R.mat_mul(m2, R.axis_angle(axis23, ang23 * ((s - u2) / (1.0 - u2)))) if ang23 else m2
    return Trsf(p[0] + 0.0, p[1] + 0.0, p[2] + 0.0, *R.angles_of(m))


def align(position: Trsf, reference: Trsf) -> Trsf:
    """9.3.4 align(trPosition, trReference): trPosition with its orientation turned (by the
    smallest rotation) so that its Z axis lies along the nearest of the X, Y, Z axes of
    trReference's orientation (either sense: +axis or -axis, whichever is nearer). x, y, z
    are those of trPosition; the translations of both are not used. Ties between axes go to X
    before Y before Z."""
    m = position.rotation()
    z = R.column(m, 2)
    ref = reference.rotation()
    best, best_dot = R.column(ref, 2), -2.0
    for i in range(3):
        a = R.column(ref, i)
        d = R.dot(z, a)
        if abs(d) > best_dot + 1e-12:
            best, best_dot = (a if d >= 0.0 else R.scale(a, -1.0)), abs(d)
    axis = R.cross(z, best)
    sn = R.length(axis)
    if sn < 1e-15:
        return Trsf(position.x, position.y, position.z, *R.canonical_angles(position.rx, position.ry, position.rz))
    turn = R.axis_angle(R.scale(axis, 1.0 / sn), math.degrees(math.atan2(sn, R.dot(z, best))))
    # New axes: Z is exactly `best`; X is the turned X made exactly orthogonal to it.
    x = R.mat_vec(turn, R.column(m, 0))
    x = R.unit(R.sub(x, R.scale(best, R.dot(x, best))))
    y = R.cross(best, x)
    return Trsf(position.x, position.y, position.z, *R.angles_of(R.from_columns(x, y, best)))
