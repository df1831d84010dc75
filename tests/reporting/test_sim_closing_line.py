"""Issue 28 item 2: every `sim` ends with one closing line: PASSED or FAILED as the exit code says,
the diagnostics by severity, the cycle time, and what was written. The text report ends with it;
with `-o`, another format or a trace it is printed on standard error."""

from __future__ import annotations

import json

from val3check.cli import main
from val3check.testing import write_app

PICKPLACE = ["fixtures/valid/PickPlace", "--robot", "tx2-60", "--scenario", "fixtures/scenarios/pickplace.toml",
             "--duration", "10"]


def test_html_written_to_a_file_says_the_verdict_and_what_was_written(tmp_path, capsys):
    folder = write_app(tmp_path, 'begin\n  putln("hi")\nend\n', name="Good")
    out = tmp_path / "r.html"
    assert main(["sim", str(folder), "--report", "html", "-o", str(out)]) == 0
    got = capsys.readouterr()
    assert got.out == "" and out.is_file()
    (line,) = [x for x in got.err.splitlines() if x.startswith("val3check sim: PASSED")]
    assert line.endswith(f"; wrote {out}") and "0 errors, 0 warnings, 0 info" in line
    assert "no cycle time (no arm model)" in line


def test_a_failing_run_says_failed_as_its_exit_code_does(tmp_path, capsys):
    folder = write_app(tmp_path, "begin\n  nI = 3\n  nA[nI] = 1\nend\n", name="Bad", globals_=["num nI", "num nA"])
    assert main(["sim", str(folder), "--report", "json", "-o", str(tmp_path / "b.json")]) == 1
    err = capsys.readouterr().err
    assert "val3check sim: FAILED: 1 error, 0 warnings, 0 info" in err
    # --fail-on never: exit 0, and the line says PASSED with the threshold
    assert main(["sim", str(folder), "--fail-on", "never"]) == 0
    got = capsys.readouterr()
    assert got.out.rstrip("\n").splitlines()[-1].startswith("PASSED (--fail-on never): 1 error, ")
    assert "PASSED" not in got.err  # the text report on standard output carries it, once


def test_the_text_report_ends_with_the_cycle_time_of_the_json(capsys):
    assert main(["sim", *PICKPLACE, "--report", "json"]) == 0
    got = capsys.readouterr()
    (cycle,) = [c for c in json.loads(got.out)["motion"]["cycles"] if c["starts"]]
    (line,) = [x for x in got.err.splitlines() if x.startswith("val3check sim: PASSED")]
    assert f"cycle time {cycle['median']:.3f} s (median of {cycle['cycles']}, task {cycle['task']})" in line
    assert "wrote" not in line  # the JSON went to standard output
    assert main(["sim", *PICKPLACE]) == 0
    last = capsys.readouterr().out.rstrip("\n").splitlines()[-1]
    assert last == line[len("val3check sim: "):]
