"""What a lint run hands to the reporters."""

from __future__ import annotations

from .records import dataclass, field

from .diagnostics import Diagnostic
from .rules.catalogue import Rule


@dataclass(slots=True)
class LintResult:
    diagnostics: list[Diagnostic]  # severity filled in, sorted by Diagnostic.sort_key
    files: list[str]  # every file examined (display paths), sorted
    applications: list[str]  # every application checked (display paths), sorted
    rules: dict[str, Rule] = field(default_factory=dict)  # the catalogue, by code
    tool_version: str = ""
    # the files the run read as VAL 3, display path -> path on disk: the only ones a report may
    # quote (None: any file, for results built by hand)
    quotable: dict[str, str] | None = None
