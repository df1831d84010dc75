"""11.2 ALTER: alterable moves altered in real time on the 4 ms setpoints, in a frame (fixed in the
world) or a tool (moving with the tool centre point), by the program's alter() or the scenario's
conveyor and offsets, with the safety rules of 11.2.3-11.2.4; the trajectory, the reports and the
collision checks see the altered path. Checked against hand-computed straight lines."""

from __future__ import annotations

import math

import numpy as np
import pytest
from interpretation.simsupport import codes, gv, sim

from val3check.robot import load_robot

TX = load_robot("TX2-60")
TICK = 0.004
LICENCE = "version = 1\n[options]\nalter = true\n"
HOME = "{0, 20, 100, 0, 60, 0}"
TRACK = {"track": {"code": """begin
  while true
    nT = nT + 1
    nAlt = alter({nT * 0.1, 0, 0, 0, 0, 0})
    if nAlt == 1
      nOk = nT
    endIf
    delay(0)
  endWhile
end
"""}}
G = ["mdesc mD", "mdesc mAlter", "point pA", "point pB", "point pEnd", "point pMid", "num nId", "num nBegin",
     "num nEnd", "num nT", "num nAlt", "num nOk", "bool bOver", "frame fRef", "tool tRef", "num nStop", "num nStop2",
     "num nStop3", "num nAlt2", "bool bEmpty", "num nId2", "joint jA", "joint jEnd"]


def run(tmp_path, body, scenario=LICENCE, **kw):
    return sim(tmp_path, "begin\n  mD.blend = off\n  movej(" + HOME + ", flange, mD)\n  waitEndMove()\n"
               "  pA = here(flange, world)\n" + body + "end\n", globals_=G, robot=TX, programs=TRACK,
               scenario=scenario, **kw)


def flange(q) -> np.ndarray:
    m = np.eye(4)
    m[:3, :4] = np.array(TX.fk_matrix(q))
    return m


def xyz(p) -> np.ndarray:
    return np.array([p["trsf"][k] for k in ("x", "y", "z")])


def test_alter_from_a_synchronous_task_draws_a_straight_line_at_25_mm_s(tmp_path):
    """The nominal path stands still (a move of 0.001 mm, enough to start alter mode: 11.2.5);
    a 4 ms synchronous task calls alter({0.1·n, 0, 0, ...}): each value applies from the next
    setpoint, so the flange goes along world x by exactly 0.1 mm per setpoint."""
    r = run(tmp_path, """  pB = appro(pA, {0, 0.001, 0, 0, 0, 0})
  nId = alterMovel(pB, flange, mD)
  nBegin = alterBegin(world, mAlter)
  taskCreateSync "track", 0.004, bOver, track()
  delay(0.4)
  nEnd = alterEnd()
  delay(0.1)
  pEnd = here(flange, world)
  taskKill("track")
""")
    assert codes(r) == []
    assert gv(r, "nBegin") == 1 and gv(r, "nEnd") == 1
    a = xyz(gv(r, "pA"))
    # the path: on the line through A along x, 0.1 mm further at each setpoint
    traj = r.motion.trajectory
    times = np.arange(math.ceil(0.6 / TICK), math.floor(0.9 / TICK)) * TICK
    P = np.array([flange(traj.position(t)) for t in times])
    assert np.abs(P[:, 1, 3] - a[1] - 0.001).max() < 1e-9 and np.abs(P[:, 2, 3] - a[2]).max() < 1e-9
    steps = np.diff(P[:, 0, 3])
    moving = steps > 1e-9
    assert np.abs(steps[moving] - 0.1).max() < 1e-9 and moving.sum() > 50
    assert np.abs(P[:, :3, :3] - flange(traj.position(0.5))[:3, :3]).max() < 1e-9  # no rotation
    # between setpoints: the joints are interpolated (the amplifiers): within 1 µm of the line
    mids = np.array([flange(traj.position(t + TICK / 2)) for t in times[:40]])
    assert np.abs(mids[:, 1:3, 3] - a[1:3] - [0.001, 0]).max() < 1e-3
    # alterEnd keeps the alteration in force: the flange stays where the last alter() put it
    assert xyz(gv(r, "pEnd")) == pytest.approx(a + [0.1 * gv(r, "nOk"), 0.001, 0], abs=1e-6)
    # alter() after alterEnd: -1 (not started or over)
    assert gv(r, "nAlt") == -1


