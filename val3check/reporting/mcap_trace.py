"""`val3check sim --trace run.mcap`: the run as an MCAP file that opens in Foxglove (docs/trace.md).

    write_trace(report, "run.mcap")        # report: reporting.sim_report.SimReport

Messages are JSON with Foxglove's well-known schemas where one exists (`foxglove.FrameTransforms`,
`foxglove.PoseInFrame`, `foxglove.SceneUpdate`, `foxglove.Log`) and val3check's own otherwise
(joint states with their limits, I/O changes, task states). Stamped with the **simulated** time
(nanoseconds from the start of the run), lengths in metres as Foxglove expects. The bytes depend
on the run only: same run, same file (no wall-clock time, fixed chunking and compression).

Everything comes from the run's record (simulation/arm_record.py): the arm's links are placed with
the forward kinematics the record of the scene gives (`result.motion.scene.kinematics`) at every
4 ms tick where the arm moves (and once at the start; Foxglove keeps a frame's last transform
while the arm stands still); the URDF travels with the trace as the record gives it. A long run
is written at a multiple of 4 ms (at most about TRACE_TICKS ticks of the arm, thinning.py), which
the file's metadata states (`arm_period_s`, `thinned`).
"""

from __future__ import annotations

import heapq
import json
import math
from typing import Any

from ..lengths import MM_M as MM  # Foxglove works in metres
from .thinning import TRACE_TICKS, io_events, left_out, part_spans, task_changes, thinned_note, tick_multiple

TICK_S = 0.004
CHUNK_SIZE = 1 << 20
BLOCK = 2048  # ticks whose poses are computed at once
LIBRARY = "val3check"

# JSON Schemas of the messages: the field names, types and required fields of Foxglove's published
# schemas (foxglove-sdk, schemas/jsonschema; the tests hold every message of a trace against them,
# tests/data/foxglove/), written out for the fields we fill.
def _obj(props: dict, required=None) -> dict:
    """An object schema; every property required unless `required` says which."""
    return {"type": "object", "properties": props, "required": list(props) if required is None else required}


def _array(items: dict | None = None) -> dict:
    """An array schema (of `items`)."""
    return {"type": "array", "items": items} if items is not None else {"type": "array"}


_TIME = _obj({"sec": {"type": "integer"}, "nsec": {"type": "integer"}}, [])
_VEC3 = _obj({k: {"type": "number"} for k in "xyz"})
_QUAT = _obj({k: {"type": "number"} for k in "xyzw"})
_POSE = _obj({"position": _VEC3, "orientation": _QUAT})
_COLOR = _obj({k: {"type": "number"} for k in "rgba"})
_FRAME_TRANSFORM = _obj({"timestamp": _TIME, "parent_frame_id": {"type": "string"},
                         "child_frame_id": {"type": "string"}, "translation": _VEC3, "rotation": _QUAT})
