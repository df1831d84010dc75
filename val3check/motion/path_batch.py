"""The rows of many geometries of one kind evaluated together (paths.Path.q, q01): a page's block
of samples crosses some seventy geometries, and evaluating each apart costs a few dozen small numpy
calls per geometry. Here each geometry finds its own rows' pieces (its knots searched alone, as
its `q` does), then one evaluation covers the rows of every geometry of the kind, each row with
its own geometry's values gathered: element by element the arithmetic of the geometry's `q`, so
the same bits (tests/motion/test_path_eval.py).

    outs = evaluate(kind, geoms, rows_of, lam, orders)   # per order, the rows' values (rows_of's order)
"""

from __future__ import annotations

import numpy as np

from .curves import bezier, hermite

SPLINE, LINE, BLEND = "spline", "line", "blend"  # the kinds (paths.batch_kind says a geometry's)


def evaluate(kind: str, geoms: list, rows_of: list, lam: np.ndarray, orders: tuple) -> list:
    """`geom.q(lam[rows], order)` of every geometry (all of `kind`) with its rows, for each order:
    one array per order, the geometries' rows one after the other (`rows_of`'s order)."""
    if kind == SPLINE:
        return _splines(geoms, rows_of, lam, orders)
    if kind == LINE:
        return _lines(geoms, rows_of, lam, orders)
    return _blends(geoms, rows_of, lam, orders)


def _each(geoms: list, rows_of: list) -> np.ndarray:
    """Each row's geometry (its position in `geoms`), rows in `rows_of`'s order."""
    return np.repeat(np.arange(len(geoms)), [len(r) for r in rows_of])


def _splines(geoms: list, rows_of: list, lam: np.ndarray, orders: tuple) -> list:
    """paths.JointSpline.q: each row's Hermite piece found in its own geometry's knots."""
    knots = np.concatenate([g.lam for g in geoms])
    Q = np.concatenate([g.Q for g in geoms])
    D = np.concatenate([g.D for g in geoms])
    n = sum(len(r) for r in rows_of)
    i = np.empty(n, dtype=np.intp)
    at = base = 0
    for g, rows in zip(geoms, rows_of):
        k = g.lam
        i[at:at + len(rows)] = np.clip(np.searchsorted(k, lam[rows], side="right") - 1, 0, len(k) - 2) + base
        at += len(rows)
        base += len(k)
    x = lam[np.concatenate(rows_of)]
    h = (knots[i + 1] - knots[i])[:, None]
    u = (x - knots[i])[:, None] / h
    p0, p1 = Q[i], Q[i + 1]
    m0, m1 = D[i] * h, D[i + 1] * h
    out = []
    for order in orders:
        d = hermite(u, p0, m0, p1, m1, order)
        out.append(d if order == 0 else d / h ** order)
    return out


def _lines(geoms: list, rows_of: list, lam: np.ndarray, orders: tuple) -> list:
    """paths.JointLine.q."""
    g_of = _each(geoms, rows_of)
    delta = np.array([g.delta for g in geoms])[g_of]
    out = []
    for order in orders:
        if order == 0:
            q0 = np.array([g.q0 for g in geoms])[g_of]
            out.append(q0 + lam[np.concatenate(rows_of)][:, None] * delta)
        elif order == 1:
            out.append(delta.copy())
        else:
            out.append(np.zeros(delta.shape))
    return out


def _blends(geoms: list, rows_of: list, lam: np.ndarray, orders: tuple) -> list:
    """paths.JointBlend.q of Bézier blends (BlendShape.point)."""
    g_of = _each(geoms, rows_of)
    shapes = [g.shape for g in geoms]
    ell = np.array([g.ell for g in geoms])[g_of]
    sig = lam[np.concatenate(rows_of)] * ell
    c1 = np.array([s.param.c1 for s in shapes])[g_of]
    c2 = np.array([s.param.c2 for s in shapes])[g_of]
    P = [np.array([s.P[k] for s in shapes])[g_of] for k in range(4)]
    u = np.clip(c1 * sig + c2 * sig * sig, 0.0, 1.0)[:, None]  # (BlendParam.u)
    out = []
    for order in orders:
        if order == 0:
            out.append(bezier(u, *P))
            continue
        du = (c1 + 2.0 * c2 * sig)[:, None]  # (BlendParam.du)
        d1 = bezier(u, *P, order=1)
        d = d1 * du if order == 1 else bezier(u, *P, order=2) * du * du + d1 * (2.0 * c2)[:, None]
        scale = np.array([g.ell ** order for g in geoms])[g_of]  # (JointBlend.q: a Python power each)
        out.append(d * scale[:, None])
    return out
