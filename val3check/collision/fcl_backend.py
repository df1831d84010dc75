"""The fcl backend: the distance and the contact between two bodies, measured by python-fcl.

Everything else of the collision package reasons on the records below and never calls fcl for a
pair of bodies itself; `measurements` counts the queries (the reports' `checks`).
"""

from __future__ import annotations

from dataclasses import dataclass

import fcl

from .bodies import Body

Point = tuple[float, float, float]


@dataclass(frozen=True, slots=True)
class Distance:
    """The distance between two bodies (mm): 0 or less when they touch or overlap (then
    `FclBackend.collide` gives the depth). point_a, point_b: the nearest points as fcl gives them.
    exact: False when a piece of a non-convex mesh was measured through its hull (a lower bound)."""

    mm: float
    point_a: Point
    point_b: Point
    exact: bool


@dataclass(frozen=True, slots=True)
class Penetration:
    """Two bodies overlapping: the deepest of fcl's contacts, its depth (mm) and its point (world)."""

    depth: float
    point: Point


class FclBackend:
    """Distance and collision queries between bodies at their current poses (`Body.place`)."""

    def __init__(self) -> None:
        # no signed distance: fcl's loops forever on concentric spheres; an overlap measures 0 or
        # less, and then `collide` gives the depth
        self._distance_request = fcl.DistanceRequest(enable_nearest_points=True)
        self._collision_request = fcl.CollisionRequest(num_max_contacts=16, enable_contact=True)
        self.measurements = 0

    def distance(self, a: Body, b: Body, exact: bool = True) -> Distance:
        """The distance between a and b: the hull of a mesh piece gives a lower bound (exact False)
        unless `exact`, or unless it touches (then the triangles decide)."""
        res = fcl.DistanceResult()
        lower_bound = a.lb or b.lb
        d = fcl.distance(a.obj, b.obj, self._distance_request, res)
        self.measurements += 1
        if lower_bound and (exact or d <= 0.0):
            res = fcl.DistanceResult()
            d = fcl.distance(a.exact_obj() if a.lb else a.obj, b.exact_obj() if b.lb else b.obj,
                             self._distance_request, res)
            self.measurements += 1
            lower_bound = False
        pa, pb = res.nearest_points
        return Distance(float(d), _point(pa), _point(pb), not lower_bound)

    def collide(self, a: Body, b: Body) -> Penetration | None:
        """The deepest contact between a and b (the triangles of meshes), or None."""
        res = fcl.CollisionResult()
        fcl.collide(a.exact_obj(), b.exact_obj(), self._collision_request, res)
        self.measurements += 1
        if not res.contacts:
            return None
        c = max(res.contacts, key=lambda c: c.penetration_depth)
        return Penetration(float(c.penetration_depth), _point(c.pos))

    def surface_distance(self, a: Body, b: Body) -> float:
        """The distance between the triangles (or shapes) of a and b, without nearest points."""
        d = fcl.distance(a.exact_obj(), b.exact_obj(), self._distance_request, fcl.DistanceResult())
        self.measurements += 1
        return float(d)


def _point(p) -> Point:
    return (float(p[0]), float(p[1]), float(p[2]))
