"""The bundled applications that move, run by `val3check sim` past their motions, with their
cells (fixtures/scenarios/): the pick-and-place cell a TX2-60 reaches, and Cell."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from val3check.cli import main
from val3check.robot import load_robot

FIXTURES = Path(__file__).resolve().parents[2] / "fixtures"
TX = load_robot("TX2-60")


def _sim(capsys, app, *args):
    code = main(["sim", str(FIXTURES / "valid" / app), "--robot", "tx2-60", "--report", "json", *args])
    return code, json.loads(capsys.readouterr().out)


def test_pick_and_place_cell_runs_its_cycles(capsys):
    code, r = _sim(capsys, "PickPlace", "--scenario", str(FIXTURES / "scenarios" / "pickplace.toml"),
                   "--duration", "40")
    assert code == 0 and r["end"]["reason"] == "duration"
    assert [d["code"] for d in r["diagnostics"]] == ["R007"]
    mo = r["motion"]
    assert mo["summary"]["failed"] == 0 and mo["summary"]["done"] >= 50
    start, cy = mo["cycles"]
    # start() moves the arm home once, outside any loop: no cycle, and why
    assert start["task"] == "PickPlace~" and start["loop"] is None and start["cycles"] == 0
    assert "outside any loop" in start["why"]
    # the robot task's cycle is cycle()'s `while bStop == false`, around the calls of pick and place
    assert cy["task"] == "robot" and cy["path"].endswith("cycle.pgx") and cy["cycles"] >= 10
    assert (cy["loop"], cy["program"], cy["line"]) == ("while", "cycle", 9) and "outermost" in cy["why"]
    # a cycle: 0.8 s of conveyor, two approaches at 250 mm/s, the gripper's 0.25 s and 0.15 s
    assert 0.8 + 0.25 + 0.15 + 4 * 100 / 250 < cy["median"] < 4.0
    # the pallet change (3 s) makes one cycle longer
    assert cy["max"] > cy["median"] + 3.0
    # every grip and release happens where the arm stands still, with the tool's centre point
    # on the pick or a pallet slot
    events = mo["tool_events"]
    assert [e["action"] for e in events[:3]] == ["open", "close", "open"]
    assert all(e["tool"] == "tGripper" and e["gripper"] == "valve1" for e in events)
    assert events[1]["tcp_in_flange"] == [0.0, 0.0, 120.0, 0.0, 0.0, 0.0]
    # the 4 ms trajectory stays within the joint speed limits
    for seg in mo["trajectory"]["segments"]:
        v = np.array(seg["velocities"])
        assert np.all(np.abs(v) <= np.array(TX.nominal_speeds) * (1 + 1e-6))
    placed = [e for e in r["transcript"] if e["kind"] == "putln"]
    assert placed and placed[-1]["text"].startswith("parts placed: ")


def test_cell_runs_to_its_honest_error(capsys):
    """Cell: home, then a pick (approach, line, close), then place's movec, whose start (the
    previous motion's target) is its own target: no arc (10.1.4.1), error 154 at its line."""
    code, r = _sim(capsys, "Cell", "--scenario", str(FIXTURES / "scenarios" / "cell.toml"), "--duration", "30")
    assert code == 1
    d = [d for d in r["diagnostics"] if d["severity"] == "error"]
    assert [(x["code"], x["error"], x["path"].rsplit("/", 1)[-1], x["line"]) for x in d] == [
        ("R015", 154, "moves.pgx", 29)]
    assert r["motion"]["summary"]["done"] >= 4
    assert "too close" in d[0]["message"]


@pytest.mark.parametrize("app", ["Cell", "Pallet"])
def test_reach_of_the_bundled_cells_is_warnings(capsys, app):
    """Their points are out of a TX2-60's reach with some tools (the cells were drawn for a
    larger arm): warnings of `val3check reach`, exit 0 unless --fail-on warning."""
    assert main(["reach", str(FIXTURES / "valid" / app), "--robot", "tx2-60"]) == 0
    out = capsys.readouterr().out
    assert "[error]" not in out
