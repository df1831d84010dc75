"""Arm identification from a controller tree's usr/configs/arm.cfx: ids as controllers write them,
SCARA strokes (lengthAxis3), mounts, arms without a model (tests/robot/controllers/)."""

from __future__ import annotations

import pytest

from val3check.cli import main
from val3check.robot import RobotError, load_robot
from val3check.robot.catalog import family_of_id, normalize_id
from val3check.robot.identify import closest_model, match_id, read_arm_config

from .robothelp import CONTROLLERS, joint_dist

TREES = {
    # tree: (arm.cfx value, model, mount)
    "ts2-60-floor": ("ts2_60-S1", "TS2-60", "floor"),  # like psi46/cmsrobot's TS2-60 cell
    "ts60-wall": ("ts60-S1", "TS60-L200", "wall"),  # like dc170's TS60 on a wall console, 200 mm stroke
    "tx200-floor": ("tx200-S3", "TX200", "floor"),  # like trigrass2/Val3_Polish
    "ts2-100-l400": ("ts2_100-S1", "TS2-100-L400", "floor"),
    "ts2-80-ceiling": ("ts2_80-S1", "TS2-80", "ceiling"),
    "tx2-60-dash": ("tx2-60-S1", "TX2-60", "floor"),
    "tx2-60-underscore": ("tx2_60-S2", "TX2-60", "ceiling"),
}


@pytest.mark.parametrize("tree", sorted(TREES))
def test_controller_trees_choose_their_arm(tree):
    value, model, mount = TREES[tree]
    cfx = CONTROLLERS / tree / "usr" / "configs" / "arm.cfx"
    assert read_arm_config(cfx).arm == value
    robot = load_robot(None, CONTROLLERS / tree / "usr" / "usrapp")
    assert robot.name == model and robot.mount == mount
    assert load_robot(str(cfx)).name == model
    assert any(value in n for n in robot.notes)


@pytest.mark.parametrize("tree,app", [("ts2-60-floor", "Pick"), ("ts60-wall", "Sort"), ("tx200-floor", "Polish")])
def test_sim_chooses_the_arm_of_real_cells(tree, app):
    from val3check.interpretation.simulate import choose_sim_robot

    robot, note = choose_sim_robot(None, str(CONTROLLERS / tree / "usr" / "usrapp" / app))
    assert robot is not None and note == "" and robot.name == TREES[tree][1]


def test_the_scara_pick_and_place_cell_is_reachable():
    """Every taught position of the TS2-60 pick-and-place fixture (pointRs, tool 60 mm below the
    flange, approaches 50 mm above) is within the model's reach and limits, in its configuration."""
    robot = load_robot(None, CONTROLLERS / "ts2-60-floor" / "usr" / "usrapp" / "Pick")
    tool = (0, 0, 60, 0, 0, 0)
    home = [0, 90, 150, 0]
    for x, y, z, rz, shoulder in ((450, 120, -40, 30, "lefty"), (430, 200, -40, 30, "lefty"), (200, -380, -40, -60, "ssame")):
        for dz in (0, 50):  # appro(p, {0, 0, -50, 0, 0, 0}): 50 mm up, the point's Z being down
            j = robot.solve((x, y, z + dz, 180, 0, rz), (shoulder,), initial=home, tool=tool)
            assert robot.in_limits(j)
            if shoulder == "lefty":
                assert robot.config_of(j) == ("lefty",)
            assert joint_dist(robot.ik(robot.fk(j, tool), near=j, tool=tool)[0], j) < 1e-6


def test_a_known_arm_without_model_names_the_closest():
    with pytest.raises(RobotError) as err:
        load_robot(None, CONTROLLERS / "tx2-200" / "usr" / "usrapp")
    msg = str(err.value)
    assert "TX2-200" in msg and "no model" in msg and "closest model is TX200" in msg


def test_sim_runs_without_an_arm_for_an_arm_without_model_and_says_why():
    from val3check.interpretation.simulate import choose_sim_robot

    robot, note = choose_sim_robot(None, str(CONTROLLERS / "tx2-200" / "usr" / "usrapp"))
    assert robot is None and "closest model is TX200" in note


def test_stroke_picks_the_model_and_an_unknown_stroke_is_derived():
    assert match_id("ts2_100-S1", 400).name == "TS2-100-L400"
    assert match_id("ts2_100-S1", 200).name == "TS2-100"
    nolength = load_robot(None, CONTROLLERS / "ts2-100-nolength" / "usr" / "usrapp")
    assert nolength.name == "TS2-100" and any("no lengthAxis3" in n for n in nolength.notes)
    ts60 = load_robot(None, CONTROLLERS / "ts60-wall" / "usr" / "usrapp")
    assert ts60.joint_limits[2] == (-0.1, 200.1) and ts60.stroke_mm == 200
    assert ts60.joint_limits[:2] == load_robot("TS60").joint_limits[:2]
    stated = {a.key: a for a in ts60.provenance.assumptions}
    assert stated["stroke_mm"].by == "controller" and "400 mm stroke" in stated["stroke_mm"].text
    assert load_robot("TS60-L200").joint_limits == ts60.joint_limits  # the same by name
    assert load_robot("ts2-100-l400").name == "TS2-100-L400"
    assert load_robot("TS2-100-L200").name == "TS2-100"
    with pytest.raises(RobotError, match="not a SCARA"):
        load_robot("TX2-60-L200")


