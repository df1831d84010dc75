"""Issue 21, hostile input round 2, the batch's surfaces: a sweep's arms (A), the cell beside an
application in a batch (B), globs (E), a sweep's size (F), NUL bytes in paths and --out-dir (I),
a case stuck outside VAL 3 code (K). Each test fails without its fix."""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path

import pytest

from val3check.cli import main

ROOT = Path(__file__).resolve().parent.parent.parent
PICKPLACE = ROOT / "fixtures" / "valid" / "PickPlace"
SCENARIO = ROOT / "fixtures" / "scenarios" / "pickplace.toml"
SECRET = "TOPSECRET-do-not-print"
FAST = ["--duration", "2"]


@pytest.fixture
def repo(tmp_path, monkeypatch):
    """tmp/repo: a git repository holding apps/A (PickPlace without its cell) and the scenario;
    tmp/outside: secrets, beside the repository."""
    (tmp_path / "outside").mkdir()
    (tmp_path / "outside" / "cell.toml").write_text(f'unit = "{SECRET}"\n')
    (tmp_path / "outside" / "secret.urdf").write_text(f"<robot name='{SECRET}'><link name='{SECRET}'/></robot>\n")
    repo = tmp_path / "repo"
    (repo / ".git").mkdir(parents=True)
    shutil.copytree(PICKPLACE, repo / "apps" / "A")
    (repo / "apps" / "A" / "val3check-cell.toml").unlink()
    shutil.copy(SCENARIO, repo / "pickplace.toml")
    monkeypatch.chdir(repo)
    return repo


def sim(capsys, *args):
    code = main(["sim", *map(str, args)])
    out, err = capsys.readouterr()
    assert "Traceback" not in err and SECRET not in out + err, out + err
    return code, out, err


# -- B: the cell beside an application, in a batch as in the single run ------------------------

def test_a_cell_file_beside_the_application_leading_out_is_refused_in_a_batch_as_alone(repo, capsys):
    os.symlink(repo.parent / "outside" / "cell.toml", repo / "apps" / "A" / "val3check-cell.toml")
    args = ["apps/A", "--robot", "tx2-60", "--scenario", "pickplace.toml", *FAST]
    code, single, _ = sim(capsys, *args, "--report", "json")
    (r030,) = [d for d in json.loads(single)["diagnostics"] if d["code"] == "R030"]
    assert "outside the application" in r030["message"]
    for jobs in ("1", "2"):
        code, out, err = sim(capsys, *args, "-j", jobs, "--out-dir", f"out{jobs}", "--format", "json")
        (case,) = json.loads(out)["cases"]
        assert "R030" in case["reason"] and "outside the application" in case["reason"], case
        (report,) = (repo / f"out{jobs}" / "cases").iterdir()
        assert report.read_text() == single  # byte for byte the single run's report
        assert SECRET not in "".join(p.read_text() for p in (repo / f"out{jobs}").rglob("*") if p.is_file())


def test_what_a_case_carries_never_holds_a_refused_file(repo):
    """The bytes of a cell leading out never travel with the case (to a Dask cluster); a link
    does, with a stand-in of no content for its target."""
    from val3check.batch.cases import Axes, RunOptions, product_cases
    from val3check.config import Settings

    os.symlink(repo.parent / "outside" / "cell.toml", repo / "apps" / "A" / "val3check-cell.toml")
    (case,) = product_cases(Axes(["apps/A"], ["tx2-60"], [], [], []), Settings(), RunOptions())
    assert not any(SECRET.encode() in data for _, data in case.files)
    assert dict(case.links) == {str(repo / "apps" / "A" / "val3check-cell.toml"): str(repo.parent / "outside" / "cell.toml")}
    assert dict(case.stubs) == {str(repo.parent / "outside" / "cell.toml"): 0}


