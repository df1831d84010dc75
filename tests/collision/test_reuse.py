"""The checks of a motion that repeats exactly are computed once (issue 29; docs/cell.md, "How checks
are sampled"), and only then: each input of the key changed in turn gives a new result, and a
reused result is the one a fresh check gives."""

from __future__ import annotations

import math

import numpy as np
import pytest

from val3check.collision import Cell, Obstacle, Part, Shape, ToolSolid  # noqa: E402
from val3check.collision.cellfile import trsf_matrix  # noqa: E402
from val3check.motion.paths import JointLine, Path, Span
from val3check.motion.trajectory import Profile, Trajectory
from val3check.simulation.own_clock import Q_S, own_clock, own_times

from .helpers import ARM, ROBOT, TOOL, MotionSpan, checker, line_motion

TOP = -100.0  # the table's top
BRICK = 40.0
A = (300.0, -150.0, 50.0)  # the TCP passes 150 mm over the ball: its jaws 100 mm from it
B = (300.0, 150.0, 50.0)
BALL = (300.0, 0.0, -100.0, 0, 0, 0)


def _cell() -> Cell:
    c = Cell(path="test", margin_mm=5.0)
    c.obstacles.append(Obstacle("table", Shape("box", (400.0, 800.0, 40.0)), "world",
                                trsf_matrix((500.0, 0.0, TOP - 20.0, 0, 0, 0))))
    c.obstacles.append(Obstacle("ball", Shape("sphere", (20.0,)), "fBall", np.eye(4)))
    for side in (-1, 1):
        c.tools.append(ToolSolid(f"jaw {side}", "tTool", Shape("box", (10.0, 30.0, 30.0)),
                                 trsf_matrix((side * 25.0, 0.0, 15.0, 0, 0, 0))))
    c.parts.append(Part("brick", "tTool", "close", Shape("box", (BRICK, BRICK, BRICK)), trsf_matrix((0, 0, 20, 0, 0, 0))))
    return c


def _own(a, b, v=200.0):
    """A motion on its own clock: (times from 0, joints)."""
    return line_motion(a, b, v)


def _same(r1, r2, shift: float) -> None:
    """Two reports of one motion, the second `shift` s later."""
    assert np.allclose(r2.times, r1.times + shift, rtol=0.0, atol=1e-12)
    assert np.array_equal(r2.clearance, r1.clearance) and np.array_equal(r2.exact, r1.exact)
    m1, m2 = r1.min_clearance, r2.min_clearance
    assert (m1 is None) == (m2 is None)
    if m1 is not None:
        assert (m2.mm, m2.body_a, m2.body_b, m2.point_a, m2.point_b) == (m1.mm, m1.body_a, m1.body_b, m1.point_a,
                                                                         m1.point_b)
        assert m2.time == pytest.approx(m1.time + shift, abs=1e-12)
    assert [(c.body_a, c.body_b, c.point, c.depth_mm, c.kind) for c in r2.contacts] == \
        [(c.body_a, c.body_b, c.point, c.depth_mm, c.kind) for c in r1.contacts]
    assert r2.too_close == r1.too_close and r2.checks == r1.checks


def test_a_repeated_motion_in_the_same_scene_is_checked_once_and_as_a_fresh_check_would():
    frames = {"fBall": BALL}
    chk = checker(_cell(), frames=frames)
    T, Q = _own(A, B)
    first = chk.check_own(MotionSpan(0), 1.0, T, Q, key="AB")
    made = chk.measurements
    again = chk.check_own(MotionSpan(5), 7.3, T, Q, key="AB")
    assert chk.reused == 1 and chk.measurements == made  # nothing measured the second time
    assert again.motion.id == 5 and again.start == pytest.approx(7.3)
    _same(first, again, 6.3)
    fresh = checker(_cell(), frames=frames).check_own(MotionSpan(5), 7.3, T, Q, key="AB")
    _same(fresh, again, 0.0)
    m = first.min_clearance
    assert "ball" in m.body_b and 95.0 < m.mm < 110.0 and not first.too_close


