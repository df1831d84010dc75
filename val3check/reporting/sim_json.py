"""`val3check sim --report json`: the documented, versioned run report (docs/sim-report.md).

Deterministic byte for byte: keys sorted, 2-space indent, ASCII only, no wall-clock value.
Numbers are written as plain decimals (never `1.6e-05`): times in simulated seconds rounded to
the microsecond, joint positions to 1e-4 degree (or mm), velocities to 1e-3 per second, other
figures to 1e-3. Arrays of numbers are written on one line, so that the 4 ms trajectory stays
compact. Bump VERSION on any incompatible change.
"""

from __future__ import annotations

import json
import math
import statistics
from typing import Any

from ..diagnostics import Severity
from . import sim_collision
from .sim_collision import Samples
from ._common import TOOL_NAME
from .thinning import JSON_TICKS, MOTION_ROWS, left_out, thinned_note, tick_multiple

VERSION = 2
TICK_S = 0.004


def _t(us: int | None) -> float | None:
    """Simulated microseconds as seconds (to the microsecond), None stays None."""
    return None if us is None else round(us / 1_000_000, 6)


def _s(x: float | None, digits: int = 6) -> float | None:
    """A number rounded to `digits` decimals, None stays None."""
    return None if x is None else round(float(x), digits)


def _pos(pos) -> dict | None:
    """(path, line, col, program) as the report's position object."""
    if not pos:
        return None
    path, line, col, program = pos
    return {"path": path, "line": line or None, "column": col or None, "program": program or None}


def _diagnostic(run: Any, d) -> dict[str, Any]:
    """A kept diagnostic in the report (a repeated one with its `count` and `last_time`)."""
    out = {"code": d.code, "name": run.rule_name(d.code), "severity": d.severity.label, "message": d.message,
            "path": d.path, "line": d.line or None, "column": d.col or None, "time": _t(d.time_us),
            "task": d.task or None, "program": d.program or None, "error": d.error}
    if d.count > 1:
        out.update(count=d.count, last_time=_t(d.last_time_us))
    return out


def _pose(v) -> list[float] | None:
    """Joint values or a trsf to 1e-4, None stays None."""
    return None if v is None else [round(float(x), 4) for x in v]


class Raw(str):
    """JSON text written as it is."""


class Rows:
    """The rows of a 2-D array, each written as a JSON array of numbers rounded to `digits`
    decimals (numpy's round; plain decimals: with at most 4 decimals Python writes no exponent for
    them), formatted block by block as the report is written: no Python object per sample."""

    def __init__(self, a, digits: int):
        self.a, self.digits = a, digits

    def chunks(self, indent: int):
        import numpy as np

        n = len(self.a)
        if not n:
            yield "[]"
            return
        inner = "  " * (indent + 1)
        yield "[\n"
        for lo in range(0, n, ROWS_BLOCK):
            r = np.round(np.asarray(self.a[lo:lo + ROWS_BLOCK], dtype=float), self.digits) + 0.0  # + 0.0: no -0.0
            rows = [inner + "[" + ", ".join(map(repr, row)) + "]" for row in r.tolist()]
            yield ("" if lo == 0 else ",\n") + ",\n".join(rows)
        yield "\n" + "  " * indent + "]"


class Lazy:
    """A list of objects (never numbers: a list written one entry a line) made as it is written:
    `make()` gives a new iterator over its entries each time the list is written."""

    def __init__(self, make) -> None:
        self.make = make


def _samples(s: Samples) -> str:
    """A per-sample array (sim_collision.Samples: rounded, NaN for null) on one line."""
    r = s.a.tolist()
    if not r:
        return "[]"
    out = ", ".join(map(repr, r))
    if "e" in out or "n" in out:  # an exponent (below 1e-4) or a NaN: as `number` writes them
        out = ", ".join(map(number, r))
    return "[" + out + "]"


ROWS_BLOCK = 4096  # rows of the trajectory formatted at once


