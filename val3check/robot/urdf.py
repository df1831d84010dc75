"""A small URDF reader: the serial chain between two links, joint limits, and val3check's metadata.

Pure Python (no numpy, no pinocchio): `val3check robots` lists the models with it, and the fast
kinematics is built from what it reads. Pinocchio reads the same file for its own model
(`models.RobotModel.pinocchio()`); the test suite checks that both give the same kinematics.

The metadata val3check needs in a URDF (robots/README.md, "Your own URDF"):

    <val3check arm="MyTX2-60" world_frame="base" flange_frame="tool0">
      <joint name="joint_1" acceleration_deg_s2="1740"/>   <!-- optional, one per joint -->
      <joint name="joint_3" acceleration_mm_s2="4000"/>    <!-- a prismatic joint (SCARA axis 3) -->
      <fact .../> <assumption .../> <alternative .../> <missing .../>   <!-- optional: provenance.py -->
    </val3check>

`world_frame` and `flange_frame` are required: they name the links that are the VAL 3 `world`
frame (six-axis: on axis 1 at the height of axis 2, X forward, Z up) and `flange` frame (Z out of
the flange). Joint limits and nominal speeds are the URDF's own `<limit lower upper velocity>`
(radians and rad/s, metres and m/s for a prismatic joint).
"""

from __future__ import annotations

import math
from pathlib import Path

from ..excerpt import shown
from ..light_dataclass import dataclass, field
from .errors import RobotError

Mat = tuple[tuple[float, float, float, float], tuple[float, float, float, float], tuple[float, float, float, float]]


@dataclass(frozen=True)
class UrdfJoint:
    name: str
    kind: str
    parent: str
    child: str
    xyz: tuple[float, float, float]
    rpy: tuple[float, float, float]
    axis: tuple[float, float, float]
    lower: float | None  # radians
    upper: float | None
    velocity: float | None  # rad/s
    effort: float | None


@dataclass
class UrdfInfo:
    path: str
    robot_name: str
    joints: dict[str, UrdfJoint]
    links: set[str]
    meta: dict[str, str] | None  # attributes of <val3check>, None when absent
    meta_joints: dict[str, dict[str, str]] = field(default_factory=dict)
    # the other children of <val3check>, in order: ("fact" | "assumption" | "alternative" |
    # "missing", attributes); see models.Provenance
    meta_items: list[tuple[str, dict[str, str]]] = field(default_factory=list)

    def chain(self, root: str, tip: str) -> list[UrdfJoint]:
        """Joints from `root` down to `tip` (both links), in order; empty when root == tip."""
        by_child = {j.child: j for j in self.joints.values()}
        out: list[UrdfJoint] = []
        link = tip
        while link != root:
            j = by_child.get(link)
            if j is None or len(out) > len(self.joints):  # a cycle (read_urdf refuses them)
                return None  # type: ignore[return-value]
            out.append(j)
            link = j.parent
        out.reverse()
        return out

    def root_link(self) -> str:
        children = {j.child for j in self.joints.values()}
        roots = [n for n in self.links if n not in children]
        return roots[0] if len(roots) == 1 else ""


def _floats(text: str | None, n: int, default: tuple, what: str, path: str) -> tuple:
    if text is None:
        return default
    try:
        vals = tuple(float(t) for t in text.split())
    except ValueError:
        raise RobotError(f"{path}: {what} is not {n} numbers: {shown(text)}") from None
    if len(vals) != n or not all(math.isfinite(v) for v in vals):
        raise RobotError(f"{path}: {what} is not {n} finite numbers: {shown(text[:80])}")
    return vals


def _opt(el, attr: str) -> float | None:
    if el is None or el.get(attr) is None:
        return None
    v = float(el.get(attr))
    if not math.isfinite(v):
        raise ValueError(f"{attr}={shown(el.get(attr)[:40])} is not a finite number")
    return v


MAX_URDF_SIZE = 32 * 1024 * 1024  # bytes: arm URDFs are a few KB (meshes are separate files)


def parse_xml_file(path: str, roots=None, what: str = "file"):  # noqa: ANN001
    """The root element of a robot XML file (URDF, arm.cfx), read through val3check.confine
    (regular file, size checked first, inside `roots` when given) and parsed with defusedxml
    (no entity, no DTD is ever followed); RobotError for anything else."""
    return _parse_xml(path, _xml_bytes(path, roots), what)