def _changed(chk, frames, tools, what: str) -> None:
    """Change one input of the check between two runs of the motion AB."""
    if what == "frame moved":
        frames["fBall"] = (300.0, 0.0, -90.0, 0, 0, 0)
    elif what == "tool pose":
        tools["tTool"] = (0.0, 0.0, 130.0, 0.0, 0.0, 0.0)
    elif what == "part carried":
        chk.gripper("tTool", "close", 2.0, joints=_own(A, B)[1][-1])
    elif what == "part left in the cell":
        T, Q = _own((300.0, 60.0, TOP + BRICK + 60.0), (300.0, 60.0, TOP + BRICK))  # its top 80 mm under the jaws
        chk.check_own(MotionSpan(1), 2.0, T, Q, key="down")
        chk.gripper("tTool", "close", 2.5, joints=Q[-1])
        chk.gripper("tTool", "open", 2.6, joints=Q[-1])
    elif what == "margin":
        chk.margin = 150.0


@pytest.mark.parametrize("what", ["frame moved", "tool pose", "part carried", "part left in the cell", "margin"])
def test_each_input_of_the_scene_changed_gives_a_new_result(what):
    frames = {"fBall": BALL}
    tools = {"tTool": TOOL}
    chk = checker(_cell(), frames=frames, tools=tools)
    T, Q = _own(A, B)
    before = chk.check_own(MotionSpan(0), 1.0, T, Q, key="AB")
    _changed(chk, frames, tools, what)
    n = chk.reused
    after = chk.check_own(MotionSpan(0), 3.0, T, Q, key="AB")
    assert chk.reused == n, what
    b, a = before.min_clearance, after.min_clearance
    assert (a.mm, a.body_a, a.body_b, after.too_close) != (b.mm, b.body_a, b.body_b, before.too_close), what


def test_the_touch_allowances_are_part_of_the_scene_and_end_as_in_a_fresh_check():
    # a brick taken 1 mm into the table (a teaching error): allowed to touch until lifted apart
    pick = (350.0, -150.0, TOP + BRICK - 1.0)
    above = (pick[0], pick[1], pick[2] + 60.0)
    chk = checker(_cell(), frames={"fBall": (0.0, 0.0, 2000.0, 0, 0, 0)})
    down, up = _own(above, pick), _own(pick, above)

    def cycle(t: float):
        chk.check_own(MotionSpan(1), t, *down, key="down")
        chk.gripper("tTool", "close", t + 1.0, joints=down[1][-1])
        assert chk.world.allowed  # the brick and the table touch
        r = chk.check_own(MotionSpan(2), t + 1.1, *up, key="up")
        assert not chk.world.allowed  # apart at the end of the lift: checked from then on
        chk.gripper("tTool", "open", t + 2.0, joints=up[1][-1])
        chk.clear_parts("brick")  # taken away: the scene is the one the cycle started in
        return r

    first = cycle(0.0)
    n = chk.reused
    second = cycle(10.0)
    assert chk.reused == n + 2 and first.first_contact is None
    _same(first, second, 10.0)
    # the same lift without the allowance (the brick put there, not grasped there): another result
    chk.check_own(MotionSpan(3), 30.0, *down, key="down")
    chk.gripper("tTool", "close", 31.0, joints=down[1][-1])
    chk.world.allowed.clear()
    n = chk.reused
    third = chk.check_own(MotionSpan(2), 31.1, *up, key="up")
    assert chk.reused == n and third.starts_in_collision is not None


