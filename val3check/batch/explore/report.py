"""The summary of `sim --explore` in text, JSON, JUnit XML and an HTML index, and the comment
of each reproducer (docs/explore.md). Deterministic byte for byte: no wall-clock figure, nothing
that depends on the executor or -j."""

from __future__ import annotations

import html
import json
import shlex
from dataclasses import dataclass
from urllib.parse import quote
from xml.sax.saxutils import escape, quoteattr

from ...reporting._common import printable, visible
from .findings import Group, deviations
from .timings import Timing, fmt

SUMMARY_VERSION = 1
SUMMARY_FILES = ("summary.txt", "summary.json", "junit.xml", "index.html")


@dataclass
class Exploration:
    application: str
    scenario: str
    command: list[str]  # the plain sim that runs a reproducer, but its path
    seed: int
    jitter: float
    max_cycle: float | None
    timings: list[Timing]
    variants: int
    runs: int  # runs in all: the nominal, the variants, the shrinking
    groups: list[Group]
    tool_version: str
    out_dir: str = ""  # prefix of the reproducers' paths ("" in the out folder's own files)

    def path(self, g: Group) -> str:
        return f"{self.out_dir.rstrip('/')}/{g.reproducer}" if self.out_dir else g.reproducer

    def headline(self) -> str:
        n = len(self.groups)
        what = "no failure" if not n else f"{n} cause{'s' if n != 1 else ''} of failure"
        return (f"val3check sim --explore: {self.application} with {self.scenario}: {self.variants} variant"
                f"{'s' if self.variants != 1 else ''} (seed {self.seed}), {what}")


def _deviation(ex: Exploration, values: tuple[float, ...]) -> str:
    ds = deviations(ex.timings, values)
    return "; ".join(f"{d['timing']} (line {d['line']}) {fmt(d['nominal'])} -> {fmt(d['value'])} s"
                     f" ({d['delta']:+.3f} s)" for d in ds) or "none: the nominal scenario fails so"


def _occurred(ex: Exploration, g: Group) -> str:
    n = f"{g.count} of {ex.variants} variant{'s' if ex.variants != 1 else ''}"
    return ("the nominal run and " + n) if g.nominal else n


def render_text(ex: Exploration) -> str:
    out = [ex.headline(), ""]
    out.append(f"{len(ex.timings)} time(s) varied, {ex.runs} runs (nominal, variants, shrinking):")
    out += [f"  {t.label} (line {t.line}): {fmt(t.nominal)} s in [{fmt(t.lo)}, {fmt(t.hi)}]" for t in ex.timings]
    for i, g in enumerate(ex.groups, 1):
        c = g.shrunk_cause or g.cause
        out += ["", f"{i}. {c.code} {c.severity}: {c.message}",
                f"   where: {c.where()}" + (f", {c.when()}" if c.when() else ""),
                f"   occurred in {_occurred(ex, g)}",
                f"   smallest deviation that fails: {_deviation(ex, g.shrunk)}",
                f"   reproduce: {shlex.join(ex.command + [ex.path(g)])}"]
    if not ex.groups:
        out += ["", "every variant passed"]
    elif not ex.out_dir:
        out += ["", "(the reproducers' paths are relative to this folder)"]
    return printable("\n".join(out), keep_newlines=True) + "\n"


def _group_dict(ex: Exploration, g: Group) -> dict:
    c = g.shrunk_cause or g.cause
    return {"code": c.code, "severity": c.severity, "path": c.path or None, "line": c.line, "col": c.col,
            "message": c.message, "task": c.task or None,
            "time": None if c.time_us is None else round(c.time_us / 1e6, 6),
            "nominal": g.nominal, "count": g.count, "variants": g.variants,
            "smallest_seen": deviations(ex.timings, g.smallest) if not g.nominal else [],
            "deviation": deviations(ex.timings, g.shrunk), "shrink_runs": g.runs, "reproducer": g.reproducer}


def render_json(ex: Exploration) -> str:
    body = {"version": SUMMARY_VERSION, "tool": {"name": "val3check", "version": ex.tool_version},
            "application": ex.application, "scenario": ex.scenario, "seed": ex.seed, "jitter": ex.jitter,
            "max_cycle_time": ex.max_cycle, "variants": ex.variants, "runs": ex.runs,
            "timings": [{"timing": t.label, "line": t.line, "nominal": t.nominal, "min": t.lo, "max": t.hi}
                        for t in ex.timings],
            "failures": [_group_dict(ex, g) for g in ex.groups]}
    return json.dumps(body, indent=2, sort_keys=True, ensure_ascii=True) + "\n"


def render_junit(ex: Exploration) -> str:
    """One <testcase> per cause of failure (a <failure>); one passing <testcase> when none."""
    n = max(1, len(ex.groups))
    out = ['<?xml version="1.0" encoding="UTF-8"?>',
           f'<testsuites name="val3check sim --explore" tests="{n}" failures="{len(ex.groups)}" errors="0">',
           (f'  <testsuite name={quoteattr(ex.application + " | " + ex.scenario)} tests="{n}"'
           f' failures="{len(ex.groups)}" errors="0">')]
    for g in ex.groups:
        c = g.shrunk_cause or g.cause
        out.append(f"    <testcase classname={quoteattr(ex.application)} name={quoteattr(c.code + ' ' + c.where())}>")
        text = (f"{c.message}\n{c.when()}\noccurred in {_occurred(ex, g)}\nsmallest deviation that fails: "
                f"{_deviation(ex, g.shrunk)}\nreproduce: {shlex.join(ex.command + [ex.path(g)])}")
        out.append(f"      <failure type={quoteattr(c.code)} message={quoteattr(c.message)}>{escape(text)}</failure>")
        out.append("    </testcase>")
    if not ex.groups:
        out.append(f"    <testcase classname={quoteattr(ex.application)}"
                   f" name={quoteattr(f'{ex.variants} variants, seed {ex.seed}')} />")
    out += ["  </testsuite>", "</testsuites>"]
    return visible("\n".join(out)) + "\n"


