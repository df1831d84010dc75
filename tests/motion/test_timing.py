"""Time parameterisation against analytic figures (10.3.1): bang-bang times of movej."""

from __future__ import annotations

import math

import numpy as np
import pytest

from val3check.motion.mdesc import MDesc
from val3check.motion.timing import duration, trapezoid

from .motionhelp import HOME, ROBOT, movej, queue, run


def bang_bang(d: float, v: float, a: float, dec: float) -> float:
    """Rest-to-rest time over distance d: trapezoid when the cruise speed is reached, else triangle."""
    if d >= v * v / (2 * a) + v * v / (2 * dec):
        return d / v + v / (2 * a) + v / (2 * dec)
    vp = math.sqrt(2 * d * a * dec / (a + dec))
    return vp / a + vp / dec


@pytest.mark.parametrize("S,V,A,D", [(90, 435, 1740, 1740), (5, 435, 1740, 1740), (90, 435, 1740, 600),
                                     (200, 100, 300, 2000), (0.001, 10, 10, 10)])
def test_trapezoid_matches_the_closed_form(S, V, A, D):
    s, sd = trapezoid(S, 0.0, V, A, D)
    assert duration(s, sd) == pytest.approx(bang_bang(S, V, A, D), rel=1e-12)
    assert sd.max() <= V * (1 + 1e-12)
    assert s[-1] == pytest.approx(S) and sd[-1] == 0.0


def test_trapezoid_from_a_moving_start():
    # from v0 = V the first ramp is missing: time = (S - V²/2D)/V + V/D
    S, V, A, D = 100.0, 50.0, 200.0, 100.0
    s, sd = trapezoid(S, V, V, A, D)
    assert duration(s, sd) == pytest.approx((S - V * V / (2 * D)) / V + V / D, rel=1e-12)
    # faster than the limit (it was lowered under way): brake to V at D first
    s, sd = trapezoid(S, 2 * V, V, A, D)
    t_brake = V / D
    d_brake = (4 * V * V - V * V) / (2 * D)
    assert duration(s, sd) == pytest.approx(t_brake + (S - d_brake - V * V / (2 * D)) / V + V / D, rel=1e-12)


def test_zero_length_profile():
    s, sd = trapezoid(0.0, 0.0, 1.0, 1.0, 1.0)
    assert duration(s, sd) == 0.0


@pytest.mark.parametrize("axis,delta", [(0, 90.0), (1, -40.0), (2, 3.0), (5, 250.0)])
@pytest.mark.parametrize("vel,accel,decel", [(100, 100, 100), (50, 30, 80), (20, 100, 10)])
def test_single_axis_movej_is_bang_bang(axis, delta, vel, accel, decel):
    q = queue()
    target = HOME.copy()
    target[axis] += delta
    q.record(movej(target, MDesc(vel=vel, accel=accel, decel=decel, blend="off")), 0.0)
    t = run(q)
    v = ROBOT.nominal_speeds[axis] * vel / 100
    a = ROBOT.accelerations[axis] * accel / 100
    d = ROBOT.accelerations[axis] * decel / 100
    assert t == pytest.approx(bang_bang(abs(delta), v, a, d), rel=1e-7)
    assert np.allclose(q.position(t), target)


@pytest.mark.parametrize("vel,accel,decel", [(100, 100, 100), (60, 36, 50)])
def test_multi_axis_movej_takes_the_slowest_axis_time(vel, accel, decel):
    q = queue()
    delta = np.array([60.0, -30.0, 45.0, 120.0, -50.0, 200.0])
    q.record(movej(HOME + delta, MDesc(vel=vel, accel=accel, decel=decel, blend="off")), 0.0)
    t = run(q)
    times = [bang_bang(abs(d), ROBOT.nominal_speeds[k] * vel / 100, ROBOT.accelerations[k] * accel / 100,
                       ROBOT.accelerations[k] * decel / 100) for k, d in enumerate(delta)]
    assert t == pytest.approx(max(times), rel=1e-7)
    # every axis moves on the straight joint line: at mid-time each is at the same fraction
    q_mid = q.position(t / 2)
    frac = (q_mid - HOME) / delta
    assert np.allclose(frac, frac[0], atol=1e-9)


