"""What the arm does on top of its motion queue's trajectory (chapter 11): the layers between the
queue's nominal trajectory and the arm's actual commanded position.

    layers = Layers(axes)
    layers.warp        # queue time as a function of real time: compliant moves hold or go back (11.1)
    layers.turns       # whole turns taken off the continuous axis from a given time (resetTurn, 11.5)
    layers.altered     # joint offsets on the 4 ms setpoints (ALTER, 11.2), a source set by alteration.py
    layers.actual(trajectory, t)              # the arm's joints at real time t
    ActualTrajectory(trajectory, layers)      # the same as a trajectory, for the run's record

The motion queue (motion/queue.py) plans and times the nominal path and knows nothing of these:
it is told queue times (`queue_time`), and what it plans is read through them. Without any of
them (`trivial`) the arm is the queue's trajectory, exactly.
"""

from __future__ import annotations

import bisect
import math
from typing import Any

import numpy as np

from ..motion.trajectory import Trajectory, tick_times

US = 1_000_000


class Warp:
    """Queue time τ over real time t: pieces from T[i] with τ = TAU[i] + R[i]·(t - T[i]), R in
    {1, 0, -1} (the arm follows its path, holds, or goes back along it). Identity at first."""

    def __init__(self) -> None:
        self.T = [0.0]
        self.TAU = [0.0]
        self.R = [1]
        self.max_tau = [0.0]  # the largest τ reached at each T[i] (queue calls never go back)

    @property
    def identity(self) -> bool:
        return len(self.T) == 1

    def _piece(self, t: float) -> int:
        if len(self.T) == 1:  # one piece (every run without compliance): asked at every cycle
            return 0
        return max(bisect.bisect_right(self.T, t) - 1, 0)

    def tau(self, t: float) -> float:
        """The queue time of the arm's position at real time t."""
        k = self._piece(t)
        return self.TAU[k] + self.R[k] * (t - self.T[k])

    def tau_many(self, times) -> np.ndarray:
        times = np.asarray(times, dtype=float)
        if self.identity:
            return times.copy()
        T = np.asarray(self.T)
        k = np.clip(np.searchsorted(T, times, side="right") - 1, 0, len(T) - 1)
        return np.asarray(self.TAU)[k] + np.asarray(self.R)[k] * (times - T[k])

    def rate(self, t: float) -> int:
        return self.R[self._piece(t)]

    def queue_time(self, t: float) -> float:
        """The time the motion queue is told at real time t: τ, never less than before."""
        if len(self.T) == 1 and self.R[0] == 1 and self.TAU[0] == 0.0 and self.max_tau[0] <= t:
            return t  # the identity, asked several times a cycle (0.0 + 1 * (t - 0.0) is t)
        k = self._piece(t)
        return max(self.max_tau[k], self.TAU[k] + self.R[k] * (t - self.T[k]))

    def set_rate(self, t: float, rate: int) -> None:
        """From real time t on, τ moves at `rate`."""
        if rate == self.rate(t) and t >= self.T[-1]:
            return
        tau = self.tau(t)
        k = self._piece(t)
        reached = max(self.max_tau[k], tau)
        del self.T[k + 1:], self.TAU[k + 1:], self.R[k + 1:], self.max_tau[k + 1:]
        if t <= self.T[k]:
            self.TAU[k], self.R[k], self.max_tau[k] = tau, rate, reached
            return
        self.T.append(t)
        self.TAU.append(tau)
        self.R.append(rate)
        self.max_tau.append(reached)

    def jump(self, t: float, tau: float, rate: int = 1) -> None:
        """From real time t on, τ goes on from `tau` (a reset skips the braking of a held arm: the
        position is kept by a residual offset)."""
        self.set_rate(t, rate)
        k = self._piece(t)
        if self.T[k] < t:
            self.T.append(t)
            self.TAU.append(tau)
            self.R.append(rate)
            self.max_tau.append(max(self.max_tau[k], tau))
        else:
            self.TAU[k] = tau
            self.max_tau[k] = max(self.max_tau[k], tau)

    def real_time(self, tau: float) -> float | None:
        """The first real time at which τ reaches `tau` (None when it has not, as planned so far:
        the last piece goes on at its rate)."""
        for i in range(len(self.T)):
            t0, a, r = self.T[i], self.TAU[i], self.R[i]
            t1 = self.T[i + 1] if i + 1 < len(self.T) else math.inf
            if a >= tau - 1e-12:
                return t0
            if r > 0:
                t = t0 + (tau - a)
                if t <= t1:
                    return t
        return None


    def leaving_time(self, tau: float) -> float | None:
        """The real time at which the arm leaves queue time `tau` for good (the end of a hold
        there): the last time τ ≤ tau. None when it holds at or before it still."""
        last = None
        n = len(self.T)
        for i in range(n):
            t0, a, r = self.T[i], self.TAU[i], self.R[i]
            t1 = self.T[i + 1] if i + 1 < n else math.inf
            end = a + r * (t1 - t0) if t1 < math.inf else None
            if r > 0:
                if a <= tau + 1e-12:
                    last = min(t0 + (tau - a), t1)
            elif a <= tau + 1e-12 or (end is not None and end <= tau + 1e-12) or (end is None and r < 0):
                if t1 == math.inf:
                    return None
                last = t1
        return last


