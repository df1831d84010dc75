"""load_robot(): the arm model a user names (catalogue name, URDF, arm.cfx, robot file) or the controller tree has.

The use case above the data modules: it identifies the arm (identify.py), builds its model
(urdf_model.py), turns it into the variant the controller or the user says (variants.py) and puts
the user's values in place of its assumptions (overrides.py).
"""

from __future__ import annotations

import os
import re
from dataclasses import replace
from pathlib import Path

from .. import tomlfile
from ..confine import Refused, Roots, read_bytes, repository_root
from ..excerpt import shown
from . import catalog as _catalog
from .errors import RobotError
from .identify import id_key, match_id, read_arm_config
from .models import RobotModel
from .overrides import apply
from .urdf_model import catalog_model, from_urdf
from .variants import with_mount, with_stroke


def load_robot(spec: str | os.PathLike | None, app_path: str | os.PathLike | None = None) -> RobotModel:
    """A robot by catalogue name (case-insensitive: 'tx2-60', 'TX2_60'; 'TS60-L200' for another
    stroke of a SCARA), by URDF path, by arm.cfx path, by robot file (.toml: a model plus the
    user's values for its assumptions, load_robot_file), or — spec None — from the
    usr/configs/arm.cfx of the controller tree holding app_path."""
    if spec is None or str(spec) == "":
        if app_path is None:
            raise RobotError("no robot named and no application to find a controller tree (arm.cfx) from")
        cfx = _catalog.find_arm_cfx(app_path)
        if cfx is None:
            raise RobotError(
                f"no usr/configs/arm.cfx above {app_path}: name the arm with --robot "
                f"(one of {', '.join(_catalog.names())}, or a URDF)"
            )
        return from_arm_cfx(cfx)
    text = os.fspath(spec)
    low = text.lower()
    if low.endswith(".cfx"):
        return from_arm_cfx(text)
    if low.endswith(".toml"):
        return load_robot_file(text, app_path)
    if low.endswith((".urdf", ".xml")) or os.path.sep in text or os.path.isfile(text):
        if not os.path.isfile(text):
            raise RobotError(f"{text}: no such URDF file")
        return from_urdf(text)
    return by_name(text)


def from_arm_cfx(path: str | os.PathLike) -> RobotModel:
    """The model of the arm a controller's usr/configs/arm.cfx names, with its stroke and mount."""
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


def by_name(text: str) -> RobotModel:
    """A catalogue model by name (case- and separator-insensitive), or '<SCARA>-L<stroke>' for a
    SCARA with another stroke (TS60-L200: an assumption the model states)."""
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
        same = [n for n, e in _catalog.catalog().items() if e.get("stroke_mm") == stroke and id_key(n).startswith(id_key(base))]
        if same:
            return catalog_model(same[0])
        return with_stroke(model, stroke, by="user")


def load_robot_file(path: str | os.PathLike, app_path=None) -> RobotModel:
    """A robot file (overrides.py's docstring): its arm with the user's values."""
    p = Path(path)
    try:  # val3check.confine: a regular file (not a FIFO or /dev/zero), 1 MB at most
        data = tomlfile.load_bytes(read_bytes(str(p), Roots.user_given(), 1 << 20))[0]
    except Refused as exc:
        raise RobotError(f"{p}: cannot read the robot file: {exc.reason}") from None
    except tomlfile.TomlError as exc:
        where = f"{p}:{exc.line}:{exc.col}" if exc.line else str(p)
        raise RobotError(f"{where}: not a valid TOML robot file: {exc.message}") from None
    extra = [k for k in data if k not in ("arm", "name", "assume")]
    if extra:
        raise RobotError(f"{p}: unknown key {', '.join(map(repr, extra))}: a robot file has arm, name and [assume]")
    arm = data.get("arm")
    if not isinstance(arm, str) or not arm.strip():
        raise RobotError(f'{p}: arm = "TX2-60" (a catalogue name, a URDF or an arm.cfx) is needed')
    if arm.lower().endswith(".toml"):
        raise RobotError(f"{p}: arm = {shown(arm)}: a robot file cannot name another robot file")
    if arm.lower().endswith((".urdf", ".xml", ".cfx")) and not os.path.isabs(arm):
        arm = str(p.parent / arm)
    if "\x00" in arm:
        raise RobotError(f"{p}: arm = {shown(data['arm'])}: a path cannot hold a NUL character")
    if arm.lower().endswith((".urdf", ".xml", ".cfx")) or os.path.sep in arm or os.path.isfile(arm):
        # a path written in a file: it stays in the robot file's repository (val3check/confine.py)
        if not Roots([repository_root(str(p))]).allows(arm):
            raise RobotError(f"{p}: arm = {shown(data['arm'])}: leads outside the robot file's repository (or its"
                             " folder, outside any repository): not read")
    model = load_robot(arm, app_path)
    assume = data.get("assume", {})
    if not isinstance(assume, dict):
        raise RobotError(f"{p}: [assume] must be a table")
    try:
        model = apply(model, assume, by="user")
    except RobotError as exc:
        raise RobotError(f"{p}: [assume] {exc}") from None
    name = data.get("name")
    if name is not None:
        if not isinstance(name, str):
            raise RobotError(f"{p}: name must be a string")
        model = replace(model, name=name)
    return replace(model, notes=model.notes + (f"robot file {p}",))
