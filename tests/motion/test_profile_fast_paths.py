"""trajectory.Profile's fast paths (issue 29, sixth round) against the general ones: `append` of a
motion that moves on every interval (no masks), and `time_at` / `speed_at` read in the chunk being
written, the same bits as the general formula and the general two-level bisect of a plain array."""

from __future__ import annotations

from array import array

import numpy as np
import pytest

from val3check.motion import history
from val3check.motion.history import History
from val3check.motion.trajectory import Profile

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

SETTINGS = settings(max_examples=80, derandomize=True, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def _append_reference(T: list, S: list, SD: list, t0: float, s, sd) -> None:
    """Profile.append as it was before its fast path: every interval through the masks."""
    if t0 > T[-1]:
        T.append(t0)
        S.append(S[-1])
        SD.append(0.0)
    t = T[-1]
    ds = np.diff(s)
    v = sd[:-1] + sd[1:]
    with np.errstate(divide="ignore", invalid="ignore"):
        dt = np.where(ds > 0, 2.0 * ds / np.maximum(v, 1e-300), 0.0)
    times = t + np.cumsum(dt)
    keep = ~(ds <= 0.0)
    T.extend(times[keep].tolist())
    S.extend(np.asarray(s, dtype=float)[1:][keep].tolist())
    SD.extend(np.asarray(sd, dtype=float)[1:][keep].tolist())


def _plain(p: Profile) -> Profile:
    """The same breakpoints as plain arrays: the general paths (no History, no chunk read in place)."""
    q = Profile()
    q.T, q.S, q.SD = array("d", p.T[:]), array("d", p.S[:]), array("d", p.SD[:])
    return q


MOTION = st.tuples(
    st.floats(0.0, 0.5),  # wait before it
    st.lists(st.one_of(st.just(0.0), st.floats(1e-3, 3.0)), min_size=1, max_size=12),  # ds (0: a pause)
    st.lists(st.floats(0.0, 4.0), min_size=13, max_size=13),  # speeds
)


@SETTINGS
@given(motions=st.lists(MOTION, min_size=1, max_size=14), probes=st.lists(st.floats(0.0, 1.0), max_size=12))
def test_fast_paths_give_the_general_paths_bits(motions, probes):
    old = history.CHUNK, history.KEEP, history.CACHE, history.FIRST
    history.CHUNK, history.KEEP, history.CACHE, history.FIRST = 8, 1, 1, 1  # the tail often short
    try:
        p = Profile()
        T, S, SD = [0.0], [0.0], [0.0]
        for wait, steps, speeds in motions:
            s = p.s_end + np.concatenate([[0.0], np.cumsum(steps)])
            sd = np.array(speeds[:len(s)], dtype=float)
            sd[0], sd[-1] = 0.0, 0.0
            t0 = p.t_end + wait
            p.append(t0, s, sd)
            _append_reference(T, S, SD, t0, s, sd)
            assert p.T[:].tolist() == T and p.S[:].tolist() == S and p.SD[:].tolist() == SD
            assert isinstance(p.T, History)
            q = _plain(p)
            for u in [*probes, 0.0, 1.0]:
                x = u * p.s_end
                targets = [x, *S[-6:], x + 1e-13]
                for target in targets:
                    assert p.time_at(target) == q.time_at(target)
                for until in (x, x + 0.5, p.s_end):
                    assert p.speed_at(x, until) == q.speed_at(x, until)
            assert p.time_at(p.s_end + 1.0) is None and q.time_at(p.s_end + 1.0) is None
    finally:
        history.CHUNK, history.KEEP, history.CACHE, history.FIRST = old


def test_the_fast_append_is_taken_and_matches_a_motion_with_pauses():
    """A motion moving on every interval takes the fast path; one with a pause the masks; the
    breakpoints of both are the reference's."""
    for steps in ([0.5, 1.0, 0.25], [0.5, 0.0, 0.25]):
        p = Profile()
        T, S, SD = [0.0], [0.0], [0.0]
        s = np.concatenate([[0.0], np.cumsum(steps)])
        sd = np.array([0.0, 1.5, 0.7, 0.0])
        p.append(0.25, s, sd)
        _append_reference(T, S, SD, 0.25, s, sd)
        assert p.T[:].tolist() == T and p.S[:].tolist() == S and p.SD[:].tolist() == SD
        assert len(T) == 2 + sum(1 for d in steps if d > 0)
