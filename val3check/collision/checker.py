"""Collision checking of the arm, its tool and the parts it carries along a joint trajectory.

    checker = CollisionChecker(arm_model(robot), cell, frames=..., tools=...)
    report = checker.check_motion(MotionSpan(id, source), times, joints)     -> MotionReport
    drops = checker.gripper("tGripper", "close", time)                        -> [PartDrop]

How it works (docs/cell.md, "How the check works"):

* Bodies are grouped by what carries them: one group per arm link with solids, the tool (on the
  flange), each carried part (on the flange), and the static set (obstacles, parts left in the
  cell). A *watch* is a pair of groups that must not touch: a moving group and the static set,
  or two arm groups that the allowed-collision matrix does not exempt (the tool and the parts
  against the links they are not mounted on).
* Motion bound: between two positions of the trajectory, no point of group g moves (relative to
  the other group of the watch) more than  B = Σ_j |Δq_j| · r_j(g)  (plus |Δq_j| for a prismatic
  axis), where r_j(g) bounds the distance from joint j's axis to any point of g in every
  configuration, and Δq_j runs over the joints that move one group and not the
  other. The bound is summed sample by sample, so a joint that turns back counts twice. For the joint
  nearest a group r is the largest distance from its axis, 0 for a solid of revolution about it
  (`ArmModel.weights`).
* Conservative advancement: a watch measured at distance d need not be measured again until the
  bound since then reaches d + touch; the next check is put there (aligned down to a sample, or
  to 1/16 of a sample, never less than 1/256 of a sample ahead). Between checks no contact can
  have happened. Far from everything, checks are rare; close to something they get dense, down
  to sub-sample steps for a fast motion that grazes a thin obstacle between two 4 ms samples.
* The measurements give, per sample, a lower bound of the clearance to the cell (the static
  set; the arm against itself is checked for contact only); the minimum of each motion is then
  refined (checks where the bound could still be below the best value found) to within
  `_tolerance`, and every sample closer than the margin is measured exactly.

Lengths are millimetres, times seconds, joints VAL 3 values (degrees; mm for a prismatic axis).
Frame and tool poses come from the caller in the application's unit (`app_unit_mm` per unit).
"""

from __future__ import annotations

import math
from typing import Any, Callable, Mapping

import fcl
import numpy as np

from .armmodel import ArmModel
from .bodies import Body, aabb_gap, make_bodies, point_inside
from .cell import Cell
from .records import CellProblem, Clearance, Contact, MotionReport, MotionSpan, PartDrop

GRID = 16  # below one sample, checks are aligned down to 1/GRID of a sample
MIN_STEP = 1.0 / 256.0  # the smallest step between two checks, in samples
MAX_TOLERANCE_MM = 0.4  # the reported minimum clearance of a motion is within this of the true one ...
FAR_MM = 50.0  # ... when it is below this; beyond, within 5 %
NEAR_MM = 50.0  # obstacles further than this from a body's box swept over a motion: one bound for all samples
EXACT_CAP = 20000  # measurements per motion spent on exact clearances (minimum, closer than the margin)

PoseSource = Callable[[str, float], Any] | Mapping[str, Any] | None


class _Group:
    """Bodies that move together: `link` is the arm link whose pose carries them (None: static)."""

    __slots__ = ("bodies", "kind", "link", "movers", "name", "placed", "weights")

    def __init__(self, name: str, kind: str, link: str | None, bodies: list[Body], weights: np.ndarray,
                 movers: frozenset[int]) -> None:
        self.name = name
        self.kind = kind
        self.link = link
        self.bodies = bodies
        self.weights = weights  # per joint: mm of motion per unit of |Δq| (per radian, or per mm)
        self.movers = movers
        self.placed = -1.0


class _Watch:
    """A pair of groups that must not touch, and what was measured on it during a motion."""

    __slots__ = ("A", "C", "E", "L", "S", "a", "b", "contact", "first_contact", "free", "landing", "skip", "weights")

    def __init__(self, a: _Group, b: _Group | None, weights: np.ndarray, skip: set[tuple[int, int]]) -> None:
        self.a = a
        self.b = b  # None: the static set
        self.weights = weights
        self.skip = skip  # body pairs (id, id) never measured (a tool solid on its own link)
        self.C = np.zeros(1)  # per sample: the motion bound from the start (mm), along the path
        self.S = np.zeros(1)  # per sample: the same from sample to sample (how far points are apart)
        self.A = np.zeros(1)  # per sample: lower bound of the distance from the bodies' boxes
        self.L = np.zeros(1)  # per sample: best lower bound of the distance so far
        self.E = np.zeros(1, dtype=bool)  # per sample: L is a measured, exact distance
        self.free = np.zeros(0, dtype=bool)  # per step: the boxes alone keep the groups apart
        self.landing: set[tuple[int, int]] = set()  # body pairs touching at the motion's start or end
        self.contact = False
        self.first_contact: Contact | None = None