def test_another_arm_geometry_gives_a_new_result():
    from dataclasses import replace

    from val3check.robot import dh as _dh
    from val3check.robot.absolute import with_dh
    from val3check.simulation.collision_run import _geometry_epochs

    nominal = _dh.nominal_dh(ROBOT)
    longer = with_dh(ROBOT, replace(nominal, a=tuple(v + (20.0 if k == 2 else 0.0) for k, v in enumerate(nominal.a))))
    arm, epochs = _geometry_epochs(ROBOT, [(10.0, longer)])
    from val3check.collision import CollisionChecker

    chk = CollisionChecker(arm, _cell(), frames={"fBall": BALL}, tools={"tTool": TOOL})
    T, Q = _own(A, B)
    epochs.at(1.0)
    before = chk.check_own(MotionSpan(0), 1.0, T, Q, key="AB")
    epochs.at(11.0)  # setDH (11.4): the same joints put the arm elsewhere
    after = chk.check_own(MotionSpan(0), 11.0, T, Q, key="AB")
    assert chk.reused == 0 and after.min_clearance.mm != before.min_clearance.mm
    assert ARM is not arm


# ---- the motion's own clock and its key --------------------------------------------------------------


def _run_of(moves, starts):
    """A trajectory of joint lines [(geometry, speed)] started at `starts` (s): a trapezoid-free
    profile (constant acceleration up to half way, then down)."""
    q0 = moves[0][0].q0
    path, prof = Path(q0), Profile(0.0, 0.0)
    out = []
    for (geom, v), t0 in zip(moves, starts):
        off = path.append(Span(geom, 0.0, 1.0))
        ell = geom.ell
        prof.append(t0, np.array([off, off + 0.5 * ell, off + ell]), np.array([0.0, v, 0.0]))
        out.append((t0, prof.t_end))
    return Trajectory(path, prof), out


def test_the_same_motion_at_another_time_and_path_position_has_the_same_key_and_samples():
    out_, back = JointLine([0, 0, 90, 0, 45, 0], [40, 10, 80, 5, 50, 30]), None
    back = JointLine(out_.q1, out_.q0)
    slow_back = back  # the same curve, timed slower
    traj, spans = _run_of([(out_, 100.0), (back, 100.0), (out_, 100.0), (slow_back, 60.0)],
                          [0.3, 2.1013, 3.7007, 5.55])
    own = [own_clock(traj, a, b) for a, b in spans]
    assert own[0].key == own[2].key and own[0].key is not None
    assert np.array_equal(own[0].times, own[2].times) and np.array_equal(own[0].joints, own[2].joints)
    assert own[0].joints[0] == pytest.approx(out_.q0) and own[0].joints[-1] == pytest.approx(out_.q1)
    assert own[1].key != own[0].key  # another curve
    assert own[3].key != own[1].key  # the same curve, another timing
    assert not np.array_equal(own[3].joints[: len(own[1].joints)], own[1].joints)
    # the samples are every 4 ms from the motion's start, then its end
    a, b = spans[2]
    assert own[2].times[1] == pytest.approx(0.004) and own[2].times[-1] == pytest.approx(b - a, abs=1e-9)
    # what the checks sample is the trajectory, to the key's rounding
    assert np.abs(own[2].joints - traj.positions(a + own[2].times)).max() < 1e3 * Q_S
    mid = own_clock(traj, a + 0.1, b)  # from inside the motion: another part of it
    assert mid.key != own[2].key


def test_motions_keyed_in_blocks_are_those_keyed_one_by_one():
    from val3check.simulation.own_clock import own_clocks

    out_ = JointLine([0, 0, 90, 0, 45, 0], [40, 10, 80, 5, 50, 30])
    back = JointLine(out_.q1, out_.q0)
    moves = [(out_, 100.0), (back, 100.0), (out_, 100.0), (back, 60.0)] * 3
    traj, spans = _run_of(moves, [0.3 + 1.9031 * k for k in range(len(moves))])
    windows = [*spans, (spans[1][0] + 0.1, spans[1][1]), (spans[2][0], spans[2][0])]  # part of one; none
    for block in (1, 3, 256):
        with pytest.MonkeyPatch.context() as mp:
            mp.setattr("val3check.simulation.own_clock.BLOCK", block)
            keyed = list(own_clocks(traj, windows))
        for own, (a, b) in zip(keyed, windows, strict=True):
            one = own_clock(traj, a, b)
            assert own.key == one.key and own.times.tobytes() == one.times.tobytes()
            assert own.joints.tobytes() == one.joints.tobytes()
            assert own.q_at(0.0123).tobytes() == one.q_at(0.0123).tobytes()
    keys = [own.key for own in keyed]
    assert keys[:4] == keys[4:8] and len(set(keys[:4])) == 3  # out, back, out, back slower: each cycle alike
    assert len(set(keys[-2:]) | set(keys[:4])) == 5  # a part of a motion, an empty one: others


