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

from .series import Packed, floats

FULL_RATE_MAX = 30_000
PLOT_BUCKETS = 15_000


def f32(values) -> str:
    """base64 of float32 values: a list, or an array of float64 (numpy, array('d')) cast at once."""
    return base64.b64encode(_f32(values)).decode("ascii")


def _f32(values) -> bytes:
    if not isinstance(values, list):
        import numpy as np

        a = np.asarray(values, dtype=float)
        b = a.astype("<f4")
        if np.isfinite(b).all() or not np.isfinite(a).all():
            return b.tobytes()
        values = a.tolist()  # a value beyond float32: struct says so (OverflowError)
    return struct.pack(f"<{len(values)}f", *values)


def f64(values) -> str:
    return base64.b64encode(_f64(values)).decode("ascii")


def _f64(values) -> bytes:
    if not isinstance(values, list):
        import numpy as np

        return np.asarray(values, dtype="<f8").tobytes()
    return struct.pack(f"<{len(values)}d", *values)


def _bucket(n: int) -> int:
    """The samples in a bucket of a series of `n` (the last bucket may be shorter); 0: no buckets."""
    return 0 if n <= FULL_RATE_MAX else math.ceil(n / PLOT_BUCKETS)


def _series(values, size: int) -> dict:
    """A plot's series: every value, or the minimum and maximum of each bucket of `size` values
    (`values`: a list, or an array('d'), reduced at once)."""
    return {k: base64.b64encode(b).decode("ascii") for k, b in _series_bytes(values, size).items()}


def _series_bytes(values, size: int) -> dict:
    """`_series` before base64: float32 bytes (a series packed block by block joins its blocks')."""
    if not size:
        return {"v": _f32(values)}
    arr = floats(values)
    if arr is None and not isinstance(values, list):  # numpy: a run's trajectory, block by block
        import numpy as np

        arr = np.asarray(values, dtype=float)
    if arr is not None:
        import numpy as np

        if not (np.signbit(arr) & (arr == 0.0)).any():  # -0.0 beside 0.0: min() keeps the first, as below
            starts = np.arange(0, len(arr), size)
            return {"lo": _f32(np.minimum.reduceat(arr, starts)), "hi": _f32(np.maximum.reduceat(arr, starts))}
        values = arr.tolist()
    starts = range(0, len(values), size)
    return {"lo": _f32([min(values[a:a + size]) for a in starts]), "hi": _f32([max(values[a:a + size]) for a in starts])}


def _firsts(values, size: int):
    """The first value of each bucket."""
    arr = floats(values)
    return values[::size] if arr is None else arr[::size]


def _trajectory(tr: dict | None) -> dict | None:
    if not tr or not tr.get("times"):
        return None
    if isinstance(tr, Packed):
        return tr.data
    one = (tr["times"], tr["positions"], tr["velocities"], tr.get("tcp_speed"))
    return _packed(tr["joints"], len(tr["times"]), [one])


def _packed(joints: list[dict], n: int, blocks) -> dict:
    """The page's trajectory of `n` samples given as `blocks` (times, positions and velocities per
    joint, TCP speed or None), each a whole number of buckets but the last: every series is
    reduced block by block and joined, the bytes of the series reduced whole."""
    size = _bucket(n)
    t: list[bytes] = []
    pos: list[list[dict]] = [[] for _ in joints]
    vel: list[list[dict]] = [[] for _ in joints]
    anim: list[list[bytes]] = [[] for _ in joints]
    tcp: list[dict] = []
    has_tcp = None
    for times, positions, velocities, speed in blocks:
        t.append(_f64(_firsts(times, size) if size else times))
        for i in range(len(joints)):
            pos[i].append(_series_bytes(positions[i], size))
            vel[i].append(_series_bytes(velocities[i], size))
            if size:
                anim[i].append(_f32(_firsts(positions[i], size)))
        has_tcp = speed is not None
        if has_tcp:
            tcp.append(_series_bytes(speed, size))
    plot_t = _b64(t)
    out: dict[str, Any] = {
        "samples": n,
        "decimated": bool(size),
        "bucket": size or 1,
        "t": plot_t,
        "joints": [{"name": j["name"], "unit": j["unit"], "min": j.get("min"), "max": j.get("max"),
                    "speed": j.get("speed"), "pos": _joined(pos[i]), "vel": _joined(vel[i])}
                   for i, j in enumerate(joints)],
        "tcp": _joined(tcp) if has_tcp else None,
        # the 3D view: full-rate positions are the plots' own, else one sample per bucket
        "anim": {"t": plot_t, "q": [_b64(a) for a in anim]} if size else None,
    }
    return out


def _b64(parts: list[bytes]) -> str:
    return base64.b64encode(b"".join(parts)).decode("ascii")


def _joined(parts: list[dict]) -> dict:
    """A series packed in blocks (`_series_bytes` of each) as `_series` of the whole."""
    return {k: _b64([p[k] for p in parts]) for k in parts[0]}


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
    number = {state: k for k, state in reversed(list(enumerate(states)))}  # as states.index, without its calls
    out = []
    for r in rows:
        segs = []
        for s in r["segments"]:
            d = s.get("detail") or ""
            if d not in details:
                details[d] = len(details)
            state = s["state"]
            segs.append([s["start"], s["end"], number[state] if state in number else states.index(state), details[d]])
        out.append({"name": r["name"], "segs": segs})
    return out, list(details)


def page_data(model: dict) -> dict:
    """The JSON object the page's script reads (its shape is private to page and script)."""
    return dict(data_items(model))


def data_items(model: dict):
    """The (key, value) pairs of `page_data`, in the order of their keys, each made when asked
    (the page writes one before it makes the next)."""
    from .model import ARM_STATES, TASK_STATES

    yield "arm", _states([{"name": "arm", "segments": model.get("arm_timeline", [])}], ARM_STATES)[0][0]["segs"] \
        if model.get("arm_timeline") else []
    yield "arm_states", list(ARM_STATES)
    yield "cycles", [{"task": c["task"], "label": c.get("label") or c["task"],
                      "it": [[it["start"], it["duration"], 1 if it.get("complete", True) else 0]
                             for it in c["iterations"]]} for c in model.get("cycles", [])]
    tasks, details = _states(model.get("tasks", []), TASK_STATES)
    yield "details", details
    yield "diags", [{"time": d.get("time"), "severity": d["severity"], "code": d["code"], "task": d.get("task"),
                     "line": d.get("line"), "message": d["message"]} for d in model.get("diagnostics", [])]
    yield "duration", model["verdict"]["simulated_duration"]
    yield "io", _io(model.get("io", []))
    yield "motions", [{"id": m["id"], "kind": m["kind"], "line": m.get("line"), "start": m["start"], "end": m["end"],
                       "vel": m.get("vel"), "tvel": m.get("tvel")} for m in model.get("motions", [])]
    yield "scene", model.get("scene")
    yield "task_states", list(TASK_STATES)
    yield "tasks", tasks
    yield "traj", _trajectory(model.get("trajectory"))
