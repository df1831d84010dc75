"""The report model: everything the HTML page shows, as one plain JSON-able dict.

Documented in docs/html-report.md (with a JSON Schema, docs/html-report.schema.json). It is
built from a run (later: the sim's JSON report plus the arm model), or by `tests/synthetic_run.py` for
tests and the demo; `page.render` turns it into the page. `check_model` gives a clear message
for a model that the page could not show, instead of a broken page.
"""

from __future__ import annotations

import math
import operator
from array import array
from itertools import islice
from typing import Any

from .series import Packed, floats

VERSION = 1

SEVERITIES = ("error", "warning", "info")
TASK_STATES = ("running", "waiting", "blocked", "stopped")
ARM_STATES = ("moving", "idle")
IO_KINDS = ("dio", "aio", "sio")
SHAPES = ("box", "cylinder", "sphere", "mesh")


class ModelError(ValueError):
    """A report model the page cannot show; the message names the key (`trajectory.times[3]`)."""


def _fail(where: str, what: str) -> None:
    raise ModelError(f"report model: {where}: {what}")


def _num(v: Any, where: str, *, null: bool = False) -> None:
    if type(v) is float and v - v == 0.0:  # finite (inf - inf and nan - nan are nan): most values
        return
    if v is None and null:
        return
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not _finite(v):
        _fail(where, f"a finite number is expected, not {v!r}")


def _finite(v: int | float) -> bool:
    try:
        return math.isfinite(v)
    except OverflowError:  # an int beyond any float
        return False


def _nums(values: Any, where: str) -> None:
    """`_num` of every value of a series (`where[k]`): at once when all are finite floats or ints (the
    trajectory's long rows), else one by one for the message."""
    a = floats(values)  # numpy's view of an array('d'): numpy is there
    if a is not None:
        import numpy as np

        if np.isfinite(a).all():
            return
    elif set(map(type, values)) <= {float, int}:
        try:
            if all(map(math.isfinite, values)):
                return
        except OverflowError:  # an int beyond a float: the message comes from `_num`
            pass
    for k, x in enumerate(values):
        _num(x, f"{where}[{k}]")


def _times(times: Any, where: str) -> None:
    """Finite numbers, not decreasing: at once, else one by one for the message."""
    a = floats(times)
    if a is not None:
        import numpy as np

        if np.isfinite(a).all() and (a[1:] >= a[:-1]).all():
            return
    elif set(map(type, times)) <= {float, int}:
        try:
            if all(map(math.isfinite, times)) and all(map(operator.le, times, islice(times, 1, None))):
                return
        except OverflowError:  # an int beyond a float: the message comes from `_num`
            pass
    prev = -math.inf
    for k, t in enumerate(times):
        _num(t, f"{where}[{k}]")
        if t < prev:
            _fail(f"{where}[{k}]", "times must not decrease")
        prev = t


def _series(v: Any, where: str) -> Any:
    """A list, or an array('d') (a model built in process: series.py)."""
    if isinstance(v, array) and v.typecode == "d":
        return v
    return _list(v, where)


def _list(v: Any, where: str) -> list:
    if not isinstance(v, list):
        _fail(where, f"a list is expected, not {type(v).__name__}")
    return v


def _dict(v: Any, where: str, keys: tuple[str, ...] = ()) -> dict:
    if not isinstance(v, dict):
        _fail(where, f"an object is expected, not {type(v).__name__}")
    for k in keys:
        if k not in v:
            _fail(where, f"key {k!r} is missing")
    return v


def _fine(x: Any) -> bool:
    """A finite float: most values, checked without naming them."""
    return type(x) is float and x - x == 0.0


def _fine_or_none(a: Any, b: Any, c: Any) -> bool:
    """Three values, each a finite float or None (one call for a motion row's three)."""
    return (a is None or type(a) is float and a - a == 0.0) and (b is None or type(b) is float and b - b == 0.0) \
        and (c is None or type(c) is float and c - c == 0.0)


def _fine_matrix(v: Any) -> bool:
    return type(v) is list and len(v) == 3 and all(type(r) is list and len(r) == 4 and all(map(_fine, r)) for r in v)


def _matrix(v: Any, where: str) -> None:
    if _fine_matrix(v):
        return
    rows = _list(v, where)
    if len(rows) != 3 or any(not isinstance(r, list) or len(r) != 4 for r in rows):
        _fail(where, "a 3x4 matrix (three rows of four numbers) is expected")
    for i, r in enumerate(rows):
        for k, x in enumerate(r):
            _num(x, f"{where}[{i}][{k}]")