def test_a_cell_and_its_meshes_reached_through_links_inside_run_as_alone(repo, capsys):
    """A cell file that is a link to a file inside the application, naming a mesh through a link
    inside too, and one leading out: the case's report is the single run's."""
    folder = repo / "apps" / "A"
    (folder / "cells").mkdir()
    shutil.copy(PICKPLACE / "val3check-cell.toml", folder / "cells" / "main.toml")
    with open(folder / "cells" / "main.toml", "a") as fh:
        fh.write('\n[[obstacle]]\nname = "guard"\nshape = "mesh"\nfile = "guard.stl"\nsolid = false\nat = [900, 900, 0, 0, 0, 0]\n'
                 '\n[[obstacle]]\nname = "leak"\nshape = "mesh"\nfile = "leak.stl"\nat = [900, -900, 0, 0, 0, 0]\n')
    (folder / "meshes").mkdir()
    (folder / "meshes" / "guard.stl").write_text("solid g\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 10 0 0\n"
                                                "vertex 0 10 0\nendloop\nendfacet\nendsolid g\n")
    os.symlink("../meshes/guard.stl", folder / "cells" / "guard.stl")
    os.symlink(repo.parent / "outside" / "cell.toml", folder / "cells" / "leak.stl")
    os.symlink("cells/main.toml", folder / "val3check-cell.toml")
    args = ["apps/A", "--robot", "tx2-60", "--scenario", "pickplace.toml", *FAST]
    _, single, _ = sim(capsys, *args, "--report", "json")
    assert "leak.stl" in single and "guard.stl" not in single  # the leak refused, the guard read
    sim(capsys, *args, "-j", "1", "--out-dir", "out")
    (report,) = (repo / "out" / "cases").iterdir()
    assert report.read_text() == single


# -- A: every arm of a sweep goes through the gate, whatever its extension ---------------------

@pytest.mark.parametrize("arm", ["/etc/passwd", "/etc/shadow", "../outside/secret.urdf", "../outside/cell.toml",
                                 "/proc/self/environ", "../outside", "~/.bashrc"])
@pytest.mark.parametrize("shape", ["product", "list"])
def test_a_sweep_arm_leading_outside_is_refused_at_its_line_before_it_is_read(repo, capsys, monkeypatch, arm, shape):
    from val3check import confine

    read = []
    real = confine.read_bytes
    monkeypatch.setattr(confine, "read_bytes", lambda path, *a, **k: read.append(os.path.abspath(path)) or real(path, *a, **k))
    text = (f'applications = ["apps/A"]\narms = ["tx2-60", "{arm}"]\n' if shape == "product"
            else f'[[case]]\napplication = "apps/A"\narm = "{arm}"\n')
    (repo / "sweep.toml").write_text(text)
    code, out, err = sim(capsys, "--sweep", "sweep.toml", *FAST, "-j", "1")
    where = "sweep.toml:2:19" if shape == "product" else "sweep.toml:3:7"
    assert code == 2 and f"{where}: {arm}: leads outside the repository of the sweep file" in err, err
    assert out == "" and read == [str(repo / "sweep.toml")]  # the sweep file alone was read


def test_a_robot_file_naming_an_arm_outside_its_repository_is_refused(repo, capsys):
    (repo / "robots").mkdir()
    shutil.copy(ROOT / "robots" / "tx2-60l.urdf", repo / "robots" / "long.urdf")
    (repo / "robots" / "mine.toml").write_text('arm = "long.urdf"\nname = "Mine"\n')
    (repo / "robots" / "evil.toml").write_text(f'arm = "{repo.parent / "outside" / "secret.urdf"}"\n')
    (repo / "robots" / "evil2.toml").write_text('arm = "/etc/passwd"\n')
    (repo / "sweep.toml").write_text('applications = ["apps/A"]\nscenarios = ["pickplace.toml"]\n'
                                     'arms = ["robots/mine.toml", "robots/evil.toml", "robots/evil2.toml"]\n')
    code, out, _ = sim(capsys, "--sweep", "sweep.toml", *FAST, "-j", "1", "--format", "json")
    cases = {c["arm"]: c for c in json.loads(out)["cases"]}
    assert cases["robots/mine.toml"]["verdict"] == "pass" and cases["robots/mine.toml"]["model"] == "Mine"
    for name in ("evil", "evil2"):
        assert cases[f"robots/{name}.toml"]["verdict"] == "not-run"
        assert "leads outside the robot file's repository" in cases[f"robots/{name}.toml"]["reason"]
    code, _, err = sim(capsys, "apps/A", "--robot", "robots/evil2.toml", *FAST)
    assert code == 2 and "robots/evil2.toml: arm = '/etc/passwd': leads outside the robot file's repository" in err


# -- I: NUL bytes in paths, --out-dir ------------------------------------------------------------

@pytest.mark.parametrize("text, where", [
    ('applications = ["apps/A\\u0000x"]\n', "sweep.toml:1:17: applications[0]"),
    ('applications = ["apps/A"]\nscenarios = [\n  "pick\\u0000.toml"]\n', "sweep.toml:3:3: scenarios[0]"),
    ('applications = ["apps/A"]\narms = ["x\\u0000"]\n', "sweep.toml:2:9: arms[0]"),
    ('[[case]]\napplication = "apps/A"\ncell = "c\\u0000.toml"\n', "sweep.toml:3:8: [[case]] 1: cell"),
])
def test_a_nul_in_a_sweep_path_is_reported_at_its_line(repo, capsys, text, where):
    (repo / "sweep.toml").write_text(text)
    code, _, err = sim(capsys, "--sweep", "sweep.toml", *FAST)
    assert code == 2 and f"{where}: a path cannot hold a NUL character" in err, err


