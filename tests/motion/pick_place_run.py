"""The machine of a real run of the bundled pick-and-place (fixtures/valid/PickPlace on a TX2-60
with its scenario), before its history is released: shared by the motion tests that compare a
reused computation with a fresh one on real commands."""

from __future__ import annotations

from pathlib import Path

from val3check.config import Settings
from val3check.lint import run as lint_run
from val3check.robot import load_robot
from val3check.simulation import SimOptions
from val3check.simulation.run import run_machine
from val3check.simulation.scenario import load_scenario

ROOT = Path(__file__).resolve().parents[2]
TX = load_robot("TX2-60")


def pick_place_machine(duration: float):
    """The machine after `duration` simulated seconds (its queue and its arm as the run left them)."""
    ws = lint_run([str(ROOT / "fixtures/valid/PickPlace")], Settings()).workspace
    scenario = load_scenario(str(ROOT / "fixtures/scenarios/pickplace.toml"))
    machine, _ = run_machine(ws, ws.apps[ws.targets[0]], SimOptions(duration=duration, max_wall=900, robot=TX), scenario)
    return machine
