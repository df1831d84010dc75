"""The solids attached to the links of a URDF (`<collision>` or `<visual>` geometry).

    solids = read_link_solids("robots/tx2-60.urdf")          # {link name: [Solid, ...]}

Read with defusedxml, like `urdf.read_urdf` (no entity is ever followed). Units are the URDF's:
metres and radians. A `<mesh>` is returned with its file name and scale, unread: resolving
`package://` names is the caller's business.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from .errors import RobotError
from .urdf import Mat, transform

SHAPES = ("box", "cylinder", "sphere", "mesh")


@dataclass(frozen=True)
class Solid:
    link: str
    name: str  # the element's name attribute, or "<link>#<n>" when it has none
    shape: str  # box | cylinder | sphere | mesh
    origin: Mat  # pose in the link frame (metres)
    # box: (x, y, z) sides; cylinder: (radius, length) along the local Z; sphere: (radius,);
    # mesh: (sx, sy, sz) scale
    size: tuple[float, ...]
    mesh: str | None = None  # a mesh's filename attribute


def _numbers(text: str | None, n: int, what: str, path: str) -> tuple[float, ...]:
    try:
        vals = tuple(float(t) for t in (text or "").split())
    except ValueError:
        vals = ()
    if len(vals) != n:
        raise RobotError(f"{path}: {what} is not {n} numbers: {text!r}")
    return vals


def read_link_solids(path: str | Path, kind: str = "collision") -> dict[str, list[Solid]]:
    """Every link's `<collision>` (or `<visual>`, kind="visual") solids, in file order."""
    from .urdf import parse_xml_file  # val3check.confine: a regular file, its size checked, no entity

    if kind not in ("collision", "visual"):
        raise ValueError(f"kind is 'collision' or 'visual', not {kind!r}")
    path = str(path)
    root = parse_xml_file(path, what="URDF")
    if root.tag != "robot":
        raise RobotError(f"{path}: not a URDF (the root element is <{root.tag}>, not <robot>)")
    out: dict[str, list[Solid]] = {}
    for link in root.findall("link"):
        lname = link.get("name", "")
        solids: list[Solid] = []
        for n, el in enumerate(link.findall(kind)):
            name = el.get("name") or f"{lname}#{n}"
            origin = el.find("origin")
            xyz = _numbers(origin.get("xyz", "0 0 0"), 3, f"{name} origin xyz", path) if origin is not None else (0.0,) * 3
            rpy = _numbers(origin.get("rpy", "0 0 0"), 3, f"{name} origin rpy", path) if origin is not None else (0.0,) * 3
            geometry = el.find("geometry")
            shape_el = next(iter(geometry), None) if geometry is not None else None
            if shape_el is None or shape_el.tag not in SHAPES:
                what = "nothing" if shape_el is None else f"<{shape_el.tag}>"
                raise RobotError(f"{path}: link {lname!r}: {kind} {name!r} has {what} in <geometry> "
                                 "(box, cylinder, sphere or mesh expected)")
            mesh = None
            if shape_el.tag == "box":
                size = _numbers(shape_el.get("size"), 3, f"{name} box size", path)
            elif shape_el.tag == "cylinder":
                size = (_numbers(shape_el.get("radius"), 1, f"{name} cylinder radius", path)[0],
                        _numbers(shape_el.get("length"), 1, f"{name} cylinder length", path)[0])
            elif shape_el.tag == "sphere":
                size = _numbers(shape_el.get("radius"), 1, f"{name} sphere radius", path)
            else:
                size = _numbers(shape_el.get("scale", "1 1 1"), 3, f"{name} mesh scale", path)
                mesh = shape_el.get("filename", "")
            if any(not v >= 0 for v in size):
                raise RobotError(f"{path}: link {lname!r}: {kind} {name!r} has a negative size")
            solids.append(Solid(lname, name, shape_el.tag, transform(xyz, rpy), size, mesh))
        out[lname] = solids
    return out
