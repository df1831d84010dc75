"""Chapter 10 end to end: applications in the Stäubli layout run by `val3check sim` (simulate()
and the command line), checked against analytic figures (bang-bang times, straight lines,
circles) and the manual's stated results (10.6), never against what the code prints."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from interpretation.simsupport import build, code_pos, codes, errors, gv, out, sim
from val3check.cli import main
from val3check.motion.kin import ArmKin
from val3check.robot import load_robot

TX = load_robot("TX2-60")
KIN = ArmKin(TX)
V = np.array(TX.nominal_speeds)
A = np.array(TX.accelerations)
HOME = "{0, 20, 100, 0, 60, 0}"  # tool pointing down in front of the arm


def bang_bang(d: float, v: float, a: float, dec: float) -> float:
    """Time-optimal rest-to-rest motion over d with speed v, acceleration a, deceleration dec."""
    d = abs(d)
    if d >= v * v / (2 * a) + v * v / (2 * dec):
        return d / v + v / (2 * a) + v / (2 * dec)
    peak = math.sqrt(2 * d * a * dec / (a + dec))
    return peak / a + peak / dec


def run(tmp_path, code, globals_=(), robot=TX, **kw):
    return sim(tmp_path, code, globals_=globals_, robot=robot, **kw)


def motions(r):
    return [m for m in r.motion.motions if m.id is not None]


# ---- timing of movej (10.3) ----------------------------------------------------------------------


@pytest.mark.parametrize("delta,vel,accel,decel", [
    ((90, 0, 0, 0, 0, 0), 100, 100, 100),
    ((90, 0, 0, 0, 0, 0), 50, 30, 70),
    ((2, 0, 0, 0, 0, 0), 100, 100, 100),  # a triangle
    ((90, -40, 60, 120, -30, 200), 100, 100, 100),
    ((10, -40, 60, 20, -30, 50), 35, 20, 60),
])
def test_movej_is_timed_at_the_bang_bang_limit_of_its_slowest_axis(tmp_path, delta, vel, accel, decel):
    r = run(tmp_path, f"""begin
  jA = herej()
  jB = jA + {{{', '.join(str(x) for x in delta)}}}
  mD.vel = {vel}
  mD.accel = {accel}
  mD.decel = {decel}
  movej(jB, flange, mD)
  waitEndMove()
  nAt = clock()
  jEnd = herej()
end
""", ["joint jA", "joint jB", "joint jEnd", "mdesc mD", "num nAt"])
    assert codes(r) == []
    (m,) = motions(r)
    expected = max(bang_bang(d, v * vel / 100, a * accel / 100, a * decel / 100)
                   for d, v, a in zip(delta, V, A) if d)
    assert m.duration == pytest.approx(expected, rel=1e-9, abs=1e-9)
    assert list(gv(r, "jEnd").values()) == pytest.approx(list(delta), abs=1e-9)
    # the program waited until the end of the motion: the 4 ms tick at or after it (clock():
    # milliseconds)
    assert m.end - 0.001 <= gv(r, "nAt") <= m.end + 0.004 + 0.001
    # the 4 ms samples never exceed the limits of any axis
    _, Q, Qd = r.motion.sample()
    assert np.all(np.abs(Qd) <= V * vel / 100 * (1 + 1e-9))


def test_monitor_speed_scales_every_limit(tmp_path):
    r = run(tmp_path, """begin
  movej({90, 0, 0, 0, 0, 0}, flange, mD)
  waitEndMove()
end
""", ["mdesc mD"], scenario="[controller]\nmonitor_speed = 40\n")
    (m,) = motions(r)
    assert m.duration == pytest.approx(bang_bang(90, V[0] * 0.4, A[0] * 0.4, A[0] * 0.4), rel=1e-9)


# ---- movel, movec (10.1.1, 10.1.4) ---------------------------------------------------------------


def test_movel_at_its_tvel_limit(tmp_path):
    r = run(tmp_path, f"""begin
  movej({HOME}, flange, mD)
  waitEndMove()
  pA = here(flange, world)
  pB = compose(pA, world, {{0, -300, 0, 0, 0, 0}})
  mD.tvel = 250
  movel(pB, flange, mD)
  waitEndMove()
  pEnd = here(flange, world)
