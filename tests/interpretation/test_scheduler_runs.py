"""`Scheduler.runs`: a number that changes whenever VAL 3 code may have run (a turn, a wait's
condition other than the machine's end-of-motion one, a task killed). The watch of the cell's
frames and tools (simulation/value_watch.py) skips its check between two cycles while it holds:
each way code runs must change it, and a skip must never keep a value a fresh read would change."""

from __future__ import annotations

from types import SimpleNamespace

from val3check.interpretation.clock import Clock
from val3check.interpretation.scheduler import WAIT, Scheduler, Task


def _scheduler():
    clock = Clock()
    machine = SimpleNamespace(clock=clock, recorder=SimpleNamespace(task_state=lambda *a, **k: None))
    s = Scheduler(machine, clock)
    machine.scheduler = s
    return s, machine


def _task(machine, s, gen=None, cond=None):
    t = Task(machine, "t", SimpleNamespace(model=SimpleNamespace(stack_size=0)), "p", 10)
    t.gen = gen
    if cond is not None:
        t.state, t.cond, t.waiting_for = WAIT, cond, "wait"
    return s.add(t)


def _body():
    while True:
        yield


def test_a_turn_an_impure_condition_and_a_kill_change_runs_a_pure_condition_does_not():
    s, machine = _scheduler()
    pure = lambda: False  # noqa: E731
    s.pure_cond = pure
    waiter = _task(machine, s, _body(), cond=pure)
    r = s.runs
    s.cycle()  # only the machine's end-of-motion condition evaluated: no VAL 3 code ran
    assert s.runs == r
    other = _task(machine, s, _body(), cond=lambda: False)  # a program's condition (may call setFrame)
    s.cycle()
    assert s.runs == r + 1
    other.cond, other.state = None, other.state.__class__.READY  # a turn
    r = s.runs
    s.clock.now += 4000
    s.cycle()
    assert s.runs > r
    r = s.runs
    s.kill(waiter)
    assert s.runs == r + 1


def test_the_watch_skips_only_while_runs_holds():
    """The same frame changed in place: read again after `runs` changed (a turn ran), kept when it did not;
    a call by a running line (cycle False) makes the next call between cycles read."""
    import numpy as np

    from val3check.collision import Cell, Obstacle, Shape
    from val3check.geometry.frames import Frame
    from val3check.geometry.trsf import Trsf
    from val3check.simulation.value_watch import ValueWatch, _read

    world = Frame(is_root=True, name="world")
    f = Frame(Trsf(1.0), world)
    sched = SimpleNamespace(runs=0)
    machine = SimpleNamespace(main=SimpleNamespace(globals={"fPart": SimpleNamespace(data=[f], off=0)}, aliases={}),
                              scheduler=sched)
    cell = Cell(path="test")
    cell.obstacles.append(Obstacle("box", Shape("box", (10.0, 10.0, 10.0)), "fPart", np.eye(4)))
    watch = ValueWatch(cell, machine)
    watch(4000, cycle=True)
    f.trsf.x = 2.0  # (no turn counted: the watch does not look)
    watch(8000, cycle=True)
    assert watch.frame("fPart", 1.0)[0, 3] == 1.0 and len(watch.values) == 1
    sched.runs += 1
    watch(12000, cycle=True)
    assert watch.frame("fPart", 1.0)[0, 3] == 2.0 and len(watch.values) == 2
    f.trsf.x = 3.0
    watch(16000, cycle=False)  # a motion command recorded: read
    assert watch.frame("fPart", 1.0)[0, 3] == 3.0
    f.trsf.x = 4.0  # a later line of the same turn
    watch(20000, cycle=True)  # runs unchanged, but the last call was a line's: read
    assert np.array_equal(watch.frame("fPart", 1.0), _read(machine, "fPart", Frame))


