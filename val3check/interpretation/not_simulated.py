"""What the simulator does not simulate stops the task on its line: never an invented result.

`SimLimit` is raised by the generated code (`ARM`, `NOTSIM`, for the instructions the
registry has no handler for, registry.py) or by a handler (chapter 9 without an arm model);
the machine stops the task, as if suspended, and reports R002 (`kind` "arm": the arm, its
motion or its hardware) or R004 ("notsim": anything else).
"""

from __future__ import annotations

from typing import Any

from ..rules import codes

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


NO_ARM = ("needs an arm model: --robot NAME (`val3check robots` lists them) or --robot arm.urdf, or run the "
          "application from a controller tree whose usr/configs/arm.cfx names the arm")
HARDWARE = frozenset({"setlatch", "getlatch", "getdh", "getdefaultdh", "setdh"})
OPTIONS = {"movejf": "compliance", "movelf": "compliance", "iscompliant": "compliance", "altermovej": "alter",
           "altermovel": "alter", "altermovec": "alter", "alterbegin": "alter", "alterend": "alter", "alter": "alter",
           "alterstoptime": "alter", "resetturn": "continuous axis"}


def limit_code(kind: str) -> str:
    """The rule of a task the simulator cannot go on with: R002 (the arm) or R004 (anything else)."""
    return codes.ARM_NOT_SIMULATED if kind == ARM_LIMIT else codes.NOT_SIMULATED


def arm_message(what: str, arm_name: str | None) -> str:
    """R002: why the arm instruction stops the task, in a few words, and what would let it run."""
    low = what.lower()
    if low in HARDWARE:
        return f"{what} needs the arm's hardware (position capture, calibration): not simulated"
    if low in OPTIONS:
        return f"{what} (the {OPTIONS[low]} option, chapter 11) is not simulated"
    if arm_name is None:
        return f"{what} {NO_ARM}"
    return f"{what} is not simulated"


def ARM(name: str, *args: Any) -> Any:
    raise SimLimit(ARM_LIMIT, name)


def NOTSIM(what: str) -> Any:
    raise SimLimit(OTHER_LIMIT, what)


# the value a `$` call the simulator does not run gives, by the type its value is used as
SYSTEM_DEFAULTS = {"num": 0.0, "bool": False, "string": "", "": None}


def SYSTEM(task, name: str, text: str, used: str, why: str = "") -> Any:
    """A `$name()` instruction of the system library that the simulator does not run
    (undocumented, or called with other arguments than the form it runs): the call is recorded
    in the transcript (kind "system"), an info says so once per line (R041), and the line goes on;
    a value used is the default of its type (0, false, "")."""
    value = SYSTEM_DEFAULTS[used]
    machine = task.machine
    machine.transcript_add(task, "system", text, None)
    shown = {"num": "0", "bool": "false", "string": '""'}.get(used)
    machine.note_outside(task, f"{name}: an undocumented instruction of the system library that the simulator does "
                               f"not run{' (' + why + ')' if why else ''}; the line goes on without it"
                               + (f", and its value is {shown}" if shown else ""))
    return value


def register(registry) -> None:
    registry.helpers(ARM=ARM, NOTSIM=NOTSIM, SYSTEM=SYSTEM)
