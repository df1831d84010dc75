"""The report of a run in the format `sim --report` names (text, json, html, junit): `render_sim`
as one text, `sim_pieces` as pieces to write one after the other."""

from __future__ import annotations

from typing import Any


def render_sim(fmt: str, report: Any, *, fail_on: str = "error", scenario: str | None = None) -> str:
    """`report`: a SimReport (sim_report.py); `scenario`: the scenario file given, for JUnit."""
    if fmt == "json":
        from .sim_json import render

        return render(report)
    if fmt == "html":
        from .html.from_run import render_run

        return render_run(report, fail_on=fail_on)
    if fmt == "junit":
        from .sim_junit import render as render_junit

        return render_junit(report, fail_on=fail_on, scenario=scenario)
    from .sim_text import render as render_text
    from .sim_verdict import closing_line

    return render_text(report) + closing_line(report, fail_on) + "\n"


def sim_pieces(fmt: str, report: Any, *, fail_on: str = "error", scenario: str | None = None):
    """The text of `render_sim`, piece by piece: the JSON report and the page are written as they
    are made (their trajectory never held whole, as series or as text); the others in one piece."""
    if fmt == "json":
        from .sim_json import pieces

        return pieces(report)
    if fmt == "html":
        from .html.from_run import page_pieces

        return page_pieces(report, fail_on=fail_on)
    return [render_sim(fmt, report, fail_on=fail_on, scenario=scenario)]