def test_a_trajectory_the_layers_of_chapter_11_move_has_no_key_and_is_sampled_as_it_is():
    line = JointLine([0, 0, 90, 0, 45, 0], [40, 10, 80, 5, 50, 30])
    traj, spans = _run_of([(line, 100.0)], [0.3])

    class Shifted(Trajectory):  # as arm_layers.ActualTrajectory: the nominal path and profile, moved
        def position(self, t):
            return super().position(t) + 1.0

        def positions(self, times):
            return super().positions(times) + 1.0

    moved = Shifted(traj.path, traj.profile)
    own = own_clock(moved, *spans[0])
    assert own.key is None
    assert np.array_equal(own.joints, moved.positions(spans[0][0] + own.times))


def test_a_copy_of_a_curve_is_not_the_curve():
    line = JointLine([0, 0, 90, 0, 45, 0], [40, 10, 80, 5, 50, 30])
    copy = JointLine(line.q0, line.q1)
    traj, spans = _run_of([(line, 100.0), (JointLine(line.q1, line.q0), 100.0), (copy, 100.0)], [0.0, 2.0, 4.0])
    a, c = own_clock(traj, *spans[0]), own_clock(traj, *spans[2])
    assert a.key != c.key and np.array_equal(a.joints, c.joints)  # a miss, never a wrong result


def test_own_times():
    assert own_times(0.0).tolist() == [0.0]
    assert own_times(0.01) == pytest.approx([0.0, 0.004, 0.008, 0.01])
    assert own_times(0.008) == pytest.approx([0.0, 0.004, 0.008]) and len(own_times(0.008 + 1e-12)) == 3
    assert math.isclose(own_times(0.0105)[-1], 0.0105)


def test_the_bundled_pick_and_place_reuses_checks_and_finds_what_fresh_checks_find(monkeypatch):
    # 70 s: the pallet of 9 cubes is filled and changed about 3 times; every check is then made
    # again without reuse and compared, motion by motion
    import sys
    from pathlib import Path as FsPath

    from val3check.simulation import collision_run, value_watch

    root = FsPath(__file__).resolve().parents[2]
    sys.path.insert(0, str(root / "tests"))
    from interpretation.simsupport import run_folder

    app = root / "fixtures" / "valid" / "PickPlace"
    scenario = (root / "fixtures" / "scenarios" / "pickplace.toml").read_text(encoding="utf-8")

    def sim():
        return run_folder(app, scenario=scenario, duration=70.0, robot=ROBOT, collisions=True,
                          cell=str(app / "val3check-cell.toml"), tmp_path=FsPath(__import__("tempfile").mkdtemp()))

    from val3check.collision.world import World

    keyed = collision_run.own_clocks

    def unkeyed(*a):
        for own in keyed(*a):
            own.key = None
            yield own

    class Asked(collision_run.Positions):  # the trajectory asked at every event
        def __init__(self, traj):
            super().__init__(traj)
            self.keyed = False

    def made_anew(world, name, solids):  # a part's solids made again at every grasp, as before copies
        world._parts_made.clear()
        return real_part_bodies(world, name, solids)

    real_part_bodies = World._part_bodies

    grips: list[int] = []
    real_check = collision_run.CollisionChecker

    def counted(*a, **kw):  # the open()/close() events reused by the checker
        chk = real_check(*a, **kw)
        grips.append(chk.world)
        return chk

    monkeypatch.setattr(collision_run, "CollisionChecker", counted)
    reused = sim()
    assert grips[-1].grips_reused > 10
    traj, windows = reused.motion.trajectory, [(s, e) for _, s, e in collision_run._spans(reused.motion)]
    assert [o.key for o in keyed(traj, windows)] == [own_clock(traj, *w).key for w in windows]  # blocks: the same keys
    # fresh: no motion, no open()/close() reused, the scene read at every motion, every frame read anew
    monkeypatch.setattr(collision_run, "own_clocks", unkeyed)
    monkeypatch.setattr(collision_run, "Positions", Asked)
    monkeypatch.setattr(World, "_part_bodies", made_anew)
    monkeypatch.setattr(World, "_grip_key", lambda self, *a: object())
    monkeypatch.setattr(collision_run.ValueWatch, "reading", lambda self, t: None)
    monkeypatch.setattr(value_watch, "_chain", lambda objects: None)
    fresh = sim()
    assert grips[-1].grips_reused == 0
    a, b = reused.collision, fresh.collision
    assert b.reused == 0 and a.reused > 0.5 * len(a.by_motion) and len(a.by_motion) > 100
    assert a.drops == b.drops
    assert _timeline(reused.motion.cell_timeline) == _timeline(fresh.motion.cell_timeline)
    assert a.checks < 0.5 * b.checks
    assert sorted(a.by_motion) == sorted(b.by_motion)
    for i, r in a.by_motion.items():
        f = b.by_motion[i]
        _same(f, r, 0.0)
        assert r.motion.id == i
    assert [(i, c) for i, c in a.contacts] == [(i, c) for i, c in b.contacts]
    assert [d.message for d in reused.diagnostics] == [d.message for d in fresh.diagnostics]


