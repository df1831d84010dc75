"""What a long run keeps per motion command (issue 29, simulation/retention.py): one object per
value for the tool, mdesc, source and loop pass of its commands (counted in entries, never in bytes
of the machine), the finished run's commands released before the reports, and the same reports."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from val3check.config import Settings
from val3check.lint import run
from val3check.reporting import sim_json
from val3check.rules.catalogue import catalogue
from val3check.simulation import retention
from val3check.simulation.budget import RunBudget
from val3check.simulation.run import SimOptions, run_machine

from .simsupport import build, frozen_clock
from .test_long_runs import LOOP, LOOP_GLOBALS, TX2_60


def _machine(tmp_path, duration: float):
    folder = build(tmp_path, LOOP, globals_=LOOP_GLOBALS)
    ws = run([str(folder)], Settings()).workspace
    return run_machine(ws, ws.apps[ws.targets[0]], SimOptions(duration=duration, robot=TX2_60,
                                                                   wall_clock=frozen_clock))


@pytest.fixture(scope="module")
def long_loop(tmp_path_factory):
    """The movej loop for 5 simulated minutes: about 800 commands."""
    return _machine(tmp_path_factory.mktemp("loop"), 300.0)


def _distinct(objects) -> int:
    return len({id(o) for o in objects})


def test_the_commands_of_a_long_run_share_one_object_per_value(long_loop):
    machine, _ = long_loop
    live = machine.arm.live  # what the run kept of its commands once they left the history (live_record.py)
    assert len(machine.arm.queue_in_use.history) < 300
    moves = [(asked[0], context) for asked, context in zip(live.kept, live.contexts) if asked[0].kind == "movej"]
    assert len(moves) > 700
    # two instructions, one mdesc, one tool: the same objects for every pass
    assert _distinct(req.source for req, _ in moves) == 2
    assert _distinct(req.mdesc for req, _ in moves) == 1
    assert _distinct(req.tool for req, _ in moves) <= 1
    # the two commands of one pass share their loop context
    contexts = [context for _, context in moves]
    assert _distinct(contexts) == len(moves) // 2 + len(moves) % 2
    counts = machine.arm.shared.counts()
    assert counts["sources"] == 2 and counts["mdescs"] == 1 and counts["tools"] <= 1
    assert counts["contexts"] <= retention.SHARED_VALUES


def test_the_interning_tables_stay_bounded_when_every_value_is_new():
    shared = retention.Shared()
    for k in range(3 * retention.SHARED_VALUES):
        tool = np.eye(4)
        tool[0, 3] = k
        got = shared.tool(tool)
        assert got[0, 3] == k
        assert shared.context((k,)) == (k,)
    counts = shared.counts()
    assert counts["tools"] == retention.SHARED_VALUES
    assert counts["contexts"] <= retention.SHARED_VALUES


def test_a_shared_tool_is_read_only_and_kept_exactly():
    shared = retention.Shared()
    a = np.eye(4)
    a[0, 3] = -0.0
    b = np.eye(4)  # +0.0: equal as numbers, not as bytes
    assert shared.tool(a) is a and shared.tool(b) is b
    assert shared.tool(np.eye(4)) is b
    with pytest.raises(ValueError):
        a[0, 0] = 2.0


def test_releasing_the_finished_run_drops_its_commands_and_keeps_the_reports(tmp_path):
    machine, result = _machine(tmp_path, 60.0)
    before = sim_json.render(_report(result))
    retention.release(machine)
    q = machine.arm.queue_in_use
    assert q.history == [] and q.pending == [] and machine.arm.contexts == {}
    assert sim_json.render(_report(result)) == before


class _Queue:
    released = False

    def release_history(self):
        self.released = True


def test_the_history_stays_when_a_layer_of_chapter_11_reads_it():
    for trivial in (True, False):
        q = _Queue()
        arm = SimpleNamespace(queue_in_use=q, layers=SimpleNamespace(trivial=trivial), contexts={1: ()})
        retention.release(SimpleNamespace(arm=arm))
        assert q.released is trivial and arm.contexts == {}


def test_the_reports_budget_does_not_keep_the_machine(long_loop):
    machine, _ = long_loop
    budget = RunBudget.of(machine)
    assert budget.memory is not machine.cell.budget and budget.memory.clock is None
    assert budget.memory.limit == machine.cell.budget.limit and budget.memory.base == machine.cell.budget.base


def _report(result):
    from val3check.reporting.sim_report import build_report

    return build_report(result, Settings(), catalogue(), "test")
