"""Closed-form kinematics of a SCARA arm (Stäubli RS/TS, manual 9.7.5): four axes, all vertical.

Millimetres and radians inside; joint 3 is prismatic and its value is a length. The geometry is
read from the URDF's zero position (`extract_scara`) and kept only if it reproduces the URDF chain
on random positions, never assumed:

  axis i         parallel to world Z; joint i turns (or, axis 3, slides) by s_i·q_i along +Z
  A1, A2, A4     where axes 1, 2 and 4 cross the XY plane at the zero position (A1 is the world
                 origin for Stäubli's arms); l1 = |A2 - A1|, l2 = |A4 - A2|
  flange         at the zero position: rotation F, height z0, horizontal offset o from axis 4

  with θ1 = s1·q1, β = s2·q2 (the elbow angle), φ = θ1 + β + s4·q4:
  flange(q) = Rz(φ)·F at A1 + Rz(θ1)·(A2 - A1) + Rz(θ1 + β)·(A4 - A2) + Rz(φ)·o, height z0 + s3·q3

Inverse: a SCARA only reaches orientations Rz(φ)·F (the flange turns about the vertical); φ
comes from R·Fᵀ, the height gives q3, and the horizontal position of axis 4 is the classic
two-link problem: cos β' = (r² - l1² - l2²) / (2·l1·l2), two elbow branches β' = ±acos(…) — the
righty and lefty configurations of 9.7.5 (sin(j2) > 0 is righty). The arm stretched or folded
(β' = 0 or 180°) is the singular position where both branches meet; they come back once.
"""

from __future__ import annotations

import math
import random

from ..light_dataclass import dataclass
from .urdf import Mat

_ORIENT_TOL = 1e-7  # rad: a target tilted more than this off the vertical is out of a SCARA's reach
_STRETCH_EPS = 1e-13  # |cos β'| this close to 1 is the stretched (folded) arm


@dataclass(frozen=True)
class Scara:
    """Parameters of a SCARA (module docstring), millimetres."""

    l1: float
    l2: float
    alpha1: float  # direction of A2 - A1 at zero (rad): 0 for Stäubli's arms (stretched along X)
    alpha2: float  # direction of A4 - A2 at zero
    a1: tuple[float, float]  # axis 1 in the world XY plane
    z0: float  # flange height at q3 = 0
    offset: tuple[float, float]  # flange centre from axis 4, horizontal, at the zero position
    F: tuple  # flange rotation at the zero position (3x3 rows)
    signs: tuple[int, int, int, int] = (1, 1, 1, 1)

    def fk(self, q) -> Mat:
        """Flange in the world frame (mm) for q = (rad, rad, mm, rad)."""
        s = self.signs
        t1 = s[0] * q[0]
        beta = s[1] * q[1]
        phi = t1 + beta + s[3] * q[3]
        u = t1 + self.alpha1
        v = t1 + beta + self.alpha2
        cphi, sphi = math.cos(phi), math.sin(phi)
        ox, oy = self.offset
        x = self.a1[0] + self.l1 * math.cos(u) + self.l2 * math.cos(v) + cphi * ox - sphi * oy
        y = self.a1[1] + self.l1 * math.sin(u) + self.l2 * math.sin(v) + sphi * ox + cphi * oy
        z = self.z0 + s[2] * q[2]
        F = self.F
        return (
            (cphi * F[0][0] - sphi * F[1][0], cphi * F[0][1] - sphi * F[1][1], cphi * F[0][2] - sphi * F[1][2], x),
            (sphi * F[0][0] + cphi * F[1][0], sphi * F[0][1] + cphi * F[1][1], sphi * F[0][2] + cphi * F[1][2], y),
            (F[2][0], F[2][1], F[2][2], z),
        )

    def elbow_angle(self, q2_rad: float) -> float:
        """β' (rad): the angle between arm 1 and arm 2, 0 when the arm is stretched."""
        return self.signs[1] * q2_rad + self.alpha2 - self.alpha1


def orientation_angle(sc: Scara, T: Mat) -> tuple[float, float]:
    """(φ, tilt): the turn about Z that takes the zero-position flange to T's orientation, and how
    far (rad) T's orientation is from any such turn (0 for a pose a SCARA can reach)."""
    F = sc.F
    # M = R·Fᵀ must be Rz(φ)
    m = [[sum(T[i][k] * F[j][k] for k in range(3)) for j in range(3)] for i in range(3)]
    tilt = math.atan2(math.hypot(m[0][2], m[1][2]), m[2][2])
    tilt = max(tilt, math.atan2(math.hypot(m[2][0], m[2][1]), m[2][2]))
    return math.atan2(m[1][0] - m[0][1], m[0][0] + m[1][1]), abs(tilt)