def _xml_bytes(path: str, roots=None) -> bytes:  # noqa: ANN001
    """`parse_xml_file`'s read: its checks, then the file's bytes."""
    from ..confine import Refused, Roots, read_bytes

    try:
        return read_bytes(path, roots or Roots.user_given(), MAX_URDF_SIZE)
    except Refused as exc:
        raise RobotError(f"{path}: {'no such file' if exc.reason == 'file not found' else exc.reason}") from None


def _parse_xml(path: str, data: bytes, what: str):  # noqa: ANN202
    """`parse_xml_file`'s parse of the bytes read."""
    from defusedxml import DefusedXmlException
    from defusedxml import ElementTree as ET

    try:
        return ET.fromstring(data, forbid_dtd=True)
    except DefusedXmlException:
        raise RobotError(f"{path}: the {what} declares a DTD or entities, which are never followed: not read") from None
    except ET.ParseError as exc:
        raise RobotError(f"{path}: not well-formed XML: {exc}") from None
    except (RecursionError, MemoryError, ValueError) as exc:
        raise RobotError(f"{path}: cannot be parsed: {type(exc).__name__}") from None


MAX_OFFSET_M = 1e4  # a joint origin beyond 10 km is no arm: the transforms would overflow


def _check_tree(path: str, joints: dict[str, UrdfJoint]) -> None:
    """URDF joints form a tree: each link is the child of one joint at most, and following the
    parents from any link ends (a cycle would make every walk down the chain endless). Axes are
    not zero, limits are in order, origins are within MAX_OFFSET_M."""
    by_child: dict[str, UrdfJoint] = {}
    for j in joints.values():
        if j.kind != "fixed" and math.sqrt(sum(a * a for a in j.axis)) < 1e-12:
            raise RobotError(f"{path}: joint {shown(j.name)} has the axis 0 0 0: an axis needs a direction")
        if j.lower is not None and j.upper is not None and j.lower > j.upper:
            raise RobotError(f"{path}: joint {shown(j.name)}: lower limit {j.lower:g} above upper limit {j.upper:g}")
        if any(abs(v) > MAX_OFFSET_M for v in j.xyz):
            raise RobotError(f"{path}: joint {shown(j.name)}: origin xyz beyond {MAX_OFFSET_M:g} m")
        if j.parent == j.child:
            raise RobotError(f"{path}: joint {shown(j.name)} connects link {shown(j.child)} to itself")
        if j.child in by_child:
            raise RobotError(f"{path}: link {shown(j.child)} is the child of two joints ({shown(by_child[j.child].name)}, {shown(j.name)})")
        by_child[j.child] = j
    done: set[str] = set()
    for start in by_child:
        seen: list[str] = []
        link = start
        while link in by_child and link not in done:
            if link in seen:
                names = " -> ".join(seen[seen.index(link):] + [link])
                raise RobotError(f"{path}: the joints form a cycle through the links {names}: a URDF is a tree")
            seen.append(link)
            link = by_child[link].parent
        done.update(seen)


_READ: dict = {}  # (path, the file's bytes) -> UrdfInfo: a run reads its arm's URDF four times
READ_KEPT = 8


def read_urdf(path: str | Path) -> UrdfInfo:
    """The URDF at `path` (its checks and its read every time; parsed again only when its path or
    its bytes are new to this process). Each call gets its own containers."""
    path = str(path)
    data = _xml_bytes(path)
    info = _READ.get((path, data))
    if info is None:
        info = _read_urdf(path, data)
        if len(_READ) >= READ_KEPT:
            _READ.pop(next(iter(_READ)))
        _READ[(path, data)] = info
    return UrdfInfo(info.path, info.robot_name, dict(info.joints), set(info.links),
                    None if info.meta is None else dict(info.meta), {k: dict(v) for k, v in info.meta_joints.items()},
                    [(tag, dict(a)) for tag, a in info.meta_items])


