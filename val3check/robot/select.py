"""choose_robot(): the arm of a simulation, from --robot or from the application's controller tree."""

from __future__ import annotations

import os

from .load import load_robot
from .models import RobotModel


def choose_robot(name_or_path: str | os.PathLike | None, app_path: str | os.PathLike | None = None) -> RobotModel:
    """--robot NAME (catalogue, case-insensitive), --robot path/to/arm.urdf, or (None) the arm named
    in usr/configs/arm.cfx of the controller tree above app_path. RobotError when none fits; its
    message lists the known arms and is fit to print as it is."""
    return load_robot(name_or_path, app_path)
