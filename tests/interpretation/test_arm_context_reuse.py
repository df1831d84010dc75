"""The arm's loop contexts (simulation/moving_arm.py, `MovingArm.context`) make a loop statement's
Loop once per loop site and reuse it for every command recorded in it (issue 29): the reuse is
keyed by the site and the program (objects, not only their ids), each input of the Loop shows in
it, and a long run's contexts are those made fresh for every command."""

from __future__ import annotations

from types import SimpleNamespace

from val3check.config import Settings
from val3check.lint import run
from val3check.motion.cycle import Loop
from val3check.simulation.moving_arm import MovingArm
from val3check.simulation.run import SimOptions, run_machine

from .simsupport import build, frozen_clock
from .test_long_runs import LOOP_GLOBALS, TX2_60

NESTED = """begin
  jA.j1 = 30
  jB.j1 = -30
  jB.j2 = 20
  while true
    for l_i = 1 to 2
      movej(jA, flange, mD)
      movej(jB, flange, mD)
    endFor
    do
      movej(jA, flange, mD)
    until true
    waitEndMove()
  endWhile
end
"""


def _program(path="a.pgx", name="cycle"):
    return SimpleNamespace(path=path, name=name)


def _site(line=3, col=5, kind="while"):
    return SimpleNamespace(line=line, col=col, kind=kind)


def _loop(arm, compiled, site, counter=None):
    return arm.context(((compiled, site, counter or [1]),))[0].loop


def test_the_same_site_gives_the_same_loop_and_each_input_shows():
    arm = MovingArm(None)
    prog, site = _program(), _site()
    first = _loop(arm, prog, site)
    assert first == Loop("a.pgx", 3, 5, "cycle", "while")
    assert _loop(arm, prog, site, [2]) is first  # reused: a second pass, a second entry
    # each input in turn: a new site or program is a new Loop, with the new value
    for other_prog, other_site, want in (
            (_program(path="b.pgx"), site, Loop("b.pgx", 3, 5, "cycle", "while")),
            (_program(name="pick"), site, Loop("a.pgx", 3, 5, "pick", "while")),
            (prog, _site(line=4), Loop("a.pgx", 4, 5, "cycle", "while")),
            (prog, _site(col=7), Loop("a.pgx", 3, 7, "cycle", "while")),
            (prog, _site(kind="for"), Loop("a.pgx", 3, 5, "cycle", "for"))):
        assert _loop(arm, other_prog, other_site) == want


def test_a_site_whose_id_is_reused_is_not_taken_for_the_old_one():
    arm = MovingArm(None)
    prog, old, new = _program(), _site(line=3), _site(line=9)
    arm._loops[id(new)] = (old, prog, Loop("a.pgx", 3, 5, "cycle", "while"))  # as if `old` had died there
    assert _loop(arm, prog, new).line == 9
    arm._loops[id(new)] = (new, _program(name="pick"), Loop("a.pgx", 9, 5, "pick", "while"))  # another program
    assert _loop(arm, prog, new).program == "cycle"


def _contexts_reused_and_afresh(tmp_path, monkeypatch, forget):
    """Every command's context and the cycles of 60 s of NESTED, with the arm's reuse as it is and
    with `forget(arm)` called before every context is made (the reference)."""
    folder = build(tmp_path, NESTED, globals_=LOOP_GLOBALS, locals_=["num l_i"])
    ws = run([str(folder)], Settings()).workspace
    app = ws.apps[ws.targets[0]]

    def contexts():
        machine, result = run_machine(ws, app, SimOptions(duration=60.0, robot=TX2_60, wall_clock=frozen_clock))
        # every command's context, in order: taken by the live record as the commands become final
        # (simulation/live_record.py: the commands themselves leave the queue's history)
        return list(machine.arm.live.contexts), repr(result.motion.cycles)

    reused = contexts()
    made = MovingArm.context

    def fresh(self, loops):
        forget(self)
        return made(self, loops)

    monkeypatch.setattr(MovingArm, "context", fresh)
    return reused, contexts()


def test_a_long_run_has_the_contexts_made_fresh_for_every_command(tmp_path, monkeypatch):
    # the Loops made again for every command
    (reused, reused_cycles), (again, fresh_cycles) = _contexts_reused_and_afresh(
        tmp_path, monkeypatch, lambda arm: arm._loops.clear())
    assert len(reused) > 150
    assert reused == again
    assert {p.loop.kind for c in reused for p in c} == {"while", "for", "do"}
    assert max(p.entry for c in reused for p in c if p.loop.kind == "for") > 20  # entered again at each pass
    assert reused_cycles == fresh_cycles


def test_the_last_context_is_given_again_only_for_the_same_loops_at_the_same_passes():
    arm = MovingArm(None)
    prog, site, counter = _program(), _site(), [1]
    first = arm.context(((prog, site, counter),))
    assert arm.context(((prog, site, counter),)) is first  # a new tuple of the same objects and passes
    counter[0] = 2  # the next pass
    second = arm.context(((prog, site, counter),))
    assert second[0].iteration == 2 and second[0].entry == 1
    again = arm.context(((prog, site, [2]),))  # a new entry of the loop (a new counter), at the same pass
    assert again[0].entry == 2 and again[0].iteration == 2
    other = arm.context(((prog, _site(line=8), [2]),))  # another loop
    assert other[0].loop.line == 8
    assert arm.context(((prog, site, counter),)) == second
    other_prog = arm.context(((_program(name="pick"), site, counter),))  # another program, the same site object
    assert other_prog[0].loop.program == "pick"
    inner = arm.context(((prog, site, counter), (prog, _site(line=9, kind="for"), [1])))  # one loop more
    assert len(inner) == 2 and arm.context(((prog, site, counter),)) == second
    assert arm.context(()) == ()


def test_a_long_run_has_the_contexts_computed_afresh_at_every_command(tmp_path, monkeypatch):
    def forget(arm):
        arm._last_context = None

    kept, afresh = _contexts_reused_and_afresh(tmp_path, monkeypatch, forget)
    assert afresh == kept and len(kept[0]) > 150
