"""The blend curves docs/motion.md documents, computed here from the words of the document and the
robot model's own IK and FK (val3check.robot), knowing nothing of val3check/motion: what the
simulated TCP is held to (tests/motion/test_blend_geometry.py, bench/bench_timing.py).

The document (docs/motion.md, "Blends"): a blend from the leave point to the reach point is the
cubic Bézier curve whose inner control points lie on the tangents of the two paths, at 2/3 of the
path length from the leave point to the via point (ℓl) and from the via point to the reach point
(ℓr): P0 = leave point, P1 = P0 + ⅔·ℓl·t_l, P2 = P3 - ⅔·ℓr·t_r, P3 = reach point (t the path's
derivative per unit of its length). For two straight lines meeting at the via point C this is the
parabola (quadratic Bézier) (1-w)²·(C - leave·u1) + 2w(1-w)·C + w²·(C + reach·u2). A Cartesian
blend draws it with the TCP (mm); a joint blend draws it in joint space (degrees), the joint
positions and their derivatives taken on the two paths at the leave and reach points.
"""

from __future__ import annotations

import numpy as np


def parabola(C, u1, u2, leave: float, reach: float, n: int = 20001) -> np.ndarray:
    """The Cartesian blend of two straight lines through the corner C (first along unit u1, then
    along unit u2): n points of the parabola, (n, 3)."""
    C, u1, u2 = (np.asarray(v, dtype=float) for v in (C, u1, u2))
    w = np.linspace(0.0, 1.0, n)[:, None]
    return (1 - w) ** 2 * (C - leave * u1) + 2 * w * (1 - w) * C + w ** 2 * (C + reach * u2)


def corner_distance(leave: float, reach: float, u1, u2) -> float:
    """How close the parabola passes to its corner: min over w of |(1-w)²·a + w²·b|, a = -leave·u1,
    b = reach·u2 (on 200,001 values of w: within 1e-9 mm). For leave = reach = L on perpendicular
    lines the nearest point is the middle, w = ½: L·√2/4."""
    a = -leave * np.asarray(u1, dtype=float)
    b = reach * np.asarray(u2, dtype=float)
    w = np.linspace(0.0, 1.0, 200001)[:, None]
    return float(np.min(np.linalg.norm((1 - w) ** 2 * a + w ** 2 * b, axis=1)))


def _ik(model, T, near):
    sols = model.ik(T, near=list(near))
    if not sols:
        raise ValueError("the blend leaves the arm's reach")
    return np.array(sols[0], dtype=float)


def _pose(R, p) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = p
    return T


def joint_blend_of_lines(model, R, C, u1, u2, leave: float, reach: float, q_near, n: int = 20001,
                         h: float = 1e-3) -> tuple[np.ndarray, np.ndarray]:
    """The joint blend of two straight lines (constant orientation R) through C: the joint curve
    (n, axes) and its TCP positions (n, 3) by the model's FK. The joints at the leave and reach
    points by IK (nearest `q_near`), their derivatives per mm along each line by central
    differences of the IK (h mm apart)."""
    C, u1, u2 = (np.asarray(v, dtype=float) for v in (C, u1, u2))
    pl, pr = C - leave * u1, C + reach * u2
    ql = _ik(model, _pose(R, pl), q_near)
    qr = _ik(model, _pose(R, pr), q_near)
    dl = (_ik(model, _pose(R, pl + h * u1), ql) - _ik(model, _pose(R, pl - h * u1), ql)) / (2 * h)
    dr = (_ik(model, _pose(R, pr + h * u2), qr) - _ik(model, _pose(R, pr - h * u2), qr)) / (2 * h)
    P = (ql, ql + 2.0 / 3.0 * leave * dl, qr - 2.0 / 3.0 * reach * dr, qr)
    w = np.linspace(0.0, 1.0, n)[:, None]
    Q = (1 - w) ** 3 * P[0] + 3 * (1 - w) ** 2 * w * P[1] + 3 * (1 - w) * w ** 2 * P[2] + w ** 3 * P[3]
    X = np.array([np.array(model.fk_matrix(list(q)))[:, 3] for q in Q])
    return Q, X


def distance_to(points, curve) -> np.ndarray:
    """The distance of each point (m, 3) from a densely sampled curve (n, 3): to the nearer of the
    two segments beside its nearest sample."""
    from scipy.spatial import cKDTree

    points, curve = np.asarray(points, dtype=float), np.asarray(curve, dtype=float)
    A, d = curve[:-1], np.diff(curve, axis=0)
    dd = np.maximum(np.einsum("ij,ij->i", d, d), 1e-300)
    _, nearest = cKDTree(curve).query(points)
    best = np.full(len(points), np.inf)
    for off in (-1, 0):
        i = np.clip(nearest + off, 0, len(A) - 1)
        w = np.clip(np.einsum("ij,ij->i", points - A[i], d[i]) / dd[i], 0.0, 1.0)
        best = np.minimum(best, np.linalg.norm(points - (A[i] + w[:, None] * d[i]), axis=1))
    return best


def segment_distance(points, A, B) -> np.ndarray:
    """The distance of each point from the segment AB."""
    points = np.asarray(points, dtype=float)
    d = np.asarray(B, dtype=float) - A
    w = np.clip(((points - A) @ d) / (d @ d), 0.0, 1.0)
    return np.linalg.norm(points - (A + w[:, None] * d), axis=1)
