"""The user's values in place of a model's assumptions: a robot file, or RobotModel.with_assumptions.

A robot file (`--robot cell3.toml` wherever a robot is named; read by load.load_robot_file) is a
catalogue arm, a URDF or an arm.cfx plus the values the user knows better than the model's
assumptions (robots/README.md, "Your values"):

    arm = "TS2-60"                     # catalogue name, URDF or arm.cfx (relative to this file)
    name = "Cell 3 SCARA"              # optional: the name shown
    [assume]
    nominal_speeds = [420, 650, 1100, 2000]   # one per axis (deg/s, mm/s for a SCARA's axis 3)
    accelerations = { j1 = 2000 }      # or a table of some axes (deg/s², mm/s²)
    ramp_s = 0.3                       # or: accelerations = nominal speed / ramp_s for every axis
    limits = { j3 = [-142.5, 142.5] }  # joint ranges (deg, mm): e.g. the other source's values
    max_torques = [126, 47, 32, 7, 8, 2]
    mount = "ceiling"                  # floor, wall, ceiling
    world_z_mm = -20                   # SCARA: flange height in the world frame at j3 = 0
    axis3_sign = 1                     # SCARA: +1 when a growing j3 raises the flange
    axis4_sign = -1                    # SCARA: +1 when a growing j4 turns the flange about world +Z
    stroke_mm = 400                    # SCARA: axis 3 stroke (range [-0.1, stroke + 0.1] mm)

Each value given replaces the model's and is listed by `val3check robots FILE` as given by the
user; everything else keeps the model's provenance.
"""

from __future__ import annotations

import math
from dataclasses import replace

from ..excerpt import shown
from .errors import RobotError
from .provenance import Assumption
from .variants import with_mount, with_stroke

KEYS = ("nominal_speeds", "accelerations", "ramp_s", "limits", "max_torques", "mount", "world_z_mm", "axis3_sign",
        "axis4_sign", "stroke_mm")
SCARA_ONLY = ("world_z_mm", "axis3_sign", "axis4_sign", "stroke_mm")


def _num(v, what: str) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise RobotError(f"{what}: a number is needed, not {shown(v)}")
    return float(v)


def _per_axis(model, value, what: str, current: tuple) -> list:
    """A list of one value per axis, or a table {j1 = .., j3 = ..} of some axes."""
    n = model.axes
    out = list(current)
    if isinstance(value, (list, tuple)):
        if len(value) != n:
            raise RobotError(f"{what}: {len(value)} values for the {n} axes of {model.name}")
        return list(value)
    if isinstance(value, dict):
        for k, v in value.items():
            ks = str(k).lower()
            if not (ks.startswith("j") and ks[1:].isdigit() and 1 <= int(ks[1:]) <= n):
                raise RobotError(f"{what}: {shown(k)} is not an axis of {model.name} (j1 to j{n})")
            out[int(ks[1:]) - 1] = v
        return out
    raise RobotError(f"{what}: a list of {n} values or a table such as {{ j1 = ... }} is needed")


def _fmt(vals) -> str:
    return " ".join(f"{v:g}" if isinstance(v, float) else str(v) for v in vals)


