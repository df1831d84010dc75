"""Shared helpers for the robot tests."""

from __future__ import annotations

import math
import random
from pathlib import Path

from val3check.robot import load_robot, names
from val3check.robot.kinematics import pose_error

ROOT = Path(__file__).resolve().parents[2]
TOML = ROOT.parent / "shared" / "robots" / "staubli-arms.toml"
ARMS = names()

# here(flange, world) with all joints at zero = {a1, b, c2 + c3 + c4, 0, 0, 0} (staubli-arms.toml header)
ZERO_POSE = {
    "TX60": (0, 20, 670), "TX60L": (0, 20, 920),
    "TX90": (50, 50, 950), "TX90L": (50, 50, 1150), "TX90XL": (50, 50, 1400),
    "TX2-60": (0, 20, 670), "TX2-60L": (0, 20, 920),
    "TX2-90": (50, 50, 950), "TX2-90L": (50, 50, 1150), "TX2-90XL": (50, 50, 1400),
    "RX160": (150, 0, 1560), "RX160L": (150, 0, 1860),
}


def random_joints(robot, rng: random.Random, margin: float = 0.0):
    return [rng.uniform(lo + margin, hi - margin) for lo, hi in robot.joint_limits]


def close_pose(A, B, pos_mm=1e-6, ang_rad=1e-9) -> bool:
    dp, da = pose_error(A, B)
    return dp < pos_mm and da < ang_rad


def joint_dist(a, b) -> float:
    return max(abs(x - y) for x, y in zip(a, b))


__all__ = ["ARMS", "ROOT", "TOML", "ZERO_POSE", "load_robot", "math", "random_joints", "close_pose", "joint_dist"]
