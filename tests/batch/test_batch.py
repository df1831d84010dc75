"""Batch simulation (issue 17): several applications and globs, the sweep file (product, list,
mistakes at their line and column), -j determinism, the Dask executor on a LocalCluster, the
summary formats, --out-dir names, --fail-fast, crashes isolated, exit codes."""

from __future__ import annotations

import json
import os
import shutil
import xml.etree.ElementTree as ET
from dataclasses import replace
from pathlib import Path

import pytest

from val3check.batch.cases import Axes, RunOptions, product_cases
from val3check.batch.outdir import OutDirError, inside
from val3check.batch.progress import Progress
from val3check.batch.summary import render_html, render_junit
from val3check.batch.sweep import Overrides, SweepError, load_sweep
from val3check.batch.worker import CaseSummary
from val3check.cli import main
from val3check.config import Settings
from val3check.testing import write_app

ROOT = Path(__file__).resolve().parent.parent.parent
PICKPLACE = ROOT / "fixtures" / "valid" / "PickPlace"
SCENARIO = ROOT / "fixtures" / "scenarios" / "pickplace.toml"
FAST = ["--duration", "4.5"]


@pytest.fixture
def cell(tmp_path, monkeypatch):
    """Two copies of PickPlace under apps/ (without the cell file beside it: the tests of cells
    bring it back), the scenario, in the current folder."""
    for name in ("A", "B"):
        shutil.copytree(PICKPLACE, tmp_path / "apps" / name)
        (tmp_path / "apps" / name / "val3check-cell.toml").unlink()
    shutil.copy(SCENARIO, tmp_path / "pickplace.toml")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def sim(capsys, *args):
    code = main(["sim", *map(str, args)])
    out, err = capsys.readouterr()
    return code, out, err


def cases_of(out: str) -> list[dict]:
    return json.loads(out)["cases"]


# -- applications, globs --------------------------------------------------------------------

def test_several_applications_by_glob_run_one_case_each_in_order(cell, capsys):
    code, out, err = sim(capsys, "apps/*", "--robot", "tx2-60", "--scenario", "pickplace.toml", *FAST,
                         "--format", "json", "-j", "1")
    assert code == 0, err
    cases = cases_of(out)
    assert [c["application"] for c in cases] == ["apps/A/PickPlace.pjx", "apps/B/PickPlace.pjx"]
    assert all(c["verdict"] == "pass" and c["model"] == "TX2-60" and c["cycles"] == 1 for c in cases)
    assert cases[0]["cycle_time"] == pytest.approx(2.679287)  # 2.748243 before the exact ramps of issue 23
    low, high = cases[0]["cycle_time_range"]  # TX2-60: accelerations assumed, the range stated
    assert low < cases[0]["cycle_time"] < high


def test_a_folder_of_applications_and_a_controller_tree(cell, capsys):
    shutil.copytree(ROOT / "fixtures" / "valid" / "controller", cell / "ctrl")
    code, out, err = sim(capsys, "apps", "ctrl", *FAST, "--format", "json", "-j", "1")
    cases = cases_of(out)
    # WeldLib is Welder's library: not a case; Welder takes the controller tree's arm.cfx
    assert [c["application"] for c in cases] == ["apps/A/PickPlace.pjx", "apps/B/PickPlace.pjx",
                                                 "ctrl/usr/usrapp/Welder/Welder.pjx"], err
    assert cases[2]["arm"] is None


def test_a_glob_that_matches_nothing_is_a_usage_error(cell, capsys):
    code, _, err = sim(capsys, "apps/*", "nothing/*", *FAST)
    assert code == 2 and "nothing/*: no file or folder matches" in err


def test_a_failing_application_does_not_stop_the_batch(cell, capsys):
    write_app(cell / "apps", "begin\n  x = 1\nend\n", name="Broken")  # x undeclared: a lint error
    code, out, err = sim(capsys, "apps/*", "--robot", "tx2-60", "--scenario", "pickplace.toml", *FAST,
                         "--format", "json", "-j", "1")
    cases = {c["name"]: c for c in cases_of(out)}
    assert code == 1
    assert cases["Broken"]["verdict"] == "not-run" and "lint error" in cases["Broken"]["reason"]
    assert [cases[n]["verdict"] for n in ("PickPlace",)] == ["pass"]


class _Boom:
    """A case setting that raises where the case runs (its settings are copied first)."""

    def __deepcopy__(self, memo):
        raise RuntimeError("boom")


def test_a_crashing_case_is_reported_and_the_others_run(cell):
    from val3check.batch.executors import run_pool

    cases = product_cases(Axes(["apps/*"], ["tx2-60"], ["pickplace.toml"], [], []), Settings(), RunOptions(duration=2.0))
    got = []
    run_pool([cases[0], replace(cases[1], settings=_Boom())], 1, got.append, lambda: False)
    assert [o.summary.verdict for o in got] == ["pass", "crash"]
    assert got[1].summary.reason.startswith("RuntimeError: boom (at test_batch.py:")


