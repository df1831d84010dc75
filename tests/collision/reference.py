"""An independent reference for the collision checks (issue 24): test meshes, dense point samples
of every kind of surface, analytic distances for spheres, and the penetration depth of convex
solids by brute force over directions. Nothing here uses val3check.collision's geometry.

Sampling bounds: a surface sampled with spacing s has every point within `cover(s)` of a sample,
so a distance measured between two samples is at most 2·cover(s) above the true distance.
"""

from __future__ import annotations

import math

import numpy as np
import trimesh


def cover(s: float) -> float:
    """The largest distance from a point of a surface sampled at spacing s to the nearest sample."""
    return s * math.sqrt(2.0) / 2.0


# ---- test meshes -------------------------------------------------------------------------------------------


def extrude(polygon: list[tuple[float, float]], height: float) -> trimesh.Trimesh:
    """A prism: a simple polygon (counter-clockwise, x-y) extruded along z from -height/2 to
    +height/2, triangulated by ear clipping; watertight."""
    pts = np.asarray(polygon, dtype=float)
    tris = _ear_clip(pts)
    n = len(pts)
    v = np.concatenate([np.c_[pts, np.full(n, -height / 2)], np.c_[pts, np.full(n, height / 2)]])
    faces = [[c, b, a] for a, b, c in tris] + [[a + n, b + n, c + n] for a, b, c in tris]
    for i in range(n):
        j = (i + 1) % n
        faces += [[i, j, j + n], [i, j + n, i + n]]
    m = trimesh.Trimesh(v, np.array(faces), process=False)
    assert m.is_watertight and m.is_winding_consistent and m.volume > 0
    return m


def _ear_clip(pts: np.ndarray) -> list[tuple[int, int, int]]:
    idx = list(range(len(pts)))
    out = []

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    while len(idx) > 3:
        for k in range(len(idx)):
            i, j, m = idx[k - 1], idx[k], idx[(k + 1) % len(idx)]
            a, b, c = pts[i], pts[j], pts[m]
            if cross(a, b, c) <= 1e-12:
                continue  # reflex
            if any(cross(a, b, pts[q]) >= 0 and cross(b, c, pts[q]) >= 0 and cross(c, a, pts[q]) >= 0
                   for q in idx if q not in (i, j, m)):
                continue
            out.append((i, j, m))
            idx.pop(k)
            break
        else:
            raise ValueError("not a simple counter-clockwise polygon")
    out.append(tuple(idx))
    return out


def channel() -> trimesh.Trimesh:
    """A U channel (non-convex), 100 x 80 mm, walls 20 mm thick, 60 mm deep along z: its outer
    bottom face is y = -40, its side faces x = ±50, its inner faces x = ±30 and y = -20."""
    return extrude([(-50, -40), (50, -40), (50, 40), (30, 40), (30, -20), (-30, -20), (-30, 40), (-50, 40)], 60.0)


def convex_meshes() -> dict[str, trimesh.Trimesh]:
    return {"icosphere": trimesh.creation.icosphere(subdivisions=2, radius=25.0),
            "boxmesh": trimesh.creation.box((50.0, 30.0, 40.0))}


# ---- dense samples of surfaces --------------------------------------------------------------------------------


def transform(points: np.ndarray, pose: np.ndarray) -> np.ndarray:
    return points @ pose[:3, :3].T + pose[:3, 3]


def sample_sphere(r: float, s: float) -> np.ndarray:
    n = max(64, int(4.0 * math.pi * r * r / (s * s) * 1.5))
    k = np.arange(n) + 0.5
    phi = np.arccos(1.0 - 2.0 * k / n)
    theta = math.pi * (1.0 + 5.0 ** 0.5) * k
    return r * np.stack([np.cos(theta) * np.sin(phi), np.sin(theta) * np.sin(phi), np.cos(phi)], axis=1)


def sample_box(size, s: float) -> np.ndarray:
    h = 0.5 * np.asarray(size, dtype=float)
    out = []
    for axis in range(3):
        u, v = [a for a in range(3) if a != axis]
        gu = np.linspace(-h[u], h[u], max(2, int(math.ceil(2 * h[u] / s)) + 1))
        gv = np.linspace(-h[v], h[v], max(2, int(math.ceil(2 * h[v] / s)) + 1))
        U, V = np.meshgrid(gu, gv)
        for sign in (-1.0, 1.0):
            p = np.zeros((U.size, 3))
            p[:, u], p[:, v], p[:, axis] = U.ravel(), V.ravel(), sign * h[axis]
            out.append(p)
    return np.concatenate(out)


