"""The sweep along one motion: conservative advancement of every watch between the samples, then
the clearance per sample and the motion's minimum (docs/cell.md, "How the check works").

* Conservative advancement: a watch measured at distance d need not be measured again until the
  motion bound since then reaches d + touch; the next check is put there (aligned down to a
  sample, or to 1/GRID of a sample, never less than MIN_STEP of a sample ahead). Between checks
  no contact can have happened. Far from everything, checks are rare; close to something they
  get dense, down to sub-sample steps for a fast motion that grazes a thin obstacle between two
  samples.
* The measurements give, per sample, a lower bound of the clearance to the cell (the static set;
  the arm against itself is checked for contact only); the minimum of the motion is then refined
  (checks where the bound could still be below the best value found) to within `tolerance`, and
  every sample closer than the margin is measured exactly.
"""

from __future__ import annotations

import math

import numpy as np

from ..light_dataclass import dataclass
from .bodies import aabb_gap
from .bounds import Track, prepare, scene_layout
from .fcl_backend import FclBackend
from .measure import Nearest, Probe
from .path import ArmPath
from .results import Clearance, Contact, MotionReport
from .world import World

GRID = 16  # below one sample, checks are aligned down to 1/GRID of a sample
MIN_STEP = 1.0 / 256.0  # the smallest step between two checks, in samples
MAX_TOLERANCE_MM = 0.4  # the reported minimum clearance of a motion is within this of the true one ...
FAR_MM = 50.0  # ... when it is below this; beyond, within 5 %
EXACT_CAP = 20000  # measurements per motion spent on exact clearances (minimum, closer than the margin)


@dataclass(frozen=True, slots=True)
class Closest:
    """The smallest exact clearance to the cell found so far: mm, at position u, where."""

    mm: float
    u: float
    nearest: Nearest


