"""Runtime errors of the virtual controller, with the codes of manual 12.1.

Instructions raise `Val3RuntimeError(code, detail)`; the scheduler stops the task that executed
the line, records the code (as `taskStatus()` reports it, 5.2) and a diagnostic with task,
program, file, line and simulated time.
"""

from __future__ import annotations

# Manual 12.1, described in our own words.
RUNTIME_CODES: dict[int, str] = {
    10: "invalid numeric computation (division by zero)",
    11: "invalid numeric computation (e.g. ln(-1))",
    20: "array index beyond the size of the array",
    21: "negative array index",
    29: "invalid task name",
    30: "no VAL 3 task has this name",
    31: "a task with this name already exists",
    32: "only two different periods of synchronous tasks are supported",
    40: "not enough system memory",
    41: "not enough execution memory for the task (stack size)",
    60: "maximum execution time of the instruction exceeded",
    61: "internal error of the VAL 3 interpreter",
    70: "invalid instruction parameter value",
    80: "data or program of a library that is not loaded",
    81: "incompatible kinematics: point/joint/config not compatible with the arm",
    82: "reference frame or tool of a variable belongs to a library that is not accessible",
    90: "the task cannot resume at the requested place",
    100: "invalid speed in the motion descriptor",
    101: "invalid acceleration in the motion descriptor",
    102: "invalid deceleration in the motion descriptor",
    103: "invalid translation speed in the motion descriptor",
    104: "invalid rotation speed in the motion descriptor",
    105: "invalid reach in the motion descriptor",
    106: "invalid leave in the motion descriptor",
    122: "write to a system input",
    123: "dio, aio or sio not linked to a system input/output",
    124: "access to a protected system input/output",
    125: "read or write error on a dio, aio or sio (field bus error)",
    150: "a previous motion could not be completed",
    153: "motion command not supported",
    154: "invalid motion instruction: check the motion descriptor",
    160: "invalid coordinates of the flange tool",
    161: "invalid coordinates of the world frame",
    162: "point without a reference frame",
    163: "frame without a reference frame",
    164: "tool without a reference tool",
    165: "invalid reference frame or tool (global linked to a local)",
    250: "no runtime licence for this instruction",
}


class Val3RuntimeError(Exception):
    """An instruction could not complete: the task stops with `code` (manual 12.1)."""

    def __init__(self, code: int, detail: str = "", rule: str | None = None) -> None:
        self.code = code
        self.detail = detail
        self.rule = rule  # the rule of the diagnostic when not R001 (a motion instruction's cause)
        text = RUNTIME_CODES.get(code, "runtime error")
        super().__init__(f"error {code}: {text}" + (f": {detail}" if detail else ""))
