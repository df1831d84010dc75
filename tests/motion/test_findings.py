"""Motion diagnostics (R010-R019) and the runtime errors of 12.1 that go with them."""

from __future__ import annotations

import math

import numpy as np
import pytest

from val3check.motion import findings as F
from val3check.motion.commands import Target
from val3check.motion.findings import MotionError
from val3check.motion.mdesc import MDesc

from .motionhelp import HOME, KIN, ROBOT, T_HOME, movec, movej, movel, point, queue, run


def pose(q):
    return KIN.fk(np.asarray(q, dtype=float)[None])[0]


@pytest.mark.parametrize("field,value,code", [
    ("vel", -1, 100), ("vel", 0, 100), ("accel", -5, 101), ("decel", -5, 102), ("tvel", -1, 103),
    ("rvel", -1, 104), ("reach", -1, 105), ("leave", -0.5, 106), ("vel", math.nan, 100)])
def test_invalid_mdesc_fields_stop_the_instruction(field, value, code):
    q = queue()
    with pytest.raises(MotionError) as e:
        q.record(movej(HOME + [10, 0, 0, 0, 0, 0], MDesc(**{field: value}), line=7), 1.5)
    assert e.value.code == code
    f = e.value.finding
    assert f.code == F.MDESC and f.source.line == 7 and f.time == 1.5 and f.error == code
    assert q.is_empty(1.5) and q.next_id == 0


def test_mdesc_defaults_are_the_manuals():
    md = MDesc()
    assert (md.accel, md.vel, md.decel, md.tvel, md.rvel, md.blend, md.leave, md.reach) == (
        100, 100, 100, 9999, 9999, "joint", 50, 50)
    assert md.check() is None
    assert MDesc.from_fields({"tvel": 10, "leave": 2, "reach": 1, "blend": "cartesian"}, 25.4) == MDesc(
        tvel=254.0, leave=50.8, reach=25.4, blend="Cartesian")


def at_instruction(q, command, now=0.0):
    """A target the command cannot reach stops the instruction with 154 (10.6 movej: "une erreur
    d'exécution est générée ... si jPosition se situe en dehors des butées logicielles, si
    pPosition ne peut pas être atteinte"): nothing is recorded, no identifier is used, no 150
    follows, and the arm goes on with what was recorded before."""
    n = q.next_id
    with pytest.raises(MotionError) as e:
        q.record(command, now)
    f = e.value.finding
    assert e.value.code == 154 and f.error == 154
    assert q.failure is None and q.next_id == n and len(q.history) == 0 and q.is_empty(now)
    assert q.record(movej(HOME + [5, 0, 0, 0, 0, 0]), now) == n  # the next instruction records
    q.reset_motion(now)
    return f


def test_unreachable_point():
    q = queue()
    far = point(dx=2000.0, name="pFar")
    f = at_instruction(q, movej(far, line=12))
    assert f.code == F.UNREACHABLE and f.source.line == 12 and "pFar" in f.message and f.severity == "error"
    assert at_instruction(queue(), movel(far, line=13)).code == F.UNREACHABLE


def test_joint_target_outside_the_limits():
    q = queue()
    target = HOME.copy()
    target[1] = 130.0  # j2 limit 127.5
    f = at_instruction(q, movej(target, line=4))
    assert f.code == F.JOINT_LIMIT
    assert f.data["axis"] == 2 and f.data["excess_deg"] == pytest.approx(2.5)
    assert "j2" in f.message and "2.500" in f.message


def test_a_target_error_leaves_the_commands_before_it_to_the_arm():
    """movej 20 degrees beyond j1's limit after a recorded move: the task stops there with 154; the
    arm completes the move before it (recorded at 0), and nothing else."""
    q = queue()
    a = HOME + [30, 0, 0, 0, 0, 0]
    assert q.record(movej(a, MDesc(blend="joint")), 0.0) == 0
    beyond = HOME.copy()
    beyond[0] = ROBOT.joint_limits[0][1] + 20.0
    with pytest.raises(MotionError) as e:
        q.record(movej(beyond, line=5), 0.01)
    assert e.value.code == 154 and e.value.finding.data["excess_deg"] == pytest.approx(20.0)
    assert e.value.finding.data["axis"] == 1 and len(q.history) == 1 and q.failure is None
    q.wait_end_move(0.02)
    q.advance(10.0)
    assert np.allclose(q.position(10.0), a)


