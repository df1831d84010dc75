"""The arm model of `val3check sim` (docs/sim.md, "The arm model")."""

from __future__ import annotations

from typing import Any


def choose_sim_robot(spec: str | None, app_path: str) -> tuple[Any, str]:
    """(RobotModel or None, a note for the user or "").

    `spec`: --robot's value: a catalogue name (case-insensitive), a URDF path, an arm.cfx, or
    "none" (no arm model). Without it, the usr/configs/arm.cfx of the controller tree that holds
    the application, if any. Raises `val3check.robot.RobotError` for a --robot that names no
    model; an arm.cfx found by itself whose arm has no model gives None and a note."""
    if spec is not None and spec.strip().lower() == "none":
        return None, ""
    from ..robot import RobotError, choose_robot
    from ..robot.catalog import find_arm_cfx

    if spec:
        return choose_robot(spec, app_path), ""
    cfx = find_arm_cfx(app_path)
    if cfx is None:
        return None, ""
    try:
        return choose_robot(str(cfx), app_path), ""
    except RobotError as exc:
        return None, f"{cfx}: {exc}; running without an arm model (name one with --robot)"
