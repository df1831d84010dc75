"""What the arm did, per motion command: the motion table of the report.

`motion_records(queue)` turns the queue's history into `MotionRecord`s: identifier, source line,
kind, when it started and ended, the TCP path length and peak speed, and the limit that was
active most of the time ("j2 speed", "j3 accel", "j1 decel", "tvel", "rvel"). Computed after the
fact from the path and its time parameterisation (nothing is recorded on the 4 ms clock while
the run goes).

A cyclic program repeats its motions: a command that repeats an earlier one (the same pieces of
path, tool, limits and timing: record_repeats.py) takes its length, peak speed and the limit of
each interval from it; its seconds under each limit are summed from its own durations, as for any
command, and an interval whose limit was a near tie is decided again on its own path.
"""

from __future__ import annotations

import bisect

import numpy as np

from ..light_dataclass import dataclass
from .findings import Source
from .paths import tcp_rates
from .record_repeats import Repeats, noise
from .record_seconds import _order, _seconds, _seconds_of, seconds_many
from . import trajectory
from .trajectory import window


@dataclass(frozen=True, slots=True)  # one per command of the run
class MotionRecord:
    """What the arm did with one command (module docstring)."""
    id: int | float | None  # the identifier the instruction returned (None: a connection move)
    kind: str  # movej | movel | movec | connection
    source: Source
    state: str  # done | cancelled (resetMotion) | failed (not executable, 150) | pending
    recorded: float  # when the instruction recorded it (s)
    start: float | None  # when the arm started it (s)
    end: float | None  # when the commanded position reached its end (s)
    length_mm: float  # TCP path length of its part of the path
    peak_tcp_mm_s: float
    dominant: str  # the limit active most of the time
    limit_share: dict  # seconds spent under each limit
    target: str = ""
    tool: str = ""

    @property
    def duration(self) -> float | None:
        """end - start, None when it never ran."""
        return None if self.start is None or self.end is None else self.end - self.start


def time_leaving(profile, s0: float) -> float | None:
    """The last time the path parameter is at or before s0 (when the arm leaves s0)."""
    S = profile.S
    k = trajectory.bisect_right(S, s0 + 1e-9) - 1
    if k < 0:
        return None
    if abs(S[k] - s0) <= 1e-9 * max(1.0, abs(s0)):
        return profile.T[k]
    return profile.time_at(s0)


def _speeds_at(profile, s: np.ndarray) -> np.ndarray:
    """ṡ at path positions s (ṡ² is linear in s between breakpoints)."""
    k0 = max(trajectory.bisect_left(profile.S, float(s.min())) - 1, 0)
    k1 = trajectory.bisect_right(profile.S, float(s.max())) + 1
    S = np.asarray(profile.S[k0:k1])
    X = np.asarray(profile.SD[k0:k1]) ** 2
    keep = np.concatenate([np.diff(S) > 0, [True]])  # one value per position (a rest repeats S)
    return np.sqrt(np.maximum(np.interp(s, S[keep], X[keep]), 0.0))


RECORD_BLOCK = 128  # commands whose path is evaluated in one pass (`motion_records`)


def motion_records(queue, end_s: float | None = None, reuse: bool = True) -> list[MotionRecord]:
    """One record per command recorded (in recording order), connection moves included, as the
    arm did it by `end_s` (the end of the run; None: as planned). A command the arm had not
    started by then has no start and no end, one it had not finished no end, and both only the
    part of the path it ran (docs/sim-report.md: "null when it never ran"). The path is evaluated
    once for all commands (grouped by tool) but those that repeat an earlier one (`reuse`: the
    module docstring)."""
    maker = RecordMaker(queue, reuse)
    prof = queue.trajectory.profile  # (up to date)
    reached = prof.s_end if end_s is None else prof.state(end_s)[0]  # how far the arm got
    for command in queue.history:
        maker.add(command, end_s, reached)
    return maker.finish()


