"""Every link of an arm with its collision solids, and where each link is for given joint values.

The kinematics of `kinematics.py` gives the flange; collision checking needs every link. This
module reads the URDF's `<collision>` elements (box, cylinder, sphere, mesh) and the whole link
tree, and computes each link's pose in the VAL 3 world frame (millimetres) from VAL 3 joint
values (degrees for revolute axes, millimetres for prismatic ones). It also gives what the
collision package needs to bound motion between two configurations (`reach_from_joint`) and the
link graph of MoveIt's allowed-collision matrix (`adjacent_pairs`).

Pure data plus numpy; no collision library here (val3check/collision/ builds the solids).
"""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np

from ..excerpt import shown
from ..lengths import M_MM
from ..light_dataclass import dataclass
from .errors import RobotError
from .urdf import UrdfInfo, read_urdf

_MOVING = ("revolute", "continuous", "prismatic")
ROWS = 8192  # rows × 4 × 4 under OpenBLAS's threshold for threads (65,536 × 4)


@dataclass(frozen=True)
class Solid:
    """One `<collision>` element of a link. Lengths in mm; `origin` is its 4x4 pose in the link frame.

    kind "box": size = (x, y, z); "cylinder": (radius, length) along the local z, centred;
    "sphere": (radius,); "mesh": size = scale (x, y, z) applied to the file's metres, and `mesh`
    is the file's path (resolved beside the URDF)."""

    link: str
    name: str
    kind: str
    size: tuple[float, ...]
    origin: np.ndarray
    mesh: str = ""


@dataclass(frozen=True)
class _Edge:
    """The joint from `parent` to `child`: fixed origin (4x4, mm), axis, kind, index in q (or -1)."""

    parent: str
    child: str
    origin: np.ndarray
    axis: np.ndarray
    kind: str
    index: int
    name: str


