"""Shared helpers of the geometry tests: tolerant comparisons and a fake arm model."""

from __future__ import annotations

import math

from val3check.geometry import rotation as R
from val3check.geometry.trsf import Trsf


def mat_close(a, b, tol=1e-9):
    return all(abs(x - y) <= tol for x, y in zip(a, b))


def same_rotation(a: Trsf, b: Trsf, tol=1e-9) -> bool:
    return mat_close(a.rotation(), b.rotation(), tol)


def trsf_close(a: Trsf, b: Trsf, tol=1e-9) -> bool:
    return math.dist((a.x, a.y, a.z), (b.x, b.y, b.z)) <= tol and same_rotation(a, b, tol)


def canonical_ok(rx: float, ry: float, rz: float) -> bool:
    """The constraints of 9.3.2 on angles the system computes."""
    if not all(-180.0 <= a <= 180.0 for a in (rx, ry, rz)):
        return False
    if abs(abs(ry) - 90.0) < 1e-9:
        return rx == 0.0
    within = sum(1 for a in (rx, ry, rz) if -90.0 <= a <= 90.0)
    return within >= 2 or (rx == 180.0 and abs(ry) < 1e-9)


class FakeArm:
    """A fake arm model whose joints ARE the flange pose: fk(j) = (j1, j2, j3, j4, j5, j6).

    config_of: shoulder lefty if j1 >= 0, elbow epositive if j3 >= 0, wrist wpositive if
    |j5| <= 90 (so the twin triple has the other wrist). ik returns the pose, the twin angle
    triple of the same rotation, and j6 one turn either side (a multi-turn axis): it leaves
    the filtering and the choice to the geometry. Software limits: |j| <= 1000 for j1..j3,
    |j6| <= 400."""

    def __init__(self):
        self.calls = []

    def fk(self, joints):
        return tuple(float(v) for v in joints)

    def config_of(self, joints):
        return ("lefty" if joints[0] >= 0 else "righty", "epositive" if joints[2] >= 0 else "enegative",
                "wpositive" if -90 <= joints[4] <= 90 else "wnegative")

    def in_range(self, joints):
        return all(abs(v) <= 1000 for v in joints[:3]) and abs(joints[5]) <= 400

    def ik(self, pose, config, near):
        self.calls.append((tuple(pose), tuple(config), tuple(near)))
        x, y, z, a, b, c = pose
        a2 = a - 180 if a > 0 else a + 180
        c2 = c - 180 if c > 0 else c + 180
        b2 = 180 - b if b >= 0 else -180 - b
        out = []
        for (aa, bb, cc) in ((a, b, c), (a2, b2, c2)):
            for turn in (-360.0, 0.0, 360.0):
                out.append((x, y, z, aa, bb, cc + turn))
        return out


def rodrigues(axis, deg):
    return R.axis_angle(R.unit(axis), deg)
