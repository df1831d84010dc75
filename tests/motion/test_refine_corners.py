"""refine places every interval's corners among the gridpoints in one pass (a sort by interval,
then along it): the same breakpoints, bit for bit, as the loop over the intervals with corners it
replaced, on random grids, grids whose speed limits bind, and the grids of a real run."""

from __future__ import annotations

import numpy as np
import pytest

from val3check.motion.timing import optimal
from val3check.motion.timing import refine as refine_module
from val3check.motion.timing.grid import Grid
from val3check.motion.timing.optimal import steps, topp
from val3check.motion.timing.refine import REL_TOL, _corners, _finite, accel_xmax, refine

from .test_topp_passes import _cruising, _grid


def _loop_refine(grid: Grid, sd, back, fwd, cap=None):
    """The interval loop refine had before (the reference)."""
    s = grid.s
    x = sd * sd
    n = len(s)
    if n < 2:
        return s.copy(), sd.copy()
    h = np.diff(s)
    cap = np.maximum(np.minimum(grid.xmax(), accel_xmax(grid)) if cap is None else cap, x)
    u_lin = (x[1:] - x[:-1]) / (2.0 * h)
    with np.errstate(over="ignore", invalid="ignore"):
        up = np.min(fwd[:, :, 0] * x[:-1, None] + fwd[:, :, 1], axis=1)
        down = np.min(back[:, :, 0] * x[1:, None] + back[:, :, 1], axis=1)
    a = _finite(np.maximum((up - x[:-1]) / (2.0 * h), u_lin))
    d = _finite(np.maximum((down - x[1:]) / (2.0 * h), -u_lin))
    tau, env = _corners(x, cap, h, a, d)
    lin = x[:-1, None] + 2.0 * u_lin[:, None] * tau
    above = np.isfinite(env) & (env > lin + REL_TOL * np.maximum(1.0, np.maximum(x[:-1], x[1:]))[:, None])
    rows = np.flatnonzero(above.any(axis=1))
    if len(rows) == 0:
        return s.copy(), sd.copy()
    out_s, out_x = [s[: rows[0] + 1]], [x[: rows[0] + 1]]
    for j, k in enumerate(rows):
        m = above[k]
        order = np.argsort(tau[k][m])
        out_s.append(s[k] + tau[k][m][order])
        out_x.append(env[k][m][order])
        end = rows[j + 1] + 1 if j + 1 < len(rows) else n
        out_s.append(s[k + 1:end])
        out_x.append(x[k + 1:end])
    return np.concatenate(out_s), np.sqrt(np.maximum(np.concatenate(out_x), 0.0))


def _same(a, b) -> bool:
    return all(x.dtype == y.dtype and x.tobytes() == y.tobytes() for x, y in zip(a, b))


@pytest.mark.parametrize("make", [_grid, _cruising])
@pytest.mark.parametrize("axes,still", [(6, 0), (6, 2), (4, 1)])
@pytest.mark.parametrize("sd0", [0.0, 3.0])
def test_the_corners_placed_together_are_the_loop_s(make, axes, still, sd0):
    rng = np.random.default_rng(axes * 10 + still)
    corners = 0
    for n in (2, 3, 9, 40, 120):
        g = make(rng, n, axes, still)
        back, fwd = steps(g)
        res = topp(g, sd0)
        for sd in (np.sqrt(np.maximum(np.interp(g.s, res.s, res.sd ** 2), 0.0)), rng.uniform(0.0, 3.0, n)):
            got, want = refine(g, sd, back, fwd), _loop_refine(g, sd, back, fwd)
            assert _same(got, want)
            corners += len(got[0]) - n
    assert corners > 20  # (the loop's case is exercised)


def test_no_corner_and_a_single_gridpoint():
    rng = np.random.default_rng(2)
    g = _grid(rng, 12, 6)
    back, fwd = steps(g)
    flat = np.zeros(12)
    assert _same(refine(g, flat, back, fwd), _loop_refine(g, flat, back, fwd))
    one = g.slice(0, 1)
    assert _same(refine(one, np.array([1.0]), back[:0], fwd[:0]), (one.s.copy(), np.array([1.0])))


def test_a_real_run_s_grids_give_the_loop_s_breakpoints(monkeypatch):
    """Every grid the solver refines in twenty seconds of the bundled pick-and-place."""
    from .pick_place_run import pick_place_machine

    seen = []
    keep = refine_module.refine

    def both(grid, sd, back, fwd, cap=None):
        got = keep(grid, sd, back, fwd, cap)
        seen.append(_same(got, _loop_refine(grid, sd, back, fwd, cap)))
        return got

    monkeypatch.setattr(optimal, "refine", both)
    pick_place_machine(20)
    assert len(seen) > 30 and all(seen)
