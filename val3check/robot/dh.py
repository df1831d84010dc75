"""The DH parameters of 11.4 ("robot absolu"): the arm's geometry in the manual's form, its
forward kinematics, and the inverse kinematics of a geometry that is no longer ortho-parallel.

11.4.1 gives the form: the flange position pCart of the joints {j1..j6} is

    pCart.trsf = {0,0,0,0,0, j1+theta[0]}
               * {a[0], b[0], d[0], alpha[0], beta[0], j2+theta[1]}
               * ...
               * {a[4], b[4], d[4], alpha[4], beta[4], j6+theta[5]}
               * {a[5], b[5], d[5], alpha[5], beta[5], 0}
               * {0, 0, d[6], 0, 0}

each factor a VAL 3 trsf (9.3.2: translation, then Rx·Ry·Rz), lengths in mm, angles in degrees.

`nominal_dh(model)` writes a six-axis model in that form, read from its URDF chain at the zero
position as the classic Denavit-Hartenberg construction does (frame i's x along the common
normal of axes i and i+1, b = beta = 0): on a Stäubli arm every theta is 0 and the lengths are the
arm's (TX2-60: d[1] = 20, a[1] = 290, d[3] = 310, d[5] = 70). Its forward kinematics equals the
model's to 1e-9 mm (tests). `fk_many` is the product above for many joint positions (numpy),
`frames_many` the joint axes on the way (the Jacobian, the links of the collision model), and
`refine` Newton's method from the nominal closed-form solutions: what the inverse of a
calibrated geometry needs (11.4.3: "La conversion d'une position cartésienne en position de
l'articulation correspondante peut échouer près des limites de l'articulation ou dans des
positions singulières").
"""

from __future__ import annotations

import math

import numpy as np

from ..light_dataclass import dataclass
from .errors import IKUnsupported

DEG = math.pi / 180.0
FIELDS = ("theta", "d", "a", "b", "alpha", "beta")
# setDH refuses a geometry "trop différente des paramètres de la géométrie standard" (11.4.4): the
# tolerance is not published; the simulation's: lengths within this fraction of the arm's reach,
# angles within this many degrees, of the nominal parameters.
MAX_LENGTH_CHANGE = 0.05
MAX_ANGLE_CHANGE_DEG = 5.0
NEWTON_STEPS = 12
NEWTON_MM = 1e-9
NEWTON_RAD = 1e-12


@dataclass(frozen=True)
class DH:
    """The six-axis form of 11.4.1: theta, a, b, alpha, beta (6 each) and d (7: d[6] the flange
    dimension of some wrists). Degrees and millimetres."""

    theta: tuple[float, ...]
    d: tuple[float, ...]
    a: tuple[float, ...]
    b: tuple[float, ...]
    alpha: tuple[float, ...]
    beta: tuple[float, ...]

    def values(self, name: str) -> tuple[float, ...]:
        return getattr(self, name)

    def differences(self, other: DH) -> tuple[float, float]:
        """(largest length difference in mm, largest angle difference in degrees) from `other`."""
        dl = max(abs(x - y) for n in ("d", "a", "b") for x, y in zip(self.values(n), other.values(n)))
        da = max(abs(math.remainder(x - y, 360.0)) for n in ("theta", "alpha", "beta")
                 for x, y in zip(self.values(n), other.values(n)))
        return dl, da


def _trsf(x, y, z, rx, ry, rz) -> np.ndarray:
    """A VAL 3 trsf as a 4x4 (9.3.2: R = Rx(rx)·Ry(ry)·Rz(rz))."""
    a, b, c = rx * DEG, ry * DEG, rz * DEG
    ca, sa, cb, sb, cc, sc = math.cos(a), math.sin(a), math.cos(b), math.sin(b), math.cos(c), math.sin(c)
    return np.array([
        [cb * cc, -cb * sc, sb, x],
        [sa * sb * cc + ca * sc, -sa * sb * sc + ca * cc, -sa * cb, y],
        [-ca * sb * cc + sa * sc, ca * sb * sc + sa * cc, ca * cb, z],
        [0.0, 0.0, 0.0, 1.0]])


def _rz_many(angles_deg: np.ndarray) -> np.ndarray:
    """Rz of many angles (N, 4, 4)."""
    t = np.asarray(angles_deg, dtype=float) * DEG
    c, s = np.cos(t), np.sin(t)
    out = np.zeros((len(t), 4, 4))
    out[:, 0, 0], out[:, 0, 1], out[:, 1, 0], out[:, 1, 1] = c, -s, s, c
    out[:, 2, 2] = out[:, 3, 3] = 1.0
    return out


def _fixed(dh: DH) -> list[np.ndarray]:
    """The constant part of each factor: Tr(a, b, d)·Rx(alpha)·Ry(beta), i = 0..5."""
    return [_trsf(dh.a[i], dh.b[i], dh.d[i], dh.alpha[i], dh.beta[i], 0.0) for i in range(6)]


