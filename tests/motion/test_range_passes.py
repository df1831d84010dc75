"""The acceleration range's cycles (simulation/collect.acceleration_range, issue 29): each task's
cycle loop and the first command of its passes found once by index for every factor, and only
those commands' starts re-timed, give the CycleEntry of every factor that cycle_stats gives on the
whole re-timed records (the same floats, bit for bit), with the run cut short by the wall-clock
budget too (passes never started left out, the same as before)."""

from __future__ import annotations

import pytest

from val3check.motion.retime import each_retimed, each_retimed_times
from val3check.robot.models import ASSUMED_ACCELERATION_RANGE
from val3check.simulation import collect as collect_module
from val3check.simulation.arm_record import CycleEntry

from .test_retime_reuse import machine_run  # noqa: F401 (the fixture)


def _cycle_entries(machine, records) -> dict:
    """The cycles as cycle_stats gives them on whole records (what collect did before)."""
    return {task: CycleEntry(st.task, st.marker, tuple(st.starts), st.loop and st.loop.program,
                             st.loop and st.loop.kind, st.why, st.passes)
            for task, st in collect_module.task_cycles(machine, records).items()}


def _records(machine):
    arm = machine.arm
    q = arm.queue_in_use
    return q, arm.live.records(arm, q, arm.queue_time(machine.end_time))


def _spent_after(n):
    calls = [0]

    def out_of_time():
        calls[0] += 1
        return calls[0] > n
    return out_of_time


def _bits(entries) -> list:
    return [(task, e.task, e.marker, [float(t).hex() for t in e.starts], e.program, e.kind, e.why, e.passes)
            for cycles in entries for task, e in cycles.items()]


@pytest.mark.parametrize("spent_after", [None, 0, 1, 3, 6])
def test_the_range_s_cycles_are_those_of_the_whole_retimed_records(machine_run, monkeypatch, spent_after):  # noqa: F811
    machine, _ = machine_run
    q, records = _records(machine)
    ref = [_cycle_entries(machine, moved)
           for moved, _ in each_retimed(q, records, ASSUMED_ACCELERATION_RANGE,
                                        None if spent_after is None else _spent_after(spent_after))]
    if spent_after is not None:
        budget = _spent_after(spent_after)
        monkeypatch.setattr(collect_module.RunBudget, "out_of_time", lambda self: budget())
    diags: list = []
    got = collect_module.acceleration_range(machine, q, records, diags)
    assert _bits(got.cycles) == _bits(ref)
    if spent_after is None:  # the passes given (arm_run: the run's, found once)
        passes = collect_module.task_cycles(machine, [collect_module._Indexed(r.id, r.source, i)
                                                      for i, r in enumerate(records)])
        assert _bits(collect_module.acceleration_range(machine, q, records, [], passes).cycles) == _bits(ref)
    assert len(ref) == len(ASSUMED_ACCELERATION_RANGE)
    assert any(e.starts for cycles in ref for e in cycles.values()) == (spent_after is None or spent_after >= 3)
    if spent_after is None:
        assert got.partial is None and not diags
        assert all(len(e.starts) == e.passes == 20 for cycles in ref for e in cycles.values())
    else:
        assert got.partial is not None and len(diags) == 1
        # a factor cut short: the passes it never started are left out, as in the whole records' cycles
        assert any(len(e.starts) < e.passes for cycles in ref for e in cycles.values())


def test_each_retimed_times_gives_the_records_starts_and_ends(machine_run):  # noqa: F811
    machine, _ = machine_run
    q, records = _records(machine)
    some = [records[i].start for i in range(0, len(records), 3)] + [None, records[-1].end]
    for (moved, _), (at, _) in zip(each_retimed(q, records, (0.5, 2.0)), each_retimed_times(q, some, (0.5, 2.0))):
        want = [r.start for r in moved[0::3]] + [None, moved[-1].end]
        assert [None if t is None else t.hex() for t in at] == [None if t is None else t.hex() for t in want]


def test_the_run_s_cycles_are_those_of_its_whole_records(machine_run):  # noqa: F811
    machine, result = machine_run
    _, records = _records(machine)
    assert _bits([result.motion.cycles]) == _bits([_cycle_entries(machine, records)])
    (entry,) = result.motion.cycles.values()
    assert len(entry.starts) == entry.passes == 20