class _DiesWhenUnpickled:
    """A case setting whose unpickling ends the worker process (as a crash in native code would)."""

    def __reduce__(self):
        return (os._exit, (7,))


def test_a_worker_process_that_dies_takes_only_its_case(cell):
    from val3check.batch.executors import run_pool

    axes = Axes(["apps/*"], ["tx2-60"], ["pickplace.toml"], [], [])
    cases = product_cases(axes, Settings(), RunOptions(duration=2.0))
    killer = replace(cases[1], settings=_DiesWhenUnpickled())
    got = []
    run_pool([cases[0], killer], 2, got.append, lambda: False)
    verdicts = {o.summary.app: o.summary.verdict for o in got}
    assert verdicts == {"apps/A/PickPlace.pjx": "pass", "apps/B/PickPlace.pjx": "crash"}
    assert "process running the case died" in next(o.summary.reason for o in got if o.summary.verdict == "crash")


# -- the sweep file -------------------------------------------------------------------------

def test_sweep_product_of_every_axis(cell):
    (cell / "slow.toml").write_text('version = 1\n[controller]\nmonitor_speed = 50\n')
    (cell / "sweep.toml").write_text(
        'applications = ["apps/*"]\narms = ["tx2-60", "tx2-90", "tx2-40"]\n'
        'scenarios = ["pickplace.toml", "none"]\n[[overrides]]\nmonitor_speed = 50\n[[overrides]]\ncycles = 1\n')
    from val3check.batch.command import _axes

    class Args:
        app, robot, scenario, cell, sweep = [], None, None, None, "sweep.toml"

    axes, sweep = _axes(Args)
    cases = product_cases(axes, Settings(), RunOptions())
    assert len(cases) == 2 * 3 * 2 * 2
    assert cases == sorted(cases, key=lambda c: c.key())
    assert {c.scenario for c in cases} == {"pickplace.toml", ""}
    assert {c.overrides for c in cases} == {Overrides(monitor_speed=50.0), Overrides(cycles=1)}
    assert len({c.name() for c in cases}) == len(cases)


def test_sweep_list_with_overrides_that_change_the_run(cell, capsys):
    (cell / "sweep.toml").write_text(
        '[[case]]\napplication = "apps/A"\narm = "tx2-60"\nscenario = "pickplace.toml"\n\n'
        '[[case]]\napplication = "apps/A"\narm = "tx2-60"\nscenario = "pickplace.toml"\nmonitor_speed = 50\n'
        'duration = 12\n')
    code, out, err = sim(capsys, "--sweep", "sweep.toml", *FAST, "--format", "json", "-j", "1")
    assert code == 0, err
    full, half = cases_of(out)
    assert full["overrides"] == {} and half["overrides"] == {"monitor_speed": 50.0, "duration": 12.0}
    assert half["cycle_time"] > full["cycle_time"] * 1.2  # the arm moves at half speed


@pytest.mark.parametrize("text, line, col, words", [
    ('arms = ["tx2-60"]\nrobots = ["tx2-90"]\n', 2, 1, "unknown key 'robots'"),
    ('arms = ["tx2-60"]\n[[overrides]]\nmonitor_speed = 150\n', 3, 17, "monitor_speed: a percentage"),
    ('arms = ["tx2-60"]\n[[overrides]]\ncycles = 0\n', 3, 10, "cycles: a positive whole number"),
    ('arms = ["tx2-60", 3]\n', 1, 19, "arms[1]: expected a non-empty string"),
    ('arms = ["tx2-60"]\nx = = 1\n', 2, 5, "invalid TOML"),
    ('applications = ["apps/A"]\n[[case]]\napplication = "apps/A"\n', 1, 1, "do not mix"),
    ('[[case]]\narm = "tx2-60"\n', 1, 1, "no application"),
    ('version = 2\n', 1, 11, "unsupported sweep version"),
])
def test_invalid_sweep_files_are_reported_at_their_line_and_column(cell, text, line, col, words):
    (cell / "sweep.toml").write_text(text)
    with pytest.raises(SweepError) as exc:
        load_sweep("sweep.toml")
    assert (exc.value.line, exc.value.col) == (line, col), str(exc.value)
    assert words in exc.value.message


def test_a_sweep_application_that_matches_nothing_is_reported_at_its_line(cell, capsys):
    (cell / "sweep.toml").write_text('arms = ["tx2-60"]\napplications = [\n  "apps/A",\n  "nowhere/*",\n]\n')
    code, _, err = sim(capsys, "--sweep", "sweep.toml", *FAST)
    assert code == 2 and "sweep.toml:4:3: nowhere/*: no file or folder matches" in err, err


