"""Joint positions along a Cartesian curve in one configuration (movel, movec, Cartesian blends).

10.1.4.2: a straight line or a circle keeps the configuration of its start. The curve is solved on
a grid of its parameter with the inverse branch of that configuration (all gridpoints at once,
`kin.ArmKin.ik_all`); axes are unwrapped from the start position, so a path that needs more than
the joint range shows up as a joint-limit violation rather than a silent turn. Where two
neighbouring solutions differ by more than `JUMP_DEG` the interval is halved, down to a spacing of
`MIN_STEP` of the path: a jump that survives is a discontinuity of the solution — the path goes
through a singularity (or a configuration boundary) and cannot be followed.

The result is `Track`: the grid, the joint positions, the distances to the singularities at
each gridpoint, and the first failure if any (`Failure`: kind "reach", "config", "limits",
"singular", with where along the path and the numbers).
"""

from __future__ import annotations

import math

import numpy as np

from ..light_dataclass import dataclass
from .kin import ArmKin, Singularity, wrap_near

JUMP_DEG = 2.0  # neighbouring gridpoints further apart on some axis are refined
MIN_STEP = 1e-6  # finest spacing of the path parameter (fraction of the path)
MAX_POINTS = 4000
LIMIT_TOL = 1e-7
DERIV_STEP = 1e-7  # of the path parameter, for dq/dλ


@dataclass
class Failure:
    """Where and why a Cartesian path cannot be followed in its configuration."""
    kind: str  # "reach" | "config" | "limits" | "singular"
    lam: float  # where along the path (fraction)
    axis: int | None = None  # 0-based axis for limits / the jumping axis for singular
    amount: float = 0.0  # degrees beyond the limit, or the jump in degrees
    which: str = ""  # singular: "wrist" | "elbow" | "shoulder"
    other_config: int | None = None  # config: a configuration that reaches the failing point
    joints: tuple[float, ...] | None = None  # the joint position at (or just before) the failure


@dataclass
class Track:
    """A Cartesian curve solved in one configuration: its grid, joints, distances to the singularities, and the first failure."""
    lam: np.ndarray
    Q: np.ndarray
    sing: Singularity
    failure: Failure | None = None
    D: np.ndarray | None = None  # dq/dλ at the gridpoints (central differences), when no failure


def grid_size(curve, per_mm: float = 0.125, per_deg: float = 0.25, per_turn_deg: float = 1 / 6, lo: int = 8,
              hi: int = 300) -> int:
    """Number of intervals for a curve: one per 8 mm of TCP path, per 4° of tool rotation and per
    6° the direction of travel turns (the spline between them stays within a micrometre of the
    curve, and its curvature, which sets how fast a circle can be followed, within a fraction of a
    percent; near a singularity the grid is refined, see `track`)."""
    n = int(math.ceil(curve.length_mm * per_mm + curve.angle_deg * per_deg + curve.turn_deg * per_turn_deg))
    return max(lo, min(hi, n))


def _select(kin: ArmKin, T: np.ndarray, code: int):
    """The solution of configuration `code` at each pose: (Q (N, 6) with NaN rows where there is
    none, a reachable other configuration code per row or -1)."""
    n = len(T)
    if kin.generic:  # one pose at a time through the model (a SCARA)
        Q = kin.solve_config(T, code)
        other = np.full(n, -1)
        for i in np.nonzero(np.isnan(Q[:, 0]))[0]:
            _, codes = kin.solutions(T[i])
            if len(codes):
                other[i] = int(codes.min())
        return Q, other
    if kin.branch_is_config:  # one branch is the configuration: solve only it, check, mend
        Q = kin.ik_all(T, (code,))[:, code]
        good = ~np.isnan(Q[:, [0, 1, 2, 4, 5]]).any(axis=1)
        if good.any():
            fill = Q[good].copy()
            fill[np.isnan(fill[:, 3]), 3] = 0.0
            good[good] = kin.config_codes(fill) == code
        if good.all():
            return Q, np.full(n, -1)
        bad = ~good
        Qb, ob = _select_all(kin, T[bad], code)
        Q[bad] = Qb
        other = np.full(n, -1)
        other[bad] = ob
        return Q, other
    return _select_all(kin, T, code)


