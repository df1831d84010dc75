"""Simulated Cartesian motions against closed forms (issue 23, "Exact timing"): where only one
axis moves, the time-optimal motion is that axis's trapezoid (10.3.1), so val3check's time must
be the bang-bang time to rounding, not merely close to a numerical optimum:

* a vertical SCARA movel moves only the prismatic axis 3: its speed and acceleration are the
  TCP's, capped by tvel;
* a movec on a circle about axis 1 with the tool turning with it moves only joint 1: TCP speed
  r·ω (tvel), rotation ω (rvel);
and the geometry of the same motions: straight, on the circle, at the end point, peak speed at
the cap (issue 23's "What will be checked": duration, straightness, peak speed, end point)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from val3check.motion.commands import MoveCommand, Target
from val3check.motion.mdesc import MDesc
from val3check.motion.queue import MotionQueue
from val3check.robot import load_robot

from . import reference as ref

TX = load_robot("TX2-60")
TS = load_robot("TS2-60")
TX_Q0 = np.array([0.0, 20.0, 100.0, 0.0, 60.0, 0.0])  # tool down in front of the arm
TS_Q0 = np.array([0.0, 90.0, 180.0, 0.0])  # flange 449.4 mm from axis 1, j3 at 180 mm


def fk(model, q) -> np.ndarray:
    T = np.eye(4)
    T[:3, :] = np.array(model.fk_matrix(list(q)))
    return T


def rz(T, deg: float) -> np.ndarray:
    """T turned about the world's Z axis (through axis 1)."""
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]]) @ T


def run(model, q0, move: MoveCommand):
    """(duration, TCP positions (N, 3), TCP speeds (N,)) of one motion from rest, sampled at 1 ms."""
    q = MotionQueue(model, np.array(q0))
    q.record(move, 0.0)
    t = q.wait_end_move(0.0)
    q.advance(t)
    times, Q, _ = q.trajectory.sample(0.0, t, 0.001)
    P = np.array([fk(model, x)[:3, 3] for x in Q])
    v = np.linalg.norm(np.diff(P, axis=0), axis=1) / np.diff(times)
    return t, P, v, q


@pytest.mark.parametrize("length", [1.0, 50.0, 150.0])
@pytest.mark.parametrize("tvel", [10.0, 250.0, 2000.0])
def test_a_vertical_scara_movel_is_the_axis_3_trapezoid(length, tvel):
    md = MDesc(blend="off", accel=80.0, decel=40.0, tvel=tvel)
    lim = ref.Limits.of(TS, accel=80.0, decel=40.0, tvel=tvel)
    T0 = fk(TS, TS_Q0)
    T1 = T0.copy()
    T1[2, 3] -= length
    t, P, v, q = run(TS, TS_Q0, MoveCommand("movel", Target.point(T1), md))
    expected = ref.bang_bang(length, min(tvel, lim.V[2]), lim.A[2], lim.D[2])
    assert t == pytest.approx(expected, rel=1e-6, abs=1e-6)
    assert np.abs(P[:, :2] - T0[:2, 3]).max() < 1e-6  # straight down
    assert np.allclose(fk(TS, q.position(t))[:3, 3], T1[:3, 3], atol=1e-6)
    peak = min(tvel, lim.V[2], math.sqrt(2 * length * lim.A[2] * lim.D[2] / (lim.A[2] + lim.D[2])))
    assert v.max() <= peak * (1 + 1e-6)
    if length / tvel > 0.05:  # long enough for 1 ms samples to see the peak
        assert v.max() == pytest.approx(peak, rel=1e-2)


@pytest.mark.parametrize("model,q0", [(TS, TS_Q0), (TX, TX_Q0)])
@pytest.mark.parametrize("tvel,rvel", [(50.0, 9999.0), (400.0, 9999.0), (9999.0, 9999.0), (9999.0, 30.0)])
def test_a_movec_about_axis_1_is_the_joint_1_trapezoid(model, q0, tvel, rvel):
    md = MDesc(blend="off", accel=100.0, decel=60.0, tvel=tvel, rvel=rvel)
    lim = ref.Limits.of(model, accel=100.0, decel=60.0, tvel=tvel, rvel=rvel)
    T0 = fk(model, q0)
    r = math.hypot(T0[0, 3], T0[1, 3])
    T1 = rz(T0, 100.0)
    t, P, v, q = run(model, q0, MoveCommand("movec", Target.point(T1), md, via=Target.point(rz(T0, 45.0))))
    w = min(lim.V[0], math.degrees(tvel / r), rvel)
    assert t == pytest.approx(ref.bang_bang(100.0, w, lim.A[0], lim.D[0]), rel=1e-6)
    assert np.abs(np.hypot(P[:, 0], P[:, 1]) - r).max() < 1e-3  # on the circle
    assert np.abs(P[:, 2] - T0[2, 3]).max() < 1e-3
    assert np.allclose(fk(model, q.position(t))[:3, 3], T1[:3, 3], atol=1e-6)
    peak = math.radians(min(w, math.sqrt(2 * 100.0 * lim.A[0] * lim.D[0] / (lim.A[0] + lim.D[0])))) * r
    assert v.max() <= peak * (1 + 1e-3)
    assert v.max() == pytest.approx(peak, rel=1e-2)