class _Asked:
    """What a record needs of its command once the command may be gone (issue 29: the record is
    taken as the run goes and the command released, simulation/live_record.py)."""

    __slots__ = ("id", "request", "state")

    def __init__(self, command) -> None:
        self.id, self.request, self.state = command.id, command.request, command.state

    @property
    def tool(self):
        return self.request.tool


class RecordMaker:
    """`motion_records` one command at a time (`add`, in recording order; `finish`: the records).
    A command added before the end of the run must be final: its state can no longer change and
    the profile and path it reads are final (simulation/live_record.py decides)."""

    def __init__(self, queue, reuse: bool = True) -> None:
        self.queue = queue
        self.prof = queue.planner.profile  # (the same object all run: never flushed from here)
        self.repeats = Repeats(queue.path, self.prof) if reuse else None
        self.out: list[MotionRecord | None] = []
        # the commands met first, by tool (group number, blocks done, commands waiting), evaluated a
        # block at a time as they come: what a command needs is dropped once its record is made
        self.groups: dict = {}
        self.doubts: list = []  # repeats with a near tie, decided at the end (`_decide`)
        self.pending: list = []  # (item, what its look-up reads) of the commands not looked up yet

    def add(self, command, end_s: float | None = None, reached: float | None = None) -> None:
        """The record of `command` (made now, or with its block or at `finish`); `end_s`, `reached`:
        the end of the run and how far the arm got (None: a final command, the run goes on)."""
        queue, prof, out = self.queue, self.prof, self.out
        place = command.placement
        if end_s is None and self.repeats is not None and command.state == "done" and place.s_end is not None \
                and place.s_begin is not None:
            # its start and breakpoints found with its block (`_place`), from the profile and path as
            # they are now (what it reads of them is final: live_record.py)
            out.append(None)
            self.pending.append((len(out) - 1, _Asked(command), place.s_begin, place.s_end, command.t_done,
                                 queue.limits_of(command), len(prof.S), len(self.repeats.path.spans)))
            if len(self.pending) >= RECORD_BLOCK:
                self._settle()
            return
        req = command.request
        base = dict(target=req.target_name, tool=req.tool_name)
        start = None if place.s_begin is None or command.state == "failed" else time_leaving(prof, place.s_begin)
        if start is None or (end_s is not None and start > end_s + 1e-9):
            out.append(MotionRecord(command.id, req.kind, req.source, command.state, req.recorded, None, None, 0.0,
                                    0.0, "", {}, **base))
            return
        s0 = place.s_begin
        s1 = place.s_end if place.s_end is not None else min(prof.s_end, place.s_provisional or prof.s_end)
        if command.state in ("cancelled", "pending"):
            s1 = min(s1, prof.s_end)
        end = command.t_done if command.state == "done" else prof.time_at(s1)
        if command.state != "done" and reached is not None and s1 > reached + 1e-9 * max(1.0, abs(s1)):
            s1, end = max(reached, s0), None  # under way when the run ended
        elif end is not None and end_s is not None and end > end_s + 1e-9:
            end = None  # a cancelled command braking when the run ended
        if s1 - s0 <= 1e-12:
            out.append(MotionRecord(command.id, req.kind, req.source, command.state, req.recorded, start,
                                    end if end is not None or command.state == "pending" else start, 0.0, 0.0, "",
                                    {}, **base))
            return
        k0 = trajectory.bisect_left(prof.S, s0)
        k1 = trajectory.bisect_right(prof.S, s1)
        item = (len(out), _Asked(command), s0, s1, start, end, k0, k1, queue.limits_of(command))
        out.append(None)
        if self.repeats is None:
            self._first(item, None)
            return
        # looked up with the block (`_settle`); what the look-up reads of the path is as it is now
        lo, hi, path = max(k0 - 1, 0), min(k1, len(prof.S) - 1), self.repeats.path
        i0, i1 = path.locate(min(prof.S[lo], s0))[0], path.locate(max(prof.S[hi], s1))[0]
        self.pending.append((item, (command.tool, item[8], s0, s1, lo, hi, i0, i1)))
        if len(self.pending) >= RECORD_BLOCK:
            self._settle()

    def _settle(self) -> None:
        """The commands added since the last call looked up together (record_repeats.find_block):
        a repeat is given the figures of the first (`_repeat`), the others are evaluated."""
        pending, self.pending = self.pending, []
        placed = [e for e in pending if len(e) == 2]
        if len(placed) < len(pending):
            placed = self._place(pending)
        if not placed:
            return
        pending = placed
        # the block's breakpoints read once (a History reads old ones through its chunk cache)
        prof = self.prof
        base = max(min(item[6] for item, _ in pending) - 1, 0)
        Sw = window(prof.S, base, max(item[7] for item, _ in pending) + 2)
        clear = []  # the repeats whose limits were all clear: their seconds in one pass (`seconds_many`)
        for (item, _), (earlier, slot, dt) in zip(pending, self.repeats.find_block([a for _, a in pending])):
            if earlier is None:
                self._first(item, slot)
            elif earlier.figures is None:  # given them when the first is evaluated (`_evaluate`)
                earlier.items.append((item, dt))
            elif earlier.figures[6]:
                clear.append((item, earlier.figures, dt))
            else:
                self.doubts.append((earlier.place + (item[0],), item, earlier.figures, dt))
        if clear:
            out = self.out
            shares = seconds_many(Sw, [(max(item[6] - 1, 0) - base, item[2], item[3], f[4], f[5], dt)
                                       for item, f, dt in clear])
            for (item, f, _), share in zip(clear, shares):
                out[item[0]] = _record(item[1], item[4], item[5], f[0], f[1], share)
        del Sw

    def _place(self, pending: list) -> list:
        """`add`'s start (time_leaving), breakpoints and spans of the final commands it left to the
        block (idx, command, s0, s1, end, limits, breakpoints and spans then), with the same searches
        made in one window of the profile; their records when they have no start or no length, the
        others as `add` makes them: [(item, what its look-up reads)]."""
        prof, path, out = self.prof, self.repeats.path, self.out
        later = [e for e in pending if len(e) != 2]
        s0 = np.array([e[2] for e in later])
        s1 = np.array([e[3] for e in later])
        x = s0 + 1e-9  # (time_leaving's search)
        lo_b = max(trajectory.bisect_left(prof.S, float(s0.min())) - 1, 0)
        hi_b = min(trajectory.bisect_right(prof.S, float(max(s1.max(), x.max()))), len(prof.S) - 1)
        S, T, SD = (window(v, lo_b, hi_b + 1) for v in (prof.S, prof.T, prof.SD))
        w = len(S)
        # a search in the window is the profile's: everything before it is below every s0
        k0 = S.searchsorted(s0, "left") + lo_b
        k1 = S.searchsorted(s1, "right") + lo_b
        # time_leaving(s0): the breakpoint at or before s0 + 1e-9 when s0 is on it, else
        # `Profile.time_at(s0)`: its search in the window is the profile's when it falls past the
        # window's first breakpoint and before its end (else asked of the profile, `nan` here)
        kl = S.searchsorted(x, "right") - 1
        tol = 1e-9 * np.maximum(1.0, np.abs(s0))
        kt = S.searchsorted(s0 - 1e-12 * np.maximum(1.0, np.abs(s0)), "left")
        start = np.full(len(s0), np.nan)
        if w > 1:
            kt_in = np.clip(kt, 1, w - 1)
            start = np.where((kt > 0) & (kt < w), np.where(np.abs(S[kt_in] - s0) <= tol, T[kt_in],
                                                           _solve_many(T, S, SD, kt_in - 1, s0)), np.nan)
        on = np.clip(kl, 0, w - 1)
        start = np.where(np.abs(S[on] - s0) <= tol, T[on], start)
        start[kl + lo_b < 0] = -np.inf  # (no start)
        # the spans each command's look-up reaches (`add`: the spans at the breakpoints around it)
        spans_then = np.array([e[7] for e in later])
        lo = np.maximum(k0 - 1, 0)
        hi = np.minimum(k1, np.array([e[6] for e in later]) - 1)
        s_lo = np.minimum(S[np.clip(lo - lo_b, 0, w - 1)], s0)
        s_hi = np.maximum(S[np.clip(hi - lo_b, 0, w - 1)], s1)
        off_lo = max(bisect.bisect_right(path.offsets, float(s_lo.min())) - 1, 0)
        offs = np.asarray(path.offsets[off_lo:bisect.bisect_right(path.offsets, float(s_hi.max())) + 1])
        i0 = np.minimum(np.maximum(offs.searchsorted(s_lo, "right") + (off_lo - 1), 0), spans_then - 1).tolist()
        i1 = np.minimum(np.maximum(offs.searchsorted(s_hi, "right") + (off_lo - 1), 0), spans_then - 1).tolist()
        outside = ((lo - lo_b < 0) | (lo - lo_b >= w) | (hi - lo_b < 0) | (hi - lo_b >= w)).tolist()
        del S, T, SD
        start, k0, k1, lo, hi = start.tolist(), k0.tolist(), k1.tolist(), lo.tolist(), hi.tolist()
        done, n = [], 0
        for e in pending:
            if len(e) == 2:
                done.append(e)
                continue
            idx, command, a, b, end, lim, breakpoints, spans = e
            t = start[n]
            if t != t:
                t = prof.time_at(a)
            elif t == -np.inf:
                t = None
            req = command.request
            if t is None or b - a <= 1e-12:  # (as `add`: no start, or no length)
                out[idx] = MotionRecord(command.id, req.kind, req.source, command.state, req.recorded, t,
                                        None if t is None else (end if end is not None else t), 0.0, 0.0,
                                        "", {}, target=req.target_name, tool=req.tool_name)
            elif outside[n]:  # (a breakpoint outside the window: read from the profile)
                done.append(((idx, command, a, b, t, end, k0[n], k1[n], lim),
                             (req.tool, lim, a, b, lo[n], hi[n],
                              min(max(bisect.bisect_right(path.offsets, min(prof.S[lo[n]], a)) - 1, 0), spans - 1),
                              min(max(bisect.bisect_right(path.offsets, max(prof.S[hi[n]], b)) - 1, 0), spans - 1))))
            else:
                done.append(((idx, command, a, b, t, end, k0[n], k1[n], lim),
                             (req.tool, lim, a, b, lo[n], hi[n], i0[n], i1[n])))
            n += 1
        return done

    def _first(self, item: tuple, slot) -> None:
        """A command met first: evaluated with its block (its Slot, if any, then given its figures)."""
        tool = item[1].tool  # the same TCP (by value: each command holds its own copy) evaluated together
        key = None if tool is None else np.asarray(tool, dtype=float).tobytes()
        group = self.groups.get(key)
        if group is None:
            group = self.groups[key] = [len(self.groups), 0, []]
        group[2].append((item, slot))
        if len(group[2]) == RECORD_BLOCK:
            _evaluate(self.queue, self.prof, self.out, group, self.doubts)

    def flush(self, ties: bool = True) -> None:
        """Every command added so far given its record: the blocks not full evaluated, the near ties
        decided (a record's figures do not depend on the commands evaluated with it: the same bits).
        `ties` False: the near ties only once DECIDE_BLOCK of them wait (a cyclic cell's repeats share
        their pieces of path: one evaluation per piece for the whole block)."""
        if self.repeats is not None:
            self._settle()
        for group in self.groups.values():
            if group[2]:
                _evaluate(self.queue, self.prof, self.out, group, self.doubts)
        if ties or len(self.doubts) >= DECIDE_BLOCK:
            _decide(self.queue, self.prof, self.out, self.doubts)

    def finish(self) -> list[MotionRecord]:
        """The records of every command added."""
        self.flush()
        return self.out  # type: ignore[return-value]


