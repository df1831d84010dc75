"""The report model of a real run: a `SimReport` (its `SimResult` and the kept diagnostics).

    model = model_from_run(report, fail_on="error")            # report: reporting.sim_report.SimReport
    html = render(model)

Everything comes from the run's record (simulation/arm_record.py), not from its JSON: the motion
table (`result.motion.motions`), the cycle of each task that loops, the joint trajectory on the
controller's 4 ms clock with the TCP speed of the tool in use (`ArmRun.tcp_speed`), the tasks'
states over time (`result.task_states`), the arm moving or idle, the I/O log, the transcript, and
the 3D scene (`result.motion.scene`: the arm's chain and collision solids, the application's
frames; the tool; the cell's obstacles).

The cell and the per-motion clearance come from the collision checks when the run has them
(`result.collision.cell`, a `collision.cell.Cell`, and each motion's `clearance`, a
`collision.results.MotionReport`), or are given (`cell=`, `clearances=`: position in
`result.motion.motions` -> MotionReport).
"""

from __future__ import annotations

import math
import statistics
from itertools import pairwise
from pathlib import Path
from typing import Any

from .._common import SourceCache
from ..thinning import MOTION_ROWS, arm_spans, io_events, left_out, part_spans, task_changes
from .excerpts import SEVERITY_ORDER, excerpt
from .model import VERSION
from .run_trajectory import packed, series_model
from .series import rounded

TICK_S = 0.004
MAX_SAMPLES = 150_001  # ten minutes at 4 ms: a longer run is sampled at a multiple of 4 ms
MAX_MESH_TRIANGLES = 50_000  # per mesh drawn: beyond, its bounding box (said in limitations)


def _r(x: float | None, digits: int = 6) -> float | None:
    """A number rounded to `digits` decimals without a negative zero; None stays None."""
    return None if x is None else round(float(x), digits) + 0.0


def _m34(M) -> list[list[float]]:
    """A 4x4 (or 3x4) matrix as the model's 3x4 rows, mm."""
    return [[_r(M[i][k], 9) for k in range(4)] for i in range(3)]


def _diagnostics(report: Any, roots: list[str]) -> list[dict]:
    """The kept diagnostics, each with the lines around it (from files inside `roots` only)."""
    cache = SourceCache()
    out = []
    for d in report.diagnostics:
        out.append({"code": d.code, "name": report.rule_name(d.code), "severity": d.severity.label,
                    "message": d.message, "path": d.path, "line": d.line or None, "column": d.col or None,
                    "time": _r(d.time_us / 1e6) if d.time_us is not None else None, "task": d.task or None,
                    "program": d.program or None,
                    "excerpt": excerpt(cache, d.path, d.line, roots)})
    return out


def _motions(report: Any, m: Any, end: float, clearances: dict) -> list[dict]:
    """The motion table: the motions that ran within the run, with their closest approach to the
    cell (`clearances`: position in m.motions -> MotionReport)."""
    out = []
    shown: dict[str, Any] = {}  # the display path of each file, once (a cycle repeats its lines)
    to: dict[tuple, str] = {}  # the obstacle of each pair of bodies, once
    times: list[float] = []  # start, end, duration of each row: rounded at once below
    # each limits and closest approach object's rounded numbers, once (a cyclic run's rows share a
    # few: collect.py's one MotionLimits per mdesc, a repeated motion's first report); held with
    # them, so that an id is not another object's
    made: dict[int, tuple] = {}
    for k, motion in enumerate(m.motions):
        if motion.start is None or motion.start > end:
            continue  # failed before it moved (its diagnostic says why), or not started within the run
        if len(out) == MOTION_ROWS:
            break  # a long run: its first rows (reporting/thinning.py), said in the limitations
        stop = end if motion.end is None else min(motion.end, end)  # None: under way when the run ended
        src = motion.source
        if src.path not in shown:
            shown[src.path] = report.display((src.path, src.line, src.col, ""))
        where = shown[src.path]
        limits = motion.limits  # None: a connection move
        times += (motion.start, stop, stop - motion.start)
        entry = {
            "id": len(out) + 1, "kind": motion.kind, "path": where[0] if where else None, "line": src.line or None,
            "column": src.col or None, "task": src.task or None, "target": motion.target or None,
            "start": None, "end": None, "duration": None, "dominant_limit": motion.dominant_limit or None,
            "vel": None, "tvel": None,
            "min_clearance": None, "clearance_to": None,
            "state": motion.state, "motion_id": motion.id,
        }
        if limits is not None:
            held = made.get(id(limits))
            if held is None or held[0] is not limits:
                held = made[id(limits)] = (limits, _r(limits.vel, 3),
                                           _r(limits.tvel, 3) if limits.tvel is not None else None)
            entry["vel"], entry["tvel"] = held[1], held[2]
        mr = clearances.get(k)  # keyed by the position in m.motions (identifiers repeat, 10.6)
        # a repeated motion's report is a view shifting its first one's times (collision/results.py):
        # the first's closest approach read as it is, its time not used here
        c = getattr(getattr(mr, "own", mr), "min_clearance", None)
        if c is not None:
            held = made.get(id(c))
            if held is None or held[0] is not c:
                held = made[id(c)] = (c, _r(c.mm, 3))
            entry["min_clearance"] = held[1]
            pair = (c.body_a, c.body_b)
            if pair not in to:
                to[pair] = _obstacle_of(*pair)
            entry["clearance_to"] = to[pair]
        out.append(entry)
    if out:
        import numpy as np

        t = iter(rounded(np.array(times, dtype=float), 6).tolist())  # as _r, in bulk (series.py)
        for entry in out:
            entry["start"], entry["end"], entry["duration"] = next(t), next(t), next(t)
    return out