def _motion(run: Any) -> dict | None:
    """The `motion` section: what the arm did (the run's record, simulation/arm_record.py)."""
    m = run.result.motion
    if m is None:
        return None
    motions = []
    for motion in m.motions[:MOTION_ROWS]:  # a long run: its first rows (thinning.py)
        src = motion.source
        where = run.display((src.path, src.line, src.col, ""))
        motions.append({
            "id": motion.id, "kind": motion.kind, "path": where[0] if where else None, "line": src.line or None,
            "column": src.col or None, "task": src.task or None, "state": motion.state,
            "recorded": _s(motion.recorded), "start": _s(motion.start), "end": _s(motion.end),
            "duration": _s(motion.duration), "length_mm": round(motion.length_mm, 3),
            "peak_tcp_mm_s": round(motion.peak_tcp_mm_s, 3), "dominant_limit": motion.dominant_limit or None,
            "limit_seconds": {k: round(v, 6) for k, v in sorted(motion.limit_seconds.items())},
            "target": motion.target or None, "frame": motion.frame or None, "tool": motion.tool or None,
            "tool_in_flange": _pose(motion.tool_trsf), "joints_start": _pose(motion.joints_start),
            "joints_end": _pose(motion.joints_end),
        })
    cycles = []
    for task in sorted(m.cycles):
        st = m.cycles[task]
        where = run.display((st.marker[0], st.marker[1], st.marker[2], "")) if st.marker is not None else None
        times = st.times
        spread = m.acceleration_range.cycle_time(task) if m.acceleration_range is not None else None
        cycles.append({"task": task, "loop": st.kind, "path": where[0] if where else None,
                       "line": st.marker[1] if st.marker else None, "column": st.marker[2] if st.marker else None,
                       "program": st.program, "why": st.why, "passes": st.passes,
                       "cycles": st.count, "starts": [_s(x) for x in st.starts], "times": [_s(x) for x in times],
                       "min": _s(min(times)) if times else None, "max": _s(max(times)) if times else None,
                       "median": _s(statistics.median(times)) if times else None,
                       "median_range": None if spread is None else [_s(spread[0]), _s(spread[1])]})
    every = tick_multiple(m, JSON_TICKS)
    period = TICK_S * every
    omitted = left_out(run.result, "the trajectory")

    def segments():  # sampled as they are written: the run's segments never held at once
        for k0, q, v in m.trajectory.iter_segments(m.end_s, period) if omitted is None else ():
            yield {"start": round(k0 * period, 6), "first_tick": k0, "positions": Rows(q, 4), "velocities": Rows(v, 3)}

    trajectory: dict[str, Any] = {"period": round(period, 6), "axes": m.scene.axes,
                                  "units": list(m.scene.joint_units), "segments": Lazy(segments)}
    if omitted is not None:
        trajectory["omitted"] = omitted
    if every > 1:
        trajectory["thinned"] = {"every_ticks": every, "max_samples": JSON_TICKS,
                                 "why": thinned_note(every, JSON_TICKS)}
    out = {
        "summary": {
            "commands": sum(1 for r in m.motions if r.id is not None),
            "done": sum(1 for r in m.motions if r.state == "done"),
            "failed": sum(1 for r in m.motions if r.state == "failed"),
            "cancelled": sum(1 for r in m.motions if r.state == "cancelled"),
            "moving": _s(m.busy_s), "idle": _s(m.idle_s),
            "tcp_length_mm": round(sum(r.length_mm for r in m.motions), 3),
        },
        "accelerations_assumed": m.acceleration_range is not None,
        "acceleration_factors": None if m.acceleration_range is None else list(m.acceleration_range.factors),
        "cycles": cycles,
        "motions": motions,
        "tool_events": Lazy(lambda: (
            {"time": _t(e.time_us), "task": e.task, "action": e.action, "tool": e.tool or None,
             "gripper": e.gripper or None, "tcp_in_flange": _pose(e.tcp_in_flange),
             **{k: v for k, v in (_pos(run.display(e.position)) or {}).items() if k != "program"}}
            for e in m.tool_events)),
        "trajectory": trajectory,
    }
    if len(m.motions) > MOTION_ROWS:
        out["motions_omitted"] = {"count": len(m.motions) - MOTION_ROWS, "kept": MOTION_ROWS,
                                  "why": f"a long run: the table keeps its first {MOTION_ROWS} motions; the "
                                         "summary, the cycles and the diagnostics cover the whole run"}
    return out


