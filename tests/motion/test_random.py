"""Random programs against the invariants of the queue: nothing but MotionError escapes, time and
the path only go forward, joint speeds stay within their limits, positions are continuous."""

from __future__ import annotations

import numpy as np
import pytest

from val3check.motion.commands import Target
from val3check.motion.findings import MotionError
from val3check.motion.mdesc import MDesc
from val3check.motion.queue import QueueFull

from .motionhelp import HOME, KIN, T_HOME, movec, movej, movel, queue


def random_md(rng):
    blend = ["off", "joint", "Cartesian"][rng.integers(3)]
    return MDesc(vel=rng.uniform(20, 100), accel=rng.uniform(20, 100), decel=rng.uniform(20, 100),
                 tvel=rng.uniform(100, 3000), blend=blend, leave=rng.uniform(0, 80), reach=rng.uniform(0, 80))


def random_pose(rng):
    T = T_HOME.copy()
    T[:3, 3] += rng.uniform([-150, -250, -30], [100, 250, 200])
    return Target.point(T)


@pytest.mark.parametrize("seed", range(int(__import__("os").environ.get("MOTION_SEEDS", "12"))))
def test_random_programs_keep_the_invariants(seed):
    rng = np.random.default_rng(seed)
    q = queue()
    now = 0.0
    for _ in range(25):
        op = rng.random()
        try:
            if op < 0.35:
                r = q.record(movej(HOME + rng.uniform(-40, 40, 6), random_md(rng)), now)
            elif op < 0.6:
                r = q.record(movel(random_pose(rng), random_md(rng)), now)
            elif op < 0.7:
                r = q.record(movec(random_pose(rng), random_pose(rng), random_md(rng)), now)
            elif op < 0.78:
                t = q.wait_end_move(now)
                now = t if t is not None else now + 0.1
                r = None
            elif op < 0.82:
                q.stop_move(now)
                r = None
            elif op < 0.86:
                q.restart_move(now)
                r = None
            elif op < 0.89:
                q.set_monitor_speed(float(rng.uniform(10, 100)), now)
                r = None
            elif op < 0.92:
                q.reset_motion(now)
                r = None
            else:
                q.set_power(bool(rng.random() < 0.7), now)
                r = None
            if isinstance(r, QueueFull):
                now = r.until if r.until is not None else now + 0.1
        except MotionError as e:
            if e.code == 150:
                q.reset_motion(now)
        now += float(rng.uniform(0.0, 0.3))
        q.advance(now)
    q.restart_move(now)
    q.set_power(True, now)
    t_end = q.end_time(now) or now
    prof = q.trajectory.profile
    T = np.array(prof.T)
    S = np.array(prof.S)
    assert np.all(np.diff(T) >= -1e-12) and np.all(np.diff(S) >= -1e-9)
    assert np.all(np.array(prof.SD) >= 0)
    times, Q, Qd = q.trajectory.sample(0.0, max(t_end, now))
    # the monitor speed may have been higher before; no axis beyond 100 % of its nominal speed
    assert np.all(np.abs(Qd) <= np.array(KIN.speeds) * (1 + 1e-6))
    jumps = np.abs(np.diff(Q, axis=0)).max(axis=1)
    assert jumps.max() <= np.max(KIN.speeds) * 0.004 * 1.01
