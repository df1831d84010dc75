"""The exact geometry of one body, in numpy and without fcl: the closest point of its surface, how
deep a point is inside it, its support point in a direction, and points of it for depth estimates.

The collision checks measure with fcl (fcl_backend) and use these to put fcl's answers in world
coordinates on the right body, to check them, and where fcl gives no answer (the depth of an
overlap with a mesh, a solid inside a closed mesh). Every function takes the body's world pose
and world points.
"""

from __future__ import annotations

import math

import numpy as np

from .bodies import Body


def closest_on_surface(body: Body, pose: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, float]:
    """The closest point of the body's surface to p (world), and its distance (the triangles of
    the body for a piece of a mesh, a surface or a convex hull)."""
    R, t = pose[:3, :3], pose[:3, 3]
    x = R.T @ (np.asarray(p, dtype=float) - t)
    kind = body.geometry
    if kind == "sphere":
        r = body.size[0]
        n = np.linalg.norm(x)
        q = x * (r / n) if n > 0.0 else np.array([0.0, 0.0, r])
    elif kind == "box":
        q = _box_closest(x, 0.5 * np.asarray(body.size, dtype=float))
    elif kind == "cylinder":
        q = _cylinder_closest(x, body.size[0], 0.5 * body.size[1])
    else:
        q, _ = body.triangle_shape.closest(x)
    return R @ q + t, float(np.linalg.norm(q - x))


def closest_on_solid(body: Body, pose: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, float]:
    """The closest point of the surface of the body's solid to p (world): the whole mesh's for a
    piece of a mesh, else the body's own (`closest_on_surface`)."""
    whole = body.whole_shape
    if body.geometry != "triangles" or whole is None:
        return closest_on_surface(body, pose, p)
    R, t = pose[:3, :3], pose[:3, 3]
    q, d = whole.closest(R.T @ (np.asarray(p, dtype=float) - t))
    return R @ q + t, d


def depth_inside(body: Body, pose: np.ndarray, points: np.ndarray, outside: bool = True) -> np.ndarray:
    """For points (P, 3) in world: how deep each is inside the body's solid (its distance to the
    surface), or minus its distance outside (-inf when `outside` is False: not computed). The
    solid of a piece of a closed mesh is the whole mesh; a surface has no inside."""
    R, t = pose[:3, :3], pose[:3, 3]
    x = (np.asarray(points, dtype=float) - t) @ R
    kind = body.geometry
    if kind == "sphere":
        return body.size[0] - np.linalg.norm(x, axis=1)
    if kind == "box":
        h = 0.5 * np.asarray(body.size, dtype=float)
        away = np.linalg.norm(np.maximum(np.abs(x) - h, 0.0), axis=1)
        return np.where(away > 0.0, -away, (h - np.abs(x)).min(axis=1))
    if kind == "cylinder":
        r, h = body.size[0], 0.5 * body.size[1]
        dr, dz = np.hypot(x[:, 0], x[:, 1]) - r, np.abs(x[:, 2]) - h
        away = np.hypot(np.maximum(dr, 0.0), np.maximum(dz, 0.0))
        return np.where((dr > 0.0) | (dz > 0.0), -away, np.minimum(-dr, -dz))
    out = np.full(len(x), -math.inf)
    if kind == "convex":
        n, d = body.planes
        out = -(x @ n.T - d).max(axis=1)  # inside: the distance to the nearest face's plane
        for k in np.nonzero(out < 0.0)[0]:
            out[k] = -body.triangle_shape.closest(x[k])[1] if outside else -math.inf
        return out
    whole = body.whole_shape
    shape = whole if whole is not None else body.triangle_shape
    inside = np.zeros(len(x), dtype=bool)
    if whole is not None and whole.closed:
        lo, hi = whole.box
        maybe = np.nonzero((x >= lo).all(axis=1) & (x <= hi).all(axis=1))[0]
        inside[maybe] = whole.inside_many(x[maybe])
    todo = np.arange(len(x)) if outside else np.nonzero(inside)[0]
    if len(todo):
        _, d = shape.closest_many(x[todo])
        out[todo] = np.where(inside[todo], d, -d)
    return out


def support(body: Body, pose: np.ndarray, n: np.ndarray) -> np.ndarray:
    """A point of the body furthest along the direction n (world)."""
    R, t = pose[:3, :3], pose[:3, 3]
    m = R.T @ np.asarray(n, dtype=float)
    kind = body.geometry
    if kind == "sphere":
        x = m * (body.size[0] / np.linalg.norm(m))
    elif kind == "box":
        x = np.where(m >= 0.0, 1.0, -1.0) * 0.5 * np.asarray(body.size, dtype=float)
    elif kind == "cylinder":
        r, h = body.size[0], 0.5 * body.size[1]
        radial = np.hypot(m[0], m[1])
        x = np.array([r * m[0] / radial, r * m[1] / radial, 0.0]) if radial > 1e-12 else np.zeros(3)
        x[2] = h if m[2] >= 0.0 else -h
    else:
        v = body.support_points
        x = v[int(np.argmax(v @ m))]
    return R @ x + t