def test_an_axis_given_twice_and_cells_are_usage_errors(cell, capsys):
    (cell / "sweep.toml").write_text('arms = ["tx2-60"]\n')
    code, _, err = sim(capsys, "apps/A", "--robot", "tx2-90", "--sweep", "sweep.toml", *FAST)
    assert code == 2 and "arms are given both" in err
    (cell / "sweep.toml").write_text('arms = ["tx2-60"]\n')
    code, _, err = sim(capsys, "apps/A", "--sweep", "sweep.toml", "--scenario", "pickplace.toml",
                       "--robot", "tx2-90", *FAST)
    assert code == 2 and "arms are given both" in err


# -- executors: -j and Dask give the same results ------------------------------------------

ARGS = ["apps/*", "--robot", "tx2-60", "--robot", "tx2-90", "--scenario", "pickplace.toml", *FAST]


def _sweep_3_arms_2_scenarios(folder: Path) -> list[str]:
    """Real applications × 3 arms (one a URDF file, carried with the case) × 2 scenarios."""
    shutil.copy(ROOT / "robots" / "tx2-60l.urdf", folder / "long.urdf")
    (folder / "slow.toml").write_text(SCENARIO.read_text() + "\n[controller]\nmonitor_speed = 40\n")
    (folder / "sweep.toml").write_text('applications = ["apps/*"]\narms = ["tx2-60", "tx2-90", "long.urdf"]\n'
                                       'scenarios = ["pickplace.toml", "slow.toml"]\n')
    return ["--sweep", "sweep.toml", *FAST]


def _outputs(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def test_jobs_1_and_2_give_byte_identical_summaries_and_reports(cell, capsys):
    args = _sweep_3_arms_2_scenarios(cell)
    code1, out1, _ = sim(capsys, *args, "-j", "1", "--out-dir", "o1")
    code2, out2, _ = sim(capsys, *args, "-j", "2", "--out-dir", "o2")
    assert code1 == code2 == 0
    assert out1 == out2 and sum(line.startswith("pass ") for line in out1.splitlines()) == 12
    one, two = _outputs(cell / "o1"), _outputs(cell / "o2")
    assert one == two
    assert len([k for k in one if k.startswith("cases/")]) == 12
    assert "long.urdf" in out1 and "TX2-60L" in one["summary.json"].decode()


@pytest.mark.dask
def test_dask_local_cluster_gives_the_same_summary(cell, capsys):
    distributed = pytest.importorskip("distributed")
    args = _sweep_3_arms_2_scenarios(cell)
    _, serial, _ = sim(capsys, *args, "-j", "1", "--format", "json")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as lc:
        code, out, err = sim(capsys, *args, "--executor", "dask", "--scheduler", lc.scheduler_address,
                             "--format", "json")
    assert code == 0, err
    assert out == serial and len(cases_of(out)) == 12


def test_scheduler_and_jobs_go_with_their_executor(cell, capsys):
    code, _, err = sim(capsys, *ARGS, "--scheduler", "tcp://127.0.0.1:8786")
    assert code == 2 and "--scheduler goes with --executor dask" in err
    code, _, err = sim(capsys, *ARGS, "--executor", "dask", "--scheduler", "tcp://127.0.0.1:8786", "-j", "2")
    assert code == 2 and "with a scheduler, the workers' processes set the parallelism" in err


@pytest.mark.dask
def test_dask_without_a_scheduler_starts_a_local_cluster_as_dask_does(cell, capsys, monkeypatch):
    """Issue 28 item 7: `--executor dask` alone runs on a local cluster (Dask's `Client()`), its
    summary the same as `-j 1`'s; the progress line says what it starts before any case ends."""
    pytest.importorskip("distributed")
    import dask

    from val3check.batch import command

    monkeypatch.delenv("DASK_SCHEDULER_ADDRESS", raising=False)
    args = ["apps/*", "--robot", "tx2-60", "--scenario", "pickplace.toml", *FAST, "--format", "json"]
    _, serial, _ = sim(capsys, *args, "-j", "1")
    shown = []
    monkeypatch.setattr(command, "Progress", lambda total: _Recorded(total, shown))
    with dask.config.set({"scheduler-address": None}):
        code, out, err = sim(capsys, *args, "--executor", "dask", "-j", "2")
    assert code == 0, err
    assert out == serial and len(cases_of(out)) == 2
    lines = "".join(shown).split("\r\x1b[K")
    assert lines[1] == "0/2 cases, 0 failed, 0:00 elapsed: starting a local Dask cluster of 2 worker process(es)"
    assert "running on 2 Dask worker processes" in lines[2]


@pytest.mark.dask
def test_dask_without_a_scheduler_takes_the_one_dask_s_configuration_names(cell, capsys, monkeypatch):
    """DASK_SCHEDULER_ADDRESS (Dask's configuration key scheduler-address): that cluster, no local one."""
    distributed = pytest.importorskip("distributed")
    import dask

    args = ["apps/A", "--robot", "tx2-60", "--scenario", "pickplace.toml", *FAST, "--format", "json"]
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None) as lc:
        def no_local_cluster(*a, **k):
            raise AssertionError("a local cluster was started although Dask's configuration names a scheduler")

        monkeypatch.setattr(distributed, "LocalCluster", no_local_cluster)
        with dask.config.set({"scheduler-address": lc.scheduler_address}):
            code, out, err = sim(capsys, *args, "--executor", "dask")
            assert code == 0, err
            assert [c["verdict"] for c in cases_of(out)] == ["pass"]
            code, _, err = sim(capsys, *args, "--executor", "dask", "-j", "2")
            assert code == 2 and "with a scheduler, the workers' processes set the parallelism" in err


