"""The exact profile inside each interval of the grid (issue 23: ramps not set by the grid).

optimal.py gives the optimal path speed at the gridpoints, with a constant path
acceleration between neighbours. Where the optimum changes regime between two gridpoints — a
ramp that reaches the speed limit, a peak where acceleration turns into braking, the end of a
cruise — a constant acceleration over the whole interval is slower than the arm: the first and
last intervals of a slow `movel` then set its ramps (0.16 s on a 200 mm line at 100 mm/s, for a
few milliseconds of real ramp). Inside an interval [s0, s1] of length h, with ṡ² = x,

    accelerating as hard as allowed from x0:   x = x0 + 2·a·τ
    braking as hard as allowed to x1:          x = x1 + 2·d·(h - τ)
    the speed limit (linear between the ends): x = c0 + (c1 - c0)·τ / h

and the fastest motion from x0 to x1 is the lowest of the three lines at every τ (10.3.1: "à
chaque instant, le robot se déplace et accélère au maximum de ses capacités"): a bang-bang
inside the interval. `a` and `d` are the path acceleration and deceleration of the solver's own
steps from x0 and to x1 (optimal.py: the bounds at both ends of the interval); `c` is the velocity limit curve (joint speeds,
tvel, rvel) and the acceleration limit curve (the speed above which no path acceleration obeys
every axis). The lowest line is piecewise linear in x: its corners become breakpoints of the
profile, with a constant path acceleration between them — the form trajectory.Profile holds.
Exact when the bounds are constant over the interval (a straight line at a constant tvel: the
trapezoid), within the grid's variation of the bounds otherwise (docs/motion.md, "Timing").
"""

from __future__ import annotations

import numpy as np

from .grid import XMAX, Grid

UMAX = 1e15  # "no bound" on s̈ (path units of degrees: far above any arm's)
REL_TOL = 1e-9  # a corner higher than the interval's straight line by less than this is dropped


def coefficients(grid: Grid) -> tuple[np.ndarray, ...]:
    """Per gridpoint and axis, s̈ ≤ uc + us·x and s̈ ≥ lc + us·x (the accel/decel bounds of
    q̈ₖ = q'ₖ·s̈ + q''ₖ·ṡ²), with `moving` (q'ₖ ≠ 0), `up` and `lo` (Grid.accel_bounds): uc and lc
    are ±inf where the axis does not move. optimal.bounds and accel_xmax both start from them."""
    up, lo = grid.accel_bounds()
    q1, q2 = grid.q1, grid.q2
    moving = np.abs(q1) > 1e-12
    g = np.where(moving, q1, 1.0)
    uc = np.where(moving, np.where(q1 > 0, up / g, -lo / g), np.inf)
    lc = np.where(moving, np.where(q1 > 0, -lo / g, up / g), -np.inf)
    us = np.where(moving, -q2 / g, 0.0)
    return uc, us, lc, moving, up, lo


def accel_xmax(grid: Grid, coef: tuple | None = None) -> np.ndarray:
    """The acceleration limit curve: per gridpoint, the largest ṡ² at which some path acceleration
    obeys every axis's accel/decel bounds (q̈ₖ = q'ₖ·s̈ + q''ₖ·ṡ²), XMAX where none binds. `coef`:
    `coefficients(grid)` when the caller has them."""
    uc, us, lc, moving, up, lo = coefficients(grid) if coef is None else coef
    q2 = grid.q2
    with np.errstate(divide="ignore", invalid="ignore"):
        coef_ = us[:, :, None] - us[:, None, :]  # lower of axis k against upper of axis j
        rhs = uc[:, None, :] - lc[:, :, None]
        pair = np.where((coef_ > 1e-15) & np.isfinite(rhs), rhs / coef_, np.inf).reshape(len(grid), -1).min(axis=1)
        # an axis that does not move along the path bounds the speed: |q''·x| within its limits
        still = np.where(~moving & (q2 > 1e-12), up / np.where(q2 > 1e-12, q2, 1.0),
                         np.where(~moving & (q2 < -1e-12), lo / np.where(q2 < -1e-12, -q2, 1.0), np.inf)).min(axis=1)
    return np.minimum(np.minimum(pair, still), XMAX)