def support_values(body: Body, pose: np.ndarray, dirs: np.ndarray) -> np.ndarray:
    """max over the body's points x of u·x, for each direction u of dirs (K, 3), world (a convex
    body: a primitive or a convex hull)."""
    R, t = pose[:3, :3], pose[:3, 3]
    m = dirs @ R  # the directions in the body's frame
    base = dirs @ t
    kind = body.geometry
    if kind == "sphere":
        return base + body.size[0] * np.linalg.norm(dirs, axis=1)
    if kind == "box":
        return base + np.abs(m) @ (0.5 * np.asarray(body.size, dtype=float))
    if kind == "cylinder":
        return base + body.size[0] * np.hypot(m[:, 0], m[:, 1]) + 0.5 * body.size[1] * np.abs(m[:, 2])
    return base + (m @ body.support_points.T).max(axis=1)


def axes(body: Body, pose: np.ndarray) -> np.ndarray:
    """The directions (world) along which a convex body's overlap with another is often least:
    a box's and a cylinder's axes, a hull's face normals; none for a sphere."""
    R = pose[:3, :3]
    kind = body.geometry
    if kind == "box":
        return R.T.copy()
    if kind == "cylinder":
        return R[:, 2][None].copy()
    if kind == "convex":
        return body.planes[0] @ R.T
    return np.zeros((0, 3))


def _fibonacci(n: int) -> np.ndarray:
    k = np.arange(n) + 0.5
    phi = np.arccos(1.0 - 2.0 * k / n)
    theta = math.pi * (1.0 + 5.0 ** 0.5) * k
    return np.stack([np.cos(theta) * np.sin(phi), np.sin(theta) * np.sin(phi), np.cos(phi)], axis=1)


_SPHERE = _fibonacci(256)  # directions all around, about 13 degrees apart


def edges(body: Body, pose: np.ndarray) -> np.ndarray:
    """The directions (world) of a body's edges: a box's axes, a cylinder's axis, a hull's edges
    (each once); none for a sphere."""
    R = pose[:3, :3]
    kind = body.geometry
    if kind == "box":
        return R.T.copy()
    if kind == "cylinder":
        return R[:, 2][None].copy()
    if kind == "convex":
        return body.edge_directions @ R.T
    return np.zeros((0, 3))


def overlap_bound(a: Body, b: Body, hints: np.ndarray, starts: int = 6) -> tuple[float, np.ndarray]:
    """An upper bound of the penetration depth of two convex bodies, and its direction (from a
    to b): the overlap of their projections on a direction u, h_a(u) + h_b(-u), is the length of a
    translation along u that separates them, and the penetration depth is its least value over
    all directions. Candidates: their axes, their edges crossed (between polyhedra the least
    overlap is on a face normal or on two edges crossed: exact), `hints`, both ways, and 256
    directions all around; between two polyhedra the least of these, else a local search on the
    sphere of directions from the `starts` best (the least overlap found; negative: a separating
    direction)."""
    d = [axes(a, a.pose), axes(b, b.pose), np.asarray(hints, dtype=float).reshape(-1, 3)]
    ea, eb = edges(a, a.pose), edges(b, b.pose)
    exact = len(ea) * len(eb) <= 4096 and "cylinder" not in (a.geometry, b.geometry) \
        and "sphere" not in (a.geometry, b.geometry)
    if len(ea) * len(eb) <= 4096:  # polyhedra: with their edges crossed, the least overlap is among these
        d.append(_cross(np.repeat(ea, len(eb), axis=0), np.tile(eb, (len(ea), 1))))
    d = np.concatenate(d)
    length = np.linalg.norm(d, axis=1)
    d = d[length > 1e-12] / length[length > 1e-12][:, None]
    d = np.concatenate([d, -d, _SPHERE])

    def overlap(u: np.ndarray) -> np.ndarray:
        return support_values(a, a.pose, u) + support_values(b, b.pose, -u)

    over = overlap(d)
    if exact:  # two polyhedra: no other direction can do better
        k = int(np.argmin(over))
        return float(over[k]), d[k]
    best = np.argsort(over, kind="stable")[:starts]
    u, value = d[best], over[best]  # every start searched at once
    step = np.full(len(u), 0.2)
    g = np.array([-1.0, 0.0, 1.0])
    grid = np.stack(np.meshgrid(g, g, indexing="ij"), axis=-1).reshape(-1, 2)  # (9, 2)
    while True:
        live = (step > 1e-6) & (value > 0.0)  # a step of 1e-6 rad moves a 100 mm lever 1e-4 mm
        if not live.any():
            break
        ul, sl = u[live], step[live]
        # two unit directions across each u
        other = np.where((np.abs(ul[:, 0]) < 0.9)[:, None], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0])
        e1 = _cross(ul, other)
        e1 /= np.linalg.norm(e1, axis=1)[:, None]
        e2 = _cross(ul, e1)
        cand = (ul[:, None, :] + sl[:, None, None] * (grid[None, :, 0, None] * e1[:, None, :]
                                                      + grid[None, :, 1, None] * e2[:, None, :]))
        cand /= np.linalg.norm(cand, axis=2)[:, :, None]
        o = overlap(cand.reshape(-1, 3)).reshape(len(ul), -1)
        j = o.argmin(axis=1)
        better = o[np.arange(len(ul)), j] < value[live] - 1e-12
        idx = np.nonzero(live)[0]
        moved, stayed = idx[better], idx[~better]
        u[moved] = cand[better, j[better]]
        value[moved] = o[better, j[better]]
        step[stayed] *= 0.5
    k = int(np.argmin(value))
    return float(value[k]), u[k]


