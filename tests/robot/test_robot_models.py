"""Arm models: every URDF loads (pinocchio too), matches the facts, and is found by name or arm.cfx."""

from __future__ import annotations

import subprocess
import sys
import tomllib

import pytest

from val3check.robot import RobotError, from_urdf, load_robot
from val3check.robot.catalog import normalize

from .robothelp import ARMS, MORE, ROOT, SCARA_ZERO_X, SCARAS, SIX_AXIS, TOML, ZERO_POSE

EXPECTED = [
    "TX40", "TX60", "TX60L", "TX90", "TX90L", "TX90XL", "TX200", "TX200L",
    "TX2-40", "TX2-60", "TX2-60L", "TX2-90", "TX2-90L", "TX2-90XL", "TX2-140", "TX2-160", "TX2-160L",
    "RX90B", "RX90BL", "RX130B", "RX160", "RX160L",
    "TS2-40", "TS2-60", "TS2-80", "TS2-100", "TS2-100-L400", "TS40", "TS60", "TS80", "TP80",
]
HAVE_FACTS = TOML.is_file() and MORE.is_file()


def test_catalogue_has_every_arm():
    assert ARMS == EXPECTED
    assert len(SIX_AXIS) == 22 and len(SCARAS) == 9


@pytest.mark.parametrize("name", EXPECTED)
def test_pinocchio_loads_every_model(name):
    pin = pytest.importorskip("pinocchio")
    robot = load_robot(name)
    model = pin.buildModelFromUrdf(robot.source)
    n = robot.axes
    assert model.nq == n and model.nv == n
    assert [model.names[i] for i in range(1, n + 1)] == [f"joint_{i}" for i in range(1, n + 1)]
    for frame in ("world", "flange"):
        assert model.existFrame(frame)
    geom = robot.collision_model()
    assert geom.ngeoms >= n + 1  # at least one solid per link
    for obj in geom.geometryObjects:
        assert type(obj.geometry).__name__ == "Cylinder"
    # limits and speeds as pinocchio reads them (metres for a SCARA's prismatic axis 3)
    import math

    for i, ((lo, hi), v, kind) in enumerate(zip(robot.joint_limits, robot.nominal_speeds, robot.joint_kinds)):
        f = (lambda x: x / 1000.0) if kind == "prismatic" else math.radians
        assert math.isclose(model.lowerPositionLimit[i], f(lo), abs_tol=1e-12)
        assert math.isclose(model.upperPositionLimit[i], f(hi), abs_tol=1e-12)
        assert math.isclose(model.velocityLimit[i], f(v), abs_tol=1e-12)
    if robot.family == "scara":
        assert model.joints[3].shortname().startswith("JointModelP")  # prismatic (PZ)


@pytest.mark.parametrize("name", SIX_AXIS)
def test_zero_position_is_a1_b_c2c3c4(name):
    robot = load_robot(name)
    x, y, z, rx, ry, rz = robot.fk([0, 0, 0, 0, 0, 0])
    ex, ey, ez = ZERO_POSE[name]
    assert (round(x, 9), round(y, 9), round(z, 9)) == (ex, ey, ez)
    assert (abs(rx), abs(ry), abs(rz)) == (0, 0, 0)
    assert max(abs(a - b) for a, b in zip(robot.fk_pinocchio([0] * 6)[0], (1, 0, 0, ex))) < 1e-9


@pytest.mark.parametrize("name", SCARAS)
def test_scara_zero_position_is_stretched_along_x_flange_down(name):
    robot = load_robot(name)
    x, y, z, rx, ry, rz = robot.fk([0, 0, 0, 0])
    assert (round(x, 9), round(y, 9) + 0.0, round(z, 9) + 0.0) == (SCARA_ZERO_X[name], 0, 0)
    assert (abs(rx), round(ry, 9) + 0.0, round(rz, 9) + 0.0) == (180, 0, 0)  # Z down, as pointRs values are taught
    assert robot.reach_mm == SCARA_ZERO_X[name]


def _facts():
    out = {}
    for path in (TOML, MORE):
        out.update(tomllib.loads(path.read_text(encoding="utf-8")))
    return out


