"""The trajectory of a run's page, sampled on the page's clock (from_run.sample_period) a block of
samples at a time, so that what the page holds does not grow with the run:

    tr = series_model(m, dt, n)   # the model's series: one array('d') each, filled block by block
    p = packed(m, dt, n)          # the page's data (series.Packed): each block reduced to the page's
                                  # min/max buckets and dropped; the full-rate series never held

A block is a whole number of the page's buckets (pack.py), at most BLOCK_SAMPLES samples and
BLOCK_S seconds of the run: sampling copies the profile's breakpoints of its window, and an
8-hour profile's are about 94 MB. A tick's time is k·dt whatever the call, and each sample is
computed alone (motion/trajectory.py, simulation/arm_record.tcp_speed): the blocks give the
values, to the bit, of one sample of the whole run.
"""

from __future__ import annotations

import math
from typing import Any

from .series import Packed, rounded


def joints(scene: Any) -> list[dict]:
    return [{"name": n, "unit": u, "min": lo, "max": hi, "speed": s}
            for n, u, (lo, hi), s in zip(scene.joint_names, scene.joint_units, scene.joint_limits,
                                         scene.nominal_speeds)]


def series_model(m: Any, dt: float, n: int) -> dict:
    """The model's trajectory: its series joined from the blocks, one array('d') each."""
    from array import array

    times, speed = array("d"), array("d")
    positions: list[array] = []
    velocities: list[array] = []
    for t, q, v, sp in _blocks(m, dt, n, 1):
        if not positions:
            positions, velocities = [array("d") for _ in q], [array("d") for _ in v]
        times.frombytes(t.tobytes())
        speed.frombytes(sp.tobytes())
        for row, a in zip(q, positions):
            a.frombytes(row.tobytes())
        for row, a in zip(v, velocities):
            a.frombytes(row.tobytes())
    return {"joints": joints(m.scene), "times": times, "positions": positions, "velocities": velocities,
            "tcp_speed": speed}


def packed(m: Any, dt: float, n: int) -> Any:
    """The page's trajectory (series.Packed) of `n` samples every `dt` from 0, made block by block:
    no series of the run held whole. None: a value check_model would refuse."""
    from .pack import _bucket, _packed

    named = joints(m.scene)
    try:
        return Packed(named, n, _packed(named, n, _checked(_blocks(m, dt, n, _bucket(n)))))
    except _Refused:
        return None


class _Refused(Exception):
    pass


def _checked(blocks):
    """The blocks, each checked as check_model checks a trajectory: finite, times not decreasing."""
    import numpy as np

    last = -math.inf
    for block in blocks:
        times = block[0]
        if not (all(np.isfinite(a).all() for a in block) and (times[1:] >= times[:-1]).all() and times[0] >= last):
            raise _Refused
        last = times[-1]
        yield block


BLOCK_SAMPLES = 16_384  # samples of the page's trajectory made at once: its temporaries bounded
BLOCK_S = 600.0  # and at most this much of the run: a sample copies the profile's breakpoints around its times


