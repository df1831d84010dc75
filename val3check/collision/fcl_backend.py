"""The fcl backend: the distance and the overlap of two bodies, measured by python-fcl and checked
against the bodies' exact geometry (`shapes`) where fcl is known to be weak.

Everything else of the collision package reasons on the records below and never calls fcl for a
pair of bodies itself; `measurements` counts the queries (the reports' `checks`).

What python-fcl (0.7) gets wrong, and what is done about it (docs/cell.md, "Meshes"):

* a sphere against triangles (a mesh's BVH): contacts come with a negative penetration depth,
  nearest points in the wrong frames or uninitialised: val3check measures a sphere against
  triangles itself (the closest point of the triangles to its centre);
* a shape against triangles: the nearest points come swapped (the BVH must be the first object
  of the query); every pair of nearest points is checked (each on its body's surface, as far
  apart as the distance) and found again by alternate projections when it is not right;
* triangles against anything: an overlap measures 0, and a contact's depth is that of one
  triangle, which says little about the depth of a solid: the depth of an overlap with a mesh is
  computed from the bodies (`estimate`), and fcl's per-triangle depth only adds a lower bound;
* EPA (the depth between convex shapes) can fail or raise on grazing contacts: every fcl call is
  guarded, and the depth of convex shapes is checked against the depth of their sample points
  (a lower bound: the larger is kept);
* a solid wholly inside a closed mesh touches no triangle: `inside` looks for it.
"""

from __future__ import annotations

import math

import fcl
import numpy as np

from ..light_dataclass import dataclass
from .bodies import Body
from .shapes import (
    closest_on_solid,
    closest_on_surface,
    depth_inside,
    overlap_bound,
    samples,
    support,
    triangle_samples,
)

Point = tuple[float, float, float]
TOL_MM = 1e-3  # a point this close to a body's surface is on it; two lengths this close agree
_PROJECTIONS = 200  # alternate projections at most when fcl's nearest points are not right
_CONVEX = ("sphere", "box", "cylinder", "convex")  # bodies fcl measures as solids, depth included


class Distance:
    """The distance between two bodies (mm), > 0 when they are apart, 0 or less when they touch or
    overlap (then `FclBackend.contact` gives the depth). exact: False when a piece of a mesh was
    measured through its hull (a lower bound). `points()`: the nearest points, in world, on a and
    on b (computed when asked, from the poses the bodies had when measured)."""

    __slots__ = ("_a", "_b", "_points", "_pose_a", "_pose_b", "_raw", "exact", "mm")

    def __init__(self, mm: float, exact: bool, a: Body, b: Body, raw, checked: bool = False) -> None:
        self.mm = mm
        self.exact = exact
        self._a, self._b = a, b
        self._pose_a, self._pose_b = a.pose, b.pose
        self._raw = raw
        self._points: tuple[Point, Point] | None = (_point(raw[0]), _point(raw[1])) if checked else None

    def points(self) -> tuple[Point, Point]:
        if self._points is None:
            pa, pb = nearest_points(self._a, self._pose_a, self._b, self._pose_b, self.mm, self._raw)
            self._points = (_point(pa), _point(pb))
        return self._points


@dataclass(frozen=True, slots=True)
class Penetration:
    """Two bodies overlapping: `depth` (mm, > 0) is the penetration depth (the length of the
    shortest translation that separates them, or a lower bound of it: docs/cell.md); point_a, a
    point of body a, and point_b, of body b, are the witnesses: one is the deepest point of its
    body inside the other, the other the point of the other's surface it must reach (their
    distance is the depth), or both the point where fcl found the deepest contact. kind: "contact"
    (their surfaces cross) or "inside" (`inner`, "a" or "b", is wholly inside the other, a closed
    mesh)."""

    depth: float
    point_a: Point
    point_b: Point
    kind: str = "contact"
    inner: str = ""


