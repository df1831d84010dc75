"""Solids as python-fcl objects, with what the broad phase and the motion bound need.

A `Body` is one convex piece of a solid: an fcl object whose distance to another is exact
(box, cylinder, sphere, or the convex hull of a closed convex mesh), or, for a piece of a
non-convex mesh or of a surface, the convex hull of its triangles (a distance that is a lower
bound) together with the triangles themselves (`exact`, an fcl BVH) for the exact distance and
for contacts. Each body keeps its pose in the frame of the group that carries it (`local`), an
oriented box around it (for a world-aligned box at any pose) and a few points that bound it (for
the motion bound); and its exact geometry for `shapes` (`geometry`: "sphere", "box",
"cylinder", "convex" for a solid convex hull, "triangles" for a piece of a mesh or a surface).

fcl measures between a cylinder and a triangle mesh slowly (milliseconds for 5,000 triangles at
an angle) but between convex shapes in microseconds: hence the pieces. `make_bodies` cuts a
non-convex mesh into pieces of at most PIECE triangles (median cuts along the longest side).
"""

from __future__ import annotations

import itertools
import math

import fcl
import numpy as np

from .mesh_shape import MeshShape, median_cuts

PIECE = 128  # triangles per piece of a non-convex mesh
RIM = 64  # points around each rim of a cylinder for depth estimates (`local_samples`)
_SIDES = 32  # polygon around a cylinder for its bounding points


def fcl_geometry(kind: str, size: tuple[float, ...], vertices=None, faces=None):
    """The fcl geometry of a box (x, y, z), cylinder (radius, length along z), sphere (radius),
    triangle mesh ("mesh": vertices, faces) or convex polyhedron ("convex": vertices, faces)."""
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
    if kind == "convex":
        f = np.asarray(faces, dtype=np.int64)
        flat = np.hstack([np.full((len(f), 1), 3), f]).ravel()
        return fcl.Convex(np.ascontiguousarray(vertices, dtype=float), len(f), flat)
    raise ValueError(f"unknown solid {kind!r}")


