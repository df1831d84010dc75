"""setDH (11.4) mid-run against the live record (issue 29, simulation/live_record.py). setDH
"attend que le mouvement soit vide" (11.4.4): every command recorded before it ran with the old
geometry, every one after it with the new. The records (TCP path length, peak TCP speed) must say
so: those before the change are those of a run without it, those after it those of a run that
changed the geometry first, even where a command after the change repeats one before it."""

from __future__ import annotations

import numpy as np
import pytest

from .simsupport import build, sim
from .test_live_record import _machine
from .test_long_runs import TX2_60

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



def _run(tmp_path, name, early="", late=""):
    code = CODE.replace("{EARLY}", early).replace("{LATE}", late)
    return sim(tmp_path / name, code, globals_=GLOBALS, robot=TX2_60, duration=30.0).motion


def _tcp(record, k, n=50):
    """The TCP speed (mm/s) the reports draw at n samples of motion k, and the samples' offsets."""
    m = record.motions[k]
    times = m.start + np.linspace(0.0, m.end - m.start, n)
    q = record.trajectory.positions(times)
    v = (record.trajectory.positions(times + 1e-6) - record.trajectory.positions(times - 1e-6)) / 2e-6
    return record.tcp_speed(times, q, v)


def test_the_reports_tcp_follows_the_geometry_in_force(tmp_path):
    """The page's TCP speed (and the traces' link poses, collect.ModelKinematics) read each sample
    with the geometry in force at its time: before setDH those of a run without it, after it those
    of a run that changed it first."""
    changed, plain, first = _run(tmp_path, "late", late=SET), _run(tmp_path, "plain"), _run(tmp_path, "early", early=SET)
    for k in range(1, 7):
        assert np.array_equal(_tcp(changed, k), _tcp(plain, k))
    for k in range(7, 13):
        new, ref, old = _tcp(changed, k), _tcp(first, k), _tcp(plain, k)
        assert new == pytest.approx(ref, rel=1e-8, abs=1e-6)
        assert np.abs(new - old).max() > 10.0  # the change shows
    # a link's pose at a time before the change and after it, for the same joints
    kin, q = changed.scene.kinematics, changed.trajectory.positions(np.array([changed.motions[3].end]))
    flange = changed.scene.flange_frame
    t_before, t_after = changed.motions[3].end, changed.motions[12].end
    a = kin.link_poses_many(q, (flange,), times=[t_before])[flange][0]
    b = kin.link_poses_many(q, (flange,), times=[t_after])[flange][0]
    assert np.array_equal(a, plain.scene.kinematics.link_poses_many(q, (flange,))[flange][0])
    assert np.array_equal(a, kin.link_poses(q[0], t_before)[flange])
    assert np.linalg.norm(a[:3, 3] - b[:3, 3]) > 1.0
    assert kin.geometry_at(t_before) == 0 and kin.geometry_at(t_after) == 1
