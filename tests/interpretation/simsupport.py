"""Helpers for the simulator tests: write an application (tests/support.py), lint it, run it."""

from __future__ import annotations

import html
import re
from pathlib import Path

from support import write_app

from val3check.config import Settings
from val3check.lint import run
from val3check.interpretation.simulate import SimOptions, SimResult, simulate


def build(tmp_path: Path, code: str, *, globals_=(), locals_=(), programs=None, name: str = "Example",
          links: dict | None = None, values: dict | None = None):
    """`links` gives dio/aio/sio globals their physical link ({"diX": "BasicIO-1\\%I0"} or a
    list for an array); `values` the value of num/string/bool globals ({"nX": "3"})."""
    folder = write_app(tmp_path, code, name=name, globals_=globals_, locals_=locals_, programs=programs)
    dtx = folder / f"{name}.dtx"
    text = dtx.read_text(encoding="utf-8")
    for var, link in (links or {}).items():
        items = link if isinstance(link, list) else [link]
        vals = "".join(f'<Value key="{i}" link="{html.escape(v, quote=True)}" />' for i, v in enumerate(items))
        text = re.sub(rf'(<Data name="{var}" [^>]*?) />', lambda m: f"{m.group(1)}>{vals}</Data>", text)
    for var, value in (values or {}).items():
        text = re.sub(rf'(<Data name="{var}" [^>]*?) />',
                      lambda m: f'{m.group(1)}><Value key="0" value="{html.escape(value, quote=True)}" /></Data>', text)
    dtx.write_text(text, encoding="utf-8")
    return folder


def sim(tmp_path: Path, code: str, *, globals_=(), locals_=(), programs=None, scenario: str | None = None,
        duration: float = 10.0, max_lines: int = 5_000_000, check_lint: bool = True, links=None, values=None,
        **opts) -> SimResult:
    folder = build(tmp_path, code, globals_=globals_, locals_=locals_, programs=programs, links=links, values=values)
    lr = run([str(folder)], Settings())
    if check_lint:
        errors = [d for d in lr.result.diagnostics if d.severity is not None and d.severity.label == "error"]
        assert not errors, errors
    ws = lr.workspace
    app = ws.apps[ws.targets[0]]
    sc = None
    if scenario is not None:
        from val3check.interpretation.scenario import load_scenario

        p = tmp_path / "scenario.toml"
        p.write_text(scenario, encoding="utf-8")
        sc = load_scenario(str(p))
    return simulate(ws, app, SimOptions(duration=duration, max_lines=max_lines, **opts), sc)


def out(result: SimResult) -> list[str]:
    """The text written by put/putln, one string per putln line."""
    lines, cur = [], ""
    for _, _, kind, text, _ in result.transcript:
        if kind == "put":
            cur += text
        elif kind == "putln":
            lines.append(cur + text)
            cur = ""
    if cur:
        lines.append(cur)
    return lines


def codes(result: SimResult) -> list[str]:
    return [d.code for d in result.diagnostics]


def errors(result: SimResult) -> list[int]:
    return [d.error for d in result.diagnostics if d.code == "R001"]


def code_pos(result: SimResult, line: int, col: int, program: str = "start") -> tuple[int, int]:
    """Where line/col of a program's code land in its .pgx (the code starts after <Code><![CDATA[)."""
    folder = Path(result.app_path).parent
    text = (folder / f"{program}.pgx").read_text(encoding="utf-8").split("\n")
    first = next(i for i, t in enumerate(text, 1) if "<![CDATA[" in t)
    start_col = text[first - 1].index("<![CDATA[") + len("<![CDATA[") + 1
    return first + line - 1, (start_col + col - 1) if line == 1 else col
