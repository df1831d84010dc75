"""What a lint run hands to the reporters."""

from __future__ import annotations

from .diagnostics import Diagnostic
from .light_dataclass import dataclass, field
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
    # display path -> text read from elsewhere than the disk (--stdin-filename, an editor's
    # unsaved buffer): quoted instead of the file
    sources: dict[str, bytes] = field(default_factory=dict)
    fail_on: str = "error"  # what fails the build (JUnit failures, the exit code)
    # the folder the CI formats (SARIF, github) make paths relative to: the repository root
    # (git top level), else the configuration's folder; "" -> the current folder
    root: str = ""
    baselined: int = 0  # findings hidden because the baseline file records them
