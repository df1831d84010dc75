"""Issue 9: hostile configurations, command-line values and arm models end with a clear message
(exit 2), never a traceback or a hang (items 4, 10, 12, 13, 14 and the misleading diagnostics)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from support import write_app
from val3check.config import ConfigError, find_config, load_settings
from val3check.robot import RobotError, load_robot
from val3check.robot.urdf import read_urdf

ROOT = Path(__file__).resolve().parent.parent.parent


def val3check(*args, cwd, timeout=60):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    return subprocess.run([sys.executable, "-m", "val3check", *map(str, args)], capture_output=True, text=True,
                          cwd=cwd, env=env, timeout=timeout)


def clean(r, codes=(0, 1, 2)):
    assert r.returncode in codes, (r.returncode, r.stdout, r.stderr)
    assert "Traceback" not in r.stderr and "internal error" not in r.stdout + r.stderr, r.stderr


# ---- configuration (items 13, 14) --------------------------------------------------------------

@pytest.mark.parametrize("text,fragment", [
    ("max-file-size = 9223372036854775807", "max-file-size"),
    ("max-file-size = -1", "max-file-size"),
    ("fail-on = 5", "fail-on"),
    ("[tool]\nval3check = []", "must be a table"),
    ("tool = 5", "'tool' must be a table"),
    ("a = " + "[" * 3000 + "]" * 3000, "nested too deeply"),
    ("select = [1]", "list of strings"),
])
def test_bad_configuration_values(tmp_path, text, fragment):
    (tmp_path / "val3check.toml").write_text(text)
    with pytest.raises(ConfigError, match=fragment):
        load_settings(str(tmp_path / "val3check.toml"))


@pytest.mark.parametrize("text", [
    "[tool.val3check\n", "[tool.val3check]\na = " + "{x = " * 2000 + "1" + "}" * 2000, "[tool.val3check]\n\xff",
    "tool = 5\n[tool.val3check]\n",
])
def test_unreadable_pyproject_is_ignored_and_said(tmp_path, text):
    (tmp_path / "pyproject.toml").write_bytes(text.encode("latin-1"))
    warnings = []
    assert find_config(str(tmp_path), warn=warnings.append) is None
    assert len(warnings) == 1 and "pyproject.toml" in warnings[0] and "ignored" in warnings[0]
    write_app(tmp_path, "begin\nend\n")
    r = val3check("lint", "Example", cwd=tmp_path)
    clean(r, (0,))
    assert "warning:" in r.stderr and "ignored" in r.stderr


def test_a_pyproject_that_is_not_ours_is_ignored_quietly(tmp_path):
    (tmp_path / "pyproject.toml").write_text("tool = 5\n[project\n")
    write_app(tmp_path, "begin\nend\n")
    r = val3check("lint", "Example", cwd=tmp_path)
    clean(r, (0,))
    assert r.stderr == ""


def test_our_section_of_the_wrong_type_is_an_error(tmp_path):
    (tmp_path / "pyproject.toml").write_text("[tool]\nval3check = 3\n")
    write_app(tmp_path, "begin\nend\n")
    r = val3check("lint", "Example", cwd=tmp_path)
    clean(r, (2,))
    assert "[tool.val3check] must be a table" in r.stderr


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="FIFOs")
def test_configuration_that_is_a_fifo_or_a_device(tmp_path):
    os.mkfifo(tmp_path / "fifo.toml")
    write_app(tmp_path, "begin\nend\n")
    for cfg in (tmp_path / "fifo.toml", "/dev/zero"):
        r = val3check("lint", "--config", cfg, "Example", cwd=tmp_path, timeout=30)
        clean(r, (2,))
        assert "cannot read configuration" in r.stderr


def test_unknown_rule_codes_are_refused_by_sim_too(tmp_path):
    write_app(tmp_path, "begin\nend\n")
    (tmp_path / "val3check.toml").write_text('ignore = ["Q999"]\n')
    for cmd in ("lint", "sim"):
        r = val3check(cmd, "Example", cwd=tmp_path)
        clean(r, (2,))
        assert "unknown rule code or prefix: Q999" in r.stderr


# ---- command line (item 10) ---------------------------------------------------------------------

@pytest.mark.parametrize("option", [("--duration", "inf"), ("--duration", "nan"), ("--duration", "1e308"),
                                    ("--max-wall", "inf"), ("--duration", "-1")])
def test_absurd_budgets(tmp_path, option):
    write_app(tmp_path, "begin\nend\n")
    r = val3check("sim", "Example", *option, cwd=tmp_path)
    clean(r, (2,))
    assert "--duration" in r.stderr


def test_empty_path_says_so(tmp_path):
    r = val3check("lint", "", cwd=tmp_path)
    clean(r, (2,))
    assert "empty path" in r.stdout


# ---- arm models (items 4, 12) ------------------------------------------------------------------

URDF = """<?xml version="1.0"?>
{doctype}<robot name="r">
  <val3check arm="X" world_frame="base" flange_frame="l2" />
  <link name="base"/><link name="l1"/><link name="l2"/>
  {joints}
