"""Which catalogue model is the arm of a controller: usr/configs/arm.cfx, arm ids, strokes, mounts.

A controller tree names its arm in usr/configs/arm.cfx (shared/formats/srs-project-files.md):

    <String name="arm" value="ts2_60-S1" />      the arm id: tx200-S3, ts60-S1, tx2-60-S1...
    <String name="mount" value="wall" />         floor, wall or ceiling ("mounting" in some files)
    <String name="lengthAxis3" value="L200" />   a SCARA's axis 3 stroke, in millimetres

The id is compared lower-case, with '_' and '-' alike, without its '-S<n>' suffix, with the ids
of robots/catalog.toml (as seen in real trees, or inferred: matched all the same, and said so)
and with the catalogue names. A SCARA's stroke picks the model of that stroke; a stroke no model
has gives the model of another stroke with axis 3's range set from arm.cfx (an assumption the
model states: variants.with_stroke). The mount places the world frame in the cell
(variants.with_mount, models.RobotModel.world_in_cell). An id of an arm that has no model is an
error that names the closest model. The model itself is built by load.from_arm_cfx.
"""

from __future__ import annotations

import math
import os
import re

from ..excerpt import shown
from ..light_dataclass import dataclass
from . import catalog as _catalog
from .errors import RobotError

_STROKE = re.compile(r"\d+(?:\.\d+)?")


@dataclass(frozen=True)
class ArmConfig:
    """What a controller's usr/configs/arm.cfx says about its arm."""

    path: str
    arm: str  # as written: "ts2_60-S1"
    mount: str | None = None  # as written
    length_axis3: str | None = None  # as written: "L200"

    @property
    def stroke_mm(self) -> float | None:
        if not self.length_axis3:
            return None
        # "L200", "200 mm", " l 200.5 ": without a regex of adjacent optional blanks (quadratic)
        t = self.length_axis3.strip()
        if t[:1] in ("L", "l"):
            t = t[1:].lstrip()
        if t[-2:].lower() == "mm":
            t = t[:-2].rstrip()
        return float(t) if _STROKE.fullmatch(t) else None


@dataclass(frozen=True)
class Match:
    name: str  # the catalogue model
    stroke_mm: float | None = None  # a stroke the model does not have: apply it (with_stroke)
    notes: tuple[str, ...] = ()


def read_arm_config(path: str | os.PathLike) -> ArmConfig:
    """The arm, mount and axis 3 length of a usr/configs/arm.cfx."""
    from .urdf import parse_xml_file  # val3check.confine: a regular file, its size checked, no entity

    try:
        root = parse_xml_file(str(path), what="arm configuration")
    except RobotError as exc:
        raise RobotError(f"cannot read the arm configuration: {exc}") from None
    values: dict[str, str] = {}
    for el in root.iter():
        name, value = el.get("name"), el.get("value")
        if name in ("arm", "mount", "mounting", "lengthAxis3") and value is not None and name not in values:
            values[name] = value
    if not values.get("arm"):
        raise RobotError(f'{path}: no <String name="arm" value="..."/> in the arm configuration')
    return ArmConfig(str(path), values["arm"], values.get("mount", values.get("mounting")), values.get("lengthAxis3"))


def id_key(text: str) -> str:
    """An arm id or a model name as compared: lower case, without separators."""
    return re.sub(r"[-_\s.]+", "", text.lower())


def _parse(arm_id: str) -> tuple[str, str, float, str] | None:
    """'tx2-60l' -> ('tx', '2', 60, 'l'); 'tx200' -> ('tx', '', 200, ''); None when not of that form."""
    m = re.fullmatch(r"([a-z]+)(?:(\d)-)?(\d+)([a-z]*)", arm_id)
    if not m:
        return None
    return m.group(1), m.group(2) or "", float(m.group(3)), m.group(4)


def closest_model(arm_id: str) -> str | None:
    """The catalogue model nearest an arm id: same kind (by the id's prefix), then the same
    letters, the nearest size number (Stäubli names give the reach in centimetres), the same
    suffix (L, XL), the same generation (TX2 or TX)."""
    n = _catalog.normalize_id(arm_id)
    family = _catalog.family_of_id(n)
    p = _parse(n)
    if family is None or p is None:
        return None
    best, best_score = None, None
    for name, entry in _catalog.catalog().items():
        if entry["family"] != family:
            continue
        q = _parse(re.sub(r"-l\d+$", "", name.lower()))
        if q is None:
            continue
        score = (p[0] != q[0], abs(math.log(p[2] / q[2])) if p[2] and q[2] else 9.0, p[3] != q[3], p[1] != q[1])
        if best_score is None or score < best_score:
            best, best_score = name, score
    return best


def _describe_kind(arm_id: str) -> str:
    fam = _catalog.family_of_id(arm_id)
    if fam == "Rs":
        return "a SCARA (RS/TS arm, manual 9.7.5; VAL 3 types pointRs, jointRs, configRs)"
    if fam == "Rx":
        return "a six-axis arm (VAL 3 types pointRx, jointRx, configRx)"
    return "not a Stäubli arm id val3check knows"


def match_id(arm_id: str, stroke_mm: float | None = None) -> Match:
    """The catalogue model for an arm id (and a SCARA's stroke), or RobotError that says what the
    id is and names the closest model."""
    n = _catalog.normalize_id(arm_id)
    key = id_key(n)
    cands = []
    for name, entry in _catalog.catalog().items():
        ids = [id_key(_catalog.normalize_id(i)) for i in entry.get("ids", []) if i]
        if key in ids or key == id_key(name):
            cands.append((name, entry))
    if not cands:
        for known in _catalog.known_without_model():
            if id_key(_catalog.normalize_id(known["id"])) == key:
                raise RobotError(f"arm {shown(arm_id)} is the Stäubli {known['arm']}, which has no model: {known['why']}; the "
                                 f"closest model is {known['closest']} (use --robot {known['closest']}, or a URDF of your own)")
        closest = closest_model(n)
        hint = f"; the closest model is {closest} (use --robot {closest}, or a URDF of your own)" if closest else \
            " (use --robot NAME or a URDF)"
        ids = ", ".join(dict.fromkeys(e["ids"][0] for e in _catalog.catalog().values() if e.get("ids")))
        raise RobotError(f"arm {shown(arm_id)} is {_describe_kind(n)} that val3check has no model for{hint}; known ids: {ids}")
    notes = []
    name, entry = cands[0]
    if len(cands) > 1:  # several strokes of one SCARA
        if stroke_mm is not None:
            same = [c for c in cands if c[1].get("stroke_mm") == stroke_mm]
            if same:
                name, entry = same[0]
        else:
            notes.append(f"no lengthAxis3 in arm.cfx: the {entry.get('stroke_mm'):g} mm stroke of {name} is taken "
                         f"(the {', '.join(c[0] for c in cands[1:])} exists too)")
    if not entry.get("confirmed"):
        notes.append(f"arm id {arm_id!r} matched on {entry['ids'][0]!r}, an id inferred for the {name} (no real arm.cfx "
                     "seen with it)")
    other_stroke = None
    if entry["kind"] == "scara" and stroke_mm is not None and entry.get("stroke_mm") != stroke_mm:
        other_stroke = stroke_mm
    return Match(name, other_stroke, tuple(notes))
