"""The trajectory's series as array('d') (reporting/html/series.py, issue 29): rounded as Python
rounds, checked and packed to the same bytes as lists of floats, and the TCP speed of a run's
page the same as computed at every sample."""

from __future__ import annotations

import copy
import math
import random
from array import array

import numpy as np
import pytest

from synthetic_run import synthetic_model
from val3check.reporting.html import ModelError, check_model, render
from val3check.reporting.html.pack import FULL_RATE_MAX, page_data
from val3check.reporting.html.series import doubles, rounded


def test_rounded_is_python_s_round():
    rng = random.Random(29)
    xs = [k * 0.004 for k in range(0, 7_200_001, 997)]  # the times of an 8-hour run
    xs += [rng.uniform(-1e4, 1e4) for _ in range(20_000)] + [rng.uniform(-1, 1) * 10 ** rng.randint(-12, 18)
                                                            for _ in range(20_000)]
    # halves and near-halves at 6 and 3 digits, ties in binary, zeros, huge and not finite values
    xs += [0.0000005, 0.0000015, 2.5e-6, 1.0000005, 0.0005, 0.0015, 2.675, 1.0005, -0.0000005, -0.0, 0.0,
           5e-7 + 1e-22, math.nextafter(5e-7, 1), math.nextafter(5e-7, 0), 2.0 ** 52, 2.0 ** 60, 1e300, -1e300,
           math.inf, -math.inf, 4503599627.3704995, 0.1 + 0.2,
           5.4959365, 1.2391815, 9.7037275, 235.0345, 5346.2715, 1286.5205]  # numpy's round: one digit off
    a = np.array(xs)
    assert (np.round(a[-6:], 6) != [round(x, 6) for x in xs[-6:]]).sum() >= 3  # what rounded() is for
    for digits in (6, 4, 3):
        got = rounded(a, digits).tolist()
        want = [round(x, digits) + 0.0 for x in xs]
        assert [math.copysign(1, g) for g in got] == [math.copysign(1, w) for w in want]
        assert got == want
    assert math.isnan(rounded(np.array([math.nan]), 6)[0])


def _as_arrays(model: dict) -> dict:
    m = copy.deepcopy(model)
    tr = m["trajectory"]
    tr["times"] = array("d", tr["times"])
    for key in ("positions", "velocities"):
        tr[key] = [array("d", row) for row in tr[key]]
    tr["tcp_speed"] = array("d", tr["tcp_speed"])
    return m


@pytest.mark.parametrize("reps", [1, 3])  # full rate, then min/max buckets
def test_arrays_pack_and_render_as_lists(reps):
    model = synthetic_model(duration=60.0)
    tr = model["trajectory"]
    n = len(tr["times"]) * reps
    tr["times"] = [round(k * 0.004, 6) for k in range(n)]
    for key in ("positions", "velocities"):
        tr[key] = [[-x for x in row] * reps for row in tr[key]]  # negative values too
    tr["tcp_speed"] = tr["tcp_speed"] * reps
    model["verdict"]["simulated_duration"] = tr["times"][-1]
    assert (n > FULL_RATE_MAX) == (reps > 1)
    arrays = _as_arrays(model)
    assert page_data(arrays) == page_data(model)
    assert render(arrays) == render(model)
    # a -0.0 beside 0.0 in a bucket: the first of them, as min() and max() of the list keep it
    tr["velocities"][0][:4] = [-0.0, 0.0, 0.0, -0.0]
    tr["velocities"][1][:2] = [0.0, -0.0]
    assert page_data(_as_arrays(model)) == page_data(model)


@pytest.mark.parametrize("where, value, message", [
    ("times", math.nan, "trajectory.times[7]: a finite number is expected, not nan"),
    ("times", -1.0, "trajectory.times[7]: times must not decrease"),
    ("positions", math.inf, "trajectory.positions[2][7]: a finite number is expected, not inf"),
    ("tcp_speed", math.nan, "trajectory.tcp_speed[7]: a finite number is expected, not nan"),
])
def test_arrays_are_checked_as_lists(where, value, message):
    model = synthetic_model(duration=3.0)
    arrays = _as_arrays(model)
    tr = arrays["trajectory"]
    check_model(arrays)
    (tr[where][2] if where == "positions" else tr[where])[7] = value
    with pytest.raises(ModelError) as e:
        check_model(arrays)
    assert message in str(e.value)
    listed = copy.deepcopy(model)
    (listed["trajectory"][where][2] if where == "positions" else listed["trajectory"][where])[7] = value
    with pytest.raises(ModelError) as f:
        check_model(listed)
    assert str(f.value) == str(e.value)


def test_the_page_s_tcp_speed_is_the_one_computed_at_every_sample():
    """The page computes the TCP's speed only where a joint moves (standing, its two poses are the
    same): the same values, to the bit, as computing it at every sample."""
    from val3check.reporting.html.from_run import model_from_run, sample_period

    from .runhelp import pickplace

    result, report = pickplace(20.0)
    m = result.motion
    tr = model_from_run(report)["trajectory"]
    times, q, v = m.sample(0.0, m.end_s, sample_period(m.end_s))
    still = ~(np.asarray(v) != 0.0).any(axis=1)
    assert 100 < still.sum() < len(times) - 100  # the run stands and moves
    full = np.round(m.tcp_speed(times, q, v), 3) + 0.0
    assert np.frombuffer(tr["tcp_speed"]).tobytes() == full.tobytes()
    assert tr["times"] == doubles([round(t, 6) + 0.0 for t in times.tolist()])
