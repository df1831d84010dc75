"""The summary of a batch: one line per case, sorted by case (application, arm, scenario,
cell, overrides), in text, JSON, JUnit XML and an HTML index. Deterministic byte for byte: no
wall-clock figure, no absolute path that the cases did not name."""

from __future__ import annotations

import html
import json
import os
import re
import xml.etree.ElementTree as ET
from collections import Counter
from urllib.parse import quote

from ..reporting._common import printable, visible
from ..reporting.junit import document, testcase, xml_text
from .worker import VERDICTS, CaseSummary

SUMMARY_VERSION = 1
CASES_DIR = "cases"  # under --out-dir: the per-case reports


def natural(value):
    """A sort key that orders the numbers inside texts as numbers (`tx2-60` before `tx2-140`,
    `ms50.toml` before `ms100.toml`), numbers as numbers, and tuples element by element."""
    if isinstance(value, tuple):
        return tuple(natural(v) for v in value)
    if isinstance(value, str):
        return tuple((0, int(t), "") if t.isdigit() else (1, 0, t) for t in re.split(r"(\d+)", value) if t)
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return ((0, value, ""),)
    return ((2, 0, repr(value)),)


def ordered(summaries: list[CaseSummary]) -> list[CaseSummary]:
    """The cases in the order of their key (application, arm, scenario, cell, overrides), numbers
    in natural order."""
    return sorted(summaries, key=lambda s: natural(s.key))


def counts(summaries: list[CaseSummary]) -> dict[str, int]:
    c = Counter(s.verdict for s in summaries)
    return {v: c[v] for v in VERDICTS if c[v]}


def _headline(summaries: list[CaseSummary]) -> str:
    n = len(summaries)
    parts = ", ".join(f"{k} {v}" for k, v in counts(summaries).items())
    return f"val3check sim: {n} case{'s' if n != 1 else ''}" + (f" ({parts})" if parts else "")


def _overrides(s: CaseSummary) -> str:
    return " ".join(f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}" for k, v in s.overrides)


def _cycle(s: CaseSummary) -> str:
    if s.cycle_time is None:
        return "-"
    spread = "" if s.cycle_range is None else f", {s.cycle_range[0]:.3f}–{s.cycle_range[1]:.3f} s if accelerations off 2×"
    return f"{s.cycle_time:.3f} s ({s.cycles} cycle{'s' if s.cycles != 1 else ''}{spread})"


def _row(s: CaseSummary) -> list[str]:
    return [s.verdict, s.app, s.arm or f"({s.model})", s.scenario or "-", s.cell or "-", _overrides(s) or "-",
            str(s.errors), _cycle(s)]


HEADERS = ["verdict", "application", "arm", "scenario", "cell", "overrides", "errors", "cycle time"]


def render_text(summaries: list[CaseSummary]) -> str:
    """A table (columns aligned), then the reason of each case that did not pass."""
    rows = [HEADERS] + [_row(s) for s in ordered(summaries)]
    keep = [i for i in range(len(HEADERS)) if i not in (4, 5) or any(r[i] != "-" for r in rows[1:])]
    widths = [max(len(r[i]) for r in rows) for i in keep]
    lines = ["  ".join(r[i].ljust(w) for i, w in zip(keep, widths, strict=True)).rstrip() for r in rows]
    out = [_headline(summaries), ""] + lines
    failed = [s for s in ordered(summaries) if s.verdict != "pass"]
    if failed:
        out += ["", "why:"]
        out += [f"  {s.verdict}: {s.app} | {s.arm or s.model} | {s.scenario or '-'}"
                + (f" | {s.cell}" if s.cell else "") + (f" | {_overrides(s)}" if s.overrides else "")
                + f": {s.reason or 'no reason recorded'}" for s in failed]
    return printable("\n".join(out), keep_newlines=True) + "\n"  # control characters of names visible


def render_json(summaries: list[CaseSummary], tool_version: str) -> str:
    body = {"version": SUMMARY_VERSION, "tool": {"name": "val3check", "version": tool_version},
            "counts": counts(summaries), "cases": [s.as_dict() for s in ordered(summaries)]}
    return json.dumps(body, indent=2, sort_keys=True, ensure_ascii=True) + "\n"


