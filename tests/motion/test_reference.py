"""The independent timing reference (reference.py) held to closed forms before anything is
measured against it: bang-bang times of joint lines, a vertical SCARA line (only the prismatic
axis moves: tvel and one constant Cartesian acceleration bind), arcs and tvel-capped joint moves
about axis 1 (only j1 moves), and on general paths: every limit respected, one limit saturated
everywhere (the bang-bang property of 10.3.1), and convergence with the grid."""

from __future__ import annotations

import math

import numpy as np
import pytest

from val3check.robot import load_robot

from . import reference as ref

TX = load_robot("TX2-60")
TS = load_robot("TS2-60")
TX_Q0 = np.array([0.0, 20.0, 100.0, 0.0, 60.0, 0.0])  # tool down in front of the arm
TS_Q0 = np.array([0.0, 90.0, 100.0, 0.0])  # flange 449.4 mm from axis 1


def fk(model, q) -> np.ndarray:
    T = np.eye(4)
    T[:3, :] = np.array(model.fk_matrix(list(q)))
    return T


def rz(T, deg: float) -> np.ndarray:
    """T turned about the world's Z axis (through axis 1)."""
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    R = np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])
    return R @ T


def test_bang_bang_closed_form():
    # trapezoid: distance covered by the ramps and the cruise adds up
    d, v, a, dec = 100.0, 50.0, 200.0, 100.0
    t = ref.bang_bang(d, v, a, dec)
    cruise = t - v / a - v / dec
    assert v * v / (2 * a) + v * cruise + v * v / (2 * dec) == pytest.approx(d)
    # triangle: the peak speed is reached exactly at the switch, both sides continuous at the threshold
    d_th = v * v / (2 * a) + v * v / (2 * dec)
    assert ref.bang_bang(d_th * (1 - 1e-12), v, a, dec) == pytest.approx(ref.bang_bang(d_th, v, a, dec), rel=1e-9)
    assert ref.bang_bang(d_th, v, a, dec) == pytest.approx(v / a + v / dec)
    assert ref.bang_bang(0.0, v, a, dec) == 0.0


@pytest.mark.parametrize("delta", [(90, 0, 0, 0, 0, 0), (60, -30, 45, 120, -50, 200), (0.01, 0.02, 0, 0, 0, 0.5)])
def test_optimal_matches_the_synchronised_joint_line(delta):
    # accelerations not proportional to the speeds, accel != decel: the tightest ratio per phase
    V, A, D = (435, 385, 500, 995, 1065, 1445), (2000, 900, 3000, 5000, 2500, 9000), (1000, 1800, 1500, 3000, 7000, 4000)
    lim = ref.Limits(V, A, D)
    q1 = TX_Q0 + np.array(delta, dtype=float)
    prof = ref.movej(TX, TX_Q0, q1, lim, n_ik=201, n=2001)
    assert prof.duration == pytest.approx(ref.movej_time(delta, V, A, D), rel=1e-9)


@pytest.mark.parametrize("length", [1.0, 50.0, 150.0])
@pytest.mark.parametrize("tvel", [10.0, 250.0, 2000.0])
def test_vertical_scara_line_is_the_axis_3_trapezoid(length, tvel):
    # only the prismatic axis moves: its speed and acceleration are the TCP's (mm/s, mm/s²)
    lim = ref.Limits.of(TS, accel=80, decel=40, tvel=tvel)
    q0 = TS_Q0 + [0.0, 0.0, 80.0, 0.0]  # j3 at 180 mm: down to 30 mm at most
    T0 = fk(TS, q0)
    T1 = T0.copy()
    T1[2, 3] -= length
    prof = ref.movel(TS, T0, T1, q0, lim, n_ik=101, n=2001)
    v = min(tvel, lim.V[2])
    assert prof.duration == pytest.approx(ref.bang_bang(length, v, lim.A[2], lim.D[2]), rel=1e-9)


@pytest.mark.parametrize("model,q0", [(TS, TS_Q0), (TX, TX_Q0)])
@pytest.mark.parametrize("tvel,rvel", [(50.0, 9999.0), (400.0, 9999.0), (9999.0, 9999.0), (9999.0, 30.0)])
def test_arc_about_axis_1_is_the_joint_1_trapezoid(model, q0, tvel, rvel):
    # a circle about axis 1 with the tool turning with it: only j1 moves (TCP speed r·ω, rotation ω)
    lim = ref.Limits.of(model, accel=100, decel=60, tvel=tvel, rvel=rvel)
    T0 = fk(model, q0)
    r = math.hypot(T0[0, 3], T0[1, 3])
    prof = ref.movec(model, T0, rz(T0, 45.0), rz(T0, 100.0), q0, lim, n_ik=201, n=4001)
    w = min(lim.V[0], math.degrees(tvel / r), rvel)
    assert prof.duration == pytest.approx(ref.bang_bang(100.0, w, lim.A[0], lim.D[0]), rel=1e-9)