def _segments(segs: Any, where: str, states: tuple[str, ...]) -> None:
    for i, s in enumerate(_list(segs, where)):
        # _fine inline: a long run's timelines hold some 16,000 segments
        if type(s) is dict and type(a := s.get("start")) is float and a - a == 0.0 \
                and type(b := s.get("end")) is float and b - b == 0.0 and b >= a and s.get("state") in states:
            continue  # the checks below pass: their messages not made
        w = f"{where}[{i}]"
        _dict(s, w, ("start", "end", "state"))
        _num(s["start"], f"{w}.start")
        _num(s["end"], f"{w}.end")
        if s["end"] < s["start"]:
            _fail(w, "end is before start")
        if s["state"] not in states:
            _fail(f"{w}.state", f"one of {', '.join(states)} is expected, not {s['state']!r}")


def _solid(s: Any, where: str) -> None:
    _dict(s, where, ("shape",))
    shape = s["shape"]
    if shape not in SHAPES:
        _fail(f"{where}.shape", f"one of {', '.join(SHAPES)} is expected, not {shape!r}")
    _matrix(s.get("pose"), f"{where}.pose")
    if shape == "box":
        size = _list(s.get("size"), f"{where}.size")
        if len(size) != 3:
            _fail(f"{where}.size", "three sides are expected")
        for k, x in enumerate(size):
            _num(x, f"{where}.size[{k}]")
    elif shape in ("cylinder", "sphere"):
        _num(s.get("radius"), f"{where}.radius")
        if shape == "cylinder":
            _num(s.get("length"), f"{where}.length")
    else:
        verts = _list(s.get("vertices"), f"{where}.vertices")
        for k, p in enumerate(verts):
            if not isinstance(p, list) or len(p) != 3:
                _fail(f"{where}.vertices[{k}]", "three coordinates are expected")
            for x in p:
                _num(x, f"{where}.vertices[{k}]")
        for k, t in enumerate(_list(s.get("triangles"), f"{where}.triangles")):
            if (not isinstance(t, list) or len(t) != 3
                    or any(isinstance(i, bool) or not isinstance(i, int) or not 0 <= i < len(verts) for i in t)):
                _fail(f"{where}.triangles[{k}]", "three vertex indices are expected")


def _check_arm(arm: Any, where: str, njoints: int | None) -> None:
    _dict(arm, where, ("root", "root_in_world", "joints", "links", "joint_names"))
    _matrix(arm["root_in_world"], f"{where}.root_in_world")
    known = {arm["root"]}
    for i, j in enumerate(_list(arm["joints"], f"{where}.joints")):
        w = f"{where}.joints[{i}]"
        _dict(j, w, ("name", "type", "parent", "child", "origin", "axis", "index"))
        if j["parent"] not in known:
            _fail(w, f"parent link {j['parent']!r} comes after its child (joints must be listed parents first)")
        known.add(j["child"])
        if j["type"] not in ("revolute", "continuous", "prismatic", "fixed"):
            _fail(f"{w}.type", f"revolute, continuous, prismatic or fixed is expected, not {j['type']!r}")
        _matrix(j["origin"], f"{w}.origin")
        if j["index"] is not None and (not isinstance(j["index"], int) or j["index"] < 0
                                       or (njoints is not None and j["index"] >= njoints)):
            _fail(f"{w}.index", f"the index of a trajectory joint is expected, not {j['index']!r}")
    for i, link in enumerate(_list(arm["links"], f"{where}.links")):
        _dict(link, f"{where}.links[{i}]", ("name", "solids"))
        if link["name"] not in known:
            _fail(f"{where}.links[{i}]", f"link {link['name']!r} is not reached by the joints")
        for k, s in enumerate(_list(link["solids"], f"{where}.links[{i}].solids")):
            _solid(s, f"{where}.links[{i}].solids[{k}]")


