"""An independent reference for the time-optimal motion of chapter 10.3, to measure the timing of
val3check/motion against (issue 23). Nothing here comes from val3check/motion: the arm is seen
through the robot model's own inverse and forward kinematics (val3check.robot), the curves are
written here in closed form, and the profile is found by a dense integration on the path
parameter.

10.3.1: "A chaque instant, le robot se déplace et accélère au maximum de ses capacités, tout en
respectant les contraintes de vitesse et d'accélération données dans la commande de mouvement":
joint speeds (nominal × vel), joint accelerations (nominal × accel while an axis speeds up) and
decelerations (nominal × decel while it slows down), the TCP speed `tvel` and the tool rotation
speed `rvel` (10.5.1), every figure times the monitor speed (docs/motion.md).

- Closed forms: `bang_bang` (distinct accel and decel, shared/notes/anchors.md) and `movej_time`,
  the synchronised straight joint line (the path parameter takes the tightest ratio of every axis).
- `optimal`: the fastest profile ṡ(s) on a path sampled at N points, given dq/ds and d²q/ds² there
  (and the TCP speed and rotation rate per unit of s). Per axis, sign(q̇)·q̈ = g·s̈ + h·ṡ² must lie
  in [-decel, accel] (g = |dq/ds|, h = sign(dq/ds)·d²q/ds²); per axis |q̇| ≤ speed; |ṗ| ≤ tvel;
  |ω| ≤ rvel. With x = ṡ² and s̈ constant between neighbouring points (x then changes linearly
  with s), a backward pass finds at each point the largest x from which the arm can still brake to
  the end; a forward pass then accelerates as hard as the limits allow without leaving that set.
  On a trapezoid in s this is exact; elsewhere the error shrinks with the spacing (tests).
- Paths: `Line` and `Arc` (TCP poses as functions of the arc length, orientation by the smallest
  rotation, 10.1.4.1), `JointLine` (movej), or any joint path given with its derivatives
  (`profile_of_joint_path`, e.g. the blended path the simulator built, timed here anew).
  Cartesian paths are followed by the robot model's IK (the solution nearest the previous one);
  their derivatives are central differences of the IK, 2·h apart.

Units: degrees (mm for a prismatic axis), millimetres, seconds.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

# ---- closed forms -----------------------------------------------------------------------------


def bang_bang(d: float, v: float, a: float, dec: float) -> float:
    """Rest-to-rest time over distance d at speed v, acceleration a, deceleration dec: trapezoid
    when the speed is reached (d >= v²/2a + v²/2dec), else triangle with peak √(2·d·a·dec/(a+dec))."""
    d = abs(d)
    if d == 0.0:
        return 0.0
    if d >= v * v / (2 * a) + v * v / (2 * dec):
        return d / v + v / (2 * a) + v / (2 * dec)
    vp = math.sqrt(2 * d * a * dec / (a + dec))
    return vp / a + vp / dec


def movej_time(delta, V, A, D) -> float:
    """A synchronised straight joint line (movej without tvel/rvel): the path parameter λ ∈ [0, 1]
    gets the tightest ratio of every axis: v = min V_i/|Δ_i|, a = min A_i/|Δ_i|, d = min D_i/|Δ_i|."""
    moving = [(abs(x), v, a, d) for x, v, a, d in zip(delta, V, A, D) if abs(x) > 0.0]
    if not moving:
        return 0.0
    return bang_bang(1.0, min(v / x for x, v, _, _ in moving), min(a / x for x, _, a, _ in moving),
                     min(d / x for x, _, _, d in moving))


# ---- limits -----------------------------------------------------------------------------------


@dataclass(frozen=True)
class Limits:
    """Per axis speed V, acceleration A, deceleration D; tvel (mm/s); rvel (deg/s)."""

    V: tuple
    A: tuple
    D: tuple
    tvel: float = math.inf
    rvel: float = math.inf

    @classmethod
    def of(cls, model, vel=100.0, accel=100.0, decel=100.0, tvel=9999.0, rvel=9999.0, monitor=100.0) -> Limits:
        """10.5.1: joint figures in % of the model's nominal ones; every limit times the monitor
        speed (docs/motion.md, "Monitor speed")."""
        m = monitor / 100.0
        return cls(tuple(v * vel / 100 * m for v in model.nominal_speeds),
                   tuple(a * accel / 100 * m for a in model.accelerations),
                   tuple(a * decel / 100 * m for a in model.accelerations), tvel * m, rvel * m)


# ---- rotations (written here: no val3check geometry) --------------------------------------------


def rotation(axis, angle_rad: float) -> np.ndarray:
    """Rodrigues: the rotation of `angle_rad` about the unit `axis`."""
    k = np.asarray(axis, dtype=float)
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(angle_rad) * K + (1 - math.cos(angle_rad)) * (K @ K)


def axis_angle(R: np.ndarray) -> tuple[np.ndarray, float]:
    """(unit axis, angle in [0, π]) of a rotation matrix (the smallest rotation); the angle by
    atan2(sin, cos), precise for tiny and near half turns alike."""
    w = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]]) / 2  # sin(angle)·axis
    sin = float(np.linalg.norm(w))
    angle = math.atan2(sin, (np.trace(R) - 1) / 2)
    if angle < 1e-15:
        return np.array([0.0, 0.0, 1.0]), 0.0
    if math.pi - angle < 1e-6:  # near a half turn: the axis from the symmetric part
        B = (R + np.eye(3)) / 2
        k = np.sqrt(np.clip(np.diag(B), 0, None))
        i = int(np.argmax(k))
        k = B[i] / k[i]
        return k / np.linalg.norm(k), angle
    return w / sin, angle


def _pose(R, p) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = p
    return T


# ---- paths ------------------------------------------------------------------------------------


class Line:
    """movel: the TCP on the segment, the orientation turning by the fraction of the smallest
    rotation (10.1.4.1). s: arc length (mm), also outside [0, L] (for the difference stencils)."""

    def __init__(self, T0, T1):
        self.p0, self.R0 = np.asarray(T0)[:3, 3], np.asarray(T0)[:3, :3]
        d = np.asarray(T1)[:3, 3] - self.p0
        self.length = float(np.linalg.norm(d))
        self.u = d / self.length
        self.axis, self.angle = axis_angle(np.asarray(T1)[:3, :3] @ self.R0.T)

    def pose(self, s: float) -> np.ndarray:
        f = s / self.length
        return _pose(rotation(self.axis, f * self.angle) @ self.R0, self.p0 + s * self.u)


class Arc:
    """movec through three poses: the TCP on the circle, the orientation turning start → via over
    the first part of the arc and via → target over the rest (10.1.4.1). s: arc length (mm)."""

    def __init__(self, T0, Tvia, T1):
        P = [np.asarray(T)[:3, 3] for T in (T0, Tvia, T1)]
        a, b = P[1] - P[0], P[2] - P[0]
        n = np.cross(a, b)
        nn = float(n @ n)
        c = P[0] + (np.cross(n, a) * float(b @ b) - np.cross(n, b) * float(a @ a)) / (2 * nn)  # circumcentre
        self.c, self.n = c, n / math.sqrt(nn)
        self.r = float(np.linalg.norm(P[0] - c))
        self.e1 = (P[0] - c) / self.r
        self.e2 = np.cross(self.n, self.e1)
        ang = [math.atan2(float((p - c) @ self.e2), float((p - c) @ self.e1)) % (2 * math.pi) for p in P[1:]]
        self.phi_via, self.phi = ang
        self.length = self.r * self.phi
        self.R = [np.asarray(T)[:3, :3] for T in (T0, Tvia, T1)]
        self.turns = [axis_angle(self.R[1] @ self.R[0].T), axis_angle(self.R[2] @ self.R[1].T)]

    def pose(self, s: float) -> np.ndarray:
        phi = s / self.r
        p = self.c + self.r * (math.cos(phi) * self.e1 + math.sin(phi) * self.e2)
        if phi <= self.phi_via:
            (k, ang), R, f = self.turns[0], self.R[0], phi / self.phi_via
        else:
            (k, ang), R, f = self.turns[1], self.R[1], (phi - self.phi_via) / (self.phi - self.phi_via)
        return _pose(rotation(k, f * ang) @ R, p)


class JointLine:
    """movej: the straight line in joint space, λ ∈ [0, 1]."""

    def __init__(self, q0, q1):
        self.q0, self.dq = np.asarray(q0, dtype=float), np.asarray(q1, dtype=float) - np.asarray(q0, dtype=float)
        self.length = 1.0

    def q(self, lam, order: int = 0) -> np.ndarray:
        lam = np.atleast_1d(np.asarray(lam, dtype=float))[:, None]
        if order == 0:
            return self.q0 + lam * self.dq
        return np.tile(self.dq if order == 1 else np.zeros_like(self.dq), (lam.shape[0], 1))


# ---- sampling a path: joint derivatives and the TCP's rates -----------------------------------


@dataclass
class Sampled:
    """A path at points s (ascending): dq/ds, d²q/ds² per axis, TCP speed |dp/ds| and tool
    rotation rate |dθ/ds| (deg per unit of s), joints q."""

    s: np.ndarray
    q: np.ndarray
    dq: np.ndarray
    ddq: np.ndarray
    dp: np.ndarray
    dw: np.ndarray


def _rates(T_minus, T_plus, h):
    """|dp/ds| and |dθ/ds| (deg) from poses 2h apart."""
    dp = float(np.linalg.norm(T_plus[:3, 3] - T_minus[:3, 3])) / (2 * h)
    _, ang = axis_angle(T_plus[:3, :3] @ T_minus[:3, :3].T)
    return dp, math.degrees(ang) / (2 * h)


def _ik_near(model, T, near, tool):
    sols = model.ik(T, near=list(near), tool=tool)
    if not sols:
        raise ValueError(f"{model.name}: the reference path leaves the arm's reach")
    return np.array(sols[0], dtype=float)


def _ghost(model, T, q1, q2, q3, tool):
    """A point beyond an end of the path: the IK there, or (past a joint limit or the reach) the
    quadratic through the three nearest points."""
    try:
        return _ik_near(model, T, q1, tool)
    except ValueError:
        return 3 * q1 - 3 * q2 + q3


def sample_cartesian(model, curve, q_start, tool=None, n: int = 2001) -> Sampled:
    """The joints along a Cartesian curve (Line, Arc) by the model's IK at n points, each the
    solution nearest the previous one from `q_start`; dq/ds and d²q/ds² by five-point central
    differences on those points (two more beyond each end, on the curve's continuation); the TCP's
    speed and rotation rate per mm from poses a thousandth of a step apart."""
    L = curve.length
    step = L / (n - 1)
    s = np.concatenate([[-2 * step, -step], np.linspace(0.0, L, n), [L + step, L + 2 * step]])
    Q = [_ik_near(model, curve.pose(0.0), q_start, tool)]
    for sk in s[3:-2]:
        Q.append(_ik_near(model, curve.pose(float(sk)), Q[-1], tool))
    for sk in s[-2:]:
        Q.append(_ghost(model, curve.pose(float(sk)), Q[-1], Q[-2], Q[-3], tool))
    for sk in (s[1], s[0]):
        Q.insert(0, _ghost(model, curve.pose(float(sk)), Q[0], Q[1], Q[2], tool))
    Q = np.array(Q)
    m2, m1, c, p1, p2 = Q[:-4], Q[1:-3], Q[2:-2], Q[3:-1], Q[4:]
    dQ = (m2 - 8 * m1 + 8 * p1 - p2) / (12 * step)
    ddQ = (-m2 + 16 * m1 - 30 * c + 16 * p1 - p2) / (12 * step * step)
    hh = step * 1e-3
    rates = [_rates(curve.pose(float(sk) - hh), curve.pose(float(sk) + hh), hh) for sk in s[2:-2]]
    return Sampled(s[2:-2], c, dQ, ddQ, np.array([r[0] for r in rates]), np.array([r[1] for r in rates]))


def sample_joint_path(model, path, s0: float, s1: float, tool=None, n: int = 2001, h: float | None = None) -> Sampled:
    """A joint path given as path.q(s, order) (order 0, 1, 2): its TCP rates by the model's FK
    (central differences 2h apart). JointLine, or any object with that method."""
    s = np.linspace(s0, s1, n)
    h = (s1 - s0) * 1e-5 if h is None else h
    # the derivatives at s1 from inside [s0, s1]: a path of pieces (val3check's Path) gives at a
    # junction those of the piece that starts there, which may go the other way
    inside = s.copy()
    inside[-1] = np.nextafter(s1, s0)
    Q, dQ, ddQ = path.q(s, 0), path.q(inside, 1), path.q(inside, 2)
    sm, sp = np.maximum(s - h, s0), np.minimum(s + h, s1)  # one-sided at the ends
    Qm, Qp = path.q(sm, 0), path.q(sp, 0)
    dP, dW = [], []
    for qm, qp, width in zip(Qm, Qp, sp - sm):
        Tm, Tp = np.eye(4), np.eye(4)
        Tm[:3, :] = np.array(model.fk_matrix(list(qm), tool))
        Tp[:3, :] = np.array(model.fk_matrix(list(qp), tool))
        dp, dw = _rates(Tm, Tp, width / 2)
        dP.append(dp)
        dW.append(dw)
    return Sampled(s, Q, dQ, ddQ, np.array(dP), np.array(dW))


# ---- the optimum --------------------------------------------------------------------------------


@dataclass
class Profile:
    """x = ṡ² at the points s; duration (s); t at each point."""

    s: np.ndarray
    x: np.ndarray
    duration: float
    t: np.ndarray


def _refine(sm: Sampled, n: int) -> Sampled:
    """The same path on n points, derivatives interpolated linearly between the samples."""
    if n <= len(sm.s):
        return sm
    s = np.linspace(sm.s[0], sm.s[-1], n)

    def lin(a):
        return np.stack([np.interp(s, sm.s, a[:, i]) for i in range(a.shape[1])], axis=1)
    return Sampled(s, lin(sm.q), lin(sm.dq), lin(sm.ddq), np.interp(s, sm.s, sm.dp), np.interp(s, sm.s, sm.dw))


def _segment_times(ds, x0, x1, a, d, cap) -> np.ndarray:
    """Per segment: accelerate at a from ṡ² = x0, brake at d to x1, cruising at cap if reached
    (the segment's own bang-bang); constant s̈ where a or d is not positive."""
    r0, r1 = np.sqrt(x0), np.sqrt(x1)
    with np.errstate(divide="ignore", invalid="ignore"):
        plain = 2 * ds / (r0 + r1)
        xp = (2 * a * d * ds + x0 * d + x1 * a) / (a + d)
        cruise = xp > cap
        xp = np.where(cruise, cap, xp)
        rp = np.sqrt(xp)
        rest = np.where(cruise, (ds - (cap - x0) / (2 * a) - (cap - x1) / (2 * d)) / rp, 0.0)
        bang = (rp - r0) / a + (rp - r1) / d + rest
    good = (a > 1e-9) & (d > 1e-9) & np.isfinite(bang)
    return np.where(good, np.minimum(bang, plain), plain)


def optimal(sm: Sampled, lim: Limits, n: int | None = None, x_start: float = 0.0, x_end: float = 0.0) -> Profile:
    """The time-optimal profile on the sampled path (see the module's docstring), on n points
    (the samples' derivatives interpolated in between), from ṡ² = x_start to x_end."""
    if n is not None:
        sm = _refine(sm, n)
    s = sm.s
    N = len(sm.s)
    V, A, D = (np.asarray(v, dtype=float) for v in (lim.V, lim.A, lim.D))
    sgn = np.where(sm.dq >= 0, 1.0, -1.0)
    g = np.abs(sm.dq)
    h = sgn * sm.ddq
    still = g < 1e-8  # an axis that does not move here (difference noise is far below)
    h = np.where(still & (np.abs(h) < 1e-6), 0.0, h)
    # speed caps on x = ṡ²: joint speeds, tvel, rvel, and the axes standing still with curvature
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        xcap = np.min(np.where(still, np.inf, (V / np.where(still, 1.0, g)) ** 2), axis=1)
        xcap = np.minimum(xcap, np.where(sm.dp > 1e-12, (lim.tvel / np.maximum(sm.dp, 1e-300)) ** 2, np.inf))
        xcap = np.minimum(xcap, np.where(sm.dw > 1e-12, (lim.rvel / np.maximum(sm.dw, 1e-300)) ** 2, np.inf))
        curb = np.where(still & (h > 0), A / np.where(h > 0, h, 1.0), np.where(still & (h < 0), D / np.where(h < 0, -h, 1.0), np.inf))
        xcap = np.minimum(xcap, curb.min(axis=1))
    gs = np.where(still, 1.0, g)
    Uc, Us = np.where(still, np.inf, A / gs), np.where(still, 0.0, -h / gs)  # s̈ ≤ Uc + Us·x
    Lc, Ls = np.where(still, -np.inf, -D / gs), np.where(still, 0.0, -h / gs)  # s̈ ≥ Lc + Ls·x
    # acceleration limit curve: the largest x where every lower bound stays under every upper one
    coef = Ls[:, :, None] - Us[:, None, :]
    rhs = Uc[:, None, :] - Lc[:, :, None]
    with np.errstate(invalid="ignore", divide="ignore"):
        bound = np.where((coef > 1e-15) & np.isfinite(rhs), rhs / coef, np.inf)
    xmax = np.minimum(xcap, bound.reshape(N, -1).min(axis=1)).tolist()
    ds = np.diff(s)
    # backward: K[k] = the largest x at k from which the end is reachable braking as hard as allowed:
    # x + 2·ds·(Lc + Ls·x) <= K[k+1] for every axis, i.e. x <= (K[k+1] - c)/e where e > 0
    two = 2 * ds[:, None]
    e = 1 + two * Ls[:-1]
    ok = ~still[:-1] & (e > 0)
    C = np.where(ok, two * np.where(still[:-1], 0.0, Lc[:-1]), -1e300).tolist()
    E = np.where(ok, e, 1.0).tolist()
    K = [0.0] * N
    K[-1] = min(x_end, xmax[-1])
    for k in range(N - 2, -1, -1):
        K1 = K[k + 1]
        K[k] = max(0.0, min(xmax[k], min([(K1 - c) / ee for c, ee in zip(C[k], E[k])])))
    # forward: as hard as allowed, never outside the braking set
    U0 = (two * Uc[:-1]).tolist()
    U1 = (1 + two * Us[:-1]).tolist()  # x + 2·ds·(Uc + Us·x) = U0 + U1·x (inf for a still axis)
    x = [0.0] * N
    x[0] = min(x_start, K[0])
    for k in range(N - 1):
        xk = x[k]
        x[k + 1] = max(0.0, min(min([a + b * xk for a, b in zip(U0[k], U1[k])]), K[k + 1]))
    xs = np.array(x)
    # each segment's time: the fastest way from x[k] to x[k+1] over ds with that segment's
    # acceleration and deceleration (bang-bang inside the segment, capped): exact when a ramp or
    # a peak ends between two points, where constant s̈ per segment would not be
    with np.errstate(invalid="ignore"):
        up = np.min(np.where(still, np.inf, Uc + Us * xs[:, None]), axis=1)[:-1]
        down = -np.max(np.where(still, -np.inf, Lc + Ls * xs[:, None]), axis=1)[:-1]
    step = (xs[1:] - xs[:-1]) / (2 * ds)
    xm = np.asarray(xmax)
    cap = np.maximum(np.minimum(xm[:-1], xm[1:]), np.maximum(xs[:-1], xs[1:]))
    dt = _segment_times(ds, xs[:-1], xs[1:], np.maximum(up, step), np.maximum(down, -step), cap)
    t = np.concatenate([[0.0], np.cumsum(dt)])
    return Profile(s, xs, float(t[-1]), t)


# ---- the motions ----------------------------------------------------------------------------------


def movel(model, T0, T1, q_start, lim: Limits, tool=None, n_ik: int = 2001, n: int = 20001) -> Profile:
    """The optimum of a rest-to-rest movel from the TCP pose T0 (joints q_start) to T1."""
    return optimal(sample_cartesian(model, Line(T0, T1), q_start, tool, n_ik), lim, n)


def movec(model, T0, Tvia, T1, q_start, lim: Limits, tool=None, n_ik: int = 2001, n: int = 20001) -> Profile:
    """The optimum of a rest-to-rest movec from T0 through Tvia to T1."""
    return optimal(sample_cartesian(model, Arc(T0, Tvia, T1), q_start, tool, n_ik), lim, n)


def movej(model, q0, q1, lim: Limits, tool=None, n_ik: int = 2001, n: int = 20001) -> Profile:
    """The optimum of a rest-to-rest movej (tvel and rvel included: the TCP's rates by FK)."""
    return optimal(sample_joint_path(model, JointLine(q0, q1), 0.0, 1.0, tool, n_ik), lim, n)


def profile_of_joint_path(model, path, s0: float, s1: float, lim: Limits, tool=None, n_ik: int = 4001,
                          n: int = 40001) -> Profile:
    """The optimum of a rest-to-rest motion along any joint path with path.q(s, order)."""
    return optimal(sample_joint_path(model, path, s0, s1, tool, n_ik), lim, n)