@pytest.mark.parametrize("command", ["lint", "sim"])
def test_a_nul_in_a_configuration_path_is_reported_at_its_line(repo, capsys, command):
    (repo / "val3check.toml").write_text('# paths\ndisk-roots = [\n  "ok",\n  "a\\u0000b",\n]\n')
    code = main([command, "apps/A", *(FAST if command == "sim" else [])])
    out, err = capsys.readouterr()
    assert code == 2 and "val3check.toml:2: 'disk-roots': a path cannot hold a NUL character" in err, err
    (repo / "val3check.toml").write_text('baseline = "b\\u0000.json"\n')
    assert main([command, "apps/A", *(FAST if command == "sim" else [])]) == 2
    assert "val3check.toml:1: 'baseline': a path cannot hold a NUL character" in capsys.readouterr().err


def test_the_gate_refuses_a_nul_in_a_path_and_allows_nothing_through_it():
    from val3check.confine import Refused, Roots, check

    roots = Roots(["/tmp", "a\x00b"])
    assert roots.folders == [os.path.realpath("/tmp")]
    assert not roots.allows("/tmp/x\x00y") and roots.containing("/tmp/x\x00") == []
    with pytest.raises(Refused, match="NUL character"):
        check("/tmp/x\x00y", Roots.user_given())


@pytest.mark.parametrize("make", ["link", "file", "link-in-cases", "summary-link"])
def test_an_out_dir_that_leads_elsewhere_is_refused_before_any_case_runs(repo, capsys, monkeypatch, make):
    from val3check.batch import command

    out, elsewhere = repo / "out", repo.parent / "outside" / "dump"
    out.mkdir()
    elsewhere.mkdir()
    if make == "link":
        os.symlink(elsewhere, out / "cases")
    elif make == "file":
        (out / "cases").write_text("x")
    elif make == "summary-link":
        os.symlink(repo.parent / "outside" / "cell.toml", out / "summary.json")
    else:
        from val3check.batch.cases import Axes, RunOptions, product_cases
        from val3check.config import Settings

        (case,) = product_cases(Axes(["apps/A"], ["tx2-60"], [], [], []), Settings(), RunOptions())
        (out / "cases").mkdir()
        os.symlink(elsewhere / "x.json", out / "cases" / (case.name() + ".json"))
    ran = []
    monkeypatch.setattr(command, "_cores", lambda: ran.append(1) or 1)  # asked only once the cases are to run
    code, _, err = sim(capsys, "apps/A", "--robot", "tx2-60", *FAST, "--out-dir", "out")
    assert code == 2 and err.startswith("val3check sim: error: --out-dir: out/") and ran == [], err
    assert list(elsewhere.iterdir()) == [] and (repo.parent / "outside" / "cell.toml").read_text().startswith("unit")


# -- E: globs stay inside their roots and never follow links into loops -------------------------

def test_a_glob_through_links_that_loop_ends_with_the_real_applications(repo):
    import subprocess
    import sys

    for name in ("l1", "l2", "l3"):
        os.symlink(".", repo / "apps" / name)
    r = subprocess.run([sys.executable, "-m", "val3check", "sim", "apps/**/*.pjx", *FAST, "-j", "1", "--format", "json"],
                       cwd=repo, capture_output=True, text=True, timeout=120,
                       env=dict(os.environ, PYTHONPATH=str(ROOT)))
    assert r.returncode == 1, r.stderr  # R002: no arm model
    assert [c["application"] for c in json.loads(r.stdout)["cases"]] == ["apps/A/PickPlace.pjx"]


def test_a_sweep_glob_from_the_root_is_refused_before_anything_is_listed(repo, capsys, monkeypatch):
    listed = []
    real = os.scandir
    monkeypatch.setattr(os, "scandir", lambda p=".": listed.append(os.path.abspath(p)) or real(p))
    for pattern in ("/**/*.pjx", "/proc/*/environ", "../../*/*.pjx", "~/**"):
        (repo / "sweep.toml").write_text(f'applications = [\n  "apps/A",\n  "{pattern}",\n]\n')
        code, _, err = sim(capsys, "--sweep", "sweep.toml", *FAST)
        assert code == 2 and f"sweep.toml:3:3: {pattern}: leads outside the repository of the sweep file" in err, err
    assert not [p for p in listed if not p.startswith(str(repo))], listed