def _timeline(tl) -> tuple:
    def changes(d):
        return {k: [(c.time, None if c.matrix is None else c.matrix.tobytes()) for c in v] for k, v in d.items()}

    return changes(tl.frames), changes(tl.tools), [(p.name, p.tool, p.carried, p.start, p.end, p.pose.tobytes())
                                                   for p in tl.parts]


# ---- open() and close() ------------------------------------------------------------------------------------

PICK = (350.0, -150.0, TOP + BRICK - 1.0)  # the brick 1 mm into the table: allowed to touch it
PLACE = (300.0, 150.0, TOP + BRICK - 5.0)  # left 5 mm into the table: a part left in collision


def _q(p):
    """The joints with the TCP at p, pointing down."""
    return _own((p[0], p[1], p[2] + 60.0), p)[1][-1]


def _grip_cell() -> Cell:
    c = _cell()  # and a bolt on a tool with no solids of its own: its pose is read only for the grasp
    c.parts.append(Part("bolt", "tOther", "close", Shape("sphere", (10.0,)), trsf_matrix((0, 0, 30, 0, 0, 0))))
    return c


def _state(chk) -> tuple:
    """What an open()/close() changes: the parts carried and left, the static set, the allowances."""
    w = chk.world
    return (list(w.carried), [(b.made_from, b.local.tobytes(), b.kind) for b in w.dropped],
            [(name, b.made_from, b.local.tobytes(), g.weights.tobytes()) for name, g in w.carried.items()
             for b in g.bodies],
            [(b.made_from, b.pose.tobytes()) for b in w.static],
            [tuple(x if isinstance(x, tuple) else x.label for x in pair) for pair in w.allowed_names()],
            w.static_lo.tobytes(), w.static_hi.tobytes())


