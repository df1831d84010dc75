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