end
""", ["point pA", "point pB", "point pEnd", "mdesc mD"])
    assert codes(r) == []
    line = motions(r)[1]
    assert line.kind == "movel" and line.dominant_limit == "tvel"
    assert line.length_mm == pytest.approx(300.0, abs=1e-3)
    assert line.peak_tcp_mm_s == pytest.approx(250.0, rel=1e-4)
    # at 250 mm/s with joint accelerations of ~1500 deg/s²: the ramps take a few hundredths of a second
    # a trapezoid of TCP speed: ramps under joint accelerations, the rest at tvel; its area is
    # the length of the line
    share = line.limit_seconds
    cruise = share["tvel"]
    ramps = sum(v for k, v in share.items() if k != "tvel")
    assert line.duration == pytest.approx(cruise + ramps, abs=1e-9)
    assert 250 * cruise + 250 * ramps / 2 == pytest.approx(300.0, rel=2e-3)
    assert ramps < 0.2
    t, Q, Qd = r.motion.sample(line.start, line.end)
    P = KIN.fk(Q)[:, :3, 3]
    p0 = np.array([gv(r, "pA")["trsf"][k] for k in "xyz"])
    p1 = np.array([gv(r, "pB")["trsf"][k] for k in "xyz"])
    assert np.allclose(p1 - p0, [0, -300, 0], atol=1e-9)
    u = (p1 - p0) / np.linalg.norm(p1 - p0)
    off = (P - p0) - np.outer((P - p0) @ u, u)
    assert np.linalg.norm(off, axis=1).max() < 0.01  # straight within 10 µm
    h = 1e-6
    speed = np.linalg.norm(KIN.fk(Q + h * Qd)[:, :3, 3] - KIN.fk(Q - h * Qd)[:, :3, 3], axis=1) / (2 * h)
    assert speed.max() <= 250 * (1 + 1e-6)
    assert gv(r, "pEnd")["trsf"]["y"] == pytest.approx(gv(r, "pB")["trsf"]["y"], abs=1e-6)


def test_half_circle_movec(tmp_path):
    R = 80.0
    r = run(tmp_path, f"""begin
  movej({HOME}, flange, mD)
  waitEndMove()
  pA = here(flange, world)
  pMid = compose(pA, world, {{{R}, {R}, 0, 0, 0, 0}})
  pEnd = compose(pA, world, {{0, {2 * R}, 0, 0, 0, 0}})
  mD.tvel = 300
  movec(pMid, pEnd, flange, mD)
  waitEndMove()
end
""", ["point pA", "point pMid", "point pEnd", "mdesc mD"])
    assert codes(r) == []
    arc = motions(r)[1]
    assert arc.kind == "movec" and arc.length_mm == pytest.approx(math.pi * R, rel=1e-4)
    assert arc.peak_tcp_mm_s == pytest.approx(300.0, rel=1e-3)
    _, Q, _ = r.motion.sample(arc.start, arc.end)
    P = KIN.fk(Q)[:, :3, 3]
    pA = np.array([gv(r, "pA")["trsf"][k] for k in "xyz"])
    centre = pA + [0, R, 0]
    assert np.abs(np.linalg.norm(P - centre, axis=1) - R).max() < 0.01
    assert np.abs(P[:, 2] - pA[2]).max() < 0.01  # in its plane
    assert P[:, 0].max() == pytest.approx(pA[0] + R, abs=0.05)  # through the intermediate point
    end = KIN.fk(r.motion.trajectory.position(arc.end)[None])[0, :3, 3]
    assert np.allclose(end, pA + [0, 2 * R, 0], atol=1e-6)


# ---- blending: the U cycle of 10.1.2.1 ----------------------------------------------------------------

U_CYCLE = f"""begin
  movej({HOME}, flange, mD)
  waitEndMove()
  pPrise = here(flange, world)
  pDegage = compose(pPrise, world, {{0, 0, 150, 0, 0, 0}})
  pAppro = compose(pPrise, world, {{0, -250, 150, 0, 0, 0}})
  pDepose = compose(pPrise, world, {{0, -250, 0, 0, 0, 0}})
  mDesc.blend = BLEND
  mDesc.leave = 50
  mDesc.reach = 200
  moveL(pDegage, tOutil, mDesc)
  mDesc.leave = 200
  mDesc.reach = 50
  moveJ(pAppro, tOutil, mDesc)
  mDesc.blend = off
  moveL(pDepose, tOutil, mDesc)
  waitEndMove()
