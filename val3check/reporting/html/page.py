"""The HTML report: one self-contained file built from a report model (docs/html-report.md).

    html = render(model)

Text (verdict, diagnostics with their source excerpt, motion and cycle tables, I/O events, the
transcript) is written here as static, escaped HTML: readable without script and when printed.
The plots, timelines and 3D view are drawn by one inlined script (assets/*.js, written for this
project: plain DOM, SVG and Canvas) from a JSON block (pack.py). A Content-Security-Policy allows
that one script and style sheet by hash and nothing else: the page cannot load anything, from
the network or from disk. Same model, same bytes.
"""

from __future__ import annotations

import base64
import hashlib
import json
import re
from functools import lru_cache
from pathlib import Path
from typing import Any

from .._common import visible, visible_data
from .model import check_model
from .pack import data_items

# Script files, concatenated in this order into the page's one <script>.
SCRIPTS = ("core.js", "plot.js", "lanes.js", "view3d.js", "main.js")
MAX_IO_ROWS = 5000  # the I/O events listed as a table (the timeline shows them all)
MAX_TRANSCRIPT_ROWS = 10_000


def _asset(name: str) -> str:
    # beside this module, installed or not: importlib.resources would import zipfile and threading
    # (0.8 % of a 60 s run's instructions)
    return (Path(__file__).parent / "assets" / name).read_text(encoding="utf-8")


def _e(value: Any) -> str:
    """Escaped HTML text; control characters (a program's chr(0), chr(27)...) written as escapes
    ("\\x00"): raw, they are parse errors in HTML (reporting._common.visible)."""
    return _escaped("" if value is None else str(value))


@lru_cache(maxsize=4096)  # the tables repeat a few paths, tasks, kinds and targets thousands of times
def _escaped(text: str) -> str:
    # html.escape(text, quote=True)'s replacements in its order: the `html` module imports its
    # table of 2,231 entities (8 M instructions) that escaping never reads
    return visible(text).replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;") \
        .replace('"', "&quot;").replace("'", "&#x27;")


def _s(seconds: float | None, digits: int = 3) -> str:
    return "–" if seconds is None else f"{seconds:.{digits}f} s"


def _num(x: float | None, digits: int = 1) -> str:
    return "–" if x is None else f"{x:.{digits}f}"


def _plural(n: int, word: str) -> str:
    return f"{n} {word}" if n == 1 else f"{n} {word}s"


def _where(path: str | None, line: int | None, column: int | None) -> str:
    if not path:
        return ""
    return f"{path}:{line}:{column}" if line and column else f"{path}:{line}" if line else path


def _time_button(start: float, end: float | None, label: str, number: bool = False) -> str:
    end_attr = f' data-end="{end:.6f}"' if end is not None else ""
    cls = "goto num" if number else "goto"
    return f'<button type="button" class="{cls}" data-start="{start:.6f}"{end_attr}>{_e(label)}</button>'


# ---- sections --------------------------------------------------------------------------------


def _header(m: dict) -> str:
    app = m["application"]
    robot = (m.get("robot") or {}).get("name")
    tool = m.get("tool") or {}
    facts = [f"<span>{_e(app.get('path') or app['name'])}</span>"]
    facts.append(f"<span>arm model: {_e(robot)}</span>" if robot else "<span>no arm model</span>")
    if tool:
        facts.append(f"<span>{_e(tool.get('name', 'val3check'))} {_e(tool.get('version', ''))}</span>")
    notes = []
    if m.get("synthetic"):
        notes.append("Synthetic run: generated for tests and demonstration, not the result of simulating an application.")
    notes += m.get("limitations") or []
    notes_html = "".join(f'<p class="synthetic" role="note">{_e(n)}</p>' for n in notes)
    return (f'<header class="top"><h1>{_e(m.get("title") or app["name"])} <span class="sub">simulation report</span></h1>'
            f'<p class="facts">{" · ".join(facts)}</p>{notes_html}</header>')


