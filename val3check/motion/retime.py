"""The run's motions re-timed with every acceleration and deceleration scaled (issue 23): what the
cycle time would be if the accelerations the model assumes were off by that factor.

Stäubli publishes no joint accelerations: where the model assumes them (RobotModel.accelerations_
assumed), the reports give the cycle time with the range it takes for accelerations half and twice
the assumption (robot.models.ASSUMED_ACCELERATION_RANGE). The same geometric path is timed again,
piece by piece between the arm's stops, with the scaled limits (cheap: the path is already
sampled, and a cyclic program times the same pieces again and again); the arm's rests keep their
length (the program waits as long for its inputs, grippers and delays); every time of the run
moves with the motions before it. The motion records of the re-timed run are the run's with their
start and end moved, so that the cycles are found exactly as in the run (cycle.cycle_stats).

    records_if = retimed(queue, records, 2.0)    # MotionRecords of the run with accelerations × 2
"""

from __future__ import annotations

import bisect
from dataclasses import replace

from .mdesc import Limits
from .trajectory import Profile


class Retiming:
    """The run's profile re-timed piece by piece (module docstring): `time(t)` maps a time of the
    run to the same point of the re-timed run."""

    def __init__(self, queue, factor: float) -> None:
        """The moving stretches of `queue`'s profile (from a rest to the next), each timed again
        with accelerations and decelerations × `factor`."""
        planner = queue.planner
        planner.flush()
        prof = planner.profile
        limits = queue.limits.of

        def scaled(key: int) -> Limits:
            lim = limits(key)
            return Limits(lim.V, lim.A * factor, lim.D * factor, lim.tvel, lim.rvel)

        self.profile = prof
        self.starts: list[float] = []  # run time at the start of each moving stretch
        self.ends: list[float] = []
        self.new_starts: list[float] = []
        self.pieces: list[Profile] = []
        shift = 0.0
        T, S, SD = prof.T, prof.S, prof.SD
        i, n = 0, len(T)
        while i < n - 1:
            if SD[i + 1] <= 0.0 and S[i + 1] <= S[i]:
                i += 1
                continue
            j = i + 1
            while j < n - 1 and SD[j] > 0.0:
                j += 1
            piece = planner.timing.time(planner.path, S[i], S[j], 0.0, scaled)
            p = Profile(S[i], 0.0)
            p.append(0.0, piece.s, piece.sd)
            self.starts.append(T[i])
            self.ends.append(T[j])
            self.new_starts.append(T[i] + shift)
            self.pieces.append(p)
            shift += p.t_end - (T[j] - T[i])
            i = j
        self.shift_end = shift

    def time(self, t: float | None) -> float | None:
        """The time of the re-timed run at the point the run reached at time t."""
        if t is None:
            return None
        k = bisect.bisect_right(self.starts, t) - 1
        if k < 0:
            return t
        if t >= self.ends[k]:  # at rest after stretch k
            return t + (self.new_starts[k] - self.starts[k]) + self.pieces[k].t_end - (self.ends[k] - self.starts[k])
        s, _, _ = self.profile.state(t)
        at = self.pieces[k].time_at(s)
        return self.new_starts[k] + (at if at is not None else self.pieces[k].t_end)


def retimed(queue, records: list, factor: float) -> list:
    """The motion records (records.MotionRecord) of the run re-timed with accelerations × factor:
    the same records, their start and end moved (module docstring)."""
    rt = Retiming(queue, factor)
    return [replace(r, start=rt.time(r.start), end=rt.time(r.end)) for r in records]
