"""Measuring one watch at one position of a motion: its body pairs nearest first (the boxes), the
distances and overlaps of those that matter (the fcl backend), and solids wholly inside a closed
mesh (which fcl, measuring to the surface, does not see).

A clearance is the distance between two solids when they are apart, and minus the penetration
depth when they overlap (docs/cell.md, "What a clearance is")."""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator

import numpy as np

from ..light_dataclass import dataclass
from .bodies import Body, aabb_gap
from .fcl_backend import Distance, FclBackend, Penetration, Point
from .groups import Watch
from .path import ArmPath
from .world import World


class Nearest:
    """Where a measured clearance is: body a, body b, and a point of each (world, mm): the
    nearest points when they are apart (from a `Distance`, computed when asked), the witnesses of
    the penetration when they overlap (`Penetration`)."""

    __slots__ = ("_distance", "_points", "a", "b")

    def __init__(self, a: Body, b: Body, distance: Distance | None = None,
                 points: tuple[Point, Point] | None = None) -> None:
        self.a = a
        self.b = b
        self._distance = distance
        self._points = points

    @property
    def points(self) -> tuple[Point, Point]:
        """(point of a, point of b)."""
        if self._points is None:
            self._points = self._distance.points()  # type: ignore[union-attr]
        return self._points


@dataclass(frozen=True, slots=True)
class Hit:
    """The deepest overlap of a measurement: the two bodies, a contact point, the depth (mm) and
    the kind ("contact": with the cell, "self": two parts of the arm, "inside": contained)."""

    a: Body
    b: Body
    point: Point
    depth: float
    kind: str


@dataclass(frozen=True, slots=True)
class Measurement:
    """A watch measured at one position.

    bound        the smallest distance between its bodies (minus the penetration depth where they
                 overlap), or a lower bound of it when every remaining pair is `need` or more apart
    clearance    the same over the pairs that count for clearance (not those landing or lifting off
                 in this motion: `landing`)
    exact        whether `clearance` is exact; nearest: where it is, when exact (else None)
    hit          the deepest overlap, or None
    valid_until, clearance_valid_until   bound and clearance hold before these positions only (a
                 pair allowed to touch since a grasp or release is left out until then), inf
                 otherwise"""

    bound: float
    clearance: float
    exact: bool
    nearest: Nearest | None
    hit: Hit | None
    valid_until: float
    clearance_valid_until: float