class Offsets:
    """Joint offsets by whole turns (resetTurn): `values[i]` from `times[i]` on."""

    def __init__(self, axes: int) -> None:
        self.times: list[float] = []
        self.values: list[np.ndarray] = []
        self.zero = np.zeros(axes)

    def at(self, t: float) -> np.ndarray:
        k = bisect.bisect_right(self.times, t) - 1
        return self.zero if k < 0 else self.values[k]

    def at_many(self, times) -> np.ndarray:
        times = np.asarray(times, dtype=float)
        out = np.tile(self.zero, (len(times), 1))
        for t0, v in zip(self.times, self.values):
            out[times >= t0] = v
        return out

    @property
    def latest(self) -> np.ndarray:
        return self.values[-1] if self.values else self.zero

    def add(self, t: float, delta: np.ndarray) -> None:
        self.times.append(t)
        self.values.append(self.latest + delta)


class Residuals:
    """Joint offsets left when a layer lets go of the arm (a reset of a held arm, the end of an
    alteration): `delta` from `t` on, decreasing to 0 along the next command recorded after it (by
    its path fraction): the arm goes from where it is to that command's target."""

    def __init__(self) -> None:
        self.items: list[tuple[float, np.ndarray, int]] = []  # (from t, delta, index in the queue's history)

    def add(self, t: float, delta: np.ndarray, index: int) -> None:
        while self.items and self.items[-1][0] >= t:
            self.items.pop()
        self.items.append((t, np.asarray(delta, dtype=float), index))

    def _decay(self, queue: Any, index: int) -> tuple[float, float] | None:
        """(s where it starts decaying, s where it is gone): the next command's part of the path."""
        for command in queue.history[index:]:
            place = command.placement
            if command.state in ("failed", "cancelled") or place.s_begin is None:
                continue
            end = place.s_end if place.s_end is not None else place.s_provisional
            return place.s_begin, end if end is not None else place.s_begin
        return None

    def at_many(self, queue: Any, times: np.ndarray, taus: np.ndarray, axes: int) -> np.ndarray:
        out = np.zeros((len(times), axes))
        if not self.items or queue is None:
            return out
        s = None
        starts = [it[0] for it in self.items]
        k = np.searchsorted(np.asarray(starts), times, side="right") - 1
        for i, (t0, delta, index) in enumerate(self.items):
            sel = k == i
            if not np.any(sel):
                continue
            window = self._decay(queue, index)
            if window is None:
                out[sel] = delta
                continue
            if s is None:
                s = queue.profile.states(taus)[0]
            a, b = window
            f = np.clip((s[sel] - a) / (b - a), 0.0, 1.0) if b > a else (s[sel] >= a).astype(float)
            out[sel] = (1.0 - f)[:, None] * delta
        return out


class Layers:
    """The layers of one arm (see the module docstring). `altered`: None, or an object with
    `offset_many(times)`, `rate(t)` (joint offsets and their speed, model units) and `moving()`
    (intervals where the offset changes). `residuals`: what a layer left when it let go.
    `hooks`: objects with `before(t)` (bring their state up to real time t before the program
    acts on the queue) and `after_reset(t, actual)` (the queue was reset at t; `actual` the arm's
    joints just before)."""

    def __init__(self, axes: int) -> None:
        self.axes = axes
        self.warp = Warp()
        self.turns = Offsets(axes)
        self.residuals = Residuals()
        self.altered: Any = None
        self.queue: Any = None
        self.hooks: list[Any] = []

    @property
    def trivial(self) -> bool:
        return self.warp.identity and not self.turns.times and self.altered is None and not self.residuals.items

    def before(self, t: float) -> None:
        for h in self.hooks:
            h.before(t)

    def after_reset(self, t: float, actual: np.ndarray) -> None:
        """The queue was reset at real time t: a held arm stays where it is (its braking is skipped),
        the layers let go, what is left of their offsets decays along the next command."""
        q = self.queue
        if self.warp.rate(t) == 0:  # held: it stopped at once, the queue's braking is not the arm's
            self.warp.jump(t, q.profile.t_end)
        for h in self.hooks:
            h.after_reset(t)
        nominal = q.trajectory.position(self.warp.tau(t))
        self.residuals.add(t, actual - self.turns.at(t) - nominal, len(q.history))

    def queue_time(self, t: float) -> float:
        return self.warp.queue_time(t)

    def offset(self, t: float) -> np.ndarray:
        return self.offset_many(np.array([t]))[0]

    def offset_many(self, times) -> np.ndarray:
        times = np.asarray(times, dtype=float)
        out = self.turns.at_many(times)
        if self.altered is not None:
            out = out + self.altered.offset_many(times)
        if self.residuals.items:
            out = out + self.residuals.at_many(self.queue, times, self.warp.tau_many(times), self.axes)
        return out

    def actual(self, trajectory: Trajectory, t: float) -> np.ndarray:
        """The arm's joints at real time t (model units)."""
        if self.trivial:
            return trajectory.position(t)
        return trajectory.position(self.warp.tau(t)) + self.offset(t)