class Sweep:
    """One motion (`path`) checked in `world`: `run(report)` fills a MotionReport.

    margin: clearance below it is a warning (every sample below it is measured exactly);
    tolerance_mm: how close to the true minimum the reported minimum is (see `tolerance`)."""

    def __init__(self, world: World, backend: FclBackend, path: ArmPath, margin: float, tolerance_mm: float) -> None:
        self.world = world
        self.path = path
        self.backend = backend
        self.margin = margin
        self.touch = world.touch
        self.tol = tolerance_mm
        self.probe = Probe(world, path, backend)
        self.closest: Closest | None = None
        self._inside_first: set[int] = set()  # arm-side bodies whose box at the first sample is in a closed mesh's box

    def run(self, report: MotionReport, per_unit: np.ndarray) -> None:
        """Check the motion: contacts (with their times), the clearance per sample and the minimum
        (`per_unit`: radians or mm per joint unit). The touch allowances of pairs that moved apart
        end with the motion."""
        world, path = self.world, self.path
        watches = world.watches()
        for g in world.arm_groups():
            g.placed = -1.0
        steps = path.step_travel(per_unit)
        tracks: list[Track] = []
        if watches:
            layout = world.per_scene("layout", lambda: scene_layout(world.arm_groups(), watches))
            tracks = prepare(path, layout, watches, steps, world.static_lo, world.static_hi, self.touch)
        self._inside_first = self._inside_static_meshes()
        self.probe.allowed_until = self._apart_from()
        for tr in tracks:
            tr.landing = self._landing(tr) | self._still_allowed(tr)
        for tr in tracks:
            self._advance(tr, report)
        report.contacts.sort(key=lambda c: c.time)
        # clearance of what the motion moves: a link no joint moves (the base) is checked for contact only
        self._refine([tr for tr in tracks if tr.watch.b is None and tr.watch.a.movers], report)
        best = self.closest
        if best is not None:
            near = best.nearest
            report.min_clearance = Clearance(float(best.mm), path.t(best.u), near.a.label, near.b.label,
                                             *near.points)
            report.too_close = (report.first_contact is None and report.starts_in_collision is None
                                and self.margin > 0.0 and best.mm < self.margin)
        n = path.last
        for key, at in self.probe.allowed_until.items():
            if at <= n - 1:
                del world.allowed[key]  # apart now: checked like any pair from the next motion on

    # ---- before the first check ----------------------------------------------------------------------

    def _apart_from(self) -> dict[frozenset[int], float]:
        """For each pair allowed to touch since a grasp or a release: the first sample where its two
        bodies are apart (further than the touch tolerance); from there on it is checked. n + 1
        when they stay together for the whole motion."""
        world, path = self.world, self.path
        out: dict[frozenset[int], float] = {}
        if not world.allowed:
            return out
        owner = {id(b): g for g in world.arm_groups() for b in g.bodies}
        n = path.last
        for key, (a, b) in world.allowed.items():
            ga, gb = owner.get(id(a)), owner.get(id(b))
            at = float(n + 1)
            for k in range(n + 1):
                boxes = [body.aabb() if g is None else path.body_box(id(body), k) for body, g in ((a, ga), (b, gb))]
                if float(aabb_gap(*boxes[0], *boxes[1])) > self.touch:
                    at = float(k)  # the boxes are apart: so are the bodies
                    break
                for body, g in ((a, ga), (b, gb)):
                    if g is not None:
                        body.place(path.poses[g.link][k])
                if self.backend.distance(a, b, False).mm > self.touch:
                    at = float(k)
                    break
            for g in (ga, gb):
                if g is not None:
                    g.placed = -1.0
            out[key] = at
        return out

    def _inside_static_meshes(self) -> set[int]:
        """The arm-side bodies whose box at the first sample lies inside the box of a closed mesh of
        the cell (they may be wholly inside it)."""
        boxes = []
        seen = set()
        for b in self.world.static:
            if b.closed_mesh and b.whole not in seen:
                seen.add(b.whole)
                boxes.append(b.whole_aabb())
        path = self.path
        if not boxes or path.box_lo is None:
            return set()
        lo, hi = path.box_lo[0], path.box_hi[0]  # type: ignore[index]  # (B, 3)
        inside = np.zeros(len(lo), dtype=bool)
        for olo, ohi in boxes:
            inside |= np.all(lo >= olo, axis=1) & np.all(hi <= ohi, axis=1)
        cols = {i: key for key, i in path.box_col.items()}
        return {cols[i] for i in np.nonzero(inside)[0]}

    def _may_be_inside_a_mesh(self, tr: Track) -> bool:
        """Whether a body of one side may lie wholly inside a closed mesh of the other at the first
        sample: its box inside the mesh's box."""
        w = tr.watch
        if w.b is None and not any(b.closed_mesh for b in w.a.bodies):
            return any(id(b) in self._inside_first for b in w.a.bodies)
        others = self.world.static if w.b is None else w.b.bodies
        for inners, outers in ((w.a.bodies, others), (others, w.a.bodies)):
            meshes = [b for b in outers if b.closed_mesh]
            if not meshes:
                continue
            self.probe.place(w, 0.0)
            boxes = [m.whole_aabb() for m in meshes]
            for inner in inners:
                lo, hi = inner.aabb()
                if any(np.all(lo >= olo) and np.all(hi <= ohi) for olo, ohi in boxes):
                    return True
        return False

    def _still_allowed(self, tr: Track) -> set[tuple[int, int]]:
        """Body pairs of the watch allowed to touch since a grasp or a release (a part let go while
        the arm still moved: resetMotion() in stop()): like landing pairs, out of the clearance of
        the motion in which they move apart, checked for contact once apart."""
        world, w = self.world, tr.watch
        if not world.allowed:
            return set()
        a = {id(b) for b in w.a.bodies}
        other = {id(b) for b in (world.static if w.b is None else w.b.bodies)}
        out = set()
        for key in world.allowed:
            x, y = tuple(key)
            if x in a and y in other:
                out.add((x, y))
            elif y in a and x in other:
                out.add((y, x))
        return out

    def _landing(self, tr: Track) -> set[tuple[int, int]]:
        """Body pairs touching (within the touch tolerance, not deeper) at the motion's first or last
        sample: a part set down on a pallet, a tool lifted off a part it let go. They are checked for
        contact all along, but left out of the clearance: touching there is the motion's purpose."""
        out: set[tuple[int, int]] = set()
        w = tr.watch
        n = self.path.last
        for u, end_gap in (((0.0, tr.gap_first), (float(n), tr.gap_last)) if n else ((0.0, tr.gap_first),)):
            if end_gap > self.touch:
                continue
            self.probe.place(w, u)
            for gap, ba, bb in self.probe.pairs(w, u):
                if gap > self.touch:
                    break
                d = self.backend.distance(ba, bb).mm
                if d <= self.touch:
                    pen = self.backend.contact(ba, bb) if d <= 0.0 else None
                    if pen is None or pen.depth <= self.touch:
                        out.add((id(ba), id(bb)))
        return out

    # ---- conservative advancement ----------------------------------------------------------------------

    def _advance(self, tr: Track, report: MotionReport) -> None:
        """Conservative advancement of one watch along the motion: no contact can happen between
        two of its checks, nor in a step that the boxes alone keep apart."""
        path, probe = self.path, self.probe
        n = path.last
        first = tr.first_todo  # the first step the boxes do not keep apart (-1: none)
        if n == 0 or tr.gap_first <= 0.0 or first == 0:
            u = 0.0
        elif self._may_be_inside_a_mesh(tr):
            u = 0.0  # a solid wholly inside a closed mesh is far from its pieces' boxes: look
        elif first < 0:
            return
        else:
            u = float(first)
        end = tr.path_bound[-1]
        todo = np.nonzero(~tr.box_free)[0]  # the steps the boxes do not keep apart
        while True:
            need = end - tr.bound_at(u)
            m = probe.measure(tr.watch, u, need if u > 0.0 else math.inf, landing=tr.landing)
            bound, hit = m.bound, m.hit
            self._record(tr, u, m.clearance, m.exact, m.nearest, m.clearance_valid_until)
            if hit is not None and hit.depth > self.touch:
                if not tr.in_contact:
                    c = Contact(path.t(u), hit.a.label, hit.b.label, hit.point, hit.depth, hit.kind)
                    if u == 0.0:
                        if report.starts_in_collision is None:
                            report.starts_in_collision = c
                    else:
                        if tr.first_contact is None:
                            tr.first_contact = c
                            report.contacts.append(c)
                        if report.first_contact is None or c.time < report.first_contact.time:
                            report.first_contact = c
                    tr.in_contact = True
                if u >= n:
                    return
                u = float(math.floor(u) + 1)
                continue
            tr.in_contact = False
            allowed = max(bound, 0.0) + self.touch - (hit.depth if hit is not None else 0.0)
            valid = m.valid_until
            if valid <= n and tr.bound_at(valid) - tr.bound_at(u) > allowed:
                valid = math.inf  # the certified step ends before the left-out pair comes back
            if u >= n or (valid > n and tr.bound_at(n) - tr.bound_at(u) <= allowed):
                return  # certified to the end of the motion
            uc = min(tr.position_at(tr.bound_at(u) + allowed), valid)
            k = np.searchsorted(todo, math.floor(uc))  # the next step the boxes do not keep apart
            if k >= len(todo):
                return
            u = snap(u, max(uc, float(todo[k])))

    def _record(self, tr: Track, u: float, d: float, exact: bool, nearest: Nearest | None,
                valid: float = math.inf) -> None:
        """Record a measurement in the watch's track, and keep the closest exact clearance to the
        cell (the static set) of what the motion moves."""
        tr.record(u, d, exact, valid)
        w = tr.watch
        if w.b is None and w.a.movers and exact and nearest is not None and (self.closest is None or d < self.closest.mm):
            self.closest = Closest(d, u, nearest)

    # ---- the clearance per sample ------------------------------------------------------------------------

    def _refine(self, tracks: list[Track], report: MotionReport) -> None:
        """Per-sample clearance: the lowest bound over the watches, then measured exactly at the
        samples closer than the margin and where the motion's minimum may be, until that minimum is
        known within the tolerance."""
        n = len(self.path.times)
        if not tracks:
            report.clearance = np.full(n, np.inf)
            report.exact = np.ones(n, dtype=bool)
            return
        spent = 0
        L = np.array([tr.lower for tr in tracks])
        E = np.array([tr.exact for tr in tracks])
        for i, tr in enumerate(tracks):  # the tracks write their bounds into these rows from now on
            tr.lower, tr.exact = L[i], E[i]
        while spent < EXACT_CAP:
            low = L.min(axis=0)
            arg = L.argmin(axis=0)
            ex = E[arg, np.arange(n)]
            best = self.closest.mm if self.closest is not None else math.inf
            target = best - self.tolerance(best)
            todo: list[tuple[int, float]] = []  # (sample, measure the watches whose bound is below this)
            if report.first_contact is None and report.starts_in_collision is None:
                cand = ~ex & (low < target)
                if cand.any():  # the sample whose bound is lowest: it may hold the minimum
                    k = int(np.argmin(np.where(cand, low, np.inf)))
                    todo.append((k, target))
            if self.margin > 0.0:
                todo.extend((int(k), self.margin) for k in np.nonzero(~ex & (low < self.margin))[0])
            if not todo:
                break
            for k, limit in todo:
                found = math.inf
                for i in sorted(np.nonzero((L[:, k] < limit) & ~E[:, k])[0], key=lambda i: L[i, k]):
                    if L[i, k] >= found:
                        break  # this watch cannot be the closest at this sample
                    tr = tracks[i]
                    # exact below the limit; above it a bound is all that is needed
                    m = self.probe.measure(tr.watch, float(k), limit, exact_mesh=True, landing=tr.landing)
                    self._record(tr, float(k), m.clearance, m.exact, m.nearest, m.clearance_valid_until)
                    found = min(found, m.clearance)
                    spent += 1
        report.clearance = L.min(axis=0)
        report.exact = E[L.argmin(axis=0), np.arange(n)]

    def tolerance(self, clearance: float) -> float:
        """How close to the true minimum a reported minimum clearance is: tolerance_mm plus 2 % of
        the clearance, at most MAX_TOLERANCE_MM below FAR_MM; 5 % beyond (0.2 mm of doubt at 10 mm
        matters no more than 0.05 mm at 1 mm, nor 5 mm at 100 mm; and the search costs less)."""
        if not math.isfinite(clearance):
            return self.tol
        if clearance >= FAR_MM:
            return 0.05 * clearance
        return max(self.tol, min(self.tol + 0.02 * max(clearance, 0.0), MAX_TOLERANCE_MM))


def snap(u: float, nxt: float) -> float:
    """The next check: at `nxt` or before it, on a sample when the step is a sample or more, else on
    a 1/GRID grid, never less than MIN_STEP ahead."""
    if nxt - u >= 1.0:
        s = math.floor(nxt)
        if s > u:
            return float(s)
    s = math.floor(nxt * GRID) / GRID
    if s > u:
        return s
    return max(math.floor(nxt / MIN_STEP) * MIN_STEP, u + MIN_STEP)