end
"""
U_GLOBALS = ["point pPrise", "point pDegage", "point pAppro", "point pDepose", "mdesc mDesc", "mdesc mD",
             "tool tOutil"]


def _u_cycle(tmp_path, blend):
    r = run(tmp_path / blend, U_CYCLE.replace("BLEND", blend), U_GLOBALS)
    assert codes(r) == []
    m = motions(r)[1:]
    start, end = m[0].start, m[-1].end
    _, Q, Qd = r.motion.sample(start, end)
    P = KIN.fk(Q)[:, :3, 3]
    p = {n: np.array([gv(r, n)["trsf"][k] for k in "xyz"]) for n in ("pDegage", "pAppro", "pDepose")}
    return r, end - start, P, Qd, p


def test_u_cycle_with_and_without_blending(tmp_path):
    r_off, t_off, P_off, Qd_off, p = _u_cycle(tmp_path, "off")
    r_on, t_on, P_on, Qd_on, _ = _u_cycle(tmp_path, "joint")
    # without blending the arm stops at pDegage and pAppro (10.1.2.1)
    traj = r_off.motion.trajectory
    for name, m in zip(("pDegage", "pAppro"), motions(r_off)[1:3]):
        at = KIN.fk(traj.position(m.end)[None])[0, :3, 3]
        assert np.linalg.norm(at - p[name]) < 1e-6 and np.abs(traj.velocity(m.end)).max() < 1e-6
    # with blending it does not stop and does not pass through them, and the cycle is shorter
    assert t_on < 0.9 * t_off
    speed = np.abs(Qd_on[5:-5]).max(axis=1)
    assert speed.min() > 1.0
    d_degage = np.linalg.norm(P_on - p["pDegage"], axis=1).min()
    d_appro = np.linalg.norm(P_on - p["pAppro"], axis=1).min()
    assert 1.0 < d_degage < 50.0 and 1.0 < d_appro < 50.0
    # the leave point of the first line: the arm leaves it 50 mm before pDegage (sampled every
    # 0.1 ms: the blend leaves the line tangentially, 1 µm off within a millimetre)
    _, Q, _ = r_on.motion.sample(motions(r_on)[1].start, motions(r_on)[2].end, dt=1e-4)
    P = KIN.fk(Q)[:, :3, 3]
    on_line = np.linalg.norm(P[:, :2] - p["pDegage"][:2], axis=1) < 1e-3
    assert P[on_line, 2].max() == pytest.approx(p["pDegage"][2] - 50.0, abs=1.0)
    # and it ends exactly on pDepose
    end = KIN.fk(r_on.motion.trajectory.position(motions(r_on)[-1].end)[None])[0, :3, 3]
    assert np.allclose(end, p["pDepose"], atol=1e-6)


def test_a_blended_chain_is_never_slower_than_the_same_commands_unblended(tmp_path):
    """Very different leave and reach (the case 10.1.2.3 warns about): still no slower."""
    code = U_CYCLE.replace("mDesc.leave = 50\n  mDesc.reach = 200", "mDesc.leave = 5\n  mDesc.reach = 120")
    times = {}
    for blend in ("off", "joint", "Cartesian"):
        r = run(tmp_path / blend, code.replace("BLEND", blend), U_GLOBALS)
        m = motions(r)[1:]
        times[blend] = m[-1].end - m[0].start
    assert times["joint"] <= times["off"] * (1 + 1e-9)
    assert times["Cartesian"] <= times["off"] * (1 + 1e-9)


# ---- identifiers (10.6) ----------------------------------------------------------------------------------


def test_getmoveid_example_of_10_6(tmp_path):
    r = run(tmp_path, f"""begin
  movej({HOME}, flange, mD)
  waitEndMove()
  resetMotion()
  setMoveId(15)
  pA = compose(here(flange, world), world, {{0, -200, 0, 0, 0, 0}})
  pB = compose(pA, world, {{0, 0, 100, 0, 0, 0}})
  mDesc.blend = off
  mDesc.tvel = 250
  nIdA = movel(pA, tOutil, mDesc)
  nIdB = movel(pB, tOutil, mDesc)
  wait(getMoveId() >= 15.8)
  pAt = here(tOutil, world)
  waitEndMove()
  nId = getMoveId()
