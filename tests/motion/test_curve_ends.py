"""A movel or movec ends at its target's own bits (motion/cartesian.py, _ending_at): the pose
interpolated to λ = 1 from the start differs from the target in the last bits, in a way that
depends on the start, and the joints at the end followed it. A cycle that returns to the same
point then never started twice from the same joints on CPUs where numpy rounds otherwise
(AVX-512): nothing was reused and successive cycles differed by 0.1 ms (docs/performance.md)."""

from __future__ import annotations

import numpy as np

from val3check.motion.cartesian import Arc, Line, expmap
from val3check.motion.construction import construct

from .motionhelp import HOME, KIN, T_HOME, movec, movel, point


def _turned(T, deg, axis):
    out = T.copy()
    out[:3, :3] = T[:3, :3] @ expmap(np.radians(deg) * np.asarray(axis, float))
    return out


def test_a_line_ends_at_its_target_bit_for_bit():
    rng = np.random.default_rng(5)
    for _ in range(50):
        T0 = _turned(T_HOME, rng.uniform(-40, 40), rng.normal(size=3))
        T1 = _turned(T_HOME, rng.uniform(-40, 40), rng.normal(size=3))
        T0[:3, 3] += rng.uniform(-200, 200, 3)
        T1[:3, 3] += rng.uniform(-200, 200, 3)
        poses = Line(T0, T1).poses(np.array([0.0, 0.3, 1.0]))
        assert poses[-1].tobytes() == T1.tobytes()
        assert poses[0].tobytes() == T0.tobytes()
        # inside, the interpolation itself (not the target)
        assert not np.array_equal(poses[1], T1)


def test_an_arc_ends_at_its_target_bit_for_bit():
    R = 100.0
    c = T_HOME[:3, 3] + [0.0, R, 0.0]
    rng = np.random.default_rng(8)
    for _ in range(20):
        via = _turned(T_HOME, rng.uniform(-20, 20), rng.normal(size=3))
        target = _turned(T_HOME, rng.uniform(-20, 20), rng.normal(size=3))
        via[:3, 3] = c + [-R, 0.0, 0.0] + rng.uniform(-5, 5, 3)
        target[:3, 3] = c + [0.0, R, 0.0] + rng.uniform(-5, 5, 3)
        arc = Arc(T_HOME, via, target)
        assert arc.poses(np.array([0.2, 1.0]))[-1].tobytes() == target.tobytes()


def test_the_joints_at_a_movel_end_do_not_depend_on_the_start_bits():
    # the same start but for the last bit of each joint: the end joints are the same bits
    start = HOME + [0.0, 0.0, 0.0, 1e-3, 0.0, 0.0]
    nudged = np.nextafter(start, np.inf)
    ends = []
    for cmd in (movel(point(0, 150, -40)), movec(point(50, 50, 0), point(0, 100, 0))):
        a = construct(KIN, cmd, start, None, 0.0).geometry.q_end
        b = construct(KIN, cmd, nudged, None, 0.0).geometry.q_end
        assert a.tobytes() == b.tobytes()
        ends.append(a)
    assert not np.array_equal(ends[0], ends[1])
