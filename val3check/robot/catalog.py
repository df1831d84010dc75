"""The Stäubli arm models shipped in `robots/` and how names, SRS arm ids and arm.cfx map to them."""

from __future__ import annotations

import functools
import os
import re
from pathlib import Path

from ..resources import resource_dir
from .errors import RobotError


def robots_dir() -> Path:
    return resource_dir("robots")


def normalize(name: str) -> str:
    """'tx2-60', 'TX2_60', 'tx260', 'Stäubli TX2-60' -> 'TX260'."""
    n = name.strip().upper()
    for prefix in ("STÄUBLI", "STAUBLI", "STAEUBLI"):
        if n.startswith(prefix):
            n = n[len(prefix):]
    return re.sub(r"[\s_\-.]+", "", n)


@functools.lru_cache(maxsize=1)
def catalog() -> dict[str, dict]:
    """Arm name -> {"path": URDF path, "srs_arm_id": ...}, in the order of `val3check robots`."""
    from .urdf import read_urdf

    out: dict[str, dict] = {}
    folder = robots_dir()
    for path in sorted(folder.glob("*.urdf")):
        info = read_urdf(path)
        if not info.meta or "arm" not in info.meta:
            continue
        out[info.meta["arm"]] = {"path": str(path), "srs_arm_id": info.meta.get("srs_arm_id", "")}
    order = ("TX60", "TX60L", "TX90", "TX90L", "TX90XL", "TX2-60", "TX2-60L", "TX2-90", "TX2-90L", "TX2-90XL", "RX160", "RX160L")
    rank = {n: i for i, n in enumerate(order)}
    return dict(sorted(out.items(), key=lambda kv: (rank.get(kv[0], len(order)), kv[0])))


def names() -> list[str]:
    return list(catalog())


def find(name: str) -> str:
    """The catalogue name for a user's spelling, or RobotError listing the known arms."""
    key = normalize(name)
    for known in catalog():
        if normalize(known) == key:
            return known
    raise RobotError(f"unknown robot {name!r}; known arms: {', '.join(names())} (or a path to a URDF)")


def find_srs(arm_id: str) -> str:
    """The catalogue name for an arm.cfx value such as 'tx2-60-S1' (match on the prefix before -S)."""
    m = re.match(r"^(.*?)-S\d*[A-Z]?$", arm_id.strip(), re.IGNORECASE)
    prefix = (m.group(1) if m else arm_id.strip()).lower()
    for known, entry in catalog().items():
        if entry["srs_arm_id"].lower() == prefix:
            return known
    ids = ", ".join(e["srs_arm_id"] for e in catalog().values())
    if re.match(r"^(ts|rs)\d", prefix):
        raise RobotError(f"arm {arm_id!r} (from arm.cfx) is a SCARA (RS/TS, manual 9.7.5): not modelled; six-axis arms: {ids}")
    raise RobotError(f"arm {arm_id!r} (from arm.cfx) is not a known arm; known ids: {ids} (use --robot NAME or a URDF)")


def read_arm_cfx(path: str | os.PathLike) -> str:
    """The arm id written in a controller's usr/configs/arm.cfx (<String name="arm" value="tx60-S1"/>)."""
    from .urdf import parse_xml_file

    try:
        root = parse_xml_file(str(path), what="arm configuration")
    except RobotError as exc:
        raise RobotError(f"cannot read the arm configuration: {exc}") from None
    for el in root.iter():
        if el.get("name") == "arm" and el.get("value"):
            return el.get("value")
    raise RobotError(f'{path}: no <String name="arm" value="..."/> in the arm configuration')


def find_arm_cfx(app_path: str | os.PathLike) -> Path | None:
    """usr/configs/arm.cfx of the controller tree that holds app_path (searching upwards).

    Only a controller tree counts (val3check.confine: nothing is read because of where a file
    happens to sit): `<ctrl>/usr/configs/arm.cfx` when app_path is in `<ctrl>/usr/usrapp`."""
    p = Path(app_path).resolve()
    if p.is_file():
        p = p.parent
    for folder in (p, *p.parents):
        if folder.name.lower() == "usrapp" and folder.parent.name.lower() == "usr":
            cand = folder.parent / "configs" / "arm.cfx"
            return cand if cand.is_file() else None
    return None


def example_robot_urdf(relative: str) -> Path | None:
    """A URDF of the optional example-robot-data package (`pip install 'val3check[robots]'`), e.g.
    'ur_description/urdf/ur5_robot.urdf'; None when the package is not installed."""
    from importlib import metadata

    try:
        dist = metadata.distribution("example-robot-data")
    except metadata.PackageNotFoundError:
        return None
    for f in dist.files or ():
        if str(f).replace("\\", "/").endswith("robots/" + relative):
            path = Path(dist.locate_file(f))
            return path if path.is_file() else None
    return None
