"""Tool centre point curves of movel, movec and Cartesian blends (10.1.1, 10.1.2.3, 10.1.4.1).

A curve gives the TCP pose in world (4x4, mm) for parameter values λ ∈ [0, 1] (arrays). The
position and orientation laws are those of `interpolateL` and `interpolateC` (9.3.4: "the same
algorithm as the motion generator"), written here on numpy arrays:

* `Line`: the position moves on the straight line at the fraction λ, the orientation turns by
  the fraction λ of the smallest rotation from start to end (10.1.4.1).
* `Arc`: the circle through start, intermediate and end positions, at the fraction λ of the arc
  angle; the orientation turns by the smallest rotation start → intermediate over the first part
  of the arc, intermediate → end over the rest. An intermediate position 180° or more from the
  start or the end (on the arc or in orientation) is ambiguous: `ArcError`.
* `Blend`: the position follows a curve from the leave point to the reach point with the
  velocities of the two paths there (paths.BlendShape: for two straight lines, in their plane);
  the orientation is the superposition of the two neighbouring rotations, each continued at its
  own rate, weighted by a smooth step: the velocity (translation and rotation) is continuous at
  both ends.
"""

from __future__ import annotations

import math

import numpy as np

from ..geometry import trsf as _gt

ARC_AMBIGUITY_DEG = 180.0 - _gt.AMBIGUITY_EPS


class ArcError(ValueError):
    """movec: the circle is not defined (positions too close or aligned), or the intermediate
    position is 180° or more from the start or the end (10.1.4.1)."""

    def __init__(self, message: str, what: str, data: dict | None = None):
        """`what`: undefined or ambiguous; `data`: the numbers behind the message."""
        super().__init__(message)
        self.what = what  # "undefined" | "ambiguous"
        self.data = data or {}


# ---- rotations on arrays --------------------------------------------------------------------------


def rotvec(R: np.ndarray) -> np.ndarray:
    """Rotation vector (axis × angle, rad) of rotation matrices (..., 3, 3), the shorter way."""
    R = np.asarray(R, dtype=float)
    v = np.stack([R[..., 2, 1] - R[..., 1, 2], R[..., 0, 2] - R[..., 2, 0], R[..., 1, 0] - R[..., 0, 1]], axis=-1)
    s = np.linalg.norm(v, axis=-1) / 2.0  # sin(angle)·... = |v|/2 = sin θ
    ang = np.arctan2(s, (R[..., 0, 0] + R[..., 1, 1] + R[..., 2, 2] - 1.0) / 2.0)
    with np.errstate(invalid="ignore", divide="ignore"):
        k = np.where(s[..., None] > 1e-12, v / (2.0 * s[..., None]), 0.0)
    out = k * ang[..., None]
    # near 180 degrees sin θ vanishes: the axis from the symmetric part (either sense is as short)
    near = ang > math.pi - 1e-6
    if np.any(near):
        Rn = R[near]
        axes = []
        for m in Rn:
            B = (m + np.eye(3)) / 2.0
            j = int(np.argmax(np.diag(B)))
            a = B[:, j] / math.sqrt(max(B[j, j], 1e-300))
            axes.append(a / np.linalg.norm(a) * math.pi)
        out[near] = np.array(axes)
    return out


def expmap(r: np.ndarray) -> np.ndarray:
    """Rotation matrices (..., 3, 3) of rotation vectors (..., 3) (Rodrigues)."""
    r = np.asarray(r, dtype=float)
    th = np.linalg.norm(r, axis=-1)
    with np.errstate(invalid="ignore", divide="ignore"):
        k = np.where(th[..., None] > 1e-15, r / th[..., None], 0.0)
    K = np.zeros(r.shape[:-1] + (3, 3))
    K[..., 0, 1] = -k[..., 2]
    K[..., 0, 2] = k[..., 1]
    K[..., 1, 0] = k[..., 2]
    K[..., 1, 2] = -k[..., 0]
    K[..., 2, 0] = -k[..., 1]
    K[..., 2, 1] = k[..., 0]
    s = np.sin(th)[..., None, None]
    c = (1.0 - np.cos(th))[..., None, None]
    return np.eye(3) + s * K + c * (K @ K)


def smallest_rotation(R0: np.ndarray, R1: np.ndarray) -> tuple[float, np.ndarray]:
    """(angle in degrees, unit axis in R0's axes) of the smallest rotation R0 → R1, as
    geometry.rotation.rotation_between computes it (interpolateL's)."""
    from ..geometry import rotation as GR

    m0 = tuple(float(v) for v in R0.reshape(9))
    m1 = tuple(float(v) for v in R1.reshape(9))
    ang, axis = GR.rotation_between(m0, m1)
    return ang, np.array(axis)


def _poses(P: np.ndarray, R: np.ndarray) -> np.ndarray:
    """4x4 poses (N, 4, 4) from positions (N, 3) and rotations (N, 3, 3)."""
    n = len(P)
    T = np.zeros((n, 4, 4))
    T[:, :3, :3] = R
    T[:, :3, 3] = P
    T[:, 3, 3] = 1.0
    return T