class _Recorded(Progress):
    """The batch's progress line as a terminal would show it, recorded."""

    def __init__(self, total: int, shown: list) -> None:
        import io

        class Terminal(io.StringIO):
            def write(self, text: str) -> int:
                shown.append(text)
                return len(text)

        super().__init__(total, Terminal(), enabled=True)


def test_the_batch_shows_its_phase_before_the_first_case_ends(cell, capsys, monkeypatch):
    """Issue 28 item 3: the first seconds of a batch (processes starting, the first cases) show a line."""
    from val3check.batch import command

    shown = []
    monkeypatch.setattr(command, "Progress", lambda total: _Recorded(total, shown))
    assert sim(capsys, "apps/*", "--robot", "tx2-60", "--scenario", "pickplace.toml", *FAST, "-j", "1")[0] == 0
    lines = [x for x in "".join(shown).split("\r\x1b[K") if x]
    assert lines[0] == "0/2 cases, 0 failed, 0:00 elapsed: running on 1 process"
    assert lines[1].startswith("1/2 cases, 0 failed") and lines[1].endswith(": running on 1 process")


def test_dask_chunks_keep_a_few_tasks_per_worker():
    from val3check.batch.executors import chunk_size

    assert chunk_size(200, 2) == 8 and chunk_size(40, 2) == 3 and chunk_size(10, 2) == 1 and chunk_size(1, 8) == 1
    assert chunk_size(10_000, 320) == 4


# -- summary, out-dir, fail-fast, exit codes -----------------------------------------------

def test_out_dir_holds_every_summary_format(cell, capsys):
    write_app(cell / "apps", "begin\n  x = 1\nend\n", name="Broken")
    code, text, _ = sim(capsys, "apps/*", "--robot", "tx2-60", "--scenario", "pickplace.toml", *FAST, "-j", "1",
                        "--out-dir", "out")
    assert code == 1
    out = cell / "out"
    assert (out / "summary.txt").read_text() == text
    summary = json.loads((out / "summary.json").read_text())
    assert summary["counts"] == {"pass": 2, "not-run": 1}
    suite = ET.parse(out / "junit.xml").getroot()
    cases = suite.findall(".//testcase")
    assert len(cases) == 3 and suite.get("errors") == "1" and suite.get("tests") == "3"
    assert [c.get("classname") for c in cases] == ["apps/A/PickPlace.pjx", "apps/B/PickPlace.pjx",
                                                   "apps/Broken/Broken.pjx"]
    assert cases[2].find("error") is not None and cases[0].find("error") is None
    index = (out / "index.html").read_text()
    for c in summary["cases"]:
        if c["verdict"] == "pass":
            assert f'href="cases/{c["report"]}.json">JSON</a>' in index
            assert (out / "cases" / f'{c["report"]}.json').is_file()
    assert "apps/Broken/Broken.pjx" in index and "<script" not in index


def _summary(**kw) -> CaseSummary:
    base = dict(key=("a",), name="n", app="a.pjx", app_name="a", arm="tx2-60", model="TX2-60", scenario="",
                cell="", overrides=(), verdict="pass")
    return CaseSummary(**{**base, **kw})


def test_html_index_and_junit_escape_what_comes_from_the_input():
    s = _summary(app='<img src=x onerror="alert(1)">.pjx', verdict="fail", reason="a < b & \"c\"",
                 name="n<x>")
    page = render_html([s], {"n<x>.json"}, "0")
    assert "<img" not in page and "&lt;img src=x onerror=&quot;alert(1)&quot;&gt;.pjx" in page
    assert 'href="cases/n%3Cx%3E.json"' in page
    root = ET.fromstring(render_junit([s]))
    assert root.find(".//failure").get("message") == 'a < b & "c"'