def _nav(sections: list[tuple[str, str]]) -> str:
    items = "".join(f'<li><a href="#{sid}">{_e(title)}</a></li>' for sid, title in sections)
    return f'<nav class="toc" aria-label="Sections"><ul>{items}</ul></nav>'


def _verdict(m: dict) -> str:
    v = m["verdict"]
    counts = v["counts"]
    passed = v.get("passed", counts.get("error", 0) == 0)
    fail_on = v.get("fail_on", "error")
    status = "passed" if passed else "failed"
    why = (f"no diagnostic at or above {_e(fail_on)}" if passed else f"diagnostics at or above {_e(fail_on)}")
    chips = "".join(
        f'<li class="chip sev-{s}"><span class="icon" aria-hidden="true"></span><b>{counts.get(s, 0)}</b> '
        f'{_e(s if counts.get(s, 0) == 1 or s == "info" else s + "s")}</li>'
        for s in ("error", "warning", "info"))
    ct = v.get("cycle_time")
    spread = (f' ({ct["range"][0]:.3f}–{_s(ct["range"][1])} if the assumed accelerations are off by '
              f'{ct.get("off_by", 2):g}×)') if ct and ct.get("range") else ""
    cycle = (f'<div><dt>Cycle time</dt><dd><b>{_s(ct["seconds"])}</b>{_e(spread)} <span class="muted">'
             f'{_e(ct.get("basis", ""))}'
             f'{_task_suffix(ct)}</span></dd></div>') if ct else (
        '<div><dt>Cycle time</dt><dd class="muted">no complete loop iteration</dd></div>')
    return (
        '<section id="verdict" aria-labelledby="verdict-h"><h2 id="verdict-h">Verdict</h2>'
        f'<div class="verdict {status}"><p class="status"><span class="badge">{status.upper()}</span> {why}</p>'
        f'<ul class="chips" aria-label="Diagnostics by severity">{chips}</ul>'
        '<dl class="facts-grid">'
        f'<div><dt>End</dt><dd>{_e(v.get("end_message") or v["end_reason"])} <span class="muted">({_e(v["end_reason"])})</span></dd></div>'
        f'<div><dt>Simulated time</dt><dd>{_s(v["simulated_duration"])}</dd></div>'
        f'{cycle}</dl></div></section>'
    )


def _task_suffix(ct: dict) -> str:
    """" (task robot)" after the cycle time's basis, unless the basis names the task already."""
    task = ct.get("task")
    return f" (task {_e(task)})" if task and f"task {task}" not in ct.get("basis", "") else ""


def _excerpt(d: dict) -> str:
    ex = d.get("excerpt")
    if not ex or not ex.get("lines"):
        return ""
    first, line, col = ex["first_line"], d.get("line"), d.get("column")
    width = len(str(first + len(ex["lines"]) - 1))
    rows = []
    for k, text in enumerate(ex["lines"]):
        n = first + k
        hit = n == line
        cls = ' class="hit"' if hit else ""
        rows.append(f'<span{cls}><span class="ln" aria-hidden="true">{n:>{width}}</span> {_e(text.expandtabs(4))}</span>')
        if hit and col:
            rows.append(f'<span class="caret" aria-hidden="true">{" " * (width + col)}^</span>')
    label = f"source lines {first} to {first + len(ex['lines']) - 1}"
    return f'<pre class="excerpt" aria-label="{_e(label)}"><code>{chr(10).join(rows)}</code></pre>'


def _has_time(m: dict) -> bool:
    """Whether the page has time charts (and so a time window to move)."""
    tr = m.get("trajectory")
    return bool((tr and tr.get("times")) or m.get("tasks") or m.get("arm_timeline") or m.get("io"))


def _name(d: dict) -> str:
    return f' <span class="muted">{_e(d["name"])}</span>' if d.get("name") else ""


