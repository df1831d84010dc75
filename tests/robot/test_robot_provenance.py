"""What is a public fact and what is an assumption, in every model; the user's values in their place."""

from __future__ import annotations

import json
import re

import pytest

from val3check.cli import main
from val3check.robot import RobotError, load_robot

from .robothelp import ARMS, ROOT, SCARAS, SIX_AXIS, close_pose, joint_dist, random_joints

BORROWED_SPEEDS = {"TX2-40": "TX40", "TX2-140": "TX2-160L", "TX2-160": "TX2-160L", "RX90B": "TX90", "RX90BL": "TX90L",
                   "RX130B": "RX160"}


@pytest.mark.parametrize("name", ARMS)
def test_every_model_states_its_sources_and_assumptions(name):
    robot = load_robot(name)
    pv = robot.provenance
    assert {f.key for f in pv.facts} >= {"geometry", "limits"}
    assert all(f.text for f in pv.facts) and all(a.text and a.value for a in pv.assumptions)
    assert "ramp_s" in robot.assumed  # no joint acceleration is public
    refs = {r.key for r in pv.references}
    for text in [f.text for f in pv.facts] + [a.text for a in pv.alternatives] + [a.text for a in pv.assumptions]:
        assert set(re.findall(r"\b(S\d)\b", text)) <= refs, (name, text)  # every source named is explained
    if name in SCARAS:
        assert {"nominal_speeds", "world_z_mm", "axis4_sign"} <= robot.assumed
        assert "max_torques" in {m.key for m in pv.missing} and robot.max_torques == (None,) * 4
    if name in BORROWED_SPEEDS:
        src = load_robot(BORROWED_SPEEDS[name])
        assert robot.nominal_speeds == src.nominal_speeds and "nominal_speeds" in robot.assumed
        assert BORROWED_SPEEDS[name] in {a.key: a for a in pv.assumptions}["nominal_speeds"].text


CHOSEN = {  # where sources disagree: the model holds the kept value
    ("TX2-60", "limits.j3"): lambda r: r.joint_limits[2] == (-152.5, 152.5),
    ("TX60", "limits.j5"): lambda r: r.joint_limits[4] == (-122.5, 132.5),
    ("TX60L", "limits.j3"): lambda r: r.joint_limits[2] == (-152.5, 152.5),
    ("TX60L", "limits.j5"): lambda r: r.joint_limits[4] == (-122.5, 132.5),
    ("TX2-160L", "limits.j2"): lambda r: r.joint_limits[1] == (-137.5, 137.5),
    ("TX2-160L", "limits.j3"): lambda r: r.joint_limits[2] == (-160, 160),
    ("TX2-160L", "limits.j5"): lambda r: r.joint_limits[4] == (-110, 135),
    ("TX2-160L", "world_height_mm"): lambda r: r.chain.world_in_root[2][3] == 550,
    ("TX200", "a1_mm"): lambda r: r.opw.a1 == 250,
    ("TX200", "c4_mm"): lambda r: r.opw.c4 == 194,
    ("TS2-100", "limits.j2"): lambda r: r.joint_limits[1] == (-141.5, 141.5),
    ("TS2-100-L400", "limits.j2"): lambda r: r.joint_limits[1] == (-160, 160),
    ("TP80", "axis3_sign"): lambda r: r.fk([0, 0, 10, 0])[2] - r.fk([0, 0, 0, 0])[2] > 0,
    ("TP80", "axis4_sign"): lambda r: r.scara.signs[3] == -1,
}


def test_disagreements_are_stated_and_the_kept_value_is_the_models():
    found = {(n, a.key) for n in ARMS for a in load_robot(n).provenance.alternatives}
    assert found == set(CHOSEN)
    for (name, key), check in CHOSEN.items():
        assert check(load_robot(name)), (name, key)


