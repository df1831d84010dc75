"""Which model is the arm of a controller: usr/configs/arm.cfx, arm ids, strokes, mounts.

A controller tree names its arm in usr/configs/arm.cfx (shared/formats/srs-project-files.md):

    <String name="arm" value="ts2_60-S1" />      the arm id: tx200-S3, ts60-S1, tx2-60-S1...
    <String name="mount" value="wall" />         floor, wall or ceiling ("mounting" in some files)
    <String name="lengthAxis3" value="L200" />   a SCARA's axis 3 stroke, in millimetres

The id is compared lower-case, with '_' and '-' alike, without its '-S<n>' suffix, with the ids
of robots/catalog.toml (as seen in real trees, or inferred: matched all the same, and said so)
and with the catalogue names. A SCARA's stroke picks the model of that stroke; a stroke no model
has gives the model of another stroke with axis 3's range set from arm.cfx (an assumption the
model states). The mount places the world frame in the cell (models.RobotModel.world_in_cell).
An id of an arm that has no model is an error that names the closest model.
"""

from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass, replace

from ..excerpt import shown
from . import catalog as _catalog
from .errors import RobotError
from .provenance import Assumption

_STROKE = re.compile(r"\d+(?:\.\d+)?")
_MOUNT_WORDS = {"floor": "floor", "ground": "floor", "wall": "wall", "ceiling": "ceiling", "roof": "ceiling"}


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


def _key(text: str) -> str:
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
    key = _key(n)
    cands = []
    for name, entry in _catalog.catalog().items():
        ids = [_key(_catalog.normalize_id(i)) for i in entry.get("ids", []) if i]
        if key in ids or key == _key(name):
            cands.append((name, entry))
    if not cands:
        for known in _catalog.known_without_model():
            if _key(_catalog.normalize_id(known["id"])) == key:
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


def with_stroke(model, stroke_mm: float, by: str = "controller"):
    """A SCARA model with another axis 3 stroke: axis 3 ranges over [-0.1, stroke + 0.1] mm (the
    pattern of the published ranges); everything else is the model's, an assumption stated."""
    from .models import RobotModel

    assert isinstance(model, RobotModel)
    if model.family != "scara":
        raise RobotError(f"{model.name} is not a SCARA: it has no axis 3 stroke")
    if not stroke_mm > 0:
        raise RobotError(f"a stroke of {stroke_mm:g} mm: a positive length is needed")
    limits = list(model.joint_limits)
    limits[2] = (-0.1, stroke_mm + 0.1)
    base = re.sub(r"-L\d+(?:\.\d+)?$", "", model.name)
    text = (f"No public data for the {base} with a {stroke_mm:g} mm stroke: the model of the {model.stroke_mm:g} mm "
            f"stroke is used with axis 3 over [-0.1, {stroke_mm + 0.1:g}] mm; its links and the other joint ranges "
            "are assumed the same (the world's height is an assumption anyway: world_z_mm)")
    prov = model.provenance.replace_assumption(Assumption("stroke_mm", f"{stroke_mm:g}", text, by))
    return replace(model, name=f"{base}-L{stroke_mm:g}", joint_limits=tuple(limits), stroke_mm=stroke_mm, provenance=prov)


def with_mount(model, mount: str, by: str = "controller"):
    """The model with its world frame placed in the cell for `mount` (floor, wall, ceiling)."""
    from .models import MOUNTS

    m = _MOUNT_WORDS.get(mount.strip().lower())
    if m is None:
        raise RobotError(f"mount {shown(mount)}: one of {', '.join(MOUNTS)}")
    text = ("The VAL 3 world frame is taken as attached to the arm's base whatever the mount (points taught on the "
            f"arm stay valid); the mount only turns it in the cell (for gravity, cell geometry and views): {m}")
    if model.family == "scara" and m == "wall":
        text += " (a SCARA's wall mount is a console: its axes stay vertical)"
    prov = model.provenance.replace_assumption(Assumption("mount", m, text, by))
    return replace(model, mount=m, provenance=prov)


def from_arm_cfx(path: str | os.PathLike):
    """The model of the arm a controller's usr/configs/arm.cfx names, with its stroke and mount."""
    from .models import catalog_model

    cfg = read_arm_config(path)
    stroke = cfg.stroke_mm
    notes = [f"{path}: arm {shown(cfg.arm)}" + (f", mount {shown(cfg.mount)}" if cfg.mount else "")
             + (f", lengthAxis3 {shown(cfg.length_axis3)}" if cfg.length_axis3 else "")]
    if cfg.length_axis3 and stroke is None:
        notes.append(f"lengthAxis3 {shown(cfg.length_axis3)} is not a length such as L200: ignored")
    match = match_id(cfg.arm, stroke)
    model = catalog_model(match.name)
    notes += match.notes
    if match.stroke_mm is not None:
        model = with_stroke(model, match.stroke_mm)
        notes.append(f"stroke {match.stroke_mm:g} mm from lengthAxis3: {model.name}, derived from {match.name} (an assumption)")
    if cfg.mount:
        try:
            model = with_mount(model, cfg.mount)
        except RobotError:
            notes.append(f"mount {shown(cfg.mount)} is not floor, wall or ceiling: {model.mount} kept")
    return replace(model, notes=tuple(notes))


def by_name(text: str):
    """A catalogue model by name (case- and separator-insensitive), or '<SCARA>-L<stroke>' for a
    SCARA with another stroke (TS60-L200: an assumption the model states)."""
    from .models import catalog_model

    try:
        return catalog_model(_catalog.find(text))
    except RobotError:
        m = re.fullmatch(r"(.+?)[-_ ]?L(\d+(?:\.\d+)?)", text.strip(), re.IGNORECASE)
        if not m:
            raise
        try:
            base = _catalog.find(m.group(1))
        except RobotError:
            raise RobotError(f"unknown robot {shown(text)}; known arms: {', '.join(_catalog.names())} (or a path to a URDF)") from None
        model = catalog_model(base)
        if model.family != "scara":
            raise RobotError(f"unknown robot {shown(text)}: {base} is not a SCARA, it has no stroke to choose") from None
        stroke = float(m.group(2))
        same = [n for n, e in _catalog.catalog().items() if e.get("stroke_mm") == stroke and _key(n).startswith(_key(base))]
        if same:
            return catalog_model(same[0])
        return with_stroke(model, stroke, by="user")
