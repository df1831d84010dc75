"""`val3check robots`: the catalogue, one model, arm.cfx choice, errors."""

from __future__ import annotations

import json

from val3check.cli import main

from .robothelp import ARMS, ROOT


def test_robots_lists_every_model_with_reach_and_limits(capsys):
    assert main(["robots"]) == 0
    out = capsys.readouterr().out
    for name in ARMS:
        assert f"\n{name} " in out
    assert "670 mm" in out and "1710 mm" in out and "2010 mm" in out
    assert "-121..132.5° 1065°/s" in out and "±270°" in out


def test_robots_shows_one_model(capsys):
    assert main(["robots", "tx2_60"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("TX2-60  (arm.cfx: tx2-60)")
    assert "here(flange, world) at zero: {0, 20, 670, 0, 0, 0}" in out
    assert "accelerations:" in out and "assumed" in out
    assert "j5      -121  132.5       1065" in out


def test_robots_json(capsys):
    assert main(["robots", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert [r["name"] for r in data["robots"]] == ARMS
    rx = data["robots"][ARMS.index("RX160")]
    assert rx["reach_mm"] == 1710 and rx["joints"][0]["min_deg"] == -160 and rx["closed_form_ik"]


def test_robots_from_a_controller_tree(capsys):
    app = ROOT / "fixtures" / "valid" / "controller" / "usr" / "usrapp" / "Welder"
    assert main(["robots", "--app", str(app)]) == 0
    assert capsys.readouterr().out.startswith("TX2-60")


def test_robots_unknown_name(capsys):
    assert main(["robots", "TX3-60"]) == 2
    err = capsys.readouterr().err
    assert "unknown robot 'TX3-60'" in err and "RX160L" in err and "TS2-60" in err