def _check_tracks(scene: dict) -> None:
    """`scene.tracks` ({name: {"times", "poses"}}) and the solids that hang on them."""
    tracks = _dict(scene.get("tracks") or {}, "scene.tracks")
    for name, tr in tracks.items():
        w = f"scene.tracks[{name!r}]"
        _dict(tr, w, ("times", "poses"))
        times, poses = _list(tr["times"], f"{w}.times"), _list(tr["poses"], f"{w}.poses")
        if not times or len(poses) != len(times):
            _fail(w, "one pose (or null) per time is expected, at least one")
        for k, t in enumerate(times):
            _num(t, f"{w}.times[{k}]")
            if k and t < times[k - 1]:
                _fail(f"{w}.times[{k}]", "times must not decrease")
        for k, p in enumerate(poses):
            if p is not None:
                _matrix(p, f"{w}.poses[{k}]")
    solids = [(f"scene.obstacles[{k}]", s) for k, s in enumerate(scene.get("obstacles") or [])]
    if scene.get("tool") is not None:
        solids += [(f"scene.tool.solids[{k}]", s) for k, s in enumerate(scene["tool"]["solids"])]
    for where, s in solids:
        if s.get("track") is not None and s["track"] not in tracks:
            _fail(f"{where}.track", f"{s['track']!r} is not in scene.tracks")


def _check_part(part: Any, where: str) -> None:
    """A part of the cell: its solids (in the part's frame) and its spans (carried or left)."""
    _dict(part, where, ("name", "solids", "spans"))
    for k, s in enumerate(_list(part["solids"], f"{where}.solids")):
        _solid(s, f"{where}.solids[{k}]")
    for k, span in enumerate(_list(part["spans"], f"{where}.spans")):
        if type(span) is dict and "end" in span and _fine(a := span.get("start")) and type(span.get("carried")) is bool \
                and ((b := span["end"]) is None or _fine(b) and b >= a) and _fine_matrix(span.get("pose")):
            continue  # the checks below pass: their messages not made
        w = f"{where}.spans[{k}]"
        _dict(span, w, ("start", "end", "carried", "pose"))
        _num(span["start"], f"{w}.start")
        _num(span["end"], f"{w}.end", null=True)
        if span["end"] is not None and span["end"] < span["start"]:
            _fail(w, "end is before start")
        if not isinstance(span["carried"], bool):
            _fail(f"{w}.carried", "true or false is expected")
        _matrix(span["pose"], f"{w}.pose")


def _check_joints(joints: Any) -> int:
    for i, j in enumerate(_list(joints, "trajectory.joints")):
        _dict(j, f"trajectory.joints[{i}]", ("name", "unit", "min", "max", "speed"))
        for k in ("min", "max", "speed"):
            _num(j[k], f"trajectory.joints[{i}].{k}", null=True)
    return len(joints)