def apply(model, values: dict, by: str = "user"):
    """A copy of `model` with `values` (KEYS) in place of its assumptions."""
    unknown = [k for k in values if k not in KEYS]
    if unknown:
        raise RobotError(f"unknown assumption {', '.join(map(repr, unknown))}: one of {', '.join(KEYS)}")
    if model.family != "scara":
        wrong = [k for k in values if k in SCARA_ONLY]
        if wrong:
            raise RobotError(f"{', '.join(wrong)}: only for a SCARA, and {model.name} is a six-axis arm (its world frame is "
                             "public: on axis 1 at the height of axis 2)")
    m = model
    said = f"given by the {by}"
    if "stroke_mm" in values:
        m = with_stroke(m, _num(values["stroke_mm"], "stroke_mm"), by=by)
    if "limits" in values:
        lims = _per_axis(m, values["limits"], "limits", m.joint_limits)
        clean = []
        for i, pair in enumerate(lims):
            if not (isinstance(pair, (list, tuple)) and len(pair) == 2):
                raise RobotError(f"limits: j{i + 1}: a pair [min, max] is needed, not {shown(pair)}")
            lo, hi = _num(pair[0], f"limits j{i + 1}"), _num(pair[1], f"limits j{i + 1}")
            if not lo < hi:
                raise RobotError(f"limits: j{i + 1}: min {lo:g} is not below max {hi:g}")
            clean.append((lo, hi))
        m = replace(m, joint_limits=tuple(clean))
        m = _said(m, "limits", " ".join(f"{lo:g}..{hi:g}" for lo, hi in clean), said)
    if "nominal_speeds" in values:
        sp = [_num(v, "nominal_speeds") for v in _per_axis(m, values["nominal_speeds"], "nominal_speeds", m.nominal_speeds)]
        if any(not v > 0 for v in sp):
            raise RobotError("nominal_speeds: positive values are needed")
        ratio = [a / v for a, v in zip(m.accelerations, m.nominal_speeds)]  # keep the ramp of each axis
        m = replace(m, nominal_speeds=tuple(sp), accelerations=tuple(r * v for r, v in zip(ratio, sp)))
        m = _said(m, "nominal_speeds", _fmt(sp), said)
    if "ramp_s" in values:
        t = _num(values["ramp_s"], "ramp_s")
        if not t > 0:
            raise RobotError("ramp_s: a positive time in seconds is needed")
        m = replace(m, accelerations=tuple(v / t for v in m.nominal_speeds),
                    acceleration_note=f"{said}: nominal speed reached in {t:g} s from rest",
                    accelerations_assumed=by != "user")
        m = _said(m, "ramp_s", f"{t:g}", said)
    if "accelerations" in values:
        acc = [_num(v, "accelerations") for v in _per_axis(m, values["accelerations"], "accelerations", m.accelerations)]
        m = m.with_accelerations(acc, note=said, assumed=by != "user")
        m = _said(m, "accelerations", _fmt(acc), said)
    if "max_torques" in values:
        tq = [_num(v, "max_torques") for v in _per_axis(m, values["max_torques"], "max_torques", m.max_torques)]
        m = replace(m, max_torques=tuple(tq))
        m = _said(m, "max_torques", _fmt(tq), said)
    if "mount" in values:
        if not isinstance(values["mount"], str):
            raise RobotError("mount: floor, wall or ceiling")
        m = with_mount(m, values["mount"], by=by)
    for axis in (3, 4):
        key = f"axis{axis}_sign"
        if key in values:
            s = values[key]
            if s not in (1, -1) or isinstance(s, bool):
                raise RobotError(f"{key}: 1 or -1")
            signs = list(m.joint_signs)
            signs[axis - 1] = int(s) * (m.scara.signs[axis - 1] if m.scara is not None else 1)
            m = replace(m, joint_signs=tuple(signs))
            m = _said(m, key, str(int(s)), said)
    if "world_z_mm" in values:
        m = _world_z(m, _num(values["world_z_mm"], "world_z_mm"))
        m = _said(m, "world_z_mm", f"{values['world_z_mm']:g}", said)
    return m


def _said(model, key: str, value: str, said: str):
    old = {a.key: a for a in model.provenance.assumptions}.get(key)
    text = said + (f" (the model assumed {old.value})" if old is not None and old.by != "user" else "")
    return replace(model, provenance=model.provenance.replace_assumption(Assumption(key, value, text, "user")))


def _world_z(model, w: float):
    """Move a SCARA's world frame so that the flange is at height w when j3 = 0."""
    from .kinematics import Chain
    from .scara import extract_scara
    from .urdf import mul, read_urdf

    dz = model.scara.z0 - w
    shift = ((1.0, 0.0, 0.0, 0.0), (0.0, 1.0, 0.0, 0.0), (0.0, 0.0, 1.0, dz))
    total = shift if model.world_shift is None else mul(model.world_shift, shift)
    chain = Chain(read_urdf(model.source), model.world_frame, model.flange_frame, total)
    sc, why = extract_scara(chain)
    if sc is None:  # cannot happen for a model that had one: the shift is a translation
        raise RobotError(f"{model.name}: {why}")
    return replace(model, chain=chain, scara=sc, world_shift=total)


__all__ = ["KEYS", "apply"]
