"""Geometry and timing of Cartesian paths against analytic figures: straight lines at a tvel limit,
half circles, orientation interpolation as interpolateL/interpolateC compute it."""

from __future__ import annotations

import math

import numpy as np
import pytest

from val3check.geometry import trsf as GT
from val3check.motion.commands import Target
from val3check.motion.mdesc import MDesc

from .motionhelp import KIN, T_HOME, movec, movel, point, queue, run, tcp_path


def cruise_checks(times, v, tvel, length, duration):
    assert np.all(v <= tvel * (1 + 1e-4))  # the joint path follows the curve within a micrometre
    at = np.abs(v - tvel) < 1e-3 * tvel
    t_up = times[np.argmax(at)]
    t_down = duration - times[len(at) - 1 - np.argmax(at[::-1])]
    # distance = tvel * cruise + what the ramps cover (between 0 and tvel over each ramp)
    assert length / tvel <= duration <= length / tvel + t_up + t_down + 0.008
    assert at.mean() > 0.6


@pytest.mark.parametrize("tvel", [100.0, 250.0, 600.0])
def test_movel_at_a_tvel_limit(tvel):
    q = queue()
    target = point(dy=250.0, dz=60.0)
    q.record(movel(target, MDesc(blend="off", tvel=tvel)), 0.0)
    t = run(q)
    times, P, v = tcp_path(q, 0.0, t)
    L = math.hypot(250.0, 60.0)
    cruise_checks(times, v, tvel, L, t)
    # straight: distance from the line
    d = (target.pose[:3, 3] - T_HOME[:3, 3]) / L
    rel = P - T_HOME[:3, 3]
    assert np.linalg.norm(rel - np.outer(rel @ d, d), axis=1).max() < 1e-3
    assert np.allclose(KIN.fk(q.position(t)[None])[0][:3, 3], target.pose[:3, 3], atol=1e-6)


def test_movel_orientation_follows_interpolateL():
    q = queue()
    T1 = T_HOME.copy()
    T1[:3, 3] += [0.0, 150.0, 50.0]
    c, s = math.cos(math.radians(40)), math.sin(math.radians(40))
    T1[:3, :3] = T1[:3, :3] @ np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])
    q.record(movel(Target.point(T1), MDesc(blend="off", tvel=300)), 0.0)
    t = run(q)
    times, Q, _ = q.trajectory.sample(0.0, t)
    T = KIN.fk(Q)
    a = GT.Trsf.from_matrix4(T_HOME)
    b = GT.Trsf.from_matrix4(T1)
    for k in range(0, len(T), 15):
        frac = float(np.linalg.norm(T[k, :3, 3] - T_HOME[:3, 3]) / np.linalg.norm(T1[:3, 3] - T_HOME[:3, 3]))
        ref = GT.interpolate_l(a, b, frac)
        assert GT.close(GT.Trsf.from_matrix4(T[k]), ref, length_tol=1e-3, angle_tol=1e-3)


@pytest.mark.parametrize("R", [40.0, 120.0])
def test_half_circle_movec(R):
    q = queue()
    c = T_HOME[:3, 3] + [0.0, R, 0.0]
    via, target = T_HOME.copy(), T_HOME.copy()
    via[:3, 3] = c + [-R, 0.0, 0.0]
    target[:3, 3] = c + [0.0, R, 0.0]
    tvel = 200.0
    q.record(movec(Target.point(via), Target.point(target), MDesc(blend="off", tvel=tvel)), 0.0)
    t = run(q)
    times, P, v = tcp_path(q, 0.0, t)
    assert np.abs(np.linalg.norm(P - c, axis=1) - R).max() < 1e-3
    assert np.abs(P[:, 2] - c[2]).max() < 1e-3
    cruise_checks(times, v, tvel, math.pi * R, t)
    # it went through the intermediate point, on the side of it
    assert np.linalg.norm(P - via[:3, 3], axis=1).min() < 0.5 * tvel * 0.004 + 1e-3


def test_movec_orientation_follows_interpolateC():
    q = queue()
    R = 80.0
    c = T_HOME[:3, 3] + [0.0, R, 0.0]
    via, target = T_HOME.copy(), T_HOME.copy()
    via[:3, 3] = c + [-R, 0.0, 0.0]
    target[:3, 3] = c + [0.0, R, 0.0]
    turn = math.radians(30)
    via[:3, :3] = via[:3, :3] @ np.array([[math.cos(turn), -math.sin(turn), 0], [math.sin(turn), math.cos(turn), 0],
                                          [0, 0, 1.0]])
    q.record(movec(Target.point(via), Target.point(target), MDesc(blend="off", tvel=300)), 0.0)
    t = run(q)
    _, Q, _ = q.trajectory.sample(0.0, t)
    T = KIN.fk(Q)
    a, m, b = (GT.Trsf.from_matrix4(x) for x in (T_HOME, via, target))
    for k in range(0, len(T), 10):
        p = T[k, :3, 3] - c
        ang = math.atan2(p[0] * -1.0, -p[1])  # angle travelled from the start, about Z
        frac = (ang % (2 * math.pi)) / math.pi
        ref = GT.interpolate_c(a, m, b, min(max(frac, 0.0), 1.0))
        # the rotation rate changes at the intermediate point: the joint path rounds that corner
        # within one gridpoint on each side (docs/motion.md)
        tol = 0.1 if abs(frac - 0.5) < 0.1 else 1e-3
        assert GT.close(GT.Trsf.from_matrix4(T[k]), ref, length_tol=1e-2, angle_tol=tol)


def test_a_knot_on_a_gridpoint_is_not_doubled():
    """movec's intermediate point is a gridpoint; when the grid already has one there (up to
    rounding), the spline must not get two knots 1e-16 apart (the time was then absurd)."""
    from val3check.motion.cartesian import Arc
    from val3check.motion.tracking import track

    from .motionhelp import HOME

    R = 100.0
    c = T_HOME[:3, 3] + [0.0, R, 0.0]
    via, target = T_HOME.copy(), T_HOME.copy()
    via[:3, 3] = c + [-R, 0.0, 0.0]
    target[:3, 3] = c + [0.0, R, 0.0]
    arc = Arc(T_HOME, via, target)
    arc.u2 = 0.5 + 1e-16  # what the arithmetic may give for a symmetric arc
    arc.knots = (arc.u2,)
    tr = track(KIN, arc, None, HOME, int(KIN.config_codes(HOME)[0]), n=40)
    assert np.diff(tr.lam).min() > 1e-9
