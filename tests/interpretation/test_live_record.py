"""The run's motion records taken as the run goes (issue 29, simulation/live_record.py): the queue's
hook (`MotionQueue.final_before`) never lets a record read a profile that changes after, the
records made live are those made after the run (several programs: blends, stops, resets,
waitEndMove, two tools; the whole JSON report compared), and a long run's history stays bounded."""

from __future__ import annotations

import random
from dataclasses import fields

import numpy as np
import pytest

from motion.motionhelp import HOME, movej, queue
from val3check.config import Settings
from val3check.lint import run
from val3check.motion.mdesc import MDesc
from val3check.reporting import sim_json
from val3check.reporting.sim_report import build_report
from val3check.rules.catalogue import catalogue
from val3check.simulation import live_record
from val3check.simulation.run import SimOptions, run_machine

from .simsupport import build, frozen_clock
from .test_long_runs import LOOP, LOOP_GLOBALS, TX2_60

# blended movel corners with two tools, a stop and a restart, waitEndMove each pass
BLENDS = """begin
  movej({0, 20, 100, 0, 60, 0}, flange, mStop)
  waitEndMove()
  tT.trsf = {0, 0, 80, 0, 0, 0}
  pA = here(flange, world)
  pB = compose(pA, world, {0, 0, 40, 0, 0, 0})
  pC = compose(pA, world, {0, 250, 40, 0, 0, 0})
  pD = compose(pA, world, {0, 250, 0, 0, 0, 0})
  mB.blend = joint
  mB.leave = 20
  mB.reach = 60
  mStop.blend = off
  while true
    movel(pB, flange, mB)
    movel(pC, flange, mB)
    movel(pD, flange, mStop)
    movej({10, 25, 95, 0, 60, 0}, tT, mB)
    movej({0, 20, 100, 0, 60, 0}, tT, mStop)
    delay(0.2)
    stopMove()
    delay(0.1)
    restartMove()
    waitEndMove()
    delay(0.05)
  endWhile
end
"""
BLENDS_GLOBALS = ["point pA", "point pB", "point pC", "point pD", "mdesc mB", "mdesc mStop", "tool tT"]
# a resetMotion in the middle of a motion every third pass, the run going on after it
RESETS = """begin
  jA.j1 = 30
  jB.j1 = -30
  jB.j2 = 20
  while true
    movej(jA, flange, mD)
    movej(jB, flange, mD)
    nI = nI + 1
    if nI >= 3
      nI = 0
      delay(0.2)
      resetMotion()
    endIf
    waitEndMove()
  endWhile
end
"""
RESETS_GLOBALS = ["joint jA", "joint jB", "mdesc mD", "num nI"]


def _machine(folder, duration, live=True, monkeypatch=None):
    if not live:  # every record made after the run, as before issue 29's live record
        monkeypatch.setattr(live_record.LiveRecord, "take", lambda self, arm, queue: None)
    ws = run([str(folder)], Settings()).workspace
    machine, result = run_machine(ws, ws.apps[ws.targets[0]], SimOptions(duration=duration, robot=TX2_60,
                                                                          wall_clock=frozen_clock))
    if not live:
        monkeypatch.undo()
    return machine, result


def _bits(entry) -> tuple:
    """A motion table row, its arrays by their bytes (floats compared bit for bit)."""
    values = (getattr(entry, f.name) for f in fields(entry))
    return tuple(v.tobytes() if isinstance(v, np.ndarray) else repr(v) for v in values)


def _report(result) -> str:
    return "".join(sim_json.render(build_report(result, Settings(), catalogue(), "test")))


@pytest.mark.parametrize("name, code, globals_, duration", [
    ("loop", LOOP, LOOP_GLOBALS, 200.0),
    ("blends", BLENDS, BLENDS_GLOBALS, 120.0),
    ("resets", RESETS, RESETS_GLOBALS, 60.0),
])
def test_the_records_made_live_are_those_made_after_the_run(tmp_path, monkeypatch, name, code, globals_, duration):
    folder = build(tmp_path, code, globals_=globals_)
    machine, live = _machine(folder, duration)
    _, after = _machine(folder, duration, live=False, monkeypatch=monkeypatch)
    taken = machine.arm.live
    assert len(taken.kept) == len(live.motion.motions) > 100
    if name == "resets":  # a cancelled command's record reads the profile as the run ends: the rest waited
        assert taken.blocked and any(m.state == "cancelled" for m in live.motion.motions)
    else:  # most commands were recorded and released while the run went
        assert machine.arm.queue_in_use.released_done >= 2 * live_record.RELEASE_AT
        assert len(machine.arm.queue_in_use.history) < live_record.RELEASE_AT + 20
    assert [_bits(m) for m in live.motion.motions] == [_bits(m) for m in after.motion.motions]
    assert live.motion.cycles == after.motion.cycles
    assert live.motion.acceleration_range == after.motion.acceleration_range
    assert _report(live) == _report(after)