def test_cases_are_in_natural_order():
    """Issue 28 item 13: numbers inside names order as numbers (tx2-60 before tx2-140, ms50.toml
    before ms100.toml), override values as numbers (monitor_speed=50 before =100), in every format."""
    from val3check.batch.summary import ordered, render_text

    cases = []
    for arm in ("tx2-140", "tx2-60"):
        for sc in ("ms100.toml", "ms50.toml"):
            for ms in (100.0, 50.0):
                ov = (("monitor_speed", ms),)
                cases.append(_summary(key=("a.pjx", arm, sc, "", ov), arm=arm, scenario=sc, overrides=ov))
    got = [(s.arm, s.scenario, s.overrides[0][1]) for s in ordered(cases)]
    assert got[:4] == [("tx2-60", "ms50.toml", 50.0), ("tx2-60", "ms50.toml", 100.0),
                       ("tx2-60", "ms100.toml", 50.0), ("tx2-60", "ms100.toml", 100.0)]
    assert got[4][0] == "tx2-140"
    text = render_text(cases)
    assert text.index("tx2-60") < text.index("tx2-140") and text.index("ms50.toml") < text.index("ms100.toml")


def test_index_paths_are_relative_to_the_index_and_link_to_the_files(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    s = _summary(app=str(tmp_path / "cell" / "Pick" / "Pick.pjx"), scenario="cell/run.toml", verdict="fail",
                 reason="cell/Pick/start.pgx:3:1: R032 error: " + "x" * 400)
    page = render_html([s], set(), "0", index_dir=str(tmp_path / "out"))
    assert '<a href="../cell/Pick/Pick.pjx">../cell/Pick/Pick.pjx</a>' in page
    assert '<a href="../cell/run.toml">../cell/run.toml</a>' in page
    assert str(tmp_path) not in page  # no absolute path
    # the reason on a row of its own, as wide as the table
    assert '<tr class="why"><td colspan="' in page and "x" * 400 in page


@pytest.mark.browser
def test_index_shows_every_reason_whole_at_1400_and_900_px(tmp_path, monkeypatch):
    """The reason of a failing case with long paths is never cut (item 13: the index cut it at 1400 px)."""
    import browser_client

    why = browser_client.skip_reason()
    if why:
        if browser_client.required():
            raise RuntimeError(why)
        pytest.skip(why)
    monkeypatch.chdir(tmp_path)
    deep = tmp_path / ("very-long-folder-name-of-a-cell-" * 3) / "Application" / "Application.pjx"
    cases = [_summary(key=(str(deep), arm), app=str(deep), arm=arm, scenario=str(deep.parent / "scenario.toml"),
                      verdict="fail", reason=f"{deep.parent}/start.pgx:15:3: R032 error: movej starts in collision: "
                      "link_1 (shoulder) hits obstacle 'table' at 0.152 s, 30.0 mm deep, at (185.0, 0.0, -133.0) mm")
             for arm in ("tx2-60", "tx2-90")]
    out = tmp_path / "out"
    out.mkdir()
    (out / "index.html").write_text(render_html(cases, set(), "0", index_dir=str(out)), encoding="utf-8")
    for width in (1400, 900):
        with browser_client.Chromium(width=width) as chromium:
            page = chromium.open(out / "index.html", wait=False)
            assert page.console_errors == [] and page.refused == []
            got = page.evaluate("""() => ({
                scroll: document.documentElement.scrollWidth, client: document.documentElement.clientWidth,
                right: Math.max(...Array.from(document.querySelectorAll('tr.why td'))
                                     .map((td) => td.getBoundingClientRect().right)),
                reasons: Array.from(document.querySelectorAll('tr.why td')).map((td) => td.textContent)})""")
            assert got["scroll"] <= got["client"] and got["right"] <= got["client"], (width, got)
            assert got["reasons"] == [c.reason for c in cases]
            page.page.screenshot(path=str(tmp_path / f"index-{width}.png"), full_page=True)


def test_case_names_are_safe_and_stay_in_the_out_dir(cell, tmp_path):
    (case,) = product_cases(Axes(["apps/A"], ["tx2-60"], [], [], []), Settings(), RunOptions())
    hostile = replace(case, app_name="../../etc/passwd", scenario="../../x/..\\evil name.toml", arm="..")
    name = hostile.name()
    assert "/" not in name and "\\" not in name and not name.startswith(".") and ".." not in name.split("__")[0]
    assert inside(str(tmp_path), "cases/" + name + ".json").startswith(str(tmp_path.resolve()))
    for bad in ("../x.json", "/etc/x", "cases/../../x"):
        with pytest.raises(OutDirError):
            inside(str(tmp_path / "out"), bad)
    (tmp_path / "out").mkdir()
    os.symlink("/tmp", tmp_path / "out" / "link")
    with pytest.raises(OutDirError):
        inside(str(tmp_path / "out"), "link/x.json")


def test_fail_fast_stops_at_the_first_failure(cell, capsys):
    # --fail-on info: the run's R007 (duration reached) fails each case
    code, out, _ = sim(capsys, *ARGS, "--fail-on", "info", "--fail-fast", "-j", "1", "--format", "json")
    assert code == 1
    assert [c["verdict"] for c in cases_of(out)] == ["fail", "skipped", "skipped", "skipped"]
    assert "R007" in cases_of(out)[0]["reason"]
    code, out, _ = sim(capsys, *ARGS, "--fail-on", "info", "-j", "1", "--format", "json")
    assert [c["verdict"] for c in cases_of(out)] == ["fail"] * 4


def test_exit_codes(cell, capsys):
    assert sim(capsys, "apps/*", "--robot", "tx2-60", "--scenario", "pickplace.toml", *FAST, "-j", "1")[0] == 0
    assert sim(capsys, "apps/*", "--robot", "tx2-60", "--scenario", "pickplace.toml", *FAST, "-j", "1",
               "--fail-on", "info")[0] == 1
    # without the scenario the run ends waiting on an input nothing sets: R009, a warning
    assert sim(capsys, "apps/*", "--robot", "tx2-60", *FAST, "-j", "1")[0] == 0
    assert sim(capsys, "apps/*", "--robot", "tx2-60", *FAST, "-j", "1", "--fail-on", "warning")[0] == 1
    (cell / "sweep.toml").write_text("nonsense = 1\n")
    assert sim(capsys, "--sweep", "sweep.toml", *FAST)[0] == 2
    assert sim(capsys, "apps/*", "-j", "0")[0] == 2
    assert sim(capsys, "apps/*", "--robot", "nosuch-arm", *FAST, "-j", "1")[0] == 1  # each case: not run


def test_progress_line():
    import io

    stream = io.StringIO()
    p = Progress(4, stream, enabled=True)
    p.start = 0.0
    p.update(True)
    p.update(False)
    assert p.line(now=10.0) == "2/4 cases, 1 failed, 0:10 elapsed, about 0:10 left"
    assert "\r" in stream.getvalue()
    quiet = io.StringIO()
    Progress(2, quiet).update(True)  # not a terminal: nothing
    assert quiet.getvalue() == ""


def test_one_application_without_batch_options_runs_as_before(cell, capsys):
    code, out, _ = sim(capsys, "apps/A", "--robot", "tx2-60", "--scenario", "pickplace.toml", *FAST)
    assert code == 0 and out.startswith("val3check sim: PickPlace (apps/A/PickPlace.pjx)")


def test_reports_travel_back_only_when_they_are_written(cell):
    from val3check.batch.worker import run_case

    axes = Axes(["apps/A"], ["tx2-60"], ["pickplace.toml"], [], [])
    (with_reports,) = product_cases(axes, Settings(), RunOptions(duration=2.0))
    (without,) = product_cases(axes, Settings(), RunOptions(duration=2.0, reports=False))
    got, bare = run_case(with_reports), run_case(without)
    assert bare.outputs == {} and bare.summary == got.summary
    report = json.loads(got.files()[".json"])
    assert report["application"]["path"] == "apps/A/PickPlace.pjx"  # as the single run shows it, no temporary path
    assert len(got.outputs[".json"]) < len(got.files()[".json"]) / 2  # compressed on the way back


def test_dask_not_installed_is_said_clearly(cell, capsys, monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "distributed", None)  # `import distributed` raises ImportError
    code, _, err = sim(capsys, *ARGS, "--executor", "dask", "--scheduler", "tcp://127.0.0.1:8786")
    assert code == 2 and "pip install 'val3check[dask]'" in err


def test_fail_fast_with_a_pool_reports_every_case(cell, capsys):
    code, out, _ = sim(capsys, *ARGS, "--fail-on", "info", "--fail-fast", "-j", "2", "--format", "json")
    verdicts = [c["verdict"] for c in cases_of(out)]
    assert code == 1 and len(verdicts) == 4 and "fail" in verdicts and set(verdicts) <= {"fail", "skipped"}


def test_an_unreadable_project_is_a_case_not_run_with_the_loaders_reason(cell, capsys):
    (cell / "apps" / "Bad").mkdir()
    (cell / "apps" / "Bad" / "Bad.pjx").write_text("<Project garbage")
    code, out, _ = sim(capsys, "apps/*", "--robot", "tx2-60", "--scenario", "pickplace.toml", *FAST,
                       "--format", "json", "-j", "1")
    cases = {c["application"]: c for c in cases_of(out)}
    assert code == 1 and cases["apps/Bad/Bad.pjx"]["verdict"] == "not-run"
    assert "could not be read: apps/Bad/Bad.pjx:" in cases["apps/Bad/Bad.pjx"]["reason"]
    assert cases["apps/A/PickPlace.pjx"]["verdict"] == "pass"


def test_the_dask_extra_and_ci_installing_it():
    import tomllib

    extras = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["optional-dependencies"]
    assert any(r.startswith("dask[distributed]") for r in extras["dask"])
    assert "val3check[dask]" in extras["test"]  # CI runs the executor's tests


def test_sweep_paths_are_relative_to_the_sweep_file(cell, capsys):
    (cell / "sweeps").mkdir()
    (cell / "sweeps" / "s.toml").write_text('applications = ["../apps/B"]\narms = ["tx2-60"]\n'
                                            'scenarios = ["../pickplace.toml"]\n')
    code, out, err = sim(capsys, "--sweep", "sweeps/s.toml", *FAST, "--format", "json", "-j", "1")
    assert code == 0, err
    (case,) = cases_of(out)
    assert (case["application"], case["scenario"]) == ("apps/B/PickPlace.pjx", "pickplace.toml")


class _DiesInADaskWorker:
    """Ends the process that unpickles it where VAL3CHECK_TEST_DIE names a file (the test's Dask
    workers and their children), after adding a line to that file; elsewhere it comes back as
    itself."""

    def __reduce__(self):
        return (eval, ("(open(__import__('os').environ['VAL3CHECK_TEST_DIE'], 'a').write('x\\n'), "
                       "__import__('os')._exit(7)) if __import__('os').environ.get('VAL3CHECK_TEST_DIE') else "
                       f"__import__('sys').modules[{__name__!r}]._DiesInADaskWorker()",))


@pytest.mark.dask
def test_dask_a_case_that_kills_its_process_takes_only_itself_and_no_worker(cell, tmp_path):
    """The case dies in the child process that runs it (runner.py), never in the Dask worker:
    the worker stays, Dask retries nothing (allowed-failures left at its default, 3), the case is
    tried twice in all and reported as a crash."""
    distributed = pytest.importorskip("distributed")
    import dask

    from val3check.batch.executors import run_dask
    from val3check.batch.runner import DIED

    axes = Axes(["apps/*"], ["tx2-60"], ["pickplace.toml"], [], [])
    good, other = product_cases(axes, Settings(), RunOptions(duration=2.0))
    killer = replace(other, settings=_DiesInADaskWorker())
    tries = tmp_path / "tries"
    got = []
    with dask.config.set({"distributed.nanny.environ": {"VAL3CHECK_TEST_DIE": str(tries)}}):
        with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None) as lc:
            workers = set(lc.scheduler_info["workers"])
            run_dask([good, killer], lc.scheduler_address, got.append, lambda: False, chunk=2)
            assert set(lc.scheduler_info["workers"]) == workers  # no worker was lost
    verdicts = {o.summary.app: o.summary.verdict for o in got}
    assert verdicts == {"apps/A/PickPlace.pjx": "pass", "apps/B/PickPlace.pjx": "crash"}
    assert next(o.summary.reason for o in got if o.summary.verdict == "crash") == DIED
    assert tries.read_text() == "x\n" * 2


