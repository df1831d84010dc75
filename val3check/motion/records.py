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


@dataclass(frozen=True)
class MotionRecord:
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
        return None if self.start is None or self.end is None else self.end - self.start

    def as_dict(self) -> dict:
        return {
            "id": self.id, "kind": self.kind, "path": self.source.path, "line": self.source.line,
            "col": self.source.col, "task": self.source.task, "state": self.state,
            "recorded": _round(self.recorded), "start": _round(self.start), "end": _round(self.end),
            "duration": _round(self.duration), "length_mm": round(self.length_mm, 3),
            "peak_tcp_mm_s": round(self.peak_tcp_mm_s, 3), "dominant_limit": self.dominant,
            "limit_seconds": {k: round(v, 6) for k, v in sorted(self.limit_share.items())},
            "target": self.target, "tool": self.tool,
        }


def _round(v):
    return None if v is None else round(v, 6)


def _time_leaving(profile, s0: float) -> float | None:
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
    S = np.asarray(profile.S)
    X = np.asarray(profile.SD) ** 2
    keep = np.concatenate([np.diff(S) > 0, [True]])  # one value per position (a rest repeats S)
    return np.sqrt(np.maximum(np.interp(s, S[keep], X[keep]), 0.0))


def record_of(queue, c) -> MotionRecord:
    prof = queue.profile
    path = queue.path
    src = c.source
    base = dict(target=c.target_name, tool=c.tool_name)
    if c.S_begin is None or c.state == "failed":
        return MotionRecord(c.id, c.kind, src, c.state, c.recorded, None, None, 0.0, 0.0, "", {}, **base)
    s0 = c.S_begin
    s1 = c.S_end if c.S_end is not None else min(prof.s_end, c.S_prov or prof.s_end)
    if c.state == "cancelled":
        s1 = min(s1, prof.s_end)
    start = _time_leaving(prof, s0)
    end = c.t_done if c.state == "done" else prof.time_at(s1)
    if s1 - s0 <= 1e-12:
        return MotionRecord(c.id, c.kind, src, c.state, c.recorded, start, end if end is not None else start, 0.0, 0.0,
                            "", {}, **base)
    # a fine grid of the command's part of the path for length and speed
    s = np.linspace(s0, s1, 129)
    k0 = bisect.bisect_left(prof.S, s0)
    k1 = bisect.bisect_right(prof.S, s1)
    s = np.unique(np.concatenate([s, np.asarray(prof.S[k0:k1])]))
    q = path.q(s)
    q1 = path.q(s, 1)
    pt, rt = tcp_rates(queue.kin, q, q1, c.tool)
    length = float(np.sum(0.5 * (pt[1:] + pt[:-1]) * np.diff(s)))
    sd = _speeds_at(prof, s)
    peak = float(np.max(pt * sd))
    share = _limit_share(queue, c, prof, k0, k1, s0, s1)
    dominant = max(share, key=share.get) if share else ""
    return MotionRecord(c.id, c.kind, src, c.state, c.recorded, start, end, length, peak, dominant, share, **base)


def _limit_share(queue, c, prof, k0: int, k1: int, s0: float, s1: float) -> dict:
    """Seconds under each limit: per breakpoint interval, the limit the profile is on (the
    acceleration or deceleration of the axis nearest its limit when the path speed changes, the
    speed limit nearest when it is held)."""
    lim = queue.limits_of(c)
    T, S, SD = prof.T, prof.S, prof.SD
    lo = max(bisect.bisect_left(S, s0) - 1, 0)
    hi = min(k1 + 1, len(S) - 1)
    out: dict[str, float] = {}
    idx = [i for i in range(lo, hi) if S[i + 1] > S[i] and S[i + 1] > s0 and S[i] < s1]
    if not idx:
        return out
    mids = np.array([0.5 * (S[i] + S[i + 1]) for i in idx])
    q = queue.path.q(mids)
    q1 = queue.path.q(mids, 1)
    q2 = queue.path.q(mids, 2)
    pt, rt = tcp_rates(queue.kin, q, q1, c.tool)
    for j, i in enumerate(idx):
        dt = T[i + 1] - T[i]
        ds = S[i + 1] - S[i]
        x = 0.5 * (SD[i] ** 2 + SD[i + 1] ** 2)
        u = (SD[i + 1] ** 2 - SD[i] ** 2) / (2.0 * ds)
        sd = x ** 0.5
        if abs(u) > 1e-6 * max(1.0, x):
            acc = np.abs(q1[j] * u + q2[j] * x)
            lim_a = lim.A if u > 0 else lim.D
            k = int(np.argmax(acc / lim_a))
            label = f"j{k + 1} {'accel' if u > 0 else 'decel'}"
        else:
            ratios = list(np.abs(q1[j]) * sd / lim.V) + [pt[j] * sd / lim.tvel, rt[j] * sd / lim.rvel]
            k = int(np.argmax(ratios))
            label = f"j{k + 1} speed" if k < len(lim.V) else ("tvel" if k == len(lim.V) else "rvel")
        # the part of the interval inside the command
        frac = (min(S[i + 1], s1) - max(S[i], s0)) / ds
        out[label] = out.get(label, 0.0) + dt * max(min(frac, 1.0), 0.0)
    return out


def motion_records(queue) -> list[MotionRecord]:
    """One record per command recorded (in recording order), connection moves included."""
    return [record_of(queue, c) for c in queue.history]


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