def _diagnostics(m: dict) -> str:
    diags = m.get("diagnostics", [])
    if not diags:
        body = '<p class="empty">No runtime diagnostic.</p>'
    else:
        items = []
        for d in diags:
            sev = d["severity"]
            where = _where(d.get("path"), d.get("line"), d.get("column"))
            who = []
            if d.get("time") is not None:
                who.append(f"at {_s(d['time'])}")
            if d.get("task"):
                who.append(f"task {_e(d['task'])}" + (f" ({_e(d['program'])}())" if d.get("program") else ""))
            goto = (_time_button(d["time"], None, "show in the timelines")
                    if d.get("time") is not None and _has_time(m) else "")
            items.append(
                f'<li class="diag sev-{sev}"><p class="dhead"><span class="sev"><span class="icon" aria-hidden="true"></span>'
                f'{_e(sev)}</span> <code class="code">{_e(d["code"])}</code>'
                f'{_name(d)}</p>'
                f'<p class="msg">{_e(d["message"])}</p>'
                f'<p class="where"><code>{_e(where)}</code> {" · ".join(who)} {goto}</p>{_excerpt(d)}</li>')
        body = f'<ol class="diags">{"".join(items)}</ol>'
    return f'<section id="diagnostics" aria-labelledby="diagnostics-h"><h2 id="diagnostics-h">Diagnostics</h2>{body}</section>'


def _motions(m: dict):
    motions = m.get("motions", [])
    if not motions:
        yield '<section id="motions" aria-labelledby="motions-h"><h2 id="motions-h">Motions</h2>' \
              '<p class="empty">No motion in this run.</p></section>'
        return
    moving = sum(mo["end"] - mo["start"] for mo in motions)
    clear = [mo for mo in motions if mo.get("min_clearance") is not None]
    closest = min(clear, key=lambda mo: mo["min_clearance"]) if clear else None
    summary = f"{_plural(len(motions), 'motion')}, {_s(moving)} moving"
    if closest:
        summary += (f"; smallest clearance {_num(closest['min_clearance'])} mm"
                    f"{' to ' + _e(closest['clearance_to']) if closest.get('clearance_to') else ''} (motion {closest['id']})")
    yield (f'<section id="motions" aria-labelledby="motions-h"><h2 id="motions-h">Motions</h2>'
           f'<p>{summary}. The number zooms the timelines on the motion.</p>'
           '<div class="scroll tall"><table class="data motions"><thead><tr>'
           '<th scope="col">#</th><th scope="col">program:line</th><th scope="col">task</th><th scope="col">kind</th>'
           '<th scope="col">target</th><th scope="col">start (s)</th><th scope="col">end (s)</th>'
           '<th scope="col">duration (s)</th><th scope="col">dominant limit</th><th scope="col">speed</th>'
           '<th scope="col">clearance (mm)</th></tr></thead><tbody>')
    for lo in range(0, len(motions), ROWS):
        yield "".join(map(_motion_row, motions[lo:lo + ROWS]))
    yield '</tbody></table></div></section>'


ROWS = 500  # table rows written as one piece


def _motion_row(mo: dict) -> str:
    get = mo.get
    clearance = _num(get("min_clearance"))
    if get("clearance_to") and get("min_clearance") is not None:
        clearance += f' <span class="muted">{_e(mo["clearance_to"])}</span>'
    start, end, duration = mo["start"], mo["end"], get("duration")
    return (f'<tr><td class="n">{_time_button(start, end, str(mo["id"]), True)}</td>'
            f'{_where_cells(get("path"), get("line"), get("column"), get("task"), mo["kind"], get("target"))}'
            f'<td class="n">{start:.3f}</td><td class="n">{end:.3f}</td>'
            f'<td class="n">{(end - start) if duration is None else duration:.3f}</td>'
            f'{_limit_cells(get("dominant_limit"), _speed(get("vel"), get("tvel")))}'
            f'<td class="n">{clearance}</td></tr>')


@lru_cache(maxsize=4096, typed=True)  # a cyclic cell's rows repeat these: made once each (from their arguments alone)
def _where_cells(path, line, column, task, kind, target) -> str:
    """The cells of a motion row from its program:line to its target."""
    return (f'<td class="nw">{_source({"path": path, "line": line, "column": column})}</td><td>{_e(task or "")}</td>'
            f'<td><code>{_e(kind)}</code></td><td>{_e(target or "")}</td>')


