"""The cycle of a task: the loop that moves the arm once per part, and how long each pass takes.

A cell program moves the arm in a loop, once per part (`while true` ... `endWhile` around a pick
and a place); inside it, loops that repeat motions within one part (a `for` over the rows of a
pallet, the passes of a milling pocket) are not the cycle. So the cycle is the **outermost loop
whose passes record motions**: each motion command carries the loops it was recorded in
(`Pass`: the loop statement, which entry of it, which pass), outermost first, across the programs
of the task's call stack (a loop in start() around a call of pick() holds pick's motions).

* Among the outermost loops that hold motions, those that **repeat** them count: motions recorded
  in two passes or more, or the task still inside the loop when the run ended (the run ended
  during its first pass: no complete cycle yet, but that is the loop). Of those, the one with
  the most passes is the cycle (a warm-up `for` of 3 passes before `while true` loses to it);
  ties go to the later.
* If none repeats (its motions in one pass, and the task left it), the same choice is made one
  level in: the loops inside it.
* None when the task records no motion in a loop that repeats: no cycle, and `why` says so.

A pass starts when the arm starts the first command recorded in it; the cycle time is the time
between the starts of successive passes. A pass whose first command never started (the run
ended first) starts no cycle: `--cycles N` counts N complete cycles when the arm has started
pass N + 1.
"""

from __future__ import annotations

from ..light_dataclass import dataclass, field


@dataclass(frozen=True)
class Loop:
    """A loop statement (2.2.5): where it is written, the program it is in, `kind` while, do or for."""

    path: str
    line: int
    col: int
    program: str
    kind: str

    def label(self) -> str:
        """The loop in a message: "the while loop at line 12 of start()"."""
        return f"the {self.kind} loop at line {self.line} of {self.program}()"


@dataclass(frozen=True)
class Pass:
    """One pass of a loop: which entry of the loop statement (1, 2... over the run: a loop inside
    another is entered again at each pass of it) and which pass of that entry (1, 2...)."""

    loop: Loop
    entry: int
    iteration: int


Context = tuple  # tuple[Pass, ...]: the loops a command was recorded in, outermost first


@dataclass
class _Group:
    """The motions recorded in one entry of one loop: its passes, in order, with the index of the
    first command of each, and the loops entered in it."""

    loop: Loop
    entry: int
    key: tuple
    firsts: dict = field(default_factory=dict)  # pass -> index of its first command
    last: int = -1  # index of the last command recorded in it
    inner: list = field(default_factory=list)  # the _Group of each loop entered in it, in order


class LoopTracker:
    """The loops of one task's motions, fed command by command (`note`); `choose` applies the rule
    of the module docstring. Used after the run (`cycle_stats`) and while it goes (`CycleCounter`)."""

    def __init__(self) -> None:
        """No command noted yet."""
        self._groups: dict[tuple, _Group] = {}
        self._outermost: list[_Group] = []

    def note(self, context: Context, index: int) -> None:
        """The command `index` (in recording order) recorded in the loops `context`."""
        key: tuple = ()
        parent = None
        for p in context:
            key = key + ((p.loop, p.entry),)
            g = self._groups.get(key)
            if g is None:
                g = self._groups[key] = _Group(p.loop, p.entry, key)
                (self._outermost if parent is None else parent.inner).append(g)
            g.firsts.setdefault(p.iteration, index)
            g.last = index
            parent = g

    def choose(self, inside: Context = ()) -> tuple[_Group | None, str]:
        """The cycle's loop and why (`inside`: the loops the task is in now, or was in when the
        run ended)."""
        inside_keys = set()
        key: tuple = ()
        for p in inside:
            key = key + ((p.loop, p.entry),)
            inside_keys.add(key)
        level, left = self._outermost, None
        while level:
            repeating = [g for g in level if len(g.firsts) >= 2 or g.key in inside_keys]
            if repeating:
                best = max(repeating, key=lambda g: (len(g.firsts), g.last))
                return best, _why(best, repeating, left, best.key in inside_keys)
            left = level[-1]
            level = [g for outer in level for g in outer.inner]
        if left is None:
            return None, "the task records its motions outside any loop: no cycle"
        return None, f"{left.loop.label()} records motions in one pass only, and no loop in it repeats them: no cycle"


