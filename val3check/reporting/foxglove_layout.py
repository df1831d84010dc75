"""A Foxglove layout for a trace of `val3check sim --trace` (docs/trace.md).

    python -m val3check.reporting.foxglove_layout run.mcap -o layout.json

The panels read the trace's topics (reporting/mcap_trace.py): a 3D view (the arm's URDF from
`/robot_description`, the scene), the joints against their limits, the clearance, the log, the
I/O and the tasks. Foxglove's State Transitions panel draws one row per message path: one path per
task, filtered on the task's name (`/tasks{task=="robot"}.state`, Foxglove's message path syntax),
so that each task has its own row. Task names and joints differ from one application and arm to
the next: the layout is made from the trace. docs/foxglove-layout.json is the bundled example's.
"""

from __future__ import annotations

import argparse
import json
import sys
from typing import Any


def _series(path: str, label: str) -> dict:
    """One series of a Plot or State Transitions panel (Foxglove's panel configuration)."""
    return {"value": path, "enabled": True, "timestampMethod": "receiveTime", "label": label}


def _plot(title: str, paths: list[dict]) -> dict:
    """A Plot panel against time, synced with the others."""
    return {"title": title, "paths": paths, "showXAxisLabels": True, "showYAxisLabels": True, "showLegend": True,
            "legendDisplay": "floating", "isSynced": True, "xAxisVal": "timestamp"}


def task_path(task: str) -> str:
    """The message path of one task's state: `/tasks` filtered on its name (a JSON string
    literal, so that quotes and backslashes in a name stay inside it)."""
    return "/tasks{task==" + json.dumps(task, ensure_ascii=False) + "}.state"


def _three_d() -> dict:
    """The 3D panel: the world frame followed, a grid, the URDF from /robot_description, the scene."""
    return {
        "followTf": "world",
        "scene": {"transforms": {"showLabel": False}},
        "topics": {"/scene": {"visible": True}, "/tcp": {"visible": True}},
        "layers": {
            "grid": {"layerId": "foxglove.Grid", "instanceId": "grid", "label": "Grid", "visible": True,
                     "frameLocked": True, "frameId": "world", "size": 2, "divisions": 20, "lineWidth": 1,
                     "color": "#64748b80", "position": [0, 0, 0], "rotation": [0, 0, 0], "order": 1},
            "arm": {"layerId": "foxglove.Urdf", "instanceId": "arm", "label": "Arm (URDF)", "visible": True,
                    "frameLocked": True, "sourceType": "topic", "topic": "/robot_description", "url": "",
                    "filePath": "", "parameter": "", "framePrefix": "", "displayMode": "collision",
                    "fallbackColor": "#e69f00", "order": 2},
        },
        "cameraState": {"perspective": True, "distance": 2.5, "phi": 60, "thetaOffset": 45,
                        "targetOffset": [0, 0, 0], "target": [0, 0, 0], "targetOrientation": [0, 0, 0, 1],
                        "fovy": 45, "near": 0.01, "far": 100},
    }


def layout(tasks: list[str], axes: int = 6) -> dict[str, Any]:
    """The layout of a trace whose tasks are `tasks` (one row each, in this order) and whose arm
    has `axes` joints (one series each, named j1, j2… as VAL 3's joint fields; joint 2's limits)."""
    joints = [f"j{i + 1}" for i in range(axes)]
    limits = [_series("/joint_states.lower[1]", f"{joints[1]} min"),
              _series("/joint_states.upper[1]", f"{joints[1]} max")] if len(joints) > 1 else []
    config = {
        "3D!val3check": _three_d(),
        "Plot!positions": _plot("Joint positions (deg, mm) and limits",
                                [_series(f"/joint_states.position[{i}]", j) for i, j in enumerate(joints)] + limits),
        "Plot!velocities": _plot("Joint velocities (deg/s, mm/s)",
                                 [_series(f"/joint_states.velocity[{i}]", j) for i, j in enumerate(joints)]),
        "Log!val3check": {"searchTerms": [], "minLogLevel": 1, "topicToRender": "/log"},
        "StateTransitions!tasks": {"paths": [_series(task_path(t), t) for t in tasks], "isSynced": True},
        "RawMessages!io": {"topicPath": "/io", "diffEnabled": False, "diffMethod": "custom", "diffTopicPath": "",
                           "showFullMessageForDiff": False},
        "Plot!clearance": _plot("Clearance to the cell (mm) and margin",
                                [_series("/clearance.clearance_mm", "clearance"),
                                 _series("/clearance.margin_mm", "margin")]),
    }
    tree = {
        "direction": "row", "first": "3D!val3check",
        "second": {
            "direction": "column",
            "first": {"direction": "column", "first": "Plot!positions",
                      "second": {"direction": "column", "first": "Plot!velocities", "second": "Plot!clearance",
                                 "splitPercentage": 60},
                      "splitPercentage": 40},
            "second": {"direction": "row", "first": "Log!val3check",
                       "second": {"direction": "column", "first": "StateTransitions!tasks",
                                  "second": "RawMessages!io"},
                       "splitPercentage": 55},
            "splitPercentage": 60},
        "splitPercentage": 50,
    }
    return {"configById": config, "globalVariables": {}, "userNodes": {}, "playbackConfig": {"speed": 1},
            "layout": tree}


def read_trace(path: str) -> tuple[list[str], int]:
    """(tasks in the order they first appear on `/tasks`, number of joints on `/joint_states`, 0
    without an arm) of a trace."""
    from mcap.reader import make_reader

    tasks: dict[str, None] = {}
    joints: list[str] = []
    with open(path, "rb") as f:
        for _, channel, message in make_reader(f).iter_messages(topics=["/tasks", "/joint_states"]):
            data = json.loads(message.data)
            if channel.topic == "/tasks":
                tasks.setdefault(data["task"], None)
            elif not joints:
                joints = list(data["name"])
    return list(tasks), len(joints)


def dumps(value: dict) -> str:
    """The layout as the file Foxglove imports (2-space JSON, a final newline)."""
    return json.dumps(value, indent=2, ensure_ascii=False) + "\n"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m val3check.reporting.foxglove_layout",
                                 description="Write a Foxglove layout for a trace of `val3check sim --trace`: "
                                             "one row per task, one series per joint.")
    ap.add_argument("trace", help="the MCAP file `val3check sim --trace` wrote")
    ap.add_argument("-o", "--output", metavar="FILE", help="the layout to write (default: standard output)")
    args = ap.parse_args(argv)
    from mcap.exceptions import McapError

    try:
        tasks, axes = read_trace(args.trace)
    except OSError as exc:
        print(f"{args.trace}: cannot read: {exc.strerror or exc}", file=sys.stderr)
        return 2
    except (McapError, ValueError, KeyError, TypeError) as exc:  # not MCAP, or not val3check's messages
        print(f"{args.trace}: not a trace of `val3check sim --trace`: {exc}", file=sys.stderr)
        return 2
    axes = axes or 6  # no arm in the run: the panels stay, empty
    text = dumps(layout(tasks, axes))
    if args.output:
        with open(args.output, "w", encoding="utf-8", newline="\n") as fh:
            fh.write(text)
        print(f"wrote {args.output}: {len(tasks)} task(s), {axes} joint(s)", file=sys.stderr)
    else:
        sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
