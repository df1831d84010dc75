"""`--baseline FILE` / `--update-baseline`: only new findings are reported and fail (issue 16 item 8)."""

from __future__ import annotations

import json

from test_cli_conventions import val3check

from val3check.testing import write_app

LEGACY = "begin\n  nZ = 1\n  nX = nX\n  nY = nY\nend\n"  # two S015 warnings


def _app(tmp_path, code):
    return write_app(tmp_path, code, globals_=["num nX", "num nY", "num nZ"])


def test_record_then_only_new_findings_fail(tmp_path):
    _app(tmp_path, LEGACY)
    r = val3check("lint", "Example", "--fail-on", "warning", cwd=tmp_path)
    assert r.returncode == 1 and r.stdout.count("S015") == 2
    r = val3check("lint", "Example", "--baseline", "bl.json", "--update-baseline", cwd=tmp_path)
    assert r.returncode == 0 and "recorded 2 findings in bl.json" in r.stderr
    data = json.loads((tmp_path / "bl.json").read_text())
    assert data["version"] == 1 and [e["code"] for e in data["findings"]] == ["S015", "S015"]
    assert all(e["path"] == "Example/start.pgx" and "line" not in e for e in data["findings"])
    r = val3check("lint", "Example", "--fail-on", "warning", "--baseline", "bl.json", cwd=tmp_path)
    assert r.returncode == 0, r.stdout
    assert "2 findings of the baseline not shown" in r.stdout
    # lines added above and a re-indented line: still known
    _app(tmp_path, "begin\n  // a new comment\n\n  nZ = 1\n      nX   =   nX\n  nY = nY\nend\n")
    r = val3check("lint", "Example", "--fail-on", "warning", "--baseline", "bl.json", "--output-format", "json",
                  cwd=tmp_path)
    assert r.returncode == 0, r.stdout
    assert json.loads(r.stdout)["summary"]["baselined"] == 2
    # a new finding, and a third copy of a known one, fail
    _app(tmp_path, "begin\n  nX = nX\n  nY = nY\n  nX = nX\n  nZ = nZ\nend\n")
    r = val3check("lint", "Example", "--fail-on", "warning", "--baseline", "bl.json", "--output-format", "concise",
                  cwd=tmp_path)
    assert r.returncode == 1
    assert [x.split(": ")[1].split(" ")[0] for x in r.stdout.splitlines() if ": S0" in x] == ["S015", "S015"]
    assert "nZ" in r.stdout


def test_paths_are_relative_to_the_baseline_file(tmp_path):
    _app(tmp_path / "repo", LEGACY)
    assert val3check("lint", "Example", "--baseline", "bl.json", "--update-baseline", cwd=tmp_path / "repo").returncode == 0
    r = val3check("lint", "repo/Example", "--fail-on", "warning", "--baseline", "repo/bl.json", cwd=tmp_path)
    assert r.returncode == 0, r.stdout
    (tmp_path / "repo" / "val3check.toml").write_text('baseline = "bl.json"\nfail-on = "warning"\n')
    assert val3check("lint", "repo/Example", cwd=tmp_path).returncode == 0
    assert val3check("lint", "repo/Example", "--isolated", "--fail-on", "warning", cwd=tmp_path).returncode == 1


def test_bad_baseline_is_a_usage_error(tmp_path):
    _app(tmp_path, LEGACY)
    r = val3check("lint", "Example", "--baseline", "none.json", cwd=tmp_path)
    assert r.returncode == 2 and "record one with --update-baseline" in r.stderr
    (tmp_path / "bad.json").write_text("{\"version\": 7}")
    r = val3check("lint", "Example", "--baseline", "bad.json", cwd=tmp_path)
    assert r.returncode == 2 and "not a val3check baseline" in r.stderr
    assert val3check("lint", "Example", "--update-baseline", cwd=tmp_path).returncode == 2