class Probe:
    """Measures the watches of one motion (`path`) in `world` through `backend`.

    allowed_until  for each pair allowed to touch since a grasp or a release: the first position
                   where its bodies are apart; the pair is left out before it"""

    def __init__(self, world: World, path: ArmPath, backend: FclBackend) -> None:
        self.world = world
        self.path = path
        self.backend = backend
        self.allowed_until: dict[frozenset[int], float] = {}
        self._insides: dict[tuple, list] = {}  # per position and watch: the solids inside a closed mesh

    def place(self, w: Watch, u: float) -> None:
        """Put the bodies of both sides of a watch where they are at position u."""
        self.path.place(w.a, u)
        if w.b is not None:
            self.path.place(w.b, u)

    def pairs(self, w: Watch, u: float | None = None) -> Iterable[tuple[float, Body, Body]]:
        """(gap between boxes, body a, body b) for the body pairs of a watch, nearest first: at a
        sample, from the boxes `bounds.prepare` computed for the whole motion; else from the bodies
        where they are. Against the static set, made as they are read (a measurement reads the
        nearest few of many)."""
        path, world = self.path, self.world
        A = w.a.bodies
        k = -1 if u is None else int(u)
        at_sample = k == u and path.box_lo is not None
        if w.b is None:
            if not world.static:
                return []
            if at_sample:
                cols = [path.box_col[id(b)] for b in A]
                lo, hi = path.box_lo[k, cols], path.box_hi[k, cols]  # type: ignore[index]
            else:
                lo, hi = _boxes(A)
            gaps = aabb_gap(lo[:, None, :], hi[:, None, :], world.static_lo[None], world.static_hi[None]).ravel()
            return _nearest_first(gaps, A, world.static)
        Bs = w.b.bodies
        if at_sample:
            cols = [path.box_col[id(b)] for b in A + Bs]
            lo, hi = path.box_lo[k, cols], path.box_hi[k, cols]  # type: ignore[index]
        else:
            lo, hi = _boxes(A + Bs)
        na = len(A)
        gaps = aabb_gap(lo[:na, None, :], hi[:na, None, :], lo[None, na:], hi[None, na:])
        out = [(float(gaps[i, j]), A[i], Bs[j]) for i in range(na) for j in range(len(Bs))
               if (id(A[i]), id(Bs[j])) not in w.skip]
        out.sort(key=lambda x: x[0])
        return out

    def measure(self, w: Watch, u: float, need: float, exact_mesh: bool | None = None,
                landing: set[tuple[int, int]] | frozenset = frozenset()) -> Measurement:
        """Measure a watch at position u: its pairs nearest first, until the next pair's boxes are
        further than what was found or than `need` (then that gap is a lower bound). exact_mesh:
        measure meshes to their triangles, not their pieces' hulls (default: when `need` is
        infinite); landing: body pairs left out of the clearance (`bounds.Track.landing`)."""
        self.place(w, u)
        pairs = self.pairs(w, u)
        # left-out pairs come back at this position: the values hold before it only (the clearance
        # ignores the landing ones anyway)
        valid = valid_clear = math.inf
        if self.allowed_until:
            until = self.allowed_until
            kept = []
            for gap, ba, bb in pairs:
                at = until.get(frozenset((id(ba), id(bb))), -1.0)
                if at <= u:
                    kept.append((gap, ba, bb))
                else:
                    valid = min(valid, at)
                    if (id(ba), id(bb)) not in landing:
                        valid_clear = min(valid_clear, at)
            pairs = kept
        bound = clear = math.inf
        exact, nearest = True, None
        # (body a, body b, leaves the clearance alone, the overlap when known)
        touching: list[tuple[Body, Body, bool, Penetration | None]] = [
            (ba, bb, False, pen) for ba, bb, pen in self.insides(w, u)]
        for gap, ba, bb in pairs:
            if gap > max(clear, 0.0):
                break
            if gap >= need:
                bound = min(bound, gap)
                if gap < clear:
                    clear, exact, nearest = gap, False, None
                break
            dist = self.backend.distance(ba, bb, need == math.inf if exact_mesh is None else exact_mesh)
            lands = bool(landing) and (id(ba), id(bb)) in landing
            if dist.mm <= 0.0:  # overlapping or touching: the depth decides, below
                touching.append((ba, bb, lands, None))
                continue
            bound = min(bound, dist.mm)
            if not lands and dist.mm < clear:
                clear, exact = dist.mm, dist.exact
                nearest = Nearest(ba, bb, dist) if dist.exact else None
        hit = None
        kind = "contact" if w.b is None else "self"
        for ba, bb, lands, known in touching:
            pen = known if known is not None else self.backend.contact(ba, bb)
            depth = pen.depth if pen is not None else 0.0
            bound = min(bound, -depth)
            if pen is not None and pen.inner == "b":  # a solid inside a closed mesh comes first
                x, y, px, py = bb, ba, pen.point_b, pen.point_a
            elif pen is not None:
                x, y, px, py = ba, bb, pen.point_a, pen.point_b
            if not lands and -depth <= clear:
                # overlapping: the penetration's witnesses; touching: where they touch
                found = Nearest(x, y, points=(px, py)) if pen is not None else Nearest(ba, bb, self.backend.distance(ba, bb))
                clear, exact, nearest = -depth, True, found
            if pen is not None and (hit is None or depth > hit.depth):
                hit = Hit(x, y, px, depth, "inside" if pen.kind == "inside" else kind)
        return Measurement(bound, clear, exact, nearest, hit, valid, valid_clear)

    def _crosses(self, body: Body, pieces: list[Body], lo: np.ndarray, hi: np.ndarray) -> bool:
        """Whether the body touches the surface of a mesh (given by its pieces): then it is not
        wholly inside, and the pairs measure the overlap."""
        for p in pieces:
            plo, phi = p.aabb()
            if float(aabb_gap(lo, hi, plo, phi)) <= 0.0 and self.backend.distance(body, p).mm <= 0.0:
                return True
        return False

    def insides(self, w: Watch, u: float) -> list[tuple[Body, Body, Penetration]]:
        """The bodies of one side of the watch wholly inside a closed mesh of the other (fcl
        measures only to the surface, so this is looked for apart): (inner, a piece of the mesh,
        the overlap). Only bodies whose box lies in the mesh's box, and that touch none of its
        triangles, are tested."""
        key = (u, id(w))
        if key in self._insides:
            return self._insides[key]
        world = self.world
        self.place(w, u)
        out: list[tuple[Body, Body, Penetration]] = []
        sides = (w.a.bodies, world.static if w.b is None else w.b.bodies)
        for inners, outers in (sides, sides[::-1]):
            wholes: dict[int, list[Body]] = {}
            for o in outers:
                if o.closed_mesh:
                    wholes.setdefault(o.whole, []).append(o)
            for pieces in wholes.values():
                outer = pieces[0]
                olo, ohi = outer.whole_aabb()
                for inner in inners:
                    if inner.whole == outer.whole or any(
                            (id(inner), id(p)) in w.skip or (id(p), id(inner)) in w.skip
                            or frozenset((id(inner), id(p))) in world.allowed for p in pieces):
                        continue
                    lo, hi = inner.aabb()
                    if np.any(lo < olo) or np.any(hi > ohi) or self._crosses(inner, pieces, lo, hi):
                        continue
                    pen = self.backend.inside(inner, outer)
                    if pen is not None:
                        out.append((inner, outer, pen))
        if len(self._insides) > 1024:
            self._insides.clear()
        self._insides[key] = out
        return out


def _nearest_first(gaps: np.ndarray, A: list[Body], static: list[Body]) -> Iterator[tuple[float, Body, Body]]:
    S = len(static)
    g = gaps.tolist()
    for i in np.argsort(gaps, kind="stable").tolist():
        yield g[i], A[i // S], static[i % S]


def _boxes(bodies: list[Body]) -> tuple[np.ndarray, np.ndarray]:
    """World-aligned boxes (low, high), (B, 3), of bodies at their current poses."""
    P = np.array([b.pose for b in bodies])
    R = P[:, :3, :3]
    c = (R @ np.array([b.center for b in bodies])[:, :, None])[..., 0] + P[:, :3, 3]
    h = (np.abs(R) @ np.array([b.half for b in bodies])[:, :, None])[..., 0]
    return c - h, c + h


def _point(p) -> Point:
    return (float(p[0]), float(p[1]), float(p[2]))
