"""The time-optimal profile of any path, by toppra (TOPP-RA, seidel solver), with VAL 3's limits.

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

Guards around toppra: empty or zero-length paths never reach it; a start speed a hair outside
the controllable set is clamped into it; a start speed really above it (the monitor speed was
lowered) first brakes along the path (safe.brake_into); and when toppra returns nothing,
`safe.integrate()` gives a slower safe profile and the caller reports it (R019).
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass

import numpy as np

from .analytic import duration
from .grid import Grid
from .safe import brake_into, integrate

_toppra = None


def _load_toppra():
    """toppra's classes, subclassed for VAL 3's constraints (imported when first timed)."""
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
                """The constraint of the grid's accelerations and decelerations."""
                super().__init__()
                self.dof = grid.q1.shape[1]
                self.grid = grid
                self.discretization_type = toppra.constraint.DiscretizationType.Interpolation
                self.identical = False
                self._format_string = "    VAL 3 accel/decel\n"

            def compute_constraint_params(self, path, gridpoints, *args, **kwargs):
                """toppra's constraint parameters, per gridpoint (interpolation discretisation)."""
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
                """The constraint ṡ² ≤ xmax per gridpoint."""
                super().__init__()
                self.dof = dof
                self.xmax = xmax
                self._format_string = "    VAL 3 speeds\n"

            def compute_constraint_params(self, path, gridpoints, *args, **kwargs):
                """Only bounds on ṡ² (x)."""
                xb = np.zeros((len(self.xmax), 2))
                xb[:, 1] = self.xmax
                return None, None, None, None, None, None, xb

        class GridPath(toppra.interpolator.AbstractGeometricPath):
            """toppra wants a path object; every constraint here is precomputed on the grid."""

            def __init__(self, s: np.ndarray, dof: int):
                """A path of `dof` axes over the grid positions s."""
                self._s = s
                self._dof = dof

            def __call__(self, path_positions, order=0):
                """Unused values (the constraints are precomputed)."""
                return np.zeros((np.size(path_positions), self._dof))

            @property
            def dof(self):
                """The number of axes."""
                return self._dof

            @property
            def path_interval(self):
                """The grid's first and last positions."""
                return np.array([self._s[0], self._s[-1]])

        from toppra.algorithm.algorithm import ParameterizationAlgorithm
        from toppra.solverwrapper.cy_seidel_solverwrapper import seidelWrapper

        class TOPPRA(toppra.algorithm.TOPPRA):
            """toppra's TOPPRA with its seidel solver, without probing for optional solvers on every
            construction (the probe costs more than a short path's whole solution)."""

            def __init__(self, constraints, path, gridpoints):
                """TOPPRA over `gridpoints` with the seidel solver wrapper."""
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
        """The profile's time (s)."""
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
