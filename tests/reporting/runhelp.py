"""A real run of the bundled pick-and-place cell (fixtures/valid/PickPlace on a TX2-60 with its
scenario), shared by the tests of the reports built from a run (HTML, MCAP, JUnit)."""

from __future__ import annotations

import functools
from pathlib import Path

from val3check.config import Settings
from val3check.lint import run
from val3check.reporting.sim_report import build_report
from val3check.robot import load_robot
from val3check.rules.catalogue import catalogue
from val3check.simulation import SimOptions, simulate
from val3check.simulation.scenario import load_scenario

ROOT = Path(__file__).resolve().parents[2]
APP = ROOT / "fixtures" / "valid" / "PickPlace"
SCENARIO = ROOT / "fixtures" / "scenarios" / "pickplace.toml"
CELL = Path(__file__).resolve().parent / "data" / "pickplace-cell.toml"


@functools.lru_cache(maxsize=4)
def pickplace(duration: float = 20.0):
    """(SimResult, SimReport) of PickPlace run for `duration` simulated seconds."""
    lr = run([str(APP)], Settings())
    ws = lr.workspace
    app = ws.apps[ws.targets[0]]
    result = simulate(ws, app, SimOptions(duration=duration, robot=load_robot("tx2-60")), load_scenario(str(SCENARIO)))
    return result, build_report(result, Settings(), catalogue(), "test")
