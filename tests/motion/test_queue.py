"""The motion queue of chapter 10 in simulated time (10.2, 10.4, 10.6)."""

from __future__ import annotations

import numpy as np
import pytest

from val3check.motion.mdesc import MDesc
from val3check.motion.queue import QueueFull

from .motionhelp import HOME, KIN, OFF, T_HOME, movej, movel, point, queue, run, tcp_path

BLEND = MDesc()  # the defaults: blend joint, leave 50, reach 50


def first_time(q, pred, t0, t1, dt=0.0005):
    t = t0
    while t <= t1:
        if pred(t):
            return t
        t += dt
    return None


def test_getmoveid_example_of_10_6():
    """nIdA = 15, nIdB = 16; 15.8 is 80 % of the way to pA; after waitEndMove getMoveId() is 17."""
    q = queue()
    q.set_move_id(15)
    pA = point(dy=300.0)
    pB = point(dy=300.0, dz=150.0)
    id_a = q.record(movel(pA, BLEND), 0.0)
    id_b = q.record(movel(pB, BLEND), 0.0)
    assert (id_a, id_b) == (15, 16)
    t_end = q.wait_end_move(0.0)
    t = first_time(q, lambda t: q.get_move_id(t) >= 15.8, 0.0, t_end)
    p = KIN.fk(q.position(t)[None])[0][:3, 3]
    assert p[1] - T_HOME[1, 3] == pytest.approx(0.8 * 300.0, abs=1.0)
    t = first_time(q, lambda t: q.get_move_id(t) >= 16.572, 0.0, t_end)
    assert 16.572 <= q.get_move_id(t) < 16.58
    assert q.get_move_id(t_end) == 17
    p = KIN.fk(q.position(t_end)[None])[0][:3, 3]
    assert np.allclose(p, pB.pose[:3, 3], atol=1e-6)


def test_setmoveid_example_of_10_6():
    q = queue()
    q.record(movej(HOME + [10, 0, 0, 0, 0, 0]), 0.0)
    q.reset_motion(0.001)
    assert q.get_move_id(0.002) == 0  # nId1
    q.set_move_id(1000)
    assert q.get_move_id(0.002) == 0  # nId2
    assert q.record(movel(point(dy=100.0), BLEND), 0.002) == 1000  # nId3
    assert q.record(movel(point(dy=100.0, dz=100.0), BLEND), 0.002) == 1001  # nId4
    t = q.wait_end_move(0.002)
    assert q.get_move_id(t) == 1002  # nId5


def test_movej_returns_at_once_and_ids_increase():
    q = queue()
    ids = [q.record(movej(HOME + [10 * k, 0, 0, 0, 0, 0], BLEND), 0.0) for k in range(1, 4)]
    assert ids == [0, 1, 2]
    assert not q.is_empty(0.0)
    assert q.get_move_id(0.0) == 0.0


def u_cycle(blended: bool):
    """10.1.2.1: moveL(pDegage), moveJ(pAppro), moveL(pDepose) from pPrise."""
    q = queue()
    md = MDesc(blend="joint" if blended else "off", leave=50, reach=200)
    md2 = MDesc(blend="joint" if blended else "off", leave=200, reach=50)
    pDegage = point(dz=250.0)
    pAppro = point(dy=-300.0, dz=250.0)
    pDepose = point(dy=-300.0)
    q.record(movel(pDegage, md), 0.0)
    q.record(movej(pAppro, md2), 0.0)
    q.record(movel(pDepose, OFF), 0.0)
    return q, run(q)


def test_u_cycle_blended_is_faster_and_its_velocity_continuous():
    q_off, t_off = u_cycle(False)
    q_bl, t_bl = u_cycle(True)
    assert t_bl < t_off
    assert t_bl < 0.9 * t_off
    times, Q, Qd = q_bl.trajectory.sample(0.0, t_bl)
    jumps = np.abs(np.diff(Qd, axis=0)) / 0.004
    assert np.all(jumps <= np.array(KIN.accels) * 1.05)
    # unblended: the arm stops at pDegage and pAppro
    for c, p in zip(q_off.history, (point(dz=250.0), point(dy=-300.0, dz=250.0))):
        assert q_off.get_speed(None, c.t_done) == pytest.approx(0.0, abs=1e-6)
        assert np.allclose(KIN.fk(q_off.position(c.t_done)[None])[0][:3, 3], p.pose[:3, 3], atol=1e-6)
    # blended: the arm leaves pDegage's line 50 mm before it and never reaches the point
    t, P, v = tcp_path(q_bl, 0.0, t_bl)
    assert np.linalg.norm(P - point(dz=250.0).pose[:3, 3], axis=1).min() > 5.0


