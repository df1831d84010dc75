"""--out-dir: the summary in every format and each case's reports, under one folder.

    OUT/summary.txt  summary.json  junit.xml  index.html
    OUT/cases/<case name><suffix>      (worker.case_outputs: .json today)

Case names are made safe by cases.Case.name (letters, digits, `._-`); every path is still
checked to stay inside OUT before it is written, so that nothing from the input (an
application's name, a scenario's file name) can place a file elsewhere. `prepare` checks every
path the batch will write before any case runs (`cases` a folder, not a link or a file; no link
where a report goes), and writes never follow a link put there afterwards."""

from __future__ import annotations

import errno
import os

from .summary import CASES_DIR, render_html, render_json, render_junit, render_text
from .worker import CaseOutcome, CaseSummary


class OutDirError(Exception):
    pass


def inside(root: str, name: str) -> str:
    """The path of `name` under `root`; OutDirError when it would land anywhere else."""
    root_real = os.path.realpath(root)
    path = os.path.realpath(os.path.join(root_real, name))
    if os.path.commonpath([root_real, path]) != root_real or path == root_real:
        raise OutDirError(f"refused to write {name!r}: outside the output folder")
    return path


# O_NOFOLLOW: a symbolic link put in place of a file after prepare() is not followed either
_WRITE_FLAGS = os.O_WRONLY | os.O_CREAT | os.O_TRUNC | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0)
SUMMARY_FILES = ("summary.txt", "summary.json", "junit.xml", "index.html")


def _write(path: str, data: bytes) -> None:
    try:
        fd = os.open(path, _WRITE_FLAGS, 0o644)
    except OSError as exc:
        raise OutDirError(f"cannot write {_shown(path)}: {_why(exc)}") from None
    with os.fdopen(fd, "wb") as fh:
        fh.write(data)


def _shown(path: str) -> str:
    from ..lint import display_path

    return display_path(path)


def _why(exc: OSError) -> str:
    return "a symbolic link is there (not followed)" if exc.errno == errno.ELOOP else (exc.strerror or str(exc))


def write_case(out_dir: str, outcome: CaseOutcome) -> list[str]:
    """Write one case's reports as soon as it ends; the file names written."""
    folder = inside(out_dir, CASES_DIR)
    try:
        os.makedirs(folder, exist_ok=True)
    except OSError as exc:
        raise OutDirError(f"cannot create {_shown(folder)}: {exc.strerror or exc}") from None
    written = []
    for suffix, data in sorted(outcome.files().items()):
        name = outcome.summary.name + suffix
        _write(inside(folder, name), data)
        written.append(name)
    return written


def write_summaries(out_dir: str, summaries: list[CaseSummary], reports: set[str], tool_version: str) -> None:
    """`reports`: the file names written under cases/ (write_case), that the index links to."""
    texts = (render_text(summaries), render_json(summaries, tool_version), render_junit(summaries),
             render_html(summaries, reports, tool_version, index_dir=out_dir))
    for name, text in zip(SUMMARY_FILES, texts, strict=True):
        _write(inside(out_dir, name), text.encode("utf-8"))


def prepare(out_dir: str, case_files: list[str] = ()) -> None:
    """Make the output folder and check, before any case runs, every path the batch will write:
    `cases` a folder of its own (not a symbolic link, not a file), the summaries and each case's
    reports (`case_files`: names under cases/) absent or regular files, never links."""
    try:
        os.makedirs(out_dir, exist_ok=True)  # named by the user: may be a link the user made
    except (OSError, ValueError) as exc:
        raise OutDirError(f"cannot create {_shown(out_dir)}: {getattr(exc, 'strerror', None) or exc}") from None
    if not os.path.isdir(out_dir):
        raise OutDirError(f"{_shown(out_dir)} is not a folder")
    cases = os.path.join(out_dir, CASES_DIR)
    if os.path.islink(cases):
        raise OutDirError(f"{_shown(cases)} is a symbolic link: the case reports are written in a folder of"
                          f" {_shown(out_dir)}, never through a link (remove it, or choose another --out-dir)")
    if os.path.lexists(cases) and not os.path.isdir(cases):
        raise OutDirError(f"{_shown(cases)} exists and is not a folder (remove it, or choose another --out-dir)")
    try:
        os.makedirs(cases, exist_ok=True)
    except OSError as exc:
        raise OutDirError(f"cannot create {_shown(cases)}: {exc.strerror or exc}") from None
    for path in [os.path.join(out_dir, n) for n in SUMMARY_FILES] + [os.path.join(cases, n) for n in case_files]:
        if os.path.islink(path):
            raise OutDirError(f"{_shown(path)} is a symbolic link: not written through (remove it)")
        if os.path.lexists(path) and not os.path.isfile(path):
            raise OutDirError(f"{_shown(path)} exists and is not a regular file (remove it)")


def write_file(out_dir: str, name: str, data: bytes) -> str:
    """Write `name` (a relative path) under `out_dir`, never outside it nor through a link at its
    place; its folders are made. The path written."""
    path = inside(out_dir, name)
    try:
        os.makedirs(os.path.dirname(path), exist_ok=True)
    except OSError as exc:
        raise OutDirError(f"cannot create {_shown(os.path.dirname(path))}: {exc.strerror or exc}") from None
    _write(path, data)
    return path
