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
  configuration (`ArmModel.reach`), and Δq_j runs over the joints that move one group and not the
  other. The bound is summed sample by sample, so a joint that turns back counts twice.
* Conservative advancement: a watch measured at distance d need not be measured again until the
  bound since then reaches d + touch; the next check is put there (aligned down to a sample, or
  to 1/16 of a sample, never less than 1/256 of a sample ahead). Between checks no contact can
  have happened. Far from everything, checks are rare; close to something they get dense, down
  to sub-sample steps for a fast motion that grazes a thin obstacle between two 4 ms samples.
* The measurements give, per sample, a lower bound of the clearance; the minimum of each motion
  is then refined (checks where the bound could still be below the best value found) to within
  `tolerance_mm`, and every sample closer than the margin is measured exactly.

Lengths are millimetres, times seconds, joints VAL 3 values (degrees; mm for a prismatic axis).
Frame and tool poses come from the caller in the application's unit (`app_unit_mm` per unit).
"""

from __future__ import annotations

import bisect
import heapq
import math
from typing import Any, Callable, Mapping

import fcl
import numpy as np

from .armmodel import ArmModel
from .bodies import Body, aabb_gap, point_inside
from .cell import Cell
from .records import CellProblem, Clearance, Contact, MotionReport, MotionSpan, PartDrop

GRID = 16  # below one sample, checks are aligned down to 1/GRID of a sample
MIN_STEP = 1.0 / 256.0  # the smallest step between two checks, in samples
REFINE_CAP = 2000  # measurements per motion spent on refining the minimum
EXACT_CAP = 20000  # measurements per motion spent on exact clearances closer than the margin

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

    __slots__ = ("a", "b", "C", "checks", "contact", "first_contact", "skip", "weights")

    def __init__(self, a: _Group, b: _Group | None, weights: np.ndarray, skip: set[tuple[int, int]]) -> None:
        self.a = a
        self.b = b  # None: the static set
        self.weights = weights
        self.skip = skip  # body pairs (id, id) never measured (a tool solid on its own link)
        self.C = np.zeros(1)
        self.checks: list[tuple[float, float, bool, Any]] = []  # (u, d, exact, (body a, body b, pa, pb))
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
        self._req = fcl.DistanceRequest(enable_nearest_points=True, enable_signed_distance=True)
        self._creq = fcl.CollisionRequest(num_max_contacts=16, enable_contact=True)
        # arm groups
        self.link_groups: dict[str, _Group] = {}
        for link, bodies in arm.bodies.items():
            w = np.zeros(J)
            for j, r in arm.reach[link].items():
                w[j] = 1.0 if arm.links.prismatic[j] else r
            self.link_groups[link] = _Group(link, "link", link, bodies, w, frozenset(arm.links.movers(link)))
        # tool solids: one body each, placed when the tool poses are read
        self._tool_bodies: list[tuple[Any, Body]] = []
        for t in cell.tools:
            label = f"tool {t.tool} {t.name!r}" if t.name else f"tool {t.tool}"
            b = Body("tool", t.tool, t.name, label, t.shape.kind, t.shape.size, t.pose, *_mesh(t.shape),
                     solid=_solid(t.shape))
            self._tool_bodies.append((t, b))
        self.tool_group: _Group | None = None
        self._tool_in_flange: dict[str, np.ndarray | None] = {}
        # parts: carried ({name: group}) and left in the cell
        self.carried: dict[str, _Group] = {}
        self._dropped: list[Body] = []
        # obstacles
        self._obstacles: list[tuple[Any, Body]] = []
        for o in cell.obstacles:
            b = Body("obstacle", o.name, o.name, f"obstacle {o.name!r}", o.shape.kind, o.shape.size, np.eye(4),
                     *_mesh(o.shape), solid=_solid(o.shape))
            self._obstacles.append((o, b))
        self._static: list[Body] = []
        self._placed_obstacles: list[Body] = []
        self._lo = np.zeros((0, 3))
        self._hi = np.zeros((0, 3))
        self._allowed: set[frozenset[int]] = set()  # body pairs touching at a grasp/release, until apart
        self._last_q: np.ndarray | None = None
        self._time = 0.0
        # state of the motion being checked
        self._Q = np.zeros((1, J))
        self._T = np.zeros(1)
        self._q_at: Callable | None = None
        self._poses_u = -1.0
        self._poses: dict[str, np.ndarray] = {}

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
        """Read the frames of the obstacles and the tool poses (at a motion's start)."""
        self._time = time
        static: list[Body] = []
        for o, b in self._obstacles:
            if o.frame == "world":
                base = np.eye(4)
            else:
                base = self._pose(self.frames, o.frame, time)
                if base is None:
                    self._problem(time, o.frame, f"obstacle {o.name!r} is in frame {o.frame}, which has no position "
                                  "in the program: the obstacle is left out", o.where)
                    continue
            b.local = base @ o.pose
            b.place(np.eye(4))
            static.append(b)
        self._placed_obstacles = static
        self._set_static([*static, *self._dropped])
        tool_bodies: list[Body] = []
        poses: dict[str, np.ndarray | None] = {}
        for t, b in self._tool_bodies:
            T = self._tool_pose(t.tool, time, poses, t.where)
            if T is None:
                continue
            b.local = T @ t.pose
            tool_bodies.append(b)
        self._tool_in_flange = poses
        self.tool_group = self._flange_group("tool", "tool", tool_bodies) if tool_bodies else None
        for g in self.carried.values():
            g.weights = self._flange_weights(g.bodies)

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
        if bodies:
            boxes = [b.aabb() for b in bodies]
            self._lo = np.array([lo for lo, _ in boxes])
            self._hi = np.array([hi for _, hi in boxes])
        else:
            self._lo = np.zeros((0, 3))
            self._hi = np.zeros((0, 3))

    def _flange_weights(self, bodies: list[Body]) -> np.ndarray:
        w = np.zeros(self._J)
        far = max(b.reach() for b in bodies)
        for j, r in self.arm.flange_reach().items():
            w[j] = 1.0 if self.arm.links.prismatic[j] else r + far
        return w

    def _flange_group(self, name: str, kind: str, bodies: list[Body]) -> _Group:
        fl = self.arm.flange_link
        return _Group(name, kind, fl, bodies, self._flange_weights(bodies), frozenset(self.arm.links.movers(fl)))

    def _watches(self) -> list[_Watch]:
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
                      for t, b in self._tool_bodies}
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

    def _place(self, g: _Group, u: float) -> None:
        if g.placed == u:
            return
        if self._poses_u != u:
            self._poses = self.arm.links.poses(self._q(u))
            self._poses_u = u
        frame = self._poses[g.link]
        for b in g.bodies:
            b.place(frame)
        g.placed = u

    # ---- measuring -------------------------------------------------------------------------------------

    def _pairs(self, w: _Watch) -> list[tuple[float, Body, Body]]:
        """Body pairs of a watch with the gap between their boxes, nearest first."""
        out: list[tuple[float, Body, Body]] = []
        if w.b is None:
            if not self._static:
                return out
            for ba in w.a.bodies:
                lo, hi = ba.aabb()
                gaps = aabb_gap(lo[None, :], hi[None, :], self._lo, self._hi)
                for i in np.argsort(gaps, kind="stable"):
                    out.append((float(gaps[i]), ba, self._static[i]))
        else:
            for ba in w.a.bodies:
                la, ha = ba.aabb()
                for bb in w.b.bodies:
                    if (id(ba), id(bb)) in w.skip:
                        continue
                    lb, hb = bb.aabb()
                    out.append((float(aabb_gap(la, ha, lb, hb)), ba, bb))
        out.sort(key=lambda x: x[0])
        return out

    def _distance(self, a: Body, b: Body) -> tuple[float, tuple, tuple]:
        res = fcl.DistanceResult()
        d = fcl.distance(a.obj, b.obj, self._req, res)
        self.measurements += 1
        pa, pb = res.nearest_points
        return float(d), _tup(pa), _tup(pb)

    def _measure(self, w: _Watch, u: float, need: float) -> tuple[float, bool, Any]:
        """(d, exact, info) for watch w at position u: the smallest distance between its bodies, or
        a lower bound of it (exact False) when every remaining pair is at least `need` apart.
        info = (body a, body b, point a, point b, depth) for exact values; depth is the penetration
        (mm) when the bodies overlap (d = -depth), else None."""
        self._place(w.a, u)
        if w.b is not None:
            self._place(w.b, u)
        pairs = self._pairs(w)
        if self._allowed:
            kept = []
            for gap, ba, bb in pairs:
                key = frozenset((id(ba), id(bb)))
                if key in self._allowed:
                    if gap > self.touch or self._distance(ba, bb)[0] > self.touch:
                        self._allowed.discard(key)  # apart: checked again from now on
                    continue
                kept.append((gap, ba, bb))
            pairs = kept
        best, exact, info = math.inf, True, None
        touching: list[tuple[Body, Body]] = []
        for gap, ba, bb in pairs:
            if gap > max(best, 0.0):
                break
            if gap >= need:
                if gap < best:
                    best, exact, info = gap, False, None
                break
            d, pa, pb = self._distance(ba, bb)
            if d <= 0.0:
                touching.append((ba, bb))
            if d < best:
                best, exact, info = d, True, (ba, bb, pa, pb, None)
        if touching:
            deepest = None
            for ba, bb in touching:
                c = self._collide(ba, bb)
                if c is not None and (deepest is None or c[0] > deepest[0]):
                    deepest = (c[0], ba, bb, c[1])
            if deepest is not None:
                depth, ba, bb, point = deepest
                best, exact, info = -depth, True, (ba, bb, point, point, depth)
            else:
                best = max(best, 0.0)
                if info is not None:
                    info = (*info[:4], 0.0)
        return best, exact, info

    def _collide(self, a: Body, b: Body) -> tuple[float, tuple] | None:
        res = fcl.CollisionResult()
        fcl.collide(a.obj, b.obj, self._creq, res)
        self.measurements += 1
        if not res.contacts:
            return None
        c = max(res.contacts, key=lambda c: c.penetration_depth)
        return float(c.penetration_depth), _tup(c.pos)

    def _contained(self, w: _Watch, u: float) -> tuple[Body, Body, float] | None:
        """A body of the watch wholly inside a closed mesh of the other side (fcl measures only
        to the surface, so this is tested apart, at a motion's start)."""
        self._place(w.a, u)
        others = self._static if w.b is None else (self._place(w.b, u) or w.b.bodies)
        for ba in w.a.bodies:
            for bb in others:
                if (id(ba), id(bb)) in w.skip or frozenset((id(ba), id(bb))) in self._allowed:
                    continue
                for inner, outer in ((ba, bb), (bb, ba)):
                    if outer.mesh is None or not outer.solid:
                        continue
                    lo, hi = inner.aabb()
                    olo, ohi = outer.aabb()
                    if np.any(lo < olo) or np.any(hi > ohi):
                        continue
                    inv = np.linalg.inv(outer.pose)
                    c = inv[:3, :3] @ (0.5 * (lo + hi)) + inv[:3, 3]
                    if point_inside(outer.mesh[0], outer.mesh[1], c):
                        depth = self._distance(inner, outer)[0]  # to the surface: how deep inside
                        return inner, outer, max(depth, 0.0)
        return None

    # ---- one motion ------------------------------------------------------------------------------------

    def check_motion(self, motion: MotionSpan, times, joints, q_at: Callable[[float], Any] | None = None) -> MotionReport:
        """Check one motion given by its samples: times (N,) in s, joints (N, axes) in VAL 3 units.
        Between samples the arm is on the straight joint-space segment, or at q_at(t) when given
        (then each step's bound also covers how far q_at bends away from the segment)."""
        T = np.asarray(times, dtype=float).reshape(-1)
        Q = np.asarray(joints, dtype=float).reshape(len(T), -1)
        if len(T) == 0:
            raise ValueError("a motion needs at least one sample")
        if Q.shape[1] != self._J:
            raise ValueError(f"joints have {Q.shape[1]} values per sample, the arm has {self._J} axes")
        if not (np.isfinite(T).all() and np.isfinite(Q).all()):
            raise ValueError("times and joints must be finite numbers")
        self._T, self._Q, self._q_at = T, Q, q_at
        self._poses_u = -1.0
        self.refresh(float(T[0]))
        watches = self._watches()
        for g in {id(w.a): w.a for w in watches}.values():
            g.placed = -1.0
        for g in self.link_groups.values():
            g.placed = -1.0
        steps = self._step_motion(Q, q_at, T)
        for w in watches:
            w.C = np.concatenate(([0.0], np.cumsum(steps @ w.weights))) if len(T) > 1 else np.zeros(1)
        report = MotionReport(motion, T, np.zeros(len(T)), np.zeros(len(T), dtype=bool), margin_mm=self.margin,
                              tolerance_mm=self.tol)
        before = self.measurements
        self._advance(watches, report)
        if report.first_contact is None and report.starts_in_collision is None:
            self._refine(watches)
        self._per_sample(watches, report)
        self._minimum(watches, report)
        report.checks = self.measurements - before
        self._last_q = Q[-1].copy()
        self._time = float(T[-1])
        return report

    def _step_motion(self, Q: np.ndarray, q_at, T: np.ndarray) -> np.ndarray:
        """Per step and joint, how much the joint may travel (rad, or mm): |Δq|, plus, with q_at, four
        times how far the path strays from the straight segment at mid-step (a parabola's detour
        past its ends is at most twice that)."""
        if len(Q) < 2:
            return np.zeros((0, self._J))
        dq = np.abs(np.diff(Q, axis=0))
        if q_at is not None:
            mids = np.array([np.asarray(q_at(0.5 * (T[k] + T[k + 1])), dtype=float) for k in range(len(T) - 1)])
            dq = dq + 4.0 * np.abs(mids - 0.5 * (Q[:-1] + Q[1:]))
        return dq * self._rad

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

    def _advance(self, watches: list[_Watch], report: MotionReport) -> None:
        n = len(self._T) - 1
        heap: list[tuple[float, int]] = [(0.0, i) for i in range(len(watches))]
        heapq.heapify(heap)
        while heap:
            u, i = heapq.heappop(heap)
            w = watches[i]
            need = w.C[-1] - self._C(w, u)
            d, exact, info = self._measure(w, u, need if u > 0.0 else math.inf)
            if u == 0.0 and d > 0.0:
                inside = self._contained(w, u)
                if inside is not None:
                    a, b, depth = inside
                    c = _tup(a.pose[:3, 3])
                    d, exact, info = -depth, True, (a, b, c, c, depth, "inside")
            w.checks.append((u, d, exact, info))
            contact = info is not None and info[4] is not None and info[4] > self.touch
            if contact:
                if not w.contact:
                    c = _contact(self._t(u), info, w)
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
                if u < n:
                    heapq.heappush(heap, (float(math.floor(u) + 1), i))
                continue
            w.contact = False
            depth = info[4] if info is not None and info[4] is not None else 0.0
            allowed = max(d, 0.0) + self.touch - depth
            if u >= n or self._C(w, n) - self._C(w, u) <= allowed:
                continue  # certified to the end of the motion
            heapq.heappush(heap, (_snap(u, self._u_of(w, self._C(w, u) + allowed)), i))

    def _refine(self, watches: list[_Watch]) -> None:
        """Measure where the lower bound could still be below the best clearance found, until the
        minimum of the motion is known within the tolerance (or REFINE_CAP measurements).

        Between two checks (u_a, d_a) and (u_b, d_b) of a watch, whose bound grows by S from u_a to
        u_b, the distance is at least min(d_a, d_b, (d_a + d_b - S) / 2); the interval with the
        lowest such bound is measured where it is reached, and split there."""
        n = float(len(self._T) - 1)
        best = min((d for w in watches for (_, d, e, _) in w.checks if e), default=math.inf)
        heap: list[tuple[float, int, float, float]] = []  # (bound, watch, u_a, u_b); u_a < 0: re-measure -u_a - 1

        def interval(wi: int, ka: int) -> None:
            w = watches[wi]
            cs = w.checks
            ua, da, ea, _ = cs[ka]
            if not ea and da < best - self.tol:
                heapq.heappush(heap, (da, wi, -1.0 - ua, ua))
            if ka + 1 < len(cs):
                ub, db = cs[ka + 1][0], cs[ka + 1][1]
                span = self._C(w, ub) - self._C(w, ua)
                lb = min(da, db, 0.5 * (da + db - span))
            else:
                ub = n
                lb = da - (self._C(w, ub) - self._C(w, ua))
            if ub - ua > MIN_STEP and lb < best - self.tol:
                heapq.heappush(heap, (lb, wi, ua, ub))

        for wi, w in enumerate(watches):
            w.checks.sort(key=lambda c: c[0])
            for k in range(len(w.checks)):
                interval(wi, k)
        spent = 0
        while heap and spent < REFINE_CAP:
            lb, wi, ua, ub = heapq.heappop(heap)
            if lb >= best - self.tol:
                break
            w = watches[wi]
            cs = w.checks
            us = [c[0] for c in cs]
            if ua < 0.0:  # an inexact value: measure it exactly
                u = -1.0 - ua
                k = bisect.bisect_left(us, u)
                if k >= len(cs) or cs[k][0] != u or cs[k][2]:
                    continue
                d, exact, info = self._measure(w, u, math.inf)
                cs[k] = (u, d, exact, info)
            else:
                k = bisect.bisect_left(us, ua)
                if k >= len(cs) or cs[k][0] != ua:
                    continue
                last = k + 1 >= len(cs)
                if (last and ub != n) or (not last and cs[k + 1][0] != ub):
                    continue  # split since: stale
                da = cs[k][1]
                if not last:
                    target = 0.5 * (da - cs[k + 1][1] + self._C(w, ua) + self._C(w, ub))
                else:
                    target = self._C(w, ub)
                u = min(max(self._u_of(w, target), ua + MIN_STEP), ub)
                if not last and u >= ub:
                    u = 0.5 * (ua + ub)
                d, exact, info = self._measure(w, u, math.inf)
                k += 1
                cs.insert(k, (u, d, exact, info))
            spent += 1
            if exact and d < best:
                best = d
            for kk in (k - 1, k):
                if 0 <= kk < len(cs):
                    interval(wi, kk)

    def _lower_bounds(self, w: _Watch) -> tuple[np.ndarray, np.ndarray]:
        """Per sample: the watch's lower bound of the distance, and whether it is an exact value."""
        n = len(self._T)
        w.checks.sort(key=lambda c: c[0])
        U = np.array([c[0] for c in w.checks])
        D = np.array([c[1] for c in w.checks])
        E = np.array([c[2] for c in w.checks], dtype=bool)
        CU = np.array([self._C(w, u) for u in U])
        k = np.arange(n, dtype=float)
        Ck = w.C[:n] if len(w.C) >= n else np.full(n, w.C[-1])
        prev = np.searchsorted(U, k, side="right") - 1
        nxt = np.searchsorted(U, k, side="left")
        lb = np.full(n, -math.inf)
        has = prev >= 0
        lb[has] = D[prev[has]] - (Ck[has] - CU[prev[has]])
        has2 = nxt < len(U)
        lb[has2] = np.maximum(lb[has2], D[nxt[has2]] - (CU[nxt[has2]] - Ck[has2]))
        exact = np.zeros(n, dtype=bool)
        at = has2 & (U[np.minimum(nxt, len(U) - 1)] == k)
        exact[at] = E[nxt[at]]
        lb[at] = D[nxt[at]]
        return lb, exact

    def _per_sample(self, watches: list[_Watch], report: MotionReport) -> None:
        n = len(self._T)
        spent = 0
        while True:
            bounds = [self._lower_bounds(w) for w in watches]
            if not bounds:
                report.clearance = np.full(n, math.inf)
                report.exact = np.ones(n, dtype=bool)
                return
            L = np.array([b[0] for b in bounds])
            X = np.array([b[1] for b in bounds])
            low = L.min(axis=0)
            todo = [(wi, k) for k in np.nonzero(low < self.margin)[0] for wi in np.nonzero(
                (L[:, k] < self.margin) & ~X[:, k])[0]] if self.margin > 0 else []
            if not todo or spent >= EXACT_CAP:
                break
            for wi, k in todo[:EXACT_CAP - spent]:
                w = watches[wi]
                w.checks = [c for c in w.checks if c[0] != float(k)]
                d, exact, info = self._measure(w, float(k), math.inf)
                w.checks.append((float(k), d, exact, info))
                spent += 1
        # the watch with the lowest bound is measured there: the others are at least as far, so the
        # clearance is that measurement
        report.clearance = low
        report.exact = X[L.argmin(axis=0), np.arange(n)]

    def _minimum(self, watches: list[_Watch], report: MotionReport) -> None:
        best = None
        for w in watches:
            for u, d, e, info in w.checks:
                if e and info is not None and (best is None or d < best[0]):
                    best = (d, u, info)
        if best is None:
            return
        d, u, (a, b, pa, pb) = best[0], best[1], best[2][:4]
        report.min_clearance = Clearance(float(d), self._t(u), a.label, b.label, pa, pb)
        report.too_close = (report.first_contact is None and report.starts_in_collision is None
                            and self.margin > 0.0 and d < self.margin)

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
        cache: dict = dict(self._tool_in_flange)
        for name in names:
            solids = [p for p in self.cell.parts if p.name == name]
            first = solids[0]
            if instruction == first.grasp and name not in self.carried:
                T = self._tool_pose(tool, time, cache, first.where)
                if T is None:
                    continue
                bodies = [Body("part", name, name, f"part {name!r}", p.shape.kind, p.shape.size, T @ p.pose,
                               *_mesh(p.shape), solid=_solid(p.shape)) for p in solids]
                for b in bodies:
                    b.place(flange)
                self._pick_up(name, bodies)
                self._allow_touching(bodies, self._static)
                self.carried[name] = self._flange_group(f"part {name!r}", "part", bodies)
            elif instruction == first.release and name in self.carried:
                g = self.carried.pop(name)
                for b in g.bodies:
                    b.place(flange)
                    b.local = b.pose.copy()
                    b.kind = "obstacle"
                drops.extend(self._dropped_inside(g.bodies, time, source))
                self._allow_touching(g.bodies, [b for b in arm_bodies if b.owner != name])
                self._dropped.extend(g.bodies)
                self._set_static([*self._placed_obstacles, *self._dropped])
        return drops

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
                d, _, _ = self._distance(a, b)
                if d <= self.touch:
                    self._allowed.add(frozenset((id(a), id(b))))

    def _dropped_inside(self, bodies: list[Body], time: float, source: Any) -> list[PartDrop]:
        out = []
        for a in bodies:
            for b in self._static:
                la, ha = a.aabb()
                lb, hb = b.aabb()
                if float(aabb_gap(la, ha, lb, hb)) > 0.0:
                    continue
                c = self._collide(a, b)
                if c is not None and c[0] > self.touch:
                    out.append(PartDrop(time, a.label, b.label, c[1], c[0], source))
                    continue
                for inner, outer in ((a, b), (b, a)):
                    if outer.mesh is not None and outer.solid:
                        inv = np.linalg.inv(outer.pose)
                        p = inv[:3, :3] @ inner.pose[:3, 3] + inv[:3, 3]
                        if point_inside(outer.mesh[0], outer.mesh[1], p):
                            out.append(PartDrop(time, a.label, b.label, _tup(inner.pose[:3, 3]), None, source))
                            break
        return out


# ---- helpers ----------------------------------------------------------------------------------------------


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


def _contact(t: float, info, w: _Watch) -> Contact:
    a, b, pa, _, depth = info[:5]
    kind = "inside" if len(info) > 5 else "contact" if w.b is None else "self"
    return Contact(t, a.label, b.label, pa, depth, kind)


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