class ArmLinks:
    """The link tree of an arm model, in the VAL 3 world frame.

    links        link names, parents before children (the root first)
    solids       every collision solid (`Solid`), in URDF order
    joint_names  the model's joints, in the order of the joint values
    poses(q)     {link: 4x4 pose in world (mm)} for VAL 3 joint values q
    """

    def __init__(self, info: UrdfInfo, solids: list[Solid], joint_names: tuple[str, ...], world: str):
        self.path = info.path
        self.joint_names = tuple(joint_names)
        self.solids = tuple(solids)
        root = info.root_link()
        if not root:
            raise RobotError(f"{info.path}: the links do not form one tree with a single root")
        children: dict[str, list] = {}
        for j in info.joints.values():
            children.setdefault(j.parent, []).append(j)
        index = {n: i for i, n in enumerate(self.joint_names)}
        missing = [n for n in self.joint_names if n not in info.joints]
        if missing:
            raise RobotError(f"{info.path}: no joint named {shown(missing[0])}")
        self.edges: dict[str, _Edge] = {}  # by child link
        order = [root]
        stack = [root]
        seen = {root}
        while stack:
            link = stack.pop()
            for j in sorted(children.get(link, []), key=lambda j: j.name):
                if j.child in seen:
                    raise RobotError(f"{info.path}: link {shown(j.child)} has two parents")
                seen.add(j.child)
                T = _transform(j.xyz, j.rpy)
                ax = np.asarray(j.axis, dtype=float)
                n = float(np.linalg.norm(ax))
                kind = j.kind if j.kind in _MOVING else "fixed"
                if kind != "fixed" and n == 0.0:
                    raise RobotError(f"{info.path}: joint {shown(j.name)} has a zero axis")
                self.edges[j.child] = _Edge(link, j.child, T, ax / n if n else ax, kind, index.get(j.name, -1), j.name)
                order.append(j.child)
                stack.append(j.child)
        self.links = tuple(order)
        if world not in seen:
            raise RobotError(f"{info.path}: no link named {shown(world)} (the world frame)")
        # pose of the root in the VAL 3 world frame: the inverse of root -> world (fixed joints)
        T = np.eye(4)
        link = world
        while link != root:
            e = self.edges[link]
            if e.kind != "fixed":
                raise RobotError(f"{info.path}: the world frame {shown(world)} must be fixed to the base")
            T = e.origin @ T
            link = e.parent
        self.root = root
        self.root_in_world = np.linalg.inv(T)
        self.world = world
        # the model's joint indices that move each link, root side first
        self._movers: dict[str, tuple[int, ...]] = {}
        for link in self.links:
            chain: list[int] = []
            n = link
            while n != root:
                e = self.edges[n]
                if e.kind != "fixed" and e.index >= 0:
                    chain.append(e.index)
                n = e.parent
            self._movers[link] = tuple(reversed(chain))
        # the FK plan: (link, parent, fixed origin, index of its joint motion or -1), parents first
        moving = [e for e in (self.edges[n] for n in self.links[1:]) if e.kind != "fixed" and e.index >= 0]
        slot = {e.child: i for i, e in enumerate(moving)}
        self._plan = [(n, self.edges[n].parent, self.edges[n].origin, slot.get(n, -1)) for n in self.links[1:]]
        self._axes = np.array([e.axis for e in moving]).reshape(-1, 3)
        self._kinds_prismatic = np.array([e.kind == "prismatic" for e in moving], dtype=bool)
        self._qindex = np.array([e.index for e in moving], dtype=int)
        self.prismatic = tuple(
            any(e.index == i and e.kind == "prismatic" for e in self.edges.values()) for i in range(len(self.joint_names))
        )

    # ---- forward kinematics ---------------------------------------------------------------------

    def poses(self, q) -> dict[str, np.ndarray]:
        """{link: 4x4 pose in the VAL 3 world frame, mm} for VAL 3 joint values (deg, or mm for a
        prismatic axis). Joints that are not the model's (a gripper finger…) stay at zero."""
        M = _motions_one(self._axes, self._kinds_prismatic, np.asarray(q, dtype=float)[self._qindex])
        out = {self.root: self.root_in_world}
        for link, parent, origin, m in self._plan:
            T = out[parent] @ origin
            out[link] = T if m < 0 else T @ M[m]
        return out

    def poses_many(self, Q, links=None) -> dict[str, np.ndarray]:
        """`poses` for many joint positions at once: Q is (N, joints); each pose (N, 4, 4). `links`:
        only those and the links between them and the root (all when None). Every joint's motion
        at once, and a fixed origin applied to all N poses in one product: the same values as one
        product per pose (a 4x4 product is the same whatever the rows around it)."""
        Q = np.asarray(Q, dtype=float)
        n = len(Q)
        plan = self._plan if links is None else self._plan_to(tuple(links))
        M = _motions_many(self._axes, self._kinds_prismatic, Q[:, self._qindex])
        out = {self.root: np.broadcast_to(self.root_in_world, (n, 4, 4))}
        for link, parent, origin, m in plan:
            T = _times(out[parent], origin)
            out[link] = T if m < 0 else T @ M[m]
        return out

    def _plan_to(self, links: tuple) -> list:
        """The FK plan's steps that reach `links` (parents first)."""
        plans = self.__dict__.setdefault("_plans", {})
        plan = plans.get(links)
        if plan is None:
            need: set = set()
            for link in links:
                while link != self.root and link not in need:
                    need.add(link)
                    link = self.edges[link].parent
            plan = plans[links] = [step for step in self._plan if step[0] in need]
        return plan

    def movers(self, link: str) -> tuple[int, ...]:
        """Indices (in the joint values) of the joints that move `link`, from the base outwards."""
        return self._movers[link]

    def reach_from_joint(self, link: str) -> dict[int, float]:
        """For each joint i moving `link`: an upper bound, valid in every configuration, of the
        distance from joint i's axis to the origin of `link` (mm): the lengths of the fixed offsets
        between them, end to end (the joints in between only turn them)."""
        out: dict[int, float] = {}
        acc = 0.0
        n = link
        while n != self.root:
            e = self.edges[n]
            if e.kind != "fixed" and e.index >= 0:
                out[e.index] = acc
            acc += float(np.linalg.norm(e.origin[:3, 3]))
            n = e.parent
        return out

    def adjacent_pairs(self, with_geometry: set[str]) -> set[tuple[str, str]]:
        """MoveIt's adjacent links: joined by one joint, or through links without geometry (those
        are removed and their neighbours joined). Pairs sorted by name, geometry links only."""
        graph: dict[str, set[str]] = {n: set() for n in self.links}
        for e in self.edges.values():
            graph[e.parent].add(e.child)
            graph[e.child].add(e.parent)
        for n in self.links:
            if n in with_geometry:
                continue
            nbrs = sorted(graph[n])
            for a in nbrs:
                for b in nbrs:
                    if a != b:
                        graph[a].add(b)
        out = set()
        for a in with_geometry:
            for b in graph.get(a, ()):
                if b in with_geometry and a != b:
                    out.add((min(a, b), max(a, b)))
        return out