def _select_all(kin: ArmKin, T: np.ndarray, code: int):
    """For each pose of T, the solution in configuration `code` among every branch (arms whose branch is not the configuration)."""
    sols = kin.ik_all(T)  # (N, 8, 6)
    n = len(T)
    flat = sols.reshape(-1, 6)
    ok = ~np.isnan(flat[:, [0, 1, 2, 4, 5]]).any(axis=1)
    codes = np.full(len(flat), -1)
    if ok.any():
        fill = flat[ok].copy()
        fill[np.isnan(fill[:, 3]), 3] = 0.0
        codes[ok] = kin.config_codes(fill)
    codes = codes.reshape(n, 8)
    match = codes == code
    Q = np.full((n, 6), np.nan)
    has = match.any(axis=1)
    idx = np.argmax(match, axis=1)
    Q[has] = sols[np.arange(n)[has], idx[has]]
    other = np.where(has, -1, np.max(np.where(codes >= 0, codes, -1), axis=1))
    return Q, other


def _fill_wrist(Q: np.ndarray, q_start: np.ndarray) -> None:
    """At an exactly singular wrist (j4 NaN, j6 = j4 + j6), keep j4 from the previous point."""
    if Q.shape[1] < 6:
        return
    bad = np.isnan(Q[:, 3]) & ~np.isnan(Q[:, 0])
    if not bad.any():
        return
    prev = q_start[3]
    for i in range(len(Q)):
        if np.isnan(Q[i, 0]):
            continue
        if bad[i]:
            Q[i, 3] = prev
            Q[i, 5] = Q[i, 5] - prev
        prev = Q[i, 3]


def _unwrap(Q: np.ndarray, q_start: np.ndarray, revolute: np.ndarray) -> np.ndarray:
    """Each revolute axis continuous along the path, starting on the turn of the start position."""
    U = Q.copy()
    U[:, revolute] = np.unwrap(Q[:, revolute], period=360.0, axis=0)
    off = np.where(revolute, 360.0 * np.round((q_start - U[0]) / 360.0), 0.0)
    return U + off


