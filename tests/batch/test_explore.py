"""`sim --explore` (issue 30): a cell whose program assumes "the clamp is closed 0.2 s after the
acknowledgement", true of its nominal scenario (fixtures/explore): exploration finds the
failure, writes a scenario that reproduces it with a plain `sim`, finds nothing on the corrected
program; same seed, same bytes; -j 1 and -j 2 and Dask, same failures. The search, the
shrinking and the scenario's ranges on their own, against figures worked out by hand."""

from __future__ import annotations

import json
import re
import shutil
from pathlib import Path

import pytest

from val3check.batch.explore.search import Observed, directed, uniform, variants
from val3check.batch.explore.shrink import shrink
from val3check.batch.explore.timings import Timing, timings, variant_text
from val3check.cli import main
from val3check.tomlfile import load_bytes

ROOT = Path(__file__).resolve().parent.parent.parent
EXPLORE = ROOT / "fixtures" / "explore"


@pytest.fixture
def cell(tmp_path, monkeypatch):
    shutil.copytree(EXPLORE, tmp_path / "explore")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def sim(capsys, *args):
    code = main(["sim", *map(str, args)])
    out, err = capsys.readouterr()
    return code, out, err


def files(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


EXPLORE_CLAMP = ["explore/Clamp", "--scenario", "explore/clamp.toml", "--explore", "12"]


# -- end to end -----------------------------------------------------------------------------------

def test_explore_finds_the_timing_assumption_and_writes_a_reproducer(cell, capsys):
    code, out, err = sim(capsys, *EXPLORE_CLAMP, "--out-dir", "out", "-j", "2")
    assert code == 1, err
    summary = json.loads((cell / "out" / "summary.json").read_text())
    [failure] = summary["failures"]
    # the program's wait for the operator (start.pgx line 18) after it found the clamp open
    assert (failure["code"], failure["path"], failure["line"]) == ("R003", "explore/Clamp/start.pgx", 18)
    assert failure["count"] >= 1 and not failure["nominal"]
    # shrunk: only the clamp's delay moved, to the first millisecond at which the check at
    # 0.05 (ack) + 0.2 (delay) s misses it: its input is seen at the first 4 ms cycle at or
    # after its time (docs/scenario.md), the check runs in the cycle of 0.252 s
    [moved] = failure["deviation"]
    assert moved["timing"] == "[[reactions]] #2 after" and moved["line"] == 11
    assert moved["nominal"] == 0.15 and 0.25 <= moved["value"] <= 0.256
    text = (cell / "out" / failure["reproducer"]).read_text()
    assert text.startswith("# val3check sim --explore") and "fails: R003" in text
    assert "where: explore/Clamp/start.pgx:18:7" in text and "at 0.2" in text
    assert re.search(r"^after = 0\.25\d*$", text, re.MULTILINE) and "min =" not in text
    assert "R003" in out and failure["reproducer"] in out
    # a plain sim of the reproducer fails the same way; the nominal scenario does not
    code, out, _ = sim(capsys, "explore/Clamp", "--scenario", cell / "out" / failure["reproducer"], "--format", "json")
    assert code == 1
    assert [(d["code"], d["line"]) for d in json.loads(out)["diagnostics"] if d["severity"] == "error"] == [("R003", 18)]
    code, _, _ = sim(capsys, "explore/Clamp", "--scenario", "explore/clamp.toml")
    assert code == 0
    # one millisecond closer to the nominal passes: the reproducer is the smallest deviation
    closer = re.sub(r"^after = (0\.25\d*)$", lambda m: f"after = {float(m.group(1)) - 0.001:.3f}", text, flags=re.MULTILINE)
    (cell / "closer.toml").write_text(closer)
    assert sim(capsys, "explore/Clamp", "--scenario", "closer.toml")[0] == 0


def test_the_corrected_program_reports_nothing(cell, capsys):
    code, out, err = sim(capsys, "explore/ClampFixed", "--scenario", "explore/clamp.toml", "--explore", "12",
                         "--out-dir", "out", "-j", "1")
    assert code == 0, err
    assert json.loads((cell / "out" / "summary.json").read_text())["failures"] == []
    assert "every variant passed" in out and not list((cell / "out").rglob("*.toml"))


def test_same_seed_same_bytes_and_jobs_do_not_matter(cell, capsys):
    runs = {}
    for name, jobs in (("a", "1"), ("b", "2"), ("c", "1")):
        code, _, err = sim(capsys, *EXPLORE_CLAMP, "--seed", "7", "--out-dir", name, "-j", jobs)
        assert code == 1, err
        runs[name] = files(cell / name)
    assert runs["a"] == runs["b"] == runs["c"]
    assert set(runs["a"]) == {"summary.txt", "summary.json", "junit.xml", "index.html",
                              "failures/01-R003-start-18.toml"}
    # another seed draws other variants (the directed ones are the same)
    sim(capsys, *EXPLORE_CLAMP, "--seed", "8", "--out-dir", "d", "-j", "2")
    assert json.loads(files(cell / "d")["summary.json"])["seed"] == 8


@pytest.mark.dask
def test_dask_finds_the_same_failures(cell, capsys):
    distributed = pytest.importorskip("distributed")
    sim(capsys, *EXPLORE_CLAMP, "--out-dir", "local", "-j", "1")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as lc:
        code, _, err = sim(capsys, *EXPLORE_CLAMP, "--out-dir", "dask", "--executor", "dask",
                           "--scheduler", lc.scheduler_address)
    assert code == 1, err
    assert files(cell / "local") == files(cell / "dask")



@pytest.mark.dask
def test_dask_without_a_scheduler_starts_a_local_cluster(cell, capsys, monkeypatch):
    pytest.importorskip("distributed")
    monkeypatch.delenv("DASK_SCHEDULER_ADDRESS", raising=False)
    sim(capsys, *EXPLORE_CLAMP, "--out-dir", "local", "-j", "1")
    code, _, err = sim(capsys, *EXPLORE_CLAMP, "--out-dir", "dask", "--executor", "dask", "-j", "2")
    assert code == 1, err
    assert files(cell / "local") == files(cell / "dask")

def test_junit_and_html_index_say_what_fails(cell, capsys):
    sim(capsys, *EXPLORE_CLAMP, "--out-dir", "out", "-j", "2")
    import xml.etree.ElementTree as ET

    suite = ET.fromstring((cell / "out" / "junit.xml").read_text())
    assert suite.get("failures") == "1"
    [case] = suite.iter("testcase")
    assert case.get("name") == "R003 explore/Clamp/start.pgx:18:7" and case.find("failure") is not None
    page = (cell / "out" / "index.html").read_text()
    assert 'href="failures/01-R003-start-18.toml"' in page and "<script" not in page
    assert "[[reactions]] #2 after (line 11): 0.15 →" in page


def test_usage_errors(cell, capsys):
    code, _, err = sim(capsys, "explore/Clamp", "--explore", "5")
    assert code == 2 and "--scenario" in err
    (cell / "fixed.toml").write_text('[[reactions]]\nwhen = "doClamp"\nafter = 0.1\nset = { diAck = true }\n')
    code, _, err = sim(capsys, "explore/Clamp", "--scenario", "fixed.toml", "--explore", "5", "--out-dir", "o")
    assert code == 2 and "nothing to vary" in err
    code, _, err = sim(capsys, "explore/Clamp", "--scenario", "fixed.toml", "--explore", "0")
    assert code == 2 and "--explore N" in err
    code, _, err = sim(capsys, "explore/Clamp", "--scenario", "fixed.toml", "--jitter", "0.1")
    assert code == 2 and "--jitter goes with --explore" in err
    code, _, err = sim(capsys, "explore/Clamp", "--scenario", "fixed.toml", "--explore", "3", "--jitter", "-1")
    assert code == 2 and "--jitter" in err
    bad = (cell / "explore" / "clamp.toml").read_text().replace("jitter = 0.02", "jitter = -0.02")
    (cell / "bad.toml").write_text(bad)
    code, _, err = sim(capsys, "explore/Clamp", "--scenario", "bad.toml", "--explore", "3")
    assert code == 2 and "bad scenario: bad.toml:" in err and "[explore] jitter = seconds" in err
    many = "".join(f"[[events]]\nat = {i}\nset = {{ diAck = true }}\n" for i in range(101))
    (cell / "many.toml").write_text(many)
    code, _, err = sim(capsys, "explore/Clamp", "--scenario", "many.toml", "--explore", "100000", "--jitter", "0.1")
    assert code == 2 and "more than 10,000,000 values" in err


# -- the scenario's ranges ------------------------------------------------------------------------

SCENARIO = """# a comment
[[events]]
at = 1.5   # the part arrives
set = { diAck = true }

[[reactions]]
when = "doClamp"
after = { min = 0.1, max = 0.4 }
set = { diClosed = true }

[[reactions]]
when = "doClamp"
becomes = false
set = { diClosed = false }

[controller]
changes = [ { at = 0.01, es_status = 2 }, { at = { min = 2, max = 3, nominal = 2.9 }, es_status = 0 } ]
"""


def test_timings_their_ranges_and_a_variant_s_text():
    data, text = load_bytes(SCENARIO.encode())
    ts = timings(data, text, 0.05)
    assert [(t.label, t.line, t.nominal, t.lo, t.hi) for t in ts] == [
        ("[[events]] #1 at", 3, 1.5, 1.45, 1.55),
        ("[[reactions]] #1 after", 8, 0.25, 0.1, 0.4),  # a range's nominal: its middle
        ("[controller] changes #1 at", 17, 0.01, 0.0, 0.06),  # never below 0
        ("[controller] changes #2 at", 17, 2.9, 2.0, 3.0)]
    out = variant_text(text, ts, (1.5, 0.304, 0.0, 2.25))
    assert out == SCENARIO.replace("after = { min = 0.1, max = 0.4 }", "after = 0.304").replace(
        "at = 0.01,", "at = 0.0,").replace("at = { min = 2, max = 3, nominal = 2.9 }", "at = 2.25")
    assert [t.nominal for t in timings(load_bytes(out.encode())[0], out, 0.0)] == [1.5, 0.304, 0.0, 2.25]


def test_a_plain_run_uses_a_range_s_nominal_and_rejects_a_bad_range(cell, capsys):
    code, out, _ = sim(capsys, "explore/Clamp", "--scenario", "explore/clamp.toml")
    assert code == 0 and re.search(r"0\.150 +dio BasicIO-1\\%I2 \(diClosed\) = true", out)
    bad = (cell / "explore" / "clamp.toml").read_text().replace("max = 0.4,", "max = 0.12,")
    (cell / "bad.toml").write_text(bad)
    code, _, err = sim(capsys, "explore/Clamp", "--scenario", "bad.toml")
    assert code == 2 and "bad.toml:11:" in err
    (cell / "bad.toml").write_text(bad.replace("max = 0.12,", "max = 0.4,").replace("jitter =", "jiter ="))
    code, _, err = sim(capsys, "explore/Clamp", "--scenario", "bad.toml")
    assert code == 2 and "[explore]: unknown key 'jiter'" in err


# -- the search and the shrinking -----------------------------------------------------------------

def _t(i: int, nominal: float, lo: float, hi: float, path=None) -> Timing:
    return Timing(path or ("events", i, "at"), f"t{i}", i + 1, nominal, lo, hi)


def test_uniform_draws_are_fixed_by_the_seed_and_the_draw_alone():
    ts = [_t(0, 1.0, 0.9, 1.1), _t(1, 0.25, 0.1, 0.4)]
    a = [uniform(ts, 3, k) for k in range(20)]
    assert a == [uniform(ts, 3, k) for k in range(20)] and len(set(a)) == 20
    assert a != [uniform(ts, 4, k) for k in range(20)]
    assert all(0.9 <= x <= 1.1 and 0.1 <= y <= 0.4 and round(y * 1000) == y * 1000 for x, y in a)
    seen = Observed()
    assert variants(ts, seen, 8, 3)[:6] == variants(ts, seen, 40, 3)[:6]  # the budget cuts, never reorders


def test_directed_variants_straddle_the_ends_of_waits_and_the_other_events():
    # an event at 1.0 s (0.7 to 1.3) and a reaction of 0.25 s (0.1 to 0.6) to doClamp set at
    # 0.5 s, so acting at 0.75 s; a task's wait ended at 0.7 s in the nominal run
    ts = [_t(0, 1.0, 0.7, 1.3),
          Timing(("reactions", 0, "after"), "r", 2, 0.25, 0.1, 0.6, when="doClamp", becomes=True)]
    seen = Observed(wait_ends=[0.7], changes={"doClamp": [(0.5, True), (0.9, False)]})
    vs = list(directed(ts, seen))
    ev = [v[0] for v in vs if v[1] == 0.25]
    re_ = [v[1] for v in vs if v[0] == 1.0]
    assert {0.7, 1.3} <= set(ev) and {0.1, 0.6} <= set(re_)  # the ends of the ranges
    # the event just before and after the reaction (0.75 s) and the wait's end (0.7 s, inside only)
    assert set(ev) == {0.7, 1.3, 0.749, 0.751, 0.701}
    # the reaction just before and after the wait's end (0.7 s) and the event (1.0 s)
    assert set(re_) == {0.1, 0.6, 0.199, 0.201, 0.499, 0.501}
    assert (0.7, 0.6) in vs and (1.3, 0.1) in vs  # pairs at opposite ends
    assert len(vs) == len(set(vs)) and (1.0, 0.25) not in vs
    # the ends, widest range first; then the boundaries closest to the nominal, each timing in turn
    assert vs[:6] == [(0.7, 0.25), (1.3, 0.25), (1.0, 0.1), (1.0, 0.6), (0.751, 0.25), (1.0, 0.201)]


def test_shrinking_finds_the_smallest_failing_deviation_of_the_timing_that_matters():
    ts = [_t(0, 1.0, 0.9, 1.1), _t(1, 0.25, 0.1, 0.4), _t(2, 0.05, 0.0, 0.1)]
    runs = []

    def check(vs):
        runs.extend(vs)
        return [v[1] >= 0.3005 for v in vs]  # fails when the second acts 0.3005 s or later

    shrunk, n = shrink(ts, (1.07, 0.389, 0.0), check)
    assert shrunk == (1.0, 0.301, 0.05) and n == len(runs) < 40


def test_the_directed_search_finds_what_as_many_uniform_draws_miss(cell, capsys):
    """The clamp's range cut to 0.1-0.26 s: it fails only from 0.252 s on (5 % of the range);
    the five uniform draws of seed 0 all miss it, the directed variants reach it (the range's end)."""
    text = (cell / "explore" / "clamp.toml").read_text().replace("max = 0.4,", "max = 0.26,")
    (cell / "narrow.toml").write_text(text)
    data, _ = load_bytes(text.encode())
    ts = timings(data, text, 0.02)
    assert all(uniform(ts, 0, k)[1] < 0.252 for k in range(5))
    code, _, err = sim(capsys, "explore/Clamp", "--scenario", "narrow.toml", "--explore", "5", "--out-dir", "o",
                       "-j", "1")
    assert code == 1, err
    [failure] = json.loads((cell / "o" / "summary.json").read_text())["failures"]
    assert failure["code"] == "R003" and failure["deviation"][0]["value"] == 0.252


def test_the_causes_of_a_run():
    from val3check.batch.explore.findings import causes
    from val3check.batch.worker import CaseSummary

    base = CaseSummary(key=(), name="n", app="A", app_name="A", arm="", model="none", scenario="s.toml#000003",
                       cell="", overrides=(), verdict="fail", cycle_time=2.8, cycles=3, cycle_max=2.95,
                       causes=(("R003", "error", "A/start.pgx", 18, 7, 256000, "A~", "waits"),
                               ("R003", "error", "A/start.pgx", 18, 7, 900000, "A~", "waits again"),
                               ("R001", "error", "A/start.pgx", 20, 3, 300000, "A~", "error 8")))
    got = causes(base, 2.9)
    assert [c.key for c in got] == [("R003", "A/start.pgx", 18), ("R001", "A/start.pgx", 20), ("cycle-time", "s.toml", 0)]
    assert got[0].when() == "at 0.256 s of simulated time, in task A~" and "2.950 s" in got[2].message
    assert [c.code for c in causes(base, 3.0)] == ["R003", "R001"]  # within the bound
    assert [c.code for c in causes(base, None)] == ["R003", "R001"]  # no bound
    crashed = causes(CaseSummary(**{**base.__dict__, "verdict": "over-budget", "reason": "stopped"}), None)
    assert [(c.code, c.message) for c in crashed] == [("over-budget", "stopped")]


def test_a_scenario_of_thousands_of_times_stays_small():
    """3,000 events and 3,000 ends of waits: the variants are made as they are taken; too many
    values for memory is a usage error."""
    ts = [_t(i, 1.0 + i, 0.5 + i, 1.5 + i) for i in range(3000)]
    seen = Observed(wait_ends=[0.25 + i for i in range(3000)])
    vs = variants(ts, seen, 40, 1)
    assert len(vs) == len(set(vs)) == 40 and all(len(v) == 3000 for v in vs)
