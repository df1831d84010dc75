"""Chapter 10: the motion instructions, as this version simulates them.

`movej` checks what it can tell exactly, then stops the task with R002: motion is not
simulated yet. The other instructions of chapter 10 (movel, movec, waitEndMove, stopMove...)
have no handler: the registry stops them with R002 (interpretation/registry.py).
"""

from __future__ import annotations

from ..geometry import frames as geo_frames
from ..geometry import jointops
from ..geometry import points as geo_points
from ..geometry import rotation
from ..geometry.frames import Tool
from ..geometry.trsf import Trsf
from ..interpretation.arm_port import KinematicsUnsupported, TargetUnreachable
from ..interpretation.chapters.ch09_geometry import check_axes, ct, jt, millimeter_unit, unsupported
from ..interpretation.not_simulated import ARM_LIMIT, SimLimit
from ..language.runtime_errors import Val3RuntimeError

E = Val3RuntimeError


def I_movej(task, unit, target, tool: Tool, mdesc: dict) -> float:
    """10.6 movej: motion is not simulated in this version (R002), but a target that the arm
    model shows no joint position can reach (out of reach, outside the joint limits, or not in
    the point's configuration from the commanded position) is error 154 (12.1: "cible hors de
    portée"), as the manual says movej raises it. Errors 160-165 of the tool and point first."""
    geo_frames.check_defined(tool)
    arm = task.machine.arm
    if type(target) is dict:  # a joint position
        if arm.has_model:
            j = jt(target)
            check_axes(arm, j, "movej")
            if not jointops.is_in_range(j, arm.joint_limits):
                raise E(154, f"movej: the joint position is outside the software joint limits of {arm.name}")
    else:
        flange = rotation.pose_mul(geo_points.world_pose(target), rotation.pose_inv(geo_frames.root_pose(tool)))
        if arm.has_model:
            pose = Trsf.from_pose(flange).as_tuple()
            now = task.machine.clock.time_of(task)
            try:
                arm.solve(pose, ct(target.config), millimeter_unit(unit), arm.joints_at(now))
            except TargetUnreachable as exc:
                raise E(154, f"movej: no joint position of {arm.name} reaches the point ({exc})") from None
            except KinematicsUnsupported as exc:
                raise unsupported("movej", arm, exc) from None
    raise SimLimit(ARM_LIMIT, "movej")


def register(registry) -> None:
    registry.instruction("movej", I_movej)