@pytest.mark.parametrize("value,expected", [
    ("tx2-60-S1", "tx2-60"), ("TX2_60-S2", "tx2-60"), ("ts2_60-S1", "ts2-60"), ("tx200-S3", "tx200"),
    ("ts60-S1", "ts60"), ("rx160", "rx160"), (" TX2-90XL-S1 ", "tx2-90xl"), ("tx2_140-S3-R1", "tx2-140"),
])
def test_ids_are_normalized(value, expected):
    assert normalize_id(value) == expected


@pytest.mark.parametrize("value,name", [
    ("tx2-60-S1", "TX2-60"), ("tx2_60-S1", "TX2-60"), ("TX2_60L-S3", "TX2-60L"), ("ts2_60-S1", "TS2-60"), ("ts2-60-S1", "TS2-60"),
    ("tx200-S3", "TX200"), ("ts60-S1", "TS60"), ("tx2_40-S3", "TX2-40"), ("tx2_160l-S3", "TX2-160L"), ("tp80-S1", "TP80"),
    ("rx90b-S1", "RX90B"),
])
def test_ids_match_in_both_spellings(value, name):
    assert match_id(value).name == name


def test_an_inferred_id_matches_and_says_so():
    m = match_id("tx2_40-S3")
    assert m.name == "TX2-40" and any("inferred" in n for n in m.notes)
    assert not match_id("ts2_60-S1").notes  # seen in a real arm.cfx


@pytest.mark.parametrize("value,family,closest", [
    ("rs80-S1", "Rs", "TS80"), ("ts20-S1", "Rs", "TS40"), ("tx2_200l-S3", "Rx", "TX200L"), ("rx170b", "Rx", "RX160"),
    ("tx3-70-S1", "Rx", "TX60"),
])
def test_unknown_ids_are_classified_and_get_the_closest_model(value, family, closest):
    assert family_of_id(value) == family
    assert closest_model(value) == closest
    with pytest.raises(RobotError) as err:
        match_id(value)
    assert f"closest model is {closest}" in str(err.value)
    assert ("SCARA" in str(err.value)) == (family == "Rs")


def test_not_a_staubli_id():
    assert family_of_id("ur5e") is None and closest_model("ur5e") is None
    with pytest.raises(RobotError, match="not a Stäubli arm id"):
        match_id("ur5e-S1")


def test_mount_places_the_world_in_the_cell_not_the_points():
    floor = load_robot("TX2-60")
    ceiling = load_robot(None, CONTROLLERS / "tx2-60-underscore" / "usr" / "usrapp")
    q = [10, 20, 30, 40, 50, 60]
    assert ceiling.fk(q) == floor.fk(q)  # VAL 3 world attached to the base: taught points are unchanged
    assert floor.world_in_cell == ((1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0))
    R = ceiling.world_in_cell
    assert [R[i][2] for i in range(3)] == [0, 0, -1]  # world Z (axis 1) points down in the cell
    assert {a.key: a.by for a in ceiling.provenance.assumptions}["mount"] == "controller"
    wall = floor.with_assumptions({"mount": "wall"})
    assert [wall.world_in_cell[i][2] for i in range(3)] == [1, 0, 0]  # axis 1 horizontal
    scara_wall = load_robot(None, CONTROLLERS / "ts60-wall" / "usr" / "usrapp")
    assert scara_wall.world_in_cell == floor.world_in_cell  # a SCARA's wall mount is a console: axes vertical
    tp80 = load_robot("TP80")
    assert tp80.native_mount == "ceiling" and tp80.world_in_cell == floor.world_in_cell


def test_bad_arm_cfx(tmp_path):
    cfx = tmp_path / "arm.cfx"
    cfx.write_text("<arm><String name='tuning' value=''/></arm>", encoding="utf-8")
    with pytest.raises(RobotError, match='no <String name="arm"'):
        load_robot(str(cfx))
    cfx.write_text("<arm><String name='arm' value='tx2-60-S1'", encoding="utf-8")
    with pytest.raises(RobotError, match="cannot read"):
        load_robot(str(cfx))
    cfx.write_text('<!DOCTYPE a [<!ENTITY e "x">]><arm><String name="arm" value="&e;"/></arm>', encoding="utf-8")
    with pytest.raises(RobotError, match="cannot read"):  # entities are never followed
        load_robot(str(cfx))
    cfx.write_text("<arm><String name='arm' value='ts2_60-S1'/><String name='mount' value='upside'/>"
                   "<String name='lengthAxis3' value='long'/></arm>", encoding="utf-8")
    robot = load_robot(str(cfx))
    assert robot.name == "TS2-60" and robot.mount == "floor"
    assert any("upside" in n for n in robot.notes) and any("'long'" in n for n in robot.notes)


def test_robots_cli_from_a_scara_tree(capsys):
    assert main(["robots", "--app", str(CONTROLLERS / "ts60-wall" / "usr" / "usrapp" / "Sort")]) == 0
    out = capsys.readouterr().out
    assert out.startswith("TS60-L200  (arm.cfx: ts60)")
    assert "SCARA (RS/TS, manual 9.7.5): VAL 3 types pointRs, jointRs, configRs" in out
    assert "mount: wall" in out and "stroke_mm = 200 [controller]" in out
    assert "chosen from:" in out and "ts60-S1" in out