def test_an_open_or_close_that_repeats_in_the_same_scene_is_done_again_as_it_was_computed():
    frames = {"fBall": BALL}
    chk = checker(_grip_cell(), frames=frames, tools={"tTool": TOOL, "tOther": TOOL})

    def numbered(c) -> None:  # the scene's number (`World.key`, set by a replay) is its content's
        w = c.world
        assert w.per_scene("key", w._scene_id) == w._scene_ids[w._scene_key()]

    def cycle(c, t: float):
        out = [c.gripper("tTool", "close", t, joints=_q(PICK), source="pick")]
        numbered(c)
        states = [_state(c)]
        out.append(c.gripper("tTool", "open", t + 1.0, joints=_q(PLACE), source="place"))
        numbered(c)
        states.append(_state(c))
        c.clear_parts("brick")  # taken away: the scene the cycle started in
        states.append(_state(c))
        return states, out

    first = cycle(chk, 1.0)
    assert first[1][1] and first[1][1][0].depth_mm == pytest.approx(5.0, abs=0.1)  # left 5 mm in the table
    assert first[0][0][4]  # the brick grasped 1 mm in the table may touch it
    n, made = chk.world.grips_reused, chk.measurements
    second = cycle(chk, 5.0)
    assert chk.world.grips_reused == n + 2 and chk.measurements == made  # nothing measured again
    assert second[0] == first[0]
    assert [(d.time, d.source) for d in second[1][1]] == [(6.0, "place")]
    fresh = checker(_grip_cell(), frames=frames, tools={"tTool": TOOL, "tOther": TOOL})
    assert cycle(fresh, 5.0) == second and fresh.world.grips_reused == 0


GRIP_INPUTS = ["joints", "instruction", "tool", "tool pose", "frame moved", "part left in the cell", "touch allowance",
               "touch tolerance", "arm geometry"]


def _grip_event(what: str | None, frames=None, tools=None, chk=None):
    """A checker in the scene of the event, with one input changed (`what`), and the event's arguments."""
    frames = frames if frames is not None else {"fBall": BALL}
    tools = tools if tools is not None else {"tTool": TOOL, "tOther": TOOL}
    chk = chk or checker(_grip_cell(), frames=frames, tools=tools)
    tool, instr, q = ("tOther" if what == "tool pose" else "tTool"), "close", _q(PICK)
    if what == "joints":
        q = _q(PLACE)
    elif what == "instruction":
        instr = "open"
    elif what == "tool":
        tool = "tOther"
    elif what == "tool pose":
        tools["tOther"] = (0.0, 0.0, 140.0, 0.0, 0.0, 0.0)
    elif what == "frame moved":
        frames["fBall"] = (300.0, 0.0, -90.0, 0, 0, 0)
    elif what == "part left in the cell":
        chk.gripper("tOther", "close", 0.5, joints=_q(PLACE))
        chk.gripper("tOther", "open", 0.6, joints=_q(PLACE))
    elif what == "touch allowance":
        chk.refresh(1.0)
        a, b = chk.world.static[0], next(iter(chk.world.link_groups.values())).bodies[0]
        chk.world.allowed[frozenset((id(a), id(b)))] = (a, b)
    elif what == "touch tolerance":
        chk.world.touch = 2.0
    elif what == "arm geometry":
        chk.world.arm.links.current = _LONGER
    return chk, (tool, instr, 1.0), q


_LONGER = None


@pytest.mark.parametrize("what", GRIP_INPUTS)
def test_each_input_of_an_open_or_close_changed_is_computed_again(what):
    global _LONGER
    from dataclasses import replace

    from val3check.robot import dh as _dh
    from val3check.robot.absolute import with_dh
    from val3check.robot.links import arm_links
    from val3check.simulation.collision_run import _geometry_epochs

    nominal = _dh.nominal_dh(ROBOT)
    longer = with_dh(ROBOT, replace(nominal, a=tuple(v + (20.0 if k == 2 else 0.0) for k, v in enumerate(nominal.a))))
    _LONGER = arm_links(longer)

    def new():  # a checker whose arm's geometry can change (setDH, 11.4)
        from val3check.collision import CollisionChecker

        arm, _ = _geometry_epochs(ROBOT, [])
        return CollisionChecker(arm, _grip_cell(), frames=frames, tools=tools)

    frames, tools = {"fBall": BALL}, {"tTool": TOOL, "tOther": TOOL}
    chk = new()
    _, (tool, instr, t), q = _grip_event(None, frames, tools, chk)
    chk.gripper(tool, instr, t, joints=q)
    before = _state(chk)
    for name in list(chk.world.carried):  # back to the scene the event ran in
        chk.gripper(chk.world.carried[name].bodies[0].owner == "bolt" and "tOther" or "tTool", "open", 2.0,
                    joints=_q((300.0, 0.0, 150.0)))
        chk.clear_parts(name)
    n = chk.world.grips_reused
    _, (tool, instr, t), q = _grip_event(what, frames, tools, chk)
    chk.gripper(tool, instr, 3.0, joints=q)
    assert chk.world.grips_reused == n, what  # not found: computed
    after = _state(chk)
    # as a checker that saw only this event computes it
    frames2, tools2 = {"fBall": BALL}, {"tTool": TOOL, "tOther": TOOL}
    other = new()
    _, (tool, instr, _t), q = _grip_event(what, frames2, tools2, other)
    other.gripper(tool, instr, 3.0, joints=q)
    assert _state(other) == after
    if what in ("tool", "tool pose", "instruction", "frame moved", "part left in the cell"):
        assert after != before, what


