"""--out-dir: the summary in every format and each case's reports, under one folder.

    OUT/summary.txt  summary.json  junit.xml  index.html
    OUT/cases/<case name><suffix>      (worker.case_outputs: .json today)

Case names are made safe by cases.Case.name (letters, digits, `._-`); every path is still
checked to stay inside OUT before it is written, so that nothing from the input (an
application's name, a scenario's file name) can place a file elsewhere."""

from __future__ import annotations

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


def _write(path: str, data: bytes) -> None:
    with open(path, "wb") as fh:
        fh.write(data)


def write_case(out_dir: str, outcome: CaseOutcome) -> list[str]:
    """Write one case's reports as soon as it ends; the file names written."""
    folder = inside(out_dir, CASES_DIR)
    os.makedirs(folder, exist_ok=True)
    written = []
    for suffix, data in sorted(outcome.files().items()):
        name = outcome.summary.name + suffix
        _write(inside(folder, name), data)
        written.append(name)
    return written


def write_summaries(out_dir: str, summaries: list[CaseSummary], reports: set[str], tool_version: str) -> None:
    """`reports`: the file names written under cases/ (write_case), that the index links to."""
    for name, text in (("summary.txt", render_text(summaries)), ("summary.json", render_json(summaries, tool_version)),
                       ("junit.xml", render_junit(summaries)),
                       ("index.html", render_html(summaries, reports, tool_version, index_dir=out_dir))):
        _write(inside(out_dir, name), text.encode("utf-8"))


def prepare(out_dir: str) -> None:
    try:
        os.makedirs(out_dir, exist_ok=True)
    except OSError as exc:
        raise OutDirError(f"cannot create {out_dir}: {exc.strerror or exc}") from None
    if not os.path.isdir(out_dir):
        raise OutDirError(f"{out_dir} is not a folder")
