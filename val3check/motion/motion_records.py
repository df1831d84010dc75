"""What the arm did, per motion command: the motion table of the report.

`motion_records(queue)` turns the queue's history into `MotionRecord`s: identifier, source line,
kind, when it started and ended, the TCP path length and peak speed, and the limit that was
active most of the time ("j2 speed", "j3 accel", "j1 decel", "tvel", "rvel"). Computed after the
fact from the path and its time parameterisation (nothing is recorded on the 4 ms clock while
the run goes).
"""

from __future__ import annotations

import bisect
from dataclasses import dataclass

import numpy as np

from .findings import Source
from .paths import tcp_rates


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
    k = bisect.bisect_right(S, s0 + 1e-9) - 1
    if k < 0:
        return None
    if abs(S[k] - s0) <= 1e-9 * max(1.0, abs(s0)):
        return profile.T[k]
    return profile.time_at(s0)


def _speeds_at(profile, s: np.ndarray) -> np.ndarray:
    """ṡ at path positions s (ṡ² is linear in s between breakpoints)."""
    k0 = max(bisect.bisect_left(profile.S, float(s.min())) - 1, 0)
    k1 = bisect.bisect_right(profile.S, float(s.max())) + 1
    S = np.asarray(profile.S[k0:k1])
    X = np.asarray(profile.SD[k0:k1]) ** 2
    keep = np.concatenate([np.diff(S) > 0, [True]])  # one value per position (a rest repeats S)
    return np.sqrt(np.maximum(np.interp(s, S[keep], X[keep]), 0.0))


RECORD_BLOCK = 128  # commands whose path is evaluated in one pass (`motion_records`)


def motion_records(queue, end_s: float | None = None) -> list[MotionRecord]:
    """One record per command recorded (in recording order), connection moves included, as the
    arm did it by `end_s` (the end of the run; None: as planned). A command the arm had not
    started by then has no start and no end, one it had not finished no end, and both only the
    part of the path it ran (docs/sim-report.md: "null when it never ran"). The path is evaluated
    once for all commands (grouped by tool)."""
    prof = queue.trajectory.profile
    reached = prof.s_end if end_s is None else prof.state(end_s)[0]  # how far the arm got
    out: list[MotionRecord | None] = []
    todo = []  # (index in out, command, s0, s1, start, end, points, mids)
    for command in queue.history:
        req = command.request
        place = command.placement
        base = dict(target=req.target_name, tool=req.tool_name)
        start = None if place.s_begin is None or command.state == "failed" else time_leaving(prof, place.s_begin)
        if start is None or (end_s is not None and start > end_s + 1e-9):
            out.append(MotionRecord(command.id, req.kind, req.source, command.state, req.recorded, None, None, 0.0,
                                    0.0, "", {}, **base))
            continue
        s0 = place.s_begin
        s1 = place.s_end if place.s_end is not None else min(prof.s_end, place.s_provisional or prof.s_end)
        if command.state in ("cancelled", "pending"):
            s1 = min(s1, prof.s_end)
        end = command.t_done if command.state == "done" else prof.time_at(s1)
        if command.state != "done" and s1 > reached + 1e-9 * max(1.0, abs(s1)):
            s1, end = max(reached, s0), None  # under way when the run ended
        elif end is not None and end_s is not None and end > end_s + 1e-9:
            end = None  # a cancelled command braking when the run ended
        if s1 - s0 <= 1e-12:
            out.append(MotionRecord(command.id, req.kind, req.source, command.state, req.recorded, start,
                                    end if end is not None or command.state == "pending" else start, 0.0, 0.0, "",
                                    {}, **base))
            continue
        k0 = bisect.bisect_left(prof.S, s0)
        k1 = bisect.bisect_right(prof.S, s1)
        pts = np.unique(np.concatenate([np.linspace(s0, s1, 33), np.asarray(prof.S[k0:k1])]))
        lo = max(k0 - 1, 0)
        S = np.asarray(prof.S[lo:k1 + 1])
        mids = 0.5 * (S[1:] + S[:-1])
        todo.append((len(out), command, s0, s1, start, end, pts, mids, lo, k1))
        out.append(None)
    groups: dict = {}
    for item in todo:
        tool = item[1].tool  # the same TCP (by value: each command holds its own copy) evaluated together
        groups.setdefault(None if tool is None else np.asarray(tool, dtype=float).tobytes(), []).append(item)
    # in blocks of commands: the memory of an evaluation does not grow with the run
    blocks = [items[k:k + RECORD_BLOCK] for items in groups.values() for k in range(0, len(items), RECORD_BLOCK)]
    for items in blocks:
        allp = np.concatenate([np.concatenate([it[6], it[7]]) for it in items])
        q = queue.path.q(allp)
        q1 = queue.path.q(allp, 1)
        q2 = queue.path.q(allp, 2)
        pt, rt = tcp_rates(queue.kin, q, q1, items[0][1].tool)
        at = 0
        for idx, command, s0, s1, start, end, pts, mids, lo, k1 in items:
            n, m = len(pts), len(mids)
            sl, sm = slice(at, at + n), slice(at + n, at + n + m)
            at += n + m
            length = float(np.sum(0.5 * (pt[sl][1:] + pt[sl][:-1]) * np.diff(pts)))
            peak = float(np.max(pt[sl] * _speeds_at(prof, pts)))
            share = _limit_share(queue.limits_of(command), prof, lo, k1, s0, s1, q1[sm], q2[sm], pt[sm], rt[sm])
            dominant = max(share, key=share.get) if share else ""
            req = command.request
            out[idx] = MotionRecord(command.id, req.kind, req.source, command.state, req.recorded, start, end, length,
                                    peak, dominant, share, target=req.target_name, tool=req.tool_name)
    return out  # type: ignore[return-value]