@pytest.mark.parametrize("move,kind", [
    ("alterMovel(pB, flange, mD)", "movel"),
    ("alterMovej(pB, flange, mD)", "movej"),
    ("alterMovec(pMid, pB, flange, mD)", "movec"),
])
def test_an_altered_path_follows_a_conveyor_of_the_scenario(tmp_path, move, kind):
    """alterMovel (alterMovej, alterMovec: the same rule) from A to B (200 mm along y), the
    scenario's conveyor at 50 mm/s along world x from the start of alter mode: at each setpoint the
    flange is the nominal one plus 50 mm/s × the time since alter mode began."""
    body = """  pB = appro(pA, {0, 200, 0, 0, 0, 0})
  pMid = appro(pA, {0, 100, 40, 0, 0, 0})
  nId = """ + move + """
  nBegin = alterBegin(world, mAlter)
  waitEndMove()
  nEnd = alterEnd()
  pEnd = here(flange, world)
"""
    nominal = run(tmp_path / "n", body.replace("  nBegin = alterBegin(world, mAlter)\n", ""))
    r = run(tmp_path / "a", body, scenario=LICENCE + "[[alterations]]\nconveyor = [50, 0, 0]\n")
    assert codes(r) == [] and gv(r, "nBegin") == 1
    (m,) = [m for m in r.motion.motions if m.id == 1]
    (mn,) = [m for m in nominal.motion.motions if m.id == 1]
    assert m.kind == mn.kind == kind
    assert m.start == mn.start and m.end == pytest.approx(mn.end)  # waitEndMove: the nominal end (11.2.2)
    times = np.arange(math.ceil(m.start / TICK), math.floor(m.end / TICK) + 1) * TICK
    alt = np.array([flange(r.motion.trajectory.position(t))[:3, 3] for t in times])
    nom = np.array([flange(nominal.motion.trajectory.position(t))[:3, 3] for t in times])
    d = alt - nom
    assert np.abs(d[:, 1:]).max() < 1e-6  # only along x
    t_m = times[0] - d[0, 0] / 50.0  # when alter mode began
    assert m.start - 1e-9 <= t_m <= m.start + TICK
    assert np.abs(d[:, 0] - 50.0 * (times - t_m)).max() < 1e-6
    # alterEnd: the conveyor's offset in force stays: the arm ends beyond B by it
    b = xyz(gv(nominal, "pEnd"))
    assert xyz(gv(r, "pEnd"))[1:] == pytest.approx(b[1:], abs=1e-6)
    assert xyz(gv(r, "pEnd"))[0] - b[0] == pytest.approx(50.0 * (math.ceil((m.end + 1e-9) / TICK) * TICK - t_m),
                                                        abs=0.21)


@pytest.mark.parametrize("ref,alteration,expected", [
    # a frame turned 90° about z: its x is the world's y
    ("fRef.trsf = {100, 0, 0, 0, 0, 90}\n  nBegin = alterBegin(fRef, mAlter)", "{10, 0, 0, 0, 0, 0}", (0, 10, 0)),
    # a tool on the flange, pointing down (the flange's z is down): its z is the world's -z
    ("tRef.trsf = {0, 0, 50, 0, 0, 0}\n  nBegin = alterBegin(tRef, mAlter)", "{0, 0, 5, 0, 0, 0}", (0, 0, -5)),
    # a rotation about the frame's centre: the flange 100 mm from it along world x turns to y
    ("fRef.trsf = {pA.trsf.x - 100, pA.trsf.y, pA.trsf.z, 0, 0, 0}\n  nBegin = alterBegin(fRef, mAlter)",
     "{0, 0, 0, 0, 0, 2}", "turn"),
])
def test_the_alteration_is_in_the_reference_frame_or_tool(tmp_path, ref, alteration, expected):
    r = run(tmp_path, f"""  pB = appro(pA, {{0, 0.001, 0, 0, 0, 0}})
  jA = herej()
  nId = alterMovel(pB, flange, mD)
  {ref}
  delay(0.1)
  nAlt = alter({alteration})
  delay(0.1)
  pEnd = here(flange, world)
  jEnd = herej()
""")
    assert codes(r) == [] and gv(r, "nBegin") == 1 and gv(r, "nAlt") == 1
    a, e = xyz(gv(r, "pA")), xyz(gv(r, "pEnd"))
    if expected == "turn":
        c, s = math.cos(math.radians(2)), math.sin(math.radians(2))
        centre = a - [100, 0, 0]
        v = a + [0, 0.001, 0] - centre  # the nominal flange (after the 0.001 mm move) from the centre
        turned = centre + np.array([c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]])
        assert e == pytest.approx(turned, abs=1e-9)
        rz = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])  # the flange turned 2° about world z
        ra, re = (flange(list(gv(r, n).values()))[:3, :3] for n in ("jA", "jEnd"))
        assert np.abs(re - rz @ ra).max() < 1e-9
    else:
        assert e - a == pytest.approx(np.array(expected) + [0, 0.001, 0], abs=1e-6)


