"""Shared helpers for the robot tests."""

from __future__ import annotations

import math
import random
from pathlib import Path

from val3check.robot import load_robot, names
from val3check.robot.catalog import catalog
from val3check.robot.kinematics import pose_error

ROOT = Path(__file__).resolve().parents[2]
CONTROLLERS = Path(__file__).resolve().parent / "controllers"


def _facts(name: str) -> Path:
    """shared/robots/NAME beside the checkout (or beside the folder of worktrees that holds it)."""
    for folder in ROOT.parents:
        if (folder / "shared" / "robots" / name).is_file():
            return folder / "shared" / "robots" / name
    return ROOT.parent / "shared" / "robots" / name


TOML = _facts("staubli-arms.toml")
MORE = _facts("staubli-arms-more.toml")
ARMS = names()
SIX_AXIS = [n for n in ARMS if catalog()[n]["kind"] == "six-axis"]
SCARAS = [n for n in ARMS if catalog()[n]["kind"] == "scara"]

# here(flange, world) with all joints at zero = {a1, b, c2 + c3 + c4, 0, 0, 0} (staubli-arms.toml header),
# figures added up by hand from the facts
ZERO_POSE = {
    "TX40": (0, 35, 515), "TX60": (0, 20, 670), "TX60L": (0, 20, 920),
    "TX90": (50, 50, 950), "TX90L": (50, 50, 1150), "TX90XL": (50, 50, 1400),
    "TX200": (250, 0, 1944), "TX200L": (250, 0, 2344),
    "TX2-40": (0, 35, 515), "TX2-60": (0, 20, 670), "TX2-60L": (0, 20, 920),
    "TX2-90": (50, 50, 950), "TX2-90L": (50, 50, 1150), "TX2-90XL": (50, 50, 1400),
    "TX2-140": (150, 0, 1360), "TX2-160": (150, 0, 1560), "TX2-160L": (150, 0, 1860),
    "RX90B": (0, 0, 985), "RX90BL": (0, 0, 1185), "RX130B": (0, 0, 1360),
    "RX160": (150, 0, 1560), "RX160L": (150, 0, 1860),
}
# SCARA at zero: arm stretched along X (link1 + link2), flange at the world's z = 0 (the assumed
# world), Z down: {l1 + l2, 0, 0, 180, 0, 0}
SCARA_ZERO_X = {"TS2-40": 460, "TS2-60": 620, "TS2-80": 800, "TS2-100": 1000, "TS2-100-L400": 1000,
                "TS40": 400, "TS60": 600, "TS80": 800, "TP80": 800}


def random_joints(robot, rng: random.Random, margin: float = 0.0):
    return [rng.uniform(lo + margin, hi - margin) for lo, hi in robot.joint_limits]


def close_pose(A, B, pos_mm=1e-6, ang_rad=1e-9) -> bool:
    dp, da = pose_error(A, B)
    return dp < pos_mm and da < ang_rad


def joint_dist(a, b) -> float:
    return max(abs(x - y) for x, y in zip(a, b))


__all__ = ["ARMS", "CONTROLLERS", "MORE", "ROOT", "SCARAS", "SCARA_ZERO_X", "SIX_AXIS", "TOML", "ZERO_POSE", "load_robot",
           "math", "random_joints", "close_pose", "joint_dist"]
