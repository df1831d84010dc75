"""The arm along one motion: its positions at the samples and between them, the poses of its
links, and the world-aligned boxes around every body it carries at every sample.

A position along the motion is `u`, in samples: u = 2.5 is halfway between the samples 2 and 3.
Between samples the arm is on the straight joint-space segment, or at `q_at(t)` when the caller
gives the path.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from .armmodel import ArmModel
from .groups import Group


class ArmPath:
    """One motion of the arm: times (N,) in s, joints (N, axes) in VAL 3 units, q_at(t) for the
    positions between samples (or None).

    poses        {link: (N, 4, 4)} every link's pose at every sample
    box_lo, box_hi  (N, B, 3): every arm-side body's box at every sample, once `set_boxes` ran
    box_col      {id(body): its column in those boxes}"""

    def __init__(self, arm: ArmModel, times: np.ndarray, joints: np.ndarray,
                 q_at: Callable[[float], Any] | None, mids: np.ndarray | None = None) -> None:
        self.arm = arm
        self.times = times
        self.joints = joints
        self.q_at = q_at
        self._mids = mids  # q_at at mid-step, when the caller has them (`step_travel`)
        self.poses: dict[str, np.ndarray] = arm.links.poses_many(joints)
        self._between_u = -1.0  # the last position between samples computed, and its link poses
        self._between: dict[str, np.ndarray] = {}
        self.box_lo: np.ndarray | None = None
        self.box_hi: np.ndarray | None = None
        self.box_col: dict[int, int] = {}

    @property
    def last(self) -> int:
        """The index of the last sample."""
        return len(self.times) - 1

    def q(self, u: float) -> np.ndarray:
        """The joints at position u."""
        Q = self.joints
        k = int(u)
        n = len(Q) - 1
        if k >= n:
            return Q[n]
        f = u - k
        if f == 0.0:
            return Q[k]
        if self.q_at is not None:
            return np.asarray(self.q_at(self.t(u)), dtype=float)
        return Q[k] + f * (Q[k + 1] - Q[k])

    def t(self, u: float) -> float:
        """The time (s) at position u."""
        T = self.times
        k = int(u)
        n = len(T) - 1
        if k >= n:
            return float(T[n])
        return float(T[k] + (u - k) * (T[k + 1] - T[k]))

    def frame(self, link: str, u: float) -> np.ndarray:
        """A link's pose at position u (at a sample: computed for the whole motion at once)."""
        k = int(u)
        if k == u:
            return self.poses[link][k]
        if self._between_u != u:
            self._between = self.arm.links.poses(self.q(u))
            self._between_u = u
        return self._between[link]

    def place(self, g: Group, u: float) -> None:
        """Put a group's bodies where its link is at position u."""
        if g.placed == u:
            return
        frame = self.frame(g.link, u)
        for b in g.bodies:
            b.place(frame)
        g.placed = u

    def step_travel(self, per_unit: np.ndarray) -> np.ndarray:
        """Per step and joint, how much the joint may travel (rad, or mm; `per_unit`: radians or mm
        per joint unit): |Δq|, plus, with q_at, four times how far the path strays from the
        straight segment at mid-step (a parabola's detour past its ends is at most twice that)."""
        Q, T, q_at = self.joints, self.times, self.q_at
        if len(Q) < 2:
            return np.zeros((0, Q.shape[1]))
        dq = np.abs(np.diff(Q, axis=0))
        if q_at is not None:
            mids = self._mids
            if mids is None:
                many = getattr(q_at, "many", None)  # positions at many times in one call, when the caller has it
                tm = mid_times(T)
                mids = (np.asarray(many(tm), dtype=float) if many is not None
                        else np.array([np.asarray(q_at(t), dtype=float) for t in tm]))
            dq = dq + 4.0 * np.abs(mids - 0.5 * (Q[:-1] + Q[1:]))
        return dq * per_unit

    def set_boxes(self, lo: np.ndarray, hi: np.ndarray, columns: dict[int, int]) -> None:
        """The boxes (N, B, 3) of the arm-side bodies at every sample (`bounds.prepare`)."""
        self.box_lo, self.box_hi, self.box_col = lo, hi, columns

    def body_box(self, body_id: int, k: int) -> tuple[np.ndarray, np.ndarray]:
        """The box (low, high) of an arm-side body at sample k."""
        col = self.box_col[body_id]
        return self.box_lo[k, col], self.box_hi[k, col]  # type: ignore[index]


def mid_times(times: np.ndarray) -> np.ndarray:
    """The times halfway between two samples (`ArmPath.step_travel`)."""
    return 0.5 * (times[:-1] + times[1:])


def samples_and_mids(q_at, times: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(joints at `times`, joints halfway between them) from one `q_at.many` call: the path is
    evaluated element by element, so each position has the bits two calls give (tests/collision/
    test_sweep_steps.py), and the path's spans and profile are looked up once, not twice."""
    n = len(times)
    both = np.asarray(q_at.many(np.concatenate([times, mid_times(times)])), dtype=float)
    return both[:n], both[n:]