def arm_links(model) -> ArmLinks:
    """The `ArmLinks` of a `RobotModel` (read from its URDF)."""
    info = read_urdf(model.source)
    solids = read_collision_solids(info.path)
    links = ArmLinks(info, solids, tuple(model.joint_names), model.world_frame)
    if getattr(model, "dh", None) is not None:  # a geometry setDH changed (11.4)
        from .dh_links import DHLinks

        return DHLinks(links, model)  # type: ignore[return-value]
    return links


def read_collision_solids(path: str | os.PathLike, resolve_meshes: bool = True) -> list[Solid]:
    """The `<collision>` elements of every link of a URDF, in mm. A mesh file is resolved beside the
    URDF (relative path or file://) and must stay inside the URDF's folder (`resolve_meshes=False`:
    its name is kept as written, for a reader that does not open meshes)."""
    import io

    from defusedxml import ElementTree as ET

    path = str(path)
    try:
        with open(path, "rb") as fh:
            data = fh.read()
        key = (path, data, resolve_meshes)
        kept = _SOLIDS.get(key)
        if kept is not None:
            return [Solid(k.link, k.name, k.kind, k.size, k.origin.copy(), k.mesh) for k in kept]
        root = ET.parse(io.BytesIO(data)).getroot()
    except (OSError, ET.ParseError) as exc:
        raise RobotError(f"{path}: cannot read the URDF: {exc}") from None
    out = _collision_solids(root, path, resolve_meshes)
    # a mesh's file is resolved on the disk: kept only without meshes (then path and bytes decide)
    if not resolve_meshes or not any(s.kind == "mesh" for s in out):
        if len(_SOLIDS) >= 8:
            _SOLIDS.pop(next(iter(_SOLIDS)))
        _SOLIDS[key] = tuple(Solid(k.link, k.name, k.kind, k.size, k.origin.copy(), k.mesh) for k in out)
    return out


_SOLIDS: dict = {}  # (path, bytes, resolve_meshes) -> the solids of a URDF without meshes (a run reads it thrice)


def _collision_solids(root, path: str, resolve_meshes: bool) -> list[Solid]:  # noqa: ANN001
    """`read_collision_solids` of the parsed URDF."""
    base = Path(path).resolve().parent
    out: list[Solid] = []
    for link in root.findall("link"):
        lname = link.get("name", "")
        for i, col in enumerate(link.findall("collision")):
            name = col.get("name") or f"{lname}#{i + 1}"
            o = col.find("origin")
            xyz = _floats(o.get("xyz") if o is not None else None, 3, (0.0, 0.0, 0.0), path, lname)
            rpy = _floats(o.get("rpy") if o is not None else None, 3, (0.0, 0.0, 0.0), path, lname)
            origin = _transform(xyz, rpy)
            g = col.find("geometry")
            shape = None if g is None or len(g) == 0 else g[0]
            if shape is None:
                raise RobotError(f"{path}: link {shown(lname)}: <collision> without <geometry>")
            tag = shape.tag
            where = f"{path}: link {shown(lname)}, collision {shown(name)}"
            if tag == "box":
                size = tuple(v * M_MM for v in _floats(shape.get("size"), 3, None, path, lname))
            elif tag == "cylinder":
                size = (_num(shape.get("radius"), where, "radius") * M_MM, _num(shape.get("length"), where, "length") * M_MM)
            elif tag == "sphere":
                size = (_num(shape.get("radius"), where, "radius") * M_MM,)
            elif tag == "mesh":
                size = tuple(v * M_MM for v in _floats(shape.get("scale"), 3, (1.0, 1.0, 1.0), path, lname))
                mesh = _mesh_path(shape.get("filename", ""), base, where) if resolve_meshes else shape.get("filename", "")
                out.append(Solid(lname, name, "mesh", size, origin, mesh))
                continue
            else:
                raise RobotError(f"{where}: <{tag}> is not a URDF collision geometry (box, cylinder, sphere, mesh)")
            if any(not (s > 0.0 and math.isfinite(s)) for s in size):
                raise RobotError(f"{where}: <{tag}> needs positive sizes")
            out.append(Solid(lname, name, tag, size, origin))
    return out


def _mesh_path(filename: str, base: Path, where: str) -> str:
    """A collision mesh's file: relative to the URDF (or file://), or package://NAME/... found in a
    folder NAME above the URDF (as ROS resolves it from a package's share folder); it must stay
    inside that folder."""
    if filename.startswith("file://"):
        filename = filename[len("file://"):]
    root = base
    if filename.startswith("package://"):
        pkg, _, rest = filename[len("package://"):].partition("/")
        for folder in (base, *base.parents):
            if folder.name == pkg:
                root, filename = folder, rest
                break
        else:
            raise RobotError(f"{where}: mesh {shown(filename)}: no folder {shown(pkg)} above the URDF to resolve package:// in")
    if not filename or "://" in filename:
        raise RobotError(f"{where}: mesh {shown(filename)}: give a path relative to the URDF")
    p = (root / filename).resolve()
    if root not in p.parents:
        raise RobotError(f"{where}: mesh {shown(filename)} is outside the URDF's folder")
    return str(p)