_SOLID = _obj({"pose": _POSE, "size": _VEC3, "color": _COLOR})
# a SceneEntity's primitive arrays: Foxglove requires every one, empty or not
PRIMITIVES = ("arrows", "cubes", "spheres", "cylinders", "lines", "triangles", "texts", "models")
SCHEMAS: dict[str, dict] = {
    "foxglove.FrameTransforms": _obj({"transforms": _array(_FRAME_TRANSFORM)}),
    "foxglove.PoseInFrame": _obj({"timestamp": _TIME, "frame_id": {"type": "string"}, "pose": _POSE}),
    "foxglove.SceneUpdate": _obj({
        "deletions": _array(_obj({"timestamp": _TIME, "type": {"type": "integer"}, "id": {"type": "string"}})),
        "entities": _array(_obj({
            "timestamp": _TIME, "frame_id": {"type": "string"}, "id": {"type": "string"},
            "lifetime": _TIME, "frame_locked": {"type": "boolean"},
            "metadata": _array(_obj({"key": {"type": "string"}, "value": {"type": "string"}})),
            "arrows": _array(_obj({
                "pose": _POSE, "shaft_length": {"type": "number"}, "shaft_diameter": {"type": "number"},
                "head_length": {"type": "number"}, "head_diameter": {"type": "number"}, "color": _COLOR})),
            "cubes": _array(_SOLID),
            "spheres": _array(_SOLID),
            "cylinders": _array(_obj({
                "pose": _POSE, "size": _VEC3, "bottom_scale": {"type": "number"}, "top_scale": {"type": "number"},
                "color": _COLOR})),
            "lines": _array(),  # never filled
            "triangles": _array(_obj({
                "pose": _POSE, "points": _array(_VEC3), "color": _COLOR, "colors": _array(_COLOR),
                "indices": _array({"type": "integer"})})),
            "texts": _array(),  # never filled
            "models": _array(),  # never filled
        }))}),
    "foxglove.Log": _obj({
        "timestamp": _TIME, "level": {"type": "integer"}, "message": {"type": "string"}, "name": {"type": "string"},
        "file": {"type": "string"}, "line": {"type": "integer"}}),
    "std_msgs/String": {"type": "object", "properties": {"data": {"type": "string"}}},
    "val3check.JointState": {"type": "object", "properties": {
        "timestamp": _TIME, "name": {"type": "array", "items": {"type": "string"}},
        "unit": {"type": "array", "items": {"type": "string"}},
        "position": {"type": "array", "items": {"type": "number"}},
        "velocity": {"type": "array", "items": {"type": "number"}},
        "lower": {"type": "array", "items": {"type": "number"}},
        "upper": {"type": "array", "items": {"type": "number"}},
        "nominal_speed": {"type": "array", "items": {"type": "number"}}}},
    "val3check.IOChange": {"type": "object", "properties": {
        "timestamp": _TIME, "kind": {"type": "string"}, "link": {"type": "string"},
        "names": {"type": "array", "items": {"type": "string"}}, "value": {}, "source": {"type": "string"}}},
    "val3check.Clearance": {"type": "object", "properties": {
        "timestamp": _TIME, "motion": {"type": "integer"}, "motion_id": {"type": ["integer", "null"]}, "clearance_mm": {"type": "number"},
        "exact": {"type": "boolean"}, "margin_mm": {"type": "number"}}},
    "val3check.TaskState": {"type": "object", "properties": {
        "timestamp": _TIME, "task": {"type": "string"}, "state": {"type": "string"}, "detail": {"type": "string"}}},
}
# topic -> schema (in this order in the file)
TOPICS = {
    "/tf": "foxglove.FrameTransforms",
    "/joint_states": "val3check.JointState",
    "/tcp": "foxglove.PoseInFrame",
    "/scene": "foxglove.SceneUpdate",
    "/log": "foxglove.Log",
    "/io": "val3check.IOChange",
    "/tasks": "val3check.TaskState",
    "/clearance": "val3check.Clearance",
    "/robot_description": "std_msgs/String",
}
LOG_LEVEL = {"info": 2, "warning": 3, "error": 4}  # foxglove.Log: INFO, WARNING, ERROR
COLORS = {"obstacle": {"r": 0.45, "g": 0.55, "b": 0.65, "a": 0.8}, "tool": {"r": 0.25, "g": 0.25, "b": 0.28, "a": 1.0},
          "tcp": {"r": 0.84, "g": 0.37, "b": 0.0, "a": 1.0}, "part": {"r": 0.0, "g": 0.62, "b": 0.45, "a": 1.0}}


def _ns(t: float) -> int:
    """Simulated seconds as nanoseconds (the trace's stamps)."""
    return round(t * 1e9)


