"""The seams the next features plug into: the instruction registry (every catalogue
instruction is either simulated or stops with the one not-simulated diagnostic), subsystems
the scheduler asks for their next event (no polling), and the arm port that open()/close()
wait on."""

from __future__ import annotations

import dis
from pathlib import Path

import pytest

from val3check.config import Settings
from val3check.interpretation.compiler.calls import INLINE_FORMS
from val3check.language.instructions import load_instructions
from val3check.lint import run
from val3check.simulation.model_arm import MotionlessArm
from val3check.simulation.collect import collect
from val3check.interpretation.registry import Registry
from val3check.simulation.run import SimOptions, build_machine, build_registry

from .simsupport import build, gv

# Every catalogue instruction the simulator does not simulate, with the diagnostic it stops on
# and why. An instruction that gets a handler leaves this table.
NOT_SIMULATED: dict[str, tuple[str, str]] = {
}


@pytest.mark.parametrize("ins", sorted(load_instructions().values(), key=lambda i: i.name), ids=lambda i: i.name)
def test_every_catalogue_instruction_is_simulated_or_stops_with_its_rule(ins):
    status = build_registry().status(ins.name)
    if ins.name in NOT_SIMULATED:
        assert not status.implemented and status.how == NOT_SIMULATED[ins.name][0]
    else:
        assert status.implemented, f"{ins.name} ({ins.section}) is neither simulated nor listed as not simulated"


def test_the_table_names_catalogue_instructions_only():
    assert set(NOT_SIMULATED) <= {i.name for i in load_instructions().values()}


def test_inline_forms_are_the_compilers():
    """What a chapter registers as inline, the compiler writes (calls.py), or compiles as a
    statement (taskCreate) or a library call (alias:libLoad)."""
    inline = build_registry().inline_names()
    assert {n for n in inline if n not in INLINE_FORMS} == {"taskcreate", "taskcreatesync", "libload", "libexist"}
    assert set(INLINE_FORMS) <= inline


def _interpreter_registry():
    """The registry of the interpreter's chapters only (no motion handlers)."""
    from val3check.simulation.run import INTERPRETER_MODULES

    registry = Registry()
    for module in INTERPRETER_MODULES:
        module.register(registry)
    return registry


def test_a_new_handler_is_used_not_ignored(tmp_path):
    """A chapter-10 handler registered in the registry is what the compiled code calls (the
    compiler decides from the registry, no hard-coded motion stub before it)."""
    calls = []

    def I_waitendmove(task, unit):
        calls.append(task.machine.clock.time_of(task))
        yield from ()

    registry = _interpreter_registry()
    registry.instruction("waitEndMove", I_waitendmove, blocking=True)
    folder = build(tmp_path, "begin\n  delay(1)\n  waitEndMove()\n  nDone = 1\nend\n", globals_=["num nDone"])
    r = _run(folder, registry=registry)
    assert len(calls) == 1 and calls[0] >= 1_000_000
    assert gv(r, "nDone") == 1.0 and not r.diagnostics


def test_without_handler_a_motion_instruction_stops_with_r002(tmp_path):
    folder = build(tmp_path, "begin\n  waitEndMove()\nend\n")
    r = _run(folder, registry=_interpreter_registry())
    assert [d.code for d in r.diagnostics] == ["R002"]


def _run(folder: Path, *, registry=None, arm=None, duration: float = 10.0):
    lr = run([str(folder)], Settings())
    ws = lr.workspace
    app = ws.apps[ws.targets[0]]
    machine = build_machine(ws, app, SimOptions(duration=duration), registry=registry, arm=arm)
    machine.load_main()
    machine.run()
    return collect(machine)


