"""The time-optimal profile of any path on its grid, with VAL 3's limits (10.3.1).

10.3.1: "à chaque instant, le robot se déplace et accélère au maximum de ses capacités, tout en
respectant les contraintes de vitesse et d'accélération". On the path parameter s, with x = ṡ²
and u = s̈, joint k moves with q̇ₖ = q'ₖ·ṡ and q̈ₖ = q'ₖ·u + q''ₖ·x. VAL 3 bounds the acceleration
with `accel` while an axis speeds up and with `decel` while it slows down, so per axis
q̈ₖ·sign(q'ₖ) ∈ [-decel, accel] — for the path acceleration, u ∈ [L(x), U(x)] with

    U(x) = minₖ (Ucₖ + Usₖ·x),   L(x) = maxₖ (Lcₖ + Lsₖ·x)   (linear in x per axis)

and x below the velocity limit curve (joint speeds, tvel, rvel) and the acceleration limit curve
(refine.accel_xmax). Between neighbouring gridpoints u is constant (x linear in s) and obeys the
bounds at both ends (the "interpolation" discretisation of TOPP-RA: never faster than allowed).

Reachability, as TOPP-RA does it (Pham & Pham 2018), written for these bounds, whose 1-D linear
programs have closed forms: a backward pass gives at each gridpoint the largest x from which the
end is still reachable braking as hard as allowed (braking from x over h: x + 2h·L(x) ≤ K next,
and the bound at the next gridpoint too); a forward pass then accelerates as hard as allowed
(x next = x + 2h·U(x), the next gridpoint's bound included) without leaving those sets. Every
step is the minimum of a few affine functions of one number. The result at the gridpoints is
the optimum of the discretised problem; refine.py then makes each interval a bang-bang, so that
ramps are not set by the grid. The grid is dense enough (paths.py) for 0.5 % of the continuous
optimum (bench/bench_timing.py).

When the start speed is above what the path allows from there (the monitor speed was lowered),
the arm first brakes along the path (safe.brake_into); when no profile exists (a cusp, the arm
standing still inside the path), `safe.integrate()` gives a slower safe profile and the caller
reports it (R019).
"""

from __future__ import annotations

import numpy as np

from ...light_dataclass import dataclass
from .analytic import duration
from .grid import Grid
from .refine import accel_xmax, coefficients, refine
from .safe import brake_into, integrate

_OFF = 1e300  # an affine bound that never binds: 0·x + _OFF


@dataclass
class TimedProfile:
    """ṡ at breakpoints s (constant path acceleration in between); `fallback` when no optimal
    profile exists and the safe numerical integration was used."""

    s: np.ndarray
    sd: np.ndarray
    fallback: bool = False

    @property
    def duration(self) -> float:
        """The profile's time (s)."""
        return duration(self.s, self.sd)


def bounds(grid: Grid, coef: tuple | None = None) -> tuple[np.ndarray, ...]:
    """Per gridpoint and axis, the path acceleration bounds u ≤ Uc + Us·x and u ≥ Lc + Ls·x
    (module docstring); an axis that does not move along the path bounds only the speed
    (accel_xmax) and is given bounds that never bind. `coef`: refine.coefficients(grid)."""
    uc, us, lc, _, _, _ = coefficients(grid) if coef is None else coef
    return uc, us, lc, us