class FclBackend:
    """Distance and overlap queries between bodies at their current poses (`Body.place`)."""

    def __init__(self) -> None:
        # no signed distance: fcl's loops forever on concentric spheres; an overlap measures 0 or
        # less, and then `contact` gives the depth
        self._distance_request = fcl.DistanceRequest(enable_nearest_points=True)
        self._collision_request = fcl.CollisionRequest(num_max_contacts=16, enable_contact=True)
        self.measurements = 0
        self._estimates: dict[tuple, tuple | None] = {}

    # ---- distance ----------------------------------------------------------------------------------------

    def distance(self, a: Body, b: Body, exact: bool = True) -> Distance:
        """The distance between a and b: the hull of a mesh piece gives a lower bound (exact False)
        unless `exact`, or unless it touches (then the triangles decide)."""
        lower_bound = a.lb or b.lb
        d, raw, checked = self._query(a, a.obj, not a.lb and a.geometry == "triangles",
                                      b, b.obj, not b.lb and b.geometry == "triangles")
        if lower_bound and (exact or d <= 0.0):
            oa, ta = (a.exact_obj(), True) if a.lb else (a.obj, a.geometry == "triangles")
            ob, tb = (b.exact_obj(), True) if b.lb else (b.obj, b.geometry == "triangles")
            d, raw, checked = self._query(a, oa, ta, b, ob, tb)
            lower_bound = False
        return Distance(d, not lower_bound, a, b, raw, checked)

    def _query(self, a: Body, oa, a_tris: bool, b: Body, ob, b_tris: bool) -> tuple[float, tuple, bool]:
        """(distance, (point for a, point for b) as found, whether those points are exact)."""
        self.measurements += 1
        if a.geometry == "sphere" and b_tris:
            return _sphere_to_triangles(a, b)
        if b.geometry == "sphere" and a_tris:
            d, (pb, pa), ok = _sphere_to_triangles(b, a)
            return d, (pa, pb), ok
        swap = b_tris and not a_tris  # with the BVH first, fcl gives the nearest points in world, in order
        res = fcl.DistanceResult()
        try:
            d = fcl.distance(ob, oa, self._distance_request, res) if swap else fcl.distance(oa, ob, self._distance_request, res)
        except Exception:  # fcl's solvers raise on some degenerate configurations: project instead
            pa, pb = _project(a, a.pose, b, b.pose, a.pose[:3, 3])
            return float(np.linalg.norm(pa - pb)), (pa, pb), True
        p0, p1 = res.nearest_points
        return float(d), ((p1, p0) if swap else (p0, p1)), False

    # ---- overlap -----------------------------------------------------------------------------------------

    def contact(self, a: Body, b: Body) -> Penetration | None:
        """How deep a and b (touching or overlapping: distance <= 0) overlap, or None when they only
        touch. A sphere against anything, and any body against a mesh that is not convex or a
        surface: from the bodies themselves (`estimate`; fcl's depth per triangle says nothing of
        the solid, and sphere-triangle depths come negative). Between other convex bodies: fcl's
        (EPA), kept between a lower bound (`estimate`) and an upper bound (the least overlap of
        their projections on their axes and fcl's normal, `shapes.overlap_bound`)."""
        self.measurements += 1
        est = self.estimate(a, b)
        if a.geometry in _CONVEX and b.geometry in _CONVEX and "sphere" not in (a.geometry, b.geometry):
            found = self._convex_depth(a, b, est)
        else:  # a sphere (exact), or a mesh: fcl's depth per triangle says nothing of the solid
            found = est
        if found is None or not found[0] > 0.0:
            return None
        depth, pa, pb = found
        for inner, outer, which in ((a, b, "a"), (b, a, "b")):
            if outer.geometry == "convex" and outer.solid and _contains(outer, inner):
                return Penetration(depth, _point(pa), _point(pb), "inside", which)
        return Penetration(depth, _point(pa), _point(pb))

    def _fcl_collide(self, oa, ob):
        """fcl's deepest contact of two objects (depth made positive: sphere-triangle depths come
        negative), or None (no contact, or fcl failed: EPA raises on some grazing contacts)."""
        res = fcl.CollisionResult()
        try:
            fcl.collide(oa, ob, self._collision_request, res)
        except Exception:
            return None
        if not res.contacts:
            return None
        c = max(res.contacts, key=lambda c: abs(c.penetration_depth))
        depth = abs(float(c.penetration_depth))
        pos = np.asarray(c.pos, dtype=float)
        n = np.asarray(c.normal, dtype=float)
        if not (math.isfinite(depth) and np.isfinite(pos).all() and np.isfinite(n).all()):
            return None
        return depth, pos, n

    def _convex_depth(self, a: Body, b: Body, est) -> tuple | None:
        """(depth, point of a, point of b) of two overlapping convex bodies (no sphere)."""
        got = self._fcl_collide(a.obj, b.obj)
        hints = [] if got is None or np.linalg.norm(got[2]) < 1e-9 else [got[2]]
        if est is not None:
            hints.append(est[2] - est[1])  # from the deepest point found towards where it gets out
        upper, u = overlap_bound(a, b, np.array(hints).reshape(-1, 3))
        if upper <= 0.0:
            return None  # a separating direction: they only touch
        lower = est[0] if est is not None else 0.0
        if got is not None and lower <= got[0] <= upper + TOL_MM:
            n = got[2] / np.linalg.norm(got[2])
            pa, pb = _witnesses(a, b, n, got[0], got[1])
            return got[0], pa, pb
        if est is not None and (got is None or got[0] < lower):
            return est
        pa = support(a, a.pose, u)  # fcl's depth is above a separating translation: take that
        return upper, pa, pa - upper * u

    def estimate(self, a: Body, b: Body) -> tuple[float, np.ndarray, np.ndarray] | None:
        """(depth, point of a, point of b) of the deepest point of one body inside the other found
        from their exact geometry, or None when none is inside: for a sphere its radius plus how
        deep its centre is (exact against a convex solid); for another body its sample points
        (`bodies.local_samples`). A lower bound of the penetration depth."""
        best = None
        for x, y, swapped in ((a, b, False), (b, a, True)):
            got = self._deepest(x, y)
            if got is not None and (best is None or got[0] > best[0]):
                depth, px, qy = got
                best = (depth, qy, px) if swapped else (depth, px, qy)
        return best

    def _deepest(self, x: Body, y: Body) -> tuple[float, np.ndarray, np.ndarray] | None:
        """The deepest point of x inside y's solid (a sphere: inside or within its radius of y's
        surface), and the point of y's surface nearest to it. The points of x tried: a sphere's
        centre; a primitive's or a hull's sample points; the triangles of a piece of a mesh where
        they are in y's box, sampled every `_spacing(y)` mm."""
        sphere = x.geometry == "sphere"
        if not sphere and y.geometry == "triangles" and not y.closed_mesh:
            return None  # a surface has no inside
        whole = x.geometry != "triangles" and y.geometry == "triangles"  # the same for every piece of y's mesh
        key = (id(x), id(y.whole_shape) if whole else id(y), x.pose.tobytes(), y.pose.tobytes())
        if key in self._estimates:
            return self._estimates[key]
        out = None
        if sphere:
            r, c = x.size[0], x.pose[:3, 3]
            d = float(depth_inside(y, y.pose, c[None])[0])
            if r + d > 0.0:
                q, _ = closest_on_solid(y, y.pose, c)
                u = q - c
                length = np.linalg.norm(u)
                u = u / length if length > 0.0 else np.array([0.0, 0.0, 1.0])
                out = (r + d, c - r * u if d > 0.0 else c + r * u, q)
        else:
            pts = samples(x, x.pose) if x.geometry != "triangles" else triangle_samples(x, y)
            if len(pts):
                depth = depth_inside(y, y.pose, pts, outside=False)
                k = int(np.argmax(depth))
                if depth[k] > 0.0:
                    out = (float(depth[k]), pts[k], closest_on_solid(y, y.pose, pts[k])[0])
        if len(self._estimates) > 256:
            self._estimates.clear()
        self._estimates[key] = out
        return out

    def inside(self, inner: Body, outer: Body) -> Penetration | None:
        """`inner` wholly inside the closed mesh `outer` belongs to, when they do not touch (the
        caller measured a distance > 0): a point of inner is inside the mesh."""
        if not outer.closed_mesh:
            return None
        self.measurements += 1
        R, t = outer.pose[:3, :3], outer.pose[:3, 3]
        p = samples(inner, inner.pose)[0]
        if not outer.whole_shape.inside(R.T @ (p - t)):
            return None
        got = self._deepest(inner, outer)
        if got is None:  # inside by the parity test, yet no point found inside: at least touching
            got = (0.0, p, closest_on_solid(outer, outer.pose, p)[0])
        depth, pi, po = got
        return Penetration(depth, _point(pi), _point(po), "inside", "a")


