"""from_urdf(): a RobotModel from a URDF and its <val3check> metadata; catalog_model() for the arms in robots/."""

from __future__ import annotations

import functools
import math
import os
from pathlib import Path

from ..excerpt import shown
from . import catalog as _catalog
from . import scara as _scara
from .errors import RobotError
from .kinematics import RAD, Chain, extract_opw
from .models import RobotModel
from .provenance import Provenance
from .urdf import Mat, read_urdf
from .variants import MOUNTS

# Acceleration assumed when a URDF gives none (robots/README.md): nominal speed reached in this time.
DEFAULT_RAMP_S = 0.25


def _clean(x: float) -> float:
    r = round(x, 9)
    return r if abs(r - x) < 1e-9 else x


def from_urdf(path: str | os.PathLike, world_frame: str | None = None, flange_frame: str | None = None,
              name: str | None = None, world_shift: Mat | None = None) -> RobotModel:
    """A RobotModel from a URDF. The URDF must say which links are the VAL 3 world and flange frames
    (<val3check world_frame=".." flange_frame=".."/>), unless world_frame/flange_frame are given.
    `world_shift` moves the world frame relative to that link (an override of its position)."""
    info = read_urdf(path)
    meta = info.meta or {}
    world = world_frame or meta.get("world_frame")
    flange = flange_frame or meta.get("flange_frame")
    missing = [a for a, v in (("world_frame", world), ("flange_frame", flange)) if not v]
    if missing:
        if info.meta is None:
            raise RobotError(
                f"{info.path}: no <val3check> element: a URDF must name the links that are the VAL 3 world "
                'and flange frames, e.g. <val3check arm="MyArm" world_frame="base" flange_frame="tool0"/> '
                "inside <robot> (robots/README.md)"
            )
        raise RobotError(f"{info.path}: <val3check> lacks {' and '.join(missing)} (the links of the VAL 3 world and flange frames)")
    chain = Chain(info, world, flange, world_shift)
    joints = chain.joints
    speeds = tuple(_clean(j.velocity if j.kind == "prismatic" else j.velocity * RAD) for j in joints)
    accs, notes = [], set()
    for j, v in zip(joints, speeds):
        attrs = info.meta_joints.get(j.name, {})
        key, other = ("acceleration_mm_s2", "acceleration_deg_s2") if j.kind == "prismatic" else ("acceleration_deg_s2", "acceleration_mm_s2")
        if attrs.get(other) is not None:
            raise RobotError(f"{info.path}: joint {shown(j.name)} is {j.kind}: its acceleration is {key}, not {other}")
        given = attrs.get(key)
        if given is not None:
            try:
                a = float(given)
            except ValueError:
                raise RobotError(f"{info.path}: joint {shown(j.name)}: {key}={shown(given)} is not a number") from None
            if not a > 0:
                raise RobotError(f"{info.path}: joint {shown(j.name)}: {key} must be positive")
            accs.append(a)
        else:
            accs.append(v / DEFAULT_RAMP_S)
            notes.add("default")
    rule = meta.get("acceleration_rule", "")
    if notes:
        note = f"assumed (not in the URDF): nominal speed reached in {DEFAULT_RAMP_S:g} s from rest"
    else:
        note = f"from the URDF: {rule}" if rule else "from the URDF"
    opw, why = extract_opw(chain)
    sc = None
    if chain.kind == "scara":
        sc, why = _scara.extract_scara(chain)
    if opw is not None:
        reach = opw.a1 + opw.c2 + math.hypot(opw.c3, opw.a2) + opw.c4
    elif sc is not None:
        reach = sc.l1 + sc.l2 + math.hypot(*sc.offset)
    else:  # upper bound: the lengths of the links after axis 1, end to end
        reach = sum(math.sqrt(sum(j.before[i][3] ** 2 for i in range(3))) for j in joints[1:])
        reach += math.sqrt(sum(chain.tip[i][3] ** 2 for i in range(3)))
    provenance = Provenance.from_meta(info.meta_items)
    stroke = meta.get("stroke_mm")
    native = meta.get("native_mount", "floor")
    if native not in MOUNTS:
        raise RobotError(f"{info.path}: <val3check native_mount={shown(native)}>: one of {', '.join(MOUNTS)}")
    return RobotModel(
        name=name or meta.get("arm") or info.robot_name or Path(info.path).stem,
        source=info.path,
        srs_arm_id=meta.get("srs_arm_id", ""),
        srs_arm_id_hint=meta.get("srs_arm_id_hint", ""),
        joint_names=tuple(j.name for j in joints),
        joint_limits=tuple((_clean(j.lower if j.kind == "prismatic" else j.lower * RAD),
                            _clean(j.upper if j.kind == "prismatic" else j.upper * RAD)) for j in joints),
        nominal_speeds=speeds,
        accelerations=tuple(accs),
        acceleration_note=note,
        max_torques=tuple(j.effort if j.effort else None for j in joints),
        reach_mm=reach,
        chain=chain,
        opw=opw,
        opw_reason=why,
        world_frame=world,
        flange_frame=flange,
        family=chain.kind,
        scara=sc,
        stroke_mm=float(stroke) if stroke else None,
        series=meta.get("series", ""),
        provenance=provenance,
        mount=native,
        native_mount=native,
        world_shift=world_shift,
        # given per joint without an <assumption> about them: the URDF's author measured them
        accelerations_assumed=bool(notes) or bool(provenance.assumed() & {"ramp_s", "accelerations"}),
    )


@functools.lru_cache(maxsize=None)
def _catalog_model(name: str) -> RobotModel:
    return from_urdf(_catalog.catalog()[name]["path"])


def catalog_model(name: str) -> RobotModel:
    """A catalogue model by its exact catalogue name (shared, unchanged: copy with replace())."""
    return _catalog_model(name)