def test_joint_speeds_and_accelerations_stay_within_the_limits():
    q = queue()
    delta = np.array([100.0, 10.0, -20.0, 0.0, 0.0, 5.0])
    q.record(movej(HOME + delta, MDesc(vel=70, accel=40, decel=90, blend="off")), 0.0)
    t = run(q)
    times, Q, Qd = q.trajectory.sample(0.0, t)
    V = np.array(ROBOT.nominal_speeds) * 0.7
    assert np.all(np.abs(Qd) <= V * (1 + 1e-9))
    acc = np.diff(Qd, axis=0) / 0.004
    A = np.array(ROBOT.accelerations)
    assert np.all(np.abs(acc) <= A * 0.9 * (1 + 1e-6))


def test_monitor_speed_scales_every_limit():
    q = queue(monitor=50.0)
    target = HOME.copy()
    target[0] += 90.0
    q.record(movej(target), 0.0)
    t = run(q)
    assert t == pytest.approx(bang_bang(90.0, 435 * 0.5, 1740 * 0.5, 1740 * 0.5), rel=1e-7)


def test_a_very_short_movej():
    q = queue()
    target = HOME.copy()
    target[3] += 1e-4
    q.record(movej(target), 0.0)
    t = run(q)
    assert t == pytest.approx(bang_bang(1e-4, 995, 3980, 3980), rel=1e-7)


def test_when_no_optimal_profile_is_found_a_safe_slower_profile_is_used_and_reported(monkeypatch):
    from val3check.motion import findings as F
    from val3check.motion.timing import optimal

    from .motionhelp import KIN, movel, point

    def broken(x0, cap, K, fwd, k0=0, at_K=None):  # a forward pass that stands still inside the path
        return [0.0] * len(cap)

    q0 = queue()
    q0.record(movel(point(dz=150.0), MDesc(leave=40, reach=40)), 0.0)
    q0.record(movel(point(dy=200.0, dz=150.0), MDesc(blend="off")), 0.0)
    t_opt = run(q0)
    monkeypatch.setattr(optimal, "forward", broken)
    q = queue()
    q.record(movel(point(dz=150.0), MDesc(leave=40, reach=40)), 0.0)
    q.record(movel(point(dy=200.0, dz=150.0), MDesc(blend="off")), 0.0)
    t = run(q)
    assert t > t_opt
    assert any(f.code == F.FALLBACK for f in q.findings)
    _, Q, Qd = q.trajectory.sample(0.0, t)
    assert np.all(np.abs(Qd) <= np.array(KIN.speeds) * (1 + 1e-9))
    assert np.all(np.abs(np.diff(Qd, axis=0)) / 0.004 <= np.array(KIN.accels) * 1.02)


def test_the_timing_interface_a_path_plus_its_limits_gives_the_profile():
    """timing.Timing, the one place where a path and its limits become a time parameterisation
    (planner.py calls nothing else): a straight joint line gets the exact bang-bang profile of its
    slowest axis, with the key of the command that owns it."""
    from val3check.motion.mdesc import Limits
    from val3check.motion.paths import JointLine, Path, Span
    from val3check.motion.timing import Timing

    from .motionhelp import KIN

    delta = np.array([90.0, -40.0, 60.0, 120.0, -30.0, 200.0])
    path = Path(HOME)
    path.append(Span(JointLine(HOME, HOME + delta), 0.0, 1.0, [(7, 0.0)]))
    md = MDesc(vel=50, accel=30, decel=70)
    piece = Timing(KIN).time(path, 0.0, path.end, 0.0, lambda key: Limits.of(KIN, md, 1.0))
    expected = max(bang_bang(abs(d), v * 0.5, a * 0.3, a * 0.7)
                   for d, v, a in zip(delta, ROBOT.nominal_speeds, ROBOT.accelerations))
    assert piece.owner == 7 and not piece.fallback
    assert piece.s[0] == 0.0 and piece.s[-1] == pytest.approx(path.end) and piece.sd[-1] == 0.0
    assert piece.duration == pytest.approx(expected, rel=1e-12)