def frames_many(dh: DH, Q) -> tuple[np.ndarray, np.ndarray]:
    """The frame of each joint before its rotation, (N, 6, 4, 4) in world (joint k turns about its
    z axis through its origin), and the flange (N, 4, 4), for joint positions Q (N, 6) degrees."""
    Q = np.atleast_2d(np.asarray(Q, dtype=float))
    n = len(Q)
    fixed = _fixed(dh)
    frames = np.empty((n, 6, 4, 4))
    T = np.broadcast_to(np.eye(4), (n, 4, 4)).copy()
    for k in range(6):
        if k > 0:
            T = T @ fixed[k - 1]
        frames[:, k] = T
        T = T @ _rz_many(Q[:, k] + dh.theta[k])
    T = T @ fixed[5]
    if dh.d[6]:
        T = T @ _trsf(0.0, 0.0, dh.d[6], 0.0, 0.0, 0.0)
    return frames, T


def fk_many(dh: DH, Q) -> np.ndarray:
    """The flange in world (N, 4, 4), mm, for joint positions Q (N, 6) in degrees (11.4.1)."""
    return frames_many(dh, Q)[1]


def fk(dh: DH, q) -> np.ndarray:
    """The flange in world (4x4, mm) at one joint position (degrees)."""
    return fk_many(dh, [q])[0]


# ---- the nominal parameters of a model ----------------------------------------------------------------


def nominal_dh(model) -> DH:
    """The parameters of 11.4.1 of a six-axis `model` (robot.RobotModel), from its chain at the zero
    position. Raises IKUnsupported for a SCARA (the manual gives the form of six revolute axes) or a
    chain whose axis 1 is not the world's Z axis through its origin."""
    if model.family != "six-axis" or len(model.joint_limits) != 6:
        raise IKUnsupported(f"{model.name}: the DH form of 11.4.1 is that of six revolute axes; the manual gives "
                            "none for this arm")
    axes = []
    for ((p, d), s) in zip(model.chain.zero_frames(), model.joint_signs):
        axes.append((np.array(p, dtype=float), s * np.array(d, dtype=float)))
    p1, z1 = axes[0]
    if np.linalg.norm(z1 - (0.0, 0.0, 1.0)) > 1e-9 or math.hypot(p1[0], p1[1]) > 1e-6:
        raise IKUnsupported(f"{model.name}: axis 1 is not the world's Z axis through its origin: the DH form of "
                            "11.4.1 does not apply")
    flange = np.eye(4)
    flange[:3, :4] = np.array(model.fk_matrix((0.0,) * 6), dtype=float)
    theta, d, a, alpha = [0.0] * 6, [0.0] * 7, [0.0] * 6, [0.0] * 6
    b, beta = [0.0] * 6, [0.0] * 6
    origin, x_prev = np.zeros(3), np.array([1.0, 0.0, 0.0])
    for i in range(5):
        (_, z), (p_next, z_next) = axes[i], axes[i + 1]
        foot, foot_next, x = _common_normal(origin, z, p_next, z_next, x_prev)
        if np.dot(x, x_prev) < -1e-12:  # the other sense of the normal: |theta| <= 90°
            x = -x
        theta[i] = _angle(x_prev, x, z)
        d[i] = float(np.dot(foot - origin, z))
        a[i] = float(np.dot(foot_next - foot, x))
        alpha[i] = _angle(z, z_next, x)
        origin, x_prev = foot_next, x
    # the flange from joint 6's frame: theta[5] puts x where the rest is Rx·Ry only
    z6 = axes[5][1]
    R6 = np.column_stack([x_prev, np.cross(z6, x_prev), z6])
    R = R6.T @ flange[:3, :3]
    t5 = math.atan2(-R[0, 1], R[1, 1])
    if math.cos(t5) * R[0, 0] + math.sin(t5) * R[1, 0] < 0:
        t5 += math.pi
    theta[5] = math.degrees(t5)
    Rz = np.array([[math.cos(t5), -math.sin(t5), 0.0], [math.sin(t5), math.cos(t5), 0.0], [0.0, 0.0, 1.0]])
    M = Rz.T @ R  # = Rx(alpha)·Ry(beta)
    alpha[5] = math.degrees(math.atan2(-M[1, 2], M[2, 2]))
    beta[5] = math.degrees(math.atan2(M[0, 2], math.hypot(M[1, 2], M[2, 2])))
    rel = (R6 @ Rz).T @ (flange[:3, 3] - origin)
    a[5], b[5], d[5] = (float(v) for v in rel)
    clean = [tuple(_clean(v) for v in arr) for arr in (theta, d, a, b, alpha, beta)]
    return DH(*clean)