@pytest.mark.parametrize("text, line, col, words", [
    ('arms = ["tx2-60"]\nscenarios = [\n  "pickplace.toml",\n  "missing.toml",\n]\n', 4, 3, "scenario missing.toml"),
    ('[[case]]\napplication = "apps/A"\narm = "nowhere.urdf"\n', 3, 7, "arm nowhere.urdf: no such file"),
    ('[[case]]\napplication = "apps/A"\nscenario = "gone.toml"\n', 3, 12, "scenario gone.toml"),
])
def test_a_missing_file_of_the_sweep_is_reported_at_its_line(cell, capsys, text, line, col, words):
    (cell / "sweep.toml").write_text(text)
    code, _, err = sim(capsys, "--sweep", "sweep.toml", *FAST, *(["apps/A"] if "[[case]]" not in text else []))
    assert code == 2 and f"sweep.toml:{line}:{col}: {words}" in err, err


@pytest.mark.dask
def test_dask_workers_must_exist_and_run_one_thread(cell, monkeypatch):
    distributed = pytest.importorskip("distributed")
    from val3check.batch import executors

    monkeypatch.setattr(executors, "WAIT_FOR_WORKERS_S", 1)
    (case,) = product_cases(Axes(["apps/A"], ["tx2-60"], ["pickplace.toml"], [], []), Settings(), RunOptions())
    with distributed.LocalCluster(n_workers=0, processes=False, dashboard_address=None) as lc:
        with pytest.raises(executors.ExecutorError, match="has no worker"):
            executors.run_dask([case], lc.scheduler_address, print, lambda: False)
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False, dashboard_address=None) as lc:
        with pytest.raises(executors.ExecutorError, match="must run one thread each"):
            executors.run_dask([case], lc.scheduler_address, print, lambda: False)