def report(run: Any) -> dict[str, Any]:
    """`run` is a `SimReport` (sim_report.py): the SimResult plus kept diagnostics."""
    r = run.result
    robot = None
    if r.robot:
        robot = dict(r.robot)
        if r.motion is not None:
            scene = r.motion.scene
            robot.update(axes=scene.axes, joint_limits=[[lo, hi] for lo, hi in scene.joint_limits],
                         nominal_speeds=list(scene.nominal_speeds), accelerations=list(scene.accelerations))
    return {
        "version": VERSION,
        "tool": {"name": TOOL_NAME, "version": run.tool_version},
        "application": {"name": r.application, "path": run.app_path},
        "robot": robot,
        "end": {"reason": r.end_reason, "message": r.end_message},
        "simulated_duration": _t(r.sim_time_us),
        "lines_executed": r.lines,
        "summary": {
            "error": sum(1 for d in run.diagnostics if d.severity is Severity.ERROR),
            "warning": sum(1 for d in run.diagnostics if d.severity is Severity.WARNING),
            "info": sum(1 for d in run.diagnostics if d.severity is Severity.INFO),
            "tasks": len(r.tasks),
            "transcript_entries": len(r.transcript),
            "io_events": len(r.io_log),
        },
        "tasks": [
            {
                "name": t.name,
                "program": t.program,
                "library": t.library,
                "priority": t.priority,
                "period": t.period,
                "created": _t(t.created),
                "ended": _t(t.ended),
                "end": t.end,
                "state_at_end_of_run": t.state_at_end_of_run,
                "error": t.error,
                "error_text": t.error_text,
                "blocked_on": t.blocked_on,
                "position": _pos(run.display(t.position)),
                "lines_executed": t.lines,
            }
            for t in r.tasks
        ],
        "destroyed": list(r.destroyed),
        "diagnostics": [_diagnostic(run, d) for d in run.diagnostics],
        "motion": _motion(run),
        "collision": sim_collision.section(run),
        # the long lists made as they are written (an 8-hour run's I/O log is some 60,000 entries)
        "transcript": Lazy(lambda: (
            {"time": _t(e.time_us), "task": e.task, "kind": e.kind, "text": e.text, "screen": e.screen}
            for e in r.transcript)),
        "io_log": Lazy(lambda: (
            {"time": _t(e.time_us), "kind": e.kind, "link": e.link, "names": run.link_names.get((e.kind, e.link), []),
             "value": e.value if not isinstance(e.value, float) or e.value == e.value else None, "source": e.source}
            for e in r.io_log)),
        "screen": r.screen,
    }


# ---- the writer ---------------------------------------------------------------------------------------


def number(x: float) -> str:
    """A float as a plain JSON decimal: `0.000016`, never `1.6e-05`; integral values keep `.0`."""
    if not math.isfinite(x):
        return "null"
    text = repr(float(x))
    if "e" in text or "E" in text:
        text = format(x, ".12f").rstrip("0")
        if text.endswith("."):
            text += "0"
    if text == "-0.0":
        text = "0.0"
    return text


def _scalar(v: Any) -> str:
    """A JSON scalar as text (or `Samples`: an array on one line)."""
    t = type(v)
    if t is float:
        return number(v)
    if t is str:
        return _ascii(v)
    if t is int:
        return str(v)
    if t is Raw:
        return v
    if t is Samples:
        return _samples(v)
    if v is None:
        return "null"
    if v is True:
        return "true"
    if v is False:
        return "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return number(v)
    return json.dumps(v, ensure_ascii=True)