def _cross(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Row-wise cross products of (N, 3) arrays (np.cross is slow on small arrays)."""
    return np.stack([x[:, 1] * y[:, 2] - x[:, 2] * y[:, 1], x[:, 2] * y[:, 0] - x[:, 0] * y[:, 2],
                     x[:, 0] * y[:, 1] - x[:, 1] * y[:, 0]], axis=1)


def samples(body: Body, pose: np.ndarray) -> np.ndarray:
    """Points of the body (world) whose depth inside another solid bounds the penetration depth
    from below: a box's corners, edge middles, face centres and centre; a cylinder's rims (RIM
    points each), cap centres and centre; a mesh's vertices; a sphere's centre (its radius is
    added by the caller)."""
    x = body.sample_points
    return x @ pose[:3, :3].T + pose[:3, 3]


def triangle_samples(x: Body, y: Body, most: int = 4000) -> np.ndarray:
    """Points of the triangles of x (a piece of a mesh, or a surface) that lie in y's box, every
    few millimetres (a tenth of y's smallest side, from 0.5 to 5 mm; coarser when there would
    be more than `most`): the deepest point of those triangles inside y is within that spacing
    of a sample (a depth changes no faster than the point moves)."""
    R, t = x.pose[:3, :3], x.pose[:3, 3]
    tri = x.triangle_shape.triangles @ R.T + t
    lo, hi = y.aabb()
    keep = (tri.min(axis=1) <= hi).all(axis=1) & (tri.max(axis=1) >= lo).all(axis=1)
    tri = tri[keep]
    if not len(tri):
        return np.zeros((0, 3))
    spacing = min(max(0.1 * float((hi - lo).min()), 0.5), 5.0)
    edges = np.linalg.norm(tri - np.roll(tri, 1, axis=1), axis=2).max(axis=1)
    n = np.maximum(1, np.ceil(edges / spacing)).astype(int)
    while (0.5 * (n + 1) * (n + 2)).sum() > most and n.max() > 1:
        n = np.maximum(1, n // 2)
    out = []
    for k in np.unique(n):
        i, j = np.meshgrid(np.arange(k + 1), np.arange(k + 1))
        sel = (i + j) <= k
        u, v = i[sel] / k, j[sel] / k
        ts = tri[n == k]
        out.append((ts[:, None, 0] + u[None, :, None] * (ts[:, None, 1] - ts[:, None, 0])
                    + v[None, :, None] * (ts[:, None, 2] - ts[:, None, 0])).reshape(-1, 3))
    return np.concatenate(out)


def _box_closest(x: np.ndarray, h: np.ndarray) -> np.ndarray:
    q = np.clip(x, -h, h)
    if np.any(q != x):
        return q  # outside: the clamped point
    k = int(np.argmin(h - np.abs(x)))  # inside: onto the nearest face
    q = x.copy()
    q[k] = h[k] if x[k] >= 0.0 else -h[k]
    return q


def _cylinder_closest(x: np.ndarray, r: float, h: float) -> np.ndarray:
    rho = math.hypot(x[0], x[1])
    radial = np.array([x[0], x[1], 0.0]) / rho if rho > 0.0 else np.array([1.0, 0.0, 0.0])
    if rho <= r and abs(x[2]) <= h:  # inside: onto the side or a cap, whichever is nearer
        if r - rho < h - abs(x[2]):
            return np.array([r * radial[0], r * radial[1], x[2]])
        return np.array([x[0], x[1], h if x[2] >= 0.0 else -h])
    q = radial * min(rho, r)
    q[2] = min(max(x[2], -h), h)
    return q
