"""The program's frames and tools as the collision checks see them (docs/cell.md): the values the
cell's frames and tools take over a run, read as it goes (simulation/collision_run.py checks the
motions with them).

Frames and tools: the interpreter keeps only the current value of a variable. The watch reads the
frames and tools the cell names each time a motion instruction records a command (ch10_motion)
and each time the scheduler advances the arm (a command ends and the next one starts:
moving_arm.py), and keeps the values that changed, with their time; a motion is checked with the
last values read at or before its start.
"""

from __future__ import annotations

import bisect
import functools
import operator
import re
import struct
from typing import Any

import numpy as np

from ..collision.cell import Cell
from ..collision.poses import same_poses
from ..geometry import frames as geo_frames
from ..interpretation.clock import TICK_US

US = 1_000_000
_NAME = re.compile(r"^(?:([A-Za-z_][A-Za-z0-9_]*):)?([A-Za-z_][A-Za-z0-9_]*)(?:\[\s*(\d+)\s*\])?$")


class ValueWatch:
    """Reads the frames and tools a cell names (world poses of frames, tools in the flange, 4x4 in
    the application's unit) in `machine` (interpretation.machine.Machine) when called with the
    simulated time; `frame(name, t)` and `tool(name, t)` give the values of the last reading at or
    before t. Registered with `MovingArm.watch`."""

    def __init__(self, cell: Cell | None, machine: Any = None) -> None:
        self.machine = machine
        self.frames = sorted({o.frame for o in cell.obstacles if o.frame != "world"}) if cell else []
        self.tools = sorted({t.tool for t in (*cell.tools, *cell.parts) if t.tool != "flange"}) if cell else []
        self.times: list[float] = []
        self.values: list[dict[str, np.ndarray | None]] = []
        self.serials: list[int] = []  # per reading, a number never given to another (`reading`)
        self._cache: dict[str, tuple] = {}  # name -> (fingerprint, matrix, objects read) of its last read
        self._reads = [*(("f:" + n, n, geo_frames.Frame) for n in self.frames),
                       *(("t:" + n, n, geo_frames.Tool) for n in self.tools)]
        self._held: list[tuple] | None = None  # per read, the objects the last call's value came from (`_unchanged`)
        self._where = [_parse(name) for _, name, _kind in self._reads]  # per read, where `_node` finds it
        # the scheduler's count of VAL 3 code that may have run (Scheduler.runs) at the last call
        # between cycles (None: the last call was not): while it holds, no value can have changed
        self._scheduler = getattr(machine, "scheduler", None)
        self._runs: int | None = None

    def __call__(self, time_us: int, cycle: bool = False) -> None:
        """Read at `time_us`; `cycle`: at the start of a scheduler cycle, before any line of it ran:
        the values hold since the lines of the cycle before (no line runs between two cycles)."""
        machine = self.machine
        if machine is None or not self._reads:
            return
        sched = self._scheduler
        if cycle and sched is not None:
            runs = sched.runs
            if runs == self._runs:
                return  # no VAL 3 code ran since the last call, between two cycles: the same values
            self._runs = runs
        else:
            self._runs = None  # (called by a running line: lines may follow in the same turn)
        held = self._held
        if held is not None and _unchanged(machine.main, self._where, held):
            return  # the very objects the last reading came from: the same values (most cycles)
        now, used = {}, []
        for key, name, kind in self._reads:
            now[key], objects = _read_node(_node(machine, name, kind), name, self._cache)
            used.append(objects)
        self._held = None if None in used else [_by_node(objects) for objects in used]
        if self.values and same_poses(now, self.values[-1]):
            return
        if cycle:
            last = int(round(self.times[-1] * US)) if self.times else 0
            time_us = max(time_us - TICK_US + 1, last + 1)
        t = time_us / US
        serial = len(self.serials) and self.serials[-1] + 1
        if self.times and self.times[-1] == t:
            self.values[-1], self.serials[-1] = now, serial
        else:
            self.times.append(t)
            self.values.append(now)
            self.serials.append(serial)

    def reading(self, t: float) -> int:
        """The reading `frame(name, t)` and `tool(name, t)` answer from, as a number that changes
        whenever what they answer may change (-1: none yet): the checker reads the cell's frames
        and tools again only then (collision.world.World.refresh)."""
        k = self._index(t)
        return -1 if k < 0 else self.serials[k]

    def _index(self, t: float) -> int:
        k = bisect.bisect_right(self.times, t + 1e-9) - 1
        return k if k >= 0 else (0 if self.values else -1)

    def _at(self, key: str, t: float):
        k = self._index(t)
        return None if k < 0 else self.values[k].get(key)

    def frame(self, name: str, t: float):
        return self._at("f:" + name, t)

    def tool(self, name: str, t: float):
        return self._at("t:" + name, t)


def _read(machine: Any, name: str, kind: type, cache: dict | None = None) -> np.ndarray | None:
    """The pose of the global frame/tool `name` ("fPallet", "fPallet[2]", "lib:fBase") in its
    root (world, flange) as a 4x4 matrix, or None when the program has no such value. `cache`:
    {name: its last read}; the same matrix object again when the chain of frames it was computed
    from is the same objects (`_objects`), or the same nodes with the same coordinates, bit for
    bit (`_chain`)."""
    return _read_node(_node(machine, name, kind), name, cache)[0]