def test_the_arm_waits_at_the_leave_point_for_the_next_command():
    q = queue()
    pA = point(dy=300.0)
    id_a = q.record(movel(pA, MDesc(leave=50, reach=50)), 0.0)
    q.advance(5.0)
    p = KIN.fk(q.position(5.0)[None])[0][:3, 3]
    assert p[1] - T_HOME[1, 3] == pytest.approx(250.0, abs=1e-4)  # stopped at the leave point
    assert q.is_settled(5.0) and not q.is_empty(5.0)
    assert id_a < q.get_move_id(5.0) < id_a + 1
    q.record(movel(point(dy=300.0, dz=100.0), OFF), 5.0)
    t = run(q, 5.0)
    p = KIN.fk(q.position(t)[None])[0][:3, 3]
    assert np.allclose(p, point(dy=300.0, dz=100.0).pose[:3, 3], atol=1e-6)
    # the arm passed near pA on the blend, not through it
    _, P, _ = tcp_path(q, 5.0, t)
    assert np.linalg.norm(P - pA.pose[:3, 3], axis=1).min() > 1.0


def test_waitendmove_cancels_the_blend_of_the_last_command():
    q = queue()
    pA = point(dy=300.0)
    q.record(movel(pA, BLEND), 0.0)
    t = run(q)
    assert np.allclose(KIN.fk(q.position(t)[None])[0][:3, 3], pA.pose[:3, 3], atol=1e-6)
    assert q.is_empty(t)


def test_late_program_the_arm_slows_at_the_leave_point_then_blends():
    q = queue()
    q.record(movel(point(dy=300.0), BLEND), 0.0)
    t_stop = q.profile.t_end
    q.record(movel(point(dy=300.0, dz=200.0), OFF), 0.5 * t_stop)  # recorded while it moves
    t = run(q, 0.5 * t_stop)
    _, Q, Qd = q.trajectory.sample(0.0, t)
    speed = np.linalg.norm(Qd, axis=1)
    assert speed[5:-5].min() > 0.0  # it never stopped between the two lines


def test_is_settled_50_ms_after_the_end():
    q = queue()
    q.record(movej(HOME + [30, 0, 0, 0, 0, 0]), 0.0)
    t = run(q)
    assert q.is_empty(t)
    assert not q.is_settled(t + 0.049)
    assert q.is_settled(t + 0.0501)
    assert not q.is_settled(t / 2)
    assert queue().is_settled(0.0)  # before any motion the arm is at rest


def test_stopmove_stops_on_the_path_and_restartmove_resumes():
    q = queue()
    target = HOME + [120, 0, 0, 0, 0, 0]
    q.record(movej(target), 0.0)
    q.stop_move(0.2)
    t_stop = q.profile.t_end
    assert t_stop > 0.2
    p_stop = q.position(t_stop)
    assert np.allclose(q.position(1.0), p_stop)
    assert np.allclose((p_stop - HOME)[1:], 0.0)  # on the joint line
    assert q.wait_end_move(1.0) is None and q.blocked_reason().startswith("stopMove")
    q.restart_move(1.0)
    t = q.wait_end_move(1.0)
    assert np.allclose(q.position(t), target)


def test_resetmotion_cancels_and_resets_the_ids():
    q = queue()
    q.record(movej(HOME + [120, 0, 0, 0, 0, 0]), 0.0)
    q.record(movej(HOME), 0.0)
    q.reset_motion(0.2)
    t = q.profile.t_end
    assert q.is_empty(t) and q.get_move_id(t) == 0
    stop = q.position(t)
    assert q.record(movej(stop + [0, 10, 0, 0, 0, 0]), t) == 0
    t2 = run(q, t)
    assert np.allclose(q.position(t2), stop + [0, 10, 0, 0, 0, 0])


def test_resetmotion_with_a_start_position_adds_a_connection_move():
    q = queue()
    q.reset_motion(0.0, HOME + [0, 0, 0, 0, 0, 30])
    q.record(movej(HOME + [20, 0, 0, 0, 0, 30]), 0.0)
    t = run(q)
    kinds = [c.kind for c in q.history]
    assert kinds == ["connection", "movej"]
    assert np.allclose(q.position(t), HOME + [20, 0, 0, 0, 0, 30])
    # the connection is at reduced speed: 10 % of the nominal joint speed
    _, _, Qd = q.trajectory.sample(0.0, q.history[0].t_done)
    assert np.abs(Qd[:, 5]).max() <= 1445 * 0.1 * (1 + 1e-9)


def test_commands_wait_for_arm_power():
    q = queue(powered=False)
    q.record(movej(HOME + [30, 0, 0, 0, 0, 0]), 0.0)
    assert q.wait_end_move(0.0) is None
    assert q.blocked_reason() == "the arm is not powered"
    assert np.allclose(q.position(3.0), HOME)
    q.set_power(True, 3.0)
    t = q.wait_end_move(3.0)
    assert t > 3.0 and np.allclose(q.position(t), HOME + [30, 0, 0, 0, 0, 0])


def test_a_full_queue_blocks_until_a_command_is_done():
    q = queue(capacity=4)
    for k in range(4):
        assert q.record(movej(HOME + [5 * (k + 1), 0, 0, 0, 0, 0]), 0.0) == k
    r = q.record(movej(HOME), 0.0)
    assert isinstance(r, QueueFull)
    assert r.until == pytest.approx(q.history[0].t_done or q.profile.time_at(q.history[0].placement.s_end))
    assert q.record(movej(HOME), r.until) == 4