def _speed(vel, tvel) -> str:
    speed = []
    if vel is not None:
        speed.append(f"vel {vel:g} %")
    if tvel is not None:
        speed.append(f"tvel {tvel:g} mm/s")
    return ", ".join(speed)


@lru_cache(maxsize=4096, typed=True)
def _limit_cells(dominant_limit, speed: str) -> str:
    """The cells of a motion row's dominant limit and speed."""
    return f'<td>{_e(dominant_limit or "–")}</td><td class="nw">{_e(speed)}</td>'


def _source(mo: dict) -> str:
    """Where a motion instruction is written, as the motion table shows it: its program file and
    line (`pick.pgx:8`), the whole position in the tooltip."""
    path, line = mo.get("path"), mo.get("line")
    if not path:
        return _e(line or "–")
    name = path.replace("\\", "/").rsplit("/", 1)[-1]
    return f'<span title="{_e(_where(path, line, mo.get("column")))}">{_e(f"{name}:{line}" if line else name)}</span>'


def _cycles(m: dict):
    cycles = m.get("cycles", [])
    head = '<section id="cycles" aria-labelledby="cycles-h"><h2 id="cycles-h">Cycle time per loop iteration</h2>'
    if not cycles or not any(c["iterations"] for c in cycles):
        yield head + '<p class="empty">No loop iteration recorded.</p></section>'
        return
    yield head
    for ci, c in enumerate(cycles):
        its = c["iterations"]
        done = [it["duration"] for it in its if it.get("complete", True)]
        stats = (f"{len(done)} complete: min {_s(min(done))}, mean {_s(sum(done) / len(done))}, max {_s(max(done))}"
                 if done else "no complete iteration")
        where = _where(c.get("path"), c.get("line"), None)
        yield (f'<h3>Task {_e(c["task"])}: {_e(c.get("label") or "")} <span class="muted">{_e(where)}</span></h3>'
               f'<p>{stats}.</p><div class="figure cyclebars" data-cycle="{ci}" role="img" '
               f'aria-label="Duration of each iteration of the loop of task {_e(c["task"])}"></div>'
               '<details><summary>Iterations</summary><table class="data"><thead><tr><th scope="col">#</th>'
               '<th scope="col">start (s)</th><th scope="col">duration (s)</th><th scope="col">note</th></tr></thead>'
               '<tbody>')
        for lo in range(0, len(its), ROWS):
            yield "".join(
                f'<tr><td class="n">{_time_button(it["start"], it["start"] + it["duration"], str(k + 1), True)}</td>'
                f'<td class="n">{it["start"]:.3f}</td><td class="n">{it["duration"]:.3f}</td>'
                f'<td>{"" if it.get("complete", True) else "cut by the end of the run"}</td></tr>'
                for k, it in enumerate(its[lo:lo + ROWS], lo))
        yield '</tbody></table></details>'
    yield '</section>'


def _joints(m: dict) -> str:
    tr = m.get("trajectory")
    if not tr or not tr.get("times"):
        body = '<p class="empty">No joint trajectory: the arm did not move in this run, or the run had no arm model.</p>'
    else:
        body = (
            '<p>Position and speed of each joint against its limits: the shaded bands are outside the joint '
            'range or above the nominal speed; dashed lines are the speed the motion descriptor allows (vel).</p>'
            '<p class="yscale"><span id="yscale-label">Vertical scale:</span> '
            '<button type="button" class="yfit" aria-pressed="true" data-fit="limits" aria-describedby="yscale-label">limits</button> '
            '<button type="button" class="yfit" aria-pressed="false" data-fit="data" aria-describedby="yscale-label">data</button></p>'
            '<div id="joint-plots" class="plots"></div>')
    return f'<section id="joints" aria-labelledby="joints-h"><h2 id="joints-h">Joint positions and speeds</h2>{body}</section>'