def _stamp(ns: int) -> dict:
    """A foxglove Time of nanoseconds."""
    return {"sec": ns // 1_000_000_000, "nsec": ns % 1_000_000_000}


SIGN_EPS = 1e-9  # a component this close to 0 is a matrix's last bits, not a sign


def quaternions(R):
    """Unit quaternions (x, y, z, w) of rotation matrices (N, 3, 3) (Shepperd's method: the largest
    of w, x, y, z is computed first, so every branch is well conditioned). Of q and -q, the one whose
    first of w, x, y, z farther than SIGN_EPS from 0 is positive: w >= 0, and a half turn (w about 0,
    a tool pointing straight down) keeps its sign whatever the last bits of its matrix."""
    import numpy as np

    R = np.asarray(R, dtype=float).reshape(-1, 3, 3)
    n = len(R)
    q = np.zeros((n, 4))
    t = np.stack([R[:, 0, 0] + R[:, 1, 1] + R[:, 2, 2], R[:, 0, 0], R[:, 1, 1], R[:, 2, 2]], axis=1)
    k = np.argmax(t, axis=1)
    for case in range(4):
        s = k == case
        if not s.any():
            continue
        r = R[s]
        if case == 0:
            w = np.sqrt(np.maximum(1.0 + t[s, 0], 0.0)) / 2
            q[s] = np.stack([(r[:, 2, 1] - r[:, 1, 2]) / (4 * w), (r[:, 0, 2] - r[:, 2, 0]) / (4 * w),
                             (r[:, 1, 0] - r[:, 0, 1]) / (4 * w), w], axis=1)
        else:
            i = case - 1
            j, m = (i + 1) % 3, (i + 2) % 3
            a = np.sqrt(np.maximum(1.0 + r[:, i, i] - r[:, j, j] - r[:, m, m], 0.0)) / 2
            out = np.zeros((len(r), 4))
            out[:, i] = a
            out[:, j] = (r[:, j, i] + r[:, i, j]) / (4 * a)
            out[:, m] = (r[:, m, i] + r[:, i, m]) / (4 * a)
            out[:, 3] = (r[:, m, j] - r[:, j, m]) / (4 * a)
            q[s] = out
    lead = q[:, [3, 0, 1, 2]]
    first = np.argmax(np.abs(lead) > SIGN_EPS, axis=1)  # a unit quaternion has one component >= 0.5
    q[lead[np.arange(n), first] < 0] *= -1.0
    return q


def _pose(M) -> dict:
    """A 4x4 (mm) as a foxglove.Pose (m; rounded as every pose of the trace, _m and _q)."""
    import numpy as np

    M = np.asarray(M, dtype=float)
    (x, y, z, w), = _q(M[None, :3, :3])
    (px, py, pz), = _m(M[None, :3, 3])
    return {"position": {"x": px, "y": py, "z": pz}, "orientation": {"x": x, "y": y, "z": z, "w": w}}


def _transforms(ns: int, parent: str, names: list[str], mats) -> list[dict]:
    """FrameTransform entries for frames `names` with poses `mats` (K, 4, 4, mm) in `parent`."""
    q = _q(mats[:, :3, :3])
    p = _m(mats[:, :3, 3])
    st = _stamp(ns)
    return [_tf(st, parent, n, a, b) for n, a, b in zip(names, p, q)]


def _tf(st: dict, parent: str, child: str, p, q) -> dict:
    """A foxglove.FrameTransform of `child` in `parent` (position p in m, quaternion q)."""
    return {"timestamp": st, "parent_frame_id": parent, "child_frame_id": child,
            "translation": {"x": p[0], "y": p[1], "z": p[2]}, "rotation": {"x": q[0], "y": q[1], "z": q[2], "w": q[3]}}


def _solid(kind: str, size, pose) -> tuple[str, dict]:
    """A cell or tool solid as a SceneEntity primitive (key, primitive); mm in, m out."""
    import numpy as np

    M = np.asarray(pose, dtype=float)
    if kind == "box":
        return "cubes", {"pose": _pose(M), "size": dict(zip("xyz", (_len(v) for v in size)))}
    if kind == "sphere":
        d = _len(2 * float(size[0]))
        return "spheres", {"pose": _pose(M), "size": {"x": d, "y": d, "z": d}}
    if kind == "cylinder":
        d = _len(2 * float(size[0]))
        return "cylinders", {"pose": _pose(M), "size": {"x": d, "y": d, "z": _len(size[1])},
                             "bottom_scale": 1.0, "top_scale": 1.0}
    raise ValueError(kind)


def _scene_entity(ns: int, frame: str, ident: str, metadata: dict[str, str]) -> dict:
    """An empty foxglove.SceneEntity in `frame` (kept there when it is not the world), every
    primitive array present: Foxglove's schema requires them all."""
    e: dict[str, Any] = {"timestamp": _stamp(ns), "frame_id": frame, "id": ident, "lifetime": {"sec": 0, "nsec": 0},
                         "frame_locked": frame != "world",
                         "metadata": [{"key": k, "value": v} for k, v in metadata.items()]}
    e.update((k, []) for k in PRIMITIVES)
    return e


def _tcp_marker(ns: int, flange: str, name: str, tool) -> dict:
    """The current tool's TCP on the flange: an arrow from the flange's origin to the TCP and a
    small sphere on it (the tool's solids come from the cell file, when there is one)."""
    import numpy as np

    T = np.asarray(tool, dtype=float)
    d = T[:3, 3]
    L = float(np.linalg.norm(d))
    e = _scene_entity(ns, flange, "tcp", {"tool": name})
    ball = np.eye(4)
    ball[:3, 3] = d
    e["spheres"].append({"pose": _pose(ball), "size": {"x": 0.012, "y": 0.012, "z": 0.012}, "color": COLORS["tcp"]})
    if L > 1.0:  # mm: an arrow along +x turned onto the flange -> TCP direction
        x = d / L
        helper = np.array([0.0, 0.0, 1.0]) if abs(x[2]) < 0.9 else np.array([1.0, 0.0, 0.0])
        y = np.cross(helper, x)
        y /= np.linalg.norm(y)
        R = np.eye(4)
        R[:3, :3] = np.column_stack([x, y, np.cross(x, y)])
        head = min(0.2 * L, 20.0)
        e["arrows"].append({"pose": _pose(R), "shaft_length": _len(L - head), "shaft_diameter": 0.006,
                            "head_length": _len(head), "head_diameter": 0.014, "color": COLORS["tcp"]})
    return e


def _entity(ns: int, frame: str, ident: str, what: str, solids: list[tuple[str, Any, Any, Any]]) -> dict:
    """A foxglove.SceneEntity of the cell's or the tool's solids (mm in, m out)."""
    import numpy as np

    e = _scene_entity(ns, frame, ident, {"kind": what})
    for name, shape, pose, _ in solids:
        if shape.kind == "mesh":
            v = _m(np.asarray(shape.mesh.vertices, dtype=float))
            f = np.asarray(shape.mesh.faces, dtype=int)
            e["triangles"].append({"pose": _pose(np.asarray(pose, dtype=float)),
                                   "points": [{"x": a, "y": b, "z": c} for a, b, c in v],
                                   "indices": f.reshape(-1).tolist(), "color": COLORS[what], "colors": []})
            continue
        key, prim = _solid(shape.kind, shape.size, pose)
        prim["color"] = COLORS[what]
        e[key].append(prim)
    return e


class _Messages:
    """The messages other than the arm's ticks (few): collected, then sorted by time."""

    def __init__(self) -> None:
        """No message yet."""
        self.items: list[tuple[int, int, int, bytes]] = []  # (time ns, topic order, seq, JSON)

    @staticmethod
    def encode(message: dict) -> bytes:
        """A message as compact JSON bytes."""
        return json.dumps(message, separators=(",", ":"), ensure_ascii=False, allow_nan=False).encode("utf-8")

    def add(self, topic: str, ns: int, message: dict) -> None:
        """A message on `topic` at `ns`."""
        self.items.append((ns, list(TOPICS).index(topic), len(self.items), self.encode(message)))


def _rigid_inverse(P):
    """The inverses of rigid transforms P (N, 4, 4)."""
    import numpy as np

    out = np.zeros_like(P)
    Rt = np.transpose(P[:, :3, :3], (0, 2, 1))
    out[:, :3, :3] = Rt
    out[:, :3, 3] = -np.einsum("nij,nj->ni", Rt, P[:, :3, 3])
    out[:, 3, 3] = 1.0
    return out


def _arm_ticks(scene, edges, tools, times, Q, V, idx):
    """The arm's messages (/tf, /tcp, /joint_states) tick by tick, made a block of ticks at a time
    (memory stays bounded whatever the length of the run): (ns, topic order, 0, JSON bytes)."""
    import numpy as np

    world, flange = scene.world_frame, scene.flange_frame
    order = list(TOPICS)
    o_tf, o_tcp, o_js = order.index("/tf"), order.index("/tcp"), order.index("/joint_states")
    names_j, units = list(scene.joint_names), list(scene.joint_units)
    limits = np.asarray(scene.joint_limits, dtype=float)
    lower, upper = limits[:, 0].tolist(), limits[:, 1].tolist()
    speeds = [float(s) for s in scene.nominal_speeds]
    dump = _Messages.encode
    for b0 in range(0, len(times), BLOCK):
        sl = slice(b0, b0 + BLOCK)
        poses = scene.kinematics.link_poses_many(Q[sl], times=times[sl])  # (the geometry then: setDH)
        tool_at = np.stack([tools[j] if j >= 0 else np.eye(4) for j in idx[sl].tolist()])
        tcp_world = poses[flange] @ tool_at
        # each link in its URDF parent (the URDF's own tree, so that Foxglove's URDF layer agrees):
        # every edge at t = 0, then the joints that move
        rel = {c: _rigid_inverse(poses[p]) @ poses[c] for p, c, moving in edges if moving or b0 == 0}
        frames_p = {c: _m(M[:, :3, 3]) for c, M in rel.items()}
        frames_q = {c: _q(M[:, :3, :3]) for c, M in rel.items()}
        parents = {c: p for p, c, _ in edges}
        tool_p, tool_q = _m(tool_at[:, :3, 3]), _q(tool_at[:, :3, :3])
        tcp_p, tcp_q = _m(tcp_world[:, :3, 3]), _q(tcp_world[:, :3, :3])
        Ql, Vl = Q[sl].tolist(), V[sl].tolist()
        for i, t in enumerate(times[sl].tolist()):
            ns = _ns(round(t, 6))
            st = _stamp(ns)
            tfs = [_tf(st, parents[c], c, frames_p[c][i], frames_q[c][i]) for p, c, moving in edges
                   if moving or (b0 == 0 and i == 0)]
            tfs.append(_tf(st, flange, "tcp", tool_p[i], tool_q[i]))
            yield ns, o_tf, 0, dump({"transforms": tfs})
            yield ns, o_js, 0, dump({"timestamp": st, "name": names_j, "unit": units, "position": Ql[i],
                                     "velocity": Vl[i], "lower": lower, "upper": upper, "nominal_speed": speeds})
            yield ns, o_tcp, 0, dump({"timestamp": st, "frame_id": world, "pose": {
                "position": dict(zip("xyz", tcp_p[i])), "orientation": dict(zip("xyzw", tcp_q[i]))}})


def _len(x) -> float:
    """A length (mm) in metres, to 1e-10 m as every position (_m)."""
    return round(float(x) * MM, 10) + 0.0


def _m(P):
    """Positions (mm) in metres, to 1e-10 m (1e-7 mm): shorter JSON, far below what is drawn."""
    import numpy as np

    return (np.round(P * MM, 10) + 0.0).tolist()


def _q(R):
    """Quaternions of rotations R, to 1e-12."""
    import numpy as np

    return (np.round(quaternions(R), 12) + 0.0).tolist()


def trace_messages(report: Any, cell: Any = None):
    """Every message of the trace in time order, as an iterator of (topic, time ns, JSON bytes),
    and what the file carries besides (`urdf`: (file name, text) of the arm's URDF, or None)."""
    import numpy as np

    result = report.result
    out = _Messages()
    arm: Any = iter(())
    m = result.motion
    collision = getattr(result, "collision", None)
    if cell is None and collision is not None:
        cell = getattr(collision, "cell", None)
    end_ns = _ns(result.sim_time_us / 1e6)
    extra: dict[str, Any] = {"urdf": None, "every": 1, "omitted": None}
    if m is not None:
        scene = m.scene
        frames = {name: f.matrix for name, f in scene.frames.items()}
        world = scene.world_frame
        edges = scene.kinematics.link_edges()
        urdf_name, urdf_text = scene.kinematics.urdf()
        extra["urdf"] = (urdf_name, urdf_text)
        out.add("/robot_description", 0, {"data": urdf_text})
        starts, tools, tool_names = [], [], []
        for motion in m.motions:
            if motion.start is not None and motion.kind != "connection":
                starts.append(motion.start)
                tools.append(np.eye(4) if motion.tool_in_flange is None else np.asarray(motion.tool_in_flange,
                                                                                          dtype=float))
                tool_names.append(motion.tool or "flange")
        flange = scene.flange_frame
        # the ticks: t = 0, then every tick of every moving segment
        ks = [np.array([0])]
        qs = [np.asarray(m.trajectory.position(0.0), dtype=float)[None, :]]
        vs = [np.zeros_like(qs[0])]
        every = tick_multiple(m, TRACE_TICKS)  # a long run: a multiple of 4 ms (thinning.py)
        extra["every"] = every
        extra["omitted"] = left_out(result, "the arm's motion")  # the run's budgets spent: t = 0 only
        for k0, q, v in m.trajectory.segments(m.end_s, TICK_S * every) if extra["omitted"] is None else ():
            q, v = np.asarray(q, dtype=float), np.asarray(v, dtype=float)
            k = k0 + np.arange(len(q))
            keep = k > 0
            ks.append(k[keep])
            qs.append(q[keep])
            vs.append(v[keep])
        K, Q, V = np.concatenate(ks), np.concatenate(qs), np.concatenate(vs)
        times = K * (TICK_S * every)
        idx = np.searchsorted(np.asarray(starts), times, side="right") - 1 if starts else np.full(len(K), -1)
        arm = _arm_ticks(scene, edges, tools, times, Q, V, idx)
        # the application's frames (world) and tools (flange): those the cell hangs solids on as the
        # collision checks read them (at each change), the others as the run left them
        timeline = m.cell_timeline
        tracks = {**timeline.frames, **timeline.tools} if timeline is not None else {}
        shown = {n: f for n, f in scene.frames.items() if "[" not in n or f.array_size > 1}  # fPallet, not fPallet[0] too
        at0 = {n: (f.kind, f.matrix) for n, f in shown.items() if n not in tracks}
        changes: dict[int, dict] = {}
        for n, track in tracks.items():
            kind = "frame" if n in timeline.frames else "tool"
            for k, c in enumerate(track):
                if c.matrix is not None:
                    changes.setdefault(0 if k == 0 else _ns(c.time), {})[n] = (kind, c.matrix)
        if at0:
            changes.setdefault(0, {}).update(at0)
        for ns in sorted(changes):
            fr = sorted((n, M) for n, (kind, M) in changes[ns].items() if kind != "tool")
            tl = sorted((n, M) for n, (kind, M) in changes[ns].items() if kind == "tool")
            tfs = []
            if fr:
                tfs += _transforms(ns, world, [n for n, _ in fr], np.stack([M for _, M in fr]))
            if tl:
                tfs += _transforms(ns, flange, [n for n, _ in tl], np.stack([M for _, M in tl]))
            out.add("/tf", ns, {"transforms": tfs})
        # the TCP marker, at each change of tool (from the start of the motion that uses it)
        last = None
        for t0, tool, name in zip(starts, tools, tool_names):
            key = tool.round(9).tobytes()
            if key != last:
                ns = _ns(round(t0, 6))
                out.add("/scene", ns, {"deletions": [], "entities": [_tcp_marker(ns, flange, name, tool)]})
                last = key
        if cell is not None:
            extra["parts_thinned"] = _cell(out, cell, m, frames, tracks)
    for e in result.transcript:
        ns = _ns(e.time_us / 1e6)
        out.add("/log", ns, {"timestamp": _stamp(ns), "level": 2, "message": f"[{e.kind}] {e.text}",
                             "name": e.task or "user page", "file": "", "line": 0})
    for d in report.diagnostics:
        ns = min(_ns((d.time_us or 0) / 1e6), end_ns)
        out.add("/log", ns, {"timestamp": _stamp(ns), "level": LOG_LEVEL.get(d.severity.label, 2),
                             "message": f"{d.code} {d.message}", "name": d.task or "val3check",
                             "file": d.path or "", "line": int(d.line or 0)})
    io, extra["io_thinned"] = io_events(result)  # the first changes on a long run (thinning.py)
    for e in io:
        ns = _ns(e.time_us / 1e6)
        value = e.value if not isinstance(e.value, float) or e.value == e.value else None
        out.add("/io", ns, {"timestamp": _stamp(ns), "kind": e.kind, "link": e.link,
                            "names": list(report.link_names.get((e.kind, e.link), [])), "value": value,
                            "source": e.source})
    # per-sample clearance to the cell, when the run checked collisions (each motion's clearance, a
    # collision.results.MotionReport): a lower bound, exact where `exact`
    motions = m.motions if m is not None else []
    for mid, motion in enumerate(motions):
        mr = motion.clearance
        times = getattr(mr, "times", None)
        if times is None:
            continue
        step = extra["every"]  # thinned as the arm's ticks
        for t, c, ex in zip(np.asarray(times, dtype=float)[::step].tolist(),
                            np.asarray(mr.clearance, dtype=float)[::step].tolist(),
                            np.asarray(mr.exact, dtype=bool)[::step].tolist()):
            if not math.isfinite(c):
                continue  # nothing measured at that sample
            ns = _ns(round(t, 6))
            out.add("/clearance", ns, {"timestamp": _stamp(ns), "motion": int(mid),
                                       "motion_id": motion.id, "clearance_mm": round(c, 6),
                                       "exact": ex, "margin_mm": float(getattr(mr, "margin_mm", 0.0))})
    changes, extra["tasks_thinned"] = task_changes(result)
    for c in changes:
        ns = _ns(c.time_us / 1e6)
        if ns > end_ns:  # stop() after a run cut by --duration, as the HTML report's timelines
            continue
        out.add("/tasks", ns, {"timestamp": _stamp(ns), "task": c.task, "state": c.state, "detail": c.detail})
    out.items.sort(key=lambda x: (x[0], x[1], x[2]))
    topics = list(TOPICS)
    merged = heapq.merge(out.items, arm, key=lambda x: (x[0], x[1]))
    return ((topics[o], ns, data) for ns, o, _, data in merged), extra


def _placed(ns_of, base, track) -> list[tuple[int, Any]]:
    """(time ns, pose of the base or None) at each change: a track of the cell timeline, else `base`
    from t = 0."""
    if not track:
        return [(0, base)]
    return [(0 if k == 0 else ns_of(c.time), c.matrix) for k, c in enumerate(track)]


def _cell(out: "_Messages", cell: Any, m: Any, frames: dict, tracks: dict) -> str | None:
    """The cell's solids (docs/trace.md): obstacles in the world, tool solids on the flange, each
    sent again when the frame or tool it hangs on changes (deleted while it has no value), and the
    parts: on the flange while carried, in the world where they were left (`m.cell_timeline`; its
    first spans on a long run: what the metadata says then, returned)."""
    import numpy as np

    world, flange = m.scene.world_frame, m.scene.flange_frame
    updates: dict[int, dict] = {}

    def put(ns: int, frame: str, ident: str, what: str, solids: list) -> None:
        updates.setdefault(ns, {"deletions": [], "entities": []})["entities"].append(
            _entity(ns, frame, ident, what, solids))

    def delete(ns: int, ident: str) -> None:
        updates.setdefault(ns, {"deletions": [], "entities": []})["deletions"].append(
            {"timestamp": _stamp(ns), "type": 0, "id": ident})

    solids = [(world, f"obstacle/{o.name}", "obstacle", o, o.frame.replace(" ", "")) for o in cell.obstacles]
    solids += [(flange, f"tool/{t.name}", "tool", t, t.tool.replace(" ", "")) for t in cell.tools]
    for frame, ident, what, solid, on in solids:
        fixed = on in ("world", "flange")
        for k, (ns, base) in enumerate(_placed(_ns, np.eye(4) if fixed else frames.get(on),
                                               None if fixed else tracks.get(on))):
            if base is not None:
                put(ns, frame, ident, what, [(solid.name, solid.shape, base @ solid.pose, None)])
            elif k:
                delete(ns, ident)
    timeline = m.cell_timeline
    left = 0
    spans, note = part_spans(timeline.parts if timeline is not None else ())
    for span in spans:
        shown = [(p.name, p.shape, span.pose @ p.pose, None) for p in cell.parts if p.name == span.name]
        ident = f"part/{span.name}"
        if not span.carried:
            left += 1
            ident = f"{ident}/{left}"
        put(_ns(span.start), flange if span.carried else world, ident, "part", shown)
        if span.end is not None:
            delete(_ns(span.end), ident)
    for ns in sorted(updates):
        out.add("/scene", ns, updates[ns])
    return note


def write_trace(report: Any, path: str, cell: Any = None) -> None:
    """Write the MCAP trace of a run (`report`: a SimReport) to `path`."""
    from mcap.writer import CompressionType, Writer

    messages, extra = trace_messages(report, cell)
    with open(path, "wb") as f:
        w = Writer(f, chunk_size=CHUNK_SIZE, compression=CompressionType.ZSTD)
        w.start(profile="", library=LIBRARY)
        schema_ids: dict[str, int] = {}
        channel_ids: dict[str, int] = {}
        seq: dict[str, int] = {}
        for topic, ns, data in messages:
            if topic not in channel_ids:  # registered when first used: a topic without message has no channel
                name = TOPICS[topic]
                if name not in schema_ids:
                    schema = {"title": name, **SCHEMAS[name]}
                    schema_ids[name] = w.register_schema(name, "jsonschema",
                                                         json.dumps(schema, separators=(",", ":")).encode("utf-8"))
                channel_ids[topic] = w.register_channel(topic, "json", schema_ids[name])
            seq[topic] = seq.get(topic, 0) + 1
            w.add_message(channel_ids[topic], log_time=ns, data=data, publish_time=ns, sequence=seq[topic])
        if extra["urdf"] is not None:
            name, text = extra["urdf"]
            w.add_attachment(create_time=0, log_time=0, name=name, media_type="application/xml",
                             data=text.encode("utf-8"))
        r = report.result
        meta = {"application": r.application, "app_path": report.app_path,
                "robot": (r.robot or {}).get("name", ""), "end_reason": r.end_reason,
                "simulated_duration_s": f"{r.sim_time_us / 1e6:.6f}", "tool_version": report.tool_version}
        if extra["omitted"] is not None:
            meta["omitted"] = extra["omitted"]
        for key in ("tasks_thinned", "io_thinned", "parts_thinned"):
            if extra.get(key):
                meta[key] = extra[key]
        if extra["every"] > 1:
            meta["arm_period_s"] = f"{TICK_S * extra['every']:.6f}"
            meta["thinned"] = thinned_note(extra["every"], TRACE_TICKS)
        w.add_metadata("val3check", meta)
        w.finish()
