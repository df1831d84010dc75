"""The arm's per-cycle calls without their extra calls (issue 29): `MovingArm.queue_time` tests
the warp's identity itself and gives what `Layers.queue_time` gives; `_sync` compares the
controller's values as they are before converting them and applies every change."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from val3check.simulation.moving_arm import MovingArm

from .test_long_runs import TX2_60


def test_queue_time_is_the_layers_queue_time_with_or_without_the_identity():
    arm = MovingArm(TX2_60)
    rng = np.random.default_rng(3)
    times = sorted(int(v) for v in rng.integers(0, 10_000_000, 200))
    for t in times:
        assert arm.queue_time(t) == arm.layers.queue_time(t / 1e6) == t / 1e6
    w = arm.layers.warp
    w.max_tau[0] = 5.0  # (a τ already reached beyond t: not the identity)
    for t in times:
        assert arm.queue_time(t) == arm.layers.queue_time(t / 1e6)
    w.max_tau[0] = 0.0
    w.set_rate(2.0, 0)  # held from 2 s, then going on from 4 s
    w.set_rate(4.0, 1)
    for t in times:
        assert arm.queue_time(t) == arm.layers.queue_time(t / 1e6)
    assert arm.queue_time(3_000_000) == 2.0


def test_sync_applies_each_change_of_power_and_monitor_speed():
    arm = MovingArm(TX2_60)
    ctl = SimpleNamespace(powered=True, monitor_speed=100.0)
    arm.bind(ctl)
    q = arm._sync(0)
    assert (q.powered, q.monitor) == (True, 100.0)
    for k, (powered, monitor, want) in enumerate([(True, 50, (True, 50.0)), (0, 50.0, (False, 50.0)),
                                                 (1, 50.0, (True, 50.0)), (1, 75.5, (True, 75.5)),
                                                 (False, 0.0, (False, 0.0)), (True, 100, (True, 100.0))]):
        ctl.powered, ctl.monitor_speed = powered, monitor
        q = arm._sync(4000 * (k + 1))
        assert (q.powered, q.monitor) == want and type(q.monitor) is float and type(q.powered) is bool, k
