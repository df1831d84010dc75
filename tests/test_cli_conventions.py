"""Conventions users know from ruff and CI tools (issue 16): exclusions, exit codes, options,
CI formats from a sub-folder, JUnit counts against the exit code. End to end, as a user runs it."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from val3check.testing import write_app

ROOT = Path(__file__).resolve().parent.parent
GOOD = "begin\n  nX = 1\nend\n"
BAD = "begin\n  if true\n    nX = 1\nend\n"
WARN = "begin\n  nX = nX\nend\n"  # S015 self-assignment: a warning


def val3check(*args, cwd=None, env_extra=None, stdin=None):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    for k in ("NO_COLOR", "FORCE_COLOR"):
        env.pop(k, None)
    env.update(env_extra or {})
    return subprocess.run([sys.executable, "-m", "val3check", *map(str, args)], capture_output=True, text=True,
                          cwd=cwd, env=env, timeout=300, input=stdin)


# -- exclusions (items 3 and 4) ----------------------------------------------------------------

def test_only_excluded_files_named_exit_0_and_missing_path_stays_2(tmp_path):
    folder = write_app(tmp_path / "ctrl" / "usr" / "templates", BAD, name="Tpl")
    (tmp_path / "val3check.toml").write_text("force-exclude = true\n")
    r = val3check("lint", folder / "start.pgx", folder / "Tpl.dtx", cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "0 files checked" in r.stdout and "nothing to check" in r.stderr
    r = val3check("lint", "--force-exclude", folder / "start.pgx", "nowhere.pgx", cwd=tmp_path)
    assert r.returncode == 2 and "nowhere.pgx: F001" in r.stdout


def test_a_named_path_is_checked_unless_force_exclude(tmp_path):
    folder = write_app(tmp_path / "archive", BAD, name="Old")
    (tmp_path / "val3check.toml").write_text('exclude = ["archive"]\n')
    assert val3check("lint", folder, cwd=tmp_path).returncode == 1  # named: checked, as ruff does
    assert val3check("lint", "--force-exclude", folder, cwd=tmp_path).returncode == 0
    assert val3check("lint", "--no-force-exclude", folder, cwd=tmp_path).returncode == 1


def test_gitignore_semantics_and_the_default(tmp_path):
    write_app(tmp_path, GOOD, name="Keep", globals_=["num nX"])
    write_app(tmp_path / "a" / "templates", BAD, name="T1")  # `templates` at any depth
    write_app(tmp_path / "ctrl" / "usr" / "templates", BAD, name="T2")  # excluded by default
    r = val3check("lint", ".", cwd=tmp_path)
    assert r.returncode == 1 and "T1/start.pgx" in r.stdout and "T2" not in r.stdout
    (tmp_path / "val3check.toml").write_text('extend-exclude = ["templates"]\n')
    r = val3check("lint", ".", cwd=tmp_path)
    assert r.returncode == 0, r.stdout
    # `exclude` replaces the default, as in ruff
    (tmp_path / "val3check.toml").write_text('exclude = ["a/templates/"]\n')
    r = val3check("lint", ".", cwd=tmp_path)
    assert r.returncode == 1 and "T2/start.pgx" in r.stdout and "T1" not in r.stdout
    # the command line: --exclude replaces, --extend-exclude adds
    r = val3check("lint", ".", "--isolated", "--exclude", "T1,T2", cwd=tmp_path)
    assert r.returncode == 0, r.stdout
    r = val3check("lint", ".", "--isolated", "--extend-exclude", "/a/", cwd=tmp_path)
    assert r.returncode == 0, r.stdout
    r = val3check("lint", ".", "--isolated", "--extend-exclude", "!T1", cwd=tmp_path)
    assert r.returncode == 1


def test_a_folder_where_everything_is_excluded_has_nothing_to_check(tmp_path):
    write_app(tmp_path / "ctrl" / "usr" / "templates", BAD, name="Tpl")
    r = val3check("lint", ".", cwd=tmp_path)
    assert r.returncode == 0 and "nothing to check" in r.stderr
    empty = tmp_path / "empty"
    empty.mkdir()
    assert val3check("lint", "empty", cwd=tmp_path).returncode == 2  # no application at all: F008


def test_a_file_that_is_not_val3(tmp_path):
    (tmp_path / "README.md").write_text("# My cell\n\nSee <here>.\n")
    r = val3check("lint", "README.md", cwd=tmp_path)
    assert r.returncode == 2
    assert "README.md: F006 [error] not a VAL 3 file" in r.stdout and "malformed XML" not in r.stdout


# -- CI formats (items 5 and 6) ----------------------------------------------------------------

def _repo(tmp_path, code=BAD):
    (tmp_path / ".git").mkdir()  # the repository root, as git leaves it
    write_app(tmp_path / "cells", code, name="Pick", globals_=["num nX"])
    return tmp_path / "cells"


def test_sarif_and_github_from_a_sub_folder_name_repository_paths(tmp_path):
    sub = _repo(tmp_path)
    schema = json.loads((ROOT / "tests" / "data" / "sarif-schema-2.1.0.json").read_text())
    import jsonschema

    r = val3check("lint", "Pick", "--output-format", "sarif", cwd=sub)
    assert r.returncode == 1
    sarif = json.loads(r.stdout)
    jsonschema.Draft7Validator(schema).validate(sarif)
    run = sarif["runs"][0]
    loc = run["results"][0]["locations"][0]["physicalLocation"]["artifactLocation"]
    assert loc == {"uri": "cells/Pick/start.pgx", "uriBaseId": "%SRCROOT%"}
    assert run["originalUriBaseIds"]["%SRCROOT%"]["uri"] == tmp_path.as_uri() + "/"
    assert run["invocations"] == [{"executionSuccessful": True, "exitCode": 1}]
    r = val3check("lint", "Pick", "--output-format", "github", cwd=sub)
    assert r.stdout.startswith("::error file=cells/Pick/start.pgx,line=7,col=1")
    r = val3check("lint", "nowhere", "--output-format", "sarif", cwd=sub)
    assert json.loads(r.stdout)["runs"][0]["invocations"] == [{"executionSuccessful": False, "exitCode": 2}]


def test_without_git_the_configuration_folder_is_the_root(tmp_path):
    write_app(tmp_path / "cells", BAD, name="Pick")
    (tmp_path / "val3check.toml").write_text("fail-on = \"error\"\n")
    r = val3check("lint", "Pick", "--output-format", "github", cwd=tmp_path / "cells")
    if (tmp_path / ".git").exists() or any((p / ".git").exists() for p in tmp_path.parents):
        pytest.skip("the temporary folder is inside a git repository")
    assert r.stdout.startswith("::error file=cells/Pick/start.pgx,")


@pytest.mark.parametrize("code,fail_on,exit_code,failures", [
    (WARN, None, 0, 0), (WARN, "warning", 1, 1), (BAD, None, 1, 1), (BAD, "never", 0, 0), (GOOD, "info", 0, 0),
])
def test_junit_failures_agree_with_the_exit_code(tmp_path, code, fail_on, exit_code, failures):
    sub = _repo(tmp_path, code)
    args = ["lint", "Pick", "--output-format", "junit"] + (["--fail-on", fail_on] if fail_on else [])
    r = val3check(*args, cwd=sub)
    assert r.returncode == exit_code, r.stdout + r.stderr
    suite = ET.fromstring(r.stdout).find("testsuite")
    assert int(suite.get("failures")) == failures
    if code == WARN and not failures:
        outs = [c.find("system-out").text for c in suite.findall("testcase") if c.find("system-out") is not None]
        assert any("S015 [warning]" in t for t in outs)
    for case in suite.findall("testcase"):
        assert case.get("file", "").startswith("Pick/")
        if case.find("failure") is not None:
            assert int(case.get("line")) > 0


# -- options (item 7) --------------------------------------------------------------------------

def test_exit_zero_and_quiet(tmp_path):
    write_app(tmp_path, BAD)
    r = val3check("lint", "Example", "--exit-zero", cwd=tmp_path)
    assert r.returncode == 0 and "F101" in r.stdout
    assert val3check("lint", "nowhere", "--exit-zero", cwd=tmp_path).returncode == 2
    r = val3check("lint", "Example", "-q", cwd=tmp_path)
    assert r.returncode == 1 and "F101" in r.stdout and "Found" not in r.stdout
    write_app(tmp_path / "ok", GOOD, globals_=["num nX"])
    r = val3check("lint", "ok/Example", "--quiet", cwd=tmp_path)
    assert r.returncode == 0 and r.stdout == "" and r.stderr == ""


def test_concise_output(tmp_path):
    write_app(tmp_path, BAD)
    r = val3check("lint", "Example", "--output-format", "concise", cwd=tmp_path)
    lines = r.stdout.splitlines()
    assert lines[0].startswith("Example/start.pgx:7:1: F101 [error] ")
    assert "|" not in r.stdout and "^" not in r.stdout
    assert lines[-1].startswith("Found 1 error")
    assert val3check("lint", "Example", "--format", "concise", cwd=tmp_path).stdout == r.stdout  # the synonym


def test_show_settings_and_show_files(tmp_path):
    write_app(tmp_path, GOOD, globals_=["num nX"])
    (tmp_path / "val3check.toml").write_text('ignore = ["S"]\nextend-exclude = ["old/"]\n')
    r = val3check("lint", "--show-settings", cwd=tmp_path)
    assert r.returncode == 0
    assert "configuration: val3check.toml" in r.stdout and "Example/Example.pjx" in r.stdout
    assert "F101" in r.stdout and " S001" not in r.stdout
    data = json.loads(val3check("lint", "--show-settings", "--output-format", "json", cwd=tmp_path).stdout)
    assert data["settings"]["extend-exclude"] == ["old/"] and data["applications"] == ["Example/Example.pjx"]
    assert "S001" not in data["rules"] and "F101" in data["rules"]
    r = val3check("lint", "--show-files", cwd=tmp_path)
    assert r.stdout.splitlines() == ["Example/Example.dtx", "Example/Example.pjx", "Example/start.pgx",
                                     "Example/stop.pgx"]


def test_force_color_and_no_color(tmp_path):
    write_app(tmp_path, BAD)
    assert "\x1b[" in val3check("lint", "Example", cwd=tmp_path, env_extra={"FORCE_COLOR": "1"}).stdout
    assert "\x1b[" not in val3check("lint", "Example", cwd=tmp_path, env_extra={"FORCE_COLOR": ""}).stdout
    r = val3check("lint", "Example", cwd=tmp_path, env_extra={"FORCE_COLOR": "1", "NO_COLOR": "1"})
    assert "\x1b[" not in r.stdout
    assert "\x1b[" not in val3check("lint", "Example", "--color", "never", cwd=tmp_path,
                                    env_extra={"FORCE_COLOR": "1"}).stdout


def test_statistics_in_json(tmp_path):
    write_app(tmp_path, BAD)
    data = json.loads(val3check("lint", "Example", "--statistics", "--output-format", "json", cwd=tmp_path).stdout)
    assert data["version"] == 1
    assert data["statistics"] == [{"code": "F101", "count": 1, "fixable": False, "name": "syntax-error",
                                   "severity": "error"}]
    assert data["summary"]["error"] == 1


def test_rule_as_json_and_all_rules():
    one = json.loads(val3check("rule", "s001", "--output-format", "json").stdout)
    assert one["code"] == "S001" and one["examples"]["bad"] and one["explanation"]
    every = json.loads(val3check("rule", "--all", "--output-format", "json").stdout)
    listing = json.loads(val3check("rules", "--output-format", "json").stdout)
    assert [r["code"] for r in every] == [r["code"] for r in listing["rules"]]
    text = val3check("rule", "--all").stdout
    assert "F101 syntax-error" in text and "S001 unused-local" in text
    assert val3check("rule").returncode == 2


def test_sim_accepts_the_one_format_flag_and_defaults_to_the_current_folder(tmp_path):
    folder = write_app(tmp_path, "begin\n  putln(\"hi\")\nend\n")
    for flag in ("--report", "--format", "--output-format"):
        r = val3check("sim", "--duration", "1", flag, "json", cwd=folder)
        assert r.returncode == 0, r.stderr
        assert json.loads(r.stdout)["application"]["name"] == "Example"


def test_stdin_filename_checks_the_unsaved_text_in_its_application(tmp_path):
    from val3check.testing import program_file

    folder = write_app(tmp_path, GOOD, globals_=["num nX"], programs={"pick": {"code": "begin\n  if true\nend\n"}})
    on_disk = (folder / "start.pgx").read_bytes()
    edited = program_file("start", "begin\n  nX = 1\n  nY = 2\n  call pick()\nend\n")
    r = val3check("lint", "--stdin-filename", "Example/start.pgx", "--output-format", "concise", cwd=tmp_path,
                  stdin=edited)
    assert r.returncode == 1, r.stdout + r.stderr
    lines = [x for x in r.stdout.splitlines() if ": " in x and "[" in x]
    # nY is not a global of the application; pick.pgx's own syntax error is not this file's
    assert len(lines) == 1 and lines[0].startswith("Example/start.pgx:6:3: N001 [error]"), r.stdout
    assert "(1 file checked)" in r.stdout
    assert (folder / "start.pgx").read_bytes() == on_disk  # nothing written
    r = val3check("lint", "--stdin-filename", "Example/start.pgx", cwd=tmp_path, stdin=program_file("start", GOOD))
    assert r.returncode == 0 and "All checks passed (1 file checked)" in r.stdout
    r = val3check("lint", "--stdin-filename", "Example/new.pgx", cwd=tmp_path, stdin=edited)
    assert r.returncode == 2 and "no such file" in r.stderr


def test_a_dash_stands_for_standard_input_as_in_ruff(tmp_path):
    from val3check.testing import program_file

    write_app(tmp_path, GOOD, globals_=["num nX"])
    edited = program_file("start", "begin\n  nX = 1\n  nY = 2\nend\n")
    r = val3check("lint", "--stdin-filename", "Example/start.pgx", "--output-format", "concise", "-", cwd=tmp_path,
                  stdin=edited)
    assert r.returncode == 1, r.stdout + r.stderr
    assert "Example/start.pgx:6:3: N001 [error]" in r.stdout and "(1 file checked)" in r.stdout
    r = val3check("lint", "-", "--stdin-filename", "Example/start.pgx", cwd=tmp_path, stdin=program_file("start", GOOD))
    assert r.returncode == 0 and "All checks passed (1 file checked)" in r.stdout, r.stdout + r.stderr
    r = val3check("lint", "-", cwd=tmp_path, stdin=edited)  # no file to stand for
    assert r.returncode == 2 and "needs --stdin-filename" in r.stderr and "Traceback" not in r.stderr