def test_monitor_speed_change_takes_effect_at_once():
    q = queue()
    target = HOME + [150, 0, 0, 0, 0, 0]
    q.record(movej(target), 0.0)
    t_full = q.profile.t_end
    q.set_monitor_speed(25.0, 0.15)
    t = run(q)
    assert t > t_full + 0.3
    _, _, Qd = q.trajectory.sample(0.6, t)
    assert np.abs(Qd[:, 0]).max() <= 435 * 0.25 * (1 + 1e-6)
    assert np.allclose(q.position(t), target)


def test_getspeed_is_the_tcp_speed():
    q = queue()
    q.record(movel(point(dy=400.0), MDesc(blend="off", tvel=300.0)), 0.0)
    t = run(q)
    assert q.get_speed(None, t / 2) == pytest.approx(300.0, rel=1e-4)
    assert q.get_speed(None, t) == pytest.approx(0.0, abs=1e-3)


def test_next_event_and_advance():
    q = queue()
    q.record(movej(HOME + [30, 0, 0, 0, 0, 0]), 0.0)
    t_done = q.trajectory.profile.time_at(q.history[0].placement.s_end)
    assert q.next_event(0.0) == pytest.approx(t_done)
    assert q.next_time(0) == int(np.ceil(t_done * 1e6 - 1e-6))
    q.advance(t_done)
    assert q.is_empty(t_done)
    assert q.next_event(t_done) == pytest.approx(t_done + 0.05)
    assert q.next_event(t_done + 0.05) is None


def test_a_scara_arm_moves_too():
    """RS/TS arms: four axes (axis 3 prismatic), configuration (shoulder,) (9.7.5)."""
    from val3check.motion.commands import MoveCommand, Target
    from val3check.motion.kin import ArmKin
    from val3check.motion.queue import MotionQueue
    from val3check.robot import load_robot

    ts = load_robot("TS2-60")
    kin = ArmKin(ts)
    q0 = np.array([30.0, 60.0, 100.0, 0.0])
    T0 = kin.fk(q0[None])[0]

    def at(dx, dy, dz):
        T = T0.copy()
        T[:3, 3] += [dx, dy, dz]
        return Target.point(T)

    q = MotionQueue(ts, q0)
    q.record(MoveCommand("movel", at(0, 0, -50), MDesc(blend="joint", leave=20, reach=20)), 0.0)
    q.record(MoveCommand("movel", at(-150, -100, -50), MDesc(blend="off", tvel=500)), 0.0)
    t = run(q)
    P = kin.fk(q.position(t)[None])[0][:3, 3]
    assert np.allclose(P - T0[:3, 3], [-150, -100, -50], atol=1e-6)
    assert q.position(t)[2] == pytest.approx(50.0)  # the prismatic axis moved 50 mm
    _, Q, _ = q.trajectory.sample(q.history[1].placement.s_begin and 0.0, t)
    path = kin.fk(Q)[:, :3, 3]
    assert path[:, 2].min() >= T0[2, 3] - 50 - 1e-6


def test_monitor_speed_0_holds_the_arm_on_its_path_and_nothing_fails():
    """8.1: setMonitorSpeed accepts 0 to 100. At 0 every limit would be 0: the arm stops on its
    path (with the decelerations it had) and holds until the monitor speed rises (issue 21 J)."""
    target = HOME + [150, 0, 0, 0, 0, 0]  # 0.6 s: at 0.2 s the arm still accelerates
    q = queue()
    q.record(movej(target), 0.0)
    t_free = q.wait_end_move(0.0)
    q = queue()
    q.record(movej(target), 0.0)
    q.set_monitor_speed(0.0, 0.2)
    assert q.wait_end_move(0.25) is None and q.blocked_reason().startswith("the monitor speed is 0 %")
    t_stop = q.profile.t_end  # braked on the path
    held = q.position(t_stop)
    assert 0.2 < t_stop < 0.5 and np.allclose(q.position(3.0), held) and not q.is_empty(3.0)
    assert q.get_speed(None, 1.0) == 0.0 and q.next_event(3.0) is None
    # a command recorded while at 0 waits too; the queue is not full
    assert q.record(movej(HOME), 1.0) == 1 and np.allclose(q.position(3.0), held)
    q.set_monitor_speed(100.0, 3.0)
    t = run(q, 3.0)
    assert np.allclose(q.position(t), HOME) and q.findings == []
    assert t > 3.0 + t_free * 0.5  # it went on from where it held: the rest of the way, then back
    # started at 0 %: nothing moves until it rises
    q = queue(monitor=0.0)
    q.record(movej(target), 0.0)
    assert q.wait_end_move(0.0) is None and np.allclose(q.position(5.0), HOME)
    q.set_monitor_speed(50.0, 5.0)
    t = run(q, 5.0)
    assert np.allclose(q.position(t), target) and t > 5.0 + t_free
