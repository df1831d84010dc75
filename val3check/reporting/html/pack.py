"""What the page's script reads: the report model's time series and scene, packed small.

Sample arrays travel as base64 of little-endian float32 (values) and float64 (times): about
5.3 characters a value, and decoded in one pass by the page. Up to FULL_RATE_MAX samples (two
minutes at 4 ms) are kept at full rate. Longer runs are cut into PLOT_BUCKETS buckets of
consecutive samples: the plots get each bucket's minimum and maximum (a peak is never lost),
the 3D view the first sample of each bucket. The page then draws at most a few points per pixel
column (min/max per column), however many samples it holds.
"""

from __future__ import annotations

import base64
import math
import struct
from typing import Any

from .series import floats

FULL_RATE_MAX = 30_000
PLOT_BUCKETS = 15_000


def f32(values) -> str:
    """base64 of float32 values: a list, or an array of float64 (numpy, array('d')) cast at once."""
    if not isinstance(values, list):
        import numpy as np

        a = np.asarray(values, dtype=float)
        b = a.astype("<f4")
        if np.isfinite(b).all() or not np.isfinite(a).all():
            return base64.b64encode(b.tobytes()).decode("ascii")
        values = a.tolist()  # a value beyond float32: struct says so (OverflowError)
    return base64.b64encode(struct.pack(f"<{len(values)}f", *values)).decode("ascii")


def f64(values) -> str:
    if not isinstance(values, list):
        import numpy as np

        return base64.b64encode(np.asarray(values, dtype="<f8").tobytes()).decode("ascii")
    return base64.b64encode(struct.pack(f"<{len(values)}d", *values)).decode("ascii")


def _bucket(n: int) -> int:
    """The samples in a bucket of a series of `n` (the last bucket may be shorter); 0: no buckets."""
    return 0 if n <= FULL_RATE_MAX else math.ceil(n / PLOT_BUCKETS)


def _series(values, size: int) -> dict:
    """A plot's series: every value, or the minimum and maximum of each bucket of `size` values
    (`values`: a list, or an array('d'), reduced at once)."""
    if not size:
        return {"v": f32(values)}
    arr = floats(values)
    if arr is not None:
        import numpy as np

        if not (np.signbit(arr) & (arr == 0.0)).any():  # -0.0 beside 0.0: min() keeps the first, as below
            starts = np.arange(0, len(arr), size)
            return {"lo": f32(np.minimum.reduceat(arr, starts)), "hi": f32(np.maximum.reduceat(arr, starts))}
        values = arr.tolist()
    starts = range(0, len(values), size)
    return {"lo": f32([min(values[a:a + size]) for a in starts]), "hi": f32([max(values[a:a + size]) for a in starts])}


def _firsts(values, size: int):
    """The first value of each bucket."""
    arr = floats(values)
    return values[::size] if arr is None else arr[::size]


def _trajectory(tr: dict | None) -> dict | None:
    if not tr or not tr.get("times"):
        return None
    times = tr["times"]
    n = len(times)
    size = _bucket(n)
    plot_times = _firsts(times, size) if size else times
    joints = []
    for i, j in enumerate(tr["joints"]):
        joints.append({
            "name": j["name"], "unit": j["unit"], "min": j.get("min"), "max": j.get("max"), "speed": j.get("speed"),
            "pos": _series(tr["positions"][i], size), "vel": _series(tr["velocities"][i], size),
        })
    out: dict[str, Any] = {
        "samples": n,
        "decimated": bool(size),
        "bucket": size or 1,
        "t": f64(plot_times),
        "joints": joints,
        "tcp": _series(tr["tcp_speed"], size) if tr.get("tcp_speed") is not None else None,
        # the 3D view: full-rate positions are the plots' own, else one sample per bucket
        "anim": None,
    }
    if size:
        out["anim"] = {"t": f64(plot_times), "q": [f32(_firsts(row, size)) for row in tr["positions"]]}
    return out


def _io(events: list[dict]) -> list[dict]:
    signals: dict[tuple[str, str], dict] = {}
    for e in events:
        key = (e["kind"], e["link"])
        s = signals.get(key)
        if s is None:
            names = e.get("names") or []
            s = signals[key] = {"kind": e["kind"], "link": e["link"], "label": ", ".join(names) or e["link"],
                                "t": [], "v": [], "src": []}
        v = e["value"]
        if e["kind"] == "sio":
            v = v if isinstance(v, str) else " ".join(str(b) for b in v) if isinstance(v, list) else str(v)
        elif e["kind"] == "dio":
            v = 1 if v else 0
        elif v is None:
            v = None  # an aio that read NaN
        s["t"].append(e["time"])
        s["v"].append(v)
        s["src"].append(e.get("source") or "")
    # outputs and inputs in a stable order: digital, analog, serial, then by label
    order = {"dio": 0, "aio": 1, "sio": 2}
    return sorted(signals.values(), key=lambda s: (order.get(s["kind"], 3), s["label"], s["link"]))


def _states(rows: list[dict], states: tuple[str, ...]) -> tuple[list[dict], list[str]]:
    details: dict[str, int] = {}
    out = []
    for r in rows:
        segs = []
        for s in r["segments"]:
            d = s.get("detail") or ""
            if d not in details:
                details[d] = len(details)
            segs.append([s["start"], s["end"], states.index(s["state"]), details[d]])
        out.append({"name": r["name"], "segs": segs})
    return out, list(details)


def page_data(model: dict) -> dict:
    """The JSON object the page's script reads (its shape is private to page and script)."""
    from .model import ARM_STATES, TASK_STATES

    tasks, details = _states(model.get("tasks", []), TASK_STATES)
    arm_rows, _ = _states([{"name": "arm", "segments": model.get("arm_timeline", [])}], ARM_STATES)
    verdict = model["verdict"]
    return {
        "duration": verdict["simulated_duration"],
        "traj": _trajectory(model.get("trajectory")),
        "motions": [{"id": m["id"], "kind": m["kind"], "line": m.get("line"), "start": m["start"], "end": m["end"],
                     "vel": m.get("vel"), "tvel": m.get("tvel")} for m in model.get("motions", [])],
        "task_states": list(TASK_STATES),
        "arm_states": list(ARM_STATES),
        "tasks": tasks,
        "details": details,
        "arm": arm_rows[0]["segs"] if model.get("arm_timeline") else [],
        "io": _io(model.get("io", [])),
        "diags": [{"time": d.get("time"), "severity": d["severity"], "code": d["code"], "task": d.get("task"),
                   "line": d.get("line"), "message": d["message"]} for d in model.get("diagnostics", [])],
        "cycles": [{"task": c["task"], "label": c.get("label") or c["task"],
                    "it": [[it["start"], it["duration"], 1 if it.get("complete", True) else 0] for it in c["iterations"]]}
                   for c in model.get("cycles", [])],
        "scene": model.get("scene"),
    }
