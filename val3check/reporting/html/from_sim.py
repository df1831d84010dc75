"""A report model from the sim's JSON report (docs/sim-report.md, versions 1 and 2) and the arm model.

    model = model_from_sim_report(json.load(open("run.json")), ReportScene(), fail_on="error")

What the JSON report holds goes in as it is: how the run ended, the diagnostics (with their
source excerpt, read from the application's folder and the given roots only), the I/O log, the
transcript and the final user page; and from version 2's `motion` section, the motion table
(with each motion's closest approach from the `collision` section), the cycles and the cycle time,
the joint trajectory on the 4 ms clock (the arm stands where the last segment left it between
segments) with the TCP speed of the tool in use, the arm moving or idle, and the 3D view that
plays it: the arm model of the run (`robot.name`, a catalogue arm, or the URDF given), the tool
most motions use, and the cell file's obstacles when the file is inside the roots. The report names
the arm and the cell without their geometry: `scene` rebuilds them (a
`simulation.report_scene.ReportScene`), so that this module imports nothing of robot/, geometry/ or
collision/.

What the JSON report does not record is absent and said so in `limitations` (shown at the top of
the page): the tasks' states over time, the motion descriptors' speeds, and the application's
frames (a solid of the cell placed in one is not drawn), and when the parts are taken and left.

The page is bounded as a run's page is (reporting/thinning.py): the first MOTION_ROWS motions,
ARM_SPANS moving and idle spans and IO_EVENTS I/O changes, each said in `limitations` when there
were more (a JSON report keeps every I/O change of its run; there is no task timeline nor part
span to bound).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from .. import thinning
from .._common import SourceCache
from .excerpts import SEVERITY_ORDER, excerpt
from .from_run import TICK_S, _note, _obstacle_of, _r, cycles_model, sample_period, scene_model
from .model import VERSION, ModelError
from .series import doubles, rounded


def model_from_sim_report(report: dict[str, Any], scene: Any, *, fail_on: str = "error",
                          roots: list[str] | None = None, title: str | None = None) -> dict:
    """The report model of a run described by the sim's JSON report (a dict, version 1 or 2).

    `scene`: what rebuilds the arm and the cell the report names (simulation.report_scene.ReportScene:
    `arm(name)`, raising robot.RobotError when there is no such arm, `cell(path, roots)`,
    `trsf_matrix(trsf)`). `roots`: folders whose files may be quoted in the excerpts or read as the
    run's cell (default: the folder of the application's project file). Raises ModelError for a
    report that is not a version 1 or 2 sim report, or whose motion section does not hold together."""
    if not isinstance(report, dict) or report.get("version") not in (1, 2) or "end" not in report \
            or "summary" not in report:
        raise ModelError("not a version 1 or 2 report of `val3check sim --report json` (docs/sim-report.md)")
    app = report.get("application") or {}
    if roots is None:
        roots = [str(Path(app.get("path") or ".").parent)]
    cache = SourceCache()
    diagnostics = []
    for d in report.get("diagnostics", []):
        entry = {k: d.get(k) for k in ("code", "name", "severity", "message", "path", "line", "column", "time", "task",
                                       "program")}
        entry["excerpt"] = excerpt(cache, d.get("path"), d.get("line"), roots)
        diagnostics.append(entry)
    counts = {s: int(report["summary"].get(s, 0)) for s in ("error", "warning", "info")}
    threshold = SEVERITY_ORDER.get(fail_on)
    passed = threshold is None or not any(SEVERITY_ORDER[s] >= threshold and counts[s] for s in counts)
    end = _r(report.get("simulated_duration") or 0.0)
    limitations = [("The JSON sim report does not record what each task was doing over time: no task timeline "
                    "(`val3check sim --report html` has it).")]
    robot = report.get("robot")
    motion = report.get("motion")
    view, motions, cycles, cycle_time, trajectory, arm_timeline = None, [], [], None, None, []
    if robot:
        arm = scene.arm(robot["name"])
        if motion:
            try:
                motions = _motions(motion, report.get("collision"), end, limitations)
                cycles, cycle_time = cycles_model(motion.get("cycles", []), end)
                trajectory = _trajectory(motion, robot, arm, scene, end, limitations)
                arm_timeline = _arm_timeline(motion, end, limitations)
            except (KeyError, TypeError, ValueError, IndexError) as exc:
                raise ModelError(f"the `motion` section does not hold together ({type(exc).__name__}: {exc})") \
                    from None
            if any(m.get("kind") != "connection" for m in motion.get("motions", [])):
                limitations.append("The JSON sim report does not record the motion descriptors: no vel or tvel "
                                   "in the motion table, no dashed speed limits on the plots.")
        view = _scene(robot, arm, scene, motion, report.get("collision"), roots, limitations)
    elif report.get("version") == 2 and motion is None:
        limitations.append("No arm model (--robot): no motion, trajectory or 3D view.")
    io, note = thinning.first(report.get("io_log", []), thinning.IO_EVENTS, "the I/O log holds", "I/O changes",
                              lambda e: e["time"])  # the first changes, as a run's page (from_run.py)
    _note(note, limitations)
    return {
        "version": VERSION,
        "title": title or app.get("name") or "val3check sim",
        "tool": report.get("tool") or {"name": "val3check"},
        "application": {"name": app.get("name") or "", "path": app.get("path")},
        "robot": {"name": robot["name"]} if robot else None,
        "limitations": limitations,
        "verdict": {
            "counts": counts,
            "fail_on": fail_on,
            "passed": passed,
            "end_reason": report["end"].get("reason", ""),
            "end_message": report["end"].get("message"),
            "simulated_duration": end,
            "cycle_time": cycle_time,
        },
        "diagnostics": diagnostics,
        "motions": motions,
        "cycles": cycles,
        "trajectory": trajectory,
        "tasks": [],
        "arm_timeline": arm_timeline,
        "io": io,
        "transcript": list(report.get("transcript", [])),
        "screen": report.get("screen"),
        "scene": view,
    }


def _motions(motion: dict, collision: dict | None, end: float, limits: list[str]) -> list[dict]:
    """The motion table: the motions that ran within the run, with their closest approach to the
    cell (the `collision` section's motions, by position in `motion.motions`): the first
    MOTION_ROWS, as a run's page (the JSON report keeps as many, and counts the others)."""
    closest = {c["motion"]: c.get("min_clearance") for c in (collision or {}).get("motions", [])}
    out = []
    listed = motion.get("motions", [])
    total = len(listed) + int((motion.get("motions_omitted") or {}).get("count", 0))
    for k, mo in enumerate(listed):
        if mo.get("start") is None or mo["start"] > end:
            continue  # failed before it moved (its diagnostic says why), or not started within the run
        if len(out) == thinning.MOTION_ROWS:
            break
        stop = end if mo.get("end") is None else min(mo["end"], end)  # None: under way when the run ended
        c = closest.get(k)
        out.append({
            "id": len(out) + 1, "kind": mo["kind"], "path": mo.get("path"), "line": mo.get("line"),
            "column": mo.get("column"), "task": mo.get("task"), "target": mo.get("target"),
            "start": _r(mo["start"]), "end": _r(stop),
            "duration": _r(mo["duration"] if mo.get("end") is not None and mo["end"] <= end
                           and mo.get("duration") is not None else stop - mo["start"]),
            "dominant_limit": mo.get("dominant_limit"), "vel": None, "tvel": None,
            "min_clearance": _r(c["mm"], 3) if c else None,
            "clearance_to": _obstacle_of(c["body_a"], c["body_b"]) if c else None,
            "state": mo.get("state"), "motion_id": mo.get("id"),
        })
    if len(out) == thinning.MOTION_ROWS and total > thinning.MOTION_ROWS:
        limits.append(f"A long run: the motion table lists the first {thinning.MOTION_ROWS} of {total} motions; "
                      "the cycles, the findings and the plots cover the whole run.")
    return out


def _joints_on_the_clock(motion: dict, robot: dict, end: float):
    """(tick indexes, joints (N, axes), joint speeds (N, axes)) at every 4 ms tick of the run from
    the trajectory's segments: between two segments the arm stands where the first one ended
    (before the first, at the run's initial joints)."""
    import numpy as np

    tr = motion["trajectory"]
    if abs(float(tr.get("period", TICK_S)) - TICK_S) > 1e-12:
        raise ValueError(f"a trajectory period of {tr.get('period')} s (the controller's is {TICK_S} s)")
    axes = int(tr["axes"])
    ticks = int(end / TICK_S + 1e-9)
    q = np.full((ticks + 1, axes), np.nan)
    v = np.zeros((ticks + 1, axes))
    q[0] = robot.get("initial_joints") or [0.0] * axes
    for seg in tr["segments"]:
        k0 = int(seg["first_tick"])
        P, V = np.asarray(seg["positions"], dtype=float), np.asarray(seg["velocities"], dtype=float)
        n = max(0, min(len(P), ticks + 1 - k0))
        q[k0:k0 + n], v[k0:k0 + n] = P[:n].reshape(n, axes), V[:n].reshape(n, axes)
    for k in range(1, ticks + 1):  # standing still: the last position
        if np.isnan(q[k, 0]):
            q[k] = q[k - 1]
    return q, v


def _trajectory(motion: dict, robot: dict, arm: Any, scene: Any, end: float, limits: list[str]) -> dict | None:
    """The joints and the TCP speed over the run, every 4 ms (or a multiple of it, as from_run)."""
    import numpy as np

    if not motion["trajectory"].get("segments"):
        return None
    q, v = _joints_on_the_clock(motion, robot, end)
    dt = sample_period(end)
    step = round(dt / TICK_S)
    if step > 1:
        limits.append(f"A long run: the plots and the 3D view sample the trajectory every {dt * 1000:g} ms "
                      f"(a multiple of the controller's 4 ms), at most {len(q[::step])} samples.")
    q, v = q[::step], v[::step]
    times = np.arange(len(q)) * dt
    uses = [(mo["start"], scene.trsf_matrix(mo.get("tool_in_flange"))) for mo in motion.get("motions", [])
            if mo.get("start") is not None and mo.get("kind") != "connection"]
    speed = arm.tcp_speed(uses, times, q, v)
    units = motion["trajectory"].get("units") or ["deg"] * q.shape[1]
    lims = robot.get("joint_limits") or [[None, None]] * q.shape[1]
    speeds = robot.get("nominal_speeds") or [None] * q.shape[1]
    return {
        "joints": [{"name": n, "unit": u, "min": lo, "max": hi, "speed": s}
                   for n, u, (lo, hi), s in zip(arm.joint_names, units, lims, speeds)],
        "times": doubles(rounded(times, 6)),  # array('d'), as a run's model (series.py)
        "positions": [doubles(row) for row in np.round(q.T, 6) + 0.0],
        "velocities": [doubles(row) for row in np.round(v.T, 4) + 0.0],
        "tcp_speed": doubles(np.round(speed, 3) + 0.0),
    }


def _arm_timeline(motion: dict, end: float, limits: list[str]) -> list[dict]:
    """The arm moving or idle over the run. Each segment of the trajectory runs from the last tick
    at or before a moving interval to the first at or after its end (sim_json.py): the interval's
    ends are within a tick of the segment's, at a motion's start and end when one falls there
    (the ends of motions give them to the microsecond), else at the segment's ticks."""
    starts = sorted(m["start"] for m in motion.get("motions", []) if m.get("start") is not None)
    ends = sorted(m["end"] for m in motion.get("motions", []) if m.get("end") is not None)
    spans = []
    for seg in motion["trajectory"]["segments"]:
        k0, k1 = int(seg["first_tick"]), int(seg["first_tick"]) + len(seg["positions"]) - 1
        a = next((t for t in starts if k0 * TICK_S - 1e-6 <= t < (k0 + 1) * TICK_S), k0 * TICK_S)
        b = next((t for t in reversed(ends) if (k1 - 1) * TICK_S < t <= k1 * TICK_S + 1e-6), k1 * TICK_S)
        a, b = min(a, end), min(b, end)
        if b > a:
            spans.append((a, b))
    segs, t = [], 0.0
    for a, b in spans:
        if a > t:
            segs.append({"start": _r(t), "end": _r(a), "state": "idle"})
        segs.append({"start": _r(a), "end": _r(b), "state": "moving"})
        t = b
    if t < end:
        segs.append({"start": _r(t), "end": _r(end), "state": "idle"})
    segs, note = thinning.arm_spans(segs)  # the first spans, as a run's page (from_run.py)
    _note(note, limits)
    return segs


def _cell(collision: dict | None, roots: list[str], scene: Any, limits: list[str]) -> Any:
    """The run's cell (a collision.cell.Cell) read again from its file by `scene`, when the report
    names one inside the roots; None otherwise (and `limits` says why)."""
    cell = (collision or {}).get("cell") or {}
    path = cell.get("path")
    if not path or not cell.get("usable"):
        return None
    p = Path(path).resolve()
    if not any(p.is_relative_to(Path(r).resolve()) for r in roots):
        limits.append(f"The cell file {path} is outside the application's folder and the given roots: not drawn.")
        return None
    cell, problem = scene.cell(str(p), roots)  # meshes: beside it or in the roots
    if problem is not None:
        limits.append(f"The cell file {path} cannot be read again: {problem}; the 3D view has no obstacles.")
    return cell


def _scene(robot: dict, arm: Any, scene: Any, motion: dict | None, collision: dict | None, roots: list[str],
           limits: list[str]) -> dict:
    """The 3D view: the arm at its initial joints, the tool most motions use, the cell's obstacles."""
    chain = arm.chain()
    uses = [(mo["tool"], scene.trsf_matrix(mo["tool_in_flange"])) for mo in (motion or {}).get("motions", [])
            if mo.get("kind") != "connection" and mo.get("tool_in_flange") is not None and mo.get("tool")]
    joints = robot.get("initial_joints") or [0.0] * len(arm.joint_names)
    cell = _cell(collision, roots, scene, limits) if motion else None
    if motion is None:
        limits.append(f"The JSON report has no motion: the 3D view shows {robot['name']} at its initial joint "
                      "position.")
    tools = {name: M for name, M in uses}
    return scene_model(chain, joints, tools, uses, cell, limits,
                       undefined="an application frame the JSON sim report does not record")