def _obstacle_of(a: str, b: str) -> str:
    """The cell's side of a clearance: the collision checks name bodies "obstacle 'table'",
    "link_4 (forearm)", "tool tGripper 'jaw'"... (collision/bodies.py): the obstacle's name."""
    for label in (b, a):
        if label.startswith("obstacle "):
            name = label[len("obstacle "):]
            return name[1:-1] if len(name) >= 2 and name[0] == name[-1] == "'" else name
    return b


def _cycles(report: Any, m: Any, end: float) -> tuple[list[dict], dict | None]:
    """Each looping task's iterations, and the cycle time of the verdict (cycles_model)."""
    loops = []
    for task in sorted(m.cycles):
        st = m.cycles[task]
        if st.marker is None or not st.starts:
            continue
        where = report.display((st.marker[0], st.marker[1], st.marker[2], ""))
        loops.append({"task": task, "loop": st.kind, "path": where[0], "line": st.marker[1],
                      "starts": list(st.starts)})
    cycles, cycle_time = cycles_model(loops, end)
    if cycle_time is not None and m.acceleration_range is not None:
        spread = m.acceleration_range.cycle_time(cycle_time["task"])
        if spread is not None:  # issue 23: the model assumes the accelerations
            cycle_time["range"] = [_r(spread[0]), _r(spread[1])]
            cycle_time["off_by"] = m.acceleration_range.off_by
    return cycles, cycle_time


def cycles_model(loops: list[dict], end: float) -> tuple[list[dict], dict | None]:
    """The page's cycles and the verdict's cycle time, from each looping task's `task`, `loop`
    (while, do, for), `path` and `line` of its cycle's loop statement and `starts` (when the arm
    started each pass; and `times` between them, when given): the iterations (the last one cut by
    the end of the run), and the median of the task with the most complete cycles (ties: the
    first task by name, as simulation.arm_record.main_cycle)."""
    cycles, best = [], None
    for loop in sorted(loops, key=lambda c: c["task"]):
        starts = loop["starts"]
        if not starts or loop.get("path") is None or loop.get("line") is None:
            continue
        name = Path(loop["path"]).name
        times = loop.get("times") or [b - a for a, b in pairwise(starts)]
        its = [{"start": _r(a), "duration": _r(d), "complete": True} for a, d in zip(starts, times)]
        if starts[-1] < end:
            its.append({"start": _r(starts[-1]), "duration": _r(end - starts[-1]), "complete": False})
        what = f"{loop['loop']} loop" if loop.get("loop") else "loop"
        cycles.append({"task": loop["task"], "path": loop["path"], "line": loop["line"],
                       "label": f"{what} at line {loop['line']} of {name}", "iterations": its})
        if times and (best is None or len(times) > len(best[1])):
            best = (loop, times, what, name)
    cycle_time = None
    if best is not None:
        loop, times, what, name = best
        cycle_time = {"seconds": _r(statistics.median(times)), "task": loop["task"],
                      "basis": f"median of {len(times)} complete cycles of task {loop['task']} (the {what} at "
                               f"line {loop['line']} of {name})"}
    return cycles, cycle_time