end
""", ["point pA", "point pB", "point pAt", "mdesc mDesc", "mdesc mD", "tool tOutil", "num nIdA", "num nIdB",
      "num nId"])
    assert codes(r) == []
    assert (gv(r, "nIdA"), gv(r, "nIdB"), gv(r, "nId")) == (15.0, 16.0, 17.0)
    # "quand getMoveId() est 15.8, la position du robot se trouve à 80 % du mouvement vers pA"
    # (within the 4 ms the wait takes to see it: at most 250 mm/s x 4 ms = 1 mm further)
    y0 = gv(r, "pA")["trsf"]["y"] + 200
    along = y0 - gv(r, "pAt")["trsf"]["y"]
    assert 160.0 <= along <= 161.0 + 1e-6


def test_setmoveid_example_of_10_6(tmp_path):
    r = run(tmp_path, f"""begin
  movej({HOME}, flange, mD)
  waitEndMove()
  pA = compose(here(flange, world), world, {{0, -100, 0, 0, 0, 0}})
  pB = compose(pA, world, {{0, 0, 100, 0, 0, 0}})
  resetMotion()
  nId1 = getMoveId()
  setMoveId(1000)
  nId2 = getMoveId()
  nId3 = movel(pA, tOutil, mDesc)
  nId4 = movel(pB, tOutil, mDesc)
  waitEndMove()
  nId5 = getMoveId()
end
""", ["point pA", "point pB", "mdesc mDesc", "mdesc mD", "tool tOutil"] + [f"num nId{i}" for i in range(1, 6)])
    assert codes(r) == []
    assert [gv(r, f"nId{i}") for i in range(1, 6)] == [0, 0, 1000, 1001, 1002]


# ---- mdesc (10.5, 12.1) ------------------------------------------------------------------------------


def test_mdesc_defaults(tmp_path):
    r = run(tmp_path, "begin\nend\n", ["mdesc mD"])
    assert gv(r, "mD") == {"accel": 100, "vel": 100, "decel": 100, "tvel": 9999, "rvel": 9999, "blend": "joint",
                           "leave": 50, "reach": 50}


@pytest.mark.parametrize("field,value,code", [("vel", -1, 100), ("accel", 0, 101), ("decel", -5, 102),
                                              ("tvel", -1, 103), ("rvel", 0, 104), ("reach", -1, 105),
                                              ("leave", -2, 106)])
def test_invalid_mdesc_stops_the_instruction(tmp_path, field, value, code):
    r = run(tmp_path, f"begin\n  mD.{field} = {value}\n  movej({HOME}, flange, mD)\n  putln(\"no\")\nend\n",
            ["mdesc mD"])
    assert out(r) == []
    (d,) = r.diagnostics
    assert (d.code, d.error, d.task) == ("R017", code, "Example~")
    assert (d.line, d.col) == code_pos(r, 3, 3) and d.time_us is not None
    assert f"error {code}" in d.message and field in d.message


# ---- what the arm cannot do, reported at its line with the time and the task ------------------------------


def _one(r, code):
    (d,) = [d for d in r.diagnostics if d.code == code]
    return d


def test_unreachable_target_is_reported_at_its_line(tmp_path):
    r = run(tmp_path, """begin
  delay(0.5)
  pFar.trsf = {1500, 0, 200, 0, 180, 0}
  movel(pFar, flange, mD)
  waitEndMove()
