"""The one record every phase produces: a finding with a rule code and a file position.

Lint findings and the simulator's runtime findings are the same type: a runtime finding also
has the simulated time, the task and the program (manual 12.1 code in `error` for R001)."""

from __future__ import annotations

from enum import IntEnum

from .light_dataclass import dataclass


class Severity(IntEnum):
    """Ordered so that `severity >= fail_on` decides the exit code."""

    INFO = 1
    WARNING = 2
    ERROR = 3

    @classmethod
    def parse(cls, text: str) -> "Severity":
        try:
            return cls[text.strip().upper()]
        except KeyError:
            raise ValueError(f"unknown severity {text!r} (expected error, warning or info)") from None

    @property
    def label(self) -> str:
        return self.name.lower()


@dataclass(frozen=True, slots=True)
class Diagnostic:
    """A finding. `path` is the file the user opens; line/col are 1-based in that file.

    line == 0 means the finding concerns the whole file (e.g. it could not be read).
    `severity` is filled from the rule catalogue (and the user's configuration) before reporting.
    Runtime findings (`val3check sim`) add `time_us` (simulated microseconds), `task` and
    `program` ("" when the finding concerns the run, not a task) and, for R001, the VAL 3
    runtime error code `error`.
    """

    code: str
    message: str
    path: str
    line: int = 0
    col: int = 0
    end_line: int | None = None
    end_col: int | None = None
    severity: Severity | None = None
    time_us: int | None = None
    task: str | None = None
    program: str | None = None
    error: int | None = None
    # what `lint --fix` may do about it, for the rules whose fix is certain (val3check/fixes.py):
    # ("rename", written, declared), ("remove-element", tag)
    fix: tuple | None = None
    # the most severe it may be shown, whatever its rule's severity: a finding that depends on a
    # guess (a library found by name, F016) is at most a warning
    at_most: Severity | None = None
    # a runtime finding repeated at one place (simulation/folding.py): how many times, and the
    # simulated time of the last one (`time_us` is the first)
    count: int = 1
    last_time_us: int | None = None

    @property
    def runtime(self) -> bool:
        """A finding of `val3check sim` (it has a simulated time)."""
        return self.time_us is not None

    def shown_severity(self, severity: Severity) -> Severity:
        """`severity` (the rule's, or the configuration's), lowered to `at_most` when it is set."""
        return severity if self.at_most is None or severity <= self.at_most else self.at_most

    def sort_key(self) -> tuple:
        return (self.path, self.line, self.col, self.code, self.message)