def _ending_at(T: np.ndarray, lam: np.ndarray, p1: np.ndarray, R1: np.ndarray) -> np.ndarray:
    """T with the pose at λ = 1 the target's own bits: interpolated from the start, it differs in
    the last bits with the start's, and the joints at the end would follow them, so that a
    repeated cycle never repeated exactly on some CPUs (docs/performance.md)."""
    end = lam == 1.0
    if end.any():
        T[end, :3, 3] = p1
        T[end, :3, :3] = R1
    return T


class Curve:
    """A TCP curve over λ ∈ [0, 1]: poses(λ) → (N, 4, 4)."""

    length_mm: float = 0.0  # TCP path length
    angle_deg: float = 0.0  # total rotation of the tool
    turn_deg: float = 0.0  # how far the direction of travel turns along the curve

    def poses(self, lam: np.ndarray) -> np.ndarray:  # pragma: no cover - interface
        """TCP poses (N, 4, 4) at λ (array)."""
        raise NotImplementedError

    def positions(self, lam: np.ndarray) -> np.ndarray:
        """TCP positions (N, 3) at λ."""
        return self.poses(lam)[:, :3, 3]

    def rates(self, lam: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """|dp/dλ| (mm) and |dθ/dλ| (deg) of the TCP (central differences; exact in subclasses)."""
        lam = np.atleast_1d(np.asarray(lam, dtype=float))
        h = 1e-6
        n = len(lam)
        T = self.poses(np.concatenate([lam + h, lam - h]))
        p = np.linalg.norm(T[:n, :3, 3] - T[n:, :3, 3], axis=1) / (2 * h)
        Rrel = np.swapaxes(T[n:, :3, :3], 1, 2) @ T[:n, :3, :3]
        c = np.clip((np.trace(Rrel, axis1=1, axis2=2) - 1.0) / 2.0, -1.0, 1.0)
        return p, np.degrees(np.arccos(c)) / (2 * h)


class Line(Curve):
    """movel: straight line, smallest rotation (interpolateL)."""

    def __init__(self, T0: np.ndarray, T1: np.ndarray):
        """The line from pose T0 to pose T1 (4x4, mm)."""
        self.p0 = T0[:3, 3].copy()
        self.p1 = T1[:3, 3].copy()
        self.R0 = T0[:3, :3].copy()
        self.R1 = T1[:3, :3].copy()
        self.ang, self.axis = smallest_rotation(T0[:3, :3], T1[:3, :3])
        self.length_mm = float(np.linalg.norm(self.p1 - self.p0))
        self.angle_deg = float(self.ang)

    def rates(self, lam):
        """|dp/dλ| (the length) and |dθ/dλ| (the rotation angle), constant along a line."""
        n = np.size(lam)
        return np.full(n, self.length_mm), np.full(n, float(self.ang))

    def poses(self, lam):
        """The poses of interpolateL at the fractions λ."""
        lam = np.atleast_1d(np.asarray(lam, dtype=float))
        P = self.p0 + lam[:, None] * (self.p1 - self.p0)
        R = self.R0 @ expmap(np.outer(lam * math.radians(self.ang), self.axis))
        return _ending_at(_poses(P, R), lam, self.p1, self.R1)


class Arc(Curve):
    """movec: the arc start → intermediate → end (interpolateC)."""

    def __init__(self, T0: np.ndarray, Tm: np.ndarray, T1: np.ndarray):
        """The arc through the positions of T0, Tm and T1; ArcError when they define none or Tm is ambiguous."""
        p1, p2, p3 = (tuple(float(v) for v in T[:3, 3]) for T in (T0, Tm, T1))
        try:
            centre, radius, e1, e2, a2, a3 = _gt.arc(p1, p2, p3)
        except Exception as exc:  # geometry raises its error 70: positions too close or aligned
            detail = getattr(exc, "detail", "") or str(exc)
            raise ArcError(f"movec: {detail.replace('interpolateC: ', '')}", "undefined") from None
        d2, d3 = math.degrees(a2), math.degrees(a3 - a2)
        if d2 >= ARC_AMBIGUITY_DEG or d3 >= ARC_AMBIGUITY_DEG:
            raise ArcError(
                f"movec: the intermediate point is {max(d2, d3):.1f}° along the arc from the "
                f"{'start' if d2 >= d3 else 'target'}: 180° or more is ambiguous (10.1.4.1); add a movec or move the "
                "intermediate point", "ambiguous", {"arc_deg": round(max(d2, d3), 3)})
        ang12, ax12 = smallest_rotation(T0[:3, :3], Tm[:3, :3])
        ang23, ax23 = smallest_rotation(Tm[:3, :3], T1[:3, :3])
        if ang12 >= ARC_AMBIGUITY_DEG or ang23 >= ARC_AMBIGUITY_DEG:
            raise ArcError(
                f"movec: the intermediate orientation is turned by {max(ang12, ang23):.1f}° from the "
                f"{'start' if ang12 >= ang23 else 'target'} orientation: 180° or more is ambiguous (10.1.4.1)",
                "ambiguous", {"rotation_deg": round(max(ang12, ang23), 3)})
        self.centre = np.array(centre)
        self.radius = float(radius)
        self.e1, self.e2 = np.array(e1), np.array(e2)
        self.a3 = float(a3)
        self.u2 = float(a2 / a3)
        self.R0, self.Rm, self.R1 = T0[:3, :3].copy(), Tm[:3, :3].copy(), T1[:3, :3].copy()
        self.p3 = T1[:3, 3].copy()
        self.r12 = math.radians(ang12) * ax12
        self.r23 = math.radians(ang23) * ax23
        self.length_mm = self.radius * self.a3
        self.angle_deg = float(ang12 + ang23)
        self.turn_deg = math.degrees(self.a3)
        # the orientation law changes at the intermediate point: a gridpoint there
        self.knots = (self.u2,)

    def rates(self, lam):
        """|dp/dλ| (the arc length) and |dθ/dλ| of each part of the orientation law."""
        lam = np.atleast_1d(np.asarray(lam, dtype=float))
        r12 = math.degrees(float(np.linalg.norm(self.r12))) / self.u2
        r23 = math.degrees(float(np.linalg.norm(self.r23))) / (1.0 - self.u2)
        return np.full(len(lam), self.radius * self.a3), np.where(lam <= self.u2, r12, r23)

    def poses(self, lam):
        """The poses of interpolateC at the fractions λ of the arc angle."""
        lam = np.atleast_1d(np.asarray(lam, dtype=float))
        t = lam * self.a3
        P = self.centre + self.radius * (np.cos(t)[:, None] * self.e1 + np.sin(t)[:, None] * self.e2)
        first = lam <= self.u2
        f1 = np.where(first, lam / self.u2, 0.0)
        f2 = np.where(first, 0.0, (lam - self.u2) / (1.0 - self.u2))
        R = np.where(first[:, None, None], self.R0 @ expmap(np.outer(f1, self.r12)),
                     self.Rm @ expmap(np.outer(f2, self.r23)))
        return _ending_at(_poses(P, R), lam, self.p3, self.R1)


def smootherstep(u: np.ndarray) -> np.ndarray:
    """6u⁵ - 15u⁴ + 10u³: 0 → 1 with zero first and second derivatives at both ends."""
    return u * u * u * (u * (6.0 * u - 15.0) + 10.0)


class Blend(Curve):
    """A Cartesian blend from the leave state to the reach state (module docstring).

    left/right: (position (3,), rotation (3, 3), dp/dσ (3,), angular velocity dω/dσ in world
    (3,), rad) of the TCP at the leave and reach points, in the composite path parameter σ;
    ell_l, ell_r: the path lengths from the leave point to the via point and from there to the
    reach point. The position is a `paths.BlendShape` in Cartesian space (in the plane of two
    straight lines); the orientation is the superposition of the two rotations continued at their
    own rates, weighted by a smooth step. λ = σ / L, L the blend's length."""

    def __init__(self, left, right, ell_l: float, ell_r: float, shape="bezier"):
        """The blend from `left` to `right`: each (position, rotation, velocity, angular velocity) per path unit."""
        from .paths import BlendShape

        self.pL, self.RL, self.vL, self.wL = (np.asarray(a, dtype=float) for a in left)
        self.pR, self.RR, self.vR, self.wR = (np.asarray(a, dtype=float) for a in right)
        self.shape = BlendShape(self.pL, self.vL, self.pR, self.vR, ell_l, ell_r, shape)
        self.ell = self.shape.ell
        lam = np.linspace(0.0, 1.0, 33)
        P = self.positions(lam)
        self.length_mm = float(np.linalg.norm(np.diff(P, axis=0), axis=1).sum())
        self.angle_deg = math.degrees(float(np.linalg.norm(rotvec(self.RL.T @ self.RR))))
        nl, nr = np.linalg.norm(self.vL), np.linalg.norm(self.vR)
        cos = float(self.vL @ self.vR) / (nl * nr) if nl > 0 and nr > 0 else 1.0
        self.turn_deg = math.degrees(math.acos(min(max(cos, -1.0), 1.0)))

    def poses(self, lam):
        """Position on the blend shape, orientation the smooth-step superposition of the two rotations."""
        lam = np.atleast_1d(np.asarray(lam, dtype=float))
        sig = lam * self.ell
        P = self.shape.point(sig)
        w = smootherstep(lam)[:, None]
        Ra = expmap(np.outer(sig, self.wL)) @ self.RL
        Rb = expmap(np.outer(sig - self.ell, self.wR)) @ self.RR
        rel = rotvec(np.swapaxes(Ra, -1, -2) @ Rb)
        R = Ra @ expmap(rel * w)
        return _poses(P, R)