def test_too_fast_an_alteration_stops_the_arm_at_its_last_valid_position(tmp_path):
    """alterBegin's mdesc: tvel 20 mm/s; the conveyor goes at 50 mm/s: at the first setpoint that
    would move the flange faster the arm stops on the previous one, alter mode is in error (alter:
    -3), the next motion instruction stops with 150; after resetMotion the arm goes on from where
    it stopped."""
    body = """  mAlter.tvel = 20
  pB = appro(pA, {0, 0.001, 0, 0, 0, 0})
  nId = alterMovel(pB, flange, mD)
  nBegin = alterBegin(world, mAlter)
  delay(0.2)
  nAlt = alter({0, 0, 0, 0, 0, 0})
  nStop = alterStopTime()
  pMid = here(flange, world)
  resetMotion()
  nAlt2 = alter({0, 0, 0, 0, 0, 0})
  movej(""" + HOME + """, flange, mD)
  waitEndMove()
  pEnd = here(flange, world)
"""
    r = run(tmp_path, body, scenario=LICENCE + "[[alterations]]\nconveyor = [50, 0, 0]\n")
    (d,) = [d for d in r.diagnostics if d.code == "R055"]
    assert "tvel 20" in d.message
    assert gv(r, "nAlt") == -3 and gv(r, "nAlt2") == -1 and gv(r, "nStop") == 0
    # a step of 50 mm/s × 4 ms = 0.2 mm is refused: the arm stays on the last setpoint, the first
    # of the session, less than one step along x from where it was
    a = xyz(gv(r, "pA"))
    mid = xyz(gv(r, "pMid")) - a
    assert mid[1:] == pytest.approx([0.001, 0], abs=1e-9) and -1e-9 <= mid[0] < 0.2 * 0.5
    assert xyz(gv(r, "pEnd")) == pytest.approx(a, abs=1e-9)
    r2 = run(tmp_path / "b", body.replace("  resetMotion()\n", ""), scenario=LICENCE + "[[alterations]]\nconveyor = "
             "[50, 0, 0]\n")
    assert [t.error for t in r2.tasks if t.error] == [150]


def test_a_move_after_the_alterable_trajectory_waits_for_alter_end(tmp_path):
    """11.2.3: the first non-alterable move after an alterable trajectory is computed only after
    alterEnd: while alter mode is on the arm waits at the end of the alterable move; alterEnd
    records it (with the identifier the instruction returned) and the arm goes from its altered
    position to its target."""
    body = """  pB = appro(pA, {0, 100, 0, 0, 0, 0})
  nId = alterMovel(pB, flange, mD)
  nBegin = alterBegin(world, mAlter)
  nAlt = alter({0, 0, 3, 0, 0, 0})
  nId2 = movej(""" + HOME + """, flange, mD)
  delay(1.5)
  bEmpty = isEmpty()
  pMid = here(flange, world)
  nEnd = alterEnd()
  waitEndMove()
  pEnd = here(flange, world)
"""
    r = run(tmp_path, body, scenario=LICENCE + "[[alterations]]\ntrsf = [0, 0, 3, 0, 0, 0]\nat = 0\n")
    assert codes(r) == []
    assert gv(r, "nId") == 1 and gv(r, "nId2") == 2 and gv(r, "bEmpty") is False
    b = xyz(gv(r, "pA")) + [0, 100, 0]
    assert xyz(gv(r, "pMid")) == pytest.approx(b + [0, 0, 6], abs=1e-6)  # the program's 3 mm and the scenario's
    assert xyz(gv(r, "pEnd")) == pytest.approx(xyz(gv(r, "pA")), abs=1e-9)
    last = next(m for m in r.motion.motions if m.id == 2)
    assert last.state == "done" and last.start >= 1.5
    # without alterEnd the program waits for ever, and the report says why
    r = run(tmp_path / "b", body.replace("  nEnd = alterEnd()\n", ""), duration=5,
            scenario=LICENCE)
    (d,) = [d for d in r.diagnostics if d.code == "R003"]
    assert "alterEnd()" in d.message