@pytest.mark.skipif(not HAVE_FACTS, reason="shared/robots/staubli-arms*.toml not beside the checkout")
def test_models_match_the_facts():
    facts = _facts()
    assert set(facts) == set(EXPECTED)
    for name, arm in facts.items():
        robot = load_robot(name)
        assert (robot.srs_arm_id or robot.srs_arm_id_hint) == arm.get("srs_arm_id", arm.get("srs_arm_id_hint"))
        assert bool(robot.srs_arm_id) == ("srs_arm_id" in arm)
        for i in range(robot.axes):
            j = arm[f"joint{i + 1}"]
            if robot.joint_kinds[i] == "prismatic":
                assert robot.joint_limits[i] == (j["min_mm"], j["max_mm"]), (name, i)
            else:
                assert robot.joint_limits[i] == (j["min_deg"], j["max_deg"]), (name, i)
            if "nominal_speed_deg_s" in j:  # a published speed is used as it is, and is not an assumption
                assert robot.nominal_speeds[i] == j["nominal_speed_deg_s"]
                assert "nominal_speeds" not in robot.assumed
            else:
                assert "nominal_speeds" in robot.assumed, name
            assert robot.max_torques[i] == j.get("max_torque_nm")
        if "opw" in arm:
            for k, v in arm["opw"].items():
                expect = v * 1000.0 - (arm["shoulder_height_mm"] if k == "c1" else 0.0)  # world at axis 2's height
                assert abs(getattr(robot.opw, k) - expect) < 1e-9, (name, k)
        if arm.get("kind") == "scara":
            assert robot.family == "scara" and robot.type_family == "Rs"
            assert (robot.scara.l1, robot.scara.l2) == (arm["link1_mm"], arm["link2_mm"])
            assert robot.stroke_mm == arm["stroke_mm"]
        else:
            assert robot.family == "six-axis" and robot.type_family == "Rx"


