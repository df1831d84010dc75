"""What a run keeps for each motion command, kept small (issue 29, docs/performance.md "Memory of
long runs").

A cyclic cell records the same few commands again and again: the same mdesc, tool, source line
and loop pass for several commands in a row. `Shared` hands out one object per value, so that a
command keeps a reference, not a copy (every command of the run is kept until its record is
taken, collect.py). Values are compared exactly (by repr or bytes: -0.0 stays -0.0). Each table
holds at most SHARED_VALUES values: a program that makes a new value for every command gets
copies beyond that, as before, and the tables never grow with the run.

`release(machine)` drops what the finished run kept per command (the queue's history, the loops
of each command) once its record is taken: the reports then run without it.

    shared = Shared()
    tool = shared.tool(array)       # read-only, one per value
    mdesc = shared.mdesc(mdesc)
"""

from __future__ import annotations

from typing import Any

import numpy as np

SHARED_VALUES = 1024  # distinct values per table (tools, mdescs, sources, loop passes)


class Shared:
    """Interning tables (module docstring); `counts()`: how many values each holds."""

    def __init__(self) -> None:
        """Empty tables."""
        self._tools: dict[bytes, np.ndarray] = {}
        self._mdescs: dict[str, Any] = {}
        self._sources: dict[Any, Any] = {}
        self._contexts: dict[tuple, tuple] = {}

    def tool(self, tool: np.ndarray) -> np.ndarray:
        """One read-only array per value (4x4 TCP in the flange, mm)."""
        key = tool.tobytes()
        hit = self._tools.get(key)
        if hit is not None:
            return hit
        tool.flags.writeable = False  # shared by many commands: never changed in place
        return _keep(self._tools, key, tool)

    def mdesc(self, mdesc: Any) -> Any:
        """One motion.mdesc.MDesc per value."""
        key = repr(mdesc)
        hit = self._mdescs.get(key)
        return hit if hit is not None else _keep(self._mdescs, key, mdesc)

    def source(self, source: Any) -> Any:
        """One motion.findings.Source per value (path, line, col, program, task)."""
        hit = self._sources.get(source)
        return hit if hit is not None else _keep(self._sources, source, source)

    def context(self, context: tuple) -> tuple:
        """One motion.cycle context (tuple of Pass) per value: the commands of one loop pass share
        it. The table is emptied when full (a pass number grows with the run)."""
        hit = self._contexts.get(context)
        if hit is not None:
            return hit
        if len(self._contexts) >= SHARED_VALUES:
            self._contexts.clear()
        self._contexts[context] = context
        return context

    def counts(self) -> dict[str, int]:
        """Values held by each table."""
        return {"tools": len(self._tools), "mdescs": len(self._mdescs), "sources": len(self._sources),
                "contexts": len(self._contexts)}


def _keep(table: dict, key: Any, value: Any) -> Any:
    """`value`, remembered under `key` while the table has room."""
    if len(table) < SHARED_VALUES:
        table[key] = value
    return value


def release(machine: Any) -> None:
    """Drop what the finished run of `machine` kept per command once collect.py took its record:
    the motion queue's history (every QueuedCommand), the loops of each command, the interning
    tables. The arm's trajectory stays (the record's `trajectory` is it), and the history too when
    a layer of chapter 11 moved the arm (the record's trajectory then reads it)."""
    arm = getattr(machine, "arm", None)
    q = getattr(arm, "queue_in_use", None)
    layers = getattr(arm, "layers", None)
    # chapter 11's layers read the history while the reports sample the arm (arm_layers.Residuals)
    if q is not None and (layers is None or layers.trivial):
        q.release_history()
    if hasattr(arm, "contexts"):
        arm.contexts = {}
        arm.shared = Shared()