@pytest.mark.parametrize("how", ["command line", "sweep"])
def test_a_glob_match_that_is_a_link_leading_out_is_refused(repo, capsys, how):
    shutil.copytree(PICKPLACE, repo.parent / "outside" / "Out")
    os.symlink(repo.parent / "outside" / "Out", repo / "apps" / "Out")
    if how == "sweep":
        (repo / "sweep.toml").write_text('applications = ["apps/*"]\n')
        code, out, err = sim(capsys, "--sweep", "sweep.toml", *FAST)
        assert code == 2 and "sweep.toml:1:17: apps/*: apps/Out leads outside the repository of the sweep file" in err
    else:
        code, out, err = sim(capsys, "apps/*", *FAST)
        assert code == 2 and f"apps/*: apps/Out leads outside {repo}: not followed" in err, err
    assert out == ""


def test_a_glob_walks_a_bounded_number_of_folders(repo, capsys, monkeypatch):
    from val3check.batch import globs

    monkeypatch.setattr(globs, "MAX_FOLDERS", 5)
    for i in range(8):
        (repo / "deep" / f"d{i}").mkdir(parents=True)
    code, _, err = sim(capsys, "deep/**/*.pjx", *FAST)
    assert code == 2 and "deep/**/*.pjx: lists more than 5 folders" in err, err


# -- F: a sweep's size is limited before anything is expanded -----------------------------------

def _overrides(n: int) -> str:
    return "".join(f"[[overrides]]\nmonitor_speed = {1 + i % 99}\ncycles = {i + 1}\n" for i in range(n))


@pytest.mark.parametrize("text, where, words", [
    ('applications = ["apps/A"]\narms = ["tx2-60", "tx2-90", "tx2-40", "tx2-60l", "tx2-90l"]\n' + _overrides(2001),
     "sweep.toml:3:3", "5 arms × 2,001 overrides make 10,005 cases for each application"),
    ('applications = ["apps/A"]\narms = [' + ", ".join(f'"a{i}"' for i in range(10_001)) + "]\n",
     "sweep.toml:2:1", "arms: 10,001 values"),
    ("".join(f'[[case]]\napplication = "apps/*"\nmonitor_speed = {1 + i % 99}\n' for i in range(10_001)),
     "sweep.toml:30001:1", "10,001 [[case]] tables"),
])
def test_a_sweep_larger_than_the_limit_is_refused_before_it_is_expanded(repo, capsys, monkeypatch, text, where, words):
    from val3check.batch import cases

    monkeypatch.setattr(cases, "find_apps", lambda *a: pytest.fail("applications searched before the limit"))
    (repo / "sweep.toml").write_text(text)
    code, out, err = sim(capsys, "--sweep", "sweep.toml", *FAST)
    assert code == 2 and f"bad sweep file: {where}: {words}" in err and "more than the 10,000" in err, err


def test_a_batch_larger_than_the_limit_once_its_applications_are_found_is_refused(repo, capsys, monkeypatch):
    from val3check.batch import cases, sweep

    monkeypatch.setattr(sweep, "MAX_CASES", 20)
    monkeypatch.setattr(cases, "MAX_CASES", 20)
    for i in range(6):
        shutil.copytree(repo / "apps" / "A", repo / "many" / f"A{i}")
    monkeypatch.setattr(cases, "_case", lambda *a: pytest.fail("a case made before the limit"))
    (repo / "sweep.toml").write_text('applications = ["many/*"]\narms = ["tx2-60", "tx2-90"]\n' + _overrides(2))
    code, _, err = sim(capsys, "--sweep", "sweep.toml", *FAST)
    assert code == 2 and "sweep.toml:1:17: 6 applications × 2 arms × 2 overrides make 24 cases, more than the 20" in err
    code, _, err = sim(capsys, "many/*", "--robot", "tx2-60", "--robot", "tx2-90", "--robot", "tx2-40", "--robot",
                       "tx2-60l", *FAST)
    assert code == 2 and "6 applications × 4 arms make 24 cases, more than the 20" in err, err
    (repo / "sweep.toml").write_text("".join(f'[[case]]\napplication = "many/*"\ncycles = {i + 1}\n' for i in range(4)))
    code, _, err = sim(capsys, "--sweep", "sweep.toml", *FAST)
    assert code == 2 and "sweep.toml:11:15: many/*: the [[case]] tables make more than the 20 cases" in err, err


