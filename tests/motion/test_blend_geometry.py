"""Blended corners against the curves docs/motion.md documents ("Blends"), computed independently
by blend_reference.py from the words of the document and the model's IK/FK (issue 23: a symmetric
corner was blended asymmetrically, 23.0 mm from the corner for 24.75 mm documented).

A Cartesian blend of two straight lines is the parabola with its control point at the corner: for
leave = reach = L on perpendicular lines it passes L·√2/4 from the corner, at the middle. A joint
blend draws the same construction in joint space: for two movej, the parabola through the corner
of the joint lines; for two movel, the cubic through the joints and joint derivatives of the two
lines at the leave and reach points."""

from __future__ import annotations

import math

import numpy as np
import pytest

from val3check.motion.commands import MoveCommand, Target
from val3check.motion.mdesc import MDesc
from val3check.motion.queue import MotionQueue
from val3check.robot import load_robot

from . import blend_reference as bref

TX = load_robot("TX2-60")
TS = load_robot("TS2-60")
TX_CORNER = (0.0, 20.0, 100.0, 0.0, 60.0, 0.0)  # the tool pointing down in front of the arm
LEG = 150.0


def fk(model, q) -> np.ndarray:
    T = np.eye(4)
    T[:3, :] = np.array(model.fk_matrix(list(q)))
    return T


def corner_joints(model) -> np.ndarray:
    if model.family == "six-axis":
        return np.array(TX_CORNER)
    T = fk(model, (0.0, 90.0, 100.0, 0.0))
    T[:3, 3] = [0.68 * model.reach_mm, 0.0, T[2, 3]]
    return np.array(model.ik(T, near=[0.0, 90.0, 100.0, 0.0])[0])


def blended_corner(model, blend, u1, u2, leave, reach, kind="movel"):
    """Two lines through the corner (150 mm before it along u1, 150 mm after it along u2), the
    first blended: the TCP positions (N, 3) along the run, the corner pose and its joints."""
    qc = corner_joints(model)
    Tc = fk(model, qc)
    Ts, Te = Tc.copy(), Tc.copy()
    Ts[:3, 3] -= LEG * np.asarray(u1, float)
    Te[:3, 3] += LEG * np.asarray(u2, float)
    q0 = np.array(model.ik(Ts, near=list(qc))[0])
    q = MotionQueue(model, q0)
    md = MDesc(blend=blend, leave=leave, reach=reach)
    if kind == "movel":
        targets = (Target.point(Tc), Target.point(Te))
    else:
        targets = (Target.joint(qc), Target.joint(np.array(model.ik(Te, near=list(qc))[0])))
    q.record(MoveCommand(kind, targets[0], md), 0.0)
    q.record(MoveCommand(kind, targets[1], MDesc(blend="off")), 0.0)
    t = q.wait_end_move(0.0)
    q.advance(t)
    times = np.linspace(0.0, t, 1201)
    Q = q.trajectory.positions(times)
    P = np.array([fk(model, x)[:3, 3] for x in Q])
    return P, Q, Tc, qc, Ts, Te


def off_documented(P, start, corner, end, u1, u2, leave, reach, curve):
    """The largest distance of the TCP from the documented path: the first line up to the leave
    point, the blend curve, the second line from the reach point."""
    on_lines = np.minimum(bref.segment_distance(P, start, corner - leave * u1),
                          bref.segment_distance(P, corner + reach * u2, end))
    return float(np.max(np.minimum(on_lines, bref.distance_to(P, curve))))


@pytest.mark.parametrize("model,u1,u2", [(TX, (0, 1, 0), (0, 0, 1)), (TX, (-1, 0, 0), (0, 1, 0)),
                                         (TS, (-1, 0, 0), (0, 1, 0)), (TS, (0, 1, 0), (1, 0, 0))])
def test_a_symmetric_cartesian_corner_is_the_parabola(model, u1, u2):
    u1, u2 = np.array(u1, float), np.array(u2, float)
    L = 70.0
    P, _, Tc, _, Ts, Te = blended_corner(model, "Cartesian", u1, u2, L, L)
    C = Tc[:3, 3]
    # the distance to the corner the document states: L·√2/4 = 24.75 mm
    assert bref.corner_distance(L, L, u1, u2) == pytest.approx(L * math.sqrt(2) / 4, abs=1e-6)
    assert float(np.min(np.linalg.norm(P - C, axis=1))) == pytest.approx(L * math.sqrt(2) / 4, abs=0.01)
    assert off_documented(P, Ts[:3, 3], C, Te[:3, 3], u1, u2, L, L, bref.parabola(C, u1, u2, L, L)) < 0.01
    # symmetric: mirrored across the bisecting plane, the curve is itself
    n = (u1 + u2) / np.linalg.norm(u1 + u2)  # normal of the mirror plane through the corner
    blend = P[np.linalg.norm(P - C, axis=1) < L * 0.9]
    mirrored = blend - 2.0 * np.outer((blend - C) @ n, n)
    assert np.max(bref.distance_to(mirrored, P)) < 0.001


