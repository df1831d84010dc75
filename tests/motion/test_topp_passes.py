"""The time-optimal solver's shortcuts give the very bits of the plain formulation (issue 29: speed
never changes a result): the unrolled minimum of the passes, the bound coefficients and limit
curves computed once per profile and shared with refine."""

from __future__ import annotations

import math
import struct

import numpy as np
import pytest

from val3check.motion.timing import optimal
from val3check.motion.timing.grid import Grid
from val3check.motion.timing.optimal import _OFF, _lowest, _lowest12, forward, reachable, steps, topp
from val3check.motion.timing.refine import accel_xmax, coefficients, refine


def _grid(rng: np.random.Generator, n: int, axes: int, still: int = 0) -> Grid:
    """A path of n gridpoints with random derivatives and limits; `still` axes do not move."""
    s = np.cumsum(rng.uniform(0.05, 2.0, n)) - 0.05
    q1 = rng.uniform(-1.0, 1.0, (n, axes))
    q1[:, :still] = 0.0
    q2 = rng.uniform(-0.05, 0.05, (n, axes))
    lim = rng.uniform(50.0, 400.0, (3, axes))
    V, A, D = (np.repeat(row[None], n, axis=0) for row in lim)
    return Grid(s, q1, q2, rng.uniform(0.5, 5.0, n), rng.uniform(0.0, 1.0, n), V, A, D,
                np.full(n, 250.0), np.full(n, 90.0))


def _bits(values) -> list:
    return [struct.pack("<d", v) for v in values]


def _plain_reachable(cap: list, back: list) -> list:
    """The backward pass as first written: a comprehension over (slope, offset) pairs."""
    n = len(cap)
    K = [0.0] * n
    K[-1] = min(0.0, cap[-1])
    for k in range(n - 2, -1, -1):
        kn = K[k + 1]
        K[k] = max(0.0, min(cap[k], min([a * kn + b for a, b in back[k]])))
    return K


def _plain_forward(x0: float, cap: list, K: list, fwd: list) -> list:
    n = len(cap)
    x = [0.0] * n
    x[0] = x0
    for k in range(n - 1):
        xk = x[k]
        x[k + 1] = max(0.0, min(min([a * xk + b for a, b in fwd[k]]), K[k + 1], cap[k + 1]))
    return x


def test_the_unrolled_minimum_is_the_comprehensions_bit_for_bit():
    rng = np.random.default_rng(7)
    rows = rng.uniform(-3.0, 3.0, (500, 24)).tolist()
    rows.append([0.0, _OFF] * 12)  # no bound binds
    rows.append([1.0, 0.0, 1.0, -0.0] * 6)  # equal values of both signs: the first is kept
    rows.append([-0.0, -0.0, 0.0, 0.0] * 6)  # -0.0 then 0.0
    for row in rows:
        for x in (0.0, 0.5, 3.0, 1e12):
            a, b = _lowest12(row, x), _lowest(row, x)
            assert struct.pack("<d", a) == struct.pack("<d", b)
            assert a == min([p * x + q for p, q in zip(row[::2], row[1::2])])
    assert math.copysign(1.0, _lowest12([-0.0, -0.0, 0.0, 0.0] * 6, 0.0)) == -1.0


@pytest.mark.parametrize("axes,still", [(6, 0), (6, 2), (4, 0), (4, 1)])
def test_both_passes_equal_the_plain_passes(axes, still):
    rng = np.random.default_rng(axes * 10 + still)
    for _ in range(5):
        g = _grid(rng, 60, axes, still)
        cap = np.minimum(g.xmax(), accel_xmax(g)).tolist()
        back, fwd = steps(g)
        K = reachable(g, cap, back.reshape(len(back), -1).tolist())
        assert _bits(K) == _bits(_plain_reachable(cap, back.tolist()))
        for x0 in (0.0, 0.5 * K[0], K[0]):
            x = forward(x0, cap, K, fwd.reshape(len(fwd), -1).tolist())
            assert _bits(x) == _bits(_plain_forward(x0, cap, K, fwd.tolist()))


def test_shared_coefficients_give_the_same_curves_and_steps():
    rng = np.random.default_rng(3)
    g = _grid(rng, 40, 6, 1)
    coef = coefficients(g)
    assert accel_xmax(g, coef).tobytes() == accel_xmax(g).tobytes()
    for a, b in zip(steps(g, coef), steps(g)):
        assert a.tobytes() == b.tobytes()
    # the bounds as first written, without the shared coefficients
    up, lo = g.accel_bounds()
    moving = np.abs(g.q1) > 1e-12
    gq = np.where(moving, g.q1, 1.0)
    uc = np.where(moving, np.where(g.q1 > 0, up / gq, -lo / gq), np.inf)
    lc = np.where(moving, np.where(g.q1 > 0, -lo / gq, up / gq), -np.inf)
    us = np.where(moving, -g.q2 / gq, 0.0)
    for a, b in zip(optimal.bounds(g), (uc, us, lc, us)):
        assert a.tobytes() == b.tobytes()