def test_the_bundled_sweep(capsys, monkeypatch):
    monkeypatch.chdir(ROOT)
    code, out, err = sim(capsys, "--sweep", "fixtures/sweeps/pickplace.toml", "--duration", "9", "-j", "1",
                         "--format", "json")
    cases = cases_of(out)
    assert [(c["arm"], c["overrides"]["monitor_speed"]) for c in cases] == [
        (arm, speed) for arm in ("tx2-60", "tx2-60l", "tx2-90") for speed in (50.0, 100.0)]
    for full, half in zip(cases[1::2], cases[0::2], strict=True):  # the arm moves at half speed: longer cycles
        assert half["cycle_time"] > full["cycle_time"] * 1.2
    # the cell beside PickPlace travels with each case: the TX2-90's shoulder hits its table
    assert code == 1 and [c["verdict"] for c in cases] == ["pass"] * 4 + ["fail"] * 2
    assert all("R032" in c["reason"] and "'table'" in c["reason"] for c in cases[4:])


@pytest.mark.parametrize("text, line, col", [
    ('applications = ["apps/A"]\narms = ["tx2-60"]\nscenarios = ["/etc/hostname"]\n', 3, 14),
    ('applications = ["apps/A", "/usr/*"]\n', 1, 27),
    ('[[case]]\napplication = "../../.."\n', 2, 15),
])
def test_sweep_paths_stay_inside_its_folder_or_repository(cell, capsys, text, line, col):
    (cell / "sweeps").mkdir()
    (cell / "sweeps" / "s.toml").write_text(text)
    code, _, err = sim(capsys, "--sweep", "sweeps/s.toml", *FAST)
    assert code == 2 and f"s.toml:{line}:{col}:" in err and "leads outside" in err, err


