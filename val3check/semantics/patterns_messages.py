"""The codes and the wording of every S (suspicious pattern) finding, in one place.

Each rule has its catalogue entry in `rules/SXXX.toml` (summary, manual section, explanation);
the functions below only build the one-line message shown at the finding's position.
"""

from __future__ import annotations

from ..rules import codes

UNUSED_LOCAL = codes.UNUSED_LOCAL
UNUSED_PARAMETER = codes.UNUSED_PARAMETER
UNUSED_GLOBAL = codes.UNUSED_GLOBAL
UNUSED_PROGRAM = codes.UNUSED_PRIVATE_PROGRAM
READ_BEFORE_ASSIGNMENT = codes.READ_BEFORE_ASSIGNMENT
UNREACHABLE_CODE = codes.UNREACHABLE_CODE
MOVE_ID_EQUALITY = codes.MOVE_ID_EQUALITY
NUM_EQUALITY = codes.NUM_EQUALITY
CASE_WITHOUT_BREAK = codes.CASE_WITHOUT_BREAK
TRAILING_COMMENT = codes.COMMENT_AFTER_CODE
STRING_TOO_LONG = codes.STRING_TOO_LONG
WAIT_NEVER_CHANGES = codes.WAIT_NEVER_CHANGES
NESTED_FOR_SAME_COUNTER = codes.NESTED_FOR_SAME_COUNTER
BUSY_WAIT_LOOP = codes.BUSY_WAIT_LOOP
SELF_ASSIGNMENT = codes.SELF_ASSIGNMENT


def unused_local(name: str, program: str) -> str:
    return f"local variable '{name}' is declared in {program}() but never used"


def unused_parameter(name: str, program: str) -> str:
    return f"parameter '{name}' of {program}() is never used"


def unused_global(name: str, library: bool) -> str:
    if library:  # only private globals of a library are reported
        return f"private global variable '{name}' is never used by a program of the application"
    return f"global variable '{name}' is never used by a program of the application"


def unused_program(name: str) -> str:
    return f"private program {name}() is never called (call, taskCreate, taskCreateSync) in the application"


def read_before_assignment(name: str, default: str) -> str:
    return (f"local variable '{name}' is read before any value is assigned to it: "
            f"it still holds its initial value ({default}) here")


def unreachable_after(keyword: str) -> str:
    if keyword == "break":
        return "unreachable code: a case ends at its 'break' (manual 2.2.5), this statement never runs"
    return "unreachable code: this statement follows a 'return' in the same block and never runs"


def move_id_equality(op: str) -> str:
    return (f"getMoveId() compared with '{op}': the motion id grows by fractions and may never take "
            f"the exact value (manual 10.6); compare with '>=' or '<'")


def num_equality(op: str, what: str) -> str:
    return (f"'{op}' on {what}: num values carry about 14 significant digits (manual 3.2.1); "
            f"compare within a tolerance, e.g. abs(a - b) < 1e-6")


def case_without_break(keyword: str) -> str:
    return f"'{keyword}' without its 'break' (manual 2.2.5: every case and default ends with break)"


def trailing_comment() -> str:
    return "'//' after code: a comment must start its line (manual 2.2.5)"


def string_too_long(size: int, concatenation: bool, partly: bool = False) -> str:
    if concatenation:
        what = "the constant parts of this concatenation make" if partly else "this concatenation of constants makes"
        return (f"{what} {size} bytes: a string holds at most 128 bytes, "
                f"'+' keeps the first 128 (manual 3.4.1, 3.4.2)")
    return f"string constant of {size} bytes (UTF-8): a string holds at most 128 bytes (manual 3.4.1)"


def wait_never_changes(names: list[str]) -> str:
    listed = ", ".join(f"'{n}'" for n in names)
    return (f"the condition of wait() only reads {listed}, which no other task can change: "
            f"the task waits forever (or not at all)")


def nested_for_same_counter(name: str, line: int) -> str:
    return f"this for loop reuses the counter '{name}' of the enclosing for loop of line {line}"


def busy_wait_loop(keyword: str) -> str:
    return (f"busy '{keyword}' loop: nothing in it waits or yields (wait, delay, watch, get...), so the "
            f"task polls at full speed (manual 5.4); use wait(condition) or add delay(0)")


def self_assignment(text: str) -> str:
    return f"'{text}' is assigned to itself: the statement has no effect"
