"""The watch of the program's frames and tools called every cycle (collision_run.ValueWatch):
its fast path (nothing of what it read changed) never keeps a value that a full read would
change."""

from __future__ import annotations

import numpy as np

from val3check.collision import Cell, Obstacle, Shape, ToolSolid
from val3check.geometry.frames import Frame, Tool
from val3check.geometry.trsf import Trsf
from val3check.simulation.collision_run import ValueWatch, _read


def _setup():
    from types import SimpleNamespace

    world = Frame(is_root=True, name="world")
    base = Frame(Trsf(100.0, 0.0, 0.0, 0.0, 0.0, 0.0), world)
    f = Frame(Trsf(0.0, 50.0, 0.0, 0.0, 0.0, 90.0), base)
    flange = Tool(is_root=True, name="flange")
    t = Tool(Trsf(0.0, 0.0, 120.0), flange)
    fglob = SimpleNamespace(data=[f], off=0)
    tglob = SimpleNamespace(data=[t], off=0)
    machine = SimpleNamespace(main=SimpleNamespace(globals={"fPart": fglob, "tGrip": tglob}, aliases={}))
    cell = Cell(path="test")
    cell.obstacles.append(Obstacle("box", Shape("box", (10.0, 10.0, 10.0)), "fPart", np.eye(4)))
    cell.tools.append(ToolSolid("jaw", "tGrip", Shape("box", (5.0, 5.0, 5.0)), np.eye(4)))
    return machine, (world, base, f, fglob), (flange, t, tglob), ValueWatch(cell, machine)


def _changes(frame_parts, tool_parts):
    world, base, f, fglob = frame_parts
    flange, t, tglob = tool_parts
    return [
        lambda: setattr(f.trsf, "x", 1.0), lambda: setattr(f.trsf, "z", -0.0),  # equal as a number, not as bits
        lambda: setattr(base.trsf, "rz", 10.0), lambda: setattr(f, "trsf", Trsf(7.0)),
        lambda: setattr(f, "ref", world), lambda: fglob.data.__setitem__(0, Frame(Trsf(5.0), world)),
        lambda: setattr(fglob.data[0], "ref", None), lambda: setattr(fglob.data[0], "ref", world),
        lambda: setattr(t.trsf, "z", 130.0), lambda: tglob.data.__setitem__(0, Tool(Trsf(1.0), flange)),
        lambda: setattr(flange.trsf, "x", 1.0),  # a modified flange: no position
        lambda: setattr(flange.trsf, "x", 0.0), lambda: tglob.data.__setitem__(0, 3),  # not a tool
        lambda: tglob.data.__setitem__(0, Tool(Trsf(2.0), flange)), lambda: setattr(world.trsf, "x", 1.0),
    ]


def _fresh(machine):
    return {"f:fPart": _read(machine, "fPart", Frame), "t:tGrip": _read(machine, "tGrip", Tool)}


def _same(a, b) -> bool:
    return all((a[k] is None) == (b[k] is None) and (a[k] is None or np.array_equal(a[k], b[k])) for k in a)


def test_each_change_of_what_a_frame_or_tool_is_computed_from_gives_a_new_reading():
    machine, frame_parts, tool_parts, watch = _setup()
    watch(0)
    for k, change in enumerate(_changes(frame_parts, tool_parts)):
        watch(8000 * k + 4000)  # nothing changed: the same reading
        n, before = len(watch.values), _fresh(machine)
        change()
        watch(8000 * k + 8000)
        fresh = _fresh(machine)
        assert _same(watch.values[-1], fresh), k  # the reading in force is what a fresh read gives
        if not _same(before, fresh):  # (-0.0 for 0.0 gives equal matrices: the same reading)
            assert len(watch.values) == n + 1, k
            assert watch.reading(8000 * k / 1e6 + 0.008) != watch.reading(8000 * k / 1e6 + 0.004), k


def test_a_long_watched_run_reads_what_fresh_reads_give_at_every_call():
    """Many calls, values changed at random moments (in place, by new objects, back to an old
    value): after every call the reading in force is what a fresh read gives."""
    rng = np.random.default_rng(7)
    machine, (_world, base, f, fglob), (flange, t, tglob), watch = _setup()
    for k in range(2000):
        r = rng.random()
        if r < 0.05:
            f.trsf.x = float(rng.integers(0, 3))
        elif r < 0.08:
            fglob.data[0] = Frame(Trsf(float(rng.integers(0, 3))), base)
        elif r < 0.10:
            t.trsf = Trsf(0.0, 0.0, float(rng.integers(100, 102)))
        elif r < 0.12:
            tglob.data[0] = t if rng.random() < 0.5 else Tool(Trsf(0.0, 0.0, 120.0), flange)
        watch(4000 * k, cycle=bool(k % 2))
        now = watch.times[-1]
        fresh = _fresh(machine)
        assert _same({"f:fPart": watch.frame("fPart", now), "t:tGrip": watch.tool("tGrip", now)}, fresh), k
    assert 20 < len(watch.values) < 400  # most calls found nothing new
