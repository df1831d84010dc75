"""What the scheduler's loop keeps to answer its frequent questions cheaply (issue 29, fifth
round) is what a fresh computation gives: the queue's count of completed commands (the progress
display's motions done) against the count over the history."""

from __future__ import annotations

from pathlib import Path

from val3check.config import Settings
from val3check.lint import run as lint_run
from val3check.simulation import SimOptions
from val3check.simulation.moving_arm import MovingArm
from val3check.simulation.run import run_machine
from val3check.simulation.scenario import load_scenario

from .pick_place_run import TX

ROOT = Path(__file__).resolve().parents[2]


def _done_over_history(queue) -> int:
    return sum(1 for c in queue.history if c.state == "done" and c.id is not None)


def test_motions_done_is_the_count_over_the_history_at_every_progress_call():
    ws = lint_run([str(ROOT / "fixtures/valid/PickPlace")], Settings()).workspace
    scenario = load_scenario(str(ROOT / "fixtures/scenarios/pickplace.toml"))
    seen: list[tuple[int, int]] = []
    arms: list[MovingArm] = []

    def progress(sim_s, motions_done):
        queue = arms[0].queue_in_use if arms else None
        seen.append((motions_done(), 0 if queue is None else _done_over_history(queue)))

    options = SimOptions(duration=60.0, max_wall=900, robot=TX, progress=progress)
    from val3check.simulation import run as run_mod

    made = run_mod.build_machine

    cycles: list[tuple[int, int]] = []

    def build(*a, **k):
        m = made(*a, **k)
        arms.append(m.arm)

        def each_cycle(time_us, cycle):  # after each record and at each cycle the arm advances
            q = m.arm.queue_in_use
            if q is not None:
                cycles.append((q.completed, _done_over_history(q)))

        m.arm.watch(each_cycle)
        return m

    run_mod.build_machine = build
    try:
        machine, _ = run_machine(ws, ws.apps[ws.targets[0]], options, scenario)
    finally:
        run_mod.build_machine = made
    assert seen and len(cycles) > 200 and cycles[-1][0] > 30
    assert all(a == b for a, b in seen + cycles)
    q = machine.arm.queue_in_use
    # a resetMotion cancels what is pending; the completed stay counted
    q.reset_motion(q.profile.t_end)
    assert q.completed == _done_over_history(q)
