"""The `point` type (9.6): a trsf in a reference frame, with an arm configuration; and
setFrame (9.4.4), which builds a frame from three points.

A `Point` is a value held by one variable: ``Point(trsf, config, ref)`` where `ref` is the
`Frame` node it is linked to (shared, so re-teaching the frame moves the point, 9.4.2), or None
for a point without reference frame (error 162 as soon as it is used in a computation).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from ..language.runtime_errors import Val3RuntimeError

from . import config_values as C
from . import rotation as R
from .frames import Frame, check_link, root_pose
from .trsf import Trsf

# setFrame (9.4.4): "too close" is not quantified by the manual; length unit.
SETFRAME_MIN_DISTANCE = 1e-6


class Point:
    """A Cartesian point (9.6.1): `trsf` in the frame `ref`, and `config`."""

    __slots__ = ("config", "local", "name", "ref", "trsf")

    def __init__(self, trsf: Trsf | None = None, config: Sequence[str] = C.DEFAULT, ref: Frame | None = None, *,
                 name: str = "", local: bool = False) -> None:
        self.trsf = trsf if trsf is not None else Trsf()
        self.config: C.Config = tuple(config)
        self.ref = ref
        self.name = name
        self.local = local

    def __eq__(self, other: object) -> bool:
        """9.6.2: same position (trsf fields, exactly) in the same reference frame; the
        configuration is not compared."""
        if type(other) is not Point:
            return NotImplemented
        return self.ref is other.ref and self.trsf == other.trsf

    def __ne__(self, other: object) -> bool:
        r = self.__eq__(other)
        return r if r is NotImplemented else not r

    __hash__ = None  # type: ignore[assignment]

    # Field access by name (``p["trsf"]``) for the interpreter's (container, key) places.
    def __getitem__(self, name: str):
        return getattr(self, name)

    def __setitem__(self, name: str, value) -> None:
        setattr(self, name, value)

    def copy(self) -> Point:
        return Point(self.trsf.copy(), self.config, self.ref, name=self.name, local=self.local)

    def __repr__(self) -> str:
        ref = "None" if self.ref is None else (self.ref.name or "?")
        return f"Point({self.trsf!r}, {self.config!r}, ref={ref})"


def _label(p: Point) -> str:
    return f"point {p.name}" if p.name else "a point"


def world_pose(p: Point) -> R.Pose:
    """Pose of `p` in world; 162 when it has no reference frame, then the frame errors."""
    ref = p.ref
    if ref is None:
        raise Val3RuntimeError(162, f"{_label(p)} has no reference frame")
    return R.pose_mul(root_pose(ref), p.trsf.pose())


def check_defined(p: Point) -> None:
    world_pose(p)


def position(p: Point, reference: Frame) -> Trsf:
    """9.6.3 position(point, frame): coordinates of `p` in `reference` (canonical angles)."""
    a = world_pose(p)
    return Trsf.from_pose(R.pose_mul(R.pose_inv(root_pose(reference)), a))


def distance(p1: Point, p2: Point) -> float:
    """9.6.3 distance(point, point): distance between the two positions, in world (the same
    as distance(position(p1, world), position(p2, world)))."""
    a = world_pose(p1)[1]
    b = world_pose(p2)[1]
    return math.sqrt((a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2 + (a[2] - b[2]) ** 2)


def compose(p: Point, reference: Frame, tr: Trsf) -> Point:
    """9.6.3 compose(pPosition, fReference, trTransformation): `p` moved by `tr` expressed in
    `reference`: world(result) = world(reference) * tr * !world(reference) * world(p). The
    rotation of `tr` turns about the origin of `reference`, so it moves x, y, z too unless `p`
    is at that origin. Reference frame and config of the result are those of `p`."""
    if p.ref is None:
        raise Val3RuntimeError(162, f"{_label(p)} has no reference frame")
    rw = root_pose(p.ref)
    fw = root_pose(reference)
    t = tr.pose()
    if t[2] == (0.0, 0.0, 0.0):
        # a pure translation: the orientation of p is kept exactly (9.6.3 example)
        d = R.mat_vec(R.transpose(rw[0]), R.mat_vec(fw[0], t[1]))
        q = p.trsf
        rx, ry, rz = R.canonical_angles(q.rx, q.ry, q.rz)
        return Point(Trsf(q.x + d[0], q.y + d[1], q.z + d[2], rx, ry, rz), p.config, p.ref)
    pw = R.pose_mul(rw, p.trsf.pose())
    moved = R.pose_mul(fw, R.pose_mul(t, R.pose_mul(R.pose_inv(fw), pw)))
    local = R.pose_mul(R.pose_inv(rw), moved)
    return Point(Trsf.from_pose(local), p.config, p.ref)


def appro(p: Point, tr: Trsf) -> Point:
    """9.6.3 appro(pPosition, trTransformation): p.trsf * tr, i.e. `tr` expressed in the axes
    of the point itself (appro(p, {0,0,-100,0,0,0}) is 100 back along the tool's Z axis).
    Reference frame and config of the result are those of `p`; 162 without reference frame."""
    ref = p.ref  # world_pose's errors (no reference frame, undefined or modified frames), not its pose
    if ref is None:
        raise Val3RuntimeError(162, f"{_label(p)} has no reference frame")
    root_pose(ref)
    return Point(p.trsf * tr, p.config, p.ref)


def link(p: Point, reference: Frame) -> None:
    """9.6.3 link(point, frame): `reference` becomes the point's reference frame, its trsf is
    unchanged. 165 when a global point would be linked to a local frame."""
    if type(reference) is not Frame:
        raise TypeError("link(point, frame)")
    check_link(p, reference)
    p.ref = reference


def assign(dst: Point, src: Point) -> None:
    """`=` (9.6.2): copy position, configuration and reference frame (165 as for link)."""
    check_link(dst, src.ref)
    if dst is src:
        return
    dst.trsf = src.trsf.copy()
    dst.config = src.config
    dst.ref = src.ref


def set_frame(origin: Point, on_x: Point, in_xy: Point, result: Frame) -> int:
    """9.4.4 setFrame(pOrigin, pAxisOx, pPlaneOxy, fResult) -> 0, 1 or 2.

    The frame has its origin at `origin`, its X axis towards `on_x`, its Y axis on the side of
    `in_xy` in the plane (origin, on_x, in_xy); only the positions of the points are used.
    Returns 1 (and leaves `result` unchanged) when `on_x` is too close to `origin`, 2 when
    `in_xy` is too close to the (Ox) axis, else sets `result.trsf` and returns 0.
    `result` keeps its reference frame; when it has none, it takes the reference frame of
    `origin` (the manual does not say which). 162 when a point has no reference frame."""
    o = world_pose(origin)[1]
    x = world_pose(on_x)[1]
    y = world_pose(in_xy)[1]
    ex = R.sub(x, o)
    lx = R.length(ex)
    if lx < SETFRAME_MIN_DISTANCE:
        return 1
    ex = R.scale(ex, 1.0 / lx)
    v = R.sub(y, o)
    vy = R.sub(v, R.scale(ex, R.dot(v, ex)))
    ly = R.length(vy)
    if ly < SETFRAME_MIN_DISTANCE:
        return 2
    ey = R.scale(vy, 1.0 / ly)
    ez = R.cross(ex, ey)
    frame_world: R.Pose = (R.from_columns(ex, ey, ez), o, None)
    if result.is_root:
        result.trsf = Trsf.from_pose(frame_world)  # "modifies" world: 161 on the next computation
        return 0
    ref = result.ref if result.ref is not None else origin.ref
    check_link(result, ref)
    local = R.pose_mul(R.pose_inv(root_pose(ref)), frame_world)  # type: ignore[arg-type]
    result.trsf = Trsf.from_pose(local)
    result.ref = ref
    return 0