def _read_urdf(path: str, data: bytes) -> UrdfInfo:
    root = _parse_xml(path, data, "URDF")
    if root.tag != "robot":
        raise RobotError(f"{path}: not a URDF (the root element is <{root.tag}>, not <robot>)")
    links = {el.get("name") for el in root.findall("link")}
    joints: dict[str, UrdfJoint] = {}
    for el in root.findall("joint"):
        name = el.get("name", "")
        origin = el.find("origin")
        axis = el.find("axis")
        limit = el.find("limit")
        parent, child = el.find("parent"), el.find("child")
        if parent is None or child is None:
            raise RobotError(f"{path}: joint {shown(name)} lacks <parent> or <child>")
        try:
            joints[name] = UrdfJoint(
                name=name,
                kind=el.get("type", ""),
                parent=parent.get("link", ""),
                child=child.get("link", ""),
                xyz=_floats(origin.get("xyz") if origin is not None else None, 3, (0.0, 0.0, 0.0), f"joint {shown(name)} origin xyz", path),
                rpy=_floats(origin.get("rpy") if origin is not None else None, 3, (0.0, 0.0, 0.0), f"joint {shown(name)} origin rpy", path),
                axis=_floats(axis.get("xyz") if axis is not None else None, 3, (1.0, 0.0, 0.0), f"joint {shown(name)} axis", path),
                lower=_opt(limit, "lower"),
                upper=_opt(limit, "upper"),
                velocity=_opt(limit, "velocity"),
                effort=_opt(limit, "effort"),
            )
        except ValueError as exc:
            raise RobotError(f"{path}: joint {shown(name)}: bad <limit>: {exc}") from None
    _check_tree(path, joints)
    meta_el = root.find("val3check")
    meta = dict(meta_el.attrib) if meta_el is not None else None
    meta_joints = {}
    meta_items = []
    if meta_el is not None:
        for child in meta_el:
            if child.tag == "joint":
                meta_joints[child.get("name", "")] = dict(child.attrib)
            elif isinstance(child.tag, str):
                meta_items.append((child.tag, dict(child.attrib)))
    return UrdfInfo(path=path, robot_name=root.get("name", ""), joints=joints, links=links, meta=meta, meta_joints=meta_joints,
                    meta_items=meta_items)


# ---- small rigid-transform helpers (3x4 row-major tuples, metres) -------------------------------


def rpy_matrix(r: float, p: float, y: float) -> tuple:
    """URDF rpy: R = Rz(y)·Ry(p)·Rx(r)."""
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return (
        (cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
        (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
        (-sp, cp * sr, cp * cr),
    )


def transform(xyz, rpy) -> Mat:
    R = rpy_matrix(*rpy)
    return tuple((R[i][0], R[i][1], R[i][2], float(xyz[i])) for i in range(3))  # type: ignore[return-value]


IDENTITY: Mat = ((1.0, 0.0, 0.0, 0.0), (0.0, 1.0, 0.0, 0.0), (0.0, 0.0, 1.0, 0.0))


def mul(A: Mat, B: Mat) -> Mat:
    return tuple(
        (
            A[i][0] * B[0][0] + A[i][1] * B[1][0] + A[i][2] * B[2][0],
            A[i][0] * B[0][1] + A[i][1] * B[1][1] + A[i][2] * B[2][1],
            A[i][0] * B[0][2] + A[i][1] * B[1][2] + A[i][2] * B[2][2],
            A[i][0] * B[0][3] + A[i][1] * B[1][3] + A[i][2] * B[2][3] + A[i][3],
        )
        for i in range(3)
    )  # type: ignore[return-value]


def inverse(A: Mat) -> Mat:
    R = [[A[j][i] for j in range(3)] for i in range(3)]  # transpose
    t = [-(R[i][0] * A[0][3] + R[i][1] * A[1][3] + R[i][2] * A[2][3]) for i in range(3)]
    return tuple((R[i][0], R[i][1], R[i][2], t[i]) for i in range(3))  # type: ignore[return-value]


def axis_angle(axis, angle: float) -> Mat:
    x, y, z = axis
    n = math.sqrt(x * x + y * y + z * z)
    x, y, z = x / n, y / n, z / n
    c, s = math.cos(angle), math.sin(angle)
    C = 1.0 - c
    return (
        (c + x * x * C, x * y * C - z * s, x * z * C + y * s, 0.0),
        (y * x * C + z * s, c + y * y * C, y * z * C - x * s, 0.0),
        (z * x * C - y * s, z * y * C + x * s, c + z * z * C, 0.0),
    )