def _node(machine: Any, name: str, kind: type) -> Any:
    """The global frame/tool `name` of `machine` (a `kind`), or None when the program has none."""
    parsed = _parse(name)
    unit = machine.main
    if parsed is None or unit is None:
        return None
    alias, var, index = parsed
    if alias is not None:
        unit = unit.aliases.get(alias)
        if unit is None or not hasattr(unit, "globals"):
            return None
    c = unit.globals.get(var)
    data = getattr(c, "data", None)
    if data is None or not 0 <= index < len(data) - c.off:
        return None
    node = data[c.off + index]
    return node if isinstance(node, kind) else None


def _read_node(node: Any, name: str, cache: dict | None) -> tuple[np.ndarray | None, tuple | None]:
    """(`_read`'s pose of `node`, the objects `_objects` found it from and `cache` now holds for
    `name`, or None when there are none)."""
    if node is None:
        return None, None
    chain = None
    objects = ()
    if cache is not None:
        objects = _objects(node)
        last = cache.get(name)
        if objects and last is not None and len(last[2]) == len(objects) and all(map(operator.is_, objects, last[2])):
            return last[1], last[2]  # the very objects root_pose reads: the same result
        chain = _chain(objects)
        if chain is not None and last is not None and last[0] == chain:
            cache[name] = (last[0], last[1], objects)  # the same nodes (their ids), held by objects
            return last[1], objects
    try:
        r, p, _ = geo_frames.root_pose(node)
    except Exception:  # undefined reference, modified root (160/161/163/164): no position
        out = None
    else:
        out = np.eye(4)
        out[:3, :3] = np.array(r, dtype=float).reshape(3, 3)
        out[:3, 3] = p
    if chain is None:
        return out, None
    cache[name] = (chain, out, objects)  # type: ignore[index]
    return out, objects


def _unchanged(unit: Any, where: list, held: list[tuple]) -> bool:
    """Whether every read (`where`: per read, `_parse`'s name) finds in the program `unit` (the
    machine's main) the very objects of `held` (its last call's, `_by_node`): then `_read` gives
    the same matrices again. `_node`'s look-up and `_objects`' walk, compared as they go (the
    same objects end them alike; the node found is the very one `_node` found of its kind),
    each node's nine objects in one C call."""
    try:
        for (alias, var, index), last in zip(where, held):
            u = unit if alias is None else unit.aliases.get(alias)
            c = u.globals.get(var)
            n = c.data[c.off + index]  # (what `_node` finds, if it is the node held)
            for node, ref, root, t, (x, y, z, rx, ry, rz) in last:  # (geo_frames.same_chain, inlined)
                if n is not node or n.ref is not ref or n.is_root is not root:
                    return False
                t2 = n.trsf
                if (t2 is not t or t2.x is not x or t2.y is not y or t2.z is not z or t2.rx is not rx
                        or t2.ry is not ry or t2.rz is not rz):
                    return False
                n = ref
    except (AttributeError, LookupError, TypeError):  # (no unit, library, variable or element)
        return False
    return True


def _by_node(objects: tuple) -> tuple:
    """`_objects`' walk as `_unchanged` compares it (geo_frames.held_chain's form): per node, (the
    node, its reference, root flag, trsf, its six floats)."""
    return tuple((objects[k], objects[k + 1], objects[k + 2], objects[k + 3], objects[k + 4:k + 10])
                 for k in range(0, len(objects), 10))



@functools.lru_cache(maxsize=1024)
def _parse(name: str) -> tuple[str | None, str, int] | None:
    """("lib", "fBase", 2) of "lib:fBase[2]"; None when it is not a name."""
    m = _NAME.match(name)
    return None if m is None else (m.group(1), m.group(2), int(m.group(3) or 0))


def _objects(node: Any) -> tuple:
    """The objects `geometry.frames.root_pose(node)` reads (each node, its reference and root
    flag, its trsf and the six floats), held: when a later read finds the very same objects, the
    values are the same bits (floats are immutable) and so is the pose."""
    out: list = []
    n = node
    try:
        while n is not None and len(out) <= 10 * (geo_frames.MAX_DEPTH + 1):
            t = n.trsf
            out += (n, n.ref, n.is_root, t, t.x, t.y, t.z, t.rx, t.ry, t.rz)
            if n.is_root:
                break
            n = n.ref
    except AttributeError:
        return ()
    return tuple(out)


_PACK = struct.Struct("6d")


def _chain(objects: tuple) -> tuple | None:
    """What `geometry.frames.root_pose` reads, by value, from `_objects`' walk (one walk gives
    both): each node up to the root (or to a missing reference, or past a loop) by identity, with
    its root flag, its reference and its coordinates' bits (the nodes are held by `objects`, so
    that no other object takes their ids). None when there is no walk or a coordinate is not a
    number."""
    if not objects:
        return None
    try:
        return tuple((id(objects[k]), objects[k + 2], id(objects[k + 1]), _PACK.pack(*objects[k + 4:k + 10]))
                     for k in range(0, len(objects), 10))
    except (TypeError, struct.error):
        return None