@pytest.mark.parametrize("sd0", [0.0, 5.0])
def test_refine_with_the_callers_cap_is_refine_alone(sd0):
    rng = np.random.default_rng(11)
    g = _grid(rng, 50, 6)
    cap = np.minimum(g.xmax(), accel_xmax(g))
    res = topp(g, sd0)
    back, fwd = steps(g)
    sd = np.sqrt(np.maximum(np.interp(g.s, res.s, res.sd ** 2), 0.0))
    for a, b in zip(refine(g, sd, back, fwd, cap), refine(g, sd, back, fwd)):
        assert a.tobytes() == b.tobytes()


def _cruising(rng: np.random.Generator, n: int, axes: int, still: int = 0) -> Grid:
    """A path whose speed limits bind over most of it (low joint speeds): the backward pass sits
    on the cap while the arm cruises, the forward one on K while it brakes."""
    g = _grid(rng, n, axes, still)
    return Grid(g.s, g.q1, g.q2, g.pt, g.rt, g.V * 0.02, g.A, g.D, g.tv, g.rv)


@pytest.mark.parametrize("axes,still", [(6, 0), (6, 2), (4, 0), (4, 1)])
@pytest.mark.parametrize("make", [_grid, _cruising])
def test_the_steps_taken_on_the_bound_give_the_plain_passes(make, axes, still):
    """`_stepped`'s values, read where a pass's input sits on the cap (backward) or on K
    (forward), rows made lists only where a step is computed: the plain passes' bits."""
    rng = np.random.default_rng(axes * 7 + still)
    hits = 0
    for _ in range(5):
        g = make(rng, 80, axes, still)
        cap_a = np.minimum(g.xmax(), accel_xmax(g))
        cap = cap_a.tolist()
        back, fwd = steps(g)
        at_cap = optimal._stepped(back, cap_a[1:], cap_a[:-1])
        assert at_cap is not None
        K = reachable(g, cap, back.reshape(len(back), -1), at_cap=at_cap)
        assert _bits(K) == _bits(_plain_reachable(cap, back.tolist()))
        hits += sum(K[k + 1] == cap[k + 1] for k in range(len(K) - 1))
        K_a = np.array(K)
        at_K = optimal._stepped(fwd, K_a[:-1], K_a[1:], cap_a[1:])
        for x0 in (0.0, 0.5 * K[0], K[0]):
            x = forward(x0, cap, K, fwd.reshape(len(fwd), -1), at_K=at_K)
            assert _bits(x) == _bits(_plain_forward(x0, cap, K, fwd.tolist()))
            hits += sum(x[k] == K[k] for k in range(len(K) - 1))
    assert hits > 0 if make is _grid else hits > 5 * 80  # the shortcut is taken


def test_a_step_on_the_bound_keeps_the_sign_rule_of_zero_and_refuses_what_is_not_finite():
    pairs = np.array([[[1.0, -0.0], [1.0, 0.0]], [[-1.0, 0.0], [2.0, -3.0]]])  # two intervals, two pairs
    x = np.array([0.0, 1.0])
    got = optimal._stepped(pairs, x, np.array([5.0, 5.0]))
    want = [max(0.0, min(_lowest(row, v), 5.0)) for row, v in zip(pairs.reshape(2, -1).tolist(), x.tolist())]
    assert _bits(got) == _bits(want) and math.copysign(1.0, got[0]) == 1.0
    assert optimal._stepped(pairs, np.array([math.nan, 1.0])) is None
    bad = pairs.copy()
    bad[1, 0, 1] = math.inf
    assert optimal._stepped(bad, x) is None


def test_topp_on_the_bound_is_topp_with_the_plain_passes(monkeypatch):
    """The whole solver with the shortcut against the solver whose passes get no shortcut."""
    rng = np.random.default_rng(5)
    grids = [_cruising(rng, 70, 6, k % 3) for k in range(4)] + [_grid(rng, 70, 6, 1) for _ in range(2)]
    fast = [topp(g, sd0) for g in grids for sd0 in (0.0, 3.0)]
    monkeypatch.setattr(optimal, "_stepped", lambda *a: None)
    plain = [topp(g, sd0) for g in grids for sd0 in (0.0, 3.0)]
    for a, b in zip(fast, plain):
        assert a.s.tobytes() == b.s.tobytes() and a.sd.tobytes() == b.sd.tobytes() and a.fallback == b.fallback
