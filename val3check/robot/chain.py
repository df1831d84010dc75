"""The arm's kinematic chain as plain data, for the HTML report's 3D view (docs/html-report.md,
`scene.arm`): the run publishes it in its record of the scene (simulation/arm_record.py).

    arm = arm_chain("robots/tx2-60.urdf")          # a plain JSON-able dict
    poses = chain_fk(arm, [0, -30, 90, 0, 45, 0])  # {link: 3x4 pose in the world frame, mm}

The page computes forward kinematics itself from the joint samples (shipping every link's pose
at every sample would be far too big), so the chain carries what that needs: every joint of the
URDF tree in parent-before-child order with its fixed origin, axis, type and the index of its
value in the trajectory, the link solids (cylinders, boxes, spheres) and where the root sits in
the VAL 3 world frame. Lengths are millimetres; joint values are degrees (revolute) or
millimetres (prismatic), as in the trajectory. `chain_fk` is the same computation in Python (the
tests hold the page to it, and it to the arm model).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Sequence

from ..lengths import M_MM
from .errors import RobotError
from .urdf import IDENTITY, Mat, axis_angle, inverse, mul, read_urdf, transform

MOVING = ("revolute", "continuous", "prismatic")


def _r(x: float) -> float:
    """Round away float noise (1e-9 mm is far below anything drawn) and negative zeros."""
    return round(x, 9) + 0.0


def _mm(M: Mat) -> list[list[float]]:
    """A 3x4 transform (metres) as rows in millimetres."""
    return [[_r(M[i][0]), _r(M[i][1]), _r(M[i][2]), _r(M[i][3] * M_MM)] for i in range(3)]


def arm_chain(urdf: str | Path, world_frame: str | None = None, flange_frame: str | None = None,
              joint_names: Sequence[str] | None = None, name: str | None = None,
              source: str | None = None) -> dict:
    """The `scene.arm` of the report model, read from a URDF.

    `world_frame`/`flange_frame` default to the URDF's `<val3check>` element (robots/README.md);
    without it, the root link is the world and the flange is the end of the chain when the tree
    has a single leaf. `joint_names` is the order of the trajectory's joints (default: the moving
    joints from the root to the flange). `source` is the path written in the model (default: the
    path given). Raises RobotError with a message for the user."""
    info = read_urdf(urdf)
    path = info.path
    root = info.root_link()
    if not root:
        raise RobotError(f"{path}: the links do not form one tree with a single root")
    meta = info.meta or {}
    world = world_frame or meta.get("world_frame") or root
    flange = flange_frame or meta.get("flange_frame")
    if not flange:
        parents = {j.parent for j in info.joints.values()}
        leaves = sorted(n for n in info.links if n not in parents)
        if len(leaves) != 1:
            raise RobotError(f"{path}: name the flange link (flange_frame): the tree has {len(leaves)} ends")
        flange = leaves[0]
    for what, link in (("world frame", world), ("flange frame", flange)):
        if link not in info.links:
            raise RobotError(f"{path}: the {what} {link!r} is not a link of the URDF")
    to_world = info.chain(root, world)
    if to_world is None or any(j.kind != "fixed" for j in to_world):
        raise RobotError(f"{path}: the world frame {world!r} must be fixed to the root link {root!r}")
    W = IDENTITY
    for j in to_world:
        W = mul(W, transform(j.xyz, j.rpy))
    to_flange = info.chain(root, flange) or []
    if joint_names is None:
        joint_names = [j.name for j in to_flange if j.kind in MOVING]
    index = {n: i for i, n in enumerate(joint_names)}
    unknown = [n for n in joint_names if n not in info.joints]
    if unknown:
        raise RobotError(f"{path}: no joint named {unknown[0]!r}")

    # every joint, parents before children (breadth first from the root, in file order)
    by_parent: dict[str, list] = {}
    for j in info.joints.values():
        by_parent.setdefault(j.parent, []).append(j)
    ordered, todo = [], [root]
    while todo:
        link = todo.pop(0)
        for j in by_parent.get(link, []):
            ordered.append(j)
            todo.append(j.child)
    joints = []
    for j in ordered:
        kind = j.kind if j.kind in MOVING or j.kind == "fixed" else "fixed"
        n = math.sqrt(sum(a * a for a in j.axis)) or 1.0
        scale = M_MM if kind == "prismatic" else 180.0 / math.pi  # mm, degrees: the trajectory's units
        limited = kind in ("revolute", "prismatic") and j.lower is not None and j.upper is not None
        joints.append({
            "name": j.name,
            "type": kind,
            "parent": j.parent,
            "child": j.child,
            "origin": _mm(transform(j.xyz, j.rpy)),
            "axis": [_r(a / n) for a in j.axis],
            "index": index.get(j.name) if kind != "fixed" else None,
            "lower": _r(j.lower * scale) if limited else None,
            "upper": _r(j.upper * scale) if limited else None,
        })
    reached = {root} | {j["child"] for j in joints}
    from .links import read_collision_solids  # the collision checks' reader (numpy: sim path only)

    solids: dict[str, list] = {}
    for s in read_collision_solids(path, resolve_meshes=False):
        solids.setdefault(s.link, []).append(s)
    links, skipped = [], []
    for lname in [root] + [j["child"] for j in joints]:
        out = []
        for s in solids.get(lname, []):
            entry = {"name": s.name, "shape": s.kind, "pose": [[_r(float(s.origin[i][k])) for k in range(4)]
                                                                for i in range(3)]}
            if s.kind == "box":
                entry["size"] = [_r(v) for v in s.size]
            elif s.kind == "cylinder":
                entry["radius"], entry["length"] = _r(s.size[0]), _r(s.size[1])
            elif s.kind == "sphere":
                entry["radius"] = _r(s.size[0])
            else:
                skipped.append(f"{lname}/{s.name}")
                continue
            out.append(entry)
        links.append({"name": lname, "solids": out})
    notes = []
    if skipped:
        notes.append(f"mesh solids not shown: {', '.join(skipped)}")
    unplaced = sorted(n for n in info.links if n not in reached)
    if unplaced:
        notes.append(f"links not attached to the root: {', '.join(unplaced)}")
    return {
        "name": name or meta.get("arm") or info.robot_name,
        "source": source if source is not None else path,
        "root": root,
        "world_frame": world,
        "flange_frame": flange,
        "joint_names": list(joint_names),
        "root_in_world": [[_r(M[i][0]), _r(M[i][1]), _r(M[i][2]), _r(M[i][3] * M_MM)] for M in [inverse(W)] for i in range(3)],
        "joints": joints,
        "links": links,
        "notes": notes,
    }


def _joint_motion(joint: dict, value: float) -> Mat:
    """The motion of one joint of the chain at `value` (degrees, or mm for a prismatic joint)."""
    if joint["type"] == "prismatic":
        x, y, z = joint["axis"]
        return ((1.0, 0.0, 0.0, x * value), (0.0, 1.0, 0.0, y * value), (0.0, 0.0, 1.0, z * value))
    return axis_angle(joint["axis"], value * math.pi / 180.0)


def chain_fk(arm: dict, joints: Sequence[float]) -> dict[str, Mat]:
    """Every link's pose in the VAL 3 world frame (3x4, mm) for these joint values (degrees for
    revolute joints, mm for prismatic ones, in the order of `arm["joint_names"]`)."""
    poses: dict[str, Mat] = {arm["root"]: tuple(tuple(r) for r in arm["root_in_world"])}  # type: ignore[dict-item]
    for j in arm["joints"]:
        T = mul(poses[j["parent"]], tuple(tuple(r) for r in j["origin"]))  # type: ignore[arg-type]
        if j["type"] != "fixed" and j["index"] is not None:
            T = mul(T, _joint_motion(j, float(joints[j["index"]])))
        poses[j["child"]] = T
    return poses