# ---- the program's frames and tools, read once per change ---------------------------------------------------


def _machine(node):
    from types import SimpleNamespace

    glob = SimpleNamespace(data=[node], off=0)
    return SimpleNamespace(main=SimpleNamespace(globals={"fPart": glob}, aliases={})), glob



def _chain():
    """world -> base -> f: a frame two levels below the world, as the reading tests change it."""
    from val3check.geometry.frames import Frame
    from val3check.geometry.trsf import Trsf

    world = Frame(is_root=True, name="world")
    base = Frame(Trsf(100.0, 0.0, 0.0, 0.0, 0.0, 0.0), world)
    return world, base, Frame(Trsf(0.0, 50.0, 0.0, 0.0, 0.0, 90.0), base)


def test_a_frame_is_computed_again_whenever_its_chain_changes_bit_for_bit():
    from val3check.geometry.frames import Frame
    from val3check.geometry.trsf import Trsf
    from val3check.simulation.collision_run import _read

    world, base, f = _chain()
    machine, glob = _machine(f)
    cache: dict = {}
    first = _read(machine, "fPart", Frame, cache)
    assert _read(machine, "fPart", Frame, cache) is first  # nothing changed: the same reading
    changes = [lambda: setattr(f.trsf, "x", 1.0), lambda: setattr(base.trsf, "rz", 10.0),
               lambda: setattr(f.trsf, "z", -0.0),  # equal as a number, not as bits
               lambda: setattr(f, "ref", world), lambda: glob.data.__setitem__(0, Frame(Trsf(5.0), world)),
               lambda: setattr(glob.data[0], "ref", None), lambda: setattr(glob.data[0], "ref", world),
               lambda: setattr(world.trsf, "x", 1.0)]  # a modified world: no position
    for k, change in enumerate(changes):
        before = _read(machine, "fPart", Frame, cache)
        change()
        after = _read(machine, "fPart", Frame, cache)
        fresh = _read(machine, "fPart", Frame)
        assert after is not before or before is None, k
        assert (after is None) == (fresh is None) and (fresh is None or np.array_equal(after, fresh)), k
    assert after is None


def test_the_reading_in_force_changes_with_every_new_value():
    from val3check.geometry.frames import Frame
    from val3check.geometry.trsf import Trsf
    from val3check.simulation.collision_run import ValueWatch

    world = Frame(is_root=True, name="world")
    f = Frame(Trsf(0.0, 50.0, 0.0), world)
    machine, _ = _machine(f)
    cell = Cell(path="test")
    cell.obstacles.append(Obstacle("box", Shape("box", (10.0, 10.0, 10.0)), "fPart", np.eye(4)))
    watch = ValueWatch(cell, machine)
    assert watch.reading(0.0) == -1
    watch(0)
    watch(4000)  # the same values: the same reading
    assert watch.reading(0.0) == watch.reading(1.0) != -1
    f.trsf.x = 3.0
    watch(8000)
    assert watch.reading(0.005) == watch.reading(0.0) != watch.reading(0.008) == watch.reading(5.0)
    r = watch.reading(0.008)
    f.trsf.x = 4.0
    watch(8000)  # another value at the same time replaces it: another reading
    assert watch.reading(0.008) != r and watch.frame("fPart", 0.008)[0, 3] == 4.0