@pytest.mark.skipif(not HAVE_FACTS, reason="shared/robots/staubli-arms*.toml not beside the checkout")
def test_generated_urdfs_are_up_to_date():
    r = subprocess.run([sys.executable, str(ROOT / "robots" / "generate.py"), "--check", "--toml", str(TOML), "--more", str(MORE)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


def test_accelerations_are_documented_and_overridable():
    robot = load_robot("TX2-60")
    assert robot.accelerations == tuple(v / 0.25 for v in robot.nominal_speeds)
    assert "0.25 s" in robot.acceleration_note and "assumed" in robot.acceleration_note
    other = robot.with_accelerations([1000, 1000, 1000, 2000, 2000, 3000])
    assert other.accelerations == (1000, 1000, 1000, 2000, 2000, 3000)
    assert robot.accelerations[0] == 1740  # the catalogue model is unchanged
    with pytest.raises(RobotError):
        robot.with_accelerations([1, 2, 3])


@pytest.mark.parametrize("spelling", ["TX2-60", "tx2-60", "TX2_60", "tx2_60", "tx260", "Tx2 60", "staubli tx2-60"])
def test_names_are_case_and_separator_insensitive(spelling):
    assert load_robot(spelling).name == "TX2-60"


def test_normalize_keeps_models_apart():
    assert len({normalize(n) for n in EXPECTED}) == len(EXPECTED)


def test_unknown_robot_lists_the_known_ones():
    with pytest.raises(RobotError) as err:
        load_robot("TX3-60")
    msg = str(err.value)
    assert "TX3-60" in msg
    for n in EXPECTED:
        assert n in msg


# ---- URDF metadata ---------------------------------------------------------------------------------

ARM_URDF = (ROOT / "robots" / "tx2-60.urdf").read_text(encoding="utf-8")


def _without_meta(text: str) -> str:
    start, end = text.index("  <val3check"), text.index("</val3check>") + len("</val3check>")
    return text[:start] + text[end:]


def test_urdf_without_metadata_says_what_is_missing(tmp_path):
    p = tmp_path / "arm.urdf"
    p.write_text(_without_meta(ARM_URDF), encoding="utf-8")
    with pytest.raises(RobotError) as err:
        load_robot(str(p))
    msg = str(err.value)
    assert "<val3check>" in msg and "world_frame" in msg and "flange_frame" in msg and str(p) in msg
    # naming the frames in code is enough
    robot = from_urdf(p, world_frame="world", flange_frame="flange")
    assert robot.fk([0] * 6)[:3] == pytest.approx((0, 20, 670))
    assert "assumed" in robot.acceleration_note


def test_urdf_metadata_without_flange_frame(tmp_path):
    p = tmp_path / "arm.urdf"
    p.write_text(ARM_URDF.replace(' flange_frame="flange"', ""), encoding="utf-8")
    with pytest.raises(RobotError, match="lacks flange_frame"):
        load_robot(str(p))


def test_urdf_metadata_naming_a_missing_link(tmp_path):
    p = tmp_path / "arm.urdf"
    p.write_text(ARM_URDF.replace('flange_frame="flange"', 'flange_frame="tool0"'), encoding="utf-8")
    with pytest.raises(RobotError, match="no link named 'tool0'"):
        load_robot(str(p))


def test_urdf_without_speed_says_which_joint(tmp_path):
    text = ARM_URDF
    i = text.index('<joint name="joint_4" type="revolute">')
    j = text.index("velocity=", i)
    k = text.index(" effort=", j)
    p = tmp_path / "arm.urdf"
    p.write_text(text[:j] + 'velocity="0"' + text[k:], encoding="utf-8")
    with pytest.raises(RobotError, match="joint 'joint_4' has no <limit velocity>"):
        load_robot(str(p))


def test_not_a_urdf(tmp_path):
    p = tmp_path / "arm.urdf"
    p.write_text("<robotx/>", encoding="utf-8")
    with pytest.raises(RobotError, match="not a URDF"):
        load_robot(str(p))
    with pytest.raises(RobotError, match="no such"):
        load_robot(str(tmp_path / "missing.urdf"))


def test_user_urdf_with_own_accelerations(tmp_path):
    text = ARM_URDF.replace('acceleration_deg_s2="1740"', 'acceleration_deg_s2="900"').replace('arm="TX2-60"', 'arm="Cell 3 arm"')
    p = tmp_path / "cell3.urdf"
    p.write_text(text, encoding="utf-8")
    robot = load_robot(str(p))
    assert robot.name == "Cell 3 arm"
    assert robot.accelerations[0] == 900
    assert "from the URDF" in robot.acceleration_note


# ---- arm.cfx ---------------------------------------------------------------------------------------

CFX = """<?xml version="1.0" encoding="utf-8"?>
<Configuration xmlns="http://www.staubli.com/robotics/Controller/Arm/1">
  <Arm>
    <String name="arm" value="{arm}" />
    <String name="mounting" value="floor" />
  </Arm>
</Configuration>
"""


def test_arm_cfx_of_the_fixture_controller():
    app = ROOT / "fixtures" / "valid" / "controller" / "usr" / "usrapp" / "Welder"
    assert load_robot(None, app).name == "TX2-60"
    assert load_robot(None, app / "Welder.pjx").name == "TX2-60"


@pytest.mark.parametrize("value,name", [("tx90l-S2", "TX90L"), ("TX2-90XL-S1", "TX2-90XL"), ("rx160", "RX160"), ("tx2-60l-S3", "TX2-60L"),
                                        ("tx2_60l-S3", "TX2-60L"), ("tx200-S3", "TX200"), ("ts2_60-S1", "TS2-60")])
def test_arm_cfx_prefix_before_s(tmp_path, value, name):
    cfg = tmp_path / "CS9" / "usr" / "configs"
    cfg.mkdir(parents=True)
    (cfg / "arm.cfx").write_text(CFX.format(arm=value), encoding="utf-8")
    app = tmp_path / "CS9" / "usr" / "usrapp" / "Cell"
    app.mkdir(parents=True)
    assert load_robot(None, app).name == name
    assert load_robot(str(cfg / "arm.cfx")).name == name


def test_arm_cfx_unknown_arm_and_missing_tree(tmp_path):
    cfg = tmp_path / "ctrl" / "usr" / "configs"
    cfg.mkdir(parents=True)
    (cfg / "arm.cfx").write_text(CFX.format(arm="tx3-70-S1"), encoding="utf-8")
    with pytest.raises(RobotError, match="tx3-70-S1.*known ids"):
        load_robot(None, tmp_path / "ctrl" / "usr" / "usrapp")
    (cfg / "arm.cfx").write_text(CFX.format(arm="rs20-S1"), encoding="utf-8")
    with pytest.raises(RobotError, match="SCARA.*no model for; the closest model is TS40"):
        load_robot(None, tmp_path / "ctrl" / "usr" / "usrapp")
    lone = tmp_path / "elsewhere"
    lone.mkdir()
    with pytest.raises(RobotError, match="no usr/configs/arm.cfx") as err:
        load_robot(None, lone)
    assert "TX2-60" in str(err.value)


def test_robot_package_is_not_imported_by_lint():
    code = "import val3check.cli, sys; print('robot' in ' '.join(m for m in sys.modules if m.startswith('val3check')))"
    r = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True)
    assert r.stdout.strip() == "False", r.stderr


def test_robot_package_imports_no_pinocchio_until_asked():
    code = (
        "import sys; from val3check.robot import load_robot; r = load_robot('TX90');"
        "r.ik(r.fk([10, 20, 30, 40, 50, 60])); print(sorted(m for m in ('pinocchio', 'numpy') if m in sys.modules))"
    )
    r = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True)
    assert r.stdout.strip() == "[]", r.stderr