end
""", ["point pFar", "mdesc mD"])
    (d,) = r.diagnostics  # 10.6 movel: "si pPosition ne peut pas être atteinte": at the movel
    assert d.code == "R010" and (d.line, d.col) == code_pos(r, 4, 3) and d.task == "Example~"
    assert d.time_us >= 500_000 and d.error == 154 and "error 154" in d.message


def test_joint_limit_violation_names_the_axis(tmp_path):
    r = run(tmp_path, "begin\n  movej({0, 130, 0, 0, 0, 0}, flange, mD)\n  waitEndMove()\nend\n", ["mdesc mD"])
    d = _one(r, "R011")
    assert (d.line, d.col) == code_pos(r, 2, 3) and "j2" in d.message and "2.500" in d.message


def test_imposed_configuration_change(tmp_path):
    r = run(tmp_path, f"""begin
  movej({HOME}, flange, mD)
  waitEndMove()
  pA = compose(here(flange, world), world, {{0, 50, 0, 0, 0, 0}})
  cA = config(herej())
  pA.config = cA
  pA.config.shoulder = righty
  movel(pA, flange, mD)
  waitEndMove()
end
""", ["point pA", "config cA", "mdesc mD"])
    assert gv(r, "cA")["shoulder"] == "lefty"
    d = _one(r, "R012")
    assert (d.line, d.col) == code_pos(r, 8, 3) and "righty" in d.message and "10.1.4.2" in d.message


def test_path_near_a_wrist_singularity_is_a_warning(tmp_path):
    r = run(tmp_path, """begin
  pMid = jointToPoint(flange, world, {0, 0, 90, 0, 0, 0})
  pMid = appro(pMid, {0, 0, 0, 1, 0, 0})
  pA = compose(pMid, world, {0, 0, 80, 0, 0, 0})
  pB = compose(pMid, world, {0, 0, -80, 0, 0, 0})
  pA.config = {ssame, esame, wpositive}
  movej(pA, flange, mD)
  mD.tvel = 250
  movel(pB, flange, mD)
  waitEndMove()
end
""", ["point pMid", "point pA", "point pB", "mdesc mD"])
    d = _one(r, "R014")
    assert (d.line, d.col) == code_pos(r, 9, 3) and d.task == "Example~"
    line = motions(r)[1]
    assert line.start < d.time_us / 1e6 < line.end  # when the arm passes it
    assert "wrist" in d.message and line.duration > 160 / 250 + 0.1


# ---- tools, power, cycles ------------------------------------------------------------------------------------


def test_close_waits_for_the_end_of_motion_then_ctime(tmp_path):
    r = run(tmp_path, """begin
  tGrip.ctime = 0.3
  movej({90, 0, 0, 0, 0, 0}, tGrip, mD)
  close(tGrip)
  nAt = clock()
end
""", ["tool tGrip", "mdesc mD", "num nAt"])
    (m,) = motions(r)
    (ev,) = r.tool_events
    assert ev.action == "close" and ev.tool == "tGrip" and m.end <= ev.time_us / 1e6 <= m.end + 0.004
    assert gv(r, "nAt") == pytest.approx(ev.time_us / 1e6 + 0.3, abs=0.004)


def test_the_run_starts_powered_and_the_scenario_can_start_it_unpowered(tmp_path):
    code = "begin\n  movej({30, 0, 0, 0, 0, 0}, flange, mD)\n  waitEndMove()\n  nAt = clock()\nend\n"
    r = run(tmp_path / "a", code, ["mdesc mD", "num nAt"])
    assert codes(r) == [] and gv(r, "nAt") < 0.5
    r = run(tmp_path / "b", code.replace("begin\n", "begin\n  enablePower()\n"), ["mdesc mD", "num nAt"],
            scenario="[controller]\npowered = false\n")
    assert codes(r) == [] and gv(r, "nAt") >= 0.5  # enablePower: 0.5 s, then the motion
    assert 0.5 <= motions(r)[0].start <= 0.504 + 1e-6  # the power comes at the 4 ms cycle
    r = run(tmp_path / "c", code, ["mdesc mD", "num nAt"], scenario="[controller]\npowered = false\n")
    d = _one(r, "R018")
    assert "powered = true" in d.message and "enablePower" in d.message and "waitEndMove" in d.message


def test_cycle_time_and_cycles_option(tmp_path):
    code = f"""begin
  movej({HOME}, flange, mD)
  pA = here(flange, world)
  while true
    movej({{20, 20, 100, 0, 60, 0}}, flange, mD)
    movej({{-20, 20, 100, 0, 60, 0}}, flange, mD)
    waitEndMove()
    delay(0.1)
  endWhile
