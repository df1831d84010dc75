"""Trajectory.sample evaluates the path once per run of samples with the same (s, ṡ) (the arm at
rest) and the moving samples in one evaluation: the same bits as evaluating every sample, alone
or all at once; Trajectory.moving vectorised: the same intervals as the loop it replaced."""

from __future__ import annotations

import numpy as np
import pytest

from val3check.motion.trajectory import Trajectory, tick_times

from .pick_place_run import pick_place_machine


@pytest.fixture(scope="module")
def pick_place():
    """Forty seconds of the bundled pick-and-place (its scenario): rest and motion, blends."""
    machine = pick_place_machine(40)
    return machine.arm.queue_in_use.trajectory, machine.end_time / 1e6


def _bits(x: np.ndarray) -> bytes:
    return np.ascontiguousarray(x, dtype=float).tobytes()


def _every_sample(traj: Trajectory, t0: float, t1: float, dt: float):
    """The path at every sample: all at once, and one sample at a time."""
    times = tick_times(t0, t1, dt)
    s, sd = traj.profile.states(times)
    bulk = traj.path.q(s), traj.path.q(s, 1) * sd[:, None]
    alone = (np.vstack([traj.path.q([x]) for x in s]),
             np.vstack([traj.path.q([x], 1) * y for x, y in zip(s, sd)]))
    return times, bulk, alone


@pytest.mark.parametrize("dt", [0.004, 0.008, 0.012])
def test_sampling_gives_the_bits_of_every_sample_evaluated(pick_place, dt):
    traj, end = pick_place
    times, (q_all, v_all), (q_one, v_one) = _every_sample(traj, 0.0, end, dt)
    got_t, q, v = traj.sample(0.0, end, dt)
    assert _bits(got_t) == _bits(times)
    assert _bits(q) == _bits(q_all) == _bits(q_one)
    assert _bits(v) == _bits(v_all) == _bits(v_one)
    rest = np.all(v == 0.0, axis=1)
    assert 0.2 * len(times) < rest.sum() < 0.8 * len(times)  # both kinds, many boundaries
    assert np.count_nonzero(np.diff(rest.astype(int))) > 10


def test_sampling_windows_starting_and_ending_at_rest_and_in_motion(pick_place):
    """Windows whose ends fall at rest, in motion, and on the ticks around each boundary."""
    traj, end = pick_place
    edges = [x for a, b in traj.moving(end) for x in (a, b)][:12]
    bounds = [0.0, end] + [e + k * 0.004 for e in edges for k in (-1, 0, 1)]
    for t0 in bounds[::3]:
        for t1 in bounds[1::2]:
            if len(tick_times(t0, t1, 0.004)) == 0:
                continue
            times, (q_all, v_all), _ = _every_sample(traj, t0, t1, 0.004)
            got_t, q, v = traj.sample(t0, t1)
            assert _bits(got_t) == _bits(times)
            assert _bits(q) == _bits(q_all) and _bits(v) == _bits(v_all)


def _moving_loop(traj: Trajectory, t_end: float) -> list:
    """The loop Trajectory.moving replaced."""
    T, SD = traj.profile.T, traj.profile.SD
    out: list = []
    for i in range(len(T) - 1):
        if T[i] >= t_end:
            break
        if SD[i] > 0.0 or SD[i + 1] > 0.0:
            a, b = T[i], min(T[i + 1], t_end)
            if out and a <= out[-1][1] + 1e-12:
                out[-1] = (out[-1][0], b)
            else:
                out.append((a, b))
    return out


def test_moving_gives_the_loop_s_intervals(pick_place):
    traj, end = pick_place
    edges = [x for a, b in _moving_loop(traj, end) for x in (a, b)]
    for t_end in [0.0, -1.0, end, np.inf, *edges[:9], *(e + 1e-13 for e in edges[:9]), *(e + 0.01 for e in edges[:9])]:
        got = traj.moving(t_end)
        want = _moving_loop(traj, t_end)
        assert got == want
        assert all(type(x) is float for ab in got for x in ab)
    assert len(traj.moving(end)) > 5


@pytest.mark.parametrize("block", [2, 3, 7, 64])
def test_moving_block_by_block_gives_the_loop_s_intervals(pick_place, monkeypatch, block):
    """Trajectory.moving reads the profile in blocks (an 8-hour profile holds millions of
    breakpoints): intervals that cross a block's edge are joined as the loop joins them."""
    import val3check.motion.trajectory as trajectory_module

    traj, end = pick_place
    monkeypatch.setattr(trajectory_module, "_MOVING_BLOCK", block)
    edges = [x for a, b in _moving_loop(traj, end) for x in (a, b)]
    for t_end in [end, *edges[:20], *(x + 1e-9 for x in edges[:20]), 0.0, 1e9]:
        assert traj.moving(t_end) == _moving_loop(traj, t_end)
