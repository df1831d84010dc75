"""The exact time-optimal profile of a straight joint line under one set of limits (10.3.1):
a trapezoid or a triangle in the path speed, with accel ≠ decel and from a non-zero speed when
re-timed under way. Profiles are breakpoints (s, ṡ) with a constant path acceleration between
them (`duration` is their time)."""

from __future__ import annotations

import math

import numpy as np


def trapezoid(S: float, v0: float, V: float, A: float, D: float) -> tuple[np.ndarray, np.ndarray]:
    """Breakpoints (s, ṡ) of the time-optimal motion over [0, S] from path speed v0 to rest, with
    |ṡ| ≤ V, s̈ ≤ A and s̈ ≥ -D (constant acceleration between breakpoints).

    From rest: the trapezoid when S ≥ V²/2A + V²/2D (time S/V + V/2A + V/2D), else the triangle
    with peak √(2SAD/(A+D)). From v0 > 0 the same with the ramp starting at v0; when v0 > V the
    motion first brakes to V; when v0 is too fast to stop within S (the limits were lowered under
    way), it brakes with the deceleration that stops it exactly at S."""
    if S <= 0.0:
        return np.array([0.0]), np.array([0.0])
    v0 = max(v0, 0.0)
    if v0 * v0 / (2.0 * D) >= S:  # cannot stop in time at D: the deceleration needed
        return np.array([0.0, S]), np.array([v0, 0.0])
    if v0 > V:
        s1 = (v0 * v0 - V * V) / (2.0 * D)
        s2 = S - V * V / (2.0 * D)
        pts = [(0.0, v0), (s1, V)]
        if s2 > s1:
            pts.append((s2, V))
        pts.append((S, 0.0))
    else:
        vp2 = (2.0 * S * A * D + v0 * v0 * D) / (A + D)
        if vp2 <= V * V:
            vp = math.sqrt(vp2)
            s1 = (vp2 - v0 * v0) / (2.0 * A)
            pts = [(0.0, v0), (s1, vp), (S, 0.0)]
        else:
            s1 = (V * V - v0 * v0) / (2.0 * A)
            s2 = S - V * V / (2.0 * D)
            pts = [(0.0, v0), (s1, V), (s2, V), (S, 0.0)]
    s = np.array([p[0] for p in pts])
    sd = np.array([p[1] for p in pts])
    keep = np.concatenate([[True], np.diff(s) > 1e-15])  # drop zero-length ramps
    keep[-1] = True
    return s[keep], sd[keep]


def duration(s: np.ndarray, sd: np.ndarray) -> float:
    """Time of a profile given by breakpoints with constant acceleration in between."""
    ds = np.diff(s)
    v = sd[:-1] + sd[1:]
    with np.errstate(divide="ignore", invalid="ignore"):
        dt = np.where(ds > 0, 2.0 * ds / v, 0.0)
    return float(dt.sum())
