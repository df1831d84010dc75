"""Stäubli arm models and their exact kinematics (issue 5, part A).

Imported only by the `robots` and `sim` code paths: `val3check lint` never loads it. The
kinematics itself is pure Python; pinocchio (and numpy) are imported on first use of
`RobotModel.pinocchio()`, `fk_pinocchio()` or `collision_model()`.

API (joints in degrees, lengths in millimetres, poses as VAL 3 trsf {x, y, z, rx, ry, rz} with
R = Rx(rx)·Ry(ry)·Rz(rz), manual 9.3.2, or 3x4/4x4 matrices in mm):

    load_robot(spec, app_path=None) -> RobotModel
        spec: a catalogue name ('TX2-60', 'tx2_60', 'rx160l'…, case-insensitive), a URDF path, an
        arm.cfx path, or None: then the usr/configs/arm.cfx of the controller tree above app_path.
        Raises RobotError (unknown name: lists the known ones; URDF without the metadata: says which).
    choose_robot(name_or_path, app_path) -> RobotModel          (select.py; for `val3check sim`)
    names() -> list[str]                                        the catalogue

    RobotModel
        name, srs_arm_id, source (URDF path), joint_names
        joint_limits      ((min, max) deg per axis)
        nominal_speeds    (deg/s)
        accelerations     (deg/s²; an assumption, see acceleration_note and robots/README.md;
                           with_accelerations([...]) gives a copy with the user's values)
        reach_mm          (axis 1 to the flange centre, arm stretched out)
        fk(joints, tool=None) -> (x, y, z, rx, ry, rz)     here(flange|tool, world) / jointToPoint
        fk_matrix(joints, tool=None) -> 3x4 matrix (mm)
        ik(pose, config=None, near=None, same_from=None, tool=None, all_turns=False) -> [joints…]
            every solution (up to 8 branches) in the joint limits and the configuration; config
            None = all free, or Config / ("righty", "esame", "wfree"); `same` is relative to
            same_from (default near); j4/j6 (±270°) take the turn nearest `near` (9.6.3); with
            `near` the nearest solution is first
        point_to_joint(pose, config, initial, tool=None) -> joints | None       (9.6.3)
        solve(pose, config, initial, tool=None) -> joints, or raises Unreachable(reason="reach" |
            "limits" | "config")                                                 (for movej)
        config_of(joints) -> (shoulder, elbow, wrist)   'righty'/'lefty', 'epositive'/'enegative',
            'wpositive'/'wnegative' by the formulas of 9.7.4
        in_limits(joints) -> bool                                                (isInRange)
        pinocchio() -> (Model, Data); fk_pinocchio(joints) -> 3x4; collision_model()

fk() and ik() use the closed form (pure Python, ~350,000 FK and ~20,000 full IK per second);
fk_pinocchio() computes the same pose from the same URDF with pinocchio, and the tests hold the
two (and the URDF chain multiplied out) equal to 1e-9 mm on every arm.

A URDF of another six-axis arm loads through the same path (from_urdf(path, world_frame=...,
flange_frame=...)); its forward kinematics works whatever its geometry, and ik() raises
IKUnsupported unless it is ortho-parallel with a spherical wrist (detected and verified, not
assumed). RS/TS SCARA arms are out of scope.
"""

from __future__ import annotations

from .catalog import names
from .configuration import Config
from .errors import IKUnsupported, RobotError, Unreachable
from .models import RobotModel, from_urdf, load_robot
from .select import choose_robot

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