def _why(best: _Group, repeating: list[_Group], left: _Group | None, inside: bool) -> str:
    """Why `best` is the cycle, in words."""
    what = f"{best.loop.label()} is the outermost loop of the task that repeats motions"
    if left is not None:
        what += f" ({left.loop.label()}, around it, records motions in one pass only)"
    if len(repeating) > 1:
        what += f"; of the {len(repeating)} loops at that level that repeat them, it has the most passes"
    n = len(best.firsts)
    if n < 2 and inside:
        return what + ": the run ended during its first pass (no complete cycle: run longer)"
    return what + f": {n} passes record motions"


@dataclass
class CycleStats:
    """The cycle of one task (module docstring): its loop (None: no cycle) and why, when the arm
    started each pass (the starts of passes it never started are left out)."""

    task: str
    loop: Loop | None
    why: str
    starts: list[float] = field(default_factory=list)
    passes: int = 0  # passes that recorded motions (started or not)

    @property
    def marker(self) -> tuple[str, int, int] | None:
        """(path, line, col) of the loop statement, None without a cycle."""
        return None if self.loop is None else (self.loop.path, self.loop.line, self.loop.col)

    @property
    def times(self) -> list[float]:
        """The cycle times: between successive starts."""
        return [b - a for a, b in zip(self.starts, self.starts[1:])]

    @property
    def count(self) -> int:
        """Complete cycles."""
        return max(len(self.starts) - 1, 0)


def cycle_stats(records, contexts, inside: dict | None = None) -> dict[str, CycleStats]:
    """Per task that recorded motion commands, its cycle. `records`: the motion records in
    recording order (records.MotionRecord: source.task, id, start); `contexts`: the loops each
    was recorded in (Context, same order); `inside`: per task, the loops it was in when the run
    ended (absent: none)."""
    inside = inside or {}
    trackers: dict[str, LoopTracker] = {}
    for index, (r, context) in enumerate(zip(records, contexts)):
        if r.id is None:  # connection moves belong to no instruction
            continue
        trackers.setdefault(r.source.task, LoopTracker()).note(context or (), index)
    out: dict[str, CycleStats] = {}
    for task, tracker in trackers.items():
        group, why = tracker.choose(inside.get(task, ()))
        st = CycleStats(task, None if group is None else group.loop, why)
        if group is not None:
            st.passes = len(group.firsts)
            for first in sorted(group.firsts.values()):
                start = records[first].start
                if start is None:
                    break  # the arm never got there: neither to the passes after it
                st.starts.append(start)
        out[task] = st
    return out


class CycleCounter:
    """Live count for `--cycles N`: `note(task, context)` for each command as the program records
    it (the task is inside `context` at that moment); `completed(task)` counts the complete cycles
    recorded so far by the rule of the module docstring (the passes of the cycle's loop minus one)."""

    def __init__(self) -> None:
        """No command noted yet."""
        self._trackers: dict[str, LoopTracker] = {}
        self._now: dict[str, Context] = {}
        self._index = 0

    def note(self, task: str, context: Context) -> None:
        """A command recorded by `task` in the loops `context`."""
        self._trackers.setdefault(task, LoopTracker()).note(context, self._index)
        self._now[task] = context
        self._index += 1

    def completed(self, task: str | None = None) -> int:
        """Complete cycles of `task` (or the most of any task) as recorded."""
        if task is not None:
            tracker = self._trackers.get(task)
            if tracker is None:
                return 0
            group, _ = tracker.choose(self._now.get(task, ()))
            return 0 if group is None else max(len(group.firsts) - 1, 0)
        return max((self.completed(t) for t in self._trackers), default=0)
