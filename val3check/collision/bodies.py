"""Solids as python-fcl objects, with the box that bounds each one (for the broad phase).

A `Body` is one solid: an fcl `CollisionObject` (its own geometry object, so that a distance
result names it), its pose in the frame of the group that carries it (`local`), and an oriented
box around it in its own frame (`center`, `half`) from which a world-aligned box is computed
cheaply at any pose. Lengths in mm.
"""

from __future__ import annotations

import fcl
import numpy as np

KINDS = ("link", "tool", "part", "obstacle")


def fcl_geometry(kind: str, size: tuple[float, ...], vertices=None, faces=None):
    """The fcl geometry of a box (x, y, z), cylinder (radius, length along z), sphere (radius) or
    triangle mesh (vertices, faces)."""
    if kind == "box":
        return fcl.Box(*size)
    if kind == "cylinder":
        return fcl.Cylinder(size[0], size[1])
    if kind == "sphere":
        return fcl.Sphere(size[0])
    if kind == "mesh":
        m = fcl.BVHModel()
        m.beginModel(len(vertices), len(faces))
        m.addSubModel(np.ascontiguousarray(vertices, dtype=float), np.ascontiguousarray(faces, dtype=np.int32))
        m.endModel()
        return m
    raise ValueError(f"unknown solid {kind!r}")


def local_box(kind: str, size: tuple[float, ...], vertices=None) -> tuple[np.ndarray, np.ndarray]:
    """(centre, half extents) of a box around the solid, in its own frame."""
    if kind == "box":
        return np.zeros(3), 0.5 * np.asarray(size, dtype=float)
    if kind == "cylinder":
        return np.zeros(3), np.array([size[0], size[0], 0.5 * size[1]])
    if kind == "sphere":
        return np.zeros(3), np.full(3, float(size[0]))
    v = np.asarray(vertices, dtype=float)
    lo, hi = v.min(axis=0), v.max(axis=0)
    return 0.5 * (lo + hi), 0.5 * (hi - lo)


class Body:
    """One solid. `kind`: link, tool, part or obstacle; `owner`: the link name, tool variable,
    part name or obstacle name; `label`: how reports name it ("link_4 (forearm)", "obstacle 'table'");
    `local`: pose in the carrying frame (link, flange, or world for obstacles)."""

    __slots__ = ("center", "half", "kind", "label", "local", "mesh", "name", "obj", "owner", "pose", "radius",
                 "solid")

    def __init__(self, kind: str, owner: str, name: str, label: str, shape_kind: str, size: tuple[float, ...],
                 local: np.ndarray, vertices=None, faces=None, solid: bool = True) -> None:
        self.kind = kind
        self.owner = owner
        self.name = name
        self.label = label
        self.local = np.asarray(local, dtype=float)
        self.obj = fcl.CollisionObject(fcl_geometry(shape_kind, size, vertices, faces), fcl.Transform())
        self.center, self.half = local_box(shape_kind, size, vertices)
        self.radius = float(np.linalg.norm(np.abs(self.center) + self.half))  # from the solid's own origin
        self.mesh = (np.asarray(vertices, dtype=float), np.asarray(faces)) if shape_kind == "mesh" else None
        self.solid = solid  # a closed volume (primitives, watertight meshes) rather than a surface
        self.pose = np.eye(4)

    def place(self, frame: np.ndarray) -> None:
        """Put the solid at `frame` @ local (world, mm)."""
        T = frame @ self.local
        self.pose = T
        self.obj.setRotation(T[:3, :3])
        self.obj.setTranslation(T[:3, 3])

    def aabb(self) -> tuple[np.ndarray, np.ndarray]:
        """World-aligned box (low, high) around the solid at its current pose."""
        R = self.pose[:3, :3]
        c = R @ self.center + self.pose[:3, 3]
        h = np.abs(R) @ self.half
        return c - h, c + h

    def reach(self, link_frame_radius: float = 0.0) -> float:
        """Largest distance from the carrying frame's origin to a point of the solid."""
        return float(np.linalg.norm(self.local[:3, 3])) + self.radius + link_frame_radius

    def __repr__(self) -> str:
        return f"Body({self.label})"


def aabb_gap(lo_a: np.ndarray, hi_a: np.ndarray, lo_b: np.ndarray, hi_b: np.ndarray) -> np.ndarray:
    """Distance between world-aligned boxes (0 when they overlap), broadcast over leading axes."""
    gap = np.maximum(0.0, np.maximum(lo_a - hi_b, lo_b - hi_a))
    return np.sqrt((gap * gap).sum(axis=-1))


# Three fixed, unrelated directions for the ray-parity test (no axis-aligned ray grazes box edges).
_RAYS = np.array([[0.5773, 0.6172, 0.5345], [-0.7071, 0.3015, 0.6396], [0.2673, -0.8018, 0.5345]])


def point_inside(vertices: np.ndarray, faces: np.ndarray, point: np.ndarray) -> bool:
    """Whether `point` is inside a closed (watertight) triangle mesh: the number of faces a ray
    from the point crosses is odd. Three rays vote, so a ray through an edge cannot decide alone."""
    a = vertices[faces[:, 0]]
    e1 = vertices[faces[:, 1]] - a
    e2 = vertices[faces[:, 2]] - a
    votes = 0
    for d in _RAYS:
        d = d / np.linalg.norm(d)
        p = np.cross(d, e2)
        det = (e1 * p).sum(axis=1)
        ok = np.abs(det) > 1e-12
        inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
        s = point - a
        u = (s * p).sum(axis=1) * inv
        q = np.cross(s, e1)
        v = (q * d).sum(axis=1) * inv
        t = (q * e2).sum(axis=1) * inv
        hits = ok & (u >= 0.0) & (v >= 0.0) & (u + v <= 1.0) & (t > 0.0)
        votes += int(hits.sum()) % 2
    return votes >= 2
