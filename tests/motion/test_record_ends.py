"""A motion's record (motion_records.py) reads its own part of the path only: the end of a motion
that stops is evaluated on its own span, not on the next motion's, which starts at the same path
position with another rate in s. The TCP length of a movel is its straight line's (10.3.2), that of
a movej the same whether another motion follows or not."""

from __future__ import annotations

import math

import pytest
from interpretation.simsupport import sim
from interpretation.test_long_runs import TX2_60

CODE = """begin
  jA.j2 = 20
  jA.j3 = 80
  jA.j5 = 60
  movej(jA, flange, mD)
  waitEndMove()
  pA = here(flange, world)
  pB = appro(pA, {0, 200, -50, 0, 0, 0})
  movel(pB, flange, mD)
  waitEndMove()
  {NEXT}
end
"""
GLOBALS = ["joint jA", "joint jB", "point pA", "point pB", "mdesc mD"]


def _lengths(tmp_path, name, after):
    r = sim(tmp_path / name, CODE.replace("{NEXT}", after), globals_=GLOBALS, robot=TX2_60, duration=30.0)
    return [m.length_mm for m in r.motion.motions]


def test_a_motion_that_stops_is_measured_on_its_own_path(tmp_path):
    alone = _lengths(tmp_path, "alone", "")
    followed = _lengths(tmp_path, "followed", "jB.j1 = 50\n  movej(jB, flange, mD)\n  waitEndMove()")
    assert len(alone) == 2 and len(followed) == 3
    # the movel: a straight line of (0, 200, -50) mm, whatever follows it (it was 206.229 when a
    # movej followed: its end point read on the movej's span)
    assert followed[1] == pytest.approx(math.hypot(200.0, 50.0), rel=1e-9)
    assert alone[1] == pytest.approx(math.hypot(200.0, 50.0), rel=1e-9)
    # the first movej is followed by the movel in both runs; it was 771.55 mm, read at its end on
    # the movel's span (a dense polyline of its flange gives 775.16)
    assert followed[0] == alone[0] == pytest.approx(775.16, abs=0.05)