def test_the_largest_sweep_file_is_refused_unread():
    from val3check.batch.sweep import MAX_CASES, MAX_SWEEP_SIZE

    assert MAX_SWEEP_SIZE == 512 * 1024 and MAX_CASES == 10_000  # docs/batch.md says so


# -- K: a case stuck outside VAL 3 code does not hold the batch --------------------------------

class _Call:
    """Unpickles as f(*args): runs in the case's own process, before the case (the test's hook)."""

    def __init__(self, f, *args):
        self.f, self.args = f, args

    def __reduce__(self):
        return (self.f, self.args)


def _cases(repo):
    from val3check.batch.cases import Axes, RunOptions, product_cases
    from val3check.config import Settings

    return product_cases(Axes(["apps/A"], ["tx2-60", "tx2-90"], ["pickplace.toml"], [], []), Settings(),
                         RunOptions(duration=2.0))


def _stuck(case, **budgets):
    """`case` with budgets, whose process spends forever in C (catastrophic backtracking in `re`,
    which holds the interpreter: no signal, no thread of that process can stop it)."""
    import re
    from dataclasses import replace

    hook = budgets.pop("hook", _Call(re.fullmatch, "(a+)+$", "a" * 64 + "!"))
    return replace(case, settings=hook, options=replace(case.options, **budgets))


@pytest.mark.parametrize("jobs", [1, 2])
def test_a_case_stuck_in_native_code_is_stopped_by_the_watchdog_and_the_batch_goes_on(repo, jobs):
    import time

    from val3check.batch.executors import run_pool

    good, other = _cases(repo)
    stuck = _stuck(other, max_wall=1.0)
    got = []
    start = time.monotonic()
    run_pool([stuck, good], jobs, got.append, lambda: False)
    assert time.monotonic() - start < 100  # the stuck case alone would never end
    verdicts = {o.summary.arm: o.summary for o in got}
    assert verdicts["tx2-60"].verdict == "pass"
    assert verdicts["tx2-90"].verdict == "over-budget"
    assert verdicts["tx2-90"].reason == ("stopped by the watchdog: still starting after 3.1 s (--max-wall 1 s and its"
                                         " grace), outside VAL 3 code")


def test_a_case_growing_in_native_code_is_stopped_by_the_memory_watchdog(repo):
    import operator
    import re

    from dataclasses import replace

    from val3check.batch.executors import run_pool

    good, other = _cases(repo)
    big = _Call(operator.add, _Call(operator.mul, b"a", 300 * 1024 * 1024), b"!")  # 300 MB, then stuck on it
    hungry = _stuck(other, max_memory_mb=16.0, hook=_Call(re.fullmatch, b"(a+)+$", big))
    small = replace(good, options=replace(good.options, max_memory_mb=16.0))  # a real case fits in a small budget
    got = []
    run_pool([small, hungry], 1, got.append, lambda: False)
    assert [o.summary.verdict for o in got] == ["pass", "over-budget"]
    assert got[1].summary.reason == ("stopped by the watchdog: its process grew by more than 145.6 MB (--max-memory 16"
                                     " MB and its margin), outside VAL 3 code")


def test_an_over_budget_case_fails_the_batch_in_every_summary():
    import xml.etree.ElementTree as ET

    from val3check.batch.summary import render_html, render_json, render_junit, render_text
    from val3check.batch.worker import CaseSummary

    s = CaseSummary(key=("a",), name="n", app="a.pjx", app_name="a", arm="tx2-60", model="TX2-60", scenario="",
                    cell="", overrides=(), verdict="over-budget", reason="stopped by the watchdog: ...")
    assert json.loads(render_json([s], "0"))["counts"] == {"over-budget": 1}
    suite = ET.fromstring(render_junit([s]))
    assert suite.get("errors") == "1" and suite.find(".//error").get("type") == "over-budget"
    assert "over-budget: a.pjx" in render_text([s]) and 'class="over-budget crash nw"' in render_html([s], set(), "0")


@pytest.mark.dask
def test_under_dask_a_stuck_case_is_stopped_and_no_worker_is_lost(repo):
    distributed = pytest.importorskip("distributed")

    from val3check.batch.executors import run_dask

    good, other = _cases(repo)
    got = []
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None) as lc:
        workers = set(lc.scheduler_info["workers"])
        run_dask([_stuck(other, max_wall=1.0), good], lc.scheduler_address, got.append, lambda: False, chunk=2)
        assert set(lc.scheduler_info["workers"]) == workers
    assert sorted((o.summary.arm, o.summary.verdict) for o in got) == [("tx2-60", "pass"), ("tx2-90", "over-budget")]
