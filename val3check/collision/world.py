"""The world between motions: the static solids (obstacles placed in their frames, parts left in
the cell), the tool placed by the tool variables, the parts carried, and the touch allowances
(body pairs touching at a grasp or a release, not checked until they have moved apart).

The world changes at a motion's start (`refresh`: frames and tools read again) and at the
grippers' open/close (`gripper`); `version` changes with it, and what is computed from the scene
(`per_scene`) is computed again.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable
from dataclasses import replace
from typing import Any

import numpy as np

from ..light_dataclass import dataclass
from .allowed import Allowed
from .armmodel import ArmModel
from .bodies import Body, aabb_gap, copies, make_bodies
from .cell import Cell, Obstacle, ToolSolid
from .fcl_backend import FclBackend
from .groups import Group, Watch, link_group, make_watches
from .poses import PoseSource, as_matrix, same_poses
from .results import CellProblem, PartDrop


@dataclass(slots=True)
class ToolBody:
    """A body of a tool solid: `in_solid` is its pose in the solid (a mesh piece's own pose)."""

    solid: ToolSolid
    body: Body
    in_solid: np.ndarray


@dataclass(slots=True)
class ObstacleBody:
    """A body of an obstacle of the cell."""

    obstacle: Obstacle
    body: Body


SCENES = 4096  # scene contents kept with their numbers (`World.key`)
GRIPS = 2048  # open()/close() events kept for reuse (`World.gripper`)


class World:
    """The scene one arm moves in: see the module's docstring.

    frames / tools: where the caller reads application frames (in world) and tool variables (in
    the flange); unit: mm per application unit; touch: mm of overlap that is only touching."""

    def __init__(self, arm: ArmModel, cell: Cell, backend: FclBackend, *, frames: PoseSource = None,
                 tools: PoseSource = None, app_unit_mm: float = 1.0, touch_mm: float = 0.05,
                 readings: Callable[[float], Hashable] | None = None) -> None:
        self.arm = arm
        self.cell = cell
        self.backend = backend
        self.frames = frames
        self.tools = tools
        # readings(t): a token that changes whenever frames/tools may answer otherwise at t
        self.readings = readings
        self._read_token: Hashable = None
        self.unit = float(app_unit_mm)
        self.touch = float(touch_mm)
        self.problems: list[CellProblem] = []
        self._reported: set[tuple[str, str]] = set()
        self.link_groups: dict[str, Group] = {link: link_group(arm, link, bodies) for link, bodies in arm.bodies.items()}
        # tool solids, placed when the tool poses are read
        self.tool_bodies: list[ToolBody] = []
        for i, t in enumerate(cell.tools):
            label = f"tool {t.tool} {t.name!r}" if t.name else f"tool {t.tool}"
            for k, b in enumerate(make_bodies("tool", t.tool, t.name, label, t.shape.kind, t.shape.size, np.eye(4),
                                              *_mesh(t.shape), solid=_solid(t.shape))):
                b.made_from = ("tool", i, k)
                self.tool_bodies.append(ToolBody(t, b, b.local))
        self.tool_group: Group | None = None
        self.tool_in_flange: dict[str, np.ndarray | None] | None = None
        # parts: carried ({name: group}) and left in the cell
        self.carried: dict[str, Group] = {}
        self.dropped: list[Body] = []
        self.obstacle_bodies: list[ObstacleBody] = []
        for i, o in enumerate(cell.obstacles):
            for k, b in enumerate(make_bodies("obstacle", o.name, o.name, f"obstacle {o.name!r}", o.shape.kind,
                                              o.shape.size, np.eye(4), *_mesh(o.shape), solid=_solid(o.shape))):
                b.made_from = ("obstacle", i, k)
                self.obstacle_bodies.append(ObstacleBody(o, b))
        # the static set, and world-aligned boxes (S, 3) around its bodies
        self.static: list[Body] = []
        self.static_lo = np.zeros((0, 3))
        self.static_hi = np.zeros((0, 3))
        self._placed_obstacles: list[Body] = []
        self._boxes: dict[int, tuple] | tuple = {}  # id of a static body -> (its pose then, its box): `_set_static`
        self._frames_read: dict | None = None
        self.version = 0
        self._scene_cache: dict[str, tuple[int, Any]] = {}
        # body pairs touching at a grasp or a release, not checked until they have moved apart
        self.allowed = {}
        self._key: tuple = (None, None, None, None)  # (links, scene number, allowed's stamp, `key`'s answer)
        self.last_q: np.ndarray | None = None
        self.time = 0.0
        self._scene_ids: dict[tuple, int] = {}  # scene content (`_scene_key`) -> a number never given to another
        self._next_scene = 0
        self._grips: dict[tuple, tuple] = {}  # `_grip_key` -> what the open()/close() did (`_replay`)
        self._parts_made: dict[tuple, list[Body]] = {}  # a part's solids (their places in the cell) -> as first made
        self.grips_reused = 0

    # ---- reading the program's frames and tools ------------------------------------------------------------

    def _pose(self, source: PoseSource, name: str, time: float) -> np.ndarray | None:
        if source is None:
            return None
        try:
            p = source(name, time) if callable(source) else source.get(name)  # type: ignore[union-attr]
        except Exception as exc:  # a caller's lookup that fails: the solid is left out, and said so
            self.problem(time, name, f"{name}: cannot be read: {exc}")
            return None
        return None if p is None else as_matrix(p, self.unit)

    def problem(self, time: float, what: str, message: str, where=None) -> None:
        """Say once that something of the cell cannot be placed."""
        key = (what, message)
        if key not in self._reported:
            self._reported.add(key)
            self.problems.append(CellProblem(time, what, message, where))

    def refresh(self, time: float) -> None:
        """Read the frames of the obstacles and the tool poses (at a motion's start); the scene is
        rebuilt only when one of them changed."""
        self.time = time
        token = None if self.readings is None else self.readings(time)
        if token is not None and token == self._read_token:
            return  # the same readings as the last time: the same scene
        self._read_token = token
        frames: dict[str, np.ndarray | None] = {"world": np.eye(4)}
        for ob in self.obstacle_bodies:
            if ob.obstacle.frame not in frames:
                frames[ob.obstacle.frame] = self._pose(self.frames, ob.obstacle.frame, time)
        poses: dict[str, np.ndarray | None] = {}
        for tb in self.tool_bodies:
            self.tool_pose(tb.solid.tool, time, poses, tb.solid.where)
        if same_poses(frames, self._frames_read) and same_poses(poses, self.tool_in_flange):
            return
        self._frames_read = frames
        static: list[Body] = []
        for ob in self.obstacle_bodies:
            o, b = ob.obstacle, ob.body
            base = frames[o.frame]
            if base is None:
                self.problem(time, o.frame, f"obstacle {o.name!r} is in frame {o.frame}, which has no "
                             "position in the program: the obstacle is left out", o.where)
                continue
            b.local = base @ o.pose
            b.place(np.eye(4))
            static.append(b)
        self._placed_obstacles = static
        self._set_static([*static, *self.dropped])
        tool_bodies: list[Body] = []
        for tb in self.tool_bodies:
            T = poses[tb.solid.tool]
            if T is not None:
                tb.body.local = T @ tb.solid.pose @ tb.in_solid
                tool_bodies.append(tb.body)
        self.tool_in_flange = poses
        self.tool_group = self._flange_group("tool", "tool", tool_bodies) if tool_bodies else None
        self.version += 1

    def tool_pose(self, tool: str, time: float, cache: dict, where=None) -> np.ndarray | None:
        """The pose of a tool variable in the flange (the flange itself for "flange"), read once
        into `cache`; a tool the program has no value for is said (its solids are left out)."""
        if tool not in cache:
            if tool == "flange":
                cache[tool] = np.eye(4)
            else:
                T = self._pose(self.tools, tool, time)
                if T is None:
                    self.problem(time, tool, f"tool {tool} has no value in the program: its solids and parts "
                                 "are left out", where)
                cache[tool] = T
        return cache[tool]

    # ---- the scene ---------------------------------------------------------------------------------------

    def _set_static(self, bodies: list[Body], given: tuple | None = None) -> None:
        """The static set is `bodies`; `given`: their boxes (lo, hi) as an equal set had them (`_replay`)."""
        self.static = bodies
        self.version += 1
        if given is not None:
            self.static_lo, self.static_hi = given
            self._boxes = (bodies, [b.pose for b in bodies], given)  # made a dict when next asked (most are not)
        elif bodies:
            # a body's box is computed again only when it was placed again (each place() makes a new pose)
            known = self._boxes
            if isinstance(known, tuple):
                known = {id(b): (pose, lo, hi) for b, pose, lo, hi in zip(known[0], known[1], *known[2])}
            boxes = []
            for b in bodies:
                hit = known.get(id(b))
                if hit is None or hit[0] is not b.pose:
                    hit = (b.pose, *b.aabb())
                boxes.append(hit)
            self._boxes = {id(b): hit for b, hit in zip(bodies, boxes)}
            boxes = [hit[1:] for hit in boxes]
            self.static_lo = np.array([lo for lo, _ in boxes])
            self.static_hi = np.array([hi for _, hi in boxes])
        else:
            self.static_lo = np.zeros((0, 3))
            self.static_hi = np.zeros((0, 3))
        self.static_lo.flags.writeable = False  # shared with `_grip`'s record
        self.static_hi.flags.writeable = False

    def _flange_group(self, name: str, kind: str, bodies: list[Body]) -> Group:
        return link_group(self.arm, self.arm.flange_link, bodies, name, kind)

    def arm_groups(self) -> list[Group]:
        """The groups the arm moves: its links, the tool, the carried parts."""
        out = list(self.link_groups.values())
        if self.tool_group is not None:
            out.append(self.tool_group)
        out.extend(self.carried.values())
        return out

    @property
    def allowed(self) -> Allowed:
        """Body pairs allowed to touch: {frozenset of their ids: (a, b)}."""
        return self._allowed

    @allowed.setter
    def allowed(self, pairs: dict) -> None:
        self._allowed = Allowed(pairs)

    def per_scene(self, key: str, make: Callable[[], Any]) -> Any:
        """make(), computed once per version of the scene."""
        version, value = self._scene_cache.get(key, (-1, None))
        if version != self.version:
            value = make()
            self._scene_cache[key] = (self.version, value)
        return value

    def key(self) -> tuple:
        """Everything of the scene a motion's check depends on, by content (the result of a motion
        that repeats in an equal scene is reused: `CollisionChecker.check_own`): the arm's geometry
        in force, the static set, the tool and the carried parts (each body by the solid of the cell
        it was made from and its pose), and the pairs allowed to touch."""
        links = getattr(self.arm.links, "current", self.arm.links)  # setDH (11.4): the geometry in force
        version, scene = self._scene_cache.get("key", (-1, None))
        if version != self.version:  # `per_scene`, inline: asked at every motion
            scene = self.per_scene("key", self._scene_id)
        last = self._key
        stamp = self._allowed.stamp
        if last[0] is links and last[1] == scene and last[2] == stamp:
            return last[3]  # nothing it is made of changed (stamps are never given twice)
        out = links, scene, tuple(self.allowed_names())
        self._key = (links, scene, stamp, out)
        return out

    def _scene_id(self) -> int:
        """The scene's content as a number, the same for an equal content (computed once per
        version of the scene: hashing the content at each lookup costs more than the lookup)."""
        content = self._scene_key()
        n = self._scene_ids.get(content)
        if n is None:
            if len(self._scene_ids) >= SCENES:
                self._scene_ids.clear()  # bounded; numbers are never given again: a forgotten scene is a miss
            n = self._scene_ids[content] = self._next_scene
            self._next_scene += 1
        return n

    def _scene_key(self) -> tuple:
        static = tuple(_placed(b) for b in self.static)
        tool = None if self.tool_group is None else tuple(_placed(b) for b in self.tool_group.bodies)
        carried = tuple((name, tuple(_placed(b) for b in g.bodies)) for name, g in self.carried.items())
        return static, tool, carried

    def forget_allowed(self, pairs) -> None:
        """The touch allowances of these pairs (by `key`'s names) end (a reused check found them apart)."""
        if not pairs:
            return
        gone = set(pairs)
        self.allowed = {k: v for k, v in self.allowed.items() if (_named(v[0]), _named(v[1])) not in gone}

    def allowed_names(self) -> list[tuple]:
        """The pairs allowed to touch, by `key`'s names, in order."""
        return [(_named(a), _named(b)) for a, b in self.allowed.values()]

    def watches(self) -> list[Watch]:
        """The pairs of groups checked in the scene as it is (`groups.make_watches`)."""
        return self.per_scene("watches", self._make_watches)

    def _make_watches(self) -> list[Watch]:
        arm = self.arm
        flange_side = [g for g in (self.tool_group, *self.carried.values()) if g is not None]
        tool_touch = {id(tb.body): (tb.solid.touch_links if tb.solid.touch_links is not None else arm.touch_links)
                      for tb in self.tool_bodies}
        return make_watches(arm, self.link_groups, flange_side, tool_touch)

    # ---- the grippers -----------------------------------------------------------------------------------

    def gripper(self, tool: str, instruction: str, time: float, joints=None, source: Any = None) -> list[PartDrop]:
        """open(tool) or close(tool) ran at `time`, the arm at `joints` (default: where the last
        motion ended): the parts grasped on it are attached, the parts released are left in the
        cell where they are; returns the parts left inside an obstacle or another part
        (`CollisionChecker.gripper`). What an event does is computed once per key (`_grip_key`:
        the tool and its pose, the instruction, the joints, the scene) and done again from what
        was recorded (`_replay`): the same solids made, taken, left and allowed to touch."""
        if instruction not in ("open", "close"):
            raise ValueError("instruction is 'open' or 'close'")
        q = np.asarray(joints, dtype=float) if joints is not None else self.last_q
        if q is None:
            q = np.zeros(self.arm.n_joints)
        self.refresh(time)
        key = self._grip_key(tool, instruction, time, q)
        done = self._grips.get(key)
        if done is not None:
            self.grips_reused += 1
            drops = self._replay(done, time, source)
            # the scene it leaves has the content it left the first time: its number then (`key`)
            self._scene_cache["key"] = (self.version, done[3])
            return drops
        steps: list[tuple] = []
        poses = self.arm.links.poses(q)
        drops = self._grip(tool, instruction, time, poses, source, steps)
        if len(self._grips) >= GRIPS:
            self._grips.clear()  # bounded: a cyclic program fills it again within a cycle or two
        self._grips[key] = (poses, steps, [replace(d, time=0.0, source=None) for d in drops],
                            self.per_scene("key", self._scene_id))
        return drops

    def _grip_key(self, tool: str, instruction: str, time: float, q: np.ndarray) -> tuple:
        """Everything an open()/close() depends on: the tool, its pose (read without a side effect:
        what the event reads is said by the event), the instruction, the joints (bits), the
        scene (`key`) and the touch tolerance."""
        if tool == "flange":
            T: Any = "flange"
        elif self.tool_in_flange is not None and tool in self.tool_in_flange:
            T = self.tool_in_flange[tool]
        else:
            source = self.tools
            try:
                T = source(tool, time) if callable(source) else None if source is None else source.get(tool)
                T = None if T is None else as_matrix(T, self.unit)
            except Exception:
                T = "unreadable"
        T = T.tobytes() if isinstance(T, np.ndarray) else T
        return tool, T, instruction, q.shape, q.tobytes(), self.key(), self.touch

    def _place_arm(self, poses: dict) -> list[Body]:
        """The arm's bodies placed at these link poses (marked for placing again at the next sample)."""
        arm_bodies: list[Body] = []
        for g in self.arm_groups():
            for b in g.bodies:
                b.place(poses[g.link])
            g.placed = -1.0
            arm_bodies.extend(g.bodies)
        return arm_bodies

    def _arm_groups_unplaced(self) -> list[Group]:
        """The arm's groups (`_place_arm`'s order of their bodies), marked for placing again at the
        next sample."""
        groups = self.arm_groups()
        for g in groups:
            g.placed = -1.0
        return groups

    def _grip(self, tool: str, instruction: str, time: float, poses: dict, source: Any, steps: list) -> list[PartDrop]:
        """open()/close() computed; what it does is appended to `steps` (`_replay` does it again)."""
        flange = poses[self.arm.flange_link]
        arm_bodies = self._place_arm(poses)
        drops: list[PartDrop] = []
        cache: dict = dict(self.tool_in_flange or {})
        for name in self._part_names(tool):
            solids = [(i, p) for i, p in enumerate(self.cell.parts) if p.name == name]
            first = solids[0][1]
            if instruction == first.grasp and name not in self.carried:
                T = self.tool_pose(tool, time, cache, first.where)
                if T is None:
                    continue
                bodies = self._part_bodies(name, solids)
                for b, p in zip(bodies, self._solid_of(bodies)):
                    b.local = T @ p.pose @ b.local
                for b in bodies:
                    b.place(flange)
                gone = self._pick_up(name, bodies)
                pairs = self._allow_touching(bodies, self.static)
                g = self.carried[name] = self._flange_group(f"part {name!r}", "part", bodies)
                self.version += 1
                steps.append(("grasp", name, solids, [b.local.copy() for b in bodies], gone, pairs, g.weights.copy(),
                              (self.static_lo, self.static_hi)))
            elif instruction == first.release and name in self.carried:
                g = self.carried.pop(name)
                self.version += 1
                for b in g.bodies:
                    b.place(flange)
                    b.local = _on_grid(b.pose)
                    b.place(np.eye(4))
                    b.kind = "obstacle"
                drops.extend(self._dropped_inside(g.bodies, time, source))
                pairs = self._allow_touching(g.bodies, [b for b in arm_bodies if b.owner != name])
                self.dropped.extend(g.bodies)
                self._set_static([*self._placed_obstacles, *self.dropped])
                steps.append(("release", name, [b.local.copy() for b in g.bodies], pairs, (self.static_lo, self.static_hi)))
        return drops

    def _replay(self, done: tuple, time: float, source: Any) -> list[PartDrop]:
        """An open()/close() recorded by `_grip` in an equal scene done again: its steps in order,
        each on the solids of this scene (found by their place in its lists)."""
        poses, steps, drops, _ = done
        flange = poses[self.arm.flange_link]
        groups = self._arm_groups_unplaced()  # not placed: every reader of their poses places them first
        world = _EYE
        for step in steps:
            if step[0] == "grasp":
                _, name, solids, locals_, gone, pairs, weights, boxes = step
                bodies = self._part_bodies(name, solids)
                for b, M in zip(bodies, locals_):
                    b.local = M.copy()
                    b.place(flange)
                self._take_away(gone, boxes)
                self._allow_pairs(bodies, self.static, pairs)
                self.carried[name] = Group(f"part {name!r}", "part", self.arm.flange_link, bodies, weights.copy(),
                                           frozenset(self.arm.links.movers(self.arm.flange_link)))
                self.version += 1
            else:
                _, name, locals_, pairs, boxes = step
                g = self.carried.pop(name)
                self.version += 1
                for b, M in zip(g.bodies, locals_):
                    b.local = M.copy()
                    b.place(world)
                    b.kind = "obstacle"
                if pairs:  # by their places among the arm's bodies as the event found them
                    arm_bodies = [b for a in groups for b in a.bodies]
                    self._allow_pairs(g.bodies, [b for b in arm_bodies if b.owner != name], pairs)
                self.dropped.extend(g.bodies)
                self._set_static([*self._placed_obstacles, *self.dropped], boxes)
        return [replace(d, time=time, source=source) for d in drops]

    def _part_names(self, tool: str) -> list[str]:
        names: list[str] = []
        for p in self.cell.parts:
            if p.tool == tool and p.name not in names:
                names.append(p.name)
        return names

    def _part_bodies(self, name: str, solids: list) -> list[Body]:
        """New solids of the part `name` (its (index, Part) in the cell), in their part's frame:
        copies of the ones made the first time (`bodies.copies`: a part is taken again and again)."""
        key = tuple(i for i, _ in solids)
        made = self._parts_made.get(key)
        if made is None:
            made = []
            for i, p in solids:
                for k, b in enumerate(make_bodies("part", name, name, f"part {name!r}", p.shape.kind, p.shape.size,
                                                  np.eye(4), *_mesh(p.shape), solid=_solid(p.shape))):
                    b.made_from = ("part", i, k)
                    made.append(b)
            self._parts_made[key] = made  # never placed nor handed out: only copied
        return copies(made)

    def _solid_of(self, bodies: list[Body]) -> list:
        return [self.cell.parts[b.made_from[1]] for b in bodies]

    def clear_parts(self, name: str) -> int:
        """The parts named `name` left in the cell are taken away: how many solids left the cell."""
        gone = {id(d) for d in self.dropped if d.owner == name}
        if gone:
            self._forget(gone)
            self.dropped = [d for d in self.dropped if id(d) not in gone]
            self._set_static([*self._placed_obstacles, *self.dropped])
        return len(gone)

    def _forget(self, gone: set[int]) -> None:
        """Touch allowances of bodies that left the cell are dropped."""
        self.allowed = {k: v for k, v in self.allowed.items() if not (k & gone)}

    def _pick_up(self, name: str, bodies: list[Body]) -> list[int]:
        """A part taken where a part of the same name was left is that part: it leaves the cell.
        Returns the places in `dropped` of the solids that left."""
        gone = [k for k, d in enumerate(self.dropped) if d.owner == name and any(self._overlap(d, b) for b in bodies)]
        self._take_away(gone)
        return gone

    def _take_away(self, gone: list[int], boxes: tuple | None = None) -> None:
        """The solids at these places in `dropped` leave the cell (`boxes`: `_set_static`'s)."""
        if gone:
            ids = {id(self.dropped[k]) for k in gone}
            self._forget(ids)
            self.dropped = [d for d in self.dropped if id(d) not in ids]
            self._set_static([*self._placed_obstacles, *self.dropped], boxes)

    def _overlap(self, a: Body, b: Body) -> bool:
        la, ha = a.aabb()
        lb, hb = b.aabb()
        if float(aabb_gap(la, ha, lb, hb)) > self.touch:
            return False
        return self.backend.distance(a, b).mm <= self.touch

    def _allow_touching(self, bodies: list[Body], others: list[Body]) -> list[tuple[int, int]]:
        """The pairs of `bodies` and `others` touching now may touch (until they have moved apart);
        returns them by their places in the two lists."""
        out: list[tuple[int, int]] = []
        if not bodies or not others:
            return out
        # the boxes of all pairs at once; fcl measures only the pairs whose boxes are that close
        box_a, box_b = ([b.aabb() for b in group] for group in (bodies, others))
        lo_a, hi_a = (np.array(x)[:, None, :] for x in zip(*box_a))
        lo_b, hi_b = (np.array(x)[None, :, :] for x in zip(*box_b))
        near = aabb_gap(lo_a, hi_a, lo_b, hi_b) <= self.touch
        for i, j in zip(*np.nonzero(near)):
            a, b = bodies[i], others[j]
            if b is not a and self.backend.distance(a, b).mm <= self.touch:
                out.append((int(i), int(j)))
        self._allow_pairs(bodies, others, out)
        return out

    def _allow_pairs(self, bodies: list[Body], others: list[Body], pairs: list[tuple[int, int]]) -> None:
        for i, j in pairs:
            a, b = bodies[i], others[j]
            self.allowed[frozenset((id(a), id(b)))] = (a, b)

    def _dropped_inside(self, bodies: list[Body], time: float, source: Any) -> list[PartDrop]:
        """The part's solids left overlapping an obstacle (deeper than the touch tolerance), or wholly
        inside a closed mesh."""
        out = []
        seen: set[tuple[int, int]] = set()
        for a in bodies:
            la, ha = a.aabb()
            for b in self.static:
                if b in bodies or (a.whole, b.whole) in seen:
                    continue
                lb, hb = b.whole_aabb()
                if float(aabb_gap(la, ha, lb, hb)) > 0.0:
                    continue
                if self.backend.distance(a, b).mm <= 0.0:
                    pen = self.backend.contact(a, b)
                    if pen is not None and pen.depth > self.touch:
                        seen.add((a.whole, b.whole))
                        out.append(PartDrop(time, a.label, b.label, pen.point_a, pen.depth, source))
                    continue
                for inner, outer in ((a, b), (b, a)):
                    pen = self.backend.inside(inner, outer)
                    if pen is not None:
                        seen.add((a.whole, b.whole))
                        out.append(PartDrop(time, a.label, b.label, pen.point_a, None, source))
                        break
        return out



_EYE = np.eye(4)  # the world frame (read only: Body.place makes a new pose)
_EYE.flags.writeable = False
GRID_MM = 1e-6  # a part left in the cell is put on this grid (and its rotation on GRID_ROT): see _on_grid
GRID_ROT = 1e-9


def _on_grid(pose: np.ndarray) -> np.ndarray:
    """The pose of a part left in the cell, rounded to GRID_MM (1e-6 mm) and its rotation to GRID_ROT: the arm lets it
    go at joints computed on the run's absolute clock, whose last bits differ from one cycle to the
    next; rounded, the part left in the same place is in the same place (`World.key`)."""
    out = pose.copy()
    out[:3, 3] = np.round(pose[:3, 3] / GRID_MM) * GRID_MM
    out[:3, :3] = np.round(pose[:3, :3] / GRID_ROT) * GRID_ROT
    return out


def _named(b: Body):
    """A body as the scene's key names it: the solid of the cell it was made from and its piece,
    or the body itself (the arm's own solids, which live as long as the arm)."""
    return b if b.made_from is None else b.made_from


def _placed(b: Body) -> tuple:
    return _named(b), b.local.tobytes()


def _mesh(shape) -> tuple:
    if shape.kind == "mesh":
        return (shape.mesh.vertices, shape.mesh.faces)
    return (None, None)


def _solid(shape) -> bool:
    return shape.mesh.solid if shape.kind == "mesh" else True
