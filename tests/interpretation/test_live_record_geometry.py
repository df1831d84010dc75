"""setDH (11.4) mid-run against the live record (issue 29, simulation/live_record.py). setDH
"attend que le mouvement soit vide" (11.4.4): every command recorded before it ran with the old
geometry, every one after it with the new. The records (TCP path length, peak TCP speed) must say
so: those before the change are those of a run without it, those after it those of a run that
changed the geometry first, even where a command after the change repeats one before it."""

from __future__ import annotations

import pytest

from .simsupport import build
from .test_live_record import _machine

# two passes of the same back-and-forth, the forearm made 4 mm longer (d[3], 11.4.1) between them
CODE = """begin
  jA.j1 = 40
  jA.j2 = 20
  jA.j3 = 80
  jA.j5 = 60
  jB.j1 = -40
  jB.j2 = 30
  jB.j3 = 70
  jB.j5 = 60
  movej(jB, flange, mD)
  waitEndMove()
  {EARLY}
  for nI = 1 to 3
    movej(jA, flange, mD)
    movej(jB, flange, mD)
  endFor
  waitEndMove()
  {LATE}
  for nI = 1 to 3
    movej(jA, flange, mD)
    movej(jB, flange, mD)
  endFor
  waitEndMove()
end
"""
GLOBALS = ["num nTheta[6]", "num nD[7]", "num nA[6]", "num nB[6]", "num nAlpha[6]", "num nBeta[6]", "bool bOk",
           "joint jA", "joint jB", "mdesc mD", "num nI"]
SET = """getDefaultDH(nTheta, nD, nA, nAlpha, nBeta)
  nD[3] = nD[3] + 4
  bOk = setDH(nTheta, nD, nA, nB, nAlpha, nBeta)"""


def _figures(tmp_path, name, early="", late="", **kw):
    code = CODE.replace("{EARLY}", early).replace("{LATE}", late)
    machine, result = _machine(build(tmp_path / name, code, globals_=GLOBALS), 30.0, **kw)
    motions = result.motion.motions
    assert len(motions) == 13 and all(m.state == "done" for m in motions)
    return [(m.length_mm, m.peak_tcp_mm_s) for m in motions]


@pytest.mark.parametrize("live", [True, False])
def test_records_before_a_geometry_change_keep_the_geometry_they_ran_with(tmp_path, monkeypatch, live):
    kw = {} if live else {"live": False, "monkeypatch": monkeypatch}
    changed = _figures(tmp_path, "late", late=SET, **kw)
    plain = _figures(tmp_path, "plain")
    first = _figures(tmp_path, "early", early=SET)
    assert changed[:7] == plain[:7]  # before setDH: the standard geometry's figures, to the bit
    # after it: the new geometry's, though the joints repeat (up to the last bits: the motions run
    # at other times and path lengths than in the run that changed it first)
    for a, b in zip(changed[7:], first[7:]):
        assert a == pytest.approx(b, rel=1e-11, abs=0)
    # the change shows: the same joint motion, another TCP path
    assert all(abs(a[0] - b[0]) > 1.0 for a, b in zip(first[7:], plain[7:]))