def _tcp(m: dict) -> str:
    tr = m.get("trajectory")
    if not tr or tr.get("tcp_speed") is None:
        body = '<p class="empty">No TCP speed in this run.</p>'
    else:
        body = ('<p>Cartesian speed of the tool centre point, with the <code>tvel</code> of each motion '
                'descriptor (dashed).</p><div id="tcp-plot" class="figure"></div>')
    return f'<section id="tcp" aria-labelledby="tcp-h"><h2 id="tcp-h">TCP speed</h2>{body}</section>'


def _timeline(m: dict) -> str:
    if not m.get("tasks") and not m.get("arm_timeline"):
        body = '<p class="empty">No task timeline in this report.</p>'
    else:
        body = ('<p>What each task was doing, and the arm. Diagnostics are marked on the top row.</p>'
                '<div id="gantt" class="figure"></div>')
    return f'<section id="timeline" aria-labelledby="timeline-h"><h2 id="timeline-h">Tasks and arm</h2>{body}</section>'


def _value(e: dict) -> str:
    v = e["value"]
    if e["kind"] == "dio":
        return "true" if v else "false"
    if isinstance(v, list):
        return " ".join(str(b) for b in v)
    return "NaN" if v is None else str(v)


def _io(m: dict) -> str:
    events = m.get("io", [])
    if not events:
        body = '<p class="empty">No input or output changed.</p>'
    else:
        shown = events[:MAX_IO_ROWS]
        more = (f" (the first {len(shown)} of {len(events)}; the timeline shows them all)" if len(shown) < len(events) else "")
        rows = "".join(
            f'<tr><td class="n">{e["time"]:.3f}</td><td>{_e(e["kind"])}</td><td>{_e(", ".join(e.get("names") or []))}</td>'
            f'<td><code>{_e(e["link"])}</code></td><td>{_e(_value(e))}</td><td>{_e(e.get("source") or "")}</td></tr>'
            for e in shown)
        body = ('<div id="io-lanes" class="figure"></div>'
                f'<details><summary>{_plural(len(events), "event")}{_e(more)}</summary><div class="scroll tall">'
                '<table class="data"><thead><tr><th scope="col">time (s)</th><th scope="col">kind</th>'
                '<th scope="col">names</th><th scope="col">link</th><th scope="col">value</th><th scope="col">source</th>'
                f'</tr></thead><tbody>{rows}</tbody></table></div></details>')
    return f'<section id="io" aria-labelledby="io-h"><h2 id="io-h">Inputs and outputs</h2>{body}</section>'


def _transcript(m: dict) -> str:
    entries = m.get("transcript", [])
    screen = m.get("screen")
    parts = []
    if not entries:
        parts.append('<p class="empty">Nothing was written to the user page.</p>')
    else:
        shown = entries[:MAX_TRANSCRIPT_ROWS]
        rows = "".join(
            f'<tr><td class="n">{e["time"]:.3f}</td><td>{_e(e["task"])}</td><td>{_e(e["kind"])}'
            f'{" &lt;" + _e(e["screen"]) + "&gt;" if e.get("screen") else ""}</td><td><code class="pre">{_e(e["text"])}</code></td></tr>'
            for e in shown)
        parts.append('<div class="scroll tall"><table class="data transcript"><thead><tr><th scope="col">time (s)</th>'
                     '<th scope="col">task</th><th scope="col">kind</th><th scope="col">text</th></tr></thead>'
                     f'<tbody>{rows}</tbody></table></div>')
    if screen and any(line.strip() for line in screen.get("lines", [])):
        title = f' title “{_e(screen.get("title"))}”' if screen.get("title") else ""
        lines = [line.rstrip().ljust(40) for line in screen["lines"]]  # the 14x40 page, blanks included
        parts.append(f'<h3>The user page at the end{title}</h3><pre class="screen">{_e(chr(10).join(lines))}</pre>')
    return (f'<section id="transcript" aria-labelledby="transcript-h"><h2 id="transcript-h">User page transcript</h2>'
            f'{"".join(parts)}</section>')


