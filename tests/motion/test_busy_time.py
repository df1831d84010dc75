"""`motion_records.busy_time` read block by block (issue 29): the same bits as the running sum over
every interval of the profile it replaced, whatever the block and wherever the run ends."""

from __future__ import annotations

import random

import numpy as np
import pytest

from val3check.motion import motion_records
from val3check.motion.trajectory import Profile


def _loop(profile, t_end):
    """The running sum, one interval at a time (the former busy_time)."""
    T, SD = profile.T, profile.SD
    busy = 0.0
    for i in range(len(T) - 1):
        if T[i] >= t_end:
            break
        if SD[i] > 0 or SD[i + 1] > 0:
            busy += min(T[i + 1], t_end) - T[i]
    return busy, max(t_end - busy, 0.0)


@pytest.mark.parametrize("block", [1, 2, 3, 7, 1 << 16])
def test_busy_time_by_blocks_is_the_running_sum(monkeypatch, block):
    monkeypatch.setattr(motion_records, "_BUSY_BLOCK", block)
    rng = random.Random(block)
    for trial in range(60):
        prof = Profile(0.0, 0.0)
        for k in range(rng.randint(0, 30)):
            n = rng.randint(2, 40)
            g = np.random.default_rng(1000 * trial + k)
            s = np.cumsum(np.r_[prof.S[-1], g.random(n - 1)])
            sd = np.r_[0.0, g.random(n - 2) + 0.1, 0.0]
            prof.append(prof.t_end + rng.choice([0.0, 0.3]), s, sd)  # motions, some after a rest
        for t_end in (0.0, prof.t_end * rng.random(), prof.t_end, prof.t_end + 1.0, float(prof.T[len(prof.T) // 2])):
            got = motion_records.busy_time(prof, t_end)
            assert [x.hex() for x in got] == [x.hex() for x in _loop(prof, t_end)]
