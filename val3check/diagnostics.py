"""The one record every phase produces: a finding with a rule code and a file position."""

from __future__ import annotations

from .records import dataclass
from enum import IntEnum


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
    """

    code: str
    message: str
    path: str
    line: int = 0
    col: int = 0
    end_line: int | None = None
    end_col: int | None = None
    severity: Severity | None = None

    def sort_key(self) -> tuple:
        return (self.path, self.line, self.col, self.code, self.message)
