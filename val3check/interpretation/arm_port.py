"""Where the arm's position comes from: the port through which the interpreter reads the arm.

Chapter 9 (`here()`, `herej()`, `jointToPoint()`, `pointToJoint()`, `config()`, `isInRange()`),
the end of motion that `open()`/`close()` wait for (9.5.4), and the instructions of chapter 10
read the arm only through this protocol. `val3check.simulation.moving_arm` implements it over
the motion queue of `val3check.motion` (the arm's state as a function of simulated time); the
interpreter never imports `motion`.

Units are converted in one place, the port: the arm model works in millimetres, an
application in its own length unit (`millimeterUnit`, 2.1.4.1); callers say which unit they
work in (`millimeter_unit`) and get poses in it. Angles are degrees. Joint positions are
tuples of floats (degrees, or length units for linear axes).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Protocol, runtime_checkable

from ..geometry.arm import Kinematics

Joints = tuple[float, ...]
Pose6 = tuple[float, float, float, float, float, float]  # x, y, z, rx, ry, rz


class KinematicsUnsupported(Exception):
    """The arm model has no closed-form inverse kinematics (or configurations): the instruction
    that needs them cannot be simulated (R002)."""


class TargetUnreachable(Exception):
    """No joint position of the arm reaches the target within the joint limits in the wanted
    configuration (`reason`: "reach", "limits" or "config")."""

    def __init__(self, message: str, reason: str = "reach") -> None:
        super().__init__(message)
        self.reason = reason


@runtime_checkable
class Arm(Protocol):
    name: str | None
    """The arm model's name (TX2-60...); None when the run has no arm model: then only
    `has_model`, `motion_done`, `initial_joints` (empty) and `start_at` may be used."""

    @property
    def has_model(self) -> bool: ...

    @property
    def type_family(self) -> str:
        """ "Rx" (six-axis RX/TX arms, and without an arm model) or "Rs" (SCARA RS/TS arms): the
        fields of joint and config values (9.7.2); a value of the other family is error 81."""
        ...

    @property
    def axes(self) -> int: ...

    @property
    def joint_limits(self) -> tuple[tuple[float, float], ...]: ...

    def joint_limits_in(self, millimeter_unit: bool) -> tuple[tuple[float, float], ...]:
        """The software joint limits with a prismatic axis (a SCARA's joint 3) in the caller's
        length unit (isInRange)."""
        ...

    @property
    def initial_joints(self) -> Joints:
        """Where the arm stands when the run starts."""
        ...

    def start_at(self, joints: Sequence[float]) -> None:
        """The initial commanded position (the scenario's `[robot] joints`)."""
        ...

    def joints_at(self, time_us: int, millimeter_unit: bool = True) -> Joints:
        """The commanded joint position at a simulated time (herej(), here(), 9.2.3/9.6.3), a
        prismatic axis in the caller's length unit."""
        ...

    def kinematics(self, millimeter_unit: bool) -> Kinematics:
        """The model's kinematics for the geometry (`geometry.arm`), lengths in the caller's
        unit. Its methods raise KinematicsUnsupported for what the model cannot compute."""
        ...

    def solve(self, flange: Pose6, config: Sequence[str], millimeter_unit: bool, initial: Sequence[float]) -> Joints:
        """The joint position that puts the flange at `flange` (in the caller's unit) in
        configuration `config` (`same` relative to `initial`), nearest `initial`; raises
        TargetUnreachable or KinematicsUnsupported (movej's check, 10.6)."""
        ...

    def motion_done(self, time_us: int) -> bool:
        """The motion queue is empty at that time: the last motion command has ended
        (waitEndMove(), and open()/close() before they act, 9.5.4)."""
        ...

    def end_motion(self, time_us: int) -> None:
        """What waitEndMove() does before it waits, and open()/close() before they act (9.5.4,
        10.6): cancel the blend of the last command; raise Val3RuntimeError(150) when a motion
        recorded before cannot be executed."""
        ...

    def waiting_reason(self) -> tuple[str, str] | None:
        """Why recorded motion cannot go on, for the report of a task waiting for it: (rule
        code, words naming the condition and the scenario key or instruction that changes it),
        or None."""
        ...
