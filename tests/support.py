"""Helpers for tests: write applications as Stäubli's tools save them, and lint them in-process."""

from __future__ import annotations

import os
from pathlib import Path

from val3check.config import Settings
from val3check.lint import LintRun, run

PJX = """<?xml version="1.0" encoding="utf-8"?>
<Project xmlns="http://www.staubli.com/robotics/VAL3/Project/3">
  <Parameters version="s7.11" stackSize="5000" millimeterUnit="true" />
  <Programs>
    <Program file="start.pgx" />
    <Program file="stop.pgx" />
  </Programs>
  <Database>
    <Data file="{name}.dtx" />
  </Database>
  <Libraries />
</Project>
"""

DTX = """<?xml version="1.0" encoding="utf-8"?>
<Database xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xmlns="http://www.staubli.com/robotics/VAL3/Data/2">
  <Datas />
</Database>
"""

PGX_HEAD = """<?xml version="1.0" encoding="utf-8"?>
<Programs xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xmlns="http://www.staubli.com/robotics/VAL3/Program/2">
  <Program name="{name}" access="public">
"""
CODE_OPEN = "    <Code><![CDATA["
PGX_TAIL = """]]></Code>
  </Program>
</Programs>
"""

# Line of the .pgx holding the first code line ("begin"), and column where the code starts.
CODE_FIRST_LINE = PGX_HEAD.count("\n") + 1
CODE_FIRST_COL = len(CODE_OPEN) + 1


def program_file(name: str, code: str) -> str:
    return PGX_HEAD.format(name=name) + CODE_OPEN + code.rstrip("\n") + PGX_TAIL


def write_app(root: Path, code: str, name: str = "Example") -> Path:
    """An s7 application whose start() holds `code`; returns its folder."""
    folder = root / name
    folder.mkdir(parents=True, exist_ok=True)
    (folder / f"{name}.pjx").write_text(PJX.format(name=name), encoding="utf-8")
    (folder / f"{name}.dtx").write_text(DTX, encoding="utf-8")
    (folder / "start.pgx").write_text(program_file("start", code), encoding="utf-8")
    (folder / "stop.pgx").write_text(program_file("stop", "begin\nend\n"), encoding="utf-8")
    return folder


def write_files(root: Path, files: dict[str, str | bytes]) -> None:
    for rel, content in files.items():
        target = root / rel
        target.parent.mkdir(parents=True, exist_ok=True)
        if isinstance(content, bytes):
            target.write_bytes(content)
        else:
            target.write_bytes(content.encode("utf-8"))


def code_position(line: int, col: int) -> tuple[int, int]:
    """Where line/col of a `write_app` snippet land in start.pgx."""
    return CODE_FIRST_LINE + line - 1, (CODE_FIRST_COL + col - 1) if line == 1 else col


def lint(paths: list[str | Path], settings: Settings | None = None, cwd: Path | None = None) -> LintRun:
    old = os.getcwd()
    if cwd is not None:
        os.chdir(cwd)
    try:
        return run([str(p) for p in paths], settings or Settings())
    finally:
        os.chdir(old)
