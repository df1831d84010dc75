"""Numerical integration along a grid: braking (stopMove, resetMotion, power off, a start faster
than the path allows) and the safe profile used when no optimal profile is found (R019: its times are an upper
bound)."""

from __future__ import annotations

import math

import numpy as np

from .analytic import trapezoid
from .grid import XMAX, Grid

EPS_U = 1e-9


def brake_into(grid: Grid, sd0: float, xcap: np.ndarray) -> tuple[np.ndarray, np.ndarray, int | None]:
    """Brake along the grid from speed sd0 with the greatest deceleration until ṡ² is within
    xcap (the controllable set). Returns the (s, ṡ) breakpoints and the gridpoint reached
    (None when the path ends first)."""
    s_out, sd_out = [grid.s[0]], [sd0]
    x = sd0 * sd0
    for i in range(len(grid) - 1):
        if x <= xcap[i] * (1.0 + 1e-9):
            return np.array(s_out), np.array(sd_out), i
        umin, _ = grid.u_range(i, x)
        if not math.isfinite(umin) or umin > -EPS_U:
            umin = -max(float(np.min(grid.D[i])), 1e-9) / max(float(np.max(np.abs(grid.q1[i]))), 1e-12)
        ds = grid.s[i + 1] - grid.s[i]
        x = max(x + 2.0 * ds * umin, 0.0)
        s_out.append(grid.s[i + 1])
        sd_out.append(math.sqrt(x))
    return np.array(s_out), np.array(sd_out), None


def brake_stop(grid: Grid, sd0: float) -> tuple[np.ndarray, np.ndarray]:
    """Stop on the path as soon as the decelerations allow (stopMove, resetMotion, power off):
    (s, ṡ) breakpoints ending at rest. When the grid ends first the last speed is forced to 0."""
    s_out, sd_out = [grid.s[0]], [sd0]
    x = sd0 * sd0
    for i in range(len(grid) - 1):
        if x <= 0.0:
            break
        umin, _ = grid.u_range(i, x)
        if not math.isfinite(umin) or umin > -EPS_U:
            umin = -max(float(np.min(grid.D[i])), 1e-9) / max(float(np.max(np.abs(grid.q1[i]))), 1e-12)
        ds = grid.s[i + 1] - grid.s[i]
        xn = x + 2.0 * ds * umin
        if xn <= 0.0:  # stops inside this interval
            s_out.append(grid.s[i] + x / (-2.0 * umin))
            sd_out.append(0.0)
            return np.array(s_out), np.array(sd_out)
        x = xn
        s_out.append(grid.s[i + 1])
        sd_out.append(math.sqrt(x))
    sd_out[-1] = 0.0
    return np.array(s_out), np.array(sd_out)


def u_bounds(grid: Grid, x) -> tuple[np.ndarray, np.ndarray]:
    """[u_min, u_max] of the path acceleration at every gridpoint for speed² x (scalar or (N,));
    u_max < u_min where x is too fast for the accelerations (the centripetal term)."""
    up, lo = grid.accel_bounds()
    x = np.broadcast_to(np.asarray(x, dtype=float), grid.s.shape)[:, None]
    a = grid.q1
    c = grid.q2 * x
    moving = np.abs(a) > 1e-12
    with np.errstate(divide="ignore", invalid="ignore"):
        hi = np.where(a > 0, (up - c) / a, (-lo - c) / a)
        low = np.where(a > 0, (-lo - c) / a, (up - c) / a)
    hi = np.where(moving, hi, np.inf)
    low = np.where(moving, low, -np.inf)
    # an axis that does not move along the path bounds the speed only: q''·x within its limits
    still_ok = np.where(moving, True, (c <= up) & (-c <= lo))
    umax = np.where(still_ok.all(axis=1), hi.min(axis=1), -np.inf)
    umin = low.max(axis=1)
    return umin, umax


def integrate(grid: Grid, sd0: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """A safe profile when no optimal one is found: a trapezoid in the path parameter whose speed,
    acceleration and deceleration hold at every gridpoint. The bounds on the path acceleration are
    concave (u_max) and convex (u_min) in ṡ², so checking them at ṡ² = 0 and at the cruise speed
    covers every speed in between; the cruise speed is halved until they hold. Slower than the
    optimum (the caller reports it, R019), never faster than the limits."""
    S = float(grid.s[-1] - grid.s[0])
    if S <= 0.0:
        return grid.s[:1].copy(), np.array([0.0])
    x = float(np.min(grid.xmax()))
    x = min(x, XMAX)
    A = D = 0.0
    for _ in range(80):
        lo0, hi0 = u_bounds(grid, 0.0)
        lo1, hi1 = u_bounds(grid, x)
        A = float(min(hi0.min(), hi1.min()))
        D = float(-max(lo0.max(), lo1.max()))
        if A > 0.0 and D > 0.0 and np.isfinite(A) and np.isfinite(D):
            break
        x *= 0.25
    else:  # nothing moves this path within the limits: creep (the caller reports the fallback)
        A = D = 1e-6
        x = 1e-12
    s, sd = trapezoid(S, sd0, math.sqrt(x), A, D)
    return s + grid.s[0], sd