# ---- the exact geometry behind the queries ---------------------------------------------------------------------


def _sphere_to_triangles(s: Body, t: Body) -> tuple[float, tuple, bool]:
    """A sphere against the triangles of a body: (distance, (point on the sphere, on the
    triangles), exact)."""
    c = s.pose[:3, 3]
    q, d = closest_on_surface(t, t.pose, c)
    r = s.size[0]
    u = q - c
    p = c + r * u / d if d > 0.0 else c
    return d - r, (p, q), True


def nearest_points(a: Body, pose_a: np.ndarray, b: Body, pose_b: np.ndarray, mm: float, raw) -> tuple[np.ndarray, np.ndarray]:
    """The nearest points of a and b in world, from fcl's (p0, p1): taken as they are, swapped,
    or from each body's frame, whichever puts each point on its body's surface at the distance
    measured; else found again by alternate projections from there."""
    p0, p1 = (np.asarray(p, dtype=float) for p in raw)
    candidates = [(p0, p1), (p1, p0)]
    for u, v in ((p0, p1), (p1, p0)):
        candidates.append((pose_a[:3, :3] @ u + pose_a[:3, 3], pose_b[:3, :3] @ v + pose_b[:3, 3]))
    best, err = None, math.inf
    for pa, pb in candidates:
        if not (np.isfinite(pa).all() and np.isfinite(pb).all()):
            continue
        e = (closest_on_surface(a, pose_a, pa)[1] + closest_on_surface(b, pose_b, pb)[1]
             + abs(float(np.linalg.norm(pa - pb)) - max(mm, 0.0)))
        if e < err:
            best, err = (pa, pb), e
    if best is not None and err <= TOL_MM * (1.0 + 1e-3 * abs(mm)):
        return best
    start = best[0] if best is not None else pose_a[:3, 3]
    return _project(a, pose_a, b, pose_b, start)


