"""A URDF read once per process (robot/urdf.read_urdf, robot/links.read_collision_solids): keyed by
the path and the file's bytes, the checks and the read done every time, each caller its own
containers; what is kept is what a fresh read gives."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

from val3check.robot import links, urdf
from val3check.robot.catalog import catalog
from val3check.robot.errors import RobotError
from val3check.robot.links import read_collision_solids
from val3check.robot.urdf import read_urdf

TX2_60 = Path(catalog()["TX2-60"]["path"])


def _same_info(a, b) -> None:
    assert (a.path, a.robot_name, a.joints, a.links, a.meta, a.meta_joints, a.meta_items) == \
           (b.path, b.robot_name, b.joints, b.links, b.meta, b.meta_joints, b.meta_items)


def _same_solids(a, b) -> None:
    assert len(a) == len(b)
    for x, y in zip(a, b):
        assert (x.link, x.name, x.kind, x.size, x.mesh) == (y.link, y.name, y.kind, y.size, y.mesh)
        assert x.origin.tobytes() == y.origin.tobytes()


@pytest.fixture
def arm(tmp_path: Path) -> Path:
    p = tmp_path / "arm.urdf"
    p.write_bytes(TX2_60.read_bytes())
    return p


def test_every_catalogue_urdf_read_again_is_a_fresh_read():
    for entry in catalog().values():
        path = entry["path"]
        data = Path(path).read_bytes()
        first, again = read_urdf(path), read_urdf(path)
        _same_info(again, urdf._read_urdf(path, data))
        _same_info(first, again)
        solids = read_collision_solids(path)
        fresh = links._collision_solids(urdf._parse_xml(path, data, "URDF"), path, True)
        _same_solids(read_collision_solids(path), fresh)
        _same_solids(solids, fresh)


def test_each_caller_gets_its_own_containers(arm: Path):
    a = read_urdf(arm)
    a.joints.clear()
    a.links.add("intruder")
    a.meta["world"] = "changed"
    a.meta_items.clear()
    for v in a.meta_joints.values():
        v["accel"] = "0"
    b = read_urdf(arm)
    _same_info(b, urdf._read_urdf(str(arm), arm.read_bytes()))
    s = read_collision_solids(arm)
    s[0].origin[0, 3] = 1e9
    s.pop()
    _same_solids(read_collision_solids(arm), links._collision_solids(
        urdf._parse_xml(str(arm), arm.read_bytes(), "URDF"), str(arm), True))


def test_changed_bytes_are_read_again(arm: Path):
    text = arm.read_text(encoding="utf-8")
    before, solids = read_urdf(arm), read_collision_solids(arm)
    edits = [('velocity="', 'velocity="1'), ('<robot name="', '<robot name="x'), ('radius="', 'radius="1')]
    for old, new in edits:
        assert old in text
        arm.write_text(text.replace(old, new, 1), encoding="utf-8")
        after, got = read_urdf(arm), read_collision_solids(arm)
        _same_info(after, urdf._read_urdf(str(arm), arm.read_bytes()))
        _same_solids(got, links._collision_solids(urdf._parse_xml(str(arm), arm.read_bytes(), "URDF"), str(arm), True))
        if old.startswith("velocity"):
            assert after.joints != before.joints
        elif old.startswith("<robot"):
            assert after.robot_name == "x" + before.robot_name
        else:
            assert [s.size for s in got] != [s.size for s in solids]


def test_another_path_with_the_same_bytes_is_its_own(arm: Path, tmp_path: Path):
    other = tmp_path / "other.urdf"
    other.write_bytes(arm.read_bytes())
    assert read_urdf(arm).path == str(arm)
    assert read_urdf(other).path == str(other)


def test_the_checks_run_every_time(arm: Path):
    read_urdf(arm)
    read_collision_solids(arm)
    os.unlink(arm)
    with pytest.raises(RobotError, match="no such file"):
        read_urdf(arm)
    with pytest.raises(RobotError, match="cannot read the URDF"):
        read_collision_solids(arm)


def test_a_urdf_with_meshes_is_not_kept_when_they_are_resolved(tmp_path: Path):
    (tmp_path / "m.stl").write_bytes(b"solid m\nendsolid m\n")
    p = tmp_path / "mesh.urdf"
    p.write_text('<robot name="r"><link name="a"><collision><geometry><mesh filename="m.stl"/></geometry>'
                 '</collision></link></robot>', encoding="utf-8")
    solids = read_collision_solids(p)
    assert solids[0].mesh == str((tmp_path / "m.stl").resolve())
    assert not any(k[0] == str(p) and k[2] for k in links._SOLIDS)
    assert read_collision_solids(p, resolve_meshes=False)[0].mesh == "m.stl"
    assert read_collision_solids(p)[0].mesh == str((tmp_path / "m.stl").resolve())
    assert np.array_equal(solids[0].origin, np.eye(4))
