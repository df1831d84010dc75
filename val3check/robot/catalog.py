"""The arm models shipped in `robots/` (their index `robots/catalog.toml`) and how names map to them.

robots/catalog.toml is generated with the URDFs (robots/generate.py). It is plain data: the VAL 3
type family of an arm id (Rx/Rs), the ids controllers write in arm.cfx, the arms that exist but
have no public kinematic data. Code that must not import this package (`val3check lint`) can read
it with tomllib (`catalog_path()`).
"""

from __future__ import annotations

import functools
import os
import re
from pathlib import Path

from ..excerpt import shown
from ..resources import resource_dir
from .errors import RobotError


def robots_dir() -> Path:
    return resource_dir("robots")


def catalog_path() -> Path:
    return robots_dir() / "catalog.toml"


def normalize(name: str) -> str:
    """'tx2-60', 'TX2_60', 'tx260', 'Stäubli TX2-60' -> 'TX260'."""
    n = name.strip().upper()
    for prefix in ("STÄUBLI", "STAUBLI", "STAEUBLI"):
        if n.startswith(prefix):
            n = n[len(prefix):]
    return re.sub(r"[\s_\-.]+", "", n)


_SUFFIX_CHARS = "-abcdefghijklmnopqrstuvwxyz0123456789"
_GENERATION = re.compile(r"-s\d")


def normalize_id(arm_id: str) -> str:
    """An arm.cfx value as compared: lower case, '_' as '-', without the '-S<n>' suffix (the arm's
    generation: tx200-S3, ts2_60-S1 -> tx200, ts2-60)."""
    n = arm_id.strip().lower().replace("_", "-")
    # As `^(.+?)-s\d+[-a-z0-9]*$` would take it, in linear time (that regex is quadratic on
    # "-s1-s1...-s1."): the suffix starts at the first "-s<digit>" of the trailing run of
    # [-a-z0-9] characters, after the first character.
    tail = len(n.rstrip(_SUFFIX_CHARS))
    m = _GENERATION.search(n, max(1, tail))
    return n[:m.start()] if m else n


@functools.lru_cache(maxsize=1)
def _data() -> dict:
    import tomllib

    path = catalog_path()
    try:
        with open(path, "rb") as fh:
            return tomllib.load(fh)
    except (OSError, tomllib.TOMLDecodeError) as exc:
        raise RobotError(f"{path}: the arm catalogue cannot be read ({exc}): run python robots/generate.py") from None


@functools.lru_cache(maxsize=1)
def catalog() -> dict[str, dict]:
    """Arm name -> {"path", "srs_arm_id", "kind", "family", "series", "ids", "confirmed", "stroke_mm"},
    in the order of `val3check robots` (grouped by series)."""
    folder = robots_dir()
    out: dict[str, dict] = {}
    for arm in _data().get("arm", []):
        entry = dict(arm)
        entry["path"] = str(folder / arm["file"])
        entry["srs_arm_id"] = arm["ids"][0] if arm.get("ids") and arm.get("confirmed") else ""
        entry.setdefault("stroke_mm", None)
        out[arm["name"]] = entry
    return out


def known_without_model() -> list[dict]:
    """Stäubli arms whose id is known but that have no public kinematic data: {id, arm, closest, why}."""
    return list(_data().get("known", []))


def family_of_id(arm_id: str) -> str | None:
    """The VAL 3 type family of an arm id by its prefix: "Rx" (tx, rx), "Rs" (ts, rs, tp), or None."""
    n = normalize_id(arm_id)
    for family, prefixes in _data().get("families", {}).items():
        if any(n.startswith(p) for p in prefixes):
            return family
    return None


def names() -> list[str]:
    return list(catalog())


def find(name: str) -> str:
    """The catalogue name for a user's spelling, or RobotError listing the known arms."""
    key = normalize(name)
    for known in catalog():
        if normalize(known) == key:
            return known
    raise RobotError(f"unknown robot {shown(name)}; known arms: {', '.join(names())} (or a path to a URDF)")


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
