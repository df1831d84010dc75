"""Time parameterisation of a geometric path: as fast as the limits of 10.3.1 allow.

A path is given on a grid of its parameter s (`Grid`): at each gridpoint the joint derivatives
q'(s), q''(s), the rates of the tool centre point |dp/ds| (mm) and |dθ/ds| (deg), and the limits
of the command the gridpoint belongs to (`mdesc.Limits`). The result is the path speed ṡ at
each gridpoint, with a constant path acceleration between gridpoints (the exact shape of a
bang-bang profile on a straight joint line, toppra's on the rest).

* Straight joint lines with constant limits: `trapezoid()`, the exact time-optimal profile
  (trapezoid or triangle), with accel ≠ decel and a non-zero initial speed (replanning).
* Everything else: toppra (TOPP-RA, seidel solver) with the constraints below.

VAL 3 limits joint acceleration with `accel` while the path speed increases and with `decel`
while it decreases; toppra's constraint is a polygon in (u = s̈, x = ṡ²) per gridpoint. For
joint k, q̈ₖ = q'ₖ·u + q''ₖ·x. The inequality that bounds u from above (the greatest path
acceleration) is q̈ₖ ≤ A if q'ₖ > 0, q̈ₖ ≥ -A if q'ₖ < 0; the one that bounds u from below (the
greatest deceleration) uses D. So per gridpoint and axis the bounds are [-D, A] when q'ₖ ≥ 0 and
[-A, D] otherwise: the forward pass (which takes the largest u) then accelerates with accel and
the backward pass (the smallest u) brakes with decel — exactly the two limits VAL 3 states, in
the two phases of a bang-bang profile. (A polygon cannot hold "A when u > 0, D when u < 0" in
general; where the path speed is held on the velocity limit curve the looser of the two applies
to the centripetal term. docs/motion.md.)

Guards around toppra: empty or zero-length paths never reach it; a path shorter than a few
gridpoints gets at least 3; a start speed a hair outside the controllable set is clamped into
it; a start speed really above it (the monitor speed was lowered) first brakes along the path;
and when toppra returns nothing, `integrate()` (the classical forward/backward numerical
integration) gives a slower safe profile and the caller reports it (R019).
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass

import numpy as np

XMAX = 1e12  # "no bound" on ṡ² (path units are degrees of joint motion: ṡ stays far below 1e6)
EPS_U = 1e-9


@dataclass
class Grid:
    """A path sampled for the time parameterisation (N gridpoints). V, A, D: (N, 6) limits;
    tv, rv: (N,) Cartesian limits; pt, rt: (N,) |dp/ds| (mm) and |dθ/ds| (deg)."""

    s: np.ndarray
    q1: np.ndarray
    q2: np.ndarray
    pt: np.ndarray
    rt: np.ndarray
    V: np.ndarray
    A: np.ndarray
    D: np.ndarray
    tv: np.ndarray
    rv: np.ndarray

    def __len__(self) -> int:
        return len(self.s)

    def slice(self, i0: int, i1: int | None = None) -> "Grid":
        sl = slice(i0, i1)
        return Grid(self.s[sl], self.q1[sl], self.q2[sl], self.pt[sl], self.rt[sl], self.V[sl], self.A[sl],
                    self.D[sl], self.tv[sl], self.rv[sl])

    def xmax(self) -> np.ndarray:
        """The velocity limit curve from the speed limits: joints, TCP, tool rotation (ṡ²)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            aq = np.abs(self.q1)
            joint = np.where(aq > 1e-12, self.V / aq, np.inf).min(axis=1)
            tcp = np.where(self.pt > 1e-12, self.tv / self.pt, np.inf)
            rot = np.where(self.rt > 1e-12, self.rv / self.rt, np.inf)
            sd = np.minimum(np.minimum(joint, tcp), rot)
        return np.minimum(sd * sd, XMAX)

    def accel_bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """(upper, lower) magnitude of q̈ per gridpoint and axis: q̈ ∈ [-lower, upper] (module doc)."""
        pos = self.q1 >= 0.0
        up = np.where(pos, self.A, self.D)
        lo = np.where(pos, self.D, self.A)
        flat = np.abs(self.q1) < 1e-12
        both = np.minimum(self.A, self.D)
        return np.where(flat, both, up), np.where(flat, both, lo)

    def u_range(self, i: int, x: float) -> tuple[float, float]:
        """[u_min, u_max] of the path acceleration at gridpoint i and speed² x (decel and accel
        limits as in the module docstring)."""
        up, lo = self.accel_bounds_at(i)
        q1 = self.q1[i]
        q2 = self.q2[i]
        umin, umax = -math.inf, math.inf
        for k in range(q1.shape[0]):
            a = q1[k]
            c = q2[k] * x
            if abs(a) < 1e-12:
                continue
            hi = (up[k] - c) / a
            low = (-lo[k] - c) / a
            if a < 0:
                hi, low = low, hi
            umax = min(umax, hi)
            umin = max(umin, low)
        return umin, umax

    def accel_bounds_at(self, i: int):
        pos = self.q1[i] >= 0.0
        return np.where(pos, self.A[i], self.D[i]), np.where(pos, self.D[i], self.A[i])