def scara_ik(sc: Scara, T: Mat, hint=None) -> tuple[list[tuple[float, float, float, float]], str]:
    """All (up to 2) joint solutions (rad, rad, mm, rad; principal angles) for the flange pose T,
    and "" or why there is none ("orientation", "reach"). Joint limits are not applied here."""
    phi, tilt = orientation_angle(sc, T)
    if tilt > _ORIENT_TOL:
        return [], "orientation"
    s = sc.signs
    cphi, sphi = math.cos(phi), math.sin(phi)
    ox, oy = sc.offset
    px = T[0][3] - (cphi * ox - sphi * oy) - sc.a1[0]
    py = T[1][3] - (sphi * ox + cphi * oy) - sc.a1[1]
    q3 = s[2] * (T[2][3] - sc.z0)
    l1, l2 = sc.l1, sc.l2
    r2 = px * px + py * py
    c = (r2 - l1 * l1 - l2 * l2) / (2.0 * l1 * l2)
    if abs(c) > 1.0 - _STRETCH_EPS:
        if abs(c) > 1.0 + 1e-12:
            return [], "reach"
        # stretched (or folded) within rounding: acos would turn the last bits of c into two
        # branches ~1e-6 degrees apart; the arm is exactly stretched (the flange moves < 1e-7 mm)
        c = 1.0 if c > 0 else -1.0
    b = math.acos(c)
    out = []
    for beta in ((b, -b) if 0.0 < b < math.pi else (b,)):
        if r2 < 1e-18:  # flange axis on axis 1 (l1 = l2, folded): q1 is free, keep the hint's
            u = (s[0] * hint[0] if hint is not None else 0.0) + sc.alpha1
        else:
            u = math.atan2(py, px) - math.atan2(l2 * math.sin(beta), l1 + l2 * math.cos(beta))
        t1 = u - sc.alpha1
        b2 = beta - sc.alpha2 + sc.alpha1  # s2·q2
        q4 = s[3] * (phi - t1 - b2)
        out.append((s[0] * t1, s[1] * b2, q3, q4))
    return out, ""


def extract_scara(chain, tol_mm: float = 1e-6) -> tuple[Scara | None, str]:
    """The SCARA parameters of a chain read from its zero position, verified on random positions.

    Returns (Scara, "") or (None, why the closed form does not apply)."""
    if chain.kind != "scara":
        return None, "not a SCARA"
    frames = chain.zero_frames()
    signs = []
    for i, (_, d) in enumerate(frames):
        if abs(abs(d[2]) - 1.0) > 1e-9:
            return None, f"axis {i + 1} is not vertical (along world Z) at the zero position"
        signs.append(1 if d[2] > 0 else -1)
    (p1, _), (p2, _), _, (p4, _) = frames
    F0 = chain.fk((0.0, 0.0, 0.0, 0.0))
    d12 = (p2[0] - p1[0], p2[1] - p1[1])
    d24 = (p4[0] - p2[0], p4[1] - p2[1])
    l1, l2 = math.hypot(*d12), math.hypot(*d24)
    if l1 < tol_mm or l2 < tol_mm:
        return None, "axes 1, 2 and 4 are not apart (no two-link arm)"
    F = tuple(tuple(F0[i][k] for k in range(3)) for i in range(3))
    sc = Scara(
        l1=l1, l2=l2, alpha1=math.atan2(d12[1], d12[0]), alpha2=math.atan2(d24[1], d24[0]),
        a1=(p1[0], p1[1]), z0=F0[2][3], offset=(F0[0][3] - p4[0], F0[1][3] - p4[1]), F=F,
        signs=tuple(signs),  # type: ignore[arg-type]
    )
    rng = random.Random(12345)
    lims = [(j.lower, j.upper) for j in chain.joints]
    from .kinematics import pose_error

    for _ in range(32):
        q = [rng.uniform(-math.pi, math.pi), rng.uniform(-math.pi, math.pi), rng.uniform(*lims[2]), rng.uniform(-math.pi, math.pi)]
        dp, da = pose_error(sc.fk(q), chain.fk(q))
        if dp > 1e-7 or da > 1e-10:
            return None, f"the closed-form model does not reproduce the URDF chain ({dp:.3g} mm off)"
    return sc, ""


def classify(j2_deg: float) -> str:
    """9.7.5: righty when sin(j2) > 0, lefty when sin(j2) <= 0. Decided on j2 modulo 360 degrees
    so that j2 = ±180 (sin = 0 exactly, but 1.2e-16 in floating point) is lefty as the manual says."""
    r = j2_deg % 360.0
    return "righty" if 0.0 < r < 180.0 else "lefty"
