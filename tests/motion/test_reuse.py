"""Motions that repeat exactly reuse their joint curves and samples (issue 29), and only then: each
input of the key changed in turn gives a new result, and setDH (11.4) forgets everything."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from val3check.motion.construction import construct
from val3check.motion.kin import ArmKin
from val3check.motion.paths import Span
from val3check.robot import dh as _dh
from val3check.robot.absolute import with_dh

from .motionhelp import HOME, ROBOT, movec, movej, movel, point

TOOL = np.eye(4)
TOOL[2, 3] = 50.0  # 50 mm along the flange's Z


def curve(kin, move, q=HOME, tool=None):
    built = construct(kin, move, np.array(q, dtype=float), tool, 0.0)
    assert built.failure is None
    return built.geometry.joint_curve


def test_the_same_motion_from_the_same_start_is_built_once():
    kin = ArmKin(ROBOT)
    a = curve(kin, movel(point(dx=40.0)))
    b = curve(kin, movel(point(dx=40.0), line=9))  # another instruction, same motion
    assert b is a
    j1 = curve(kin, movej(point(dy=30.0)))
    assert curve(kin, movej(point(dy=30.0))) is j1


def test_each_input_of_the_key_changed_gives_another_curve():
    kin = ArmKin(ROBOT)
    base = curve(kin, movel(point(dx=40.0)))
    others = {
        "start joints": curve(kin, movel(point(dx=40.0)), q=HOME + [0.0, 0.0, 0.0, 0.0, 1.0, 0.0]),
        "tool": curve(kin, movel(point(dx=40.0)), tool=TOOL),
        "target": curve(kin, movel(point(dx=40.5))),
        "kind": curve(kin, movec(point(dx=20.0, dz=10.0), point(dx=40.0))),
    }
    for what, other in others.items():
        assert other is not base, what
        assert not np.array_equal(other.Q[-1], base.Q[-1]) or not np.array_equal(other.Q[len(other.Q) // 2],
                                                                                base.Q[len(base.Q) // 2]), what
    arc = curve(kin, movec(point(dx=20.0, dz=10.0), point(dx=40.0)))
    assert curve(kin, movec(point(dx=20.0, dz=12.0), point(dx=40.0))) is not arc  # the intermediate point
    line = curve(kin, movej(point(dy=30.0)))
    assert curve(kin, movej(point(dy=30.0)), q=HOME + 1.0) is not line
    assert curve(kin, movej(point(dy=31.0))) is not line


def test_set_dh_forgets_what_the_old_geometry_gave():
    kin = ArmKin(ROBOT)
    before = curve(kin, movel(point(dx=40.0)))
    nominal = _dh.nominal_dh(ROBOT)
    changed = replace(nominal, a=tuple(v + (0.5 if k == 2 else 0.0) for k, v in enumerate(nominal.a)))
    kin.use_geometry(with_dh(ROBOT, changed))
    after = curve(kin, movel(point(dx=40.0)))
    assert after is not before
    assert np.max(np.abs(after.Q - before.Q)) > 1e-6  # the same TCP line needs other joints


def test_span_samples_are_shared_only_for_the_same_part_tool_and_arm():
    kin = ArmKin(ROBOT)
    geom = curve(kin, movej(point(dy=30.0)))
    first = Span(geom, 0.0, 1.0).sample(kin)
    assert Span(geom, 0.0, 1.0).sample(kin) is first
    tooled = Span(geom, 0.0, 1.0, tool=TOOL).sample(kin)
    assert tooled is not first and not np.array_equal(tooled["pt"], first["pt"])
    part = Span(geom, 0.0, 0.5).sample(kin)
    assert part is not first and part["sigma"][-2] != first["sigma"][-2]
    other = ArmKin(ROBOT)  # another arm object: its own samples
    assert Span(geom, 0.0, 1.0).sample(other) is not first
    nominal = _dh.nominal_dh(ROBOT)
    kin.use_geometry(with_dh(ROBOT, replace(nominal, d=tuple(v + (1.0 if k == 3 else 0.0)
                                                            for k, v in enumerate(nominal.d)))))
    moved = Span(geom, 0.0, 1.0).sample(kin)  # the same joints, a new geometry: the TCP rates again
    assert moved is not first and not np.array_equal(moved["pt"], first["pt"])


def _blends(md_reach: float):
    """The blend curves of a cycle from the home position (movej to joints: the same start each
    time) through three blended lines, recorded three times."""
    from val3check.motion.mdesc import MDesc

    from .motionhelp import OFF, queue, run

    q = queue()
    md = MDesc(blend="joint", leave=20.0, reach=md_reach)
    for _ in range(3):
        q.record(movej(HOME, OFF), 0.0)
        for dx, dy in ((60.0, 40.0), (60.0, 0.0), (0.0, 40.0)):
            q.record(movel(point(dx=dx, dy=dy), md), 0.0)
    run(q)
    return [sp.geom for sp in q.path.spans if len(sp.owners) == 2]


def test_a_repeated_blend_is_reused_and_another_reach_is_not():
    first = _blends(20.0)
    assert len(first) >= 3
    assert len({id(g) for g in first}) < len(first)  # blends of later cycles are those of the first
    other = _blends(25.0)
    assert all(g is not f for g in other for f in first)