def test_the_scene_is_read_again_when_the_readings_change_and_only_then():
    frames = {"fBall": BALL}
    token = [0]
    chk = checker(_cell(), frames=frames, readings=lambda t: token[0])
    chk.refresh(1.0)
    v = chk.world.version
    frames["fBall"] = (300.0, 0.0, -50.0, 0, 0, 0)
    chk.refresh(2.0)  # the same readings: what the frames give is the same (the caller's promise)
    assert chk.world.version == v
    token[0] = 1
    chk.refresh(3.0)
    assert chk.world.version != v
    ball = next(b for b in chk.world.static if "ball" in b.label)
    assert ball.pose[2, 3] == -50.0


def test_a_frame_given_the_same_bits_in_new_objects_keeps_its_reading():
    """The reading is reused when root_pose would read the very same objects (`_objects`), or
    other objects with the same bits (`_chain`); each object it reads replaced in turn."""
    from val3check.geometry.frames import Frame
    from val3check.geometry.trsf import Trsf
    from val3check.simulation.collision_run import _read

    world, base, f = _chain()
    machine, _ = _machine(f)
    cache: dict = {}
    first = _read(machine, "fPart", Frame, cache)
    same = [lambda: setattr(f.trsf, "y", float("50")), lambda: setattr(f, "trsf", Trsf(0.0, 50.0, 0.0, 0.0, 0.0, 90.0)),
            lambda: setattr(base.trsf, "x", float("100")), lambda: setattr(world.trsf, "z", float("0"))]
    for k, change in enumerate(same):
        change()
        assert _read(machine, "fPart", Frame, cache) is first, k
        assert _read(machine, "fPart", Frame, cache) is first, k  # and again, on the fast path
    for k, change in enumerate([lambda: setattr(f.trsf, "y", 50.5), lambda: setattr(base, "trsf", Trsf(1.0)),
                                lambda: setattr(base, "is_root", True)]):
        before = _read(machine, "fPart", Frame, cache)
        change()
        after = _read(machine, "fPart", Frame, cache)
        fresh = _read(machine, "fPart", Frame)
        assert after is not before and np.array_equal(after, fresh), k


def test_a_shifted_report_reads_as_the_shifted_copy_bit_for_bit():
    from dataclasses import replace

    from val3check.collision.checker import shifted
    from val3check.collision.results import Clearance, Contact, MotionReport

    own = MotionReport(MotionSpan(1), np.array([0.0, 0.004, 0.0071]), np.array([5.0, 3.0, 4.0]),
                       np.array([False, True, True]), Contact(0.0, "a", "b", (1.0, 2.0, 3.0), 0.5),
                       Contact(0.004, "c", "d", (0.0, 0.0, 0.0), 1.0),
                       Clearance(3.0, 0.004, "a", "b", (0.0, 0.0, 0.0), (1.0, 1.0, 1.0)), True, 10.0, 0.05, 7,
                       [Contact(0.004, "c", "d", (0.0, 0.0, 0.0), 1.0)])
    start = 3601.123456789
    r = shifted(own, MotionSpan(9), start)
    assert (start + own.times).tobytes() == r.times.tobytes()
    assert r.clearance is own.clearance and r.exact is own.exact
    assert r.start == float((start + own.times)[0]) and r.end == float((start + own.times)[-1])
    for name in ("starts_in_collision", "first_contact", "min_clearance"):
        assert getattr(r, name) == replace(getattr(own, name), time=start + getattr(own, name).time), name
    assert r.contacts == [replace(c, time=start + c.time) for c in own.contacts]
    assert (r.too_close, r.margin_mm, r.tolerance_mm, r.checks, r.motion.id) == (True, 10.0, 0.05, 7, 9)
