"""Lint in-process from a given folder (display paths are relative to the current folder).
Applications are written with `val3check.testing`."""

from __future__ import annotations

import os
from pathlib import Path

from val3check.config import Settings
from val3check.lint import LintRun, run


def lint(paths: list[str | Path], settings: Settings | None = None, cwd: Path | None = None) -> LintRun:
    old = os.getcwd()
    if cwd is not None:
        os.chdir(cwd)
    try:
        return run([str(p) for p in paths], settings or Settings())
    finally:
        os.chdir(old)