def _limit_share(lim, prof, lo: int, k1: int, s0: float, s1: float, q1, q2, pt, rt) -> dict:
    """Seconds under each limit: per breakpoint interval, the limit the profile is on (the
    acceleration or deceleration of the axis nearest its limit when the path speed changes, the
    speed limit nearest when it is held). q1..rt: the path at the intervals' midpoints."""
    S = np.asarray(prof.S[lo:k1 + 1])
    T = np.asarray(prof.T[lo:k1 + 1])
    SD = np.asarray(prof.SD[lo:k1 + 1])
    if len(S) < 2:
        return {}
    ds_all = np.diff(S)
    m = (ds_all > 0) & (S[1:] > s0) & (S[:-1] < s1)
    if not m.any():
        return {}
    i = np.nonzero(m)[0]
    ds = ds_all[i]
    dt = T[i + 1] - T[i]
    x0, x1 = SD[i] ** 2, SD[i + 1] ** 2
    x = 0.5 * (x0 + x1)
    u = (x1 - x0) / (2.0 * ds)
    q1, q2, pt, rt = q1[i], q2[i], pt[i], rt[i]
    acc = np.abs(q1 * u[:, None] + q2 * x[:, None])
    up = u > 0
    ka = np.argmax(acc / np.where(up[:, None], lim.A, lim.D), axis=1)
    sd = np.sqrt(x)
    speed = np.hstack([np.abs(q1) * sd[:, None] / lim.V, (pt * sd / lim.tvel)[:, None], (rt * sd / lim.rvel)[:, None]])
    kv = np.argmax(speed, axis=1)
    changing = np.abs(u) > 1e-6 * np.maximum(1.0, x)
    frac = np.clip((np.minimum(S[i + 1], s1) - np.maximum(S[i], s0)) / ds, 0.0, 1.0)
    n = len(lim.V)
    out: dict[str, float] = {}
    for j in range(len(i)):
        if changing[j]:
            label = f"j{ka[j] + 1} {'accel' if up[j] else 'decel'}"
        else:
            k = int(kv[j])
            label = f"j{k + 1} speed" if k < n else ("tvel" if k == n else "rvel")
        out[label] = out.get(label, 0.0) + float(dt[j] * frac[j])
    return out


def busy_time(profile, t_end: float) -> tuple[float, float]:
    """(seconds the arm moved, seconds it stood still) between 0 and t_end."""
    T, SD = profile.T, profile.SD
    busy = 0.0
    for i in range(len(T) - 1):
        if T[i] >= t_end:
            break
        if SD[i] > 0 or SD[i + 1] > 0:
            busy += min(T[i + 1], t_end) - T[i]
    return busy, max(t_end - busy, 0.0)