@pytest.mark.parametrize("model,u1,u2,leave,reach", [(TX, (0, 1, 0), (-1, 0, 0), 70.0, 30.0),
                                                     (TX, (0, 1, 0), (0, 0, -1), 30.0, 70.0),
                                                     (TS, (1, 0, 0), (0, 1, 0), 70.0, 30.0)])
def test_an_asymmetric_cartesian_corner_is_the_parabola(model, u1, u2, leave, reach):
    u1, u2 = np.array(u1, float), np.array(u2, float)
    P, _, Tc, _, Ts, Te = blended_corner(model, "Cartesian", u1, u2, leave, reach)
    C = Tc[:3, 3]
    expected = bref.corner_distance(leave, reach, u1, u2)
    assert expected == pytest.approx(15.2729, abs=1e-4)  # 70/30 and 30/70 on perpendicular lines
    assert float(np.min(np.linalg.norm(P - C, axis=1))) == pytest.approx(expected, abs=0.01)
    curve = bref.parabola(C, u1, u2, leave, reach)
    assert off_documented(P, Ts[:3, 3], C, Te[:3, 3], u1, u2, leave, reach, curve) < 0.01


@pytest.mark.parametrize("model,u1,u2,leave,reach", [(TX, (0, 1, 0), (0, 0, 1), 70.0, 70.0),
                                                     (TX, (-1, 0, 0), (0, 1, 0), 70.0, 30.0),
                                                     (TS, (0, 1, 0), (-1, 0, 0), 70.0, 70.0)])
def test_a_joint_blend_of_two_lines_is_the_documented_joint_curve(model, u1, u2, leave, reach):
    u1, u2 = np.array(u1, float), np.array(u2, float)
    P, _, Tc, qc, Ts, Te = blended_corner(model, "joint", u1, u2, leave, reach)
    C = Tc[:3, 3]
    _, X = bref.joint_blend_of_lines(model, Tc[:3, :3], C, u1, u2, leave, reach, qc, n=4001)
    assert off_documented(P, Ts[:3, 3], C, Te[:3, 3], u1, u2, leave, reach, X) < 0.01
    assert float(np.min(np.linalg.norm(P - C, axis=1))) == pytest.approx(
        float(np.min(np.linalg.norm(X - C, axis=1))), abs=0.01)
    # in joint space the TCP is not on the Cartesian parabola, but near it (docs/motion.md: < 1 mm here)
    para = bref.parabola(C, u1, u2, leave, reach)
    assert 0.01 < off_documented(P, Ts[:3, 3], C, Te[:3, 3], u1, u2, leave, reach, para) < 1.0


def test_a_joint_blend_of_two_movej_is_the_parabola_through_the_joint_corner():
    u1, u2 = np.array((0.0, 1.0, 0.0)), np.array((0.0, 0.0, 1.0))
    _, Q, _, qc, Ts, Te = blended_corner(TX, "joint", u1, u2, 40.0, 40.0, kind="movej")
    q0 = np.array(TX.ik(Ts, near=list(qc))[0])
    q1 = np.array(TX.ik(Te, near=list(qc))[0])
    # leave and reach are TCP distances: the points of each joint line at 40 mm from the target
    fl = _fraction_at(TX, q0, qc, 40.0, from_end=True)
    fr = _fraction_at(TX, qc, q1, 40.0, from_end=False)
    ql, qr = q0 + fl * (qc - q0), qc + fr * (q1 - qc)
    w = np.linspace(0.0, 1.0, 20001)[:, None]
    curve = (1 - w) ** 2 * ql + 2 * w * (1 - w) * qc + w ** 2 * qr
    on = np.minimum(bref.segment_distance(Q, q0, ql), bref.segment_distance(Q, qr, q1))
    assert float(np.max(np.minimum(on, bref.distance_to(Q, curve)))) < 1e-3  # degrees


def _fraction_at(model, qa, qb, d, from_end):
    """The fraction of the joint line qa → qb where the TCP is d mm from its end (or start)."""
    ref = fk(model, qb if from_end else qa)[:3, 3]
    f = np.linspace(0.0, 1.0, 200001)
    pts = np.array([fk(model, qa + x * (qb - qa))[:3, 3] for x in f[::100]])
    dist = np.linalg.norm(pts - ref, axis=1)
    k = int(np.nonzero(dist >= d)[0].max() if from_end else np.nonzero(dist >= d)[0].min())
    lo, hi = (f[::100][k], f[::100][min(k + 1, len(pts) - 1)]) if from_end else (f[::100][max(k - 1, 0)], f[::100][k])
    for _ in range(60):  # bisection on the distance
        mid = (lo + hi) / 2
        dm = np.linalg.norm(fk(model, qa + mid * (qb - qa))[:3, 3] - ref)
        if (dm >= d) == from_end:
            lo = mid
        else:
            hi = mid
    return (lo + hi) / 2