@pytest.mark.parametrize("model,q0", [(TS, TS_Q0), (TX, TX_Q0)])
@pytest.mark.parametrize("tvel", [10.0, 500.0, 2000.0])
def test_tvel_capped_joint_1_move(model, q0, tvel):
    lim = ref.Limits.of(model, tvel=tvel)
    q1 = q0.copy()
    q1[0] += 90.0
    r = math.hypot(*fk(model, q0)[:2, 3])
    prof = ref.movej(model, q0, q1, lim, n_ik=201, n=2001)
    w = min(lim.V[0], math.degrees(tvel / r))
    assert prof.duration == pytest.approx(ref.bang_bang(90.0, w, lim.A[0], lim.D[0]), rel=1e-9)


def line_poses():
    """A diagonal line on the TX2-60 with a 50° turn of the tool: every axis moves."""
    T0 = fk(TX, TX_Q0)
    T1 = T0.copy()
    T1[:3, 3] += [-120.0, 260.0, 80.0]
    c, s = math.cos(math.radians(50)), math.sin(math.radians(50))
    T1[:3, :3] = T1[:3, :3] @ np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])
    return T0, T1


def general_line(n: int = 401):
    return ref.sample_cartesian(TX, ref.Line(*line_poses()), TX_Q0, n=n)


def test_a_general_profile_respects_every_limit_and_saturates_one():
    sm = general_line()
    lim = ref.Limits.of(TX, vel=80, accel=100, decel=50, tvel=700, rvel=120)
    prof = ref.optimal(sm, lim, n=8001)
    fine = ref._refine(sm, 8001)
    x = prof.x
    sdd = np.diff(x) / (2 * np.diff(prof.s))  # constant on each segment
    V, A, D = (np.array(v) for v in (lim.V, lim.A, lim.D))
    qd = fine.dq * np.sqrt(x)[:, None]
    assert np.all(np.abs(qd) <= V * (1 + 1e-9))
    assert np.all(fine.dp * np.sqrt(x) <= lim.tvel * (1 + 1e-9))
    assert np.all(fine.dw * np.sqrt(x) <= lim.rvel * (1 + 1e-9))
    # per axis, at the start of each segment: sign(q̇)·q̈ in [-decel, accel]
    sgn = np.where(fine.dq[:-1] >= 0, 1.0, -1.0)
    acc = sgn * (fine.dq[:-1] * sdd[:, None] + fine.ddq[:-1] * x[:-1, None])
    assert np.all(acc <= A * (1 + 1e-9) + 1e-9) and np.all(acc >= -D * (1 + 1e-9) - 1e-9)
    # time-optimal: on every segment a speed or an acceleration limit is reached
    speed_sat = np.max(np.abs(qd) / V, axis=1)
    speed_sat = np.maximum(speed_sat, fine.dp * np.sqrt(x) / lim.tvel)
    speed_sat = np.maximum(speed_sat, fine.dw * np.sqrt(x) / lim.rvel)
    acc_sat = np.max(np.maximum(acc / A, -acc / D), axis=1)
    sat = np.maximum(np.maximum(speed_sat[:-1], speed_sat[1:]), acc_sat)
    assert sat.min() > 1 - 1e-6


def test_the_duration_converges_with_the_grid():
    sm = general_line()
    lim = ref.Limits.of(TX, tvel=1500)
    coarse = ref.optimal(sm, lim, n=2001).duration
    fine = ref.optimal(sm, lim, n=32001).duration
    assert fine == pytest.approx(coarse, rel=2e-4)
    # and a finer IK sampling of the same line changes nothing that matters
    denser = ref.optimal(general_line(1601), lim, n=32001).duration
    assert denser == pytest.approx(fine, rel=1e-5)


def test_a_straight_line_at_tvel_is_bounded_by_its_cruise():
    T0 = fk(TX, TX_Q0)
    T1 = T0.copy()
    T1[1, 3] += 200.0
    prof = ref.movel(TX, T0, T1, TX_Q0, ref.Limits.of(TX, tvel=100.0), n_ik=201, n=4001)
    # 200 mm at 100 mm/s: 2 s of cruise plus ramps the joints' accelerations make short (issue 23:
    # "about 2.01 s")
    assert 2.0 < prof.duration < 2.0 + 100.0 / 1000.0
    assert prof.duration == pytest.approx(2.008, abs=1e-3)