# ---- the exact profile of a straight joint line -------------------------------------------------


def trapezoid(S: float, v0: float, V: float, A: float, D: float) -> tuple[np.ndarray, np.ndarray]:
    """Breakpoints (s, ṡ) of the time-optimal motion over [0, S] from path speed v0 to rest, with
    |ṡ| ≤ V, s̈ ≤ A and s̈ ≥ -D (constant acceleration between breakpoints).

    From rest: the trapezoid when S ≥ V²/2A + V²/2D (time S/V + V/2A + V/2D), else the triangle
    with peak √(2SAD/(A+D)). From v0 > 0 the same with the ramp starting at v0; when v0 > V the
    motion first brakes to V; when v0 is too fast to stop within S (the limits were lowered under
    way), it brakes with the deceleration that stops it exactly at S."""
    if S <= 0.0:
        return np.array([0.0]), np.array([0.0])
    v0 = max(v0, 0.0)
    if v0 * v0 / (2.0 * D) >= S:  # cannot stop in time at D: the deceleration needed
        return np.array([0.0, S]), np.array([v0, 0.0])
    if v0 > V:
        s1 = (v0 * v0 - V * V) / (2.0 * D)
        s2 = S - V * V / (2.0 * D)
        pts = [(0.0, v0), (s1, V)]
        if s2 > s1:
            pts.append((s2, V))
        pts.append((S, 0.0))
    else:
        vp2 = (2.0 * S * A * D + v0 * v0 * D) / (A + D)
        if vp2 <= V * V:
            vp = math.sqrt(vp2)
            s1 = (vp2 - v0 * v0) / (2.0 * A)
            pts = [(0.0, v0), (s1, vp), (S, 0.0)]
        else:
            s1 = (V * V - v0 * v0) / (2.0 * A)
            s2 = S - V * V / (2.0 * D)
            pts = [(0.0, v0), (s1, V), (s2, V), (S, 0.0)]
    s = np.array([p[0] for p in pts])
    sd = np.array([p[1] for p in pts])
    keep = np.concatenate([[True], np.diff(s) > 1e-15])  # drop zero-length ramps
    keep[-1] = True
    return s[keep], sd[keep]


def duration(s: np.ndarray, sd: np.ndarray) -> float:
    """Time of a profile given by breakpoints with constant acceleration in between."""
    ds = np.diff(s)
    v = sd[:-1] + sd[1:]
    with np.errstate(divide="ignore", invalid="ignore"):
        dt = np.where(ds > 0, 2.0 * ds / v, 0.0)
    return float(dt.sum())


# ---- toppra ---------------------------------------------------------------------------------------

_toppra = None


def _load_toppra():
    global _toppra
    if _toppra is None:
        import toppra
        import toppra.algorithm
        import toppra.constraint
        from toppra.constraint.linear_constraint import LinearConstraint, canlinear_colloc_to_interpolate

        logging.getLogger("toppra").setLevel(logging.ERROR)

        class AccelConstraint(LinearConstraint):
            """q̈ₖ = q'ₖ u + q''ₖ x within per-gridpoint bounds (module docstring)."""

            def __init__(self, grid: Grid):
                super().__init__()
                self.dof = grid.q1.shape[1]
                self.grid = grid
                self.discretization_type = toppra.constraint.DiscretizationType.Interpolation
                self.identical = False
                self._format_string = "    VAL 3 accel/decel\n"

            def compute_constraint_params(self, path, gridpoints, *args, **kwargs):
                g = self.grid
                n, d = g.q1.shape
                up, lo = g.accel_bounds()
                F = np.zeros((n, 2 * d, d))
                eye = np.eye(d)
                F[:, :d, :] = eye
                F[:, d:, :] = -eye
                # interpolation scheme: each interval's constant u obeys the limits at both ends
                return canlinear_colloc_to_interpolate(g.q1, g.q2, np.zeros_like(g.q1), F, np.hstack([up, lo]),
                                                       None, None, gridpoints, identical=False)

        class SpeedConstraint(LinearConstraint):
            """ṡ² below the velocity limit curve (joint speeds, tvel, rvel)."""

            def __init__(self, xmax: np.ndarray, dof: int):
                super().__init__()
                self.dof = dof
                self.xmax = xmax
                self._format_string = "    VAL 3 speeds\n"

            def compute_constraint_params(self, path, gridpoints, *args, **kwargs):
                xb = np.zeros((len(self.xmax), 2))
                xb[:, 1] = self.xmax
                return None, None, None, None, None, None, xb

        class GridPath(toppra.interpolator.AbstractGeometricPath):
            """toppra wants a path object; every constraint here is precomputed on the grid."""

            def __init__(self, s: np.ndarray, dof: int):
                self._s = s
                self._dof = dof

            def __call__(self, path_positions, order=0):
                return np.zeros((np.size(path_positions), self._dof))

            @property
            def dof(self):
                return self._dof

            @property
            def path_interval(self):
                return np.array([self._s[0], self._s[-1]])

        from toppra.algorithm.algorithm import ParameterizationAlgorithm
        from toppra.solverwrapper.cy_seidel_solverwrapper import seidelWrapper

        class TOPPRA(toppra.algorithm.TOPPRA):
            """toppra's TOPPRA with its seidel solver, without probing for optional solvers on every
            construction (the probe costs more than a short path's whole solution)."""

            def __init__(self, constraints, path, gridpoints):
                ParameterizationAlgorithm.__init__(self, constraints, path, gridpoints=gridpoints)
                self.solver_wrapper = seidelWrapper(self.constraints, self.path, self.gridpoints, solve_lp1d=True)

        _toppra = (TOPPRA, AccelConstraint, SpeedConstraint, GridPath)
    return _toppra


