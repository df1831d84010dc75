"""`Task.frames`: the frames of the VAL 3 programs a task is in, which each program pushes at its
start and pops at its end (compiler/program.py). `Machine.line_running` and `loop_passes` read
the running task's list instead of walking the Python stack: they must give, at every call of a
run, what the walk gives."""

from __future__ import annotations

from val3check.interpretation.machine import Machine
from val3check.robot import load_robot

from .simsupport import sim

CODE = """begin
  for l_i = 1 to 30
    l_n = l_i % 3
    while l_n < 3
      call step(l_n)
      l_n = l_n + 1
    endWhile
    open(flange)
    wait(l_i > 0)
  endFor
  call broken()
end"""
STEP = """begin
  do
    movej({0, 0, 90, 0, 90, 0}, flange, mD)
    if x_n == 1
      movej({10, 0, 90, 0, 90, 0}, flange, mD)
    endIf
    x_n = x_n + 1
  until x_n > 1
end"""
BROKEN = """begin
  movej({0, 0, 90, 0, 90, 0}, flange, mD)
  nX = 1 / 0
end"""


def _shown(result):
    """A loop_passes result with the pass counters by identity (they are lists)."""
    if type(result) is tuple and result and type(result[0]) is tuple:
        return [(c, site, id(counter)) for c, site, counter in result]
    return result


def test_the_running_tasks_frames_give_what_the_python_stack_gives(tmp_path, monkeypatch):
    seen = []
    machines = []

    def both(fn):
        def checked(self, *args):
            got = fn(self, *args)
            if args and args[0] is not None:  # (a suspended task: read from its generators, as before)
                return got
            running, self.clock.current = self.clock.current, None  # without a running task: the walk
            try:
                walked = fn(self, *args)
            finally:
                self.clock.current = running
            seen.append((fn.__name__, _shown(got), _shown(walked), running is not None))
            return got
        return checked

    monkeypatch.setattr(Machine, "line_running", both(Machine.line_running))
    monkeypatch.setattr(Machine, "loop_passes", both(Machine.loop_passes))
    run = Machine.run

    def kept(self):
        machines.append(self)
        return run(self)

    monkeypatch.setattr(Machine, "run", kept)
    res = sim(tmp_path, CODE, globals_=["mdesc mD", "num nX"], locals_=["num l_i", "num l_n"],
              programs={"step": {"params": ["num x_n"], "code": STEP}, "broken": {"code": BROKEN}},
              duration=300.0, robot=load_robot("tx2-60"))
    assert [d.message for d in res.diagnostics if d.code == "R001"] == [
        "error 10: invalid numeric computation (division by zero)"]  # (in broken(), after its movej)
    assert len(seen) > 150
    assert all(got == walked for _, got, walked, _ in seen)
    assert all(running for *_, running in seen)
    loops = [got for name, got, _, _ in seen if name == "loop_passes"]
    assert max(len(x) for x in loops) == 3  # for, while (start) and do (step): across two programs
    assert all(got is not None for name, got, _, _ in seen if name == "line_running")
    # every program popped its frame, however it ended (its end, an error, the task destroyed)
    (machine,) = machines
    assert machine.scheduler.history and all(t.frames == [] for t in machine.scheduler.history)