def _key3d(scene: dict, moving: bool) -> str:
    key = ["yellow: the arm"] if scene.get("arm") else []
    if scene.get("arm") and scene.get("tool"):
        key += ["dark grey: the tool", "orange dot: the TCP"]
    if scene.get("obstacles"):
        key.append("blue-grey: the cell")
    if scene.get("parts"):
        key.append("green: the parts, carried or left in the cell")
    if moving and scene.get("arm"):
        key.append(f"blue line: the path of the {'TCP' if scene.get('tool') else 'flange'} (darker where already travelled)")
    return "; ".join(key).capitalize() + "." if key else ""


def _view3d(m: dict) -> str:
    scene = m.get("scene") or {}
    if not scene.get("arm") and not scene.get("obstacles"):
        body = '<p class="empty">No 3D scene: the run had no arm model and the cell no obstacle.</p>'
    else:
        notes = "".join(f'<p class="muted">{_e(n)}</p>' for n in (scene.get("arm") or {}).get("notes", []))
        tr = m.get("trajectory")
        moving = bool(tr and tr.get("times"))
        playback = (
            '<button type="button" id="play" aria-pressed="false">Play</button>'
            '<label>time <input type="range" id="scrub" min="0" max="1000" value="0" step="1"></label>'
            '<output id="scrub-time" for="scrub">0.000 s</output>'
            '<label>speed <select id="speed"><option value="0.25">0.25×</option><option value="0.5">0.5×</option>'
            '<option value="1" selected>1×</option><option value="2">2×</option><option value="4">4×</option></select></label>'
        ) if moving else ""
        intro = ("The arm along its path, with the tool and the cell. Drag to turn the view, wheel or +/− to zoom, "
                 "arrow keys to turn when the view has focus, space to play or pause." if moving else
                 "The arm where it is during the whole run, with the cell. Drag to turn the view, wheel or +/− to "
                 "zoom, arrow keys to turn when the view has focus.")
        body = (
            f'<p>{intro}</p>'
            '<div class="view3d"><canvas id="view3d" tabindex="0" role="img" aria-label="3D view of the arm and the cell" '
            'aria-describedby="view3d-state"></canvas>'
            '<div class="side"><table class="data jointnow" aria-label="Joint values at the current time"><thead><tr>'
            '<th scope="col">joint</th><th scope="col">value</th><th scope="col">range</th></tr></thead><tbody id="jointnow">'
            '</tbody></table><p id="view3d-state" aria-live="off"></p>'
            f'<p class="muted key3d">{_e(_key3d(scene, moving))}</p></div></div>'
            f'<div class="controls" role="group" aria-label="Playback">{playback}'
            f'<button type="button" id="reset-view">Reset view</button></div>{notes}')
    return f'<section id="view3d-section" aria-labelledby="view3d-h"><h2 id="view3d-h">3D view</h2>{body}</section>'


SECTIONS = (
    ("verdict", "Verdict", _verdict),
    ("diagnostics", "Diagnostics", _diagnostics),
    ("motions", "Motions", _motions),
    ("cycles", "Cycle time", _cycles),
    ("joints", "Joints", _joints),
    ("tcp", "TCP speed", _tcp),
    ("timeline", "Tasks and arm", _timeline),
    ("io", "I/O", _io),
    ("transcript", "Transcript", _transcript),
    ("view3d-section", "3D view", _view3d),
)


def _timebar(m: dict) -> str:
    d = m["verdict"]["simulated_duration"]
    return (
        '<div class="timebar" role="toolbar" aria-label="Time window of the plots and timelines">'
        '<span class="tb-label">Time window</span> <output id="tw-range">'
        f'0.000 – {d:.3f} s</output> '
        '<button type="button" id="tw-in" aria-label="Zoom in (time)">+</button>'
        '<button type="button" id="tw-out" aria-label="Zoom out (time)">−</button>'
        '<button type="button" id="tw-left" aria-label="Earlier">◀</button>'
        '<button type="button" id="tw-right" aria-label="Later">▶</button>'
        '<button type="button" id="tw-reset">Whole run</button>'
        '<span class="tb-help">drag across a plot to zoom, click to set the time, double-click for the whole run; '
        'Ctrl+wheel zooms, Shift+wheel pans</span></div>')