def _evaluate(queue, prof, out: list, group: list, doubts: list) -> None:
    """Fill `out` with the records of a block of commands met first (`group`: its number, blocks
    done, [((index in out, command, s0, s1, start, end, k0, k1, limits), its Slot)]), all with
    the same tool, in one evaluation of the path (the memory of an evaluation does not grow with
    the run); then those of the repeats that waited for them (`_repeat`)."""
    number, done, items = group
    group[1], group[2] = done + 1, []
    where = []
    for (_, _, s0, s1, _, _, k0, k1, _), _ in items:
        # return_index: the same values, and numpy does not import numpy.ma (48 M instructions)
        pts = np.unique(np.concatenate([np.linspace(s0, s1, 33), np.asarray(prof.S[k0:k1])]), return_index=True)[0]
        lo = max(k0 - 1, 0)
        S = np.asarray(prof.S[lo:k1 + 1])
        where.append((pts, 0.5 * (S[1:] + S[:-1]), lo))
    allp = np.concatenate([np.concatenate([pts, mids]) for pts, mids, _ in where])
    q = queue.path.q(allp)
    q1 = queue.path.q(allp, 1)
    q2 = queue.path.q(allp, 2)
    last = np.cumsum([len(p) + len(m) for p, m, _ in where]) - np.array([len(m) + 1 for _, m, _ in where])
    q[last], q1[last] = queue.path.q_end(allp[last]), queue.path.q_end(allp[last], 1)  # s1: its own span
    pt, rt = tcp_rates(queue.kin, q, q1, items[0][0][1].tool)
    at = 0
    for n_item, (((idx, command, s0, s1, start, end, _, k1, lim), slot), (pts, mids, lo)) in enumerate(zip(items, where)):
        n, m = len(pts), len(mids)
        sl, sm = slice(at, at + n), slice(at + n, at + n + m)
        at += n + m
        length = float(np.sum(0.5 * (pt[sl][1:] + pt[sl][:-1]) * np.diff(pts)))
        peak = float(np.max(pt[sl] * _speeds_at(prof, pts)))
        rows = _intervals(prof, lo, k1, s0, s1)
        i = rows[5]
        codes, clear = _limits_on(lim, rows, q1[sm][i], q2[sm][i], pt[sm][i], rt[sm][i], prof, lo, k1, s1)
        share = _seconds(rows, codes, len(lim.V))
        out[idx] = _record(command, start, end, length, peak, share)
        if slot is not None:
            # where it was evaluated: the near ties of its repeats are decided in that order
            # (all clear: its repeats' seconds summed a block at a time, `seconds_many`)
            unclear = np.flatnonzero(~clear)
            slot.figures = (length, peak, codes, clear, i, _order(codes, len(lim.V)), not len(unclear), unclear,
                            i[unclear])
            slot.place = (number, done * RECORD_BLOCK + n_item)
            for item, dt in slot.items:
                _repeat(prof, out, item, dt, slot, doubts)
            slot.items = []


