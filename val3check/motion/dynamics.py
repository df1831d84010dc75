"""getJointForce (10.6): the joint torques of the commanded motion, when the arm model has masses.

The controller measures motor currents; the simulation has no motors, so it gives the inverse
dynamics of the commanded motion (gravity, inertia, Coriolis; no friction, no payload beyond the
URDF) computed by pinocchio from the URDF's inertial data. The Stäubli models in robots/ carry no
masses (they are not published): for them `joint_forces` returns None and the instruction says
"not simulated" (docs/motion.md).
"""

from __future__ import annotations

import functools
import math

import numpy as np

DEG = math.pi / 180.0


@functools.lru_cache(maxsize=None)
def _has_inertia(path: str) -> bool:
    """Whether the URDF at `path` gives a mass to some link (pinocchio reads it)."""
    from ..robot.models import pinocchio_model

    model, _ = pinocchio_model(path)
    return any(float(model.inertias[i].mass) > 0.0 for i in range(1, model.njoints))


def has_dynamics(robot) -> bool:
    """True when the arm's URDF gives masses to its links."""
    try:
        return _has_inertia(robot.source)
    except Exception:  # no URDF pinocchio can read: no dynamics
        return False


def joint_forces(robot, q_deg, qd_deg_s, qdd_deg_s2) -> np.ndarray | None:
    """Joint torques (N·m, one per axis) of the motion (degrees, deg/s, deg/s²), or None when the
    arm model has no inertial data."""
    if not has_dynamics(robot):
        return None
    import pinocchio as pin

    from ..robot.models import pinocchio_ids

    model, data = robot.pinocchio()
    ids = pinocchio_ids(robot.source, robot.joint_names, robot.world_frame, robot.flange_frame)[0]
    q = pin.neutral(model)
    v = np.zeros(model.nv)
    a = np.zeros(model.nv)
    vidx = []
    for (iq, nq), name, j, jd, jdd in zip(ids, robot.joint_names, q_deg, qd_deg_s, qdd_deg_s2):
        jid = model.getJointId(name)
        iv = model.joints[jid].idx_v
        vidx.append(iv)
        t = j * DEG
        if nq == 1:
            q[iq] = t
        else:  # continuous joint: (cos, sin)
            q[iq], q[iq + 1] = math.cos(t), math.sin(t)
        v[iv] = jd * DEG
        a[iv] = jdd * DEG
    tau = pin.rnea(model, data, q, v, a)
    return np.array([float(tau[i]) for i in vidx])
