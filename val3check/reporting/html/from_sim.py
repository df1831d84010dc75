"""A report model from the sim's JSON report (docs/sim-report.md, versions 1 and 2) and the arm model.

    model = model_from_sim_report(json.load(open("run.json")), fail_on="error")

What the JSON report holds goes in as it is: how the run ended, the diagnostics (with their
source excerpt, read from the application's folder and the given roots only), the I/O log, the
transcript and the final user page, and the arm model of the run (`robot.name`, a catalogue arm,
or `arm_urdf`) at its initial joint position. What is not drawn yet is absent and said so in
`limitations` (shown at the top of the page): the tasks' states over time, and the arm's motion
(version 2's `motion`: the next version of the page draws it).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from .._common import SourceCache
from .excerpts import SEVERITY_ORDER, excerpt
from .model import VERSION, ModelError

def model_from_sim_report(report: dict[str, Any], *, fail_on: str = "error", arm_urdf: str | None = None,
                          roots: list[str] | None = None, title: str | None = None) -> dict:
    """The report model of a run described by the sim's JSON report (a dict, version 1 or 2).

    `roots`: folders whose files may be quoted in the excerpts (default: the folder of the
    application's project file). `arm_urdf`: the arm's URDF when `robot.name` is not a catalogue
    arm. Raises ModelError for a report that is not a version 1 or 2 sim report."""
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
    limitations = ["The JSON sim report does not record what each task was doing over time: no task timeline "
                   "(`val3check sim --report html` has it)."]
    robot = report.get("robot")
    scene = None
    if robot:
        limitations.append(f"Built from the JSON report: the arm's motion is not drawn (the 3D view shows "
                           f"{robot['name']} at its initial joint position); `val3check sim --report html` draws it.")
        from ...robot import load_robot
        from ...robot.chain import arm_chain

        model = load_robot(arm_urdf or robot["name"])
        scene = {"arm": arm_chain(model.source, joint_names=model.joint_names, name=model.name,
                                  source=arm_urdf or f"robots/{Path(model.source).name}"),
                 "tool": None, "obstacles": [], "joints": list(robot.get("initial_joints") or [0.0] * 6)}
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
            "simulated_duration": report.get("simulated_duration") or 0.0,
            "cycle_time": None,
        },
        "diagnostics": diagnostics,
        "motions": [],
        "cycles": [],
        "trajectory": None,
        "tasks": [],
        "arm_timeline": [],
        "io": list(report.get("io_log", [])),
        "transcript": list(report.get("transcript", [])),
        "screen": report.get("screen"),
        "scene": scene,
    }
