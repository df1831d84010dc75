"""Shared set-up of the motion tests: a TX2-60, a tool pointing down in front of it."""

from __future__ import annotations

import numpy as np

from val3check.motion.commands import MoveCommand, Target
from val3check.motion.findings import Source
from val3check.motion.kin import ArmKin
from val3check.motion.mdesc import MDesc
from val3check.motion.queue import MotionQueue
from val3check.robot import load_robot

ROBOT = load_robot("TX2-60")
KIN = ArmKin(ROBOT)
HOME = np.array([0.0, 20.0, 100.0, 0.0, 60.0, 0.0])  # tool down, in front of the arm
T_HOME = KIN.fk(HOME[None])[0]
OFF = MDesc(blend="off")


def queue(joints=HOME, **kw) -> MotionQueue:
    return MotionQueue(ROBOT, joints, **kw)


def point(dx=0.0, dy=0.0, dz=0.0, base=None, config=("ssame", "esame", "wsame"), name="") -> Target:
    """A TCP pose translated from the home pose (mm)."""
    T = (T_HOME if base is None else base).copy()
    T[:3, 3] += [dx, dy, dz]
    return Target.point(T, config, name)


def movej(target, md=OFF, line=1, **kw) -> MoveCommand:
    if not isinstance(target, Target):
        target = Target.joint(target)
    return MoveCommand("movej", target, md, source=Source("app/start.pgx", line, 5, "start", "t"), **kw)


def movel(target, md=OFF, line=1, **kw) -> MoveCommand:
    return MoveCommand("movel", target, md, source=Source("app/start.pgx", line, 5, "start", "t"), **kw)


def movec(via, target, md=OFF, line=1, **kw) -> MoveCommand:
    return MoveCommand("movec", target, md, via=via, source=Source("app/start.pgx", line, 5, "start", "t"), **kw)


def run(q: MotionQueue, now: float = 0.0) -> float:
    """waitEndMove, then let time reach the end; returns that time."""
    t = q.wait_end_move(now)
    q.advance(t)
    return t


def tcp_path(q: MotionQueue, t0: float, t1: float, tool=None):
    """TCP positions and speeds sampled on the 4 ms clock."""
    times, Q, Qd = q.trajectory.sample(t0, t1)
    P = KIN.tcp(Q, tool)[:, :3, 3]
    h = 1e-5
    Pp = KIN.tcp(Q + h * Qd, tool)[:, :3, 3]
    Pm = KIN.tcp(Q - h * Qd, tool)[:, :3, 3]
    v = np.linalg.norm(Pp - Pm, axis=1) / (2 * h)
    return times, P, v