def sample_period(end_s: float) -> float:
    """The controller's 4 ms, or a multiple of it for a run longer than MAX_SAMPLES ticks (the
    page draws at most 15,000 min/max buckets anyway: memory and size stay bounded)."""
    ticks = int(end_s / TICK_S + 1e-9)
    return TICK_S * max(1, -(-ticks // (MAX_SAMPLES - 1)))


def _trajectory(report: Any, m: Any, limits: list[str], moving: list | None = None) -> dict | None:
    """The joints and the TCP speed over the run, every 4 ms (or a multiple of it), as array('d')
    (series.py). `moving`: the intervals in which the arm moves (default: computed)."""
    clock = _clock(report, m, limits, m.trajectory.moving(m.end_s) if moving is None else moving)
    return None if clock is None else series_model(m, *clock)


def _packed(report: Any, m: Any, limits: list[str], moving: list) -> Any:
    """The trajectory as the page's script reads it (series.Packed), made block by block; a value
    check_model would refuse: the model's series instead, so that check_model says which."""
    clock = _clock(report, m, limits, moving)
    if clock is None:
        return None
    return packed(m, *clock) or series_model(m, *clock)


def _clock(report: Any, m: Any, limits: list[str], moving: list) -> tuple[float, int] | None:
    """The page's clock of the run: (period, samples from 0), or None: no motion, or the
    trajectory left out (said in `limits`)."""
    if not moving:
        return None
    omitted = left_out(report.result, "The plots and the 3D view's motion are")
    if omitted is not None:
        limits.append(omitted + ".")
        return None
    dt = sample_period(m.end_s)
    if dt > TICK_S:
        limits.append(f"A long run: the plots and the 3D view sample the trajectory every {dt * 1000:g} ms "
                      f"(a multiple of the controller's 4 ms), at most {MAX_SAMPLES} samples.")
    return dt, math.floor(m.end_s / dt + 1e-9) + 1  # as motion.trajectory.tick_times from 0


def _task_segments(result: Any, end: float, limits: list[str]) -> list[dict]:
    """Each task's states over the run, as segments of the timeline: up to the first task state
    change left out on a long run (reporting/thinning.py, said in `limits`)."""
    by_task: dict[str, list[dict]] = {}
    changes, note = task_changes(result)
    if note is not None:
        end = min(end, _r(result.task_states[len(changes)].time_us / 1e6))
        _note(note, limits)
    times = [min(c.time_us / 1e6, end) for c in changes]
    if times:
        import numpy as np

        shown = rounded(np.array(times, dtype=float), 6).tolist()  # as _r, in bulk (series.py)
    for c, t, r in zip(changes, times, shown if times else ()):
        segs = by_task.setdefault(c.task, [])
        if segs and segs[-1]["end"] is None:
            segs[-1]["end"] = r
            if segs[-1]["end"] <= segs[-1]["start"]:
                segs.pop()
        if c.state != "ended" and t < end:
            segs.append({"start": r, "end": None, "state": c.state, "detail": c.detail or None})
    out = []
    for name, segs in by_task.items():
        if segs and segs[-1]["end"] is None:
            segs[-1]["end"] = _r(end)
        segs = [s for s in segs if s["end"] > s["start"]]
        if segs:  # (stop() runs after a run cut by --duration: at its very end)
            out.append({"name": name, "segments": segs})
    return out


def _note(note: str | None, limits: list[str]) -> None:
    """A bound reached on a long run (reporting/thinning.py), said in `limits` as a sentence."""
    if note is not None:
        limits.append(note[0].upper() + note[1:] + ".")


def _arm_timeline(moving: list, end: float, limits: list[str]) -> list[dict]:
    """The arm moving or idle over the run (`moving`: the intervals in which it moves): its first
    spans on a long run (thinning.py, said), the others counted, never made."""
    spans, note = arm_spans(_arm_spans(moving, end), lambda s: _r(s[0]))
    _note(note, limits)
    ends = _bulk([x for a, b, _ in spans for x in (a, b)])
    return [{"start": ends[2 * k], "end": ends[2 * k + 1], "state": state} for k, (_, _, state) in enumerate(spans)]


def _bulk(values: list) -> list:
    """[_r(x) for x in values] in bulk (series.rounded)."""
    if not values:
        return []
    import numpy as np

    return rounded(np.array(values, dtype=float), 6).tolist()


def _arm_spans(moving: list, end: float):
    """(start, end, "idle" or "moving") over the run."""
    t = 0.0
    for a, b in moving:
        a, b = min(a, end), min(b, end)
        if a > t:
            yield t, a, "idle"
        if b > a:
            yield a, b, "moving"
        t = max(t, b)
    if t < end:
        yield t, end, "idle"


def _shape_solid(name: str, shape: Any, pose, limits: list[str]) -> dict:
    """A solid of the cell (a collision.cell shape) at `pose`, as the 3D view draws it (a mesh of
    too many triangles as its bounding box)."""
    import numpy as np

    s: dict[str, Any] = {"name": name, "pose": _m34(pose)}
    if shape.kind == "box":
        s.update(shape="box", size=[_r(x, 6) for x in shape.size])
    elif shape.kind == "cylinder":
        s.update(shape="cylinder", radius=_r(shape.size[0], 6), length=_r(shape.size[1], 6))
    elif shape.kind == "sphere":
        s.update(shape="sphere", radius=_r(shape.size[0], 6))
    else:
        v = np.asarray(shape.mesh.vertices, dtype=float)
        f = np.asarray(shape.mesh.faces, dtype=int)
        if len(f) > MAX_MESH_TRIANGLES:
            lo, hi = v.min(axis=0), v.max(axis=0)
            box = np.eye(4)
            box[:3, 3] = (lo + hi) / 2
            limits.append(f"The mesh {name!r} has {len(f)} triangles: the 3D view draws its bounding box.")
            return {"name": name, "shape": "box", "size": [_r(x, 6) for x in (hi - lo)],
                    "pose": _m34(np.asarray(pose) @ box)}
        s.update(shape="mesh", vertices=(np.round(v, 4) + 0.0).tolist(), triangles=f.tolist())
    return s


def _track(changes) -> dict:
    """A frame or tool variable over the run, as changes: {"times", "poses"} (null: no value)."""
    return {"times": [_r(c.time) for c in changes],
            "poses": [None if c.matrix is None else _m34(c.matrix) for c in changes]}


def _hung_on(cell: Any) -> dict[str, str]:
    """The application frames the cell's obstacles are placed in ("frame") and the tool variables
    its tool solids hang on ("tool"), by name as the program writes it without spaces."""
    wanted = {o.frame.replace(" ", ""): "frame" for o in cell.obstacles if o.frame != "world"}
    wanted.update({t.tool.replace(" ", ""): "tool" for t in cell.tools if t.tool != "flange"})
    return wanted


def _tracks(m: Any, cell: Any, limits: list[str]) -> dict:
    """The frames obstacles hang on and the tools tool solids hang on, over the run: as the
    collision checks placed them (`m.cell_timeline`), else as the run left them (said)."""
    timeline = m.cell_timeline
    wanted = _hung_on(cell)
    out = {}
    end_of_run = []
    for name, kind in sorted(wanted.items()):
        changes = None if timeline is None else (timeline.frames if kind == "frame" else timeline.tools).get(name)
        if changes:
            out[name] = _track(changes)
            continue
        if timeline is None and kind == "frame":
            end_of_run.append(name)
        f = m.scene.frames.get(name)
        out[name] = {"times": [0.0], "poses": [None if f is None else _m34(f.matrix)]}
    if end_of_run:
        limits.append("The collision checks did not run: obstacles placed in application frames are drawn where "
                      "those frames are at the end of the run.")
    return out


def _parts(m: Any, cell: Any, limits: list[str]) -> list[dict]:
    """The cell's parts, each with its solids (in the part's frame) and its spans: carried on the
    flange or left in the cell, from the collision checks (`m.cell_timeline`)."""
    if not cell.parts:
        return []
    if m.cell_timeline is None:
        limits.append("The collision checks did not run: the parts of the cell file (what the tool carries) are "
                      "not drawn.")
        return []
    out: dict[str, dict] = {}
    spans, note = part_spans(m.cell_timeline.parts)  # the first spans on a long run (thinning.py)
    _note(note, limits)
    for p in cell.parts:
        part = out.setdefault(p.name, {"name": p.name, "solids": [], "spans": []})
        part["solids"].append(_shape_solid(p.name, p.shape, p.pose, limits))
    if spans:
        import numpy as np

        # as _m34 of each pose, in bulk (series.py)
        poses = rounded(np.array([span.pose for span in spans], dtype=float)[:, :3, :4], 9).tolist()
        for span, pose in zip(spans, poses):
            out[span.name]["spans"].append({"start": _r(span.start), "end": _r(span.end), "carried": span.carried,
                                            "pose": pose})
    return [p for p in out.values() if p["spans"]]


def _scene(result: Any, m: Any, cell: Any, limits: list[str]) -> dict:
    """The 3D view of a run (scene_model), with the frames and tools the cell hangs on, and the
    parts, over the run."""
    uses = [(motion.tool, motion.tool_in_flange) for motion in m.motions
            if motion.kind != "connection" and motion.tool_in_flange is not None and motion.tool]
    tracks = _tracks(m, cell, limits) if cell is not None else None
    parts = _parts(m, cell, limits) if cell is not None else None
    return scene_model(m.scene.kinematics.chain(), m.scene.initial_joints or [0.0] * m.scene.axes,
                       {name: f.matrix for name, f in m.scene.frames.items()}, uses, cell, limits,
                       tracks=tracks, parts=parts)


UNDEFINED_FRAME = "which the run did not define"


def _static_tracks(cell: Any, frames: dict, tool_uses: list) -> dict:
    """Tracks for a report that records one value per frame or tool (a JSON sim report): each at
    that value from the start (null when it has none)."""
    import numpy as np

    tcp = dict(tool_uses)
    wanted = _hung_on(cell)
    out = {}
    for name, kind in sorted(wanted.items()):
        M = frames.get(name)
        if M is None and kind == "tool":
            M = tcp.get(name)
        out[name] = {"times": [0.0], "poses": [None if M is None else _m34(np.asarray(M, dtype=float))]}
    return out


def scene_model(chain: dict, joints, frames: dict, tool_uses: list, cell: Any, limits: list[str],
                undefined: str = UNDEFINED_FRAME, tracks: dict | None = None, parts: list | None = None) -> dict:
    """The 3D view: the arm's `chain` at `joints`, the tool most motions use (`tool_uses`: (tool
    name, its TCP in the flange, 4x4) per motion; its solids from the cell file), the cell's
    obstacles and parts. `tracks`: the frames and tools the cell's solids hang on over the run
    (from_run._tracks); None: their one value in `frames` (application frames and tools by name,
    4x4). A solid placed in a frame without a value is not drawn, and `limits` says why
    (`undefined`). `parts`: the parts' spans (from_run._parts); None: not known, not drawn (said)."""
    import numpy as np

    scene: dict[str, Any] = {"arm": chain, "tool": None, "obstacles": [], "joints": [_r(x) for x in joints]}
    if cell is not None and tracks is None:
        tracks = _static_tracks(cell, frames, tool_uses)
    # the tool: the one the motions use most (the page draws one tool)
    counts: dict[str, int] = {}
    tcp: dict[str, Any] = {}
    for name, matrix in tool_uses:
        counts[name] = counts.get(name, 0) + 1
        tcp.setdefault(name, matrix)
    if counts:
        name = max(sorted(counts), key=counts.get)
        solids = []
        if cell is not None:  # a tool solid sits in its tool variable's frame (a track in the flange)
            for ts in cell.tools:
                solid = _shape_solid(ts.name, ts.shape, ts.pose, limits)
                if ts.tool != "flange":
                    key = ts.tool.replace(" ", "")
                    if all(p is None for p in tracks[key]["poses"]):
                        limits.append(f"The tool solid {ts.name!r} hangs on {ts.tool}, {undefined}: not drawn.")
                        continue
                    solid["track"] = key
                solids.append(solid)
        scene["tool"] = {"name": name, "tcp": _m34(np.asarray(tcp[name], dtype=float)), "solids": solids}
    if cell is not None:
        for ob in cell.obstacles:
            solid = _shape_solid(ob.name, ob.shape, ob.pose, limits)
            if ob.frame != "world":
                key = ob.frame.replace(" ", "")
                if all(p is None for p in tracks[key]["poses"]):
                    limits.append(f"The obstacle {ob.name!r} is placed in {ob.frame}, {undefined}: not drawn.")
                    continue
                solid["track"] = key
            scene["obstacles"].append(solid)
        if parts is None and cell.parts:
            limits.append("The parts of the cell file (what the tool carries) are not drawn: the report does not "
                          "record when they are taken and left.")
        scene["parts"] = parts or []
        scene["tracks"] = tracks
    return scene


def model_from_run(report: Any, *, fail_on: str = "error", cell: Any = None, clearances: dict | None = None,
                   roots: list[str] | None = None, title: str | None = None, packed: bool = False) -> dict:
    """The report model (docs/html-report.md) of a run. `report`: a `reporting.sim_report.SimReport`.
    `cell`, `clearances`: the cell and per-motion `MotionReport`s by position in the motions
    (default: `result.collision.cell` and each motion's `clearance`).
    `roots`: folders whose files the excerpts may quote (default: the application's folder).
    `packed`: the trajectory as the page's script reads it (series.Packed, the page of a run), not
    its series."""
    result = report.result
    collision = getattr(result, "collision", None)
    if cell is None and collision is not None:
        cell = getattr(collision, "cell", None)
    m = result.motion
    if clearances is None:
        clearances = {k: mo.clearance for k, mo in enumerate(m.motions) if mo.clearance is not None} if m else {}
    if roots is None:
        roots = [str(Path(result.app_path).parent)]
    end = _r(result.sim_time_us / 1e6)
    counts = {s: sum(1 for d in report.diagnostics if d.severity.label == s) for s in ("error", "warning", "info")}
    threshold = SEVERITY_ORDER.get(fail_on)
    passed = threshold is None or not any(SEVERITY_ORDER[s] >= threshold and counts[s] for s in counts)
    limits: list[str] = []
    motions, cycles, cycle_time, trajectory, arm_timeline = [], [], None, None, []
    if m is not None:
        motions = _motions(report, m, end, clearances)
        if len(motions) == MOTION_ROWS and len(m.motions) > MOTION_ROWS:
            limits.append(f"A long run: the motion table lists the first {MOTION_ROWS} of {len(m.motions)} motions; "
                          "the cycles, the findings and the plots cover the whole run.")
        cycles, cycle_time = _cycles(report, m, end)
        moving = m.trajectory.moving(m.end_s)  # once: it walks the whole run
        trajectory = (_packed if packed else _trajectory)(report, m, limits, moving)
        arm_timeline = _arm_timeline(moving, end, limits)
        if cell is None:
            limits.append("No cell file: the 3D view has no obstacles and the motions no clearance (docs/cell.md).")
    elif result.robot is None:
        limits.append("No arm model (--robot): no motion, trajectory or 3D view.")
    scene = _scene(result, m, cell, limits) if m is not None else None
    tasks = _task_segments(result, end, limits)
    io, note = io_events(result)  # the first changes on a long run (thinning.py)
    _note(note, limits)
    return {
        "version": VERSION,
        "title": title or result.application,
        "tool": {"name": "val3check", "version": report.tool_version},
        "application": {"name": result.application, "path": report.app_path},
        "robot": {"name": m.scene.name} if m is not None else None,
        "synthetic": False,
        "limitations": limits,
        "verdict": {
            "counts": counts,
            "fail_on": fail_on,
            "passed": passed,
            "end_reason": result.end_reason,
            "end_message": result.end_message,
            "simulated_duration": end,
            "cycle_time": cycle_time,
        },
        "diagnostics": _diagnostics(report, roots),
        "motions": motions,
        "cycles": cycles,
        "trajectory": trajectory,
        "tasks": tasks,
        "arm_timeline": arm_timeline,
        "io": [{"time": t, "kind": e.kind, "link": e.link,
                "names": report.link_names.get((e.kind, e.link), []),
                "value": e.value if not isinstance(e.value, float) or e.value == e.value else None,
                "source": e.source} for e, t in zip(io, _bulk([e.time_us / 1e6 for e in io]))],
        "transcript": [{"time": _r(e.time_us / 1e6), "task": e.task, "kind": e.kind, "text": e.text,
                        "screen": e.screen} for e in result.transcript],
        "screen": result.screen,
        "scene": scene,
    }


def render_run(report: Any, *, fail_on: str = "error") -> str:
    """`val3check sim --report html`: the page of a run."""
    return "".join(page_pieces(report, fail_on=fail_on))


def page_pieces(report: Any, *, fail_on: str = "error"):
    """The page of a run piece by piece (page.pieces), its trajectory packed block by block."""
    from .page import pieces

    return pieces(model_from_run(report, fail_on=fail_on, packed=True))