class ActualTrajectory(Trajectory):
    """The arm's trajectory as it moves (the layers applied), with the nominal trajectory's
    interface (arm_record.JointTrajectory): what the run's record, its reports and the collision
    checks read."""

    def __init__(self, nominal: Trajectory, layers: Layers) -> None:
        super().__init__(nominal.path, nominal.profile)
        self.nominal = nominal
        self.layers = layers

    def position(self, t: float) -> np.ndarray:
        return self.layers.actual(self.nominal, t)

    def positions(self, times) -> np.ndarray:
        times = np.asarray(times, dtype=float)
        lay = self.layers
        return self.nominal.positions(lay.warp.tau_many(times)) + lay.offset_many(times)

    def velocity(self, t: float) -> np.ndarray:
        lay = self.layers
        v = self.nominal.velocity(lay.warp.tau(t)) * lay.warp.rate(t)
        if lay.altered is not None:
            v = v + lay.altered.rate(t)
        return v

    def sample(self, t0: float, t1: float, dt: float = 0.004):
        times = tick_times(t0, t1, dt)
        if len(times) == 0:
            n = len(self.path.q_rest)
            return times, np.zeros((0, n)), np.zeros((0, n))
        return times, self.positions(times), np.array([self.velocity(t) for t in times])

    def moving(self, t_end: float) -> list[tuple[float, float]]:
        """Where the nominal motion runs (in real time) or the alteration changes."""
        warp = self.layers.warp
        spans = []
        for a, b in self.nominal.moving(math.inf):
            ra, rb = warp.real_time(a), warp.real_time(b)
            if ra is None:
                continue
            spans.append((ra, t_end if rb is None else rb))
        if not warp.identity:  # going back along the path: a motion too
            for i, r in enumerate(warp.R):
                if r < 0:
                    spans.append((warp.T[i], warp.T[i + 1] if i + 1 < len(warp.T) else t_end))
        if self.layers.altered is not None:
            spans.extend(self.layers.altered.moving())
        out: list[tuple[float, float]] = []
        for a, b in sorted((a, min(b, t_end)) for a, b in spans if a < t_end):
            if out and a <= out[-1][1] + 1e-12:
                out[-1] = (out[-1][0], max(out[-1][1], b))
            else:
                out.append((a, b))
        return out


class QueueView:
    """The motion queue as the chapter 10 handlers use it (`MovingArm.sync`), told queue times
    for real ones when a layer holds the arm (the handlers pass seconds of real time)."""

    _TIMED = frozenset({"is_settled", "stop_move", "restart_move", "get_speed", "get_move_id", "position",
                        "velocity", "acceleration", "joint_force", "is_empty", "end_time", "wait_end_move", "advance",
                        "reset_motion"})

    def __init__(self, queue: Any, layers: Layers) -> None:
        object.__setattr__(self, "_queue", queue)
        object.__setattr__(self, "_layers", layers)

    def __getattr__(self, name: str) -> Any:
        attr = getattr(self._queue, name)
        if name not in self._TIMED:
            return attr
        layers = self._layers

        def timed(*args, **kw):
            args = list(args)
            i = 1 if name == "get_speed" else 0
            t = args[i] if len(args) > i else None
            if t is not None:
                layers.before(t)
                args[i] = layers.queue_time(t)
            if name != "reset_motion" or t is None:
                return attr(*args, **kw)
            actual = layers.actual(self._queue.trajectory, t)
            out = attr(*args, **kw)
            layers.after_reset(t, actual)
            return out

        return timed

    def __setattr__(self, name: str, value: Any) -> None:
        setattr(self._queue, name, value)