def check_model(model: Any) -> None:
    """Raise ModelError if `model` is not a report model the page can show (docs/html-report.md)."""
    m = _dict(model, "model", ("version", "application", "verdict"))
    if m["version"] != VERSION:
        _fail("version", f"version {VERSION} is expected, not {m['version']!r}")
    _dict(m["application"], "application", ("name",))
    if any(not isinstance(t, str) for t in _list(m.get("limitations", []), "limitations")):
        _fail("limitations", "strings are expected")
    v = _dict(m["verdict"], "verdict", ("counts", "end_reason", "simulated_duration"))
    _num(v["simulated_duration"], "verdict.simulated_duration")
    for s in SEVERITIES:
        if not isinstance(v["counts"].get(s, 0), int):
            _fail(f"verdict.counts.{s}", "an integer is expected")
    if v.get("cycle_time") is not None:
        _dict(v["cycle_time"], "verdict.cycle_time", ("seconds",))
        _num(v["cycle_time"]["seconds"], "verdict.cycle_time.seconds")
    for i, d in enumerate(_list(m.get("diagnostics", []), "diagnostics")):
        w = f"diagnostics[{i}]"
        _dict(d, w, ("code", "severity", "message"))
        if d["severity"] not in SEVERITIES:
            _fail(f"{w}.severity", f"one of {', '.join(SEVERITIES)} is expected, not {d['severity']!r}")
        _num(d.get("time"), f"{w}.time", null=True)
        ex = d.get("excerpt")
        if ex is not None:
            _dict(ex, f"{w}.excerpt", ("first_line", "lines"))
            if not isinstance(ex["first_line"], int) or ex["first_line"] < 1:
                _fail(f"{w}.excerpt.first_line", "a line number (from 1) is expected")
            if any(not isinstance(t, str) for t in _list(ex["lines"], f"{w}.excerpt.lines")):
                _fail(f"{w}.excerpt.lines", "strings are expected")
    for i, mo in enumerate(_list(m.get("motions", []), "motions")):
        if type(mo) is dict and "id" in mo and "kind" in mo and _fine(mo.get("start")) and _fine(mo.get("end")) \
                and _fine_or_none(mo.get("vel"), mo.get("tvel"), mo.get("min_clearance")):
            continue  # the checks below pass: their messages not made
        w = f"motions[{i}]"
        _dict(mo, w, ("id", "kind", "start", "end"))
        _num(mo["start"], f"{w}.start")
        _num(mo["end"], f"{w}.end")
        for k in ("vel", "tvel", "min_clearance"):
            _num(mo.get(k), f"{w}.{k}", null=True)
    for i, c in enumerate(_list(m.get("cycles", []), "cycles")):
        _dict(c, f"cycles[{i}]", ("task", "iterations"))
        for k, it in enumerate(_list(c["iterations"], f"cycles[{i}].iterations")):
            _dict(it, f"cycles[{i}].iterations[{k}]", ("start", "duration"))
            _num(it["start"], f"cycles[{i}].iterations[{k}].start")
            _num(it["duration"], f"cycles[{i}].iterations[{k}].duration")
    njoints = None
    tr = m.get("trajectory")
    if isinstance(tr, Packed):  # a run's page: its values checked block by block (run_trajectory.py)
        njoints = _check_joints(tr.joints)
    elif tr is not None:
        _dict(tr, "trajectory", ("joints", "times", "positions", "velocities"))
        times = _series(tr["times"], "trajectory.times")
        n = len(times)
        _times(times, "trajectory.times")
        njoints = _check_joints(tr["joints"])
        for key in ("positions", "velocities"):
            rows = _list(tr[key], f"trajectory.{key}")
            if len(rows) != njoints:
                _fail(f"trajectory.{key}", f"one list per joint ({njoints}) is expected, not {len(rows)}")
            for i, row in enumerate(rows):
                if len(_series(row, f"trajectory.{key}[{i}]")) != n:
                    _fail(f"trajectory.{key}[{i}]", f"{n} values (one per time) are expected, not {len(row)}")
                _nums(row, f"trajectory.{key}[{i}]")
        if tr.get("tcp_speed") is not None:
            speed = _series(tr["tcp_speed"], "trajectory.tcp_speed")
            if len(speed) != n:
                _fail("trajectory.tcp_speed", f"{n} values (one per time) are expected, not {len(speed)}")
            _nums(speed, "trajectory.tcp_speed")
    for i, t in enumerate(_list(m.get("tasks", []), "tasks")):
        _dict(t, f"tasks[{i}]", ("name", "segments"))
        _segments(t["segments"], f"tasks[{i}].segments", TASK_STATES)
    _segments(m.get("arm_timeline", []), "arm_timeline", ARM_STATES)
    for i, e in enumerate(_list(m.get("io", []), "io")):
        _dict(e, f"io[{i}]", ("time", "kind", "link", "value"))
        _num(e["time"], f"io[{i}].time")
        if e["kind"] not in IO_KINDS:
            _fail(f"io[{i}].kind", f"one of {', '.join(IO_KINDS)} is expected, not {e['kind']!r}")
    for i, e in enumerate(_list(m.get("transcript", []), "transcript")):
        _dict(e, f"transcript[{i}]", ("time", "task", "kind", "text"))
        _num(e["time"], f"transcript[{i}].time")
    scene = m.get("scene")
    if scene is not None:
        _dict(scene, "scene")
        if scene.get("arm") is not None:
            _check_arm(scene["arm"], "scene.arm", njoints)
        if scene.get("tool") is not None:
            tool = _dict(scene["tool"], "scene.tool", ("name", "tcp", "solids"))
            _matrix(tool["tcp"], "scene.tool.tcp")
            for k, s in enumerate(_list(tool["solids"], "scene.tool.solids")):
                _solid(s, f"scene.tool.solids[{k}]")
        for k, s in enumerate(_list(scene.get("obstacles") or [], "scene.obstacles")):
            _solid(s, f"scene.obstacles[{k}]")
        _check_tracks(scene)
        for i, part in enumerate(_list(scene.get("parts") or [], "scene.parts")):
            _check_part(part, f"scene.parts[{i}]")
        if scene.get("joints") is not None:
            for k, x in enumerate(_list(scene["joints"], "scene.joints")):
                _num(x, f"scene.joints[{k}]")
