"""What the motion core reports: typed records with the command's position, time and numbers.

A `Finding` is one motion diagnostic (rule family R, codes R010-R029): the rule code, its
default severity, a message in the user's terms, the source position of the motion instruction,
the simulated time, the task, and `data` (the numbers behind the message: axis, amount, distance,
speeds...). `error` is the runtime error of 12.1 the controller raises for it, if any: at the
motion instruction (`MotionError` is raised at once), or 150 on the next motion instruction,
waitEndMove, open or close when an already recorded command cannot be executed.
"""

from __future__ import annotations

from typing import Any

from ..light_dataclass import dataclass, field
from ..rules import codes

# The motion rules (rules/R0xx.toml describe them).
UNREACHABLE = codes.TARGET_OUT_OF_REACH  # no joint position reaches a target (or a point of the path)
JOINT_LIMIT = codes.JOINT_LIMIT  # a joint target or a path outside the software joint limits
CONFIG_CHANGE = codes.CONFIGURATION_CHANGE  # a configuration change imposed in movel/movec (10.1.4.2)
SINGULAR_STOP = codes.PATH_THROUGH_SINGULARITY  # a Cartesian path through a singularity: it cannot be followed
SINGULAR_SLOW = codes.NEAR_SINGULARITY  # a Cartesian path near a singularity: the TCP slows far below its speed
CIRCLE = codes.CIRCLE_UNDEFINED  # movec: arc undefined or orientation ambiguous (10.1.4.1)
NO_OP = codes.MOVEJ_NO_OP  # movej to the position it starts from
MDESC = codes.INVALID_MDESC  # invalid motion descriptor field (12.1: 100-106)
NO_POWER = codes.MOTION_WITHOUT_POWER  # a task waits for a motion that arm power never allows
FALLBACK = codes.SLOW_SAFE_PROFILE  # the time-optimal parameterisation failed: a slower safe profile was used

SEVERITY = {
    UNREACHABLE: "error", JOINT_LIMIT: "error", CONFIG_CHANGE: "error", SINGULAR_STOP: "error",
    SINGULAR_SLOW: "warning", CIRCLE: "error", NO_OP: "info", MDESC: "error", NO_POWER: "error",
    FALLBACK: "warning",
}


@dataclass(frozen=True)
class Source:
    """Where a motion instruction is written: the file the user opens, 1-based line and column,
    the program and the task that executed it."""

    path: str = ""
    line: int = 0
    col: int = 0
    program: str = ""
    task: str = ""

    def label(self) -> str:
        """Where, in a message: the file's name and the line."""
        name = self.path.replace("\\", "/").rsplit("/", 1)[-1]
        return f"{name}:{self.line}" if name else f"line {self.line}"


@dataclass(frozen=True)
class Finding:
    """One motion diagnostic (module docstring): code, message, source, simulated time, the identifier, the runtime error that goes with it, the numbers (`data`)."""
    code: str
    message: str
    source: Source
    time: float  # simulated seconds
    move_id: float | None = None
    error: int | None = None  # runtime error of 12.1 that goes with it (154, 150, 100-106, 70)
    data: dict[str, Any] = field(default_factory=dict)

    @property
    def severity(self) -> str:
        """The rule's default severity (rules/R0xx.toml)."""
        return SEVERITY.get(self.code, "error")

    @property
    def task(self) -> str:
        """The task that executed the instruction."""
        return self.source.task


class MotionError(Exception):
    """A motion instruction stops its task with the runtime error `code` of 12.1; `finding` is the
    motion diagnostic behind it (None for 150, whose finding was reported with the command that
    could not be executed)."""

    def __init__(self, code: int, message: str, finding: Finding | None = None):
        """`code` (12.1), the message, and the finding behind it."""
        super().__init__(message)
        self.code = code
        self.message = message
        self.finding = finding