# the monitor speed halved between two motions (BETWEEN) or while the second runs (DURING): 8.1
SPEED_CHANGE = """begin
  jA.j1 = 60
  jB.j1 = -60
  jB.j2 = 30
  movej(jA, flange, mD)
  waitEndMove()
  {BETWEEN}
  movej(jB, flange, mD)
  {DURING}
  waitEndMove()
  movej(jA, flange, mD)
  waitEndMove()
end
"""
SPEED_CHANGE_GLOBALS = ["joint jA", "joint jB", "mdesc mD", "num nR"]


@pytest.mark.parametrize("between, during", [("nR = setMonitorSpeed(50)", ""),
                                             ("", "delay(0.2)\n  nR = setMonitorSpeed(50)")])
def test_a_monitor_speed_change_mid_run_gives_the_records_made_after_the_run(tmp_path, monkeypatch, between, during):
    """The live record takes a command's limits when the command is final; made after the run,
    every record read the limits in force at the end. A monitor speed change mid-run (8.1) leaves
    the two the same, and the motions before it those of a run without it."""
    code = SPEED_CHANGE.replace("{BETWEEN}", between).replace("{DURING}", during)
    machine, live = _machine(build(tmp_path / "change", code, globals_=SPEED_CHANGE_GLOBALS), 30.0)
    _, after = _machine(build(tmp_path / "after", code, globals_=SPEED_CHANGE_GLOBALS), 30.0, live=False,
                        monkeypatch=monkeypatch)
    plain = SPEED_CHANGE.replace("{BETWEEN}", "").replace("{DURING}", "delay(0.2)" if during else "")
    _, same = _machine(build(tmp_path / "plain", plain, globals_=SPEED_CHANGE_GLOBALS), 30.0)
    assert machine.arm.live.kept and len(live.motion.motions) == 3
    def row(m):  # its source (a path in another folder) aside
        b = _bits(m)
        return b[:2] + b[3:]

    assert [row(m) for m in live.motion.motions] == [row(m) for m in after.motion.motions]
    first, second, third = live.motion.motions
    assert row(first) == row(same.motion.motions[0])
    # at half the speed the second motion (changed before or while it runs) and the third are slower
    for k, m in ((1, second), (2, third)):
        ref = same.motion.motions[k]
        assert m.end - m.start > (ref.end - ref.start) * 1.05 and m.peak_tcp_mm_s < ref.peak_tcp_mm_s


def test_a_long_run_keeps_a_bounded_history_and_counts_its_motions(tmp_path):
    seen = []
    folder = build(tmp_path, LOOP, globals_=LOOP_GLOBALS)
    ws = run([str(folder)], Settings()).workspace
    machine, result = run_machine(ws, ws.apps[ws.targets[0]], SimOptions(
        duration=600.0, robot=TX2_60, wall_clock=frozen_clock, progress=lambda t, done: seen.append((t, done()))))
    q = machine.arm.queue_in_use
    assert len(result.motion.motions) > 1500
    assert len(q.history) < live_record.RELEASE_AT + 20 and len(q._by_key) == len(q.history)
    assert len(machine.arm.contexts) < live_record.RELEASE_AT + 20
    # the progress count (run.py's motions_done) adds the commands released
    done = sum(1 for m in result.motion.motions if m.state == "done" and m.id is not None)
    assert seen and seen[-1][1] <= done and q.released_done + sum(
        1 for c in q.history if c.state == "done" and c.id is not None) == done