</robot>
"""


def _joint(name, parent, child):
    return (f'<joint name="{name}" type="revolute"><parent link="{parent}"/><child link="{child}"/>'
            '<axis xyz="0 0 1"/><limit lower="-1" upper="1" velocity="1" effort="1"/></joint>')


@pytest.mark.parametrize("joints,fragment", [
    (_joint("j1", "base", "l1") + _joint("j2", "l1", "l2") + _joint("j3", "l2", "l1"), "child of two joints"),
    (_joint("j1", "l1", "l2") + _joint("j2", "l2", "l1"), "cycle"),
    (_joint("j1", "base", "l1") + _joint("j2", "l2", "l2"), "to itself"),
])
def test_urdf_joints_that_are_not_a_tree(tmp_path, joints, fragment):
    p = tmp_path / "r.urdf"
    p.write_text(URDF.format(doctype="", joints=joints))
    with pytest.raises(RobotError, match=fragment):
        read_urdf(p)
    write_app(tmp_path, "begin\nend\n")
    r = val3check("sim", "Example", "--robot", p, cwd=tmp_path, timeout=30)
    clean(r, (2,))


ENTITY = '<!DOCTYPE robot [<!ENTITY e "boom">]>\n'


def test_urdf_and_arm_cfx_with_entities_are_refused(tmp_path):
    p = tmp_path / "r.urdf"
    p.write_text(URDF.format(doctype=ENTITY, joints=_joint("j1", "base", "l1")))
    with pytest.raises(RobotError, match="never followed"):
        read_urdf(p)
    ctrl = tmp_path / "ctrl" / "usr"
    (ctrl / "configs").mkdir(parents=True)
    (ctrl / "configs" / "arm.cfx").write_text(
        '<?xml version="1.0"?>\n' + ENTITY.replace("robot", "Configuration")
        + '<Configuration><String name="arm" value="&e;"/></Configuration>\n')
    app = write_app(ctrl / "usrapp", "begin\nend\n")
    with pytest.raises(RobotError, match="never followed"):
        load_robot(None, app)
    r = val3check("sim", app, cwd=tmp_path)
    clean(r)
    r = val3check("robots", "--app", app, cwd=tmp_path)
    clean(r, (2,))


@pytest.mark.parametrize("old,new,fragment", [
    ('<axis xyz="0 0 1"/>', '<axis xyz="0 0 0"/>', "axis 0 0 0"),
    ('lower="-1"', 'lower="2"', "above upper"),
    ('<axis', '<origin xyz="1e300 0 0"/><axis', "beyond"),
])
def test_urdf_joint_values_that_make_no_arm(tmp_path, old, new, fragment):
    p = tmp_path / "r.urdf"
    p.write_text(URDF.format(doctype="", joints=_joint("j1", "base", "l1").replace(old, new)))
    with pytest.raises(RobotError, match=fragment):
        read_urdf(p)
    r = val3check("robots", p, cwd=tmp_path)
    clean(r, (2,))


def test_urdf_absurd_numbers_and_special_files(tmp_path):
    p = tmp_path / "r.urdf"
    p.write_text(URDF.format(doctype="", joints=_joint("j1", "base", "l1").replace('upper="1"', 'upper="nan"')))
    with pytest.raises(RobotError, match="finite"):
        read_urdf(p)
    with pytest.raises(RobotError, match="special file"):
        read_urdf("/dev/zero")


def test_arm_cfx_is_only_taken_from_a_controller_tree(tmp_path):
    # a folder that merely has configs/arm.cfx above the application is not a controller tree
    (tmp_path / "configs").mkdir()
    (tmp_path / "configs" / "arm.cfx").write_text('<C><String name="arm" value="tx2-60-S1"/></C>')
    (tmp_path / "usr" / "configs").mkdir(parents=True)
    (tmp_path / "usr" / "configs" / "arm.cfx").write_text('<C><String name="arm" value="tx2-60-S1"/></C>')
    app = write_app(tmp_path / "apps", "begin\nend\n")
    with pytest.raises(RobotError, match="no usr/configs/arm.cfx"):
        load_robot(None, app)