_STYLE = """body{font:14px system-ui,sans-serif;margin:1.5em;color:#222;max-width:75em}
table{border-collapse:collapse;margin:.5em 0 1.5em}th,td{border:1px solid #ccc;padding:.25em .5em;text-align:left;
vertical-align:top}th{background:#f3f3f3}td.n{text-align:right}.fail{color:#a11;font-weight:600}
.pass{color:#176117;font-weight:600}.why{color:#555;font-size:12px}code{font-size:12px}"""


def render_html(ex: Exploration) -> str:
    """A self-contained page (no script, no remote resource), every text escaped."""
    e = html.escape
    timings = "".join(f"<tr><td>{e(t.label)}</td><td class=\"n\">{t.line}</td><td class=\"n\">{e(fmt(t.nominal))}</td>"
                      f"<td class=\"n\">{e(fmt(t.lo))}</td><td class=\"n\">{e(fmt(t.hi))}</td></tr>"
                      for t in ex.timings)
    rows = []
    for i, g in enumerate(ex.groups, 1):
        c = g.shrunk_cause or g.cause
        dev = "<br>".join(e(f"{d['timing']} (line {d['line']}): {fmt(d['nominal'])} → {fmt(d['value'])} s "
                            f"({d['delta']:+.3f} s)") for d in deviations(ex.timings, g.shrunk)) or "none (nominal)"
        link = f'<a href="{e(quote(g.reproducer))}">{e(g.reproducer.rsplit("/", 1)[-1])}</a>'
        cmd = e(shlex.join(ex.command + [g.reproducer]))
        rows.append(f'<tr><td class="n">{i}</td><td class="fail">{e(c.code)}</td><td>{e(c.where())}'
                    f'<div class="why">{e(c.when())}</div></td><td>{e(c.message)}</td>'
                    f'<td class="n">{e(_occurred(ex, g))}</td><td>{dev}</td><td>{link}<div class="why"><code>{cmd}'
                    "</code></div></td></tr>")
    verdict = (f'<p class="fail">{len(ex.groups)} cause(s) of failure: exit code 1</p>' if ex.groups
               else '<p class="pass">every variant passed</p>')
    failures = ("<h2>Failures, by cause</h2>\n<table><thead><tr><th>#</th><th>rule</th><th>where, when</th>"
                "<th>what</th><th>occurred in</th><th>smallest deviation that fails</th><th>reproducer</th></tr>"
                "</thead><tbody>\n" + "\n".join(rows) + "\n</tbody></table>\n"
                "<p class=\"why\">Each reproducer is a plain scenario file (its path relative to this page): run the"
                " command shown from the folder the exploration ran in, with the reproducer's path.</p>\n") if rows else ""
    return visible("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
                   "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; style-src 'unsafe-inline'\">"
                   f"<title>val3check sim --explore</title><style>{_STYLE}</style></head><body>\n"
                   f"<h1>val3check sim --explore</h1>\n<p>{e(ex.headline().split(': ', 1)[1])}</p>\n{verdict}\n"
                   f"<p>val3check {e(ex.tool_version)}; {ex.runs} runs (nominal, variants, shrinking); jitter "
                   f"± {e(fmt(ex.jitter))} s" + (f"; cycle time bound {e(fmt(ex.max_cycle))} s" if ex.max_cycle else "")
                   + "</p>\n" + failures
                   + "<h2>Times varied</h2>\n<table><thead><tr><th>time</th><th>line</th><th>nominal (s)</th>"
                   "<th>min (s)</th><th>max (s)</th></tr></thead><tbody>\n" + timings
                   + "\n</tbody></table>\n</body></html>\n")


def reproducer(ex: Exploration, g: Group, text: str) -> str:
    """The scenario text of a shrunk failing variant, under a comment saying what fails, where,
    when, and how far from the nominal."""
    c = g.shrunk_cause or g.cause
    lines = [(f"val3check sim --explore: a variant of {ex.scenario} (seed {ex.seed}) that fails, shrunk toward"
             " its nominal times"),
             f"fails: {c.code} {c.severity}: {c.message}",
             f"where: {c.where()}" + (f", {c.when()}" if c.when() else ""),
             f"occurred in {_occurred(ex, g)}"]
    if c.code == "cycle-time":
        lines.append("a plain sim reports this cycle time; the bound is --explore's ([explore] max_cycle_time)")
    lines += ["moved from the nominal: " + d for d in _deviation(ex, g.shrunk).split("; ")]
    lines.append(f"reproduce: {shlex.join(ex.command)} THIS_FILE (from the folder explored from)")
    head = "".join("# " + printable(line) + "\n" for line in lines)
    return head + "\n" + text