_NESTED = (dict, list, Rows, Lazy)  # what `dumps` writes itself (anything else: `_scalar`)
_ascii = json.encoder.encode_basestring_ascii  # json.dumps of a str, without its dispatch
_KEYS: dict[str, str] = {}  # each key as JSON text, once


def _key(k: Any) -> str:
    text = _KEYS.get(k)
    if text is None:
        text = _KEYS[k] = _ascii(str(k))
    return text


def _flat(v: Any) -> bool:
    """A list written on one line (numbers only)."""
    if type(v) is list and all(type(x) is float or type(x) is int for x in v):
        return True  # most lists: decided in one pass
    return isinstance(v, list) and all(not isinstance(x, (list, dict)) for x in v) and all(
        not isinstance(x, str) or type(x) is Raw for x in v) and not (v and type(v[0]) is Raw)


def _rows_in(v: Any) -> bool:
    """A dict holding trajectory rows (a segment): written piece by piece."""
    return type(v) is dict and any(type(x) is Rows for x in v.values())


def chunks(obj: Any, indent: int = 0):
    """The text of `dumps(obj, indent)`, piece by piece: a report is written as it goes, its
    trajectory's rows (`Rows`) block by block, each entry of a list (a motion with its per-sample
    clearances) as one piece: never held whole as text."""
    if type(obj) is Rows:
        yield from obj.chunks(indent)
        return
    inner = "  " * (indent + 1)
    if type(obj) is dict and obj:
        yield "{"
        for i, k in enumerate(sorted(obj)):
            v = obj[k]
            head = f"{',' if i else ''}\n{inner}{_key(k)}: "
            if isinstance(v, _NESTED):
                yield head
                yield from chunks(v, indent + 1)
            else:
                yield head + _scalar(v)
        yield "\n" + "  " * indent + "}"
        return
    if type(obj) is Lazy or type(obj) is list and obj and not _flat(obj):
        opened = False
        for i, x in enumerate(obj.make() if type(obj) is Lazy else obj):
            if not opened:
                yield "["
                opened = True
            if _rows_in(x) or type(x) is list:
                yield f"{',' if i else ''}\n{inner}"
                yield from chunks(x, indent + 1)
            else:
                yield f"{',' if i else ''}\n{inner}{dumps(x, indent + 1)}"
        yield "\n" + "  " * indent + "]" if opened else "[]"
        return
    yield dumps(obj, indent)


def dumps(obj: Any, indent: int = 0) -> str:
    """Sorted keys, 2-space indent, ASCII; a list of numbers on one line."""
    if type(obj) is Rows:
        return "".join(obj.chunks(indent))
    if type(obj) is Lazy:
        return "".join(chunks(obj, indent))
    if isinstance(obj, dict):
        if not obj:
            return "{}"
        inner = "  " * (indent + 1)
        items = [f"{inner}{_key(k)}: {dumps(v, indent + 1) if isinstance(v, _NESTED) else _scalar(v)}"
                 for k, v in sorted(obj.items())]
        return "{\n" + ",\n".join(items) + "\n" + "  " * indent + "}"
    if isinstance(obj, list):
        if not obj:
            return "[]"
        if _flat(obj):
            return "[" + ", ".join(_scalar(x) for x in obj) + "]"
        inner = "  " * (indent + 1)
        return "[\n" + ",\n".join(inner + dumps(x, indent + 1) for x in obj) + "\n" + "  " * indent + "]"
    return _scalar(obj)


def pieces(run: Any):
    """The text of `render(run)` piece by piece, made as it is written."""
    yield from chunks(report(run))
    yield "\n"


def render(run: Any) -> str:
    """The report as text (sorted keys, 2-space indent, ASCII, a final newline)."""
    return "".join(pieces(run))
