"""A whole triangle mesh for exact point queries in numpy (no fcl): the closest point of its
surface to a point, and whether a point is inside it (closed meshes).

The triangles are kept in groups of at most GROUP, each with its box, so that a query looks only
at the groups that can hold the answer. Points are in the mesh's own frame.
"""

from __future__ import annotations

import numpy as np

GROUP = 64  # triangles per group of the search

# Three fixed, unrelated directions for the ray-parity test (no axis-aligned ray grazes box edges).
_RAYS = np.array([[0.5773, 0.6172, 0.5345], [-0.7071, 0.3015, 0.6396], [0.2673, -0.8018, 0.5345]])
_RAYS = _RAYS / np.linalg.norm(_RAYS, axis=1)[:, None]


def closest_on_triangles(p: np.ndarray, tri: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For points p (P, 3) and triangles tri (T, 3, 3): the closest point of each triangle to each
    point (P, T, 3) and the squared distances (P, T): the closest feature (a vertex, an edge or the
    face) chosen by the regions of the triangle, as in Ericson, Real-Time Collision Detection,
    5.1.5, for all pairs at once. A flat (degenerate) triangle gives its nearest vertex."""
    p = np.asarray(p, dtype=float)[:, None, :]
    a, b, c = tri[None, :, 0], tri[None, :, 1], tri[None, :, 2]
    ab, ac = b - a, c - a
    ap, bp, cp = p - a, p - b, p - c
    d1, d2 = (ab * ap).sum(-1), (ac * ap).sum(-1)
    d3, d4 = (ab * bp).sum(-1), (ac * bp).sum(-1)
    d5, d6 = (ab * cp).sum(-1), (ac * cp).sum(-1)
    va = d3 * d6 - d5 * d4
    vb = d5 * d2 - d1 * d6
    vc = d1 * d4 - d3 * d2
    shape = d1.shape
    out = np.empty(shape + (3,))
    done = np.zeros(shape, dtype=bool)

    def put(mask: np.ndarray, value) -> None:
        m = mask & ~done
        if m.any():
            out[m] = np.broadcast_to(value, shape + (3,))[m]
            done[m] = True

    with np.errstate(divide="ignore", invalid="ignore"):
        put((d1 <= 0) & (d2 <= 0), a)
        put((d3 >= 0) & (d4 <= d3), b)
        put((vc <= 0) & (d1 >= 0) & (d3 <= 0), a + (d1 / (d1 - d3))[..., None] * ab)
        put((d6 >= 0) & (d5 <= d6), c)
        put((vb <= 0) & (d2 >= 0) & (d6 <= 0), a + (d2 / (d2 - d6))[..., None] * ac)
        e, f = d4 - d3, d5 - d6
        put((va <= 0) & (e >= 0) & (f >= 0), b + (e / (e + f))[..., None] * (c - b))
        denom = 1.0 / (va + vb + vc)
        put(np.ones(shape, dtype=bool), a + (vb * denom)[..., None] * ab + (vc * denom)[..., None] * ac)
    bad = ~np.isfinite(out).all(-1)
    if bad.any():
        verts = np.broadcast_to(tri[None], shape + (3, 3))
        dv = ((verts - p[..., None, :]) ** 2).sum(-1)
        nearest = np.take_along_axis(verts, dv.argmin(-1)[..., None, None], axis=-2)[..., 0, :]
        out[bad] = nearest[bad]
    d = out - p
    return out, (d * d).sum(-1)


class MeshShape:
    """The triangles of a mesh (vertices (V, 3), faces (F, 3)) in its own frame; `closed`: a
    watertight solid (it has an inside), else a surface."""

    def __init__(self, vertices: np.ndarray, faces: np.ndarray, closed: bool) -> None:
        v = np.asarray(vertices, dtype=float)
        f = np.asarray(faces, dtype=np.int64)
        self.closed = closed
        self.vertices = v
        tri = v[f]
        order = _groups(tri.mean(axis=1))
        self.triangles = tri[order]  # grouped: group g is triangles[starts[g]:starts[g + 1]]
        n = len(order)
        self.starts = np.arange(0, n + GROUP, GROUP).clip(max=n)
        g = [self.triangles[s:e] for s, e in zip(self.starts[:-1], self.starts[1:])]
        self.lo = np.array([t.reshape(-1, 3).min(axis=0) for t in g])
        self.hi = np.array([t.reshape(-1, 3).max(axis=0) for t in g])
        self.corner = np.array([t[0, 0] for t in g])  # a vertex of each group
        self.box = (v.min(axis=0), v.max(axis=0))
        self._members = [np.arange(s, e) for s, e in zip(self.starts[:-1], self.starts[1:])]
        # ray test: each triangle's first vertex and its two edges
        self._a = self.triangles[:, 0]
        self._e1 = self.triangles[:, 1] - self._a
        self._e2 = self.triangles[:, 2] - self._a

    def closest(self, p: np.ndarray) -> tuple[np.ndarray, float]:
        """The closest point of the surface to p (3,), and its distance."""
        q, d = self.closest_many(np.asarray(p, dtype=float)[None])
        return q[0], float(d[0])

    def closest_many(self, points: np.ndarray, chunk: int = 200_000) -> tuple[np.ndarray, np.ndarray]:
        """The closest points of the surface to points (P, 3), and their distances (P,): for each
        point, the triangles of every group whose box is nearer than the nearest group's corner
        (a vertex: an upper bound of the distance)."""
        p = np.asarray(points, dtype=float)
        gap = _box_gaps(p, self.lo, self.hi)  # (P, G)
        upper = np.sqrt(((p[:, None, :] - self.corner[None]) ** 2).sum(axis=2)).min(axis=1)
        near = gap <= upper[:, None]
        out_q = np.empty_like(p)
        out_d = np.empty(len(p))
        # points that look at the same groups are measured together
        keys: dict[bytes, list[int]] = {}
        for k, row in enumerate(near):
            keys.setdefault(np.packbits(row).tobytes(), []).append(k)
        for rows in keys.values():
            idx = np.concatenate([self._members[g] for g in np.nonzero(near[rows[0]])[0]])
            tri = self.triangles[idx]
            step = max(1, chunk // max(1, len(idx)))
            for s in range(0, len(rows), step):
                sel = rows[s:s + step]
                q, d2 = closest_on_triangles(p[sel], tri)
                j = d2.argmin(axis=1)
                out_q[sel] = q[np.arange(len(sel)), j]
                out_d[sel] = np.sqrt(d2[np.arange(len(sel)), j])
        return out_q, out_d

    def inside(self, p: np.ndarray) -> bool:
        """Whether p is inside the closed mesh (`inside_many`)."""
        return bool(self.inside_many(np.asarray(p, dtype=float)[None])[0])

    def inside_many(self, points: np.ndarray) -> np.ndarray:
        """For points (P, 3): whether each is inside the closed mesh: the number of triangles a ray
        from it crosses is odd; three rays vote, so a ray through an edge cannot decide alone.
        False for a surface."""
        p = np.asarray(points, dtype=float)
        if not self.closed or not len(p):
            return np.zeros(len(p), dtype=bool)
        votes = np.zeros(len(p), dtype=int)
        for d in _RAYS:
            idx = self._ray_groups(p, d)
            if not len(idx):
                continue
            a, e1, e2 = self._a[idx], self._e1[idx], self._e2[idx]
            h = np.cross(d, e2)  # (T, 3)
            det = (e1 * h).sum(axis=1)
            ok = np.abs(det) > 1e-12
            inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
            s = p[:, None, :] - a[None]  # (P, T, 3)
            u = (s * h[None]).sum(axis=2) * inv
            q = np.cross(s, e1[None])
            v = (q * d).sum(axis=2) * inv
            t = (q * e2[None]).sum(axis=2) * inv
            hits = ok & (u >= 0.0) & (v >= 0.0) & (u + v <= 1.0) & (t > 0.0)
            votes += hits.sum(axis=1) % 2
        return votes >= 2

    def _ray_groups(self, p: np.ndarray, d: np.ndarray) -> np.ndarray:
        """Indices of the triangles in the groups whose box a ray p + t d (t > 0) from any of the
        points p (P, 3) crosses."""
        with np.errstate(divide="ignore", invalid="ignore"):
            inv = 1.0 / d
            t1 = (self.lo[None] - p[:, None, :]) * inv
            t2 = (self.hi[None] - p[:, None, :]) * inv
        near = np.minimum(t1, t2).max(axis=2)
        far = np.maximum(t1, t2).min(axis=2)
        crossed = np.nonzero((far >= np.maximum(near, 0.0)).any(axis=0))[0]
        if not len(crossed):
            return np.zeros(0, dtype=np.int64)
        return np.concatenate([self._members[g] for g in crossed])


def median_cuts(centres: np.ndarray, size: int, whole: bool = False) -> list[np.ndarray]:
    """Indices of the triangles in pieces of at most `size` close together: median cuts of their
    centres along the longest side, in order. `whole`: every piece but the last has `size` exactly."""
    todo = [np.arange(len(centres))]
    out = []
    while todo:
        idx = todo.pop()
        if len(idx) <= size:
            out.append(idx)
            continue
        c = centres[idx]
        axis = int(np.argmax(c.max(axis=0) - c.min(axis=0)))
        order = idx[np.argsort(c[:, axis], kind="stable")]
        half = (len(order) // 2 + size - 1) // size * size if whole else len(order) // 2
        todo.extend((order[half:], order[:half]))
    return out


def _groups(centres: np.ndarray) -> np.ndarray:
    """An order of the triangles in which every GROUP consecutive ones are close together."""
    out = median_cuts(centres, GROUP, whole=True)
    return np.concatenate(out) if out else np.zeros(0, dtype=np.int64)


def _box_gaps(p: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Distances (P, G) from points (P, 3) to boxes (G, 3)."""
    gap = np.maximum(0.0, np.maximum(lo[None] - p[:, None, :], p[:, None, :] - hi[None]))
    return np.sqrt((gap * gap).sum(axis=-1))