@dataclass
class TimedProfile:
    """ṡ at the gridpoints of a Grid (constant path acceleration in between); `fallback` when
    toppra failed and the safe numerical integration was used."""

    s: np.ndarray
    sd: np.ndarray
    fallback: bool = False

    @property
    def duration(self) -> float:
        return duration(self.s, self.sd)


def topp(grid: Grid, sd0: float = 0.0) -> TimedProfile:
    """The time-optimal profile along `grid` from path speed sd0 to rest (module docstring)."""
    n = len(grid)
    if n < 2 or grid.s[-1] - grid.s[0] <= 0.0:
        return TimedProfile(grid.s[:1].copy(), np.array([0.0]))
    xmax = grid.xmax()
    dof = grid.q1.shape[1]
    gp = grid.s
    try:
        TOPPRA, AccelConstraint, SpeedConstraint, GridPath = _load_toppra()
        inst = TOPPRA([SpeedConstraint(xmax, dof), AccelConstraint(grid)], GridPath(gp, dof), gp)
        sdd, sd, _v, K = inst.compute_parameterization(0.0, 0.0, return_data=True) if sd0 <= 0 else \
            _with_start(inst, sd0)
    except ImportError:
        raise
    except Exception:  # toppra raised (bad conditioning): the safe profile below
        sd, K = None, None
    if sd is not None and np.all(np.isfinite(sd)):
        sd = np.maximum(sd, 0.0)
        sd[-1] = 0.0
        # the arm must not stand still inside the path (two zero speeds in a row: a cusp or a
        # grid too coarse for toppra's discretisation): then the safe profile
        still = (sd[:-1] + sd[1:] <= 1e-9 * max(float(sd.max()), 1.0)) & (np.diff(gp) > 0.0)
        if not np.any(still):
            return TimedProfile(gp.copy(), sd)
        sd, K = None, None
    if K is not None and sd0 > 0 and np.all(np.isfinite(K)) and sd0 * sd0 > K[0, 1]:
        # the start is faster than the path allows from here (limits lowered under way): brake
        # along the path into the controllable set, then the optimal profile from there
        s_b, sd_b, j = brake_into(grid, sd0, K[:, 1])
        if j is not None and j < n - 1:
            rest = topp(grid.slice(j), sd_b[-1])
            return TimedProfile(np.concatenate([s_b[:-1], rest.s]), np.concatenate([sd_b[:-1], rest.sd]),
                                rest.fallback)
    s_i, sd_i = integrate(grid, sd0)
    return TimedProfile(s_i, sd_i, fallback=True)


def _with_start(inst, sd0: float):
    """compute_parameterization from speed sd0, clamping a start a hair outside the controllable
    set (numerical noise of a new grid) into it."""
    sdd, sd, v, K = inst.compute_parameterization(sd0, 0.0, return_data=True)
    if sd is None and K is not None and np.all(np.isfinite(K)):
        x0 = sd0 * sd0
        if x0 > K[0, 1] and x0 <= K[0, 1] * 1.02 + 1e-9:
            sdd, sd, v, K = inst.compute_parameterization(math.sqrt(max(K[0, 1], 0.0)) * 0.999999, 0.0,
                                                          return_data=True)
    return sdd, sd, v, K


# ---- numerical integration (braking, and the safe fallback) -------------------------------------


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
    """A safe profile when toppra fails: a trapezoid in the path parameter whose speed,
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