def test_a_stop_condition_gives_the_alteration_alter_stop_time_then_locks_it(tmp_path):
    """stopMove with the alteration moving at 10 mm/s along x (a conveyor) and alterBegin's decel
    at 10 %: alterStopTime is the time to stop that joint speed with 10 % of the nominal
    decelerations, then 0: alter() returns 0 and the alteration is locked until restartMove."""
    r = run(tmp_path, """  mAlter.decel = 10
  pB = appro(pA, {0, 0.001, 0, 0, 0, 0})
  nId = alterMovel(pB, flange, mD)
  nBegin = alterBegin(world, mAlter)
  delay(0.2)
  nStop = alterStopTime()
  stopMove()
  delay(0.008)
  nStop2 = alterStopTime()
  delay(1)
  nStop3 = alterStopTime()
  nAlt = alter({0, 0, 0, 0, 0, 0})
  pMid = here(flange, world)
  delay(0.5)
  pEnd = here(flange, world)
  nAlt2 = alterStopTime()
  restartMove()
  delay(0.1)
""", scenario=LICENCE + "[[alterations]]\nconveyor = [10, 0, 0]\n")
    assert gv(r, "nStop") == -1 and gv(r, "nStop3") == 0 and gv(r, "nAlt") == 0 and gv(r, "nAlt2") == 0
    # the conveyor went on while the alteration was locked: when the motion restarts, the
    # alteration would jump to it at once, far beyond any speed: the arm stops in error (11.2.3:
    # "Un changement important de l'altération ne peut être appliqué que progressivement")
    (d,) = [d for d in r.diagnostics if d.code == "R055"]
    assert d.time_us / 1e6 > 1.2
    # the conveyor moves joint 1 (mostly) at 10 mm/s: the time to stop it at 10 % decel is small
    # but not 0, and it decreases
    assert 0 < gv(r, "nStop2") < 0.05
    # locked: the flange does not follow the conveyor any more
    assert xyz(gv(r, "pEnd")) == pytest.approx(xyz(gv(r, "pMid")), abs=1e-9)


def test_the_collision_checks_see_the_altered_path(tmp_path):
    """A sphere 5 mm clear of the arm on the nominal straight line, on the side the scenario moves
    the path 10 mm to: no contact on the nominal path, a contact on the altered one."""
    F = flange((0, 20, 100, 0, 60, 0))
    middle = F[:3, 3] + [0, 100, 0]
    body = """  pB = appro(pA, {0, 200, 0, 0, 0, 0})
  nId = alterMovel(pB, flange, mD)
  nBegin = alterBegin(world, mAlter)
  waitEndMove()
  nEnd = alterEnd()
"""

    def cell(d: float) -> str:
        path = tmp_path / f"cell{d:g}.toml"
        c = middle + [d, 0, 0]
        path.write_text(f'version = 1\n[[obstacle]]\nname = "pin"\nshape = "sphere"\nradius = 8\n'
                        f'at = {{ x = {c[0]}, y = {c[1]}, z = {c[2]} }}\n', encoding="utf-8")
        return str(path)

    def clearance(r) -> float:
        (m,) = [m for m in r.motion.motions if m.kind == "movel"]
        return m.clearance.min_clearance.mm

    d = 200.0
    for k in range(4):  # place it 5 mm clear of the nominal path
        d -= clearance(run(tmp_path / f"p{k}", body, cell=cell(d), collisions=True)) - 5.0
    nominal = run(tmp_path / "n", body, cell=cell(d), collisions=True)
    assert "R031" not in codes(nominal) and clearance(nominal) == pytest.approx(5.0, abs=0.5)
    r = run(tmp_path / "a", body, cell=cell(d), collisions=True,
            scenario=LICENCE + "[[alterations]]\ntrsf = [10, 0, 0, 0, 0, 0]\nat = 0.45\nramp = 0.1\n")
    assert codes(r) == ["R031"]