def render(model: dict) -> str:
    """The self-contained HTML page of a report model (raises ModelError for a bad model)."""
    return "".join(pieces(model))


def pieces(model: dict):
    """The text of `render(model)` piece by piece, to be written as it is made: no piece holds
    more than a section's header, a block of table rows or one value of the page's data. The
    model is checked first (ModelError before any piece)."""
    check_model(model)
    return _pieces(model)


def _pieces(model: dict):
    css = _asset("report.css")
    script = "\n".join(_asset(name) for name in SCRIPTS)
    csp = ("default-src 'none'; "
           f"script-src '{_sha256(script)}'; style-src '{_sha256(css)}'; img-src data:; "
           "base-uri 'none'; form-action 'none'")
    tool = model.get("tool") or {}
    replacements = {
        "csp": csp,
        "generator": _e(f"{tool.get('name', 'val3check')} {tool.get('version', '')}".strip()),
        "title": _e(f"{model.get('title') or model['application']['name']}: simulation report"),
        "css": css,
        "body": _body,
        "data": _data,
        "script": script,
    }
    template = _asset("page.html")
    pos = 0
    while True:  # one pass, so that no inserted text is ever taken for a placeholder
        start = template.find("{{", pos)
        if start < 0:
            yield template[pos:]
            break
        end = template.index("}}", start)
        yield template[pos:start]
        value = replacements[template[start + 2:end]]
        if isinstance(value, str):
            yield value
        else:
            yield from value(model)
        pos = end + 2


def _body(model: dict):
    yield f"{_header(model)}{_nav([(sid, title) for sid, title, _ in SECTIONS])}"
    yield f'<main id="main">{_timebar(model) if _has_time(model) else ""}'
    for _, _, fn in SECTIONS:
        yield from _parts(fn(model))
    yield ('</main><footer><p>This page is self-contained: it loads nothing, from the network or from disk. '
           'Its plots and 3D view need JavaScript; the tables above do not.</p></footer>'
           '<noscript><p class="empty">JavaScript is off: the plots, timelines and the 3D view are not drawn.</p></noscript>')


def _parts(section):
    """A section's text: a str, or its pieces (a long table's rows, a block at a time)."""
    if isinstance(section, str):
        yield section
    else:
        yield from section


def _data(model: dict):
    """The page's data as `_data_json(page_data(model))`, one top-level value at a time (in the
    order sort_keys gives), each escaped for <script>: no "</script>", "<!--" can be formed."""
    yield "{"
    for k, (key, value) in enumerate(data_items(model)):
        text = ("," if k else "") + json.dumps(key) + ":" + _data_json(value)
        yield text.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")
    yield "}"


# In ensure_ascii JSON, every character `visible` rewrites is an escape this finds (and some it
# keeps: a backslash before "u00", a surrogate pair): without one, the walk would change nothing.
_MAY_REWRITE = re.compile(r"\\u00[01]|\\u007f|\\u00[89]|\\ud[89a-f]|\\ufff[ef]|\\[bfr]")


def _data_json(data: dict) -> str:
    """The page's data as JSON, control characters of its strings visible (_common.visible_data):
    walked only when the JSON holds one (the walk was a tenth of a long run's page)."""
    text = json.dumps(data, separators=(",", ":"), sort_keys=True, ensure_ascii=True, allow_nan=False)
    if _MAY_REWRITE.search(text):
        text = json.dumps(visible_data(data), separators=(",", ":"), sort_keys=True, ensure_ascii=True,
                          allow_nan=False)
    return text


def _sha256(text: str) -> str:
    return "sha256-" + base64.b64encode(hashlib.sha256(text.encode("utf-8")).digest()).decode("ascii")