def render_junit(summaries: list[CaseSummary]) -> str:
    """One <testcase> per case: classname the application, name the arm, scenario, cell and
    overrides; a failing run is a <failure>, a case not run, crashed or stopped by the watchdog
    an <error>, a case left by --fail-fast <skipped>. Written by reporting/junit.py."""
    c = counts(summaries)
    errors = c.get("not-run", 0) + c.get("crash", 0) + c.get("over-budget", 0)
    cases = []
    for s in ordered(summaries):
        name = " | ".join(x for x in (s.arm or f"({s.model})", s.scenario or "no scenario", s.cell, _overrides(s)) if x)
        case = testcase(s.app, name, time=False)
        reason = xml_text(s.reason or s.verdict)
        if s.verdict == "fail":
            ET.SubElement(case, "failure", {"type": "fail", "message": reason}).text = reason
        elif s.verdict in ("not-run", "crash", "over-budget"):
            ET.SubElement(case, "error", {"type": s.verdict, "message": reason}).text = reason
        elif s.verdict == "skipped":
            ET.SubElement(case, "skipped", {"message": reason})
        props = f"errors {s.errors}, cycle time {_cycle(s)}, model {s.model}"
        if s.verdict in ("pass", "fail"):  # a run, so a report (under --out-dir)
            props += f", report {CASES_DIR}/{s.name}.json"
        ET.SubElement(case, "system-out").text = xml_text(props)
        cases.append(case)
    total = {"tests": str(len(summaries)), "failures": str(c.get("fail", 0)), "errors": str(errors),
             "skipped": str(c.get("skipped", 0))}
    return document("val3check sim", cases, total, ascii_only=False)


_STYLE = """body{font:14px system-ui,sans-serif;margin:1.5em;color:#222}
table{border-collapse:collapse;width:100%}
th,td{border:1px solid #ccc;padding:.25em .5em;text-align:left;vertical-align:top}
th{background:#f3f3f3;white-space:nowrap}td.n{text-align:right}.nw{white-space:nowrap}
td.path{overflow-wrap:anywhere;min-width:8em}tr.why td{overflow-wrap:anywhere;color:#555;font-size:12px;border-top:0}
tr.case.with-why td{border-bottom:0}
.pass{color:#176117}.fail,.crash,.not-run{color:#a11;font-weight:600}.skipped{color:#777}"""


def _linked(shown: str, index_dir: str | None) -> str:
    """A path of a case as the index shows it: relative to the index's folder (so that the
    index and what it names move together), a link to the file."""
    e = html.escape
    if not shown or shown in ("-", "none") or index_dir is None:
        return e(shown)
    rel = os.path.relpath(os.path.abspath(shown), os.path.abspath(index_dir)).replace(os.sep, "/")
    return f'<a href="{e(quote(rel))}">{e(rel)}</a>'


def render_html(summaries: list[CaseSummary], reports: set[str], tool_version: str,
                index_dir: str | None = None) -> str:
    """A self-contained page (no script, no remote resource); every text from a case escaped;
    each case links to its reports under cases/ that were written (`reports`: file names): the
    HTML page, the JSON report, the MCAP trace. `index_dir`: the folder the page is written in;
    the application, scenario and cell are then links relative to it. Columns no case fills
    (cell, overrides) are left out; the reason of a case that did not pass is a row of its own
    under it, as wide as the table."""
    e = html.escape
    cases = ordered(summaries)
    table = [_row(s) for s in cases]
    keep = [i for i in range(1, len(HEADERS)) if i not in (4, 5) or any(r[i] != "-" for r in table)]
    rows = []
    for s, cells in zip(cases, table):
        css = "over-budget crash" if s.verdict == "over-budget" else s.verdict  # shown as a crash is
        out = [f'<td class="{e(css)} nw">{e(s.verdict)}</td>']
        for i in keep:
            if i in (1, 3, 4):
                out.append(f'<td class="path">{_linked(cells[i], index_dir)}</td>')
            elif i in (6, 7):
                out.append(f'<td class="n">{e(cells[i])}</td>')
            else:
                out.append(f'<td class="nw">{e(cells[i])}</td>')
        links = [f'<a href="{e(CASES_DIR + "/" + quote(s.name + suffix))}">{label}</a>'
                 for suffix, label in ((".html", "page"), (".json", "JSON"), (".mcap", "trace"))
                 if s.name + suffix in reports]
        out.append(f'<td class="nw">{" · ".join(links) or "-"}</td>')
        rows.append(f'<tr class="case{" with-why" if s.reason else ""}">' + "".join(out) + "</tr>")
        if s.reason:  # on its own row under the case, as wide as the table: never cut
            rows.append(f'<tr class="why"><td colspan="{len(keep) + 2}">{e(s.reason)}</td></tr>')
    heads = [HEADERS[0]] + [HEADERS[i] for i in keep] + ["report"]
    head = "".join(f"<th>{e(h)}</th>" for h in heads)
    return visible("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
            "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; style-src 'unsafe-inline'\">"
            f"<title>val3check sim batch</title><style>{_STYLE}</style></head><body>\n"
            f"<h1>{e(_headline(summaries))}</h1>\n<p>val3check {e(tool_version)}</p>\n"
            f"<table><thead><tr>{head}</tr></thead><tbody>\n" + "\n".join(rows)
            + "\n</tbody></table>\n</body></html>\n")  # control characters: parse errors in HTML
