"""Issue 21 I (TOML parts): every TOML file a user gives (cell, scenario, sweep, configuration,
robot file) goes through val3check.tomlfile; what tomllib lets through as something other than a
TOMLDecodeError (an integer of more than 4,300 digits, nesting hundreds deep, integers beyond 64
bits) or answers in quadratic time (a dotted key of thousands of parts) is an error at its line
and column, never a traceback."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from val3check import tomlfile
from val3check.testing import write_app

ROOT = Path(__file__).resolve().parent.parent.parent

BIG_INT = "x = 1\ny = [1, " + "9" * 5000 + "]\n"  # the integer at 2:9
DEEP = "x = 1\na = " + "[" * 100_000 + "]" * 100_000 + "\n"  # the 65th bracket at 2:69
DEEP_TABLES = "a = " + "{b = " * 100_000 + "1" + "}" * 100_000 + "\n"
DOTTED = "x = 1\n" + "a" + ".a" * 40_000 + " = 1\n"  # tomllib: about a minute, quadratic
QUOTED_DOTTED = "x = 1\n" + '"a"' + '."a"' * 40_000 + " = 1\n"
HEADER_DOTTED = "[" + "a." * 40_000 + "a]\n"
INT65 = "a = [1, 2]\n[t]\nb = { c = 0x" + "f" * 17 + " }\n"


@pytest.mark.parametrize("text,line,col,fragment", [
    (BIG_INT, 2, 9, "more than 4300 digits"),
    ('x = "' + "9" * 5000 + '"\ny = ' + "8" * 5000 + "\n", 2, 5, "more than 4300 digits"),  # a string is not one
    (DEEP, 2, 69, "nested too deeply (at most 64)"),
    (DEEP_TABLES, 1, 325, "nested too deeply"),  # "a = " then 64 "{b = "
    (DOTTED, 2, 1, "dotted key of more than 64 parts"),
    (QUOTED_DOTTED, 2, 1, "dotted key of more than 64 parts"),
    (HEADER_DOTTED, 1, 2, "dotted key of more than 64 parts"),
    (INT65, 3, 11, "beyond 64 bits"),
    ("a = -9223372036854775809\n", 1, 5, "beyond 64 bits"),
    ("a = \n", 1, 5, "invalid TOML: Invalid value"),
])
def test_hostile_toml_is_a_positioned_error(text, line, col, fragment):
    with pytest.raises(tomlfile.TomlError) as e:
        tomlfile.loads(text)
    assert (e.value.line, e.value.col) == (line, col) and fragment in e.value.message, e.value


def test_what_tomllib_accepts_and_fits_is_unchanged():
    text = ('a = 1.5\nb = [1.5, 2.5, -9223372036854775808, 9223372036854775807]\nc = "x.y.z [ { #"\n'
            "d = 1979-05-27T07:32:00.999\ne = '''[[[[\n]]]]'''\n" + "k" + ".k" * 63 + " = 2\n"  # 64 parts: the limit
            "[t.u.v]\n\"q.r\".s = 1  # a.b.c.d\n")
    import tomllib

    assert tomlfile.loads(text) == tomllib.loads(text)


def test_not_utf8_is_positioned():
    with pytest.raises(tomlfile.TomlError) as e:
        tomlfile.load_bytes(b"a = 1\nb = '\xff'\n")
    assert (e.value.line, e.value.col) == (2, 6) and "not UTF-8" in e.value.message


# ---- every reader -----------------------------------------------------------------------------------

@pytest.mark.parametrize("text,line", [(BIG_INT, 2), (DEEP, 2), (DOTTED, 2), (INT65, 3)])
def test_cell_file(tmp_path, text, line):
    from val3check.collision import CellError, read_cell

    (tmp_path / "cell.toml").write_text(text)
    with pytest.raises(CellError) as e:
        read_cell(tmp_path / "cell.toml")
    assert [p[1] for p in e.value.problems] == [line], e.value.problems


@pytest.mark.parametrize("text,line", [(BIG_INT, 2), (DEEP, 2), (DOTTED, 2), (INT65, 3)])
def test_scenario_file(tmp_path, text, line):
    from val3check.simulation.scenario import ScenarioError, load_scenario

    (tmp_path / "sc.toml").write_text(text)
    with pytest.raises(ScenarioError) as e:
        load_scenario(str(tmp_path / "sc.toml"))
    assert e.value.line == line, e.value


@pytest.mark.parametrize("text,line", [(BIG_INT, 2), (DEEP, 2), (DOTTED, 2), (INT65, 3)])
def test_sweep_file(tmp_path, text, line):
    from val3check.batch.sweep import SweepError, load_sweep

    (tmp_path / "sweep.toml").write_text(text)
    with pytest.raises(SweepError) as e:
        load_sweep(str(tmp_path / "sweep.toml"))
    assert e.value.line == line, e.value


@pytest.mark.parametrize("text,where", [(BIG_INT, ":2:9:"), (DEEP, ":2:69:"), (DOTTED, ":2:1:"), (INT65, ":3:11:")])
def test_configuration_file(tmp_path, text, where):
    from val3check.config import ConfigError, load_settings

    (tmp_path / "val3check.toml").write_text(text)
    with pytest.raises(ConfigError, match=where):
        load_settings(str(tmp_path / "val3check.toml"))


def test_robot_file(tmp_path):
    from val3check.robot import RobotError
    from val3check.robot.load import load_robot_file

    (tmp_path / "arm.toml").write_text('arm = "TX2-60"\n[assume]\nx = ' + "7" * 5000 + "\n")
    with pytest.raises(RobotError, match=r"arm\.toml:3:5: .*more than 4300 digits"):
        load_robot_file(tmp_path / "arm.toml")


def test_lint_with_such_a_configuration_ends_with_exit_2(tmp_path):
    write_app(tmp_path, "begin\nend\n")
    (tmp_path / "val3check.toml").write_text("max-file-size = " + "9" * 5000 + "\n")
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    r = subprocess.run([sys.executable, "-m", "val3check", "lint", "Example"], cwd=tmp_path, env=env, check=False,
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
    assert "val3check.toml:1:17:" in r.stderr and "4300 digits" in r.stderr