def test_point_reachable_only_outside_the_limits_names_the_axis():
    q = queue()
    j = HOME.copy()
    j[4] = -125.0  # below j5's limit of -121
    T = pose(j)
    f = at_instruction(q, movej(Target.point(T, ("righty" if KIN.shoulder_value(j[None])[0] < 0 else "lefty",
                                                 "epositive", "wnegative"))))
    assert f.code == F.JOINT_LIMIT and f.data["axis"] == 5 and f.data["excess_deg"] == pytest.approx(4.0, abs=1e-6)


def test_movel_path_outside_the_joint_limits_is_150_on_the_next_instruction():
    """A line behind the arm from j1 = 170 to j1 = -170: j1 would have to pass 180."""
    a = np.array([170.0, 20.0, 100.0, 0.0, 60.0, 0.0])
    b = a.copy()
    b[0] = -170.0
    q = queue(joints=a)
    i = q.record(movel(Target.point(pose(b)), line=20), 0.0)
    assert i == 0
    f = q.findings[-1]
    assert f.code == F.JOINT_LIMIT and f.error == 150 and f.source.line == 20 and f.data["axis"] == 1
    assert f.data["excess_deg"] > 0
    with pytest.raises(MotionError) as e:
        q.record(movej(a, line=21), 0.1)
    assert e.value.code == 150 and e.value.finding is None
    with pytest.raises(MotionError):
        q.wait_end_move(0.1)
    assert np.allclose(q.position(1.0), a)  # the arm never started it
    q.reset_motion(0.2)
    assert q.record(movej(a + [0, 5, 0, 0, 0, 0]), 0.2) == 0


def test_imposed_configuration_change_in_movel():
    q = queue()
    other = "righty" if KIN.shoulder_value(HOME[None])[0] >= 0 else "lefty"
    f = at_instruction(q, movel(point(dy=50.0, config=(other, "esame", "wsame")), line=9))
    assert f.code == F.CONFIG_CHANGE and f.data["field"] == "shoulder" and f.source.line == 9
    # free and same are fine
    q.record(movel(point(dy=50.0, config=("sfree", "efree", "wsame"))), 0.0)
    run(q)


def test_movel_target_only_reachable_in_another_configuration():
    """j5 ranges over [-121, 132.5]: with j5 = 125 the wrist-flipped twin (j5 = -125) is out of range."""
    start = np.array([0.0, 20.0, 100.0, 180.0, -60.0, 180.0])  # wnegative
    q = queue(joints=start)
    target = Target.point(pose([0.0, 20.0, 100.0, 0.0, 125.0, 0.0]), ("sfree", "efree", "wfree"))
    f = at_instruction(q, movel(target, line=8))
    assert f.code == F.JOINT_LIMIT and f.data["axis"] == 5
    # movej may change configuration: it goes there
    q.record(movej(target), 0.0)
    t = run(q)
    assert np.allclose(q.position(t), [0.0, 20.0, 100.0, 0.0, 125.0, 0.0], atol=1e-6)


def wrist_line(yaw_deg: float, half: float = 80.0):
    """A vertical line of the flange with the tool horizontal: the forearm is horizontal at mid-way,
    where the wrist is straight (j5 = 0) unless the tool is turned by `yaw_deg` about Z."""
    q_mid = np.array([0.0, 0.0, 90.0, 0.0, 0.0, 0.0])
    T = pose(q_mid)
    c, s = math.cos(math.radians(yaw_deg)), math.sin(math.radians(yaw_deg))
    Rz = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])
    T[:3, :3] = Rz @ T[:3, :3]
    Ta, Tb = T.copy(), T.copy()
    Ta[2, 3] += half
    Tb[2, 3] -= half
    return Ta, Tb


def start_at(Ta, ref):
    return np.asarray(__import__("val3check.robot", fromlist=["x"]).load_robot("TX2-60").point_to_joint(
        Ta[:3].tolist(), None, tuple(ref)))