end
"""
    r = run(tmp_path / "a", code, ["mdesc mD", "point pA"], duration=5.0)
    st = r.motion.cycles["Example~"]
    one = bang_bang(40, V[0], A[0], A[0])  # each move: 40 degrees of axis 1
    # a cycle: two moves (no blend: the second returns), the wait to the next tick, 0.1 s
    # (the first pass starts in the blend from the move before the loop: from the second on)
    assert st.count >= 3
    for t in st.times[1:]:
        assert 2 * one + 0.1 <= t <= 2 * one + 0.1 + 0.004 + 1e-6
    r = run(tmp_path / "b", code, ["mdesc mD", "point pA"], duration=60.0, cycles=2)
    assert r.end_reason == "cycles" and r.motion.cycles["Example~"].count == 2
    assert "R006" not in codes(r)  # stop() ran and ended
    assert r.sim_time_us / 1e6 < 3 * (2 * one + 0.2) + 1.0


def test_json_report_has_the_motion_and_the_4ms_trajectory(tmp_path, capsys):
    folder = build(tmp_path, f"""begin
  movej({HOME}, flange, mD)
  waitEndMove()
  delay(0.2)
  movej({{10, 20, 100, 0, 60, 0}}, flange, mD)
  waitEndMove()
end
""", globals_=["mdesc mD"])
    assert main(["sim", str(folder), "--robot", "TX2-60", "--report", "json"]) == 0
    text = capsys.readouterr().out
    assert "e-0" not in text and "e-1" not in text  # plain decimals
    data = json.loads(text)
    assert data["version"] == 2
    mo = data["motion"]
    assert [m["kind"] for m in mo["motions"]] == ["movej", "movej"]
    traj = mo["trajectory"]
    assert traj["period"] == 0.004 and traj["axes"] == 6 and len(traj["segments"]) == 2
    seg = traj["segments"][1]
    assert seg["positions"][0] == [0.0, 20.0, 100.0, 0.0, 60.0, 0.0]
    assert seg["positions"][-1] == [10.0, 20.0, 100.0, 0.0, 60.0, 0.0]
    assert seg["velocities"][0] == [0.0] * 6 and seg["velocities"][-1] == [0.0] * 6
    assert max(abs(v[0]) for v in seg["velocities"]) <= TX.nominal_speeds[0]
    assert seg["start"] == pytest.approx(seg["first_tick"] * 0.004)
    m2 = mo["motions"][1]
    assert seg["start"] <= m2["start"] and m2["end"] <= seg["start"] + 0.004 * (len(seg["positions"]) - 1)
    assert main(["sim", str(folder), "--robot", "TX2-60", "--report", "json"]) == 0
    assert capsys.readouterr().out == text  # deterministic


def test_text_summary_leads_with_cycle_time_and_motion_diagnostics(tmp_path, capsys):
    folder = build(tmp_path, f"""begin
  while true
    movej({HOME}, flange, mD)
    movej({{1000, 0, 0, 0, 0, 0}}, flange, mD)
    waitEndMove()
  endWhile
end
""", globals_=["mdesc mD"])
    main(["sim", str(folder), "--robot", "TX2-60", "--duration", "3"])
    text = capsys.readouterr().out
    lines = text.splitlines()
    assert lines[1].startswith("arm model: TX2-60")
    first = next(i for i, s in enumerate(lines) if "R011" in s)
    assert first < next(i for i, s in enumerate(lines) if s.startswith("tasks:"))


def test_getjointforce_is_the_inverse_dynamics_when_the_model_has_masses(tmp_path):
    from val3check.robot import from_urdf
    from val3check.robot.catalog import example_robot_urdf

    code = """begin
  movej({0, -60, 80, -90, -90, 0}, flange, mD)
  waitEndMove()
  getJointForce(nForce)