def _repeat(prof, out: list, item: tuple, dt: np.ndarray, slot, doubts: list, S=None, base: int = 0) -> None:
    """The record of a command that repeats an earlier one (its Slot's figures): its length and
    peak, its limits per interval, its own seconds under each (`dt`: the durations of its intervals
    that count, record_repeats.Repeats.inputs); when a limit was a near tie, left to `_decide`
    (`doubts`). `S`: the profile's positions from breakpoint `base` (its window), else read there."""
    length, peak, _, _, i, order, clear, _, _ = slot.figures
    idx, command, s0, s1, start, end, k0, k1, _ = item
    if clear:  # the earlier's intervals (the key holds where s0 and s1 fall) and limits
        share = _seconds_of(prof.S if S is None else S, max(k0 - 1, 0) - base, s0, s1, i, order, dt)
        out[idx] = _record(command, start, end, length, peak, share)
    else:
        doubts.append((slot.place + (idx,), item, slot.figures, dt))


DECIDE_BLOCK = 256  # near ties decided in one evaluation (what is held for them is bounded)


def _decide(queue, prof, out: list, doubts: list) -> None:
    """The records of the repeats whose limit in some interval was a near tie: decided again on
    their own path, DECIDE_BLOCK of them in one evaluation per tool and one choice of limits (in
    the order the earlier commands were evaluated, then of the run; a row's choice depends on its
    own values only)."""
    doubts.sort(key=lambda d: d[0])
    for at in range(0, len(doubts), DECIDE_BLOCK):
        _decide_block(queue, prof, out, doubts[at:at + DECIDE_BLOCK])
    doubts.clear()