def test_movel_through_the_wrist_singularity_cannot_be_followed():
    Ta, Tb = wrist_line(0.0)
    qa = start_at(Ta, [0.0, 0.0, 90.0, 0.0, 10.0, 0.0])
    assert qa[4] > 0
    q = queue(joints=qa)
    q.record(movel(Target.point(Tb), MDesc(blend="off", tvel=250), line=31), 0.0)
    f = q.findings[-1]
    assert f.code == F.SINGULAR_STOP and f.error == 150 and f.data["singularity"] == "wrist"
    assert f.data["along_mm"] == pytest.approx(80.0, abs=2.0)
    with pytest.raises(MotionError) as e:
        q.wait_end_move(0.0)
    assert e.value.code == 150


def test_movel_near_the_wrist_singularity_slows_down_with_a_warning():
    Ta, Tb = wrist_line(1.0)
    qa = start_at(Ta, [0.0, 0.0, 90.0, 0.0, 10.0, 0.0])
    q = queue(joints=qa)
    q.record(movel(Target.point(Tb), MDesc(blend="off", tvel=250), line=32), 0.0)
    t = run(q)
    warn = [f for f in q.findings if f.code == F.SINGULAR_SLOW]
    assert len(warn) == 1
    w = warn[0]
    assert w.severity == "warning" and w.source.line == 32 and w.data["singularity"] == "wrist"
    assert 0.5 < w.data["distance"] < 2.0
    assert w.data["axis"] in (4, 6) and w.data["needed_deg_s"] > w.data["limit_deg_s"]
    assert 0.0 < w.time < t
    # the path was followed, slower than 160 mm at 250 mm/s
    assert t > 160.0 / 250.0 + 0.1
    P = KIN.fk(q.trajectory.sample(0.0, t)[1])[:, :3, 3]
    assert np.abs(P[:, 0] - Ta[0, 3]).max() < 1e-3 and np.abs(P[:, 1] - Ta[1, 3]).max() < 1e-3


def test_movec_ambiguous_intermediate_point():
    q = queue()
    R = 80.0
    c = T_HOME[:3, 3] + [0, R, 0]

    def on_circle(deg):
        a = math.radians(deg)
        T = T_HOME.copy()
        T[:3, 3] = c + R * np.array([math.sin(a), -math.cos(a), 0.0])
        return Target.point(T)

    with pytest.raises(MotionError) as e:
        q.record(movec(on_circle(200.0), on_circle(270.0), line=40), 0.0)
    f = e.value.finding
    assert e.value.code == 154 and f.code == F.CIRCLE and f.data["what"] == "ambiguous"
    with pytest.raises(MotionError) as e:
        q.record(movec(point(dy=10.0), point(dy=20.0)), 0.0)  # aligned: no circle
    assert e.value.finding.data["what"] == "undefined"
    # orientation turned by 180 degrees at the intermediate point
    mid = on_circle(90.0)
    T = mid.pose.copy()
    T[:3, :3] = T[:3, :3] @ np.diag([-1.0, -1.0, 1.0])
    with pytest.raises(MotionError) as e:
        q.record(movec(Target.point(T), on_circle(180.0)), 0.0)
    assert e.value.finding.code == F.CIRCLE


def test_movec_intermediate_point_out_of_reach_stops_the_instruction():
    """10.6 movec: "une erreur d'exécution est générée ... si point pIntermédiaire (ou point pCible)
    ne peut pas être atteint": 154 at the instruction, whatever the circle."""
    f = at_instruction(queue(), movec(point(dx=900.0, dy=400.0, name="pVia"), point(dy=800.0), line=41))
    assert f.code == F.UNREACHABLE and "intermediate point pVia" in f.message and f.source.line == 41
    # the same circle through a reachable intermediate point is recorded
    q = queue()
    assert q.record(movec(point(dx=60.0, dy=60.0), point(dy=120.0)), 0.0) == 0


def test_movej_to_its_own_start_is_a_noop():
    q = queue()
    assert q.record(movej(HOME, line=3), 0.0) == 0
    f = q.findings[-1]
    assert f.code == F.NO_OP and f.severity == "info" and f.source.line == 3
    assert q.wait_end_move(0.0) == 0.0
    assert q.get_move_id(0.0) == 1
