"""A motion on its own clock (issue 29; docs/cell.md, "How checks are sampled"): the part of the
run's trajectory between a motion's start and its end, expressed from time 0 and path position
0, with a key made of everything that determines it, so that the collision checks of a motion
that repeats exactly are computed once.

    own = own_clock(trajectory, start, end)   # -> Own: times from 0 every 4 ms and the end,
                                              #    joints there, q_at(t) between, key (or None)

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

import math
from collections.abc import Callable

import numpy as np

from ..interpretation.clock import TICK_US
from ..motion.paths import Path
from ..motion.trajectory import Profile, Trajectory, bisect_left, bisect_right

TICK = TICK_US / 1_000_000
Q_T = 1e-9  # s: the profile's times within the motion
Q_S = 1e-7  # path units (degrees of joint motion): positions along the motion's path
Q_SD = 1e-7  # path units per second: path speeds
_QUANTA = np.array([[Q_T], [Q_S], [Q_SD]])


class Own:
    """A motion on its own clock: `key` what determines it (hashable; None when the trajectory
    gives none); `times` (N,) from 0 every 4 ms, then its duration; `joints` (N, axes) there;
    `q_at(t)` the joints at any time of it (`q_at.many(ts)` at many). The samples are computed
    when first asked for (a check found by its key needs none)."""

    def __init__(self, key: tuple | None, duration: float, q_at: Callable) -> None:
        self.key = key
        self.q_at = q_at
        self._duration = duration
        self._times: np.ndarray | None = None
        self._joints: np.ndarray | None = None

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


def _keyed(traj: Trajectory, start: float, end: float) -> Own:
    prof, path = traj.profile, traj.path
    s0, sd0, _ = prof.state(start)
    s1, sd1, _ = prof.state(end)
    i0, _ = path.locate(s0)
    i1, _ = path.locate(s1)
    spans = path.spans[i0:i1 + 1]
    base = path.offsets[i0]
    lo = bisect_right(prof.T, start)  # the profile holds the whole run: no array of it
    hi = bisect_left(prof.T, end, lo)
    # the three rows at once, each shifted and rounded as it was alone (the same operations, element by element)
    rows = np.array([[start, *prof.T[lo:hi], end], [s0, *prof.S[lo:hi], s1], [sd0, *prof.SD[lo:hi], sd1]])
    k = np.rint((rows - np.array([[start], [base], [0.0]])) / _QUANTA).astype(np.int64)
    kt, ks, ksd = k
    key = (tuple([(sp.geom, sp.a, sp.b) for sp in spans]), k.tobytes())
    own: list[Trajectory] = []  # built from the key when first needed

    def at(ts):
        if not own:
            own.append(_trajectory(spans, kt * Q_T, ks * Q_S, ksd * Q_SD))
        return own[0].positions(ts)

    def q_at(t: float):
        return at(np.array([t], dtype=float))[0]

    q_at.many = at
    return Own(key, float(kt[-1] * Q_T), q_at)


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