def _decide_block(queue, prof, out: list, doubts: list) -> None:
    """`_decide` of a block of doubts: only the intervals in doubt are read from the profile (as
    `_intervals` gives them), the seconds summed from the durations the repeat's key holds
    (`seconds_many`: the same arithmetic as `_seconds`)."""
    doubt: dict = {}  # tool -> [(item, codes, unclear rows, their intervals, where its window starts, noise,
    #                            length, peak, intervals, durations)]
    # the breakpoints the block reads, in one window from `base` (a History reads old ones one by one)
    base = min(max(d[1][6] - 1, 0) for d in doubts)
    # (no list of the window: it spans every breakpoint since the last decision, ~80,000 at 1 h)
    Sw, SDw = (window(v, base, max(d[1][7] for d in doubts) + 2) for v in (prof.S, prof.SD))
    last = len(prof.S) - 1
    for _, item, (length, peak, codes, _, i, _, _, j, at), dt in doubts:
        idx, command, s0, s1, start, end, k0, k1, lim = item
        lo = max(k0 - 1, 0)
        tool = command.tool
        doubt.setdefault(None if tool is None else np.asarray(tool, dtype=float).tobytes(), []).append(
            (item, codes.copy(), j, at, lo - base,
             noise(prof, lo, k1, max(abs(float(Sw[min(k1, last) - base])), abs(s1)), SDw, base), length, peak, i, dt))
    for items in doubt.values():
        # one row per interval in doubt: its breakpoints (the earlier's `at` moved to this one's
        # window), its command's limits and noise
        m = np.array([len(e[2]) for e in items])
        k = np.concatenate([e[3] for e in items]) + np.repeat(np.array([e[4] for e in items]), m)
        a, b, sd0, sd1 = Sw[k], Sw[k + 1], SDw[k], SDw[k + 1]
        lims = [e[0][8] for e in items]
        V, A, D = (np.repeat(np.array([getattr(lim, x) for lim in lims]), m, axis=0) for x in ("V", "A", "D"))
        tvel, rvel = (np.repeat(np.array([getattr(lim, x) for lim in lims]), m) for x in ("tvel", "rvel"))
        e_s, e_v = (np.repeat(np.array(v), m) for v in zip(*(e[5] for e in items)))
        q, q1, q2 = _path_at(queue.path, 0.5 * (a + b))
        pt, rt = tcp_rates(queue.kin, q, q1, items[0][0][1].tool)
        chosen = _choose(b - a, sd0 ** 2, sd1 ** 2, q1, q2, pt, rt, V, A, D, tvel, rvel, e_s, e_v)[0]
        n, rows = 0, []
        for (idx, command, s0, s1, start, end, k0, k1, lim), codes, j, _, _, _, length, peak, i, dt in items:
            codes[j] = chosen[n:n + len(j)]
            n += len(j)
            rows.append((max(k0 - 1, 0) - base, s0, s1, i, _order(codes, len(lim.V)), dt))
        for (item, *_, length, peak, _, _), share in zip(items, seconds_many(Sw, rows)):
            out[item[0]] = _record(item[1], item[4], item[5], length, peak, share)
    del Sw, SDw


