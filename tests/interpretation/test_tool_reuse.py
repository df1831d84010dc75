"""A tool's TCP in the flange, computed once per tool value (issue 29): chapter 10's `_tool` gives
the same read-only matrix while the tool and its base tools are the very objects it was computed
from, and the arm's `_tool_mm` the same shared array for that matrix and unit; each input changed
gives what a fresh computation gives."""

from __future__ import annotations

import numpy as np

from val3check.geometry import frames as geo_frames
from val3check.geometry.frames import Tool
from val3check.geometry.trsf import Trsf
from val3check.simulation import ch10_motion
from val3check.simulation.moving_arm import MovingArm


def _fresh(tool):
    return None if tool.is_root else ch10_motion._matrix(geo_frames.root_pose(tool))


def test_the_same_tool_gives_the_same_matrix_and_each_change_a_fresh_one():
    flange = Tool(is_root=True, name="flange")
    base = Tool(Trsf(0.0, 0.0, 50.0), flange)
    t = Tool(Trsf(1.0, 2.0, 120.0, 0.0, 0.0, 30.0), base)
    kept: dict = {}  # (the run's table: MovingArm.tools)
    first = ch10_motion._tool(t, kept)
    assert ch10_motion._tool(t, kept) is first and not first.flags.writeable
    assert ch10_motion._tool(t) is not first  # without the run's table: nothing kept
    assert np.array_equal(first, _fresh(t))
    other_flange = Tool(is_root=True, name="flange")
    changes = [lambda: setattr(t.trsf, "x", 5.0), lambda: setattr(t.trsf, "y", -1.0),
               lambda: setattr(t.trsf, "z", 100.0), lambda: setattr(t.trsf, "rx", 10.0),
               lambda: setattr(t.trsf, "ry", 20.0), lambda: setattr(t.trsf, "rz", -0.0),  # bits, not value
               lambda: setattr(t, "trsf", Trsf(3.0)), lambda: setattr(base.trsf, "z", 60.0),
               lambda: setattr(base, "trsf", Trsf(0.0, 9.0)), lambda: setattr(t, "ref", flange),
               lambda: setattr(t, "ref", base), lambda: setattr(base, "ref", other_flange)]
    for k, change in enumerate(changes):
        before = ch10_motion._tool(t, kept)
        change()
        after = ch10_motion._tool(t, kept)
        assert after is not before, k
        assert np.array_equal(after, _fresh(t)) and after.tobytes() == _fresh(t).tobytes(), k
        assert ch10_motion._tool(t, kept) is after, k
    assert ch10_motion._tool(flange, kept) is None
    base.is_root = True  # a root with a reference: modified (160), raised every time
    for _ in range(2):
        try:
            ch10_motion._tool(t, kept)
        except Exception as exc:  # noqa: BLE001
            assert getattr(exc, "code", None) == 160
        else:
            raise AssertionError("160")


def test_the_arm_gives_the_shared_array_of_the_matrix_and_unit():
    arm = MovingArm(None)
    m = np.eye(4)
    m[:3, 3] = (1.0, 2.0, 3.0)
    m.flags.writeable = False
    a = arm._tool_mm(m, 1.0)
    b = arm._tool_mm(m, 1.0)  # the table held it now: the same shared array
    assert b is a and arm._tool_mm(m, 1.0) is a
    inch = arm._tool_mm(m, 25.4)  # another unit: scaled
    assert np.array_equal(inch[:3, 3], np.array([1.0, 2.0, 3.0]) * 25.4)
    assert arm._tool_mm(m, 25.4) is inch and arm._tool_mm(m, 1.0) is a
    w = np.array(m)  # writeable: never taken as unchanged
    assert arm._tool_mm(w, 1.0) is a and arm._tool_mm(w, 1.0) is a
    w[0, 3] = 7.0
    assert arm._tool_mm(w, 1.0)[0, 3] == 7.0
    m2 = np.array(m)  # another read-only matrix of another value
    m2[1, 3] = 9.0
    m2.flags.writeable = False
    assert arm._tool_mm(m2, 1.0)[1, 3] == 9.0 and arm._tool_mm(m, 1.0) is a


def _task(config_fields=("shoulder", "elbow", "wrist"), data=None):
    from types import SimpleNamespace

    model = SimpleNamespace(config_fields=config_fields)
    return SimpleNamespace(machine=SimpleNamespace(arm=SimpleNamespace(model=model, name="TS2-60", targets={}),
                                                   app=SimpleNamespace(data=data or {})))


def _fresh_target(task, p):
    from val3check.geometry import points as geo_points
    from val3check.motion.commands import Target

    ref = p.ref
    frame = getattr(ref, "name", "") or ("world" if ref is not None and ref.is_root else "")
    return Target.point(ch10_motion._matrix(geo_points.world_pose(p)), ch10_motion.ct(p.config), p.name or "",
                        frame, note=ch10_motion._other_family_note(task, p))


def _equal(a, b) -> bool:
    return (a.pose.tobytes() == b.pose.tobytes() and (a.config, a.name, a.frame, a.note, a.joints)
            == (b.config, b.name, b.frame, b.note, b.joints))