def test_alter_instructions_before_alter_begin_and_without_the_option(tmp_path):
    r = run(tmp_path, """  nAlt = alter({1, 0, 0, 0, 0, 0})
  nEnd = alterEnd()
  nStop = alterStopTime()
  nBegin = alterBegin(world, mAlter)
  nAlt2 = alterBegin(world, mAlter)
""")
    assert gv(r, "nAlt") == -1 and gv(r, "nEnd") == -1 and gv(r, "nStop") == 0
    assert gv(r, "nBegin") == 0 and gv(r, "nAlt2") == -1  # waits for an alterable move; already started
    r = run(tmp_path / "b", "  nBegin = alterBegin(world, mAlter)\n  nAlt = alter({1, 0, 0, 0, 0, 0})\n",
            scenario="version = 1\n[options]\nalter = false\n")
    assert gv(r, "nBegin") == -2 and gv(r, "nAlt") == -2


@pytest.mark.parametrize("text,line", [
    ("[[alterations]]\nat = 1\n", 2),
    ("[[alterations]]\nconveyor = [1, 2]\n", 3),
    ("[[alterations]]\ntrsf = [1, 2, 3]\n", 3),
    ("[[alterations]]\nconveyor = [1, 0, 0]\nat = 2\nuntil = 1\n", 5),
    ("[[alterations]]\ntrsf = [0, 0, 1, 0, 0, 0]\nramp = -1\n", 4),
])
def test_bad_alterations_are_scenario_errors_with_their_line(tmp_path, text, line):
    from val3check.simulation.scenario import ScenarioError

    with pytest.raises(ScenarioError) as exc:
        run(tmp_path, "", scenario="version = 1\n" + text)
    assert exc.value.line == line


def test_a_second_alterable_trajectory_is_altered_from_its_own_start(tmp_path):
    """Two alterable trajectories, each with its alter mode (alterBegin ... alterEnd), a movej
    between them: the first ends 2 mm up (its offset then decreases to nothing along the movej);
    the second starts on its nominal path and ends 3 mm along x, nothing of the first left."""
    r = run(tmp_path, """  pB = appro(pA, {0, 50, 0, 0, 0, 0})
  nId = alterMovel(pB, flange, mD)
  nBegin = alterBegin(world, mAlter)
  delay(0.05)
  nAlt = alter({0, 0, 2, 0, 0, 0})
  waitEndMove()
  nEnd = alterEnd()
  nId2 = movej(""" + HOME + """, flange, mD)
  waitEndMove()
  jA = herej()
  delay(0.2)
  nId = alterMovel(pB, flange, mD)
  nT = alterBegin(world, mAlter)
  delay(0.05)
  nAlt2 = alter({3, 0, 0, 0, 0, 0})
  waitEndMove()
  delay(0.05)
  pEnd = here(flange, world)
  nOk = alterEnd()
""", scenario=LICENCE)
    assert codes(r) == []
    assert gv(r, "nBegin") == 1 and gv(r, "nT") == 1 and gv(r, "nAlt") == 1 and gv(r, "nAlt2") == 1
    assert gv(r, "nEnd") == 1 and gv(r, "nOk") == 1
    assert list(gv(r, "jA").values()) == pytest.approx([0, 20, 100, 0, 60, 0], abs=1e-9)
    b = xyz(gv(r, "pA")) + [0, 50, 0]
    assert xyz(gv(r, "pEnd")) == pytest.approx(b + [3, 0, 0], abs=1e-6)
    # the run's record: the movej ends at HOME, the second alterable move leaves from the nominal
    # start (nothing of the first session)
    (m1, m2) = [m for m in r.motion.motions if m.kind == "movel"]
    (mj,) = [m for m in r.motion.motions if m.id == 2]
    assert r.motion.trajectory.position(mj.end) == pytest.approx([0, 20, 100, 0, 60, 0], abs=1e-9)
    assert r.motion.trajectory.position((mj.end + m2.start) / 2) == pytest.approx([0, 20, 100, 0, 60, 0], abs=1e-9)
    # from the end of the first alterable move the offset left (2 mm up) only decreases
    tr = r.motion.trajectory
    for t in np.linspace(m1.end, mj.end, 200):
        dz = xyz_of(tr.position(t))[2] - xyz_of(tr.nominal.position(t))[2]
        assert -1e-4 <= dz <= 2 + 1e-4  # (linear in the joints between setpoints: 1e-5 mm off)
    t = math.ceil(m2.start / TICK) * TICK + 0.002
    assert xyz_of(r.motion.trajectory.position(t))[2] == pytest.approx(xyz(gv(r, "pA"))[2], abs=1e-6)


