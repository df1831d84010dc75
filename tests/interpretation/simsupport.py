"""Helpers for the simulator tests: write an application (tests/support.py), lint it, run it."""

from __future__ import annotations

import html
import re
from pathlib import Path

from val3check.testing import write_app

from val3check.config import Settings
from val3check.simulation import SimOptions, SimResult, simulate
from val3check.lint import run


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
        from val3check.simulation.scenario import load_scenario

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
    """The rule of every finding, a repeated one (simulation/folding.py) as many times as it occurred."""
    return [d.code for d in result.diagnostics for _ in range(d.count)]


def errors(result: SimResult) -> list[int]:
    """The error code of every R001, a repeated one as many times as it occurred."""
    return [d.error for d in result.diagnostics if d.code == "R001" for _ in range(d.count)]


def code_pos(result: SimResult, line: int, col: int, program: str = "start") -> tuple[int, int]:
    """Where line/col of a program's code land in its .pgx (the code starts after <Code><![CDATA[)."""
    folder = Path(result.app_path).parent
    text = (folder / f"{program}.pgx").read_text(encoding="utf-8").split("\n")
    first = next(i for i, t in enumerate(text, 1) if "<![CDATA[" in t)
    start_col = text[first - 1].index("<![CDATA[") + len("<![CDATA[") + 1
    return first + line - 1, (start_col + col - 1) if line == 1 else col


def _plain(v):
    from val3check.geometry import Frame, Point, Tool, Trsf
    from val3check.interpretation.values import Arr, Coll, IOPoint

    if type(v) is IOPoint:
        return v.value
    if type(v) is Trsf:
        return v.to_dict()
    if type(v) is Point:
        return {"trsf": v.trsf.to_dict(), "config": _plain(v.config)}
    if type(v) is Tool:
        return {"trsf": v.trsf.to_dict(), "gripper": _plain(v.gripper), "otime": v.otime, "ctime": v.ctime}
    if type(v) is Frame:
        return {"trsf": v.trsf.to_dict()}
    if type(v) is Arr:
        return [_plain(x) for x in v.data[v.off:]]
    if type(v) is Coll:
        return {k: _plain(v.d[k]) for k in v.keys()}
    if type(v) is dict:
        return {k: _plain(x) for k, x in v.items()}
    return v


def gv(result: SimResult, name: str):
    """The value of a global at the end of the run, as plain Python: a num is a float, an
    element (array of size 1) its single value, an array a list, a collection a dict (keys in
    VAL 3 order), a structured value a dict of its fields (trsf/frame/tool/point too: use
    `result.globals` for the objects themselves), a dio/aio its state."""
    c = result.globals[name]
    from val3check.interpretation.values import Arr

    if type(c) is Arr and c.dims is None and len(c.data) == 1:
        return _plain(c.data[0])
    return _plain(c)


def add_libraries(folder: Path, libs: dict[str, str], name: str = "Example", autoload: str | None = "false") -> None:
    """Declare library aliases ({"part": "Disk://Part"}) in an application written by `build`:
    not loaded at start by default (loaded by libLoad); `autoload=None` writes no attribute."""
    pjx = folder / f"{name}.pjx"
    auto = "" if autoload is None else f' autoload="{autoload}"'
    entries = "".join(f'<Library alias="{a}" path="{html.escape(p, quote=True)}"{auto} />' for a, p in libs.items())
    pjx.write_text(pjx.read_text(encoding="utf-8").replace("<Libraries />", f"<Libraries>{entries}</Libraries>"),
                   encoding="utf-8")


def make_library(tmp_path: Path, name: str, *, globals_=(), programs=None, values=None) -> Path:
    """A library (an application without start()/stop()) in tmp_path/name."""
    folder = build(tmp_path, "begin\nend\n", name=name, globals_=globals_, programs=programs, values=values)
    for p in ("start", "stop"):
        if not (programs and p in programs):
            (folder / f"{p}.pgx").unlink()
    pjx = folder / f"{name}.pjx"
    text = pjx.read_text(encoding="utf-8")
    for p in ("start", "stop"):
        if not (programs and p in programs):
            text = text.replace(f'    <Program file="{p}.pgx" />\n', "")
    pjx.write_text(text, encoding="utf-8")
    return folder


def run_folder(folder: Path, *, scenario: str | None = None, duration: float = 10.0, tmp_path: Path | None = None,
               check_lint: bool = True, **opts) -> SimResult:
    """Lint and simulate an application folder (one written by `build` and then edited)."""
    lr = run([str(folder)], Settings())
    if check_lint:
        errs = [d for d in lr.result.diagnostics if d.severity is not None and d.severity.label == "error"]
        assert not errs, errs
    ws = lr.workspace
    app = ws.apps[ws.targets[0]]
    sc = None
    if scenario is not None:
        from val3check.simulation.scenario import load_scenario

        p = (tmp_path or folder.parent) / "scenario.toml"
        p.write_text(scenario, encoding="utf-8")
        sc = load_scenario(str(p))
    return simulate(ws, app, SimOptions(duration=duration, **opts), sc)


class StepClock:
    """A wall clock for `SimOptions(wall_clock=...)` that advances `step` seconds each time it is
    read: a wall budget is reached after a number of readings, whatever the machine's speed."""

    def __init__(self, step: float = 0.001) -> None:
        self.step = step
        self.reads = 0

    def __call__(self) -> float:
        self.reads += 1
        return self.reads * self.step


def frozen_clock() -> float:
    """A wall clock that never moves: the wall budget is never what ends the run."""
    return 0.0
