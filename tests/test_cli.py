"""The command line end to end, as a user runs it (subprocesses, real files)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from val3check.testing import write_app

ROOT = Path(__file__).resolve().parent.parent


def val3check(*args, cwd=None, env_extra=None):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    env.pop("NO_COLOR", None)
    env.update(env_extra or {})
    return subprocess.run(
        [sys.executable, "-m", "val3check", *map(str, args)], capture_output=True, text=True, cwd=cwd, env=env, timeout=120
    )


GOOD = "begin\n  nX = 1\nend\n"
BAD = "begin\n  if true\n    nX = 1\nend\n"


def test_clean_application_exits_0(tmp_path):
    write_app(tmp_path, GOOD, globals_=["num nX"])
    r = val3check("lint", "Example", cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "All checks passed" in r.stdout
    assert r.stderr == ""


def test_syntax_error_exits_1_with_position_and_caret(tmp_path):
    write_app(tmp_path, BAD)
    r = val3check("lint", "Example", cwd=tmp_path)
    assert r.returncode == 1
    first = r.stdout.splitlines()[0]
    assert first.startswith("Example/start.pgx:7:1: F101")
    assert "\x1b[" not in r.stdout  # no colour when not on a terminal
    assert "^" in r.stdout


def test_missing_path_exits_2(tmp_path):
    r = val3check("lint", "nowhere", cwd=tmp_path)
    assert r.returncode == 2
    assert "F001" in r.stdout and "nowhere" in r.stdout
    assert "Traceback" not in r.stderr


def test_usage_error_exits_2(tmp_path):
    r = val3check("lint", "--format", "xml", cwd=tmp_path)
    assert r.returncode == 2
    assert "invalid choice" in r.stderr


def test_unknown_code_in_select_exits_2(tmp_path):
    write_app(tmp_path, GOOD)
    r = val3check("lint", "Example", "--select", "Z9", cwd=tmp_path)
    assert r.returncode == 2 and "Z9" in r.stderr


def test_fail_on_and_ignore(tmp_path):
    write_app(tmp_path, BAD)
    assert val3check("lint", "Example", "--ignore", "F101", cwd=tmp_path).returncode == 0
    assert val3check("lint", "Example", "--fail-on", "never", cwd=tmp_path).returncode == 0


def test_config_file_ignore_and_severity(tmp_path):
    write_app(tmp_path, BAD)
    (tmp_path / "val3check.toml").write_text('[severity]\nF101 = "warning"\n')
    r = val3check("lint", "Example", "--format", "json", cwd=tmp_path)
    assert r.returncode == 0, r.stdout  # a warning is below the default fail-on (error)
    report = json.loads(r.stdout)
    assert [d["severity"] for d in report["diagnostics"]] == ["warning"]
    assert val3check("lint", "Example", "--fail-on", "warning", cwd=tmp_path).returncode == 1
    assert val3check("lint", "Example", "--isolated", cwd=tmp_path).returncode == 1


def test_bad_config_exits_2(tmp_path):
    write_app(tmp_path, GOOD)
    (tmp_path / "val3check.toml").write_text("select = [\n")
    r = val3check("lint", "Example", cwd=tmp_path)
    assert r.returncode == 2 and "val3check.toml" in r.stderr


def test_output_file_and_nothing_else_written(tmp_path):
    write_app(tmp_path, BAD)
    before = sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*"))
    r = val3check("lint", "Example", "--format", "sarif", "-o", "out.sarif", cwd=tmp_path)
    assert r.returncode == 1 and r.stdout == ""
    after = sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*"))
    assert set(after) - set(before) == {Path("out.sarif")}
    assert json.loads((tmp_path / "out.sarif").read_text())["version"] == "2.1.0"


@pytest.mark.parametrize("fmt", ["text", "json", "sarif", "junit", "github"])
def test_every_format_is_deterministic(tmp_path, fmt):
    write_app(tmp_path, BAD)
    a = val3check("lint", "Example", "--format", fmt, cwd=tmp_path)
    b = val3check("lint", "Example", "--format", fmt, cwd=tmp_path)
    assert a.returncode == b.returncode == 1
    assert a.stdout == b.stdout and a.stdout


def test_colour_when_forced(tmp_path):
    write_app(tmp_path, BAD)
    r = val3check("lint", "Example", "--color", "always", cwd=tmp_path)
    assert "\x1b[" in r.stdout


def test_statistics(tmp_path):
    write_app(tmp_path, BAD)
    r = val3check("lint", "Example", "--statistics", cwd=tmp_path)
    assert "F101" in r.stdout and "syntax-error" in r.stdout


def test_rules_and_rule(tmp_path):
    r = val3check("rules")
    assert r.returncode == 0 and "F101" in r.stdout
    listing = json.loads(val3check("rules", "--format", "json").stdout)
    assert any(x["code"] == "F101" for x in listing["rules"])
    r = val3check("rule", "f101")
    assert r.returncode == 0 and "F101" in r.stdout and "Fails" in r.stdout and "Passes" in r.stdout
    r = val3check("rule", "X999")
    assert r.returncode == 2


def test_version_and_no_command():
    assert val3check("--version").stdout.startswith("val3check ")
    assert val3check().returncode == 2


def test_dtx_argument_stands_for_its_application(tmp_path):
    folder = write_app(tmp_path, BAD)
    r = val3check("lint", folder / "Example.dtx", folder / "start.pgx", cwd=tmp_path)
    assert r.returncode == 1
    assert r.stdout.count("F101") == 1  # one application, checked once


def test_excluded_folders_report_nothing(tmp_path):
    write_app(tmp_path / "keep", GOOD, globals_=["num nX"])
    write_app(tmp_path / "archive", BAD)
    (tmp_path / "archive" / "Example" / "Example.dtx").write_text("<Database")  # a loader finding too
    assert val3check("lint", ".", cwd=tmp_path).returncode == 1
    (tmp_path / "val3check.toml").write_text('exclude = ["archive/**"]\n')
    r = val3check("lint", ".", cwd=tmp_path)
    assert r.returncode == 0, r.stdout
    assert "archive" not in r.stdout


def test_a_report_written_in_pieces_leaves_no_half_file(tmp_path, capsys):
    # cli.common.write takes a streamed report's pieces: a fault while making one propagates
    # and a write error is reported; neither leaves a partial report behind
    from val3check.cli.common import write

    def pieces():
        yield "{\n"
        raise RuntimeError("fault while making the report")

    out = tmp_path / "r.json"
    with pytest.raises(RuntimeError):
        write(pieces(), str(out))
    assert not out.exists()
    assert write(iter(["{", "}\n"]), str(out)) and out.read_text() == "{}\n"
    if Path("/dev/full").exists():  # a device: reported, and not removed
        for size in (1, 100_000):  # the error comes at close, or at a write
            assert write(iter(["x" * size]), "/dev/full") is False
            assert "cannot write" in capsys.readouterr().err
        assert Path("/dev/full").exists()
