"""Stäubli arm models and their exact kinematics: six-axis RX/TX arms and SCARA RS/TS arms.

Imported only by the `robots` and `sim` code paths: `val3check lint` never loads it (code that
must not import it reads robots/catalog.toml with tomllib: `catalog.catalog_path()`). The
kinematics itself is pure Python; pinocchio (and numpy) are imported on first use of
`RobotModel.pinocchio()`, `fk_pinocchio()` or `collision_model()`.

API (joints in degrees, and in millimetres for a SCARA's prismatic axis 3; lengths in
millimetres; poses as VAL 3 trsf {x, y, z, rx, ry, rz} with R = Rx(rx)·Ry(ry)·Rz(rz), manual
9.3.2, or 3x4/4x4 matrices in mm):

    load_robot(spec, app_path=None) -> RobotModel               (load.py)
        spec: a catalogue name ('TX2-60', 'tx2_60', 'ts2-60', 'rx160l'…, case-insensitive; 'TS60-L200'
        for a SCARA with another stroke), a URDF path, an arm.cfx path, a robot file (.toml: a model
        plus the user's values for its assumptions, overrides.py), or None: then the usr/configs/arm.cfx
        of the controller tree above app_path (identify.py: 'ts2_60-S1' and 'ts2-60-S1' alike, the
        '-S<n>' suffix ignored, lengthAxis3 picks the stroke, mount places the world in the cell).
        Raises RobotError (unknown name: lists the known ones; a known arm without a model: names the
        closest model; URDF without the metadata: says which).
    choose_robot(name_or_path, app_path) -> RobotModel          (select.py; for `val3check sim`)
    names() -> list[str]                                        the catalogue, grouped by series

    RobotModel
        name, srs_arm_id (seen in a real arm.cfx) / srs_arm_id_hint (inferred), source (URDF path)
        family          "six-axis" | "scara"
        type_family     "Rx" | "Rs": the VAL 3 types the arm takes (pointRx/jointRx/configRx or
                        pointRs/jointRs/configRs); a value of the other family is error 81 at run time
        axes            6 or 4; joint_names; joint_kinds ("revolute" | "prismatic" per axis);
                        joint_units ("deg" | "mm" per axis: a prismatic axis is a length, in the
                        application's length unit once the interpreter scales it)
        config_fields   ("shoulder", "elbow", "wrist"), or ("shoulder",) for a SCARA (9.7.2)
        joint_limits    ((min, max) per axis, deg or mm)
        nominal_speeds  (deg/s, mm/s)
        accelerations   (deg/s², mm/s²; an assumption, see acceleration_note and robots/README.md;
                        with_accelerations([...]) gives a copy with the user's values)
        max_torques     (N·m or None where not public)
        reach_mm        (axis 1 to the flange centre, arm stretched out); stroke_mm (SCARA axis 3)
        provenance      .facts (key, source), .assumptions (key, value, why, by: "model" |
                        "controller" | "user"), .alternatives (where sources disagree: kept value,
                        other value, why), .missing, .references; `assumed` = keys of assumptions
        with_assumptions({key: value}) -> copy with the user's values (overrides.KEYS)
        mount           "floor" | "wall" | "ceiling"; world_in_cell (3x4 rotation: the VAL 3 world,
                        attached to the arm's base, in a cell frame whose Z is up)
        notes           how the model was chosen (arm.cfx, robot file)
        fk(joints, tool=None) -> (x, y, z, rx, ry, rz)     here(flange|tool, world) / jointToPoint
        fk_matrix(joints, tool=None) -> 3x4 matrix (mm)
        ik(pose, config=None, near=None, same_from=None, tool=None, all_turns=False) -> [joints…]
            every solution (up to 8 branches; 2 for a SCARA, its elbow lefty/righty) in the joint
            limits and the configuration; config None = all free, or Config / ("righty", "esame",
            "wfree") / for a SCARA ("righty",) (three fields accepted when elbow and wrist are
            same/free; a value there is a RobotError: 9.7.2); `same` is relative to same_from
            (default near); multi-turn axes (j4/j6 ±270°, a SCARA's j4 ±500°) take the turn nearest
            `near` (9.6.3); with `near` the nearest solution is first. A SCARA reaches only
            orientations turned about the vertical from its flange's (Z down: rx = 180).
        point_to_joint(pose, config, initial, tool=None) -> joints | None       (9.6.3)
        solve(pose, config, initial, tool=None) -> joints, or raises Unreachable(reason="reach" |
            "limits" | "config")                                                 (for movej)
        config_of(joints) -> (shoulder, elbow, wrist) by the formulas of 9.7.4 ('righty'/'lefty',
            'epositive'/'enegative', 'wpositive'/'wnegative'); a SCARA: (shoulder,), righty when
            sin(j2) > 0 (9.7.5)
        singularities(joints) -> ("elbow", "wrist", "shoulder"…): the singular positions `joints`
            is at (six-axis: j5 = 0, arm stretched/folded, wrist centre on the shoulder axis;
            SCARA: arm stretched/folded, i.e. sin(j2) = 0, or axis 4 on axis 1)
        in_limits(joints) -> bool                                                (isInRange)
        pinocchio() -> (Model, Data); fk_pinocchio(joints) -> 3x4; collision_model()

fk() and ik() use closed forms (pure Python, ~350,000 FK and ~20,000 full IK per second on a
six-axis arm; bench/bench_kinematics.py); fk_pinocchio() computes the same pose from the same
URDF with pinocchio, and the tests hold the two (and the URDF chain multiplied out) equal to
1e-9 mm on every arm, SCARA included (prismatic joint in metres for pinocchio).

A URDF of another arm loads through the same path (urdf_model.from_urdf(path, world_frame=...,
flange_frame=...)): six revolute joints, or a SCARA's revolute-revolute-prismatic-revolute chain.
Its forward kinematics works whatever its geometry; ik() raises IKUnsupported unless it is
ortho-parallel with a spherical wrist, or a SCARA with four vertical axes (detected and verified
on random positions, not assumed).
"""

from __future__ import annotations

from .catalog import names
from .configuration import Config
from .errors import IKUnsupported, RobotError, Unreachable
from .load import load_robot
from .models import RobotModel
from .select import choose_robot
from .urdf_model import from_urdf

__all__ = [
    "Config",
    "IKUnsupported",
    "RobotError",
    "RobotModel",
    "Unreachable",
    "choose_robot",
    "from_urdf",
    "load_robot",
    "names",
]
