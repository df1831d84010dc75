"""The timings a blend decision makes (planner.py, `blend_pays`), remembered: a cyclic program
decides the same blend from the same state every cycle (issue 29).

    memo = TrialMemo(kin, timing, limits_of)
    key = memo.key(spans, a, v0, *named, owners=(k1, k2))   # None: reuse is off
    hit = memo.get(key, spans, check)     # the remembered answer, or None
    memo.keep(key, spans, calls, used, answer)

A trial times a path of spans from position a at path speed v0. Its answer is a function of: each
span's geometry (the same object: construction.py and blending.py reuse them), the part of it
(a, b), whether it joins its neighbour smoothly, its tool, which spans belong to the same command
and that command's limits (mdesc and monitor speed), a, v0, the speeds the arm had where the
trial re-times from (`calls`: asked of the plan again and compared), and the time-optimal
parameterisations it read (timing.Timing solves each relative to its grid's start, so a first
answer and a remembered one are the same bits; an answer is used only while the remembered ones
it read are still remembered). The arm's geometry (setDH)
clears kin.reuse, and this memo with it. Results are shared, never copied: their arrays are
read-only.

A span's part of a key is one number kept on the span (`Span.kpart`); a geometry is named by its
id, which is safe because an entry holds the geometries of its key alive. Spans a trial adds may
be named instead by what makes them (planner._trials: the two commands' classes, queued.py), with
`owners` the keys of those commands, numbered with the owners of `spans`.
"""

from __future__ import annotations

import itertools

import numpy as np

REUSE = True  # off: every trial, command check and distance computed here and in construction.py, blending.py
SIZE = 512  # answers remembered
_numbers = itertools.count(1)  # spans' parts (`TrialMemo._part`), commands' classes: never given twice


def number() -> int:
    """A number never given before in this process (`_part`, queue.MotionQueue._class_of)."""
    return next(_numbers)