def test_the_bundled_pick_and_place_reads_at_every_call_what_a_fresh_read_gives(monkeypatch):
    """60 s of the bundled cell (the pallet's frame and the gripper's tool): after every call of
    the watch, the reading in force is what a fresh read of the program's values gives."""
    from pathlib import Path

    import numpy as np

    from val3check.geometry.frames import Frame, Tool
    from val3check.simulation import value_watch

    from .simsupport import run_folder

    calls = {"skipped": 0, "all": 0}
    real = value_watch.ValueWatch.__call__

    def checked(self, time_us, cycle=False):
        before = (self._runs, len(self.values))
        real(self, time_us, cycle)
        calls["all"] += 1
        if cycle and before[0] == self._runs and before[1] == len(self.values):
            calls["skipped"] += 1
        t = self.times[-1]
        for n in self.frames:
            a, b = self.frame(n, t), value_watch._read(self.machine, n, Frame)
            assert (a is None) == (b is None) and (a is None or np.array_equal(a, b)), (time_us, n)
        for n in self.tools:
            a, b = self.tool(n, t), value_watch._read(self.machine, n, Tool)
            assert (a is None) == (b is None) and (a is None or np.array_equal(a, b)), (time_us, n)

    monkeypatch.setattr(value_watch.ValueWatch, "__call__", checked)
    root = Path(__file__).resolve().parents[2]
    app = root / "fixtures" / "valid" / "PickPlace"
    scenario = (root / "fixtures" / "scenarios" / "pickplace.toml").read_text(encoding="utf-8")
    import tempfile

    from val3check.robot import load_robot

    r = run_folder(app, scenario=scenario, duration=60.0, robot=load_robot("TX2-60"), collisions=True,
                   cell=str(app / "val3check-cell.toml"), tmp_path=Path(tempfile.mkdtemp()))
    assert r.motion is not None
    assert calls["all"] > 300 and calls["skipped"] > 50  # the skip is taken, and every reading is right


def test_the_watch_s_fast_check_finds_each_missing_or_replaced_piece_of_a_library_s_frame():
    """`_unchanged` on "lib:fPart": the library, its variable, the element, the node replaced or
    gone in turn; after each, the reading in force is what a fresh read gives."""
    import numpy as np

    from val3check.collision import Cell, Obstacle, Shape
    from val3check.geometry.frames import Frame
    from val3check.geometry.trsf import Trsf
    from val3check.simulation.value_watch import ValueWatch, _read

    world = Frame(is_root=True, name="world")
    f = Frame(Trsf(1.0), world)
    cont = SimpleNamespace(data=[Frame(Trsf(9.0), world), f], off=1)
    lib = SimpleNamespace(globals={"fPart": cont}, aliases={})
    main = SimpleNamespace(globals={}, aliases={"lib": lib})
    machine = SimpleNamespace(main=main)  # (no scheduler: every call checks)
    cell = Cell(path="test")
    cell.obstacles.append(Obstacle("box", Shape("box", (10.0, 10.0, 10.0)), "lib:fPart", np.eye(4)))
    watch = ValueWatch(cell, machine)
    other = SimpleNamespace(globals={"fPart": SimpleNamespace(data=[Frame(Trsf(5.0), world)], off=0)}, aliases={})
    changes = [lambda: setattr(cont, "off", 0), lambda: setattr(cont, "off", 1),
               lambda: cont.data.__setitem__(1, Frame(Trsf(2.0), world)), lambda: cont.data.pop(),
               lambda: cont.data.append(f), lambda: lib.globals.pop("fPart"),
               lambda: lib.globals.__setitem__("fPart", cont), lambda: main.aliases.pop("lib"),
               lambda: main.aliases.__setitem__("lib", other), lambda: main.aliases.__setitem__("lib", lib),
               lambda: setattr(machine, "main", None), lambda: setattr(machine, "main", main),
               lambda: setattr(cont, "data", None), lambda: setattr(cont, "data", [f, f])]
    watch(0)
    for k, change in enumerate(changes):
        change()
        watch(4000 * (k + 1))
        a, b = watch.frame("lib:fPart", 1.0), _read(machine, "lib:fPart", Frame)
        assert (a is None) == (b is None) and (a is None or np.array_equal(a, b)), k