end
"""
    r = run(tmp_path / "tx", code, ["mdesc mD", "num nForce[6]"])
    assert codes(r) == ["R002"] and "masses" in r.diagnostics[0].message  # Stäubli: not public
    urdf = example_robot_urdf("ur_description/urdf/ur5_robot.urdf")
    if urdf is None:
        pytest.skip("example-robot-data is not installed")
    import pinocchio as pin

    ur5 = from_urdf(urdf, world_frame="base_link", flange_frame="tool0")
    r = run(tmp_path / "ur5", code, ["mdesc mD", "num nForce[6]"], robot=ur5)
    assert codes(r) == []
    model, data = ur5.pinocchio()
    g = pin.computeGeneralizedGravity(model, data, np.radians([0, -60, 80, -90, -90, 0]))
    assert gv(r, "nForce") == pytest.approx(list(g), abs=1e-6)


# ---- monitor speed 0 (8.1: 0 to 100; issue 21 J) -----------------------------------------------------------


def test_a_scenario_setting_the_monitor_speed_to_0_during_a_motion_holds_the_arm(tmp_path):
    code = "begin\n  movej({150, 0, 0, 0, 0, 0}, flange, mD)\n  waitEndMove()\n  nAt = clock()\n  jEnd = herej()\nend\n"
    r = run(tmp_path, code, ["mdesc mD", "num nAt", "joint jEnd"],
            scenario="[controller]\nchanges = [{ at = 0.2, monitor_speed = 0 }, { at = 2.0, monitor_speed = 100 }]\n")
    assert codes(r) == [] and r.end_reason == "ended"
    assert list(gv(r, "jEnd").values()) == pytest.approx([150, 0, 0, 0, 0, 0], abs=1e-9)
    assert gv(r, "nAt") > 2.0  # it went on when the monitor speed rose
    q1, q2 = r.motion.trajectory.position(0.6), r.motion.trajectory.position(1.9)
    assert np.allclose(q1, q2) and 0.0 < q1[0] < 150.0  # held on its path in between
    _, _, Qd = r.motion.sample()
    assert np.all(np.abs(Qd) <= V * (1 + 1e-9))


def test_set_monitor_speed_0_in_the_program_holds_the_arm_and_is_no_error(tmp_path):
    code = """begin
  movej({150, 0, 0, 0, 0, 0}, flange, mD)
  delay(0.2)
  nRet = setMonitorSpeed(0)
  delay(1)
  jHeld = herej()
  nSpeed = getSpeed(flange)
  nRet2 = setMonitorSpeed(100)
  waitEndMove()
  jEnd = herej()
end
"""
    r = run(tmp_path, code, ["mdesc mD", "num nRet", "num nRet2", "num nSpeed", "joint jHeld", "joint jEnd"],
            scenario="[controller]\nworking_mode = 4\n")
    assert codes(r) == [] and errors(r) == [] and r.end_reason == "ended"
    assert gv(r, "nRet") == 0 and gv(r, "nRet2") == 0 and gv(r, "nSpeed") == 0
    assert 0.0 < gv(r, "jHeld")["j1"] < 150.0
    assert gv(r, "jEnd")["j1"] == pytest.approx(150.0, abs=1e-9)


def test_a_motion_the_monitor_speed_0_never_allows_is_a_deadlock_that_says_why(tmp_path):
    r = run(tmp_path, "begin\n  movej({30, 0, 0, 0, 0, 0}, flange, mD)\n  waitEndMove()\nend\n", ["mdesc mD"],
            scenario="[controller]\nmonitor_speed = 0\n")
    assert r.end_reason == "deadlock"
    d = _one(r, "R003")
    assert "monitor speed is 0 %" in d.message and "monitor_speed" in d.message
    assert np.allclose(r.motion.trajectory.position(r.sim_time_us / 1e6), 0.0)