def test_robots_list_groups_by_family_and_marks_assumptions(capsys):
    assert main(["robots"]) == 0
    out = capsys.readouterr().out
    titles = [line for line in out.splitlines() if "VAL 3 types" in line]
    assert [t.split(":")[0] for t in titles] == ["TX six-axis arms (CS8)", "TX2 six-axis arms (CS9)", "RX six-axis arms",
                                                 "TS2 SCARA arms (CS9)", "TS SCARA arms (CS8)",
                                                 "TP fast picker (four-axis, ceiling-mounted)"]
    sections = out.split("\n\n")
    scara_part = "\n".join(s for s in sections if "pointRs" in s)
    for name in SCARAS:
        assert f"\n{name} " in scara_part
    # the TS2-60 is the SCARA rule's reference reach (620 mm): its reference speeds (robots/dynamics.py)
    assert "±500° 3000°/s*" in scara_part and "-0.1..200.1 mm 2000 mm/s*" in scara_part
    row = next(line for line in out.splitlines() if line.startswith("TX2-40 "))
    assert "555°/s*" in row and row.endswith("accel, speeds") and "tx2_40?" in row
    assert "TX2-200   tx2_200   TX200" in out


def test_robots_detail_shows_facts_assumptions_and_alternatives(capsys):
    assert main(["robots", "TX2-60"]) == 0
    out = capsys.readouterr().out
    assert "public facts" in out and "ROS-Industrial" in out
    assert "ramp_s = 0.25" in out
    assert "limits.j3: -152.5..152.5 (kept), -142.5..142.5 (other)" in out
    assert main(["robots", "TS2-60"]) == 0
    out = capsys.readouterr().out
    for key in ("world_z_mm = 0", "axis4_sign = -1", "nominal_speeds = 800 1200 2000 3000", "ramp_s = 0.04:"):
        assert key in out
    assert "not public" in out and "max_torques" in out
    assert "j3      mm    -0.1  200.1     2000*" in out


