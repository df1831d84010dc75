"""The cubic curves the joint paths are made of (paths.py): Hermite pieces and Bézier curves, with
their derivatives in the curve's parameter. Element by element numpy arithmetic: a row's value
does not depend on the rows evaluated with it (path_batch.py evaluates many geometries at once).
"""

from __future__ import annotations

import numpy as np


def hermite(u: np.ndarray, p0, m0, p1, m1, order: int = 0) -> np.ndarray:
    """Cubic Hermite curve (or its derivatives in u) with end points p0, p1 and tangents m0, m1."""
    if order == 0:
        u2, u3 = u * u, u * u * u
        return (2 * u3 - 3 * u2 + 1) * p0 + (u3 - 2 * u2 + u) * m0 + (-2 * u3 + 3 * u2) * p1 + (u3 - u2) * m1
    if order == 1:
        u2 = u * u
        return (6 * u2 - 6 * u) * p0 + (3 * u2 - 4 * u + 1) * m0 + (-6 * u2 + 6 * u) * p1 + (3 * u2 - 2 * u) * m1
    return (12 * u - 6) * p0 + (6 * u - 4) * m0 + (-12 * u + 6) * p1 + (6 * u - 2) * m1


def bezier(u: np.ndarray, P0, P1, P2, P3, order: int = 0) -> np.ndarray:
    """Cubic Bézier curve (or its derivatives in u)."""
    v = 1.0 - u
    if order == 0:
        return v * v * v * P0 + 3 * v * v * u * P1 + 3 * v * u * u * P2 + u * u * u * P3
    if order == 1:
        return 3 * v * v * (P1 - P0) + 6 * v * u * (P2 - P1) + 3 * u * u * (P3 - P2)
    return 6 * v * (P2 - 2 * P1 + P0) + 6 * u * (P3 - 2 * P2 + P1)
