"""The arm as the interpreter sees it: the `Arm` port (interpretation/arm_port.py) and a
`Subsystem` of the scheduler (interpretation/subsystem.py).

`MotionlessArm` stands at its initial joint position (all zeros, or the scenario's `[robot]
joints`) for the whole run, and its motion queue is always empty: the arm of tests and tools
that need no motion. `sim` runs use `moving_arm.MovingArm`.

Units are converted here and nowhere else: the arm model (val3check.robot) works in
millimetres, an application in its own length unit (2.1.4.1, `millimeterUnit`): 25.4 mm per
inch.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from ..interpretation.arm_port import Joints, KinematicsUnsupported, Pose6, TargetUnreachable
from ..lengths import INCH_MM
from ..robot.errors import IKUnsupported, Unreachable


class UnitKinematics:
    """A `RobotModel` seen by the geometry (`geometry.arm.Kinematics`) in an application's
    length unit: poses in and out are scaled by `scale` (millimetres per unit), and so are the
    values of prismatic axes (a SCARA's joint 3)."""

    def __init__(self, model: Any, scale: float) -> None:
        """`model` seen in a unit of `scale` millimetres."""
        self.model = model
        self.scale = scale
        kinds = getattr(model, "joint_kinds", None) or ()
        self._lin = tuple(i for i, k in enumerate(kinds) if k == "prismatic") if scale != 1.0 else ()

    def _jin(self, joints):
        """Joint values in the unit into the model's (prismatic axes scaled)."""
        if not self._lin:
            return joints
        j = list(joints)
        for i in self._lin:
            if i < len(j):
                j[i] = j[i] * self.scale
        return tuple(j)

    def _jout(self, joints):
        """Joint values of the model into the unit."""
        if not self._lin:
            return joints
        j = list(joints)
        for i in self._lin:
            if i < len(j):
                j[i] = j[i] / self.scale
        return tuple(j)

    def fk(self, joints):
        """The flange pose (x, y, z in the unit, rx, ry, rz) at joints in the unit."""
        x, y, z, rx, ry, rz = self.model.fk(self._jin(joints))
        s = self.scale
        if s != 1.0:
            x, y, z = x / s, y / s, z / s
        return (x, y, z, rx, ry, rz)

    def ik(self, pose, config, near):
        """Every joint position reaching the flange pose in configuration `config`, nearest `near` first."""
        x, y, z, rx, ry, rz = pose
        s = self.scale
        try:
            sols = self.model.ik((x * s, y * s, z * s, rx, ry, rz), config=tuple(config),
                                 near=None if near is None else self._jin(near))
        except IKUnsupported as exc:
            raise KinematicsUnsupported(str(exc)) from None
        return [self._jout(j) for j in sols] if self._lin else sols

    def config_of(self, joints):
        """The configuration of a joint position (9.7.2)."""
        try:
            return self.model.config_of(self._jin(joints))
        except IKUnsupported as exc:
            raise KinematicsUnsupported(str(exc)) from None

    def in_limits(self, joints) -> bool:
        """Whether the joints are within the software limits."""
        return self.model.in_limits(self._jin(joints))


def solve_in_unit(model: Any, flange: Pose6, config: Sequence[str], millimeter_unit: bool,
                  initial: Sequence[float]) -> Joints:
    """movej's check (10.6): the joint position reaching `flange` (in the caller's length unit),
    joints in the caller's unit; raises TargetUnreachable or KinematicsUnsupported."""
    k = UnitKinematics(model, 1.0 if millimeter_unit else INCH_MM)
    x, y, z, rx, ry, rz = flange
    s = k.scale
    try:
        j = model.solve((x * s, y * s, z * s, rx, ry, rz), tuple(config), initial=k._jin(tuple(initial)))
    except Unreachable as exc:
        raise TargetUnreachable(str(exc), exc.reason) from None
    except IKUnsupported as exc:
        raise KinematicsUnsupported(str(exc)) from None
    return tuple(k._jout(tuple(j)))


class ModelArm:
    """What every arm of a run knows from its model (the model-facing half of the Arm port):
    its family, axes, limits and kinematics in the application's unit, and where it starts.
    `model` is a `val3check.robot.RobotModel` or None."""

    def __init__(self, model: Any = None) -> None:
        """The arm of `model` (None: no arm model) at all zeros."""
        self.model = model
        self.name: str | None = model.name if model is not None else None
        self._initial: Joints = (0.0,) * len(model.joint_limits) if model is not None else ()
        self._kin: dict[bool, UnitKinematics] = {}

    @property
    def has_model(self) -> bool:
        """An arm model was named (--robot, arm.cfx)."""
        return self.model is not None

    @property
    def type_family(self) -> str:
        """Rx (six-axis, or no model) or Rs (SCARA): the joint and config fields of its values."""
        return getattr(self.model, "type_family", "Rx") if self.model is not None else "Rx"

    @property
    def axes(self) -> int:
        """The number of axes."""
        return len(self.model.joint_limits)

    @property
    def joint_limits(self) -> tuple[tuple[float, float], ...]:
        """The software joint limits (degrees, mm for a prismatic axis)."""
        return tuple(self.model.joint_limits)

    def joint_limits_in(self, millimeter_unit: bool) -> tuple[tuple[float, float], ...]:
        """The joint limits with a prismatic axis in the caller's length unit."""
        k = self.kinematics(millimeter_unit)
        lim = tuple(self.model.joint_limits)
        if not k._lin:
            return lim
        return tuple(zip(k._jout(tuple(lo for lo, _ in lim)), k._jout(tuple(hi for _, hi in lim))))

    @property
    def initial_joints(self) -> Joints:
        """Where the arm starts."""
        return self._initial

    def start_at(self, joints: Sequence[float]) -> None:
        """The scenario's [robot] joints: the arm starts there."""
        self._initial = tuple(float(v) + 0.0 for v in joints)

    def kinematics(self, millimeter_unit: bool) -> UnitKinematics:
        """The kinematics in the application's unit (geometry.arm.Kinematics), made once per unit."""
        k = self._kin.get(millimeter_unit)
        if k is None:
            k = self._kin[millimeter_unit] = UnitKinematics(self.model, 1.0 if millimeter_unit else INCH_MM)
        return k

    def solve(self, flange: Pose6, config: Sequence[str], millimeter_unit: bool, initial: Sequence[float]) -> Joints:
        """movej's check: the joints reaching `flange` in `config` (solve_in_unit)."""
        return solve_in_unit(self.model, flange, config, millimeter_unit, initial)


class MotionlessArm(ModelArm):
    """See the module docstring."""

    # ---- the Arm port ----------------------------------------------------------------------------

    def joints_at(self, time_us: int, millimeter_unit: bool = True) -> Joints:
        """The initial joints: the arm never moves."""
        return self._initial  # an arm that does not move (tests, tools)

    def end_motion(self, time_us: int) -> None:
        """Nothing to wait for: nothing is ever recorded."""
        pass  # nothing is ever recorded

    def waiting_reason(self):
        """Never waiting: no motion."""
        return None

    def motion_done(self, time_us: int) -> bool:
        """Always: the queue is always empty."""
        return True  # no motion command is ever accepted: the queue is always empty

    # ---- the Subsystem ---------------------------------------------------------------------------

    def next_time(self, now_us: int) -> int | None:
        """Nothing is ever scheduled."""
        return None  # nothing ever changes

    def advance(self, to_us: int) -> None:
        """Nothing changes with time."""
        pass
