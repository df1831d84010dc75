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
def pickplace(duration: float = 20.0, cell: str | None = None):
    """(SimResult, SimReport) of PickPlace run for `duration` simulated seconds; with `cell`, its
    collisions checked in that cell file (`result.collision`, `result.motion.cell_timeline`)."""
    lr = run([str(APP)], Settings())
    ws = lr.workspace
    app = ws.apps[ws.targets[0]]
    checks = {"collisions": True, "cell": cell, "cell_found": "option"} if cell else {}
    result = simulate(ws, app, SimOptions(duration=duration, robot=load_robot("tx2-60"), **checks),
                      load_scenario(str(SCENARIO)))
    return result, build_report(result, Settings(), catalogue(), "test")


# A run that moves a frame and carries a part (issue 24): the TCP (tGrip, 100 mm out of the flange,
# pointing down) takes a brick at pPick, lifts it, and sets it down at pPlace; between the lift and
# the way to pPlace the program moves fBlock from x = -400 to x = 400 (a block hangs on it, 300 mm
# beside the path).
MOVING = """
begin
  tGrip.trsf = {0, 0, 100, 0, 0, 0}
  pPick.trsf = {400, -200, 40, 0, 180, 0}
  pPick.config = {sfree, efree, wfree}
  pPlace = pPick
  pPlace.trsf.y = 200
  fBlock.trsf = {-400, 0, 0, 0, 0, 0}
  movej(appro(pPick, {0, 0, -100, 0, 0, 0}), tGrip, mD)
  movel(pPick, tGrip, mD)
  close(tGrip)
  movel(appro(pPick, {0, 0, -100, 0, 0, 0}), tGrip, mD)
  waitEndMove()
  fBlock.trsf.x = 400
  movel(appro(pPlace, {0, 0, -100, 0, 0, 0}), tGrip, mD)
  movel(pPlace, tGrip, mD)
  open(tGrip)
  movel(appro(pPlace, {0, 0, -100, 0, 0, 0}), tGrip, mD)
  waitEndMove()
end
"""
MOVING_GLOBALS = ["point pPick", "point pPlace", "tool tGrip", "mdesc mD", "frame fBlock"]
MOVING_CELL = """version = 1
[[obstacle]]
name = "table"
shape = "box"
size = [200, 600, 40]
at = { x = 400, z = -20 }

[[obstacle]]
name = "block"
shape = "box"
frame = "fBlock"
size = [120, 120, 120]
at = { y = 500, z = 100 }

[[tool]]
name = "finger"
tool = "tGrip"
shape = "sphere"
radius = 4
at = { z = -5 }

[[part]]
name = "brick"
tool = "tGrip"
grasp = "close"
shape = "box"
size = [40, 40, 40]
at = { z = 20 }
"""


def moving_run(tmp_path: Path):
    """(SimResult, SimReport) of MOVING, its collisions checked in MOVING_CELL."""
    from interpretation.simsupport import sim

    cell = tmp_path / "cell.toml"
    cell.write_text(MOVING_CELL, encoding="utf-8")
    result = sim(tmp_path, MOVING, globals_=MOVING_GLOBALS, robot=load_robot("tx2-60"), collisions=True,
                 cell=str(cell))
    return result, build_report(result, Settings(), catalogue(), "test")