def test_robots_json_has_the_provenance(capsys):
    assert main(["robots", "TS60", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)["robots"][0]
    assert data["family"] == "scara" and data["type_family"] == "Rs"
    assert data["joints"][2]["unit"] == "mm" and data["joints"][2]["max_mm"] == 400.1
    assert {a["key"] for a in data["assumptions"]} >= {"world_z_mm", "axis4_sign", "nominal_speeds", "ramp_s"}
    assert data["scara_mm"]["l1"] == 330


# ---- the user's values (robot files, with_assumptions) ---------------------------------------------


ROBOT_FILE = """
arm = "TS2-60"
name = "Cell 3 SCARA"
[assume]
nominal_speeds = [420, 650, 1100, 2000]
ramp_s = 0.2
limits = { j3 = [0, 180] }
mount = "ceiling"
world_z_mm = -25
axis4_sign = 1
"""


def test_robot_file_replaces_assumptions(tmp_path, capsys):
    p = tmp_path / "cell3.toml"
    p.write_text(ROBOT_FILE, encoding="utf-8")
    robot = load_robot(str(p))
    assert robot.name == "Cell 3 SCARA" and robot.mount == "ceiling"
    assert robot.nominal_speeds == (420, 650, 1100, 2000)
    assert robot.accelerations == pytest.approx((2100, 3250, 5500, 10000))  # nominal / 0.2 s
    assert robot.joint_limits[2] == (0, 180)
    assert robot.fk([0, 0, 0, 0])[2] == pytest.approx(-25)  # the flange at j3 = 0 in the user's world
    assert robot.fk([0, 0, 40, 0])[2] == pytest.approx(15)
    rz0, rz1 = robot.fk([0, 0, 0, 0])[5], robot.fk([0, 0, 0, 30])[5]
    assert rz1 - rz0 == pytest.approx(-30)  # axis 4 about +Z now
    by = {a.key: a.by for a in robot.provenance.assumptions}
    assert all(by[k] == "user" for k in ("nominal_speeds", "ramp_s", "limits", "mount", "world_z_mm", "axis4_sign"))
    assert load_robot("TS2-60").nominal_speeds == (800, 1200, 2000, 3000)  # the catalogue model is unchanged
    # the kinematics stays whole: closed form, chain and pinocchio agree, IK round trip
    import random

    rng = random.Random(3)
    for _ in range(100):
        q = random_joints(robot, rng)
        T = robot.fk_matrix(q)
        assert close_pose(T, robot.fk_chain(q))
        assert joint_dist(robot.ik(T, near=q)[0], q) < 1e-6
    pytest.importorskip("pinocchio")
    q = [10, 20, 30, 40]
    assert close_pose(robot.fk_matrix(q), robot.fk_pinocchio(q))
    assert main(["robots", str(p)]) == 0
    out = capsys.readouterr().out
    assert out.startswith("Cell 3 SCARA") and "world_z_mm = -25 [user]: given by the user (the model assumed 0)" in out


def test_robot_file_with_a_urdf_beside_it(tmp_path):
    (tmp_path / "arm.urdf").write_text((ROOT / "robots" / "tx2-60.urdf").read_text(encoding="utf-8"), encoding="utf-8")
    p = tmp_path / "cell.toml"
    p.write_text('arm = "arm.urdf"\n[assume]\nlimits = { j3 = [-142.5, 142.5] }\n', encoding="utf-8")
    robot = load_robot(str(p))
    assert robot.joint_limits[2] == (-142.5, 142.5)  # the other source's value, chosen by the user
    assert not robot.in_limits([0, 0, 150, 0, 0, 0]) and load_robot("TX2-60").in_limits([0, 0, 150, 0, 0, 0])


@pytest.mark.parametrize("text,message", [
    ('arm = "TX2-60"\n[assume]\nspeed = 3\n', "unknown assumption 'speed'"),
    ('arm = "TX2-60"\n[assume]\nworld_z_mm = 3\n', "only for a SCARA"),
    ('arm = "TX2-60"\n[assume]\nnominal_speeds = [1, 2, 3]\n', "3 values for the 6 axes"),
    ('arm = "TX2-60"\n[assume]\nnominal_speeds = { j7 = 3 }\n', "not an axis"),
    ('arm = "TX2-60"\n[assume]\nnominal_speeds = { j1 = -3 }\n', "positive"),
    ('arm = "TX2-60"\n[assume]\nlimits = { j1 = [10, -10] }\n', "not below"),
    ('arm = "TX2-60"\n[assume]\nmount = "sky"\n', "floor, wall, ceiling"),
    ('arm = "TS2-60"\n[assume]\naxis4_sign = 2\n', "1 or -1"),
    ('arm = "TS2-60"\n[assume]\nramp_s = "fast"\n', "a number"),
    ('[assume]\nramp_s = 1\n', 'arm = "TX2-60"'),
    ('arm = "other.toml"\n', "cannot name another robot file"),
    ('arm = "TX2-60"\nspeed = 1\n', "unknown key 'speed'"),
    ('arm = "TX2-60"\n[assume\n', "not a valid TOML"),
    ('arm = "TX9-99"\n', "unknown robot"),
])
def test_robot_file_errors(tmp_path, text, message):
    p = tmp_path / "bad.toml"
    p.write_text(text, encoding="utf-8")
    with pytest.raises(RobotError, match=re.escape(message)):
        load_robot(str(p))


def test_with_assumptions_in_code():
    robot = load_robot("RX130B").with_assumptions({"nominal_speeds": {"j1": 150}, "max_torques": [1, 2, 3, 4, 5, 6]})
    assert robot.nominal_speeds[0] == 150 and robot.nominal_speeds[1:] == load_robot("RX130B").nominal_speeds[1:]
    assert robot.accelerations[0] == 600 and robot.max_torques == (1, 2, 3, 4, 5, 6)
    assert "given by the user" in {a.key: a for a in robot.provenance.assumptions}["nominal_speeds"].text


@pytest.mark.parametrize("name", SIX_AXIS[:3] + SCARAS[:2])
def test_family_api(name):
    robot = load_robot(name)
    scara = name in SCARAS
    assert robot.family == ("scara" if scara else "six-axis")
    assert robot.type_family == ("Rs" if scara else "Rx")
    assert robot.axes == (4 if scara else 6) and len(robot.config_of([0.0] * robot.axes)) == (1 if scara else 3)