def _solve_many(T, S, SD, k: np.ndarray, s: np.ndarray) -> np.ndarray:
    """trajectory._solve(T, S, SD, k, s) of each (k, s) with its arithmetic in numpy: the same bits
    (tests/motion/test_records.py)."""
    t0, t1, sd0 = T[k], T[k + 1], SD[k]
    dt = t1 - t0
    ds = s - S[k]
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        u = (SD[k + 1] - sd0) / dt
        tau = np.where(np.abs(u) < 1e-15, np.where(sd0 > 0, ds / sd0, dt),
                       (-sd0 + np.sqrt(np.maximum(sd0 * sd0 + 2.0 * u * ds, 0.0))) / u)
        solved = t0 + np.minimum(np.maximum(tau, 0.0), dt)
    return np.where(ds <= 0.0, t0, np.where(dt <= 0.0, t1, solved))


def _path_at(path, s: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The path's joints and their first two derivatives at positions s, as `Path.q` gives them
    (the span at or before each, its σ clipped to it), one evaluation per piece of geometry: the
    spans of a repeated motion are the same part of the same geometry."""
    groups: dict = {}
    for k, x in enumerate(s.tolist()):
        i = min(max(bisect.bisect_right(path.offsets, x) - 1, 0), len(path.spans) - 1)
        sp = path.spans[i]
        g = groups.get((id(sp.geom), sp.a, sp.b))
        if g is None:
            g = groups[(id(sp.geom), sp.a, sp.b)] = (sp, [], [])
        g[1].append(k)
        g[2].append(path.offsets[i])
    out = [np.empty((len(s), len(path.q_rest))) for _ in range(3)]
    for sp, rows, offsets in groups.values():
        sigma = np.clip(s[rows] - np.asarray(offsets), 0.0, sp.length)
        for order in range(3):
            out[order][rows] = sp.q(sigma, order)
    return out[0], out[1], out[2]


def _record(command, start, end, length: float, peak: float, share: dict) -> MotionRecord:
    """The record of a command that ran: its figures, and the limit it spent the most time on."""
    req = command.request
    dominant = max(share, key=share.get) if share else ""
    return MotionRecord(command.id, req.kind, req.source, command.state, req.recorded, start, end, length, peak,
                        dominant, share, target=req.target_name, tool=req.tool_name)


def _intervals(prof, lo: int, k1: int, s0: float, s1: float) -> tuple:
    """The breakpoint intervals of the profile that lie in (s0, s1), from breakpoint lo: (S of the
    slice lo..k1, ṡ² at each interval's start and end, its duration, the share of it in (s0, s1),
    its index in the slice); the ones with no length left out."""
    S = np.asarray(prof.S[lo:k1 + 1])
    T = np.asarray(prof.T[lo:k1 + 1])
    SD = np.asarray(prof.SD[lo:k1 + 1])
    ds_all = S[1:] - S[:-1]  # (np.diff's arithmetic)
    i = np.nonzero((ds_all > 0) & (S[1:] > s0) & (S[:-1] < s1))[0]
    ds = ds_all[i]
    frac = np.clip((np.minimum(S[i + 1], s1) - np.maximum(S[i], s0)) / ds, 0.0, 1.0)
    return S, SD[i] ** 2, SD[i + 1] ** 2, T[i + 1] - T[i], frac, i


def _limits_on(lim, rows, q1, q2, pt, rt, prof, lo: int, k1: int, s1: float) -> tuple[np.ndarray, np.ndarray]:
    """The limit the profile is on in each interval of `rows` (`_intervals`) as a code (`_label`),
    and whether each choice is clear (`_choose`)."""
    S, x0, x1, _, _, i = rows
    if not len(i):
        return np.zeros(0, dtype=np.intp), np.ones(0, dtype=bool)
    e_s, e_v = noise(prof, lo, k1, max(abs(S[-1]), abs(s1)))
    return _choose(S[i + 1] - S[i], x0, x1, q1, q2, pt, rt, lim.V, lim.A, lim.D, lim.tvel, lim.rvel, e_s, e_v)


def _choose(ds, x0, x1, q1, q2, pt, rt, V, A, D, tvel, rvel, e_s, e_v) -> tuple[np.ndarray, np.ndarray]:
    """Per interval (of length ds, ṡ² from x0 to x1; q1..rt: the path at its midpoint): the
    acceleration or deceleration of the axis nearest its limit when the path speed changes, the
    speed limit nearest when it is held. With it, whether each choice is clear by more than a
    repetition's rounding (record_repeats.noise: e_s, e_v), else a repetition could choose another.
    The limits (V, A, D, tvel, rvel) and the noise are one command's or one per interval: the same
    arithmetic per interval."""
    n = V.shape[-1]
    x = 0.5 * (x0 + x1)
    u = (x1 - x0) / (2.0 * ds)
    acc = np.abs(q1 * u[:, None] + q2 * x[:, None])
    up = u > 0
    lim_a = np.where(up[:, None], A, D)
    ratio = acc / lim_a
    ka = np.argmax(ratio, axis=1)
    sd = np.sqrt(x)
    speed = np.hstack([np.abs(q1) * sd[:, None] / V, (pt * sd / tvel)[:, None], (rt * sd / rvel)[:, None]])
    kv = np.argmax(speed, axis=1)
    thr = 1e-6 * np.maximum(1.0, x)
    changing = np.abs(u) > thr
    codes = np.where(changing, 2 * ka + np.where(up, 0, 1), 2 * n + kv)
    # how far a repetition's inputs may move each choice: positions by e_s, path speeds by e_v, so
    # ṡ² by dx, its slope u by du
    dx = 2.0 * np.sqrt(np.maximum(x0, x1)) * e_v + e_v * e_v
    du = dx / ds + np.abs(u) * 2.0 * e_s / ds
    clear = np.abs(np.abs(u) - thr) > du + 1e-6 * dx + 1e-9 * thr
    clear &= ~changing | _apart(ratio, (np.abs(q1) * du[:, None] + np.abs(q2) * dx[:, None]) / lim_a)
    rel = dx / (2.0 * np.maximum(x, 1e-300))  # relative change of ṡ
    clear &= changing | _apart(speed, speed * rel[:, None])
    return codes.astype(np.intp), clear


def _apart(values, slack) -> np.ndarray:
    """Per row, whether the largest value exceeds every other by more than both slacks and 1e-9
    of itself (its argmax cannot change by the slacks)."""
    if values.shape[1] < 2:
        return np.ones(len(values), dtype=bool)
    k = np.argmax(values, axis=1)
    rows = np.arange(len(values))
    top = values[rows, k]
    others = values.copy()
    others[rows, k] = -np.inf
    reach = np.max(others + slack, axis=1)
    return top - slack[rows, k] > reach + 1e-9 * np.abs(top)


_BUSY_BLOCK = 1 << 16  # breakpoints read at a time by `busy_time`


def busy_time(profile, t_end: float) -> tuple[float, float]:
    """(seconds the arm moved, seconds it stood still) between 0 and t_end: the intervals moving at
    either end, each min(its end, t_end) - its start, summed in order (a running sum, block by
    block: the same bits as one loop over the breakpoints; views of the profile, dropped here)."""
    T, SD = profile.T, profile.SD
    n = len(T)
    busy = 0.0
    for lo in range(0, max(n - 1, 0), _BUSY_BLOCK):
        hi = min(lo + _BUSY_BLOCK, n - 1)
        t, sd = window(T, lo, hi + 1), window(SD, lo, hi + 1)
        stop = np.flatnonzero(t[:-1] >= t_end)
        m = int(stop[0]) if len(stop) else hi - lo
        moving = (sd[:m] > 0) | (sd[1:m + 1] > 0)
        d = np.minimum(t[1:m + 1], t_end)[moving] - t[:m][moving]
        busy = float(np.add.accumulate(np.concatenate(([busy], d)))[-1])  # sequential, as busy += each
        del t, sd
        if len(stop):
            break
    return busy, max(t_end - busy, 0.0)
