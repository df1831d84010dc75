"""Path.q and Path.q01 evaluate each geometry once per call for all its rows (λ found for every row
at once, both orders from one search of a geometry's pieces): the same bits as evaluating each row
alone on its own span (Span.q), on a real run's path and on each kind of geometry."""

from __future__ import annotations

import numpy as np
import pytest

from val3check.motion.paths import BlendShape, JointBlend, JointLine, JointSpline, Path, Span

from .pick_place_run import pick_place_machine


@pytest.fixture(scope="module")
def path():
    """Twenty seconds of the bundled pick-and-place: joint lines, splines and blends."""
    return pick_place_machine(20).arm.queue_in_use.trajectory.path


def _bits(x) -> bytes:
    return np.ascontiguousarray(x, dtype=float).tobytes()


def _alone(path: Path, s: np.ndarray, order: int) -> np.ndarray:
    """Each row on its own span: the plain formulation."""
    rows = []
    for x in s.tolist():
        i, _ = path.locate(x)
        sp = path.spans[i]
        rows.append(sp.q(np.clip(np.array([x - path.offsets[i]]), 0.0, sp.length), order)[0])
    return np.array(rows)


def _positions(path: Path, rng) -> np.ndarray:
    """Random positions, every junction and its neighbours, both ends and beyond them."""
    offs = np.array(path.offsets)
    s = np.concatenate([rng.uniform(0.0, path.end, 3000), offs, np.nextafter(offs, -np.inf), np.nextafter(offs, np.inf),
                        [0.0, path.end, -1.0, path.end + 5.0]])
    return s


def test_the_run_s_path_gives_the_bits_of_each_row_alone(path):
    kinds = {type(sp.geom).__name__ for sp in path.spans}
    assert {"JointLine", "JointSpline", "JointBlend"} <= kinds
    rng = np.random.default_rng(7)
    s = _positions(path, rng)
    rng.shuffle(s)
    for order in (0, 1, 2):
        assert _bits(path.q(s, order)) == _bits(_alone(path, s, order))
    q, q1 = path.q01(s)
    assert _bits(q) == _bits(path.q(s)) and _bits(q1) == _bits(path.q(s, 1))


def test_within_one_span_and_on_an_empty_path(path):
    sp = path.spans[len(path.spans) // 2]
    s = path.offsets[len(path.spans) // 2] + np.linspace(0.0, sp.length, 37)
    for order in (0, 1):
        assert _bits(path.q(s, order)) == _bits(_alone(path, s, order))
    q, q1 = path.q01(s)
    assert _bits(q) == _bits(path.q(s)) and _bits(q1) == _bits(path.q(s, 1))
    empty = Path(np.arange(6.0))
    q, q1 = empty.q01([1.0, 2.0])
    assert _bits(q) == _bits(empty.q([1.0, 2.0])) == _bits(np.tile(np.arange(6.0), (2, 1)))
    assert _bits(q1) == _bits(empty.q([1.0, 2.0], 1)) == _bits(np.zeros((2, 6)))


def _geometries(rng):
    q0, q1 = rng.normal(size=6) * 40, rng.normal(size=6) * 40
    lam = np.sort(rng.uniform(0.0, 1.0, 12))
    lam[0], lam[-1] = 0.0, 1.0
    spline = JointSpline(lam, rng.normal(size=(12, 6)) * 30, rng.normal(size=(12, 6)) * 50)
    vL, vR = rng.normal(size=6), rng.normal(size=6)
    return [JointLine(q0, q1), spline, JointBlend(q0, vL, q1, vR, 12.0, 30.0),
            JointBlend(q0, vL, q1, vR, 12.0, 30.0, shape=0.6)]


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_each_geometry_s_both_orders_are_its_two_evaluations(seed):
    rng = np.random.default_rng(seed)
    lam = np.concatenate([rng.uniform(-0.1, 1.1, 500), [0.0, 1.0, 0.5]])
    for geom in _geometries(rng):
        both = getattr(geom, "q01", None)
        if both is None:
            continue
        q, q1 = both(lam)
        assert _bits(q) == _bits(geom.q(lam, 0)) and _bits(q1) == _bits(geom.q(lam, 1))
    shape = BlendShape(np.zeros(3), np.ones(3), np.ones(3), -np.ones(3), 5.0, 9.0)
    sig = rng.uniform(0.0, shape.ell, 100)
    p, d = shape.point01(sig)
    assert _bits(p) == _bits(shape.point(sig)) and _bits(d) == _bits(shape.point(sig, 1))


def test_a_path_of_every_kind_gives_the_bits_of_each_row_alone():
    rng = np.random.default_rng(11)
    path = Path(np.zeros(6))
    for _ in range(3):
        for geom in _geometries(rng):
            a = float(rng.uniform(0.0, 0.3))
            path.append(Span(geom, a, float(rng.uniform(0.6, 1.0))))
    s = rng.uniform(-1.0, path.end + 1.0, 2000)
    for order in (0, 1, 2):
        assert _bits(path.q(s, order)) == _bits(_alone(path, s, order))
    q, q1 = path.q01(s)
    assert _bits(q) == _bits(_alone(path, s, 0)) and _bits(q1) == _bits(_alone(path, s, 1))


def test_a_subclass_with_its_own_q_is_evaluated_by_it():
    """Neither the batch of a kind nor `q01` bypasses a subclass's own `q`."""

    class Shifted(JointSpline):
        def q(self, lam, order: int = 0):
            return super().q(lam, order) + 1.0

    rng = np.random.default_rng(4)
    lam = np.linspace(0.0, 1.0, 12)
    path = Path(np.zeros(6))
    for _ in range(2):
        path.append(Span(Shifted(lam, rng.normal(size=(12, 6)) * 30, rng.normal(size=(12, 6)) * 50), 0.0, 1.0))
        path.append(Span(_geometries(rng)[1], 0.0, 1.0))
    s = rng.uniform(0.0, path.end, 300)
    q, q1 = path.q01(s)
    assert _bits(q) == _bits(_alone(path, s, 0)) and _bits(q1) == _bits(_alone(path, s, 1))
    assert _bits(path.q(s)) == _bits(q)
