"""Shared helpers for the collision tests: analytic trajectories and small cells."""

from __future__ import annotations

import math

import numpy as np
import pytest

fcl = pytest.importorskip("fcl")
pytest.importorskip("trimesh")

from val3check.collision import CollisionChecker, MotionSpan, arm_model, read_cell  # noqa: E402
from val3check.robot import load_robot  # noqa: E402

DT = 0.004
DOWN = (180.0, 0.0, 0.0)  # tool pointing down
TOOL = (0.0, 0.0, 100.0, 0.0, 0.0, 0.0)  # tTool: 100 mm out of the flange

ROBOT = load_robot("TX2-60")
ARM = arm_model(ROBOT)


def line_motion(a, b, speed: float, tool=TOOL, ori=DOWN, t0: float = 0.0, robot=ROBOT):
    """The TCP from a to b at constant speed (mm/s) on the 4 ms clock: (times, joints). The last
    sample is at b (so the final step may be shorter)."""
    length = math.dist(a, b)
    n = max(1, math.ceil(length / speed / DT - 1e-9))
    times = t0 + np.minimum(np.arange(n + 1) * DT, length / speed)
    joints, q = [], None
    for t in times:
        s = min(1.0, (t - t0) * speed / length)
        p = [a[i] + s * (b[i] - a[i]) for i in range(3)]
        q = robot.solve((*p, *ori), None, q, tool=tool)
        joints.append(q)
    return times, np.array(joints)


def joint_motion(q0, q1, duration: float, t0: float = 0.0):
    """Joints from q0 to q1 at constant speed over `duration` s, on the 4 ms clock."""
    n = max(1, math.ceil(duration / DT - 1e-9))
    times = t0 + np.arange(n + 1) * (duration / n)
    s = np.linspace(0.0, 1.0, n + 1)[:, None]
    return times, np.asarray(q0, float) + s * (np.asarray(q1, float) - np.asarray(q0, float))


def write_cell(folder, text: str, name: str = "cell.toml"):
    path = folder / name
    path.write_text(text, encoding="utf-8")
    return path


def checker(cell, **kw) -> CollisionChecker:
    kw.setdefault("tools", {"tTool": TOOL})
    return CollisionChecker(ARM, cell, **kw)


__all__ = ["ARM", "DOWN", "DT", "MotionSpan", "ROBOT", "TOOL", "checker", "joint_motion", "line_motion", "read_cell",
           "write_cell"]