class Body:
    """One convex piece of a solid.

    kind: link, tool, part or obstacle; owner: the link name, tool variable, part name or obstacle
    name; label: how reports name it ("link_4 (forearm)", "obstacle 'table'"); local: pose in the
    carrying frame (link, flange, or world); obj: fcl object (exact distances when `exact` is None);
    exact: fcl BVH of the piece's triangles, or None; whole_shape: the whole mesh the piece
    belongs to (`mesh_shape.MeshShape`: its inside when closed), or None.

    Exact geometry (`shapes`): geometry ("sphere", "box", "cylinder", "convex", "triangles"),
    size (of a primitive), triangle_shape (the piece's triangles, or the hull's), planes (a
    convex hull's faces: outward normals (F, 3) and offsets (F,)), edge_directions (a convex
    hull's edges, unit, each direction once), support_points (a polyhedron's vertices),
    sample_points (points of the body for depth estimates), all in the body's frame."""

    __slots__ = ("axis", "center", "edge_directions", "exact", "fcl_shapes", "geometry", "half", "kind", "label", "lb",
                 "local", "made_from", "name", "obj", "owner", "planes", "points", "pose", "radius", "sample_points", "size",
                 "solid", "support_points", "triangle_shape", "whole", "whole_box", "whole_shape")

    def __init__(self, kind: str, owner: str, name: str, label: str, shape_kind: str, size: tuple[float, ...],
                 local: np.ndarray, vertices=None, faces=None, solid: bool = True, exact=None,
                 whole_shape: MeshShape | None = None, whole: int = 0, triangles: MeshShape | None = None,
                 hull_solid: bool = True) -> None:
        self.kind = kind
        self.owner = owner
        self.made_from: tuple | None = None  # what the scene's key names it by (World.key); None: the body itself
        self.name = name
        self.label = label
        self.local = np.asarray(local, dtype=float)
        geom = fcl_geometry(shape_kind, size, vertices, faces)
        self.obj = fcl.CollisionObject(geom, fcl.Transform())
        self.fcl_shapes = (geom, None)  # the fcl geometries of obj and exact (`copies`)
        self.exact = exact
        self.lb = False  # True: obj is the hull of a piece, its distance a lower bound (exact: the BVH)
        self.whole_shape = whole_shape
        self.solid = solid
        self.whole = whole  # id of the solid the piece belongs to (pieces of one mesh share it)
        self.pose = np.eye(4)
        self.size = tuple(float(x) for x in size)
        self.planes = None
        self.edge_directions = None
        # bounding points in the body's own frame, and its axis of revolution (point, direction) if any
        if shape_kind == "box":
            hx, hy, hz = (0.5 * s for s in size)
            self.points = np.array([[sx * hx, sy * hy, sz * hz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
            self.axis = None
            self.radius = 0.0
        elif shape_kind == "cylinder":
            r = size[0] / math.cos(math.pi / _SIDES)
            a = np.arange(_SIDES) * 2 * math.pi / _SIDES
            ring = np.stack([r * np.cos(a), r * np.sin(a), np.zeros(_SIDES)], axis=1)
            self.points = np.concatenate([ring + [0, 0, -0.5 * size[1]], ring + [0, 0, 0.5 * size[1]]])
            self.axis = (np.zeros(3), np.array([0.0, 0.0, 1.0]))
            self.radius = 0.0
        elif shape_kind == "sphere":
            self.points = np.zeros((1, 3))
            self.axis = (np.zeros(3), None)  # symmetric about any line through its centre
            self.radius = float(size[0])
        else:
            self.points = np.asarray(vertices, dtype=float)
            self.axis = None
            self.radius = 0.0
        lo = self.points.min(axis=0) - self.radius
        hi = self.points.max(axis=0) + self.radius
        self.center, self.half = 0.5 * (lo + hi), 0.5 * (hi - lo)
        self.whole_box = (self.center, self.half)  # box around the whole solid a piece belongs to
        # exact geometry
        if shape_kind in ("box", "cylinder", "sphere"):
            self.geometry = shape_kind
            self.triangle_shape = None
            self.support_points = None
        elif shape_kind == "convex" and hull_solid:
            self.geometry = "convex"
            self.triangle_shape = MeshShape(vertices, faces, closed=True)
            self.planes = _planes(np.asarray(vertices, dtype=float), np.asarray(faces, dtype=np.int64))
            self.edge_directions = _edge_directions(np.asarray(vertices, dtype=float), np.asarray(faces, dtype=np.int64))
            self.support_points = np.asarray(vertices, dtype=float)
        else:  # a piece of a mesh, or a surface: its own triangles
            self.geometry = "triangles"
            self.triangle_shape = triangles if triangles is not None else MeshShape(vertices, faces, closed=False)
            self.support_points = self.triangle_shape.vertices
        self.sample_points = local_samples(self.geometry, self.size, self.support_points)

    @property
    def closed_mesh(self) -> bool:
        """A piece of a closed mesh that is not convex (its inside is not its hull's: `whole_shape`)."""
        return self.geometry == "triangles" and self.whole_shape is not None and self.whole_shape.closed

    def place(self, frame: np.ndarray) -> None:
        """Put the body at `frame` @ local (world, mm)."""
        T = frame @ self.local
        self.pose = T
        self.obj.setRotation(T[:3, :3])
        self.obj.setTranslation(T[:3, 3])

    def exact_obj(self):
        """The fcl object for an exact distance or a contact (the triangles of a mesh), at the body's pose."""
        if self.exact is None:
            return self.obj
        self.exact.setRotation(self.pose[:3, :3])
        self.exact.setTranslation(self.pose[:3, 3])
        return self.exact

    def aabb(self) -> tuple[np.ndarray, np.ndarray]:
        """World-aligned box (low, high) around the body at its current pose."""
        R = self.pose[:3, :3]
        c = R @ self.center + self.pose[:3, 3]
        h = np.abs(R) @ self.half
        return c - h, c + h

    def whole_aabb(self) -> tuple[np.ndarray, np.ndarray]:
        """World-aligned box around the whole solid (all the pieces of its mesh)."""
        R = self.pose[:3, :3]
        c = R @ self.whole_box[0] + self.pose[:3, 3]
        h = np.abs(R) @ self.whole_box[1]
        return c - h, c + h

    def reach(self) -> float:
        """Largest distance from the carrying frame's origin to a point of the body."""
        p = self.points @ self.local[:3, :3].T + self.local[:3, 3]
        return float(np.sqrt((p * p).sum(axis=1)).max()) + self.radius

    def from_line(self, point: np.ndarray, direction: np.ndarray) -> float:
        """Largest distance from a line (in the carrying frame) to a point of the body; 0 when the
        body is a solid of revolution about that line (turning about it moves none of its points)."""
        R, t = self.local[:3, :3], self.local[:3, 3]
        if self.axis is not None:
            c = R @ self.axis[0] + t - point
            on_line = np.linalg.norm(c - (c @ direction) * direction) < 1e-9
            if on_line and (self.axis[1] is None or abs(abs(float((R @ self.axis[1]) @ direction)) - 1.0) < 1e-12):
                return 0.0
        p = self.points @ R.T + t - point
        along = p @ direction
        d = np.sqrt(np.maximum((p * p).sum(axis=1) - along * along, 0.0))
        return float(d.max()) + self.radius

    def __repr__(self) -> str:
        return f"Body({self.label})"


_COPIED = ("axis", "center", "edge_directions", "fcl_shapes", "geometry", "half", "kind", "label", "lb", "made_from",
           "name", "owner", "planes", "points", "radius", "sample_points", "size", "solid", "support_points",
           "triangle_shape", "whole_box", "whole_shape")


def copies(bodies: list[Body]) -> list[Body]:
    """New bodies as `make_bodies` made `bodies` (none of them placed yet): the same values, the
    arrays and fcl geometries shared (never changed in place), their own fcl objects, pose and
    local, and their own solid (`whole`), shared by the copies of pieces of one solid."""
    wholes: dict[int, int] = {}
    out = []
    for src in bodies:
        b = Body.__new__(Body)
        for name in _COPIED:
            setattr(b, name, getattr(src, name))
        geom, exact = src.fcl_shapes
        b.obj = fcl.CollisionObject(geom, fcl.Transform())
        b.exact = None if exact is None else fcl.CollisionObject(exact, fcl.Transform())
        b.local = src.local.copy()
        b.pose = np.eye(4)
        b.whole = id(b) if src.whole == id(src) else wholes.setdefault(src.whole, next(_WHOLES))
        out.append(b)
    return out


def make_bodies(kind: str, owner: str, name: str, label: str, shape_kind: str, size: tuple[float, ...],
                local: np.ndarray, vertices=None, faces=None, solid: bool = True,
                hull_solid: bool | None = None) -> list[Body]:
    """The bodies of one solid: one for a primitive or a convex mesh, pieces for another mesh.
    solid: a mesh is a closed volume (else a surface); hull_solid: a convex mesh is measured as
    its solid hull (default: when solid; the arm's link meshes are envelopes: always)."""
    if shape_kind != "mesh":
        b = Body(kind, owner, name, label, shape_kind, size, local, solid=solid)
        b.whole = id(b)
        return [b]
    hull_solid = solid if hull_solid is None else hull_solid
    v = np.asarray(vertices, dtype=float)
    f = np.asarray(faces, dtype=np.int64)
    pieces, whole_shape = _pieces(v, f, solid, hull_solid)
    whole = next(_WHOLES)
    lo, hi = v.min(axis=0), v.max(axis=0)
    whole_box = (0.5 * (lo + hi), 0.5 * (hi - lo))
    out = []
    for pv, pf, hv, hf, bvh, lb, tris in pieces:
        exact = fcl.CollisionObject(bvh, fcl.Transform())
        if hv is None:  # a flat piece: its triangles are the convex object too
            b = Body(kind, owner, name, label, "mesh", (), local, pv, pf, solid=solid, exact=exact,
                     whole_shape=whole_shape, triangles=tris)
        else:
            b = Body(kind, owner, name, label, "convex", (), local, hv, hf, solid=solid, exact=exact,
                     whole_shape=whole_shape, triangles=tris, hull_solid=not lb)
            b.lb = lb
        b.fcl_shapes = (b.fcl_shapes[0], bvh)
        b.whole = whole
        b.whole_box = whole_box
        out.append(b)
    return out


_PIECES: dict[tuple, tuple] = {}
# the solid a mesh's pieces belong to: a number never given to another (the id of an object that
# lives no longer than the call could be given to the next mesh's pieces); far below any id
_WHOLES = itertools.count(1)


def _pieces(v: np.ndarray, f: np.ndarray, solid: bool, hull_solid: bool) -> tuple[list, MeshShape]:
    """(vertices, faces, hull vertices, hull faces, BVH geometry, hull is a lower bound only, the
    piece's triangles) per piece, and the whole mesh; one piece (the hull, exact) for a convex mesh
    measured as its solid hull. Computed once per mesh."""
    import hashlib

    import trimesh

    key = (hashlib.sha1(v.tobytes() + f.tobytes()).digest(), solid, hull_solid)
    if key in _PIECES:
        return _PIECES[key]
    out = []
    whole = MeshShape(v, f, closed=solid)
    if trimesh.Trimesh(v, f, process=False).is_convex:
        hull = _hull(v, f)
        if hull is not None:
            # a surface's hull is only a lower bound: the surface has no inside
            out.append((v, f, hull[0], hull[1], fcl_geometry("mesh", (), v, f), not hull_solid, whole))
    if not out:
        for idx in _split(v, f):
            used, inv = np.unique(f[idx], return_inverse=True)
            pv, pf = v[used], inv.reshape(-1, 3)
            ph = _hull(pv, pf)
            out.append((pv, pf, None if ph is None else ph[0], None if ph is None else ph[1],
                        fcl_geometry("mesh", (), pv, pf), True, MeshShape(pv, pf, closed=False)))
    if len(_PIECES) > 64:
        _PIECES.clear()
    _PIECES[key] = (out, whole)
    return out, whole


def _split(v: np.ndarray, f: np.ndarray) -> list[np.ndarray]:
    """Indices of the faces of each piece: median cuts of the face centres along the longest side."""
    return median_cuts(v[f].mean(axis=1), PIECE)


def _hull(v: np.ndarray, f: np.ndarray):
    """(vertices, faces) of the convex hull, or None when the points are flat or too few."""
    import trimesh

    try:
        h = trimesh.convex.convex_hull(v)
    except Exception:  # qhull refuses flat or degenerate point sets
        return None
    if len(h.faces) < 4 or h.volume <= 1e-9:
        return None
    return np.asarray(h.vertices, dtype=float), np.asarray(h.faces, dtype=np.int64)


def aabb_gap(lo_a: np.ndarray, hi_a: np.ndarray, lo_b: np.ndarray, hi_b: np.ndarray) -> np.ndarray:
    """Distance between world-aligned boxes (0 when they overlap), broadcast over leading axes."""
    gap = np.maximum(lo_a - hi_b, lo_b - hi_a)
    np.maximum(gap, 0.0, out=gap)
    gap *= gap
    # (x² + y²) + z²: the order `.sum(axis=-1)` adds three in (the same bits), without its reduction
    d = gap[..., 0] + gap[..., 1]
    d += gap[..., 2]
    return np.sqrt(d, out=d) if d.ndim else np.sqrt(d)


def local_samples(geometry: str, size: tuple[float, ...], vertices) -> np.ndarray:
    """Points of a body in its own frame whose depth inside another solid bounds the penetration
    depth from below (`shapes.samples`): a box's corners, edge middles, face centres and centre; a
    cylinder's rims (RIM points each), cap centres and centre; a polyhedron's vertices; a sphere's
    centre (its radius is added by the caller)."""
    if geometry == "sphere":
        return np.zeros((1, 3))
    if geometry == "box":
        h = 0.5 * np.asarray(size, dtype=float)
        g = np.array([[i, j, k] for i in (-1, 0, 1) for j in (-1, 0, 1) for k in (-1, 0, 1)], dtype=float)
        return g * h
    if geometry == "cylinder":
        r, h = size[0], 0.5 * size[1]
        a = np.arange(RIM) * 2.0 * math.pi / RIM
        ring = np.stack([r * np.cos(a), r * np.sin(a), np.zeros(RIM)], axis=1)
        return np.concatenate([ring + [0.0, 0.0, -h], ring + [0.0, 0.0, h], [[0.0, 0.0, -h], [0.0, 0.0, h],
                                                                            [0.0, 0.0, 0.0]]])
    return np.asarray(vertices, dtype=float)


def _edge_directions(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """The directions of a polyhedron's edges, unit, each once (up to sign); the diagonals of flat
    faces cut into triangles come too (more directions to try are harmless)."""
    e = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    d = vertices[e[:, 1]] - vertices[e[:, 0]]
    d = d[np.linalg.norm(d, axis=1) > 1e-12]
    d /= np.linalg.norm(d, axis=1)[:, None]
    sign = np.where((d[:, 0] < -1e-9) | ((np.abs(d[:, 0]) <= 1e-9) & ((d[:, 1] < -1e-9)
                    | ((np.abs(d[:, 1]) <= 1e-9) & (d[:, 2] < 0.0)))), -1.0, 1.0)
    d = d * sign[:, None]
    return np.unique(np.round(d, 9), axis=0)


def _planes(vertices: np.ndarray, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The face planes of a convex polyhedron: outward unit normals (F, 3) and offsets (F,) (a
    point x is inside when n·x <= d for every face)."""
    tri = vertices[faces]
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    length = np.linalg.norm(n, axis=1)
    keep = length > 1e-12
    n = n[keep] / length[keep][:, None]
    d = (n * tri[keep, 0]).sum(axis=1)
    centre = vertices.mean(axis=0)
    flip = (n @ centre) > d  # the centre must be inside: turn inward normals out
    n[flip] *= -1.0
    d[flip] *= -1.0
    return n, d
