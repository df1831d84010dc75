"""Variants of one arm model: its world placed for another mount, a SCARA with another stroke.

Both come from a controller's arm.cfx (identify.py), a robot file or RobotModel.with_assumptions
(overrides.py); each states what it assumes in the model's provenance.
"""

from __future__ import annotations

import re
from dataclasses import replace

from ..excerpt import shown
from .errors import RobotError
from .provenance import Assumption

MOUNTS = ("floor", "wall", "ceiling")
_MOUNT_WORDS = {"floor": "floor", "ground": "floor", "wall": "wall", "ceiling": "ceiling", "roof": "ceiling"}


def with_stroke(model, stroke_mm: float, by: str = "controller"):
    """A SCARA model with another axis 3 stroke: axis 3 ranges over [-0.1, stroke + 0.1] mm (the
    pattern of the published ranges); everything else is the model's, an assumption stated."""
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
    m = _MOUNT_WORDS.get(mount.strip().lower())
    if m is None:
        raise RobotError(f"mount {shown(mount)}: one of {', '.join(MOUNTS)}")
    text = ("The VAL 3 world frame is taken as attached to the arm's base whatever the mount (points taught on the "
            f"arm stay valid); the mount only turns it in the cell (for gravity, cell geometry and views): {m}")
    if model.family == "scara" and m == "wall":
        text += " (a SCARA's wall mount is a console: its axes stay vertical)"
    prov = model.provenance.replace_assumption(Assumption("mount", m, text, by))
    return replace(model, mount=m, provenance=prov)
