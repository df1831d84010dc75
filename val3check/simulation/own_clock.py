"""A motion on its own clock (issue 29; docs/cell.md, "How checks are sampled"): the part of the
run's trajectory between a motion's start and its end, expressed from time 0 and path position
0, with a key made of everything that determines it, so that the collision checks of a motion
that repeats exactly are computed once.

    own = own_clock(trajectory, start, end)   # -> Own: times from 0 every 4 ms and the end,
                                              #    joints there, q_at(t) between, key (or None)
    for own in own_clocks(trajectory, windows):   # the same for many (start, end), keyed in blocks
    q = Positions(trajectory)(t)              # trajectory.position(t), found again by its span

The run's trajectory (motion.trajectory.Trajectory) holds one path for the whole run (global path
position s) and one profile s(t) on the run's clock: the same motion one cycle later has the same
curves and the same timing, but its numbers sit at other absolute times and positions and differ
in their last bits. Here the motion is rebuilt from its own pieces: the path's spans it crosses
(the same curve objects for a motion that repeats: motion/construction.py), laid end to end from
0, and the profile's breakpoints inside it, shifted to its start and rounded to Q_T, Q_S and
Q_SD. The key is those spans and those rounded numbers, and the joints are computed from the key
alone: a result computed for the key holds for every motion with that key.

The rounding is far below anything the checks resolve (1e-7 path units, i.e. degrees of joint
motion, move a point 1 m from an axis by 2e-6 mm) and far above the rounding errors of a long
run's absolute numbers (1e-10 at a path position of 10^6). A trajectory of another kind (chapter
11's alter and compliance layers: simulation/arm_layers.py) is sampled on the motion's own clock
too, from the trajectory itself, without a key.
"""

from __future__ import annotations

import bisect
import functools
import itertools
import math
from collections.abc import Callable, Iterable, Iterator

import numpy as np

from ..interpretation.clock import TICK_US
from ..motion.paths import Path
from ..motion.trajectory import Profile, Trajectory, bisect_left, bisect_right, window

TICK = TICK_US / 1_000_000
Q_T = 1e-9  # s: the profile's times within the motion
Q_S = 1e-7  # path units (degrees of joint motion): positions along the motion's path
Q_SD = 1e-7  # path units per second: path speeds
_QUANTA = np.array([[Q_T], [Q_S], [Q_SD]])
BLOCK = 256  # motions keyed at once (`own_clocks`)


class Own:
    """A motion on its own clock: `key` what determines it (hashable; None when the trajectory
    gives none); `times` (N,) from 0 every 4 ms, then its duration; `joints` (N, axes) there;
    `q_at(t)` the joints at any time of it (`q_at.many(ts)` at many). The samples are computed
    when first asked for (a check found by its key needs none), and so is `q_at` when `make_q_at`
    gives it."""

    __slots__ = ("_duration", "_joints", "_make", "_q_at", "_times", "key")

    def __init__(self, key: tuple | None, duration: float, q_at: Callable | None = None,
                 make_q_at: Callable[[], Callable] | None = None) -> None:
        self.key = key
        self._q_at = q_at
        self._make = make_q_at
        self._duration = duration
        self._times: np.ndarray | None = None
        self._joints: np.ndarray | None = None

    @property
    def q_at(self) -> Callable:
        if self._q_at is None:
            self._q_at = self._make()
        return self._q_at

    @property
    def times(self) -> np.ndarray:
        if self._times is None:
            self._times = own_times(self._duration)
        return self._times

    @property
    def joints(self) -> np.ndarray:
        if self._joints is None:
            self._joints = np.asarray(self.q_at.many(self.times), dtype=float)
        return self._joints


def own_times(duration: float) -> np.ndarray:
    """0, 4 ms, 8 ms, ... and `duration` (the last tick dropped when it is within 1 ns of it)."""
    n = max(math.floor(duration / TICK + 1e-6), 0)
    times = np.arange(n + 1) * TICK
    if duration - times[-1] > Q_T:
        times = np.append(times, duration)
    elif n > 0:
        times[-1] = duration
    return times