def _common_normal(o, z, p, w, x_prev):
    """The feet of the common normal of the line (o, z) and the line (p, w), and its direction x
    (unit, perpendicular to z): through o when the lines are parallel (d = 0)."""
    n = np.cross(z, w)
    if np.linalg.norm(n) < 1e-9:  # parallel: the normal through o
        v = (p - o) - np.dot(p - o, z) * z
        if np.linalg.norm(v) < 1e-9:  # the same line: keep x
            return o, o.copy(), x_prev
        return o, o + v, v / np.linalg.norm(v)
    n = n / np.linalg.norm(n)
    # o + s z and p + t w with (o + s z) - (p + t w) parallel to n
    A = np.array([[np.dot(z, z), -np.dot(z, w)], [np.dot(z, w), -np.dot(w, w)]])
    r = p - o
    s, t = np.linalg.solve(A, [np.dot(r, z), np.dot(r, w)])
    foot, foot_next = o + s * z, p + t * w
    return foot, foot_next, n


def _angle(u, v, axis) -> float:
    """The angle (degrees) turning u to v about `axis`."""
    return math.degrees(math.atan2(float(np.dot(np.cross(u, v), axis)), float(np.dot(u, v))))


def _clean(x: float) -> float:
    r = round(x, 9)
    return (r if abs(r - x) < 1e-9 else x) + 0.0


def too_different(model, nominal: DH, new: DH) -> str | None:
    """Why setDH would refuse `new` ("trop différente des paramètres de la géométrie standard",
    11.4.4), or None."""
    dl, da = new.differences(nominal)
    limit = MAX_LENGTH_CHANGE * model.reach_mm
    if dl > limit:
        return f"a length differs by {dl:.3f} mm from the standard geometry (the simulation accepts {limit:.1f} mm)"
    if da > MAX_ANGLE_CHANGE_DEG:
        return (f"an angle differs by {da:.3f}° from the standard geometry (the simulation accepts "
                f"{MAX_ANGLE_CHANGE_DEG:g}°)")
    return None


# ---- inverse kinematics of a calibrated geometry ---------------------------------------------------------


def refine(dh: DH, T, Q0) -> np.ndarray:
    """Joint positions (N, 6) degrees reaching the flange poses T (N, 4, 4) for the geometry `dh`,
    by Newton's method from Q0 (the nominal closed-form solutions, same branch); NaN rows where it
    does not converge (a singular position)."""
    T = np.asarray(T, dtype=float).reshape(-1, 4, 4)
    Q = np.array(Q0, dtype=float).reshape(-1, 6)
    ok = np.all(np.isfinite(Q), axis=1)
    Q[~ok] = 0.0
    for _ in range(NEWTON_STEPS):
        frames, F = frames_many(dh, Q)
        e = _error(F, T)
        done = (np.linalg.norm(e[:, :3], axis=1) < NEWTON_MM) & (np.linalg.norm(e[:, 3:], axis=1) < NEWTON_RAD)
        if np.all(done | ~ok):
            break
        J = _jacobian(frames, F)
        step = np.zeros_like(Q)
        act = ok & ~done
        if np.any(act):
            Ja = J[act]
            lam = 1e-12
            JT = np.swapaxes(Ja, 1, 2)
            step[act] = np.linalg.solve(JT @ Ja + lam * np.eye(6), (JT @ e[act][..., None]))[..., 0]
        Q = Q + step / DEG
    frames, F = frames_many(dh, Q)
    e = _error(F, T)
    good = ok & (np.linalg.norm(e[:, :3], axis=1) < 1e-6) & (np.linalg.norm(e[:, 3:], axis=1) < 1e-9)
    Q[~good] = np.nan
    return Q


def _error(F: np.ndarray, T: np.ndarray) -> np.ndarray:
    """(N, 6): the translation (mm) and the rotation vector (rad, world) taking F to T."""
    dp = T[:, :3, 3] - F[:, :3, 3]
    R = T[:, :3, :3] @ np.swapaxes(F[:, :3, :3], 1, 2)
    v = np.stack([R[:, 2, 1] - R[:, 1, 2], R[:, 0, 2] - R[:, 2, 0], R[:, 1, 0] - R[:, 0, 1]], axis=1) / 2.0
    s = np.linalg.norm(v, axis=1)
    c = (np.trace(R, axis1=1, axis2=2) - 1.0) / 2.0
    ang = np.arctan2(s, c)
    with np.errstate(invalid="ignore", divide="ignore"):
        k = np.where(s > 1e-15, ang / s, 1.0)
    return np.concatenate([dp, v * k[:, None]], axis=1)


def _jacobian(frames: np.ndarray, F: np.ndarray) -> np.ndarray:
    """The geometric Jacobian (N, 6, 6) of the flange (mm/rad, rad/rad) in world."""
    z = frames[:, :, :3, 2]
    o = frames[:, :, :3, 3]
    p = F[:, None, :3, 3]
    lin = np.cross(z, p - o)
    return np.concatenate([np.swapaxes(lin, 1, 2), np.swapaxes(z, 1, 2)], axis=1)
