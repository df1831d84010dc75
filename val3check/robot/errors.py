"""Errors of the robot package (all derive from RobotError, a ValueError)."""

from __future__ import annotations


class RobotError(ValueError):
    """A robot could not be loaded or used: unknown name, bad URDF, missing metadata…"""


class IKUnsupported(RobotError):
    """The arm has no closed-form inverse kinematics here (not ortho-parallel with a spherical wrist)."""


class Unreachable(RobotError):
    """No joint position reaches a pose (out of reach, out of the joint limits, or not in the
    requested configuration). `reason` is one of "reach", "limits", "config"."""

    def __init__(self, message: str, reason: str):
        super().__init__(message)
        self.reason = reason