def own_clock(traj, start: float, end: float) -> Own:
    """The motion of `traj` from `start` to `end` (s, on the run's clock) on its own clock."""
    # exactly the queue's trajectory: a subclass (arm_layers.ActualTrajectory) moves the arm off it
    if type(traj) is Trajectory and traj.path.spans:
        return _keyed(traj, start, end)

    def q_at(t: float):
        return traj.position(start + t)

    q_at.many = lambda ts: traj.positions(start + np.asarray(ts, dtype=float))
    return Own(None, max(end - start, 0.0), q_at)


def own_clocks(traj, windows: Iterable[tuple[float, float]]) -> Iterator[Own]:
    """`own_clock(traj, start, end)` of each (start, end) of `windows`, in order: the keys of
    BLOCK motions computed at once, the same numbers (the same operations, element by element).
    `windows` is read a block at a time (a long run has many motions)."""
    if not (type(traj) is Trajectory and traj.path.spans and len(traj.profile.T) >= 2):
        for start, end in windows:
            yield own_clock(traj, start, end)
        return
    it = iter(windows)
    while block := list(itertools.islice(it, BLOCK)):
        yield from _block(traj, block)


def _block(traj: Trajectory, windows: list[tuple[float, float]]) -> Iterator[Own]:
    prof, path = traj.profile, traj.path
    w = np.array(windows, dtype=float).reshape(-1, 2)
    starts, ends = w[:, 0].copy(), w[:, 1].copy()
    # only the breakpoints around the block's motions, from a to b (the profile holds the whole run):
    # those before a are at or before every time asked, those from b on after every one
    n = len(prof.T)
    a = max(bisect_right(prof.T, float(min(starts.min(), ends.min()))) - 1, 0)
    b = min(bisect_right(prof.T, float(max(starts.max(), ends.max()))) + 1, n)
    a = min(a, max(b - 2, 0))  # at least two of them
    b = max(b, min(a + 2, n))
    T, S, SD = window(prof.T, a, b), window(prof.S, a, b), window(prof.SD, a, b)
    head = (prof.T[0], prof.S[0])
    s0, sd0 = _states(T, S, SD, starts, head, b == n)
    s1, sd1 = _states(T, S, SD, ends, head, b == n)
    i0, base = _locate(path, s0)
    i1, _ = _locate(path, s1)
    lo = np.searchsorted(T, starts, side="right") + a  # bisect_right, bisect_left from lo: as _keyed
    hi = np.maximum(np.searchsorted(T, ends, side="left") + a, lo)
    # each motion's rows [start, T[lo:hi], end] (and S, SD) end to end in one array
    count = hi - lo + 2
    first = np.cumsum(count) - count
    last = first + count - 1
    seg = np.repeat(np.arange(len(w)), count)
    src = np.clip(lo[seg] + (np.arange(len(seg)) - first[seg]) - 1 - a, 0, len(T) - 1)
    rows = np.stack([T[src], S[src], SD[src]])
    del T, S, SD  # views of the profile's arrays: dropped at once
    rows[:, first] = starts, s0, sd0
    rows[:, last] = ends, s1, sd1
    rows[0] -= starts[seg]
    rows[1] -= base[seg]
    rows /= _QUANTA
    # a motion's rows end to end in one buffer (time, position, speed per breakpoint): its key is a
    # slice of the bytes, made with none of the arrays of one motion
    k = np.ascontiguousarray(np.rint(rows, out=rows).astype(np.int64).T)
    raw = k.tobytes()
    size = k.itemsize * 3
    duration = (k[last, 0] * Q_T).tolist()
    spans = path.spans
    for a, z, j0, j1, d in zip(first.tolist(), last.tolist(), i0.tolist(), i1.tolist(), duration):
        sp = spans[j0:j1 + 1]
        yield Own((tuple([(x.geom, x.a, x.b) for x in sp]), raw[a * size:(z + 1) * size]), d,
                  make_q_at=functools.partial(_q_at_rows, sp, k, a, z + 1))


