"""Poses the caller gives the checker (application frames, tool variables) as 4x4 matrices in mm,
and whether two readings of them are the same."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

# frames(name, time) or {name: pose}: where the caller reads a frame or a tool variable
PoseSource = Callable[[str, float], Any] | Mapping[str, Any] | None


def as_matrix(p, unit_mm: float = 1.0) -> np.ndarray:
    """A pose from the caller (trsf 6-tuple, an object with x..rz, a 3x4/4x4 matrix; lengths in
    the application's unit) as a 4x4 matrix in mm."""
    from .cellfile import trsf_matrix

    if hasattr(p, "rx"):
        t = (p.x, p.y, p.z, p.rx, p.ry, p.rz)
        M = trsf_matrix(t)
    else:
        a = np.asarray(p, dtype=float)
        if a.shape == (6,):
            M = trsf_matrix(a)
        elif a.shape in ((3, 4), (4, 4)):
            M = np.eye(4)
            M[:3, :] = a[:3, :]
        else:
            raise ValueError("a pose is a trsf (x, y, z, rx, ry, rz) or a 3x4/4x4 matrix")
    M = M.copy()
    M[:3, 3] *= unit_mm
    return M


def same_poses(a: dict, b: dict | None) -> bool:
    """Two {name: pose or None} readings are the same."""
    if b is None or a.keys() != b.keys():
        return False
    for k, v in a.items():
        w = b[k]
        if v is w:  # the same reading (collision_run.ValueWatch gives the same matrix again)
            continue
        if (v is None) != (w is None) or not np.array_equal(v, w):
            return False
    return True