def sample_cylinder(r: float, length: float, s: float) -> np.ndarray:
    h = length / 2.0
    na = max(16, int(math.ceil(2 * math.pi * r / s)))
    a = np.arange(na) * 2 * math.pi / na
    z = np.linspace(-h, h, max(2, int(math.ceil(length / s)) + 1))
    A, Z = np.meshgrid(a, z)
    side = np.stack([r * np.cos(A.ravel()), r * np.sin(A.ravel()), Z.ravel()], axis=1)
    caps = []
    for rho in np.linspace(0.0, r, max(2, int(math.ceil(r / s)) + 1)):
        m = max(1, int(math.ceil(2 * math.pi * rho / s)))
        b = np.arange(m) * 2 * math.pi / m
        ring = np.stack([rho * np.cos(b), rho * np.sin(b), np.zeros(m)], axis=1)
        caps += [ring + [0, 0, -h], ring + [0, 0, h]]
    return np.concatenate([side] + caps)


def sample_mesh(m: trimesh.Trimesh, s: float) -> np.ndarray:
    tri = np.asarray(m.triangles)
    out = [tri.reshape(-1, 3)]
    for t in tri:
        longest = max(np.linalg.norm(t[1] - t[0]), np.linalg.norm(t[2] - t[1]), np.linalg.norm(t[0] - t[2]))
        n = max(1, int(math.ceil(longest / s)))
        i, j = np.meshgrid(np.arange(n + 1), np.arange(n + 1))
        keep = (i + j) <= n
        u, v = i[keep] / n, j[keep] / n
        out.append(t[0] + u[:, None] * (t[1] - t[0]) + v[:, None] * (t[2] - t[0]))
    return np.concatenate(out)


# ---- distances and depths -----------------------------------------------------------------------------------


def sample_distance(pa: np.ndarray, pb: np.ndarray) -> float:
    """The smallest distance between two point sets (scipy's KD-tree)."""
    from scipy.spatial import cKDTree

    d, _ = cKDTree(pb).query(pa)
    return float(d.min())


def point_to_box(p: np.ndarray, size) -> float:
    """Distance from a point (box frame) to a box's solid (0 inside)."""
    h = 0.5 * np.asarray(size, dtype=float)
    return float(np.linalg.norm(np.maximum(np.abs(p) - h, 0.0)))


def point_to_cylinder(p: np.ndarray, r: float, length: float) -> float:
    dr = max(math.hypot(p[0], p[1]) - r, 0.0)
    dz = max(abs(p[2]) - length / 2.0, 0.0)
    return math.hypot(dr, dz)


def fibonacci_directions(n: int) -> np.ndarray:
    k = np.arange(n) + 0.5
    phi = np.arccos(1.0 - 2.0 * k / n)
    theta = math.pi * (1.0 + 5.0 ** 0.5) * k
    return np.stack([np.cos(theta) * np.sin(phi), np.sin(theta) * np.sin(phi), np.cos(phi)], axis=1)


def penetration_depth(pa: np.ndarray, pb: np.ndarray, directions: int = 4000) -> float:
    """The penetration depth of two convex solids given by dense samples of their surfaces (world):
    the least overlap of their projections over many directions, refined around the best one
    (min over u of max_a u·a - min_b u·b). Negative: they are apart."""
    from scipy.spatial import ConvexHull

    pa = pa[ConvexHull(pa).vertices]  # only the hull's vertices reach out in any direction
    pb = pb[ConvexHull(pb).vertices]
    d = fibonacci_directions(directions)
    best = _overlaps(pa, pb, d)
    k = int(np.argmin(best))
    u = d[k]
    step = 2.0 * math.sqrt(4.0 * math.pi / directions)
    for _ in range(30):  # a local refinement around the best direction
        e1 = np.cross(u, [1.0, 0.0, 0.0] if abs(u[0]) < 0.9 else [0.0, 1.0, 0.0])
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(u, e1)
        g = np.linspace(-step, step, 7)
        cand = np.array([u + x * e1 + y * e2 for x in g for y in g])
        cand /= np.linalg.norm(cand, axis=1)[:, None]
        o = _overlaps(pa, pb, cand)
        j = int(np.argmin(o))
        u = cand[j]
        step *= 0.6
    return float(_overlaps(pa, pb, u[None])[0])


def _overlaps(pa: np.ndarray, pb: np.ndarray, d: np.ndarray) -> np.ndarray:
    return (pa @ d.T).max(axis=0) - (pb @ d.T).min(axis=0)


def random_rotation(q) -> np.ndarray:
    """A rotation from three numbers in [0, 1) (Shoemake's uniform quaternion)."""
    u1, u2, u3 = q
    a, b = math.sqrt(1 - u1), math.sqrt(u1)
    w, x, y, z = a * math.sin(2 * math.pi * u2), a * math.cos(2 * math.pi * u2), b * math.sin(2 * math.pi * u3), \
        b * math.cos(2 * math.pi * u3)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
