"""The geometry of chapter 9 by VAL 3 name: one function per instruction or operator, with the
overloads of the manual dispatched on the Python types (`Trsf`, `Point`, `Frame`, `Tool`), for
scripts and tests (see the package docstring for the value shapes; the interpreter's own
boundary is interpretation/chapters/ch09_geometry.py).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from . import arm, frames, jointops, points
from . import trsf as trsf_ops
from .frames import Frame, Tool
from .points import Point
from .trsf import Trsf


def position(obj: Point | Frame | Tool, reference: Frame | Tool) -> Trsf:
    """position(point, frame) 9.6.3, position(frame, frame) 9.4.4, position(tool, tool) 9.5.4."""
    if type(obj) is Point:
        if type(reference) is not Frame:
            raise TypeError("position(point, frame)")
        return points.position(obj, reference)
    return frames.position(obj, reference)  # type: ignore[arg-type]


def link(obj: Point | Frame | Tool, reference: Frame | Tool) -> None:
    """link(point, frame) 9.6.3, link(frame, frame) 9.4.4, link(tool, tool) 9.5.4."""
    if type(obj) is Point:
        points.link(obj, reference)  # type: ignore[arg-type]
    else:
        frames.link(obj, reference)  # type: ignore[arg-type]


def assign(dst: Any, src: Any) -> None:
    """`=` for point, frame and tool (copy into the existing node/value `dst`)."""
    if type(dst) is Point:
        points.assign(dst, src)
    else:
        frames.assign(dst, src)


def distance(a: Trsf | Point, b: Trsf | Point) -> float:
    """distance(trsf, trsf) 9.3.4, distance(point, point) 9.6.3."""
    if type(a) is Point:
        return points.distance(a, b)  # type: ignore[arg-type]
    return trsf_ops.distance(a, b)  # type: ignore[arg-type]


def compose(p: Point, reference: Frame, tr: Trsf) -> Point:
    return points.compose(p, reference, tr)


def appro(p: Point, tr: Trsf) -> Point:
    return points.appro(p, tr)


def setFrame(origin: Point, on_x: Point, in_xy: Point, result: Frame) -> int:
    return points.set_frame(origin, on_x, in_xy, result)


def interpolateL(start: Trsf, end: Trsf, s: float) -> Trsf:
    return trsf_ops.interpolate_l(start, end, s)


def interpolateC(start: Trsf, mid: Trsf, end: Trsf, s: float) -> Trsf:
    return trsf_ops.interpolate_c(start, mid, end, s)


def align(tr: Trsf, reference: Trsf) -> Trsf:
    return trsf_ops.align(tr, reference)


def trsf_mul(a: Trsf, b: Trsf) -> Trsf:
    """trsf `*` (9.3.3)."""
    return a * b


def trsf_inv(a: Trsf) -> Trsf:
    """trsf `!` (9.3.3)."""
    return a.inverse()


def equal(a: Any, b: Any) -> bool:
    """`==` for trsf (fields, exact), frame/tool/point (same reference, same trsf; tools also
    gripper and times), config (fields); joint values use `jointops.eq` (tolerance)."""
    if isinstance(a, (tuple, list)) and isinstance(b, (tuple, list)) and a and isinstance(a[0], str):
        return tuple(a) == tuple(b)
    if isinstance(a, (tuple, list)):
        return jointops.eq(a, b)
    return bool(a == b)


def abs_joint(j: Sequence[float]) -> tuple[float, ...]:
    return jointops.abs_(j)


isInRange = jointops.is_in_range
herej = jointops.herej
here = arm.here
jointToPoint = arm.joint_to_point
pointToJoint = arm.point_to_joint
config = arm.config_of