def test_a_point_of_the_same_values_in_the_same_frames_gives_the_same_target_and_each_change_a_fresh_one():
    from types import SimpleNamespace

    from val3check.geometry.frames import Frame
    from val3check.geometry.points import Point

    world = Frame(is_root=True, name="world")
    other_world = Frame(is_root=True, name="world")
    pallet = Frame(Trsf(400.0, 0.0, 10.0, 0.0, 0.0, 45.0), world, name="fPallet")
    other = Frame(Trsf(400.0, 0.0, 10.0, 0.0, 0.0, 45.0), world, name="fOther")
    task = _task()

    def point(**kw):
        p = Point(Trsf(10.0, 20.0, 30.0, 0.0, 180.0, 0.0), ref=pallet, name="pA")
        p.config = {"shoulder": "lefty", "elbow": "epositive", "wrist": "wsame"}
        for k, v in kw.items():
            setattr(p, k, v)
        return p

    first = ch10_motion._point(task, point(), "movel")
    assert ch10_motion._point(task, point(), "movel") is first  # another point object, the same values
    assert not first.pose.flags.writeable and _equal(first, _fresh_target(task, point()))
    scara = SimpleNamespace(type="point", values=[SimpleNamespace(key="0", fields={"elbow": "epositive"})])
    changes = [
        (lambda p: setattr(p.trsf, "x", 11.0), None), (lambda p: setattr(p.trsf, "y", 21.0), None),
        (lambda p: setattr(p.trsf, "z", 31.0), None), (lambda p: setattr(p.trsf, "rx", 1.0), None),
        (lambda p: setattr(p.trsf, "ry", -180.0), None), (lambda p: setattr(p.trsf, "rz", -0.0), None),
        (lambda p: setattr(p, "ref", other), None), (lambda p: setattr(p, "ref", world), None),
        (lambda p: setattr(p, "name", "pB"), None), (lambda p: setattr(p, "name", ""), None),
        (lambda p: p.config.__setitem__("shoulder", "righty"), None),
        (lambda p: p.config.__setitem__("elbow", "enegative"), None),
        (lambda p: setattr(p.trsf, "x", 1), None),  # an int: not taken for the float's bits
        (None, lambda: setattr(pallet.trsf, "z", 11.0)), (None, lambda: setattr(pallet, "trsf", Trsf(1.0))),
        (None, lambda: setattr(pallet, "ref", other_world)), (None, lambda: setattr(pallet, "name", "fRenamed")),
        (None, lambda: setattr(task.machine.arm.model, "config_fields", ("shoulder",))),  # a SCARA: the note
        (None, lambda: task.machine.app.data.__setitem__("pA", scara)),
    ]
    for k, (on_point, on_world) in enumerate(changes):
        before = ch10_motion._point(task, point(), "movel")
        p = point()
        if on_point is not None:
            on_point(p)
        else:
            on_world()
            p = point()
        after = ch10_motion._point(task, p, "movel")
        fresh = _fresh_target(task, p)
        assert _equal(after, fresh), k
        if not _equal(before, fresh):
            assert after is not before, k
    assert task.machine.app.data and ch10_motion._point(task, point(), "movel").note  # (the last change showed)
    ints = [point(trsf=Trsf(10.0, 20.0, 30.0, 0.0, 180.0, 0.0)) for _ in range(2)]
    for p in ints:
        p.trsf.x = 10  # an int field: not kept (its bits are not what the pose computes with)
    assert ch10_motion._point(task, ints[0], "movel") is not ch10_motion._point(task, ints[1], "movel")
    try:
        ch10_motion._point(task, point(ref=None), "movel")
    except Exception as exc:  # noqa: BLE001
        assert getattr(exc, "code", None) == 162
    else:
        raise AssertionError("162")


def test_open_and_close_record_the_tool_s_centre_point_as_it_is_at_each_action(tmp_path):
    """Machine.tool_action keeps the tool's TCP in the flange while the tool is the very same
    objects (geometry.frames.kept): each change in place, by a new value, of its base, shows."""
    from .simsupport import sim

    r = sim(tmp_path, """begin
  open(tT)
  close(tT)
  tT.trsf.z = 150
  open(tT)
  tT.trsf = {0, 0, 150, 0, 0, 0}
  close(tT)
  link(tT, tBase)
  open(tT)
  tBase.trsf.x = 5
  close(tT)
  tBase.trsf.rz = 90
  open(tT)
end
""", globals_=["tool tT", "tool tBase"], duration=2)
    tcps = [tuple(round(v, 9) + 0.0 for v in e.tcp_in_flange) for e in r.tool_events]
    assert tcps == [(0.0,) * 6, (0.0,) * 6, (0.0, 0.0, 150.0, 0.0, 0.0, 0.0), (0.0, 0.0, 150.0, 0.0, 0.0, 0.0),
                    (0.0, 0.0, 150.0, 0.0, 0.0, 0.0), (5.0, 0.0, 150.0, 0.0, 0.0, 0.0),
                    (5.0, 0.0, 150.0, 0.0, 0.0, 90.0)]


def test_a_point_that_cannot_be_keyed_raises_what_it_raised_before_in_its_order():
    from val3check.geometry.points import Point

    p = Point(Trsf(1.0), ref=None, name="pA")
    p.config = None  # (not a configuration: the key's part raises, the point's own error comes first)
    try:
        ch10_motion._point(_task(), p, "movel")
    except Exception as exc:  # noqa: BLE001
        assert getattr(exc, "code", None) == 162
    else:
        raise AssertionError("162")