def track(kin: ArmKin, curve, tool: np.ndarray | None, q_start, code: int, n: int | None = None,
          exact_start: bool = True) -> Track:
    """Solve `curve` (TCP poses) in configuration `code`, starting at joints q_start."""
    q_start = np.asarray(q_start, dtype=float)
    tinv = None if tool is None else np.linalg.inv(tool)
    n = grid_size(curve) if n is None else n
    lam = np.linspace(0.0, 1.0, n + 1)
    knots = getattr(curve, "knots", ())
    if knots:  # where the curve's orientation law changes (movec's intermediate point)
        k = np.asarray(knots, dtype=float)
        k = k[np.abs(lam[np.clip(np.searchsorted(lam, k), 0, len(lam) - 1)] - k) > 1e-9]
        k = k[np.abs(lam[np.clip(np.searchsorted(lam, k) - 1, 0, len(lam) - 1)] - k) > 1e-9]
        lam = np.unique(np.concatenate([lam, k]), return_index=True)[0]  # (return_index: no numpy.ma import)

    def solve(ls):
        """The joints at the path parameters ls (in the start configuration)."""
        T = curve.poses(ls)
        if tinv is not None:
            T = T @ tinv
        return _select(kin, T, code)

    def near(ls):  # the same branch a hair away from solved points (for dq/dλ): no checks needed
        """The same branch a hair away from solved points (for dq/dλ)."""
        if not kin.branch_is_config:
            return solve(ls)[0]
        T = curve.poses(ls)
        if tinv is not None:
            T = T @ tinv
        return kin.ik_all(T, (code,))[:, code]

    Q, other = solve(lam)
    failure = None
    for depth in range(64):
        missing = np.isnan(Q[:, 0])
        if missing.any():
            i = int(np.argmax(missing))
            kind = "config" if other[i] >= 0 else "reach"
            before = Q[i - 1] if i > 0 and not np.isnan(Q[i - 1, 0]) else None
            failure = Failure(kind, float(lam[i]), other_config=int(other[i]) if other[i] >= 0 else None,
                              joints=None if before is None else tuple(before))
            Q = Q[:i]
            lam = lam[:i]
            other = other[:i]
            break
        _fill_wrist(Q, q_start)
        Q = _unwrap(Q, q_start, kin.revolute)
        if exact_start:
            Q[0] = q_start
        jumps = np.abs(np.diff(Q, axis=0)).max(axis=1)
        big = np.nonzero(jumps > JUMP_DEG)[0]
        if len(big) == 0:
            break
        widths = lam[big + 1] - lam[big]
        refinable = big[widths > MIN_STEP]
        if len(refinable) == 0 or len(lam) + len(refinable) > MAX_POINTS:
            i = int(big[0])
            ax = int(np.argmax(np.abs(Q[i + 1] - Q[i])))
            sing = kin.singularity(Q[i:i + 2])
            which = _nearest_singularity(kin, sing)
            failure = Failure("singular", float(lam[i]), axis=ax, amount=float(abs(Q[i + 1, ax] - Q[i, ax])),
                              which=which, joints=tuple(Q[i]))
            Q = Q[: i + 1]
            lam = lam[: i + 1]
            break
        mids = (lam[refinable] + lam[refinable + 1]) / 2.0
        Qm, om = solve(mids)
        lam = np.concatenate([lam, mids])
        order = np.argsort(lam, kind="stable")
        lam = lam[order]
        Q = np.concatenate([Q, Qm])[order]
        other = np.concatenate([other, om])[order]
    if failure is None and len(Q):
        out_lo = kin.lo - LIMIT_TOL - Q
        out_hi = Q - kin.hi - LIMIT_TOL
        excess = np.maximum(out_lo, out_hi)
        bad = excess > 0
        if bad.any():
            i = int(np.argmax(bad.any(axis=1)))
            ax = int(np.argmax(excess.max(axis=0)))
            failure = Failure("limits", float(lam[i]), axis=ax, amount=float(excess[:, ax].max() + LIMIT_TOL),
                              joints=tuple(Q[i]))
    sing = kin.singularity(Q) if len(Q) else Singularity(np.zeros(0), np.zeros(0), np.zeros(0))
    D = None
    if failure is None:
        # dq/dλ by central differences of the same branch (the curve continues past its ends)
        h = DERIV_STEP
        Qp = near(lam + h)
        Qm = near(lam - h)
        if Q.shape[1] >= 6:
            Qp[np.isnan(Qp[:, 3]), 3] = Q[np.isnan(Qp[:, 3]), 3]
            Qm[np.isnan(Qm[:, 3]), 3] = Q[np.isnan(Qm[:, 3]), 3]
        rev = kin.revolute
        Qp = np.where(rev, wrap_near(Qp, Q), Qp)
        Qm = np.where(rev, wrap_near(Qm, Q), Qm)
        D = (Qp - Qm) / (2 * h)
        bad = ~np.isfinite(D).all(axis=1)
        if bad.any():  # a derivative point out of reach (the path ends on the boundary): one-sided
            fwd = (Qp - Q) / h
            back = (Q - Qm) / h
            D[bad] = np.where(np.isfinite(fwd[bad]), fwd[bad], back[bad])
            D[~np.isfinite(D)] = 0.0
    return Track(lam, Q, sing, failure, D)


def _nearest_singularity(kin: ArmKin, sing: Singularity) -> str:
    """Which singularity a jump belongs to: the one nearest, relative to its threshold."""
    from .checks import THRESHOLDS

    scores = {
        "wrist": float(np.min(sing.wrist)) / THRESHOLDS["wrist"],
        "elbow": float(np.min(sing.elbow)) / THRESHOLDS["elbow"],
        "shoulder": float(np.min(sing.shoulder)) / THRESHOLDS["shoulder"],
    }
    return min(scores, key=scores.get)