def xyz_of(q) -> np.ndarray:
    return flange(q)[:3, 3]


def test_the_trace_shows_the_altered_path(tmp_path):
    """The MCAP trace (read back): its joint states are the altered path's at every sampled time,
    the nominal line moved along x by the scenario's conveyor (50 mm/s) while alter mode is on."""
    import json

    from mcap.reader import make_reader

    from val3check.config import Settings
    from val3check.reporting.mcap_trace import write_trace
    from val3check.reporting.sim_report import build_report
    from val3check.rules.catalogue import catalogue

    body = """  pB = appro(pA, {0, 200, 0, 0, 0, 0})
  nId = alterMovel(pB, flange, mD)
  nBegin = alterBegin(world, mAlter)
  waitEndMove()
  nEnd = alterEnd()
"""
    nominal = run(tmp_path / "n", body.replace("  nBegin = alterBegin(world, mAlter)\n", ""))
    r = run(tmp_path / "a", body, scenario=LICENCE + "[[alterations]]\nconveyor = [50, 0, 0]\n")
    assert codes(r) == [] and gv(r, "nBegin") == 1
    path = tmp_path / "run.mcap"
    write_trace(build_report(r, Settings(), catalogue(), "test"), str(path))
    with open(path, "rb") as f:
        states = [(msg.log_time / 1e9, json.loads(msg.data)["position"])
                  for _, ch, msg in make_reader(f).iter_messages() if ch.topic == "/joint_states"]
    (m,) = [m for m in r.motion.motions if m.id == 1]
    inside = [(t, q) for t, q in states if m.start + TICK < t < m.end]
    assert len(inside) > 20
    d = np.array([flange(q)[:3, 3] - flange(nominal.motion.trajectory.position(t))[:3, 3] for t, q in inside])
    times = np.array([t for t, _ in inside])
    assert np.abs(d[:, 1:]).max() < 1e-6
    t_m = times[0] - d[0, 0] / 50.0  # when alter mode began
    assert m.start - 1e-9 <= t_m <= m.start + TICK
    assert np.abs(d[:, 0] - 50.0 * (times - t_m)).max() < 1e-3  # (linear in the joints between setpoints)


def test_a_null_move_after_the_alteration_is_said_not_hidden(tmp_path):
    """After alterEnd the arm is off the nominal end by the alteration; a movej to that nominal end
    moves the arm on the controller (computed from where it is, 11.2.3) but is null in the nominal
    plan: the run says so (R052, once) rather than showing it as a move."""
    body = """  pB = appro(pA, {0, 50, 0, 0, 0, 0})
  nId = alterMovel(pB, flange, mD)
  nBegin = alterBegin(world, mAlter)
  nAlt = alter({0, 0, 2, 0, 0, 0})
  waitEndMove()
  nEnd = alterEnd()
  nId2 = movej(pB, flange, mD)
  waitEndMove()
"""
    r = run(tmp_path, body)
    (d,) = [d for d in r.diagnostics if d.code == "R052"]
    assert "computed from the altered position" in d.message and d.line > 0
    # a move that goes somewhere carries the offset away along its path: nothing said
    r = run(tmp_path / "b", body.replace("movej(pB, flange, mD)", "movej(" + HOME + ", flange, mD)"))
    assert "R052" not in codes(r)