def test_the_profile_never_changes_before_the_time_the_queue_says_is_final():
    """Records, blends, waits, stops, restarts, monitor speeds, power and resets at random times:
    every breakpoint before `final_before` stays as it was, whatever comes after."""
    rng = random.Random(29)
    for trial in range(6):
        q = queue()
        now, frozen = 0.0, []
        for step in range(60):
            now += rng.choice([0.0, 0.0005, 0.01, 0.1, 0.4, 1.0])
            op = rng.random()
            blend = MDesc(blend="joint", leave=30, reach=30) if rng.random() < 0.5 else MDesc(blend="off")
            if op < 0.45:
                joints = HOME + np.array([rng.uniform(-60, 60), rng.uniform(-10, 10), 0, 0, 0, 0])
                q.record(movej(joints, blend), now)
            elif op < 0.55:
                q.wait_end_move(now)
            elif op < 0.62:
                q.stop_move(now)
            elif op < 0.7:
                q.restart_move(now)
            elif op < 0.76:
                q.set_monitor_speed(rng.choice([0.0, 30.0, 100.0]), now)
            elif op < 0.8:
                q.set_power(rng.random() < 0.7, now)
            elif op < 0.84:
                q.reset_motion(now)
            else:
                q.advance(now)
            q.advance(now)
            final = q.final_before()
            assert final <= now + 1e-12
            prof = q.planner.profile
            k = int(np.searchsorted(np.asarray(prof.T), final, side="right"))
            frozen.append((k, bytes(prof.T[:k]), bytes(prof.S[:k]), bytes(prof.SD[:k])))
            _ = q.trajectory  # the replan due done: what any reader sees
            for k, T, S, SD in frozen:
                assert (bytes(prof.T[:k]), bytes(prof.S[:k]), bytes(prof.SD[:k])) == (T, S, SD), (trial, step)


def test_chapter_11_reading_the_history_stops_the_release():
    from types import SimpleNamespace as NS

    plain = NS(layers=NS(trivial=True), alteration=NS(alterable=set(), state="off", deferred=[]),
               compliance=NS(moves=[]))
    assert not live_record._history_read(plain)
    for changed in (dict(layers=NS(trivial=False)), dict(alteration=NS(alterable={3}, state="off", deferred=[])),
                    dict(alteration=NS(alterable=set(), state="pending", deferred=[])),
                    dict(compliance=NS(moves=[object()]))):
        assert live_record._history_read(NS(**{**vars(plain), **changed}))


def _pick_place(duration: float, live: bool, monkeypatch):
    """The bundled pick-and-place (its scenario) on a TX2-60: the machine and its result."""
    from motion.pick_place_run import ROOT, TX
    from val3check.simulation.scenario import load_scenario

    if not live:
        monkeypatch.setattr(live_record.LiveRecord, "take", lambda self, arm, queue: None)
    ws = run([str(ROOT / "fixtures/valid/PickPlace")], Settings()).workspace
    scenario = load_scenario(str(ROOT / "fixtures/scenarios/pickplace.toml"))
    out = run_machine(ws, ws.apps[ws.targets[0]], SimOptions(duration=duration, max_wall=900, robot=TX,
                                                             wall_clock=frozen_clock), scenario)
    if not live:
        monkeypatch.undo()
    return out


def test_near_ties_decided_in_blocks_during_the_run_give_the_records_made_after_it(monkeypatch):
    """The live record decides the repeats' near ties once DECIDE_BLOCK of them wait (one evaluation
    of each piece of path for the block), not at every flush: with blocks of 3 decided all along a
    real run, the rows, cycles, acceleration range and report are those made after the run."""
    from val3check.motion import motion_records

    _, after = _pick_place(300.0, False, monkeypatch)
    monkeypatch.setattr(motion_records, "DECIDE_BLOCK", 3)
    decided = []
    decide = motion_records._decide

    def spy(queue, prof, out, doubts):
        decided.append(len(doubts))
        return decide(queue, prof, out, doubts)

    monkeypatch.setattr(motion_records, "_decide", spy)
    machine, live = _pick_place(300.0, True, monkeypatch)
    assert machine.arm.queue_in_use.released_done >= live_record.RELEASE_AT  # taken and released live
    assert sum(n >= 3 for n in decided[:-1]) >= 3  # decided in blocks along the run, not only at its end
    assert [_bits(m) for m in live.motion.motions] == [_bits(m) for m in after.motion.motions]
    assert live.motion.cycles == after.motion.cycles
    assert live.motion.acceleration_range == after.motion.acceleration_range
    assert _report(live) == _report(after)