class CollisionChecker:
    """Checks motions of one arm in one cell; keeps the state between motions (parts carried or
    left in the cell, frames and tools as last read).

    frames(name, time) / frames[name]: pose of an application frame in world; tools(name, time) /
    tools[name]: pose of a tool variable in the flange. A pose is a trsf (x, y, z, rx, ry, rz) in the
    application's unit and degrees, an object with those attributes (geometry.Trsf), or a 4x4 /
    3x4 matrix; None when the program has none (the solids on it are left out and a CellProblem
    says so). margin_mm: clearance below it is a warning (default: the cell's). touch_mm: a
    penetration up to it is touching, not a contact (default: the cell's)."""

    def __init__(self, arm: ArmModel, cell: Cell, *, frames: PoseSource = None, tools: PoseSource = None,
                 margin_mm: float | None = None, touch_mm: float | None = None, app_unit_mm: float = 1.0,
                 tolerance_mm: float = 0.05) -> None:
        self.arm = arm
        self.cell = cell
        self.frames = frames
        self.tools = tools
        self.margin = float(cell.margin_mm if margin_mm is None else margin_mm)
        self.touch = float(cell.touch_mm if touch_mm is None else touch_mm)
        self.unit = float(app_unit_mm)
        self.tol = float(tolerance_mm)
        self.problems: list[CellProblem] = []
        self._reported: set[tuple[str, str]] = set()
        self.measurements = 0
        J = arm.n_joints
        self._J = J
        self._rad = np.array([1.0 if p else math.pi / 180.0 for p in arm.links.prismatic])
        # no signed distance: fcl's loops forever on concentric spheres; an overlap measures 0 or
        # less, and then `collide` gives the depth
        self._req = fcl.DistanceRequest(enable_nearest_points=True)
        self._creq = fcl.CollisionRequest(num_max_contacts=16, enable_contact=True)
        # arm groups
        self.link_groups: dict[str, _Group] = {}
        for link, bodies in arm.bodies.items():
            self.link_groups[link] = _Group(link, "link", link, bodies, arm.weights(link, bodies),
                                            frozenset(arm.links.movers(link)))
        # tool solids, placed when the tool poses are read: (solid, body, its pose in the solid)
        self._tool_bodies: list[tuple[Any, Body, np.ndarray]] = []
        for t in cell.tools:
            label = f"tool {t.tool} {t.name!r}" if t.name else f"tool {t.tool}"
            for b in make_bodies("tool", t.tool, t.name, label, t.shape.kind, t.shape.size, np.eye(4),
                                 *_mesh(t.shape), solid=_solid(t.shape)):
                self._tool_bodies.append((t, b, b.local))
        self.tool_group: _Group | None = None
        self._tool_in_flange: dict[str, np.ndarray | None] | None = None
        # parts: carried ({name: group}) and left in the cell
        self.carried: dict[str, _Group] = {}
        self._dropped: list[Body] = []
        # obstacles
        self._obstacles: list[tuple[Any, Body]] = []
        for o in cell.obstacles:
            for b in make_bodies("obstacle", o.name, o.name, f"obstacle {o.name!r}", o.shape.kind, o.shape.size,
                                 np.eye(4), *_mesh(o.shape), solid=_solid(o.shape)):
                self._obstacles.append((o, b))
        self._static: list[Body] = []
        self._version = 0  # changes with the scene: the watches are rebuilt
        self._watch_cache: tuple[int, list] = (-1, [])
        self._layout_cache: tuple[int, dict] = (-1, {})
        self._frames_read: dict | None = None
        self._placed_obstacles: list[Body] = []
        self._lo = np.zeros((0, 3))
        self._hi = np.zeros((0, 3))
        # body pairs touching at a grasp or a release, not checked until they have moved apart
        self._allowed: dict[frozenset[int], tuple[Body, Body]] = {}
        self._allowed_until: dict[frozenset[int], float] = {}  # in the motion being checked: apart from
        self._last_q: np.ndarray | None = None
        self._time = 0.0
        # state of the motion being checked
        self._Q = np.zeros((1, J))
        self._T = np.zeros(1)
        self._q_at: Callable | None = None
        self._poses_u = -1.0
        self._poses: dict[str, np.ndarray] = {}
        self._P: dict[str, np.ndarray] | None = None
        self._box_lo: np.ndarray | None = None  # (N, B, 3): every arm-side body's box at every sample
        self._box_hi: np.ndarray | None = None
        self._box_col: dict[int, int] = {}
        self._inside0: set[int] = set()
        self._best = None

    # ---- the scene between motions --------------------------------------------------------------------

    def _pose(self, source: PoseSource, name: str, time: float) -> np.ndarray | None:
        if source is None:
            return None
        try:
            p = source(name, time) if callable(source) else source.get(name)  # type: ignore[union-attr]
        except Exception as exc:  # a caller's lookup that fails: the solid is left out, and said so
            self._problem(time, name, f"{name}: cannot be read: {exc}")
            return None
        return None if p is None else as_matrix(p, self.unit)

    def _problem(self, time: float, what: str, message: str, where=None) -> None:
        key = (what, message)
        if key not in self._reported:
            self._reported.add(key)
            self.problems.append(CellProblem(time, what, message, where))

    def refresh(self, time: float) -> None:
        """Read the frames of the obstacles and the tool poses (at a motion's start); the scene is
        rebuilt only when one of them changed."""
        self._time = time
        frames: dict[str, np.ndarray | None] = {"world": np.eye(4)}
        for o, _ in self._obstacles:
            if o.frame not in frames:
                frames[o.frame] = self._pose(self.frames, o.frame, time)
        poses: dict[str, np.ndarray | None] = {}
        for t, _, _ in self._tool_bodies:
            self._tool_pose(t.tool, time, poses, t.where)
        if same_poses(frames, self._frames_read) and same_poses(poses, self._tool_in_flange):
            return
        self._frames_read = frames
        static: list[Body] = []
        for o, b in self._obstacles:
            base = frames[o.frame]
            if base is None:
                self._problem(time, o.frame, f"obstacle {o.name!r} is in frame {o.frame}, which has no "
                              "position in the program: the obstacle is left out", o.where)
                continue
            b.local = base @ o.pose
            b.place(np.eye(4))
            static.append(b)
        self._placed_obstacles = static
        self._set_static([*static, *self._dropped])
        tool_bodies: list[Body] = []
        for t, b, piece in self._tool_bodies:
            T = poses[t.tool]
            if T is not None:
                b.local = T @ t.pose @ piece
                tool_bodies.append(b)
        self._tool_in_flange = poses
        self.tool_group = self._flange_group("tool", "tool", tool_bodies) if tool_bodies else None
        self._version += 1

    def _tool_pose(self, tool: str, time: float, cache: dict, where=None) -> np.ndarray | None:
        if tool not in cache:
            if tool == "flange":
                cache[tool] = np.eye(4)
            else:
                T = self._pose(self.tools, tool, time)
                if T is None:
                    self._problem(time, tool, f"tool {tool} has no value in the program: its solids and parts "
                                  "are left out", where)
                cache[tool] = T
        return cache[tool]

    def _set_static(self, bodies: list[Body]) -> None:
        self._static = bodies
        self._version += 1
        if bodies:
            boxes = [b.aabb() for b in bodies]
            self._lo = np.array([lo for lo, _ in boxes])
            self._hi = np.array([hi for _, hi in boxes])
        else:
            self._lo = np.zeros((0, 3))
            self._hi = np.zeros((0, 3))

    def _flange_weights(self, bodies: list[Body]) -> np.ndarray:
        return self.arm.weights(self.arm.flange_link, bodies)

    def _flange_group(self, name: str, kind: str, bodies: list[Body]) -> _Group:
        fl = self.arm.flange_link
        return _Group(name, kind, fl, bodies, self._flange_weights(bodies), frozenset(self.arm.links.movers(fl)))

    def _watches(self) -> list[_Watch]:
        if self._watch_cache[0] == self._version:
            return self._watch_cache[1]
        out = self._make_watches()
        self._watch_cache = (self._version, out)
        return out

    def _make_watches(self) -> list[_Watch]:
        arm = self.arm
        moving: list[_Group] = list(self.link_groups.values())
        if self.tool_group is not None:
            moving.append(self.tool_group)
        moving.extend(self.carried.values())
        out = [_Watch(g, None, g.weights, set()) for g in moving]
        links = sorted(self.link_groups)
        for i, a in enumerate(links):
            for b in links[i + 1:]:
                if not arm.acm.allowed(a, b):
                    ga, gb = self.link_groups[a], self.link_groups[b]
                    out.append(_Watch(ga, gb, _relative(ga, gb), set()))
        flange_side = [g for g in (self.tool_group, *self.carried.values()) if g is not None]
        tool_touch = {id(b): (t.touch_links if t.touch_links is not None else arm.touch_links)
                      for t, b, _ in self._tool_bodies}
        for g in flange_side:
            for link in links:
                lg = self.link_groups[link]
                skip = set()
                for b in g.bodies:
                    touch = tool_touch.get(id(b), arm.touch_links)
                    if link in touch:
                        skip.update((id(b), id(x)) for x in lg.bodies)
                if len(skip) == len(g.bodies) * len(lg.bodies):
                    continue
                out.append(_Watch(g, lg, _relative(g, lg), skip))
        return out

    # ---- configurations ---------------------------------------------------------------------------------

    def _q(self, u: float) -> np.ndarray:
        k = int(u)
        n = len(self._Q) - 1
        if k >= n:
            return self._Q[n]
        f = u - k
        if f == 0.0:
            return self._Q[k]
        if self._q_at is not None:
            return np.asarray(self._q_at(self._t(u)), dtype=float)
        return self._Q[k] + f * (self._Q[k + 1] - self._Q[k])

    def _t(self, u: float) -> float:
        k = int(u)
        n = len(self._T) - 1
        if k >= n:
            return float(self._T[n])
        return float(self._T[k] + (u - k) * (self._T[k + 1] - self._T[k]))

    def _frame(self, link: str, u: float) -> np.ndarray:
        """A link's pose at position u (samples: computed for the whole motion at once)."""
        k = int(u)
        if k == u and self._P is not None:
            return self._P[link][k]
        if self._poses_u != u:
            self._poses = self.arm.links.poses(self._q(u))
            self._poses_u = u
        return self._poses[link]

    def _place(self, g: _Group, u: float) -> None:
        if g.placed == u:
            return
        frame = self._frame(g.link, u)
        for b in g.bodies:
            b.place(frame)
        g.placed = u

    # ---- measuring -------------------------------------------------------------------------------------

    def _pairs(self, w: _Watch, u: float | None = None) -> list[tuple[float, Body, Body]]:
        """Body pairs of a watch with the gap between their boxes, nearest first: at sample u, the
        boxes _prepare computed for the whole motion; else from the bodies where they are."""
        A = w.a.bodies
        k = -1 if u is None else int(u)
        at_sample = k == u and self._box_lo is not None
        if w.b is None:
            if not self._static:
                return []
            if at_sample:
                cols = [self._box_col[id(b)] for b in A]
                lo, hi = self._box_lo[k, cols], self._box_hi[k, cols]
            else:
                lo, hi = _boxes(A)
            gaps = aabb_gap(lo[:, None, :], hi[:, None, :], self._lo[None], self._hi[None]).ravel()
            S, st = len(self._static), self._static
            return [(float(gaps[i]), A[i // S], st[i % S]) for i in np.argsort(gaps, kind="stable")]
        Bs = w.b.bodies
        if at_sample:
            cols = [self._box_col[id(b)] for b in A + Bs]
            lo, hi = self._box_lo[k, cols], self._box_hi[k, cols]
        else:
            lo, hi = _boxes(A + Bs)
        na = len(A)
        gaps = aabb_gap(lo[:na, None, :], hi[:na, None, :], lo[None, na:], hi[None, na:])
        out = [(float(gaps[i, j]), A[i], Bs[j]) for i in range(na) for j in range(len(Bs))
               if (id(A[i]), id(Bs[j])) not in w.skip]
        out.sort(key=lambda x: x[0])
        return out

    def _distance(self, a: Body, b: Body, exact: bool = True) -> tuple[float, tuple, tuple, bool]:
        """(distance, nearest point on a, on b, exact): the hull of a mesh piece gives a lower bound
        (exact False) unless `exact`, or unless it touches (then the triangles decide)."""
        res = fcl.DistanceResult()
        lb = a.lb or b.lb
        d = fcl.distance(a.obj, b.obj, self._req, res)
        self.measurements += 1
        if lb and (exact or d <= 0.0):
            res = fcl.DistanceResult()
            d = fcl.distance(a.exact_obj() if a.lb else a.obj, b.exact_obj() if b.lb else b.obj, self._req, res)
            self.measurements += 1
            lb = False
        pa, pb = res.nearest_points
        return float(d), _tup(pa), _tup(pb), not lb

    def _measure(self, w: _Watch, u: float, need: float, exact_mesh: bool | None = None):
        """Watch w at position u -> (cert, clear, exact, info, hit):
        cert   the smallest distance between its bodies (minus the penetration depth where they
               overlap), or a lower bound of it when every remaining pair is `need` or more apart;
        clear  the same over the pairs that count for clearance (not those landing or lifting off
               in this motion, `w.landing`); exact: whether it is exact; info: (body a, body b,
               point a, point b) of it when exact;
        hit    (body a, body b, point, depth, kind) of the deepest overlap, or None;
        exact_mesh: measure meshes to their triangles, not their pieces' hulls (default: when
        `need` is infinite);
        valid  (for cert, for clear): the values hold before these positions only (a pair allowed
               to touch since a grasp or release is left out until then), inf otherwise."""
        self._place(w.a, u)
        if w.b is not None:
            self._place(w.b, u)
        pairs = self._pairs(w, u)
        # left-out pairs come back at this sample: the values hold before it only (`clear` ignores
        # the landing ones anyway)
        valid = valid_clear = math.inf
        landing = w.landing
        if self._allowed_until:
            until = self._allowed_until
            kept = []
            for p in pairs:
                at = until.get(frozenset((id(p[1]), id(p[2]))), -1.0)
                if at <= u:
                    kept.append(p)
                else:
                    valid = min(valid, at)
                    if (id(p[1]), id(p[2])) not in landing:
                        valid_clear = min(valid_clear, at)
            pairs = kept
        cert = clear = math.inf
        exact, info = True, None
        touching: list[tuple[Body, Body, bool]] = []
        for gap, ba, bb in pairs:
            if gap > max(clear, 0.0):
                break
            if gap >= need:
                cert = min(cert, gap)
                if gap < clear:
                    clear, exact, info = gap, False, None
                break
            d, pa, pb, ok = self._distance(ba, bb, need == math.inf if exact_mesh is None else exact_mesh)
            lands = bool(landing) and (id(ba), id(bb)) in landing
            if d <= 0.0:  # overlapping or touching: the depth decides, below
                touching.append((ba, bb, lands))
                continue
            cert = min(cert, d)
            if not lands and d < clear:
                clear, exact, info = d, ok, ((ba, bb, pa, pb) if ok else None)
        hit = None
        for ba, bb, lands in touching:
            c = self._collide(ba, bb)
            depth, point = (c[0], c[1]) if c is not None else (0.0, None)
            cert = min(cert, -depth)
            if not lands and -depth <= clear:
                p = point if point is not None else _tup(0.5 * (ba.pose[:3, 3] + bb.pose[:3, 3]))
                clear, exact, info = -depth, True, (ba, bb, p, p)
            if c is not None and (hit is None or depth > hit[3]):
                hit = (ba, bb, point, depth, "contact" if w.b is None else "self")
        return cert, clear, exact, info, hit, (valid, valid_clear)

    def _collide(self, a: Body, b: Body) -> tuple[float, tuple] | None:
        res = fcl.CollisionResult()
        fcl.collide(a.exact_obj(), b.exact_obj(), self._creq, res)
        self.measurements += 1
        if not res.contacts:
            return None
        c = max(res.contacts, key=lambda c: c.penetration_depth)
        return float(c.penetration_depth), _tup(c.pos)

    def _contained(self, w: _Watch, u: float) -> tuple[Body, Body, float] | None:
        """A body of the watch wholly inside a closed mesh of the other side (fcl measures only
        to the surface, so this is tested apart, at a motion's start): (inner, a piece of the
        mesh, how deep inside: the distance to the mesh's triangles)."""
        self._place(w.a, u)
        if w.b is not None:
            self._place(w.b, u)
        sides = (w.a.bodies, self._static if w.b is None else w.b.bodies)
        for inners, outers in (sides, sides[::-1]):
            wholes: dict[int, list[Body]] = {}
            for o in outers:
                if o.mesh is not None and o.solid:
                    wholes.setdefault(o.whole, []).append(o)
            for pieces in wholes.values():
                outer = pieces[0]
                olo, ohi = outer.whole_aabb()
                for inner in inners:
                    if inner.whole == outer.whole or any(
                            (id(inner), id(p)) in w.skip or (id(p), id(inner)) in w.skip
                            or frozenset((id(inner), id(p))) in self._allowed for p in pieces):
                        continue
                    lo, hi = inner.aabb()
                    if np.any(lo < olo) or np.any(hi > ohi):
                        continue
                    inv = np.linalg.inv(outer.pose)
                    c = inv[:3, :3] @ (0.5 * (lo + hi)) + inv[:3, 3]
                    if point_inside(outer.mesh[0], outer.mesh[1], c):
                        depth = math.inf
                        for p in pieces:
                            d = fcl.distance(inner.exact_obj(), p.exact_obj(), self._req, fcl.DistanceResult())
                            self.measurements += 1
                            depth = min(depth, float(d))
                        return inner, outer, max(depth, 0.0)
        return None

    # ---- one motion ------------------------------------------------------------------------------------

    def check_motion(self, motion: MotionSpan, times, joints, q_at: Callable[[float], Any] | None = None) -> MotionReport:
        """Check one motion given by its samples: times (N,) in s, joints (N, axes) in VAL 3 units.
        Between samples the arm is on the straight joint-space segment, or at q_at(t) when given
        (then each step's bound also covers how far q_at bends away from the segment; `q_at.many(ts)`,
        when q_at has it, gives the positions at many times at once)."""
        T = np.asarray(times, dtype=float).reshape(-1)
        if len(T) == 0:
            raise ValueError("a motion needs at least one sample")
        Q = np.asarray(joints, dtype=float).reshape(len(T), -1)
        if Q.shape[1] != self._J:
            raise ValueError(f"joints have {Q.shape[1]} values per sample, the arm has {self._J} axes")
        if not (np.isfinite(T).all() and np.isfinite(Q).all()):
            raise ValueError("times and joints must be finite numbers")
        before = self.measurements
        self._T, self._Q, self._q_at = T, Q, q_at
        self._poses_u = -1.0
        self._P = None
        self._box_lo = self._box_hi = None
        self.refresh(float(T[0]))
        watches = self._watches()
        self._P = self.arm.links.poses_many(Q)
        for g in self._arm_groups():
            g.placed = -1.0
        steps = self._step_motion(Q, q_at, T)
        n = len(T)
        self._prepare(watches, steps)
        self._inside0 = self._inside_static_meshes()
        self._allowed_until = self._apart_from()
        for w in watches:
            w.contact = False
            w.first_contact = None
            w.landing = set()
            w.landing = self._landing(w) | self._still_allowed(w)
        report = MotionReport(motion, T, np.zeros(n), np.zeros(n, dtype=bool), margin_mm=self.margin,
                              tolerance_mm=self.tol)
        self._best = None
        for w in watches:
            self._advance(w, report)
        report.contacts.sort(key=lambda c: c.time)
        # clearance of what the motion moves: a link no joint moves (the base) is checked for contact only
        self._samples([w for w in watches if w.b is None and w.a.movers], report)
        if self._best is not None:
            d, u, (a, b, pa, pb) = self._best
            report.min_clearance = Clearance(float(d), self._t(u), a.label, b.label, pa, pb)
            report.too_close = (report.first_contact is None and report.starts_in_collision is None
                                and self.margin > 0.0 and d < self.margin)
        report.checks = self.measurements - before
        for key, at in self._allowed_until.items():
            if at <= n - 1:
                del self._allowed[key]  # apart now: checked like any pair from the next motion on
        self._allowed_until = {}
        self._last_q = Q[-1].copy()
        self._time = float(T[-1])
        self._P = None
        self._box_lo = self._box_hi = None
        return report

    def _step_motion(self, Q: np.ndarray, q_at, T: np.ndarray) -> np.ndarray:
        """Per step and joint, how much the joint may travel (rad, or mm): |Δq|, plus, with q_at, four
        times how far the path strays from the straight segment at mid-step (a parabola's detour
        past its ends is at most twice that)."""
        if len(Q) < 2:
            return np.zeros((0, self._J))
        dq = np.abs(np.diff(Q, axis=0))
        if q_at is not None:
            many = getattr(q_at, "many", None)  # positions at many times in one call, when the caller has it
            tm = 0.5 * (T[:-1] + T[1:])
            mids = (np.asarray(many(tm), dtype=float) if many is not None
                    else np.array([np.asarray(q_at(t), dtype=float) for t in tm]))
            dq = dq + 4.0 * np.abs(mids - 0.5 * (Q[:-1] + Q[1:]))
        return dq * self._rad

    def _layout(self, watches: list[_Watch]) -> dict:
        """What _prepare needs that depends only on the scene (cached with the watches)."""
        if self._layout_cache[0] == self._version:
            return self._layout_cache[1]
        groups = self._arm_groups()
        bodies = [b for g in groups for b in g.bodies]
        index = {id(b): i for i, b in enumerate(bodies)}
        spheres = []
        for g in groups:
            pts = np.concatenate([b.points @ b.local[:3, :3].T + b.local[:3, 3] for b in g.bodies])
            rad = max(b.radius for b in g.bodies)
            c = 0.5 * (pts.min(axis=0) + pts.max(axis=0))
            spheres.append((c, float(np.sqrt(((pts - c) ** 2).sum(axis=1)).max()) + rad))
        gindex = {id(g): i for i, g in enumerate(groups)}
        ia, ib, starts, self_w = [], [], [], []
        static_w, static_cols = [], []
        for wi, w in enumerate(watches):
            if w.b is None:
                static_w.append(wi)
                static_cols.append(np.array([index[id(b)] for b in w.a.bodies], dtype=int))
                continue
            first = len(ia)
            for ba in w.a.bodies:
                for bb in w.b.bodies:
                    if (id(ba), id(bb)) not in w.skip:
                        ia.append(index[id(ba)])
                        ib.append(index[id(bb)])
            if len(ia) > first:
                starts.append(first)
                self_w.append(wi)
        lay = {
            "groups": groups,
            "bodies": bodies,
            "body_group": np.array([gindex[id(g)] for g in groups for _ in g.bodies], dtype=int),
            "c_local": np.array([b.local[:3, :3] @ b.center + b.local[:3, 3] for b in bodies]),
            "h_local": np.array([np.abs(b.local[:3, :3]) @ b.half for b in bodies]),
            "sph_c": np.array([c for c, _ in spheres]).reshape(-1, 3),
            "sph_r": np.array([r for _, r in spheres]),
            "ga": np.array([gindex[id(w.a)] for w in watches], dtype=int),
            "gb": np.array([gindex[id(w.b)] if w.b is not None else -1 for w in watches], dtype=int),
            "W": np.array([w.weights for w in watches]).T,
            "ia": np.array(ia, dtype=int),
            "ib": np.array(ib, dtype=int),
            "starts": np.array(starts, dtype=int),
            "self_w": np.array(self_w, dtype=int),
            "static_w": static_w,
            "static_cols": static_cols,
        }
        self._layout_cache = (self._version, lay)
        return lay

    def _prepare(self, watches: list[_Watch], steps: np.ndarray) -> None:
        """Per watch and sample: C, the path bound from the start; S, the same from sample to
        sample (per step the smaller of C's step and how far the two groups' points move in world
        between the two samples: S bounds distances at samples, C between them too); A, a lower
        bound of the distance from the boxes around the bodies (the broad phase); L = A; E = False;
        and per step, whether the boxes alone keep the watch apart along it (`free`)."""
        n = len(self._T)
        nw = len(watches)
        if not nw:
            return
        lay = self._layout(watches)
        groups = lay["groups"]
        F = np.stack([self._P[g.link] for g in groups])  # (G, N, 4, 4)
        if n > 1:
            dC = steps @ lay["W"]  # (N-1, watches)
            # how far each group's points move from a sample to the next: |ΔT·c| + ρ·2·sin(θ/2)
            R = F[:, :, :3, :3]
            p = (R @ lay["sph_c"][:, None, :, None])[..., 0] + F[:, :, :3, 3]
            move = np.sqrt(((p[:, 1:] - p[:, :-1]) ** 2).sum(axis=2))
            cos = 0.5 * ((R[:, 1:] * R[:, :-1]).sum(axis=(2, 3)) - 1.0)
            moves = move + lay["sph_r"][:, None] * np.sqrt(np.maximum(2.0 - 2.0 * np.clip(cos, -1.0, 1.0), 0.0))
            moves = np.vstack([moves, np.zeros((1, n - 1))])  # row -1: the static set does not move
            dS = (moves[lay["ga"]] + moves[lay["gb"]]).T
            dS = np.minimum(dS, dC)
            Cm = np.vstack([np.zeros(nw), np.cumsum(dC, axis=0)]).T
            Sm = np.vstack([np.zeros(nw), np.cumsum(dS, axis=0)]).T
        else:
            dC = np.zeros((0, nw))
            Cm = Sm = np.zeros((nw, 1))
        # each body's box: its centre carried by its group's frame; its half sizes through |R|
        # (|R_group·R_local| <= |R_group|·|R_local|: exact for solids square to their link)
        Fb = F[lay["body_group"]]  # (B, N, 4, 4)
        Rg = Fb[..., :3, :3]
        c = (Rg @ lay["c_local"][:, None, :, None])[..., 0] + Fb[..., :3, 3]
        h = (np.abs(Rg) @ lay["h_local"][:, None, :, None])[..., 0]
        lo, hi = (c - h).transpose(1, 0, 2), (c + h).transpose(1, 0, 2)  # (N, B, 3)
        self._box_lo, self._box_hi = lo, hi
        self._box_col = {id(b): i for i, b in enumerate(lay["bodies"])}
        A = np.full((nw, n), np.inf)
        if self._static and lay["static_w"]:
            # boxes swept over the whole motion first: a far obstacle bounds every sample alike
            far = aabb_gap(lo.min(axis=0)[:, None], hi.max(axis=0)[:, None], self._lo[None], self._hi[None])  # (B, S)
            near = far < NEAR_MM
            to_static = np.broadcast_to(np.where(near, np.inf, far).min(axis=1), (n, len(far))).copy()
            bi, si = np.nonzero(near)
            if len(bi):
                g = aabb_gap(lo[:, bi], hi[:, bi], self._lo[si][None], self._hi[si][None])  # (N, pairs)
                for j in range(len(bi)):
                    np.minimum(to_static[:, bi[j]], g[:, j], out=to_static[:, bi[j]])
            for wi, cols in zip(lay["static_w"], lay["static_cols"]):
                A[wi] = to_static[:, cols].min(axis=1)
        if len(lay["ia"]):
            ia, ib = lay["ia"], lay["ib"]
            pair = aabb_gap(lo[:, ia], hi[:, ia], lo[:, ib], hi[:, ib])  # (N, pairs)
            A[lay["self_w"]] = np.minimum.reduceat(pair, lay["starts"], axis=1).T
        free = (A[:, :-1] + A[:, 1:] - dC.T) > 2.0 * self.touch
        L = A.copy()
        E = np.zeros((nw, n), dtype=bool)
        for wi, w in enumerate(watches):
            w.C, w.S, w.A, w.L, w.E, w.free = Cm[wi], Sm[wi], A[wi], L[wi], E[wi], free[wi]

    def _tolerance(self, clearance: float) -> float:
        """How close to the true minimum a reported minimum clearance is: tolerance_mm plus 2 % of
        the clearance, at most MAX_TOLERANCE_MM below FAR_MM; 5 % beyond (0.2 mm of doubt at 10 mm
        matters no more than 0.05 mm at 1 mm, nor 5 mm at 100 mm; and the search costs less)."""
        if not math.isfinite(clearance):
            return self.tol
        if clearance >= FAR_MM:
            return 0.05 * clearance
        return max(self.tol, min(self.tol + 0.02 * max(clearance, 0.0), MAX_TOLERANCE_MM))

    def _u_of(self, w: _Watch, target: float) -> float:
        """The first position u where the watch's cumulative bound reaches `target`."""
        C = w.C
        n = len(C) - 1
        if target >= C[n]:
            return float(n)
        k = int(np.searchsorted(C, target, side="right")) - 1
        k = max(0, min(k, n - 1))
        span = C[k + 1] - C[k]
        f = 0.0 if span <= 0.0 else (target - C[k]) / span
        return k + min(max(f, 0.0), 1.0)

    def _C(self, w: _Watch, u: float) -> float:
        C = w.C
        n = len(C) - 1
        k = int(u)
        if k >= n:
            return float(C[n])
        return float(C[k] + (u - k) * (C[k + 1] - C[k]))

    def _record(self, w: _Watch, u: float, d: float, exact: bool, info, valid: float = math.inf) -> None:
        """A measurement bounds the watch's distance at every sample (before `valid`): d minus the
        motion since."""
        k = int(u)
        if k == u:
            bound = d - np.abs(w.S - w.S[k])
        else:  # between samples: the path bound to the samples around it, then from sample to sample
            n = len(w.S) - 1
            before = d - (self._C(w, u) - w.C[k]) - np.abs(w.S - w.S[k])
            after = d - (w.C[min(k + 1, n)] - self._C(w, u)) - np.abs(w.S - w.S[min(k + 1, n)])
            bound = np.maximum(before, after)
        if valid < len(w.L):
            bound[int(math.ceil(valid)):] = -math.inf
        np.maximum(w.L, bound, out=w.L)
        if k == u:
            w.L[k] = max(w.L[k], d) if not exact else d
            w.E[k] = w.E[k] or exact
        if w.b is None and w.a.movers and exact and info is not None and (self._best is None or d < self._best[0]):
            self._best = (d, u, info[:4])  # the clearance is to the cell: the static set

    def _apart_from(self) -> dict[frozenset[int], float]:
        """For each pair allowed to touch since a grasp or a release: the first sample where its two
        bodies are apart (further than the touch tolerance); from there on it is checked. n + 1
        when they stay together for the whole motion."""
        out: dict[frozenset[int], float] = {}
        if not self._allowed:
            return out
        owner = {id(b): g for g in self._arm_groups() for b in g.bodies}
        n = len(self._T) - 1
        for key, (a, b) in self._allowed.items():
            ga, gb = owner.get(id(a)), owner.get(id(b))
            at = float(n + 1)
            for k in range(n + 1):
                boxes = []
                for body, g in ((a, ga), (b, gb)):
                    if g is None:
                        boxes.append(body.aabb())
                    else:
                        col = self._box_col[id(body)]
                        boxes.append((self._box_lo[k, col], self._box_hi[k, col]))
                if float(aabb_gap(*boxes[0], *boxes[1])) > self.touch:
                    at = float(k)  # the boxes are apart: so are the bodies
                    break
                for body, g in ((a, ga), (b, gb)):
                    if g is not None:
                        body.place(self._P[g.link][k])
                if self._distance(a, b, False)[0] > self.touch:
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
        for b in self._static:
            if b.mesh is not None and b.solid and b.whole not in seen:
                seen.add(b.whole)
                boxes.append(b.whole_aabb())
        if not boxes or self._box_lo is None:
            return set()
        lo, hi = self._box_lo[0], self._box_hi[0]  # (B, 3)
        inside = np.zeros(len(lo), dtype=bool)
        for olo, ohi in boxes:
            inside |= np.all(lo >= olo, axis=1) & np.all(hi <= ohi, axis=1)
        cols = {i: key for key, i in self._box_col.items()}
        return {cols[i] for i in np.nonzero(inside)[0]}

    def _solid_mesh(self, w: _Watch) -> bool:
        """Whether a body of one side may lie wholly inside a closed mesh of the other at the first
        sample: its box inside the mesh's box."""
        if w.b is None and not any(b.mesh is not None and b.solid for b in w.a.bodies):
            return any(id(b) in self._inside0 for b in w.a.bodies)
        others = self._static if w.b is None else w.b.bodies
        for inners, outers in ((w.a.bodies, others), (others, w.a.bodies)):
            meshes = [b for b in outers if b.mesh is not None and b.solid]
            if not meshes:
                continue
            self._place(w.a, 0.0)
            if w.b is not None:
                self._place(w.b, 0.0)
            boxes = [m.whole_aabb() for m in meshes]
            for inner in inners:
                lo, hi = inner.aabb()
                if any(np.all(lo >= olo) and np.all(hi <= ohi) for olo, ohi in boxes):
                    return True
        return False

    def _still_allowed(self, w: _Watch) -> set[tuple[int, int]]:
        """Body pairs of the watch allowed to touch since a grasp or a release (a part let go while
        the arm still moved: resetMotion() in stop()): like landing pairs, out of the clearance of
        the motion in which they move apart, checked for contact once apart."""
        if not self._allowed:
            return set()
        a = {id(b) for b in w.a.bodies}
        other = {id(b) for b in (self._static if w.b is None else w.b.bodies)}
        out = set()
        for key in self._allowed:
            x, y = tuple(key)
            if x in a and y in other:
                out.add((x, y))
            elif y in a and x in other:
                out.add((y, x))
        return out

    def _landing(self, w: _Watch) -> set[tuple[int, int]]:
        """Body pairs touching (within the touch tolerance, not deeper) at the motion's first or last
        sample: a part set down on a pallet, a tool lifted off a part it let go. They are checked for
        contact all along, but left out of the clearance: touching there is the motion's purpose."""
        out: set[tuple[int, int]] = set()
        n = len(self._T) - 1
        for u in ((0.0, float(n)) if n else (0.0,)):
            if w.A[int(u)] > self.touch:
                continue
            self._place(w.a, u)
            if w.b is not None:
                self._place(w.b, u)
            for gap, ba, bb in self._pairs(w, u):
                if gap > self.touch:
                    break
                d = self._distance(ba, bb)[0]
                if d <= self.touch:
                    c = self._collide(ba, bb) if d <= 0.0 else None
                    if c is None or c[0] <= self.touch:
                        out.add((id(ba), id(bb)))
        return out

    def _advance(self, w: _Watch, report: MotionReport) -> None:
        """Conservative advancement of one watch along the motion: no contact can happen between
        two of its checks, nor in a step that the boxes alone keep apart."""
        n = len(self._T) - 1
        A, C = w.A, w.C
        # a step is free when the boxes at its two ends are further apart than it can close
        todo = np.nonzero(~w.free)[0]
        if n == 0 or A[0] <= 0.0 or (len(todo) and todo[0] == 0):
            u = 0.0
        elif self._solid_mesh(w):
            u = 0.0  # a solid wholly inside a closed mesh is far from its pieces' boxes: look
        elif len(todo) == 0:
            return
        else:
            u = float(todo[0])
        while True:
            need = C[-1] - self._C(w, u)
            cert, clear, exact, info, hit, (valid, valid_clear) = self._measure(w, u, need if u > 0.0 else math.inf)
            if u == 0.0 and hit is None:
                inside = self._contained(w, u)
                if inside is not None:
                    a, b, depth = inside
                    c = _tup(a.pose[:3, 3])
                    hit = (a, b, c, depth, "inside")
                    cert = clear = -depth
                    info = (a, b, c, c)
            self._record(w, u, clear, exact, info, valid_clear)
            if hit is not None and hit[3] > self.touch:
                if not w.contact:
                    c = Contact(self._t(u), hit[0].label, hit[1].label, hit[2], hit[3], hit[4])
                    if u == 0.0:
                        if report.starts_in_collision is None:
                            report.starts_in_collision = c
                    else:
                        if w.first_contact is None:
                            w.first_contact = c
                            report.contacts.append(c)
                        if report.first_contact is None or c.time < report.first_contact.time:
                            report.first_contact = c
                    w.contact = True
                if u >= n:
                    return
                u = float(math.floor(u) + 1)
                continue
            w.contact = False
            allowed = max(cert, 0.0) + self.touch - (hit[3] if hit is not None else 0.0)
            if valid <= n and self._C(w, valid) - self._C(w, u) > allowed:
                valid = math.inf  # the certified step ends before the left-out pair comes back
            if u >= n or (valid > n and self._C(w, n) - self._C(w, u) <= allowed):
                return  # certified to the end of the motion
            uc = min(self._u_of(w, self._C(w, u) + allowed), valid)
            k = np.searchsorted(todo, math.floor(uc))  # the next step the boxes do not keep apart
            if k >= len(todo):
                return
            u = _snap(u, max(uc, float(todo[k])))

    def _samples(self, watches: list[_Watch], report: MotionReport) -> None:
        """Per-sample clearance: the lowest bound over the watches, then measured exactly at the
        samples closer than the margin and where the motion's minimum may be, until that minimum is
        known within the tolerance."""
        n = len(self._T)
        if not watches:
            report.clearance = np.full(n, np.inf)
            report.exact = np.ones(n, dtype=bool)
            return
        spent = 0
        L = np.array([w.L for w in watches])
        E = np.array([w.E for w in watches])
        for wi, w in enumerate(watches):  # the watches write their bounds into these rows from now on
            w.L, w.E = L[wi], E[wi]
        while spent < EXACT_CAP:
            low = L.min(axis=0)
            arg = L.argmin(axis=0)
            ex = E[arg, np.arange(n)]
            best = self._best[0] if self._best is not None else math.inf
            target = best - self._tolerance(best)
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
                for wi in sorted(np.nonzero((L[:, k] < limit) & ~E[:, k])[0], key=lambda i: L[i, k]):
                    if L[wi, k] >= found:
                        break  # this watch cannot be the closest at this sample
                    w = watches[wi]
                    # exact below the limit; above it a bound is all that is needed
                    _, d, exact, info, _, (_, valid) = self._measure(w, float(k), limit, exact_mesh=True)
                    self._record(w, float(k), d, exact, info, valid)
                    found = min(found, d)
                    spent += 1
        report.clearance = L.min(axis=0)
        report.exact = E[L.argmin(axis=0), np.arange(n)]

    # ---- gripper ---------------------------------------------------------------------------------------

    def gripper(self, tool: str, instruction: str, time: float, joints=None, source: Any = None) -> list[PartDrop]:
        """The program ran open(tool) or close(tool) (instruction "open"/"close") at `time`, the arm
        at `joints` (default: where the last motion ended). The cell's parts grasped by that tool
        on that instruction are attached; the parts it carries and releases on it are left in the
        cell where they are. Returns the parts left inside an obstacle or another part.

        Bodies touching at that moment (the part and the table it lies on, the jaws and the part
        they let go) may touch until they have moved apart."""
        if instruction not in ("open", "close"):
            raise ValueError("instruction is 'open' or 'close'")
        q = np.asarray(joints, dtype=float) if joints is not None else self._last_q
        if q is None:
            q = np.zeros(self._J)
        self.refresh(time)
        poses = self.arm.links.poses(q)
        flange = poses[self.arm.flange_link]
        arm_bodies: list[Body] = []
        for g in self._arm_groups():
            for b in g.bodies:
                b.place(poses[g.link])
            g.placed = -1.0
            arm_bodies.extend(b for b in g.bodies)
        names: list[str] = []
        for p in self.cell.parts:
            if p.tool == tool and p.name not in names:
                names.append(p.name)
        drops: list[PartDrop] = []
        cache: dict = dict(self._tool_in_flange or {})
        for name in names:
            solids = [p for p in self.cell.parts if p.name == name]
            first = solids[0]
            if instruction == first.grasp and name not in self.carried:
                T = self._tool_pose(tool, time, cache, first.where)
                if T is None:
                    continue
                bodies = []
                for p in solids:
                    for b in make_bodies("part", name, name, f"part {name!r}", p.shape.kind, p.shape.size, np.eye(4),
                                         *_mesh(p.shape), solid=_solid(p.shape)):
                        b.local = T @ p.pose @ b.local
                        bodies.append(b)
                for b in bodies:
                    b.place(flange)
                self._pick_up(name, bodies)
                self._allow_touching(bodies, self._static)
                self.carried[name] = self._flange_group(f"part {name!r}", "part", bodies)
                self._version += 1
            elif instruction == first.release and name in self.carried:
                g = self.carried.pop(name)
                self._version += 1
                for b in g.bodies:
                    b.place(flange)
                    b.local = b.pose.copy()
                    b.kind = "obstacle"
                drops.extend(self._dropped_inside(g.bodies, time, source))
                self._allow_touching(g.bodies, [b for b in arm_bodies if b.owner != name])
                self._dropped.extend(g.bodies)
                self._set_static([*self._placed_obstacles, *self._dropped])
        return drops

    def clear_parts(self, name: str) -> int:
        """The parts named `name` left in the cell are taken away (the cell's `cleared_by`): how many
        solids left the cell."""
        gone = {id(d) for d in self._dropped if d.owner == name}
        if gone:
            self._allowed = {k: v for k, v in self._allowed.items() if not (k & gone)}
            self._dropped = [d for d in self._dropped if id(d) not in gone]
            self._set_static([*self._placed_obstacles, *self._dropped])
        return len(gone)

    def _arm_groups(self) -> list[_Group]:
        out = list(self.link_groups.values())
        if self.tool_group is not None:
            out.append(self.tool_group)
        out.extend(self.carried.values())
        return out

    def _pick_up(self, name: str, bodies: list[Body]) -> None:
        """A part taken where a part of the same name was left is that part: it leaves the cell."""
        keep = [d for d in self._dropped if not (d.owner == name and any(self._overlap(d, b) for b in bodies))]
        if len(keep) != len(self._dropped):
            gone = {id(d) for d in self._dropped} - {id(d) for d in keep}
            self._allowed = {k: v for k, v in self._allowed.items() if not (k & gone)}
            self._dropped = keep
            self._set_static([*self._placed_obstacles, *self._dropped])

    def _overlap(self, a: Body, b: Body) -> bool:
        la, ha = a.aabb()
        lb, hb = b.aabb()
        if float(aabb_gap(la, ha, lb, hb)) > self.touch:
            return False
        return self._distance(a, b)[0] <= self.touch

    def _allow_touching(self, bodies: list[Body], others: list[Body]) -> None:
        for a in bodies:
            for b in others:
                if b is a:
                    continue
                la, ha = a.aabb()
                lb, hb = b.aabb()
                if float(aabb_gap(la, ha, lb, hb)) > self.touch:
                    continue
                d = self._distance(a, b)[0]
                if d <= self.touch:
                    self._allowed[frozenset((id(a), id(b)))] = (a, b)

    def _dropped_inside(self, bodies: list[Body], time: float, source: Any) -> list[PartDrop]:
        """The part's solids left overlapping an obstacle (deeper than the touch tolerance), or wholly
        inside a closed mesh."""
        out = []
        seen: set[tuple[int, int]] = set()
        for a in bodies:
            la, ha = a.aabb()
            for b in self._static:
                if b in bodies or (a.whole, b.whole) in seen:
                    continue
                lb, hb = b.whole_aabb()
                if float(aabb_gap(la, ha, lb, hb)) > 0.0:
                    continue
                c = self._collide(a, b)
                if c is not None and c[0] > self.touch:
                    seen.add((a.whole, b.whole))
                    out.append(PartDrop(time, a.label, b.label, c[1], c[0], source))
                    continue
                for inner, outer in ((a, b), (b, a)):
                    if outer.mesh is not None and outer.solid:
                        inv = np.linalg.inv(outer.pose)
                        p = inv[:3, :3] @ inner.pose[:3, 3] + inv[:3, 3]
                        if point_inside(outer.mesh[0], outer.mesh[1], p):
                            seen.add((a.whole, b.whole))
                            out.append(PartDrop(time, a.label, b.label, _tup(inner.pose[:3, 3]), None, source))
                            break
        return out


# ---- helpers ----------------------------------------------------------------------------------------------


def _boxes(bodies: list[Body]) -> tuple[np.ndarray, np.ndarray]:
    """World-aligned boxes (low, high), (B, 3), of bodies at their current poses."""
    P = np.array([b.pose for b in bodies])
    R = P[:, :3, :3]
    c = (R @ np.array([b.center for b in bodies])[:, :, None])[..., 0] + P[:, :3, 3]
    h = (np.abs(R) @ np.array([b.half for b in bodies])[:, :, None])[..., 0]
    return c - h, c + h


def same_poses(a: dict, b: dict | None) -> bool:
    """Two {name: pose or None} readings are the same."""
    if b is None or a.keys() != b.keys():
        return False
    for k, v in a.items():
        w = b[k]
        if (v is None) != (w is None) or (v is not None and not np.array_equal(v, w)):
            return False
    return True


def _relative(a: _Group, b: _Group) -> np.ndarray:
    """Bound weights of the motion of a relative to b: joints that move both move them together."""
    w = np.zeros_like(a.weights)
    for j in a.movers - b.movers:
        w[j] += a.weights[j]
    for j in b.movers - a.movers:
        w[j] += b.weights[j]
    return w


def _snap(u: float, nxt: float) -> float:
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


def _tup(p) -> tuple[float, float, float]:
    return (float(p[0]), float(p[1]), float(p[2]))


def _mesh(shape) -> tuple:
    if shape.kind == "mesh":
        return (shape.mesh.vertices, shape.mesh.faces)
    return (None, None)


def _solid(shape) -> bool:
    return shape.mesh.solid if shape.kind == "mesh" else True


def as_matrix(p, unit_mm: float = 1.0) -> np.ndarray:
    """A pose from the caller (trsf 6-tuple, an object with x..rz, a 3x4/4x4 matrix; lengths in
    the application's unit) as a 4x4 matrix in mm."""
    from .cellfile import trsf_matrix

    if hasattr(p, "rx"):
        t = (p.x, p.y, p.z, p.rx, p.ry, p.rz)
        M = trsf_matrix(t)
    else:
        a = np.asarray(p, dtype=float)
        if a.shape == (6,):
            M = trsf_matrix(a)
        elif a.shape in ((3, 4), (4, 4)):
            M = np.eye(4)
            M[:3, :] = a[:3, :]
        else:
            raise ValueError("a pose is a trsf (x, y, z, rx, ry, rz) or a 3x4/4x4 matrix")
    M = M.copy()
    M[:3, 3] *= unit_mm
    return M