def steps(grid: Grid, coef: tuple | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The affine maps of both passes, per interval k (between gridpoints k and k+1), as arrays
    (intervals, pairs, 2) of (slope, offset) pairs: backward, K[k] ≤ slope·K[k+1] + offset; forward, x[k+1] ≤ slope·x[k] +
    offset. Each pair is one axis's bound at one end of the interval (module docstring)."""
    uc, us, lc, ls = bounds(grid, coef)
    h = np.diff(grid.s)[:, None]
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        # backward: braking at the start's bound, x(1 + 2h·Ls) + 2h·Lc ≤ K  (where 1 + 2h·Ls > 0)
        e0 = 1.0 + 2.0 * h * ls[:-1]
        ok0 = np.isfinite(lc[:-1]) & (e0 > 1e-12)
        b_sl0 = np.where(ok0, 1.0 / np.where(ok0, e0, 1.0), 0.0)
        b_of0 = np.where(ok0, -2.0 * h * lc[:-1] * b_sl0, _OFF)
        # ... and at the end's bound, x ≤ K - 2h·(Lc' + Ls'·K)
        ok1 = np.isfinite(lc[1:])
        b_sl1 = np.where(ok1, 1.0 - 2.0 * h * ls[1:], 0.0)
        b_of1 = np.where(ok1, -2.0 * h * lc[1:], _OFF)
        # forward: accelerating at the start's bound, x + 2h·(Uc + Us·x)
        f_sl0 = np.where(np.isfinite(uc[:-1]), 1.0 + 2.0 * h * us[:-1], 0.0)
        f_of0 = np.where(np.isfinite(uc[:-1]), 2.0 * h * uc[:-1], _OFF)
        # ... and at the end's: y ≤ x + 2h·(Uc' + Us'·y), i.e. y ≤ (x + 2h·Uc') / (1 - 2h·Us')
        e1 = 1.0 - 2.0 * h * us[1:]
        ok2 = np.isfinite(uc[1:]) & (e1 > 1e-12)
        f_sl1 = np.where(ok2, 1.0 / np.where(ok2, e1, 1.0), 0.0)
        f_of1 = np.where(ok2, 2.0 * h * uc[1:] * f_sl1, _OFF)
    m, axes = b_sl0.shape  # the pairs filled in place: np.stack and concatenate cost as much as the arithmetic
    back = np.empty((m, 2 * axes, 2))
    back[:, :axes, 0], back[:, :axes, 1], back[:, axes:, 0], back[:, axes:, 1] = b_sl0, b_of0, b_sl1, b_of1
    fwd = np.empty((m, 2 * axes, 2))
    fwd[:, :axes, 0], fwd[:, :axes, 1], fwd[:, axes:, 0], fwd[:, axes:, 1] = f_sl0, f_of0, f_sl1, f_of1
    return back, fwd


def reachable(grid: Grid, cap: list, back: list, x_end: float = 0.0, at_cap: list | None = None) -> list:
    """The backward pass: K[k], the largest ṡ² at gridpoint k from which the end (at x_end) is
    reachable within the limits. `back`: per interval, its pairs as one row [a0, b0, a1, b1...].
    `at_cap`: each step's value from K[k + 1] = cap[k + 1] (`_stepped`), taken where that holds;
    `back` may then be a 2-D array, a row made a list only where a step is computed."""
    n = len(cap)
    K = [0.0] * n
    K[-1] = min(x_end, cap[-1])
    lowest = _lowest_of(back)
    if at_cap is None:
        for k in range(n - 2, -1, -1):
            K[k] = max(0.0, min(cap[k], lowest(back[k], K[k + 1])))
        return K
    row = _rows(back)
    for k in range(n - 2, -1, -1):
        kn = K[k + 1]
        K[k] = at_cap[k] if kn == cap[k + 1] else max(0.0, min(cap[k], lowest(row(k), kn)))
    return K


def forward(x0: float, cap: list, K: list, fwd: list, k0: int = 0, at_K: list | None = None) -> list:
    """The forward pass from ṡ² = x0 at gridpoint k0: as fast as allowed, within K (`fwd`: rows
    as in `reachable`). `at_K`: each step's value from x[k] = K[k] (`_stepped`), taken where that
    holds; `fwd` may then be a 2-D array, as in `reachable`."""
    n = len(cap)
    x = [0.0] * n
    x[k0] = x0
    lowest = _lowest_of(fwd)
    if at_K is None:
        for k in range(k0, n - 1):
            x[k + 1] = max(0.0, min(lowest(fwd[k], x[k]), K[k + 1], cap[k + 1]))
        return x
    row = _rows(fwd)
    for k in range(k0, n - 1):
        xk = x[k]
        x[k + 1] = at_K[k] if xk == K[k] else max(0.0, min(lowest(row(k), xk), K[k + 1], cap[k + 1]))
    return x


def _rows(rows):
    """Row k of `rows` as a list of floats: a list's own, or a 2-D array's made when asked (about
    half the rows of a pass are: converting them all cost as much as the pass)."""
    return rows.__getitem__ if isinstance(rows, list) else (lambda k: rows[k].tolist())


def _stepped(pairs: np.ndarray, x: np.ndarray, *bounds: np.ndarray) -> list | None:
    """Per interval k, a pass's step max(0, min(lowest(pairs[k], x[k]), bounds...[k])) for all k at
    once: where a pass's input is x[k] (the cruise of the backward pass, K = cap; the braking of the
    forward one, x = K) it needs no step of its own. The same bits: each a·x + b is the same two
    roundings, a minimum's value does not depend on the order but for the sign of a zero, and
    max(0, ·) makes any zero +0. None when a number is not finite (a NaN's place in min matters)."""
    if not (np.isfinite(pairs).all() and np.isfinite(x).all()):
        return None
    v = np.min(pairs[:, :, 0] * x[:, None] + pairs[:, :, 1], axis=1)
    for b in bounds:
        v = np.minimum(v, b)
    return np.where(v > 0.0, v, 0.0).tolist()


def _lowest_of(rows: list):
    """The function giving min(a·x + b) over a row's pairs: unrolled for six axes' rows."""
    return _lowest12 if len(rows) and len(rows[0]) == 24 else _lowest


def _lowest(row: list, x: float) -> float:
    """min over the pairs of a row [a0, b0, a1, b1, ...] of a·x + b, taken in the row's order."""
    return min([row[i] * x + row[i + 1] for i in range(0, len(row), 2)])


def _lowest12(row: list, x: float) -> float:
    """`_lowest` of a 12-pair row, unrolled (the same operations in the same order, so the same
    bits): the passes spent half their time in the comprehension."""
    a0, b0, a1, b1, a2, b2, a3, b3, a4, b4, a5, b5, a6, b6, a7, b7, a8, b8, a9, b9, a10, b10, a11, b11 = row
    return min(a0 * x + b0, a1 * x + b1, a2 * x + b2, a3 * x + b3, a4 * x + b4, a5 * x + b5, a6 * x + b6,
               a7 * x + b7, a8 * x + b8, a9 * x + b9, a10 * x + b10, a11 * x + b11)


def topp(grid: Grid, sd0: float = 0.0) -> TimedProfile:
    """The time-optimal profile along `grid` from path speed sd0 to rest (module docstring)."""
    n = len(grid)
    if n < 2 or grid.s[-1] - grid.s[0] <= 0.0:
        return TimedProfile(grid.s[:1].copy(), np.array([0.0]))
    coef = coefficients(grid)  # shared by both curves and both passes' steps
    cap_a = np.minimum(grid.xmax(), accel_xmax(grid, coef))
    cap = cap_a.tolist()
    back, fwd = steps(grid, coef)
    at_cap = _stepped(back, cap_a[1:], cap_a[:-1])
    rows = back.reshape(len(back), -1)
    K = reachable(grid, cap, rows.tolist() if at_cap is None else rows, at_cap=at_cap)
    x0 = sd0 * sd0
    if x0 > K[0]:
        if x0 <= K[0] * 1.02 + 1e-9:  # a hair outside (numerical noise of a new grid): clamp
            x0 = K[0]
        else:  # faster than the path allows from here (limits lowered under way): brake first
            s_b, sd_b, j = brake_into(grid, sd0, np.asarray(K))
            if j is not None and j < n - 1:
                rest = topp(grid.slice(j), sd_b[-1])
                return TimedProfile(np.concatenate([s_b[:-1], rest.s]), np.concatenate([sd_b[:-1], rest.sd]),
                                    rest.fallback)
            s_i, sd_i = integrate(grid, sd0)
            return TimedProfile(s_i, sd_i, fallback=True)
    K_a = np.array(K)
    at_K = _stepped(fwd, K_a[:-1], K_a[1:], cap_a[1:])
    rows = fwd.reshape(len(fwd), -1)
    x = np.array(forward(x0, cap, K, rows.tolist() if at_K is None else rows, at_K=at_K))
    x[-1] = 0.0
    sd = np.sqrt(x)
    # the arm must not stand still inside the path (two zero speeds in a row: a cusp, or a path
    # the limits cannot move along): then the safe profile
    still = (sd[:-1] + sd[1:] <= 1e-9 * max(float(sd.max()), 1.0)) & (np.diff(grid.s) > 0.0)
    if np.all(np.isfinite(sd)) and not np.any(still):
        s_r, sd_r = refine(grid, sd, back, fwd, cap_a)
        return TimedProfile(s_r, sd_r)
    s_i, sd_i = integrate(grid, sd0)
    return TimedProfile(s_i, sd_i, fallback=True)