def refine(grid: Grid, sd: np.ndarray, back: np.ndarray, fwd: np.ndarray,
           cap: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The breakpoints (s, ṡ) of the fastest motion through the gridpoints' speeds `sd` (module
    docstring): the gridpoints, and the corners of the bang-bang inside each interval. `back`,
    `fwd`: the solver's braking and accelerating steps (optimal.steps): the lines inside an
    interval are the solver's own, so that a re-timing from a point of a line finds the same line
    (planner.py). `cap`: the velocity and acceleration limit curves' minimum, when the caller has it."""
    s = grid.s
    x = sd * sd
    n = len(s)
    if n < 2:
        return s.copy(), sd.copy()
    h = np.diff(s)
    cap = np.maximum(np.minimum(grid.xmax(), accel_xmax(grid)) if cap is None else cap, x)
    u_lin = (x[1:] - x[:-1]) / (2.0 * h)
    with np.errstate(over="ignore", invalid="ignore"):
        up = np.min(fwd[:, :, 0] * x[:-1, None] + fwd[:, :, 1], axis=1)  # ṡ² at the end accelerating
        down = np.min(back[:, :, 0] * x[1:, None] + back[:, :, 1], axis=1)  # ṡ² at the start braking
    a = _finite(np.maximum((up - x[:-1]) / (2.0 * h), u_lin))
    d = _finite(np.maximum((down - x[1:]) / (2.0 * h), -u_lin))
    tau, env = _corners(x, cap, h, a, d)
    lin = x[:-1, None] + 2.0 * u_lin[:, None] * tau
    above = np.isfinite(env) & (env > lin + REL_TOL * np.maximum(1.0, np.maximum(x[:-1], x[1:]))[:, None])
    k, c = np.nonzero(above)  # the corners: interval k, in order
    if len(k) == 0:
        return s.copy(), sd.copy()
    t = tau[k, c]
    order = np.lexsort((t, k))  # by interval, then along it (equal τ: the same corner twice, either order)
    k, t, e = k[order], t[order], env[k, c][order]
    # each interval's corners between its two gridpoints: gridpoint i after the corners of the
    # intervals before it, corner j after the gridpoints up to its interval's start and the corners before it
    m = len(k)
    s_out, x_out = np.empty(n + m), np.empty(n + m)
    at = np.arange(n) + np.searchsorted(k, np.arange(n), side="left")
    s_out[at], x_out[at] = s, x
    at = k + 1 + np.arange(m)
    s_out[at], x_out[at] = s[k] + t, e
    return s_out, np.sqrt(np.maximum(x_out, 0.0))


def _finite(u: np.ndarray) -> np.ndarray:
    """A path acceleration bound, "none" (inf) as a finite number far above any used."""
    return np.minimum(u, UMAX)


def _corners(x, cap, h, a, d) -> tuple[np.ndarray, np.ndarray]:
    """Per interval, the three pairwise crossings of the accelerating, braking and speed-limit
    lines strictly inside it (τ, NaN where none) and the lowest line's value there."""
    x0, x1 = x[:-1], x[1:]
    c0, c1 = cap[:-1], cap[1:]
    m = (c1 - c0) / h
    with np.errstate(divide="ignore", invalid="ignore"):
        t_ab = np.where(a + d > 0, (x1 - x0 + 2.0 * d * h) / (2.0 * (a + d)), np.nan)
        t_ac = np.where(2.0 * a - m > 0, (c0 - x0) / (2.0 * a - m), np.nan)
        t_bc = np.where(2.0 * d + m > 0, (x1 + 2.0 * d * h - c0) / (2.0 * d + m), np.nan)
    tau = np.empty((len(h), 3))
    tau[:, 0], tau[:, 1], tau[:, 2] = t_ab, t_ac, t_bc
    inside = (tau > 1e-12 * h[:, None]) & (tau < h[:, None] * (1.0 - 1e-12))
    tau = np.where(inside, tau, np.nan)
    env = np.minimum(np.minimum(x0[:, None] + 2.0 * a[:, None] * tau, x1[:, None] + 2.0 * d[:, None] * (h[:, None] - tau)),
                     c0[:, None] + m[:, None] * tau)
    return tau, env