def test_sweep_mode_must_match_its_shape(cell):
    (cell / "sweep.toml").write_text('mode = "list"\narms = ["tx2-60"]\n')
    with pytest.raises(SweepError, match=r'mode = "list" needs \[\[case\]\] tables') as exc:
        load_sweep("sweep.toml")
    assert (exc.value.line, exc.value.col) == (1, 8)


def test_case_reports_are_the_single_runs(cell, capsys):
    """A case runs as the single run (simulation/case.py) in a mirror of its files: its reports
    are the single run's, byte for byte, with no path of the mirror."""
    code, _, err = sim(capsys, "apps/A", "--robot", "tx2-60", "--scenario", "pickplace.toml", *FAST, "--out-dir", "o",
                       "--case-reports", "json,html,trace")
    assert code == 0, err
    files = {p.suffix: p for p in (cell / "o" / "cases").iterdir()}
    assert sorted(files) == [".html", ".json", ".mcap"]
    single = ["apps/A", "--robot", "tx2-60", "--scenario", "pickplace.toml", *FAST]
    assert main(["sim", *single, "--report", "html", "-o", "one.html", "--trace", "one.mcap"]) == 0
    assert main(["sim", *single, "--report", "json", "-o", "one.json"]) == 0
    assert files[".json"].read_bytes() == (cell / "one.json").read_bytes()
    assert files[".html"].read_bytes() == (cell / "one.html").read_bytes()
    assert files[".mcap"].read_bytes() == (cell / "one.mcap").read_bytes()
    index = (cell / "o" / "index.html").read_text()
    assert f'href="cases/{files[".html"].name}">page</a>' in index and ">trace</a>" in index
    code, _, err = sim(capsys, "apps/A", "--out-dir", "o", "--case-reports", "json,pdf")
    assert code == 2 and "--case-reports: pdf" in err
    code, _, err = sim(capsys, "apps/*", "--trace", "x.mcap")
    assert code == 2 and "--case-reports json,trace" in err


def test_cells_travel_with_the_cases_as_sim_cell_chooses_them(cell, capsys):
    """The cell beside the application (found as `sim` finds it), a cell named by the sweep, and
    none: each case carries its cell file and the verdicts follow the collisions."""
    shutil.copy(PICKPLACE / "val3check-cell.toml", cell / "apps" / "A" / "val3check-cell.toml")
    shutil.copy(PICKPLACE / "val3check-cell.toml", cell / "named-cell.toml")
    (cell / "sweep.toml").write_text('applications = ["apps/A"]\narms = ["tx2-90"]\nscenarios = ["pickplace.toml"]\n'
                                     'cells = ["none", "named-cell.toml"]\n')
    code, out, _ = sim(capsys, "--sweep", "sweep.toml", *FAST, "--format", "json", "-j", "2", "--out-dir", "o")
    by_cell = {c["cell"]: c for c in cases_of(out)}
    assert code == 1 and set(by_cell) == {"none", "named-cell.toml"}
    assert by_cell["none"]["verdict"] == "pass"
    assert by_cell["named-cell.toml"]["verdict"] == "fail" and "R032" in by_cell["named-cell.toml"]["reason"]
    # the default: the cell beside the application, as a single run finds it; same report
    code, _, _ = sim(capsys, "apps/A", "--robot", "tx2-90", "--scenario", "pickplace.toml", *FAST, "--out-dir", "d")
    (report,) = (cell / "d" / "cases").iterdir()
    single = ["apps/A", "--robot", "tx2-90", "--scenario", "pickplace.toml", *FAST, "--format", "json"]
    code_single, text, _ = sim(capsys, *single)
    assert code == code_single == 1 and report.read_text() == text
