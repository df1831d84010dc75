"""getJointForce: inverse dynamics of the commanded motion when the URDF has masses."""

from __future__ import annotations

import numpy as np
import pytest

from val3check.motion.dynamics import has_dynamics, joint_forces
from val3check.motion.mdesc import MDesc
from val3check.motion.queue import MotionQueue
from val3check.robot import from_urdf
from val3check.robot.catalog import example_robot_urdf

from .motionhelp import HOME, ROBOT, movej, queue, run

UR5 = example_robot_urdf("ur_description/urdf/ur5_robot.urdf")


def test_staubli_models_have_no_masses():
    assert not has_dynamics(ROBOT)
    q = queue()
    assert q.joint_force(0.0) is None


@pytest.mark.skipif(UR5 is None, reason="example-robot-data is not installed")
def test_gravity_at_rest_and_inertia_in_motion():
    import pinocchio as pin

    ur5 = from_urdf(UR5, world_frame="base_link", flange_frame="tool0")
    assert has_dynamics(ur5)
    q0 = np.array([0.0, -60.0, 80.0, -90.0, -90.0, 0.0])
    model, data = ur5.pinocchio()
    g = pin.computeGeneralizedGravity(model, data, np.radians(q0))
    tau = joint_forces(ur5, q0, np.zeros(6), np.zeros(6))
    assert np.allclose(tau, g, atol=1e-9) and abs(tau[1]) > 1.0
    q = MotionQueue(ur5, q0)
    q.record(movej(q0 + [60, 0, 0, 0, 0, 0], MDesc(blend="off")), 0.0)
    t = run(q)
    rest = q.joint_force(t)
    accel = q.joint_force(0.01)  # axis 1 accelerating: inertia on axis 1, none at rest
    assert abs(rest[0]) < 1e-9 and abs(accel[0]) > 0.1
    assert np.allclose(q.acceleration(0.01)[1:], 0.0) and q.acceleration(0.01)[0] == pytest.approx(
        ur5.accelerations[0], rel=1e-9)


def test_acceleration_at_rest_is_zero():
    q = queue()
    q.record(movej(HOME + [20, 0, 0, 0, 0, 0], MDesc(blend="off")), 0.0)
    t = run(q)
    assert np.all(q.acceleration(t + 1.0) == 0.0)