def _project(a: Body, pose_a: np.ndarray, b: Body, pose_b: np.ndarray, start: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Nearest points by alternate projections onto the two surfaces (exact for convex bodies
    apart; a local answer for a piece of a mesh, which is small)."""
    pa = closest_on_surface(a, pose_a, start)[0]
    pb = closest_on_surface(b, pose_b, pa)[0]
    for _ in range(_PROJECTIONS):
        na = closest_on_surface(a, pose_a, pb)[0]
        nb = closest_on_surface(b, pose_b, na)[0]
        done = np.linalg.norm(na - pa) + np.linalg.norm(nb - pb) < 1e-9
        pa, pb = na, nb
        if done:
            break
    return pa, pb


def _witnesses(a: Body, b: Body, n: np.ndarray, depth: float, pos: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The witness points of the penetration of two convex bodies along n (fcl's normal, from a
    to b, checked): the point of a deepest inside b (on the support plane of a along n, at fcl's
    contact point when that is on a's surface), and the point of b's surface it must reach."""
    # the normal points from a to b: a's support point along it is inside b (else fcl's sign is the other)
    if depth_inside(b, b.pose, support(a, a.pose, n)[None])[0] < depth_inside(b, b.pose, support(a, a.pose, -n)[None])[0]:
        n = -n
    s = support(a, a.pose, n)
    pa = pos + float(n @ (s - pos)) * n
    if closest_on_surface(a, a.pose, pa)[1] > TOL_MM:
        pa = s
    pb = pa - depth * n
    if closest_on_surface(b, b.pose, pb)[1] > TOL_MM * (1.0 + depth):
        pb = closest_on_surface(b, b.pose, pa)[0]
    return pa, pb


def _contains(outer: Body, inner: Body) -> bool:
    """Whether the convex solid `outer` (a closed convex mesh) holds `inner` wholly: every sample
    point of inner inside it (a sphere: its centre at least its radius deep)."""
    if inner.geometry == "sphere":
        return bool(depth_inside(outer, outer.pose, inner.pose[:3, 3][None])[0] >= inner.size[0])
    return bool((depth_inside(outer, outer.pose, samples(inner, inner.pose), outside=False) > 0.0).all())


def _point(p) -> Point:
    return (float(p[0]), float(p[1]), float(p[2]))