def _num(text, where: str, what: str) -> float:
    try:
        return float(text)
    except (TypeError, ValueError):
        raise RobotError(f"{where}: {what}={shown(text)} is not a number") from None


def _floats(text, n, default, path, link) -> tuple[float, ...]:
    if text is None:
        if default is None:
            raise RobotError(f"{path}: link {shown(link)}: a collision size is missing")
        return default
    try:
        vals = tuple(float(t) for t in text.split())
    except ValueError:
        raise RobotError(f"{path}: link {shown(link)}: {shown(text)} is not {n} numbers") from None
    if len(vals) != n or not all(math.isfinite(v) for v in vals):
        raise RobotError(f"{path}: link {shown(link)}: {shown(text)} is not {n} numbers")
    return vals


def _transform(xyz, rpy) -> np.ndarray:
    """URDF origin (metres, rpy: R = Rz(y)·Ry(p)·Rx(r)) -> 4x4 in mm."""
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    T = np.eye(4)
    T[:3, :3] = (
        (cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
        (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
        (-sp, cp * sr, cp * cr),
    )
    T[:3, 3] = [v * M_MM for v in xyz]
    return T


def _motions_one(axes: np.ndarray, prismatic: np.ndarray, values: np.ndarray) -> np.ndarray:
    """The motions of several joints (one value each) at once: (J, 4, 4), a turn of the value in
    degrees about the joint's axis (Rodrigues), or a slide of the value in mm along it."""
    n = len(values)
    a = np.where(prismatic, 0.0, np.radians(values))
    c, s = np.cos(a), np.sin(a)
    x, y, z = axes[:, 0], axes[:, 1], axes[:, 2]
    T = np.zeros((n, 4, 4))
    _rodrigues(T, c, s, x, y, z)
    T[:, :3, 3] = np.where(prismatic, values, 0.0)[:, None] * axes
    T[:, 3, 3] = 1.0
    return T


def _times(P: np.ndarray, origin: np.ndarray) -> np.ndarray:
    """P @ origin for poses P (N, 4, 4) and one 4x4: the rows of all poses times origin, a block of
    rows at a time (small enough that BLAS keeps to one thread: no threads spinning on a busy
    machine)."""
    rows = np.ascontiguousarray(P).reshape(-1, 4)
    out = np.empty_like(rows)
    for a in range(0, len(rows), ROWS):
        np.matmul(rows[a:a + ROWS], origin, out=out[a:a + ROWS])
    return out.reshape(P.shape)


def _motions_many(axes: np.ndarray, prismatic: np.ndarray, values: np.ndarray) -> np.ndarray:
    """The motions of J joints at N positions (values (N, J)): (J, N, 4, 4), as `_motions_one`
    for each row (joint by joint: each product reads one contiguous block)."""
    n, j = values.shape
    T = np.zeros((j, n, 4, 4))
    T[:, :, 3, 3] = 1.0
    a = np.radians(values.T)
    c, s = np.cos(a), np.sin(a)
    for k in range(j):
        if prismatic[k]:
            T[k, :, 0, 0] = T[k, :, 1, 1] = T[k, :, 2, 2] = 1.0
            T[k, :, :3, 3] = values[:, k, None] * axes[k][None, :]
        else:
            x, y, z = axes[k]
            _rodrigues(T[k], c[k], s[k], x, y, z)
    return T


def _rodrigues(T: np.ndarray, c, s, x, y, z) -> None:  # noqa: ANN001
    """Fill the rotation blocks of T (N, 4, 4): turns of cosines c, sines s about the unit axis
    (x, y, z) (arrays or scalars), Rodrigues' formula."""
    C = 1.0 - c
    T[:, 0, 0] = c + x * x * C
    T[:, 0, 1] = x * y * C - z * s
    T[:, 0, 2] = x * z * C + y * s
    T[:, 1, 0] = y * x * C + z * s
    T[:, 1, 1] = c + y * y * C
    T[:, 1, 2] = y * z * C - x * s
    T[:, 2, 0] = z * x * C - y * s
    T[:, 2, 1] = z * y * C + x * s
    T[:, 2, 2] = c + z * z * C
