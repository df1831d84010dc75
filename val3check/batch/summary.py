"""The summary of a batch: one line per case, sorted by case (application, arm, scenario,
cell, overrides), in text, JSON, JUnit XML and an HTML index. Deterministic byte for byte: no
wall-clock figure, no absolute path that the cases did not name."""

from __future__ import annotations

import html
import json
from collections import Counter
from urllib.parse import quote
from xml.sax.saxutils import escape, quoteattr

from ..reporting._common import printable, visible
from .worker import VERDICTS, CaseSummary

SUMMARY_VERSION = 1
CASES_DIR = "cases"  # under --out-dir: the per-case reports


def ordered(summaries: list[CaseSummary]) -> list[CaseSummary]:
    return sorted(summaries, key=lambda s: s.key)


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
    an <error>, a case left by --fail-fast <skipped>."""
    c = counts(summaries)
    errors = c.get("not-run", 0) + c.get("crash", 0) + c.get("over-budget", 0)
    out = ['<?xml version="1.0" encoding="UTF-8"?>',
           f'<testsuites name="val3check sim" tests="{len(summaries)}" failures="{c.get("fail", 0)}"'
           f' errors="{errors}" skipped="{c.get("skipped", 0)}">',
           f'  <testsuite name="val3check sim" tests="{len(summaries)}" failures="{c.get("fail", 0)}"'
           f' errors="{errors}" skipped="{c.get("skipped", 0)}">']
    for s in ordered(summaries):
        name = " | ".join(x for x in (s.arm or f"({s.model})", s.scenario or "no scenario", s.cell, _overrides(s)) if x)
        out.append(f"    <testcase classname={quoteattr(s.app)} name={quoteattr(name)}>")
        reason = s.reason or s.verdict
        if s.verdict == "fail":
            out.append(f"      <failure type=\"fail\" message={quoteattr(reason)}>{escape(reason)}</failure>")
        elif s.verdict in ("not-run", "crash", "over-budget"):
            out.append(f"      <error type={quoteattr(s.verdict)} message={quoteattr(reason)}>{escape(reason)}</error>")
        elif s.verdict == "skipped":
            out.append(f"      <skipped message={quoteattr(reason)} />")
        props = f"errors {s.errors}, cycle time {_cycle(s)}, model {s.model}"
        if s.verdict in ("pass", "fail"):  # a run, so a report (under --out-dir)
            props += f", report {CASES_DIR}/{s.name}.json"
        out.append(f"      <system-out>{escape(props)}</system-out>")
        out.append("    </testcase>")
    out += ["  </testsuite>", "</testsuites>"]
    return visible("\n".join(out)) + "\n"  # XML 1.0 cannot hold control characters


_STYLE = """body{font:14px system-ui,sans-serif;margin:1.5em;color:#222}
table{border-collapse:collapse}th,td{border:1px solid #ccc;padding:.25em .5em;text-align:left;vertical-align:top}
th{background:#f3f3f3}td.n{text-align:right}.pass{color:#176117}.fail,.crash,.not-run{color:#a11;font-weight:600}
.skipped{color:#777}.why{color:#555;font-size:12px}"""


def render_html(summaries: list[CaseSummary], reports: set[str], tool_version: str) -> str:
    """A self-contained page (no script, no remote resource); every text from a case escaped;
    each case links to its reports under cases/ that were written (`reports`: file names): the
    HTML page, the JSON report, the MCAP trace."""
    e = html.escape
    rows = []
    for s in ordered(summaries):
        cells = _row(s)
        css = "over-budget crash" if s.verdict == "over-budget" else s.verdict  # shown as a crash is
        verdict = f'<td class="{e(css)}">{e(s.verdict)}</td>'
        links = [f'<a href="{e(CASES_DIR + "/" + quote(s.name + suffix))}">{label}</a>'
                 for suffix, label in ((".html", "page"), (".json", "JSON"), (".mcap", "trace"))
                 if s.name + suffix in reports]
        link = " · ".join(links) or "-"
        why = f'<div class="why">{e(s.reason)}</div>' if s.reason else ""
        rows.append("<tr>" + verdict + "".join(f"<td>{e(c)}</td>" for c in cells[1:6])
                    + f'<td class="n">{e(cells[6])}</td><td class="n">{e(cells[7])}</td><td>{link}{why}</td></tr>')
    head = "".join(f"<th>{e(h)}</th>" for h in HEADERS + ["report"])
    return visible("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; style-src 'unsafe-inline'\">"
            f"<title>val3check sim batch</title><style>{_STYLE}</style></head><body>\n"
            f"<h1>{e(_headline(summaries))}</h1>\n<p>val3check {e(tool_version)}</p>\n"
            f"<table><thead><tr>{head}</tr></thead><tbody>\n" + "\n".join(rows)
            + "\n</tbody></table>\n</body></html>\n")  # control characters: parse errors in HTML
