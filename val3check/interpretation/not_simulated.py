"""What the simulator does not simulate stops the task on its line: never an invented result.

`SimLimit` is raised by the generated code (`ARM`, `NOTSIM`, for the instructions the
registry has no handler for, registry.py) or by a handler (chapter 9 without an arm model);
the machine stops the task, as if suspended, and reports R002 (`kind` "arm": the arm, its
motion or its hardware) or R004 ("notsim": anything else).
"""

from __future__ import annotations

from typing import Any

ARM_LIMIT = "arm"  # R002
OTHER_LIMIT = "notsim"  # R004


class SimLimit(Exception):
    """The simulator cannot go on with this task: `kind` ARM_LIMIT (R002) or OTHER_LIMIT (R004).
    `message` is the diagnostic's text (default: made by the machine from `what`)."""

    def __init__(self, kind: str, what: str, message: str = "") -> None:
        super().__init__(what)
        self.kind = kind
        self.what = what
        self.message = message


NO_ARM = ("needs the arm model: pass --robot NAME (a catalogue arm such as tx2-60, listed by `val3check robots`), "
          "--robot path/to/arm.urdf, or run the application from a controller tree whose usr/configs/arm.cfx "
          "names the arm")
HARDWARE = frozenset({"setlatch", "getlatch", "getdh", "getdefaultdh", "setdh"})


def arm_message(what: str, arm_name: str | None) -> str:
    """R002: why the arm instruction stops the task, and (without an arm model) how to give one."""
    if what.lower() in HARDWARE:
        return f"instruction {what} needs the arm's hardware (position capture, calibration), which this " \
               f"version does not simulate"
    text = f"instruction {what} moves the arm or reads its motion, which this version does not simulate (chapter 10)"
    if arm_name is None:
        return f"{text}; the run has no arm model either (to have movej targets checked, " \
               f"{NO_ARM[len('needs the arm model: '):]})"
    return f"{text}; the arm model {arm_name} stays at its initial joint position"


def ARM(name: str, *args: Any) -> Any:
    raise SimLimit(ARM_LIMIT, name)


def NOTSIM(what: str) -> Any:
    raise SimLimit(OTHER_LIMIT, what)


def register(registry) -> None:
    registry.helpers(ARM=ARM, NOTSIM=NOTSIM)