class TrialMemo:
    """See the module docstring."""

    def __init__(self, kin, timing, limits_of, value_keys: dict | None = None) -> None:
        """Answers kept in `kin.reuse` (forgotten with the arm's geometry). `value_keys`: where the
        values of a command's limits are kept by command key, cleared by its owner whenever
        `limits_of` may give another answer (mdesc.CommandLimits.value_keys); None: not kept."""
        self.kin = kin
        self.timing = timing
        self.limits_of = limits_of
        self.value_keys = value_keys
        self._limit_keys: dict[int, tuple] = {}
        self._tools: dict[int, tuple] = {}
        self._parts: dict[tuple, int] = {}  # `_part`

    def _store(self) -> dict:
        store = self.kin.reuse.get("trial-memo")
        if store is None:
            store = self.kin.reuse.keep("trial-memo", {})
        return store

    def key(self, spans, *rest, owners=()) -> tuple | None:
        """The key of a trial of `spans` with the other inputs `rest` (floats, and what names the
        spans the trial adds: planner._trials), None when reuse is off. `owners`: the keys of the
        commands `rest` names, numbered with those of `spans` (which are the same, which new)."""
        if not REUSE:
            return None
        canon: dict[int, int] = {}
        parts = []
        part_of = self._part
        for sp in spans:  # (loops, not generators: asked twice per motion command)
            part = sp.kpart
            if part is None:
                part = part_of(sp)
            own = sp.owners
            if len(own) == 1:
                k, st = own[0]
                c = canon.get(k)
                if c is None:
                    c = canon[k] = len(canon)
                parts.append((part, c, st))
            else:
                parts.append((part, *[(canon.setdefault(k, len(canon)), st) for k, st in own]))
        named = tuple([canon.setdefault(k, len(canon)) for k in owners])
        vk = self.value_keys
        if vk is not None:  # (by command key: one look-up per owner)
            limits = []
            for k in canon:
                hit = vk.get(k)
                if hit is None:
                    hit = vk[k] = self._limits_key(k)
                    if len(vk) > 4096:
                        vk.clear()
                limits.append(hit)
            return (tuple(parts), named, tuple(limits), *rest)
        limits_of, kept = self.limits_of, self._limit_keys
        limits = []
        for k in canon:  # (`_limits_key` inline: its kept values first)
            lim = limits_of(k)
            hit = kept.get(id(lim))
            limits.append(hit[1] if hit is not None and hit[0] is lim else self._limits_key(k))
        return (tuple(parts), named, tuple(limits), *rest)

    def _part(self, sp) -> int:
        """A span's geometry (by the object), part, smoothness and tool as one number, the same for
        the same values; kept on the span when its tool is read-only (a span never changes).
        Numbers are never given twice, and the geometry's id is safe in them: an entry that holds
        the number holds its geometries alive (`keep`), so no other object has that id meanwhile."""
        tool = sp.tool
        values = (id(sp.geom), sp.a, sp.b, sp.smooth, self._tool_key(tool))
        n = self._parts.get(values)
        if n is None:
            if len(self._parts) >= 4096:
                self._parts.clear()
            n = self._parts[values] = number()
        if tool is None or (getattr(tool, "flags", None) is not None and not tool.flags.writeable):
            sp.kpart = n
        return n

    def _tool_key(self, tool) -> bytes | None:
        """A tool's values; by the object when it is read-only (the run's tools are shared and never
        changed in place: simulation/retention.py)."""
        if tool is None:
            return None
        if getattr(tool, "flags", None) is None or tool.flags.writeable:
            return np.asarray(tool, dtype=float).tobytes()
        hit = self._tools.get(id(tool))
        if hit is None or hit[0] is not tool:
            hit = (tool, np.asarray(tool, dtype=float).tobytes())
            if len(self._tools) > 64:
                self._tools.clear()
            self._tools[id(tool)] = hit
        return hit[1]

    def _limits_key(self, owner: int) -> tuple:
        """The values of a command's limits (by the Limits object: one per mdesc and monitor speed)."""
        lim = self.limits_of(owner)
        hit = self._limit_keys.get(id(lim))
        if hit is None or hit[0] is not lim:
            hit = (lim, (lim.V.tobytes(), lim.A.tobytes(), lim.D.tobytes(), float(lim.tvel), float(lim.rvel)))
            if len(self._limit_keys) > 64:
                self._limit_keys.clear()
            self._limit_keys[id(lim)] = hit
        return hit[1]

    def get(self, key, spans, speed_at=None, shift=None):
        """The answer kept under `key` when it still holds: the same geometries, the same speeds
        asked of the plan (`speed_at(g, a)`, or `speed_at(g + shift, a + shift)` with `shift`:
        the path's positions of the spans' relative ones), the same remembered parameterisations."""
        if key is None:
            return None
        hit = self._store().get(key)
        if hit is None:
            return None
        # (the key names each geometry by its id: the entry holds them, so they are the spans')
        _, calls, used, answer = hit
        if shift is None:
            for g, a, v in calls:
                if speed_at(g, a) != v:
                    return None
        else:
            for g, a, v in calls:
                if speed_at(g + shift, a + shift) != v:
                    return None
        if used and not self.timing.holds(used):
            return None
        return answer

    def start(self) -> list:
        """Record what a computation reads (before it)."""
        used: list = []
        self.timing.used = used
        return used

    def stop(self) -> None:
        """Stop recording (after the computation, however it ended)."""
        self.timing.used = None

    def keep(self, key, spans, started, calls, answer) -> None:
        """Keep `answer` (after `start` and `stop`, whose record of what it read is `started`)."""
        if key is None:
            return
        used = started
        store = self._store()
        if len(store) >= SIZE:
            store.pop(next(iter(store)))
        store[key] = (tuple(sp.geom for sp in spans), tuple(calls), tuple(used), answer)


def frozen(a: np.ndarray) -> np.ndarray:
    """`a`, read-only (shared between the plans that reuse it)."""
    a.flags.writeable = False
    return a