def _states(T: np.ndarray, S: np.ndarray, SD: np.ndarray, t: np.ndarray, head: tuple | None = None,
            at_end: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """`Profile.state`'s (s, ṡ) at many times: its cases in its order and its arithmetic, element by
    element, so the same numbers. T, S, SD: at least two breakpoints, every time asked at or after
    the first unless it is the profile's first (`head`: the profile's first time and position);
    `at_end`: the last is the profile's last (else every time asked is before it)."""
    T0, S0 = (T[0], S[0]) if head is None else head
    n = len(T)
    k = np.searchsorted(T, t, side="right") - 1
    k0 = np.clip(k, 0, n - 2)
    k1 = k0 + 1
    dt = T[k1] - T[k0]
    sd0 = SD[k0]
    with np.errstate(divide="ignore", invalid="ignore"):
        u = (SD[k1] - sd0) / dt
        tau = t - T[k0]
        s = S[k0] + sd0 * tau + 0.5 * u * tau * tau
        sd = sd0 + u * tau
    flat = dt <= 0.0
    s, sd = np.where(flat, S[k1], s), np.where(flat, SD[k1], sd)
    if at_end:
        end = k >= n - 1
        s, sd = np.where(end, S[-1], s), np.where(end, 0.0, sd)
    before = t <= T0
    return np.where(before, S0, s), np.where(before, 0.0, sd)


def _locate(path: Path, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """`Path.locate`'s span index at many positions, and the offset of each span found."""
    offsets = path.offsets
    a = max(bisect.bisect_right(offsets, float(s.min())) - 1, 0)
    b = bisect.bisect_right(offsets, float(s.max()))
    near = np.asarray(offsets[a:max(b, a + 1)], dtype=float)
    i = np.clip(np.searchsorted(near, s, side="right") - 1 + a, 0, len(path.spans) - 1)
    return i, np.asarray([offsets[j] for j in i.tolist()], dtype=float)


def _keyed(traj: Trajectory, start: float, end: float) -> Own:
    prof, path = traj.profile, traj.path
    s0, sd0, _ = prof.state(start)
    s1, sd1, _ = prof.state(end)
    i0, _ = path.locate(s0)
    i1, _ = path.locate(s1)
    lo = bisect_right(prof.T, start)  # the profile holds the whole run: no array of it
    hi = bisect_left(prof.T, end, lo)
    # the three rows at once, filled from views of the profile, each shifted and rounded as it was
    # alone (the same operations, element by element: x - 0.0 is x, so the speeds are not shifted)
    rows = np.empty((3, hi - lo + 2))
    rows[:, 0] = start, s0, sd0
    rows[:, -1] = end, s1, sd1
    rows[0, 1:-1] = window(prof.T, lo, hi)
    rows[1, 1:-1] = window(prof.S, lo, hi)
    rows[2, 1:-1] = window(prof.SD, lo, hi)
    rows[0] -= start
    rows[1] -= path.offsets[i0]
    rows /= _QUANTA
    return _own(path.spans[i0:i1 + 1], np.rint(rows, out=rows).astype(np.int64))


def _own(spans: list, k: np.ndarray) -> Own:
    """The motion along `spans` (laid end to end from 0) by its profile `k` (3, N): times,
    positions and speeds in Q_T, Q_S and Q_SD (the key holds them breakpoint by breakpoint, as
    `_block` makes it)."""
    key = (tuple([(sp.geom, sp.a, sp.b) for sp in spans]), np.ascontiguousarray(k.T).tobytes())
    return Own(key, float(k[0, -1] * Q_T), make_q_at=lambda: _q_at(spans, k))


def _q_at_rows(spans: list, k: np.ndarray, a: int, z: int) -> Callable:
    """`_q_at` of the breakpoints a to z of `k` (N, 3), `_block`'s rows."""
    return _q_at(spans, k[a:z].T)


def _q_at(spans: list, k: np.ndarray) -> Callable:
    kt, ks, ksd = k
    own: list[Trajectory] = []  # built from the key when first needed

    def at(ts):
        if not own:
            own.append(_trajectory(spans, kt * Q_T, ks * Q_S, ksd * Q_SD))
        return own[0].positions(ts)

    def q_at(t: float):  # one time (between two samples): `at`'s numbers without its arrays
        if not own:
            own.append(_trajectory(spans, kt * Q_T, ks * Q_S, ksd * Q_SD))
        return own[0].path.q(np.array([_s_at(own[0].profile, float(t))]))[0]

    q_at.many = at
    return q_at


def _s_at(prof: Profile, t: float) -> float:
    """`Profile.states`' path position at one time: its cases and its arithmetic on floats, so the
    same bits (a motion's profile here is lists: `_trajectory`)."""
    T, S, SD = prof.T, prof.S, prof.SD
    if t <= T[0]:
        return S[0]
    j = bisect.bisect_right(T, t)
    if j >= len(T):
        return S[-1]
    k = j - 1
    dt = T[j] - T[k]
    u = (SD[j] - SD[k]) / dt if dt > 0 else 0.0
    tau = max(t - T[k], 0.0)
    return S[k] + SD[k] * tau + 0.5 * u * tau * tau


class Positions:
    """`traj.position(t)` (the arm's joints at a gripper event), each computed once per what
    determines it: the path's span there (its geometry, by identity, and its ends) and the
    position along it, as `Path.q` clips it. A cyclic program opens and closes its grippers at
    a few places, at other times and path positions each cycle. A trajectory of another kind is
    asked every time."""

    def __init__(self, traj, size: int = 1024) -> None:
        self.traj = traj
        self.keyed = type(traj) is Trajectory
        self.size = size
        self.memo: dict[tuple, tuple] = {}  # key -> (the geometry, held: its id is not given again; the joints)
        self.hits = 0

    def each(self, times: Iterable[float]) -> Iterator[np.ndarray]:
        """`self(t)` for each t of `times` (in any order), the path positions of BLOCK of them
        computed at once (`_states`: Profile.state's numbers)."""
        prof = self.traj.profile
        if not (self.keyed and self.traj.path.spans and len(prof.T) >= 2):
            yield from map(self, times)
            return
        it = iter(times)
        while block := list(itertools.islice(it, BLOCK)):
            t = np.array(block, dtype=float)
            n = len(prof.T)
            a = max(bisect_right(prof.T, float(t.min())) - 1, 0)
            b = min(bisect_right(prof.T, float(t.max())) + 1, n)
            a = min(a, max(b - 2, 0))  # at least two breakpoints, as `_block`
            b = max(b, min(a + 2, n))
            s, _ = _states(window(prof.T, a, b), window(prof.S, a, b), window(prof.SD, a, b), t,
                           (prof.T[0], prof.S[0]), b == n)
            for tk, sk in zip(block, s.tolist()):
                yield self(tk, sk)

    def __call__(self, t: float, s: float | None = None) -> np.ndarray:
        """The joints at `t`; `s`: the path position there when known (Profile.state's)."""
        traj = self.traj
        path = traj.path
        if not self.keyed or not path.spans:
            return traj.position(t)
        if s is None:
            s, _, _ = traj.profile.state(t)
        i, sigma = path.locate(s)
        sp = path.spans[i]
        key = (id(sp.geom), sp.a, sp.b, min(max(sigma, 0.0), sp.length))
        hit = self.memo.get(key)
        if hit is not None:
            self.hits += 1
            return hit[1].copy()
        q = traj.position(t)
        if len(self.memo) >= self.size:
            self.memo.clear()  # bounded: a cyclic program fills it again within a cycle
        self.memo[key] = (sp.geom, q.copy())
        return q


def _trajectory(spans, T: np.ndarray, S: np.ndarray, SD: np.ndarray) -> Trajectory:
    """The spans laid end to end from 0, along the profile (T, S, SD) from time 0."""
    path = Path(spans[0].q([0.0])[0])
    offsets = np.concatenate(([0.0], np.cumsum([sp.length for sp in spans])))
    path.spans = list(spans)  # the spans themselves are shared, never changed (Path.append would set their offset)
    path.offsets = offsets[:-1].tolist()
    path.end = float(offsets[-1])
    path.q_rest = spans[-1].q([spans[-1].length])[0]
    prof = Profile(float(S[0]), 0.0)
    prof.T, prof.S, prof.SD = T.tolist(), S.tolist(), np.maximum(SD, 0.0).tolist()
    return Trajectory(path, prof)