def _blocks(m: Any, dt: float, n: int, size: int):
    """The samples 0..n-1 (every dt from 0) as the page's series, a block at a time: times (b,),
    positions and velocities (axes, b), TCP speed (b,), rounded. Each block a whole number of
    buckets of `size` samples (the page's min/max buckets, pack.py) but the last."""

    unit = max(size, 1)
    per = max(unit, min(BLOCK_SAMPLES, int(BLOCK_S / dt)) // unit * unit)
    tcp = _TcpSpeed(m)
    for k0 in range(0, n, per):
        yield _block(m, tcp, k0, min(k0 + per, n) - 1, dt)


def _block(m: Any, tcp: Any, k0: int, k1: int, dt: float):
    """The ticks k0..k1 (a tick's time is k·dt whatever the call), rounded; the samples dropped
    on return."""
    import numpy as np

    times, q, v = m.sample(k0 * dt, k1 * dt, dt)
    times, q, v = np.asarray(times, dtype=float), np.asarray(q, dtype=float), np.asarray(v, dtype=float)
    if len(times) != k1 - k0 + 1:
        raise AssertionError(f"the trajectory's ticks {k0}..{k1} gave {len(times)} samples")
    # standing still (every joint speed 0), the TCP's two poses are the same: its speed is 0 exactly
    speed = np.zeros(len(times))
    on = np.flatnonzero((v != 0.0).any(axis=1))
    if len(on):
        speed[on] = tcp(times[on], q[on], v[on])
    return rounded(times, 6), np.round(q.T, 6) + 0.0, np.round(v.T, 4) + 0.0, np.round(speed, 3) + 0.0


class _TcpSpeed:
    """`ArmRun.tcp_speed` of the samples of a block, given only the motions whose tool they can use
    (the tool of the last motion started at or before a sample; before any, the first's), and
    computed once for each distinct (tool, joints, joint velocities): a cyclic cell passes the same
    rows cycle after cycle (at 1 h, 82,824 moving samples hold 19,922 distinct rows), and a
    sample's speed is a function of its row and its tool alone, to the bit (tcp_speed)."""

    def __init__(self, m: Any) -> None:
        import numpy as np

        self.m = m
        self.uses = [(motion.start, motion.tool_in_flange) for motion in m.motions
                     if motion.start is not None and motion.kind != "connection"]
        self.starts = np.array([t for t, _ in self.uses], dtype=float)
        self.window = bool((self.starts[1:] >= self.starts[:-1]).all())  # in order of start: a window
        # each use's tool as the number of its value (None apart), as tcp_speed tells them apart
        numbers: dict = {}
        self.tools = np.array([numbers.setdefault(None if t is None else np.asarray(t, dtype=float).tobytes(),
                                                  len(numbers)) for _, t in self.uses], dtype=float)
        self.seen = _Seen()

    def __call__(self, times, q, v):
        import numpy as np

        if not (self.window and self.uses):
            return self._speed(times, q, v)
        at = np.maximum(np.searchsorted(self.starts, times, side="right") - 1, 0)
        rows = np.ascontiguousarray(np.column_stack([self.tools[at], q, v]))
        known, todo = self.seen.split(rows)
        out = np.empty(len(times))
        out[known[0]] = known[1]
        if len(todo):
            out[todo] = self._speed(times[todo], q[todo], v[todo])
        self.seen.keep(rows, out)
        return out

    def _speed(self, times, q, v):
        import numpy as np

        from ...simulation.arm_record import tcp_speed

        uses = self.uses
        if self.window and uses:
            a = max(int(np.searchsorted(self.starts, times[0], side="right")) - 1, 0)
            b = int(np.searchsorted(self.starts, times[-1], side="right"))
            uses = uses[a:max(b, a + 1)]
        scene = self.m.scene
        return tcp_speed(scene.kinematics, scene.flange_frame, uses, times, q, v)


class _Seen:
    """The distinct rows (tool, joints, joint velocities) of the last block and their speeds: each
    row of the next block found among them or computed, once for equal rows (the first of them).
    Rows are grouped by a hash of their bits, then each compared bit for bit with its group's
    first: a row that differs (a hash collision) is computed itself."""

    def __init__(self) -> None:
        self.rows = self.speeds = None

    def split(self, rows):
        """((indices of the rows known, their speeds), indices of the rows to compute)."""
        import numpy as np

        old = 0 if self.rows is None else len(self.rows)
        both = rows if not old else np.concatenate([self.rows, rows])
        bits = both.view(np.uint64)
        _, first, inverse = np.unique(_hash(bits), return_index=True, return_inverse=True)
        self._inverse = inverse = inverse.ravel()[old:]
        source = first[inverse]  # each row's first row of its hash, in `both`
        here = np.arange(old, old + len(rows))
        differs = np.flatnonzero((bits[source] != bits[old:]).any(axis=1))
        source[differs] = here[differs]
        self._source = source = source - old  # < 0: a row of the last block
        known = np.flatnonzero(source < 0)
        return (known, self.speeds[source[known] + old] if old else np.zeros(0)), \
            np.flatnonzero(source == here - old)

    def keep(self, rows, out) -> None:
        """`out` (the speeds, known and computed) given to the rows equal to a computed one; this
        block's first row of each hash kept for the next (with its own speed)."""
        import numpy as np

        later = np.flatnonzero(self._source >= 0)
        later = later[self._source[later] != later]
        out[later] = out[self._source[later]]
        distinct = np.unique(self._inverse, return_index=True)[1]
        self.rows, self.speeds = rows[distinct], out[distinct]


def _hash(bits):
    """A 64-bit hash of each row of 64-bit words (wrapping arithmetic, column by column)."""
    import numpy as np

    h = np.zeros(len(bits), dtype=np.uint64)
    for k in range(bits.shape[1]):
        h *= np.uint64(0x9E3779B97F4A7C15)
        h ^= bits[:, k]
    return h