def test_generated_code_calls_only_names_the_registry_provides(tmp_path):
    """Every global name the generated code loads is in the unit's namespace: the helpers are
    registered explicitly, not listed by hand elsewhere."""
    import builtins

    fixtures = Path(__file__).resolve().parents[2] / "fixtures" / "valid"
    checked = 0
    for pjx in sorted(fixtures.rglob("*.pjx")):
        lr = run([str(pjx)], Settings())
        if not lr.workspace.targets:
            continue
        app = lr.workspace.apps[lr.workspace.targets[0]]
        machine = build_machine(lr.workspace, app, SimOptions())
        unit = machine.load_main()
        for compiled in unit.programs.values():
            code = compile(compiled.source, compiled.filename, "exec")
            for name in _global_loads(code):
                assert name in unit.ns or hasattr(builtins, name) or name.startswith("P_"), (pjx.name, name)
            checked += 1
    assert checked > 20


def _global_loads(code):
    for ins in dis.get_instructions(code):
        if ins.opname in ("LOAD_GLOBAL", "LOAD_NAME"):
            yield ins.argval
    for const in code.co_consts:
        if hasattr(const, "co_code"):
            yield from _global_loads(const)


# ---- subsystems ------------------------------------------------------------------------------------


class InputAt:
    """A toy subsystem: an input becomes true at a given time."""

    def __init__(self, machine, name: str, at_us: int) -> None:
        self.machine, self.name, self.at_us = machine, name, at_us
        self.advanced = 0

    def next_time(self, now_us: int) -> int | None:
        return self.at_us if now_us < self.at_us else None

    def advance(self, to_us: int) -> None:
        self.advanced += 1
        if to_us >= self.at_us:
            self.machine.main.globals[self.name].data[0].value = True


def test_the_clock_jumps_to_a_subsystems_next_event(tmp_path):
    folder = build(tmp_path, "begin\n  wait(diReady == true)\n  nAt = clock()\nend\n",
                   globals_=["dio diReady", "num nAt"], links={"diReady": "Cell\\ready"})
    lr = run([str(folder)], Settings())
    app = lr.workspace.apps[lr.workspace.targets[0]]
    machine = build_machine(lr.workspace, app, SimOptions())
    machine.load_main()
    sub = InputAt(machine, "diReady", 1_502_000)
    machine.add_subsystem(sub)
    machine.run()
    r = collect(machine)
    assert gv(r, "nAt") == 1.504  # the first tick at or after the event
    assert sub.advanced < 10  # no cycle-by-cycle polling: 376 cycles would be


class ArmInMotion(MotionlessArm):
    """An arm port whose motion queue empties at `done_us` (None: never)."""

    def __init__(self, done_us: int | None) -> None:
        super().__init__(None)
        self.done_us = done_us
        self.asked = 0

    def motion_done(self, time_us: int) -> bool:
        self.asked += 1
        return self.done_us is not None and time_us >= self.done_us

    def next_time(self, now_us: int) -> int | None:
        return self.done_us if self.done_us is not None and now_us < self.done_us else None


def test_open_waits_for_the_end_of_motion(tmp_path):
    """9.5.4: open() first waits for the end of the motion (waitEndMove), through the arm port;
    the clock jumps to the end of the motion."""
    folder = build(tmp_path, "begin\n  open(tGrip)\n  nAt = clock()\nend\n", globals_=["tool tGrip", "num nAt"])
    arm = ArmInMotion(2_000_000)
    r = _run(folder, arm=arm)
    assert gv(r, "nAt") == 2.0
    assert arm.asked < 10
    assert [(round(e.time_us / 1e6, 3), e.value) for e in r.io_log if e.link == "valve1"] == [(2.0, True)]


def test_a_motion_that_never_ends_is_a_deadlock_of_open(tmp_path):
    folder = build(tmp_path, "begin\n  close(tGrip)\nend\n", globals_=["tool tGrip"])
    r = _run(folder, arm=ArmInMotion(None))
    assert r.end_reason == "deadlock"
    (d,) = [d for d in r.diagnostics if d.code == "R003"]
    assert "waits in close (end of motion)" in d.message and d.line > 0
