"""`val3check sim --trace run.mcap` (reporting/mcap_trace.py), read back with the mcap reader:
schemas and channels, message counts, time order, the transforms against the arm model's forward
kinematics (here()) at the sampled times, the log, I/O and task channels, the URDF, determinism."""

from __future__ import annotations

import json
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from mcap.reader import make_reader

from val3check.cli import main
from val3check.collision.results import MotionReport, MotionSpan
from val3check.reporting.mcap_trace import SCHEMAS, TOPICS, write_trace
from val3check.robot import load_robot

from .runhelp import APP, CELL, SCENARIO, pickplace

FOXGLOVE = {"foxglove.FrameTransforms", "foxglove.PoseInFrame", "foxglove.SceneUpdate", "foxglove.Log"}
# Foxglove's published JSON schemas (tests/data/foxglove/README.md says where they come from)
PUBLISHED = Path(__file__).resolve().parents[1] / "data" / "foxglove"


def _published() -> dict:
    """{schema name: Foxglove's JSON schema} of the four Foxglove schemas the trace uses."""
    out = {}
    for f in sorted(PUBLISHED.glob("*.json")):
        schema = json.loads(f.read_text(encoding="utf-8"))
        out[schema["title"]] = schema
    assert set(out) == FOXGLOVE
    return out


def _violations(path) -> tuple[dict, list]:
    """Read a trace back: ({schema name: messages}, [(topic, error)]) of every message of a
    Foxglove schema against Foxglove's published schema, and of every message against the schema
    the file embeds."""
    import jsonschema

    published = {n: jsonschema.Draft7Validator(s) for n, s in _published().items()}
    counts: dict = {}
    bad = []
    with open(path, "rb") as f:
        for sc, ch, msg in make_reader(f).iter_messages():
            message = json.loads(msg.data)
            counts[sc.name] = counts.get(sc.name, 0) + 1
            checks = [jsonschema.Draft7Validator(json.loads(sc.data))]
            if sc.name in published:
                checks.append(published[sc.name])
            bad += [(ch.topic, e.message) for v in checks for e in v.iter_errors(message)]
    return counts, bad


@pytest.fixture(scope="module")
def run():
    return pickplace(20.0, str(CELL))  # its collisions checked: the parts carried and left


@pytest.fixture(scope="module")
def trace(run, tmp_path_factory):
    result, report = run
    path = tmp_path_factory.mktemp("mcap") / "run.mcap"
    rec = next(r for r in result.motion.motions if r.id is not None and r.start is not None)
    checked = MotionReport(MotionSpan(rec.id), np.array([rec.start, rec.start + 0.004, rec.start + 0.008]),
                           np.array([80.0, 75.5, np.inf]), np.array([False, True, False]), margin_mm=10.0)
    kept = [r.clearance for r in result.motion.motions]
    for r in result.motion.motions:  # one motion's clearances slot (simulation/arm_record.py), known values
        r.clearance = checked if r is rec else None
    try:
        write_trace(report, str(path))
    finally:
        for r, c in zip(result.motion.motions, kept):
            r.clearance = c
    with open(path, "rb") as f:
        reader = make_reader(f)
        summary = reader.get_summary()
        messages = [(ch.topic, sc.name, msg.log_time, msg.publish_time, json.loads(msg.data))
                    for sc, ch, msg in reader.iter_messages(log_time_order=False)]
        attachments = list(reader.iter_attachments())
        metadata = list(reader.iter_metadata())
    return SimpleNamespace(path=path, summary=summary, messages=messages, attachments=attachments, metadata=metadata)


def _by(trace, topic):
    return [m for m in trace.messages if m[0] == topic]


def test_schemas_channels_and_counts(trace, run):
    result, report = run
    s = trace.summary
    schemas = {sc.name: sc for sc in s.schemas.values()}
    assert set(schemas) == set(TOPICS.values())
    assert FOXGLOVE <= set(schemas)
    for sc in schemas.values():
        assert sc.encoding == "jsonschema" and json.loads(sc.data)["title"] == sc.name
    channels = {ch.topic: ch for ch in s.channels.values()}
    assert set(channels) == set(TOPICS)
    assert all(ch.message_encoding == "json" and schemas[TOPICS[ch.topic]].id == ch.schema_id for ch in channels.values())
    counts = {channels[t].id: n for t, n in ((t, len(_by(trace, t))) for t in TOPICS)}
    assert s.statistics.channel_message_counts == counts
    ticks = len(_by(trace, "/joint_states"))
    segs = result.motion.trajectory.segments(result.motion.end_s, 0.004)
    assert ticks == 1 + sum(len(q) for _, q, _ in segs) - (1 if segs and segs[0][0] == 0 else 0)
    assert len(_by(trace, "/tf")) == ticks + 1  # and the application's frames and tools, once
    assert len(_by(trace, "/tcp")) == ticks
    assert len(_by(trace, "/io")) == len(result.io_log)
    assert len(_by(trace, "/tasks")) == sum(1 for c in result.task_states if c.time_us <= result.sim_time_us)
    assert len(_by(trace, "/log")) == len(result.transcript) + len(report.diagnostics)
    assert len(_by(trace, "/robot_description")) == 1
    # the per-sample clearance of the collision checks (a sample without a measure is left out)
    clear = [m[4] for m in _by(trace, "/clearance")]
    assert [(c["clearance_mm"], c["exact"], c["margin_mm"]) for c in clear] == [(80.0, False, 10.0), (75.5, True, 10.0)]
    first = next(k for k, r in enumerate(result.motion.motions) if r.id is not None and r.start is not None)
    assert {(c["motion"], c["motion_id"]) for c in clear} == {(first, result.motion.motions[first].id)}
    # the cell once, the TCP marker at each change of tool (tGripper from the first motion on), and
    # the part: taken at each close(tGripper), left at the next open(tGripper)
    moves = [e.action for e in result.motion.tool_events if e.tool == "tGripper"]
    carried, part_updates = False, 0
    for action in moves:
        if (action == "close") != carried:
            carried = not carried
            part_updates += 1
    assert part_updates >= 10 and len(_by(trace, "/scene")) == 2 + part_updates


def test_messages_are_in_time_order_on_the_simulated_clock(trace, run):
    times = [m[2] for m in trace.messages]
    assert times == sorted(times) and times[0] == 0
    assert all(m[2] == m[3] for m in trace.messages)
    # the arm's samples end with the run; stop() may still log and set outputs after a run cut by --duration
    assert max(m[2] for m in trace.messages if m[0] in ("/tf", "/joint_states", "/tcp")) == run[0].sim_time_us * 1000
    for topic, _, t, _, msg in trace.messages:
        if "timestamp" in msg:
            assert msg["timestamp"]["sec"] * 10**9 + msg["timestamp"]["nsec"] == t
    assert trace.summary.statistics.message_start_time == 0


def _matrix(tr):
    x, y, z, w = (tr["rotation"][k] for k in "xyzw")
    R = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                  [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                  [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    M = np.eye(4)
    M[:3, :3] = R
    M[:3, 3] = [tr["translation"][k] * 1000.0 for k in "xyz"]
    return M


def _in_world(tree, frame, world):
    """The pose (4x4, mm) of `frame` in `world`, from {child: (parent, 4x4)} (the transform tree)."""
    def to_root(f):
        M = np.eye(4)
        while f in tree:
            parent, T = tree[f]
            M = T @ M
            f = parent
        return f, M

    root, A = to_root(frame)
    root_w, W = to_root(world)
    assert root == root_w
    return np.linalg.inv(W) @ A


def test_transforms_reproduce_here_at_the_sampled_times(trace, run):
    result, _ = run
    model = load_robot(result.motion.scene.name)
    tree = {}  # the latest transform of each frame, as a viewer keeps them
    tcps = {m[2]: m[4] for m in _by(trace, "/tcp")}
    joints = {m[2]: m[4] for m in _by(trace, "/joint_states")}
    tool = np.eye(4)
    tool[2, 3] = 120.0  # tGripper
    checked = 0
    for n, (topic, _, t, _, msg) in enumerate(m for m in trace.messages if m[0] == "/tf"):
        for x in msg["transforms"]:
            tree[x["child_frame_id"]] = (x["parent_frame_id"], _matrix(x))
        if t < 1e9 or n % 97:
            continue  # from the first motion on (before it, the TCP is the flange), every 97th tick
        q = result.motion.trajectory.position(t / 1e9)
        assert joints[t]["position"] == pytest.approx(list(q), abs=1e-9)
        flange = _in_world(tree, model.flange_frame, model.world_frame)
        assert np.abs(flange[:3] - np.array(model.fk_matrix(q))).max() < 1e-6  # mm (and rotation entries)
        tcp = _in_world(tree, "tcp", model.world_frame)
        assert np.abs(tcp[:3] - np.array(model.fk_matrix(q, tool))).max() < 1e-6
        pose = tcps[t]["pose"]
        assert [pose["position"][a] * 1000 for a in "xyz"] == pytest.approx(tcp[:3, 3].tolist(), abs=1e-6)
        checked += 1
    assert checked > 10
    # the tree is the URDF's: each link in its parent link (base_link -> world is fixed, like the URDF)
    parents = {c: p for c, (p, _) in tree.items()}
    assert parents["link_1"] == "base_link" and parents["flange"] == "link_6" and parents["world"] == "base_link"
    assert parents["tcp"] == "flange"
    moving = [m[4] for m in _by(trace, "/tf")][5]["transforms"]
    assert [x["child_frame_id"] for x in moving] == [f"link_{i}" for i in range(1, 7)] + ["tcp"]


def test_frames_tools_scene_log_io_tasks_and_urdf(trace, run):
    result, _ = run
    static = next(m[4] for m in _by(trace, "/tf") if m[2] == 0 and any(
        x["child_frame_id"] == "fPallet" for x in m[4]["transforms"]))
    by = {x["child_frame_id"]: x for x in static["transforms"]}
    assert by["fPallet"]["parent_frame_id"] == result.motion.scene.world_frame and by["fPallet"]["translation"]["x"] == pytest.approx(0.3)
    assert by["tGripper"]["parent_frame_id"] == result.motion.scene.flange_frame
    assert "fPallet[0]" not in by  # a one-element array is its name
    scenes = _by(trace, "/scene")
    cell = next(m for m in scenes if m[2] == 0 and len(m[4]["entities"]) > 1)
    parts = [m for m in scenes if m[4]["entities"][0]["id"].startswith("part/")]
    ents = {e["id"]: e for e in cell[4]["entities"]}
    assert set(ents) == {"obstacle/table", "obstacle/pallet", "obstacle/post", "tool/jaws", "tool/body"}
    assert ents["obstacle/table"]["cubes"][0]["size"] == pytest.approx({"x": 0.5, "y": 1.2, "z": 0.04})
    assert ents["obstacle/post"]["cylinders"][0]["size"]["z"] == pytest.approx(0.8)
    assert ents["tool/jaws"]["frame_id"] == "flange" and ents["tool/jaws"]["frame_locked"]
    (marker,) = [m for m in scenes if m[4]["entities"][0]["id"] == "tcp"]
    first = min(r.start for r in result.motion.motions if r.start is not None and r.kind != "connection")
    assert marker[2] == round(first * 1e9)
    (tcp,) = marker[4]["entities"]
    assert tcp["id"] == "tcp" and tcp["metadata"] == [{"key": "tool", "value": "tGripper"}]
    assert tcp["spheres"][0]["pose"]["position"]["z"] == pytest.approx(0.12)
    (arrow,) = tcp["arrows"]  # +x turned onto the flange's z: the arrow points to the TCP
    q = arrow["pose"]["orientation"]
    x_axis = _matrix({"rotation": q, "translation": {"x": 0, "y": 0, "z": 0}})[:3, 0]
    assert x_axis == pytest.approx([0, 0, 1], abs=1e-11) and arrow["shaft_length"] + arrow["head_length"] == pytest.approx(0.12)
    # the part rides on the flange from close(), and stays in the world where open() leaves it
    model = load_robot(result.motion.scene.name)
    tool = np.eye(4)
    tool[2, 3] = 120.0
    centre = np.array([0.0, 0.0, 15.0, 1.0])
    taken = [m for m in parts if m[4]["entities"][0]["frame_id"] == "flange"]
    left = [m for m in parts if m[4]["entities"][0]["frame_id"] == "world"]
    assert len(taken) == len(left) + (1 if len(taken) > len(left) else 0) and left
    assert taken[0][4]["entities"][0]["cubes"][0]["pose"]["position"]["z"] == pytest.approx(0.135)
    for m in left:
        (e,) = m[4]["entities"]
        assert m[4]["deletions"] == [{"timestamp": e["timestamp"], "type": 0, "id": "part/part"}]
        q = result.motion.trajectory.position(m[2] / 1e9)
        where = np.array(model.fk_matrix(q, tool)) @ centre
        got = e["cubes"][0]["pose"]["position"]
        assert [got[a] * 1000 for a in "xyz"] == pytest.approx(where.tolist(), abs=1e-6)
    assert len({e["id"] for m in left for e in m[4]["entities"]}) == len(left)  # one entity per part left
    logs = [m[4] for m in _by(trace, "/log")]
    r007 = [x for x in logs if x["message"].startswith("R007 ")]
    assert len(r007) == 1 and r007[0]["level"] == 2 and r007[0]["file"].endswith("PickPlace.pjx")
    io = [m[4] for m in _by(trace, "/io")]
    assert {x["link"] for x in io} >= {"BasicIO-1\\%Q0"} and all("names" in x for x in io)
    tasks = [m[4] for m in _by(trace, "/tasks")]
    assert {x["state"] for x in tasks if x["task"] == "robot"} == {"running", "waiting", "blocked"}
    (desc,) = _by(trace, "/robot_description")
    (att,) = trace.attachments
    assert att.name == "tx2-60.urdf" and att.data.decode() == desc[4]["data"] and "<robot" in desc[4]["data"]
    assert trace.metadata[0].metadata["robot"] == "TX2-60"


@pytest.fixture(scope="module")
def readme_trace(tmp_path_factory):
    """The README's run of the bundled example (its cell beside it, so that the scene has the
    cell, the tool and the parts), 12 simulated seconds, through the command line."""
    path = tmp_path_factory.mktemp("readme") / "run.mcap"
    assert main(["sim", str(APP), "--robot", "tx2-60", "--scenario", str(SCENARIO), "--duration", "12",
                 "--trace", str(path)]) == 0
    return path


def test_every_message_of_the_bundled_example_holds_to_foxglove_s_schemas(readme_trace, capsys):
    """Read back, every message of a Foxglove schema validates against Foxglove's published JSON
    schema (a SceneEntity needs all its primitive arrays, even empty)."""
    capsys.readouterr()
    counts, bad = _violations(readme_trace)
    assert bad == []
    assert counts["foxglove.SceneUpdate"] > 5 and counts["foxglove.FrameTransforms"] > 1000
    assert FOXGLOVE <= set(counts)


def _decimals(x: float) -> int:
    r = repr(float(x))
    if "e" in r:
        mant, exp = r.split("e")
        return (len(mant.split(".")[1]) if "." in mant else 0) - int(exp)
    return len(r.split(".")[1]) if "." in r else 0


def _too_precise(message, limit: int, out: list) -> list:
    """Numbers of the poses, sizes and lengths written with more decimals than docs/trace.md says
    (quaternion components 12, lengths in metres 10)."""
    if isinstance(message, dict):
        for k, v in message.items():
            if k in ("rotation", "orientation"):
                _too_precise(v, 12, out)
            elif k not in ("color", "colors", "timestamp", "lifetime", "indices", "metadata"):
                _too_precise(v, limit, out)
    elif isinstance(message, list):
        for v in message:
            _too_precise(v, limit, out)
    elif isinstance(message, float) and _decimals(message) > limit:
        out.append(message)
    return out


def test_poses_are_written_to_the_precision_docs_trace_md_says(readme_trace):
    """Positions and lengths to 1e-10 m, quaternion components to 1e-12: the arm's ticks, the
    application's frames and tools, the cell, the tool and the parts (item 12: the static frames and
    the scene were written to the last bit)."""
    bad, n = [], 0
    with open(readme_trace, "rb") as f:
        for _, _, m in make_reader(f).iter_messages(topics=["/tf", "/tcp", "/scene"]):
            _too_precise(json.loads(m.data), 10, bad)
            n += 1
    assert n > 2000 and bad == []


def test_the_shipped_layout_is_the_bundled_example_s_one_row_per_task(readme_trace, tmp_path, capsys):
    """docs/foxglove-layout.json is what `python -m val3check.reporting.foxglove_layout` makes of the
    bundled example's trace: Foxglove's State Transitions panel draws one row per path, and each
    task's path keeps that task's messages only (a message path filter on its name)."""
    from val3check.reporting.foxglove_layout import main as layout_main

    out = tmp_path / "layout.json"
    assert layout_main([str(readme_trace), "-o", str(out)]) == 0
    assert "3 task(s), 6 joint(s)" in capsys.readouterr().err
    shipped = (Path(__file__).resolve().parents[2] / "docs" / "foxglove-layout.json").read_text(encoding="utf-8")
    assert out.read_text(encoding="utf-8") == shipped
    rows = json.loads(shipped)["configById"]["StateTransitions!tasks"]["paths"]
    with open(readme_trace, "rb") as f:
        tasks = [json.loads(m.data)["task"] for _, _, m in make_reader(f).iter_messages(topics=["/tasks"])]
    assert [r["label"] for r in rows] == list(dict.fromkeys(tasks)) == ["PickPlace~", "robot", "~PickPlace"]
    assert [r["value"] for r in rows] == [f'/tasks{{task=="{t}"}}.state' for t in ("PickPlace~", "robot", "~PickPlace")]


def test_layout_of_a_scara_and_of_names_that_need_quoting():
    from val3check.reporting.foxglove_layout import layout, task_path

    lay = layout(["a\"b", "t"], axes=4)
    assert [p["label"] for p in lay["configById"]["Plot!velocities"]["paths"]] == ["j1", "j2", "j3", "j4"]
    assert task_path('a"b') == '/tasks{task=="a\\"b"}.state'


def test_a_file_that_is_no_trace_is_refused_with_its_name(tmp_path, capsys):
    from val3check.reporting.foxglove_layout import main as layout_main

    bad = tmp_path / "x.mcap"
    bad.write_text("not mcap")
    assert layout_main([str(bad)]) == 2
    assert layout_main([str(tmp_path / "none.mcap")]) == 2
    err = capsys.readouterr().err
    assert "x.mcap: not a trace" in err and "none.mcap: cannot read" in err


def test_the_test_trace_holds_to_foxglove_s_schemas(trace):
    """The module's trace (a cell, a clearance, the log): every message validates."""
    counts, bad = _violations(trace.path)
    assert bad == [] and FOXGLOVE <= set(counts)


def test_a_mesh_obstacle_is_a_triangle_list_foxglove_accepts():
    """A mesh of the cell (docs/cell.md) as a SceneEntity's triangle list (with its `colors`, empty)."""
    import jsonschema

    from val3check.reporting.mcap_trace import _entity

    mesh = SimpleNamespace(vertices=[[0, 0, 0], [100, 0, 0], [0, 100, 0], [0, 0, 100]],
                           faces=[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    e = _entity(0, "world", "obstacle/machine", "obstacle", [("machine", SimpleNamespace(kind="mesh", mesh=mesh),
                                                                np.eye(4), None)])
    (tri,) = e["triangles"]
    assert len(tri["points"]) == 4 and tri["indices"][:3] == [0, 2, 1] and tri["points"][1]["x"] == 0.1
    jsonschema.Draft7Validator(_published()["foxglove.SceneUpdate"]).validate({"deletions": [], "entities": [e]})


def _required(ours: dict, theirs: dict, where: str = "") -> list[str]:
    """Where the schema val3check embeds requires other fields than Foxglove's (walking the
    properties both describe)."""
    out = []
    if "properties" in ours:
        if set(ours.get("required", [])) != set(theirs.get("required", [])):
            out.append(f"{where or '/'}: {sorted(ours.get('required', []))} != {sorted(theirs.get('required', []))}")
        for k, sub in ours["properties"].items():
            if k in theirs.get("properties", {}):
                out += _required(sub, theirs["properties"][k], f"{where}/{k}")
    if "items" in ours and "items" in theirs:
        out += _required(ours["items"], theirs["items"], f"{where}[]")
    return out


def test_the_embedded_schemas_require_what_foxglove_s_require():
    for name, theirs in _published().items():
        ours = SCHEMAS[name]
        assert _required(ours, theirs) == [], name
        assert set(ours["properties"]) <= set(theirs["properties"])


def test_schema_field_names_are_foxglove_s():
    """The fields val3check fills, by Foxglove's names (docs.foxglove.dev schemas)."""
    tf = SCHEMAS["foxglove.FrameTransforms"]["properties"]["transforms"]["items"]["properties"]
    assert set(tf) == {"timestamp", "parent_frame_id", "child_frame_id", "translation", "rotation"}
    assert set(SCHEMAS["foxglove.PoseInFrame"]["properties"]) == {"timestamp", "frame_id", "pose"}
    assert set(SCHEMAS["foxglove.Log"]["properties"]) == {"timestamp", "level", "message", "name", "file", "line"}
    ent = SCHEMAS["foxglove.SceneUpdate"]["properties"]["entities"]["items"]["properties"]
    assert {"frame_id", "id", "frame_locked", "cubes", "spheres", "cylinders", "triangles"} <= set(ent)


def test_sim_trace_option_is_deterministic(tmp_path, monkeypatch, capsys):
    outs = []
    for n in (1, 2):
        path = tmp_path / f"run{n}.mcap"
        code = main(["sim", str(APP), "--robot", "tx2-60", "--scenario", str(SCENARIO), "--duration", "8",
                     "--trace", str(path)])
        assert code == 0
        outs.append(path.read_bytes())
    assert outs[0] == outs[1] and len(outs[0]) > 10_000
    assert "cycle" in capsys.readouterr().out  # the text report still goes to stdout


def test_trace_to_an_unwritable_place_is_a_clear_error(tmp_path, capsys):
    code = main(["sim", str(APP), "--robot", "tx2-60", "--scenario", str(SCENARIO), "--duration", "2",
                 "--trace", str(tmp_path / "no" / "such" / "dir" / "run.mcap")])
    assert code == 2
    assert "cannot write the trace" in capsys.readouterr().err


def test_foxglove_layout_opens_the_trace_s_topics():
    """docs/foxglove-layout.json: the 3D view (URDF from /robot_description, the scene), joint
    plots, the log; every panel in the layout is configured and reads a topic the trace has."""
    from pathlib import Path

    layout = json.loads((Path(__file__).resolve().parents[2] / "docs" / "foxglove-layout.json").read_text())
    panels = set(layout["configById"])

    def leaves(node):
        return [node] if isinstance(node, str) else leaves(node["first"]) + leaves(node["second"])

    assert sorted(leaves(layout["layout"])) == sorted(panels)
    text = json.dumps(layout["configById"])
    import re

    used = set(re.findall(r'"(/[a-z_]+)', text))
    assert used and used <= set(TOPICS), used - set(TOPICS)
    assert {"3D", "Plot", "Log"} <= {p.split("!")[0] for p in panels}
    assert layout["configById"]["3D!val3check"]["layers"]["arm"]["topic"] == "/robot_description"


def test_trace_of_a_run_without_an_arm_has_no_arm_topics(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(APP.parents[2])
    path = tmp_path / "run.mcap"
    main(["sim", "fixtures/valid/Supervisor", "--duration", "5", "--trace", str(path)])
    capsys.readouterr()
    with open(path, "rb") as f:
        reader = make_reader(f)
        topics = {ch.topic for ch in reader.get_summary().channels.values()}
        assert list(reader.iter_attachments()) == []
    assert topics and topics <= {"/log", "/io", "/tasks"} and "/tasks" in topics


def test_quaternions_of_any_rotation():
    """Every branch of the conversion (trace largest, or x, y, z largest), against the matrix."""
    from val3check.reporting.mcap_trace import quaternions

    rng = np.random.default_rng(7)
    A = rng.normal(size=(400, 3, 3))
    R = np.linalg.qr(A)[0] * np.sign(np.linalg.det(np.linalg.qr(A)[0]))[:, None, None]
    R = np.concatenate([R, np.array([np.diag([1.0, -1, -1]), np.diag([-1.0, 1, -1]), np.diag([-1.0, -1, 1]), np.eye(3)])])
    q = quaternions(R)
    assert np.allclose(np.linalg.norm(q, axis=1), 1.0) and (q[:, 3] >= 0).all()
    for Rk, qk in zip(R, q):
        back = _matrix({"rotation": dict(zip("xyzw", qk)), "translation": {"x": 0, "y": 0, "z": 0}})[:3, :3]
        assert np.abs(back - Rk).max() < 1e-12


def test_a_half_turn_keeps_its_sign_whatever_the_last_bits():
    """A tool pointing straight down is a half turn about a horizontal axis: w is 0 up to the
    matrix's last bits, and the w >= 0 rule alone wrote x and y with either sign (the traces of one
    motion timed two ways, issue 29). The first of w, x, y, z that is not about 0 is positive."""
    from val3check.reporting.mcap_trace import quaternions

    c, s = np.cos(0.7), np.sin(0.7)
    axis = np.array([c, s, 0.0])
    R0 = 2 * np.outer(axis, axis) - np.eye(3)  # a half turn about `axis`
    qs = []
    for e in (0.0, 1e-15, -1e-15, 3e-16, -3e-16):
        R = R0.copy()
        R[2, 1] += e
        R[1, 2] -= e  # w = (R21 - R12) / 4x: its sign follows e
        qs.append(quaternions(R[None])[0])
    for q in qs:
        assert np.allclose(q, [c, s, 0.0, 0.0], atol=1e-12)
    q = quaternions(np.stack([R0, np.diag([-1.0, -1, 1]), np.eye(3)]))
    assert np.allclose(q, [[c, s, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]], atol=1e-12)


def test_obstacles_follow_their_frame_and_parts_their_spans(tmp_path):
    """A run that moves fBlock between two motions and carries a part (runhelp.MOVING), read back:
    the block is sent again, 800 mm further, when the checks read fBlock's new value, and fBlock's
    transform with it; the brick rides on the flange from close() and is left where open() leaves it."""
    from .runhelp import moving_run

    result, report = moving_run(tmp_path)
    path = tmp_path / "moving.mcap"
    write_trace(report, str(path))
    with open(path, "rb") as f:
        messages = [(ch.topic, msg.log_time, json.loads(msg.data))
                    for _, ch, msg in make_reader(f).iter_messages(log_time_order=True)]
    moved = round(result.motion.motions[3].start * 1e9)
    close, open_ = (e.time_us * 1000 for e in result.motion.tool_events)
    ents = [(t, e) for topic, t, m in messages if topic == "/scene" for e in m["entities"]]
    block = [(t, e["frame_id"], e["cubes"][0]["pose"]["position"]) for t, e in ents if e["id"] == "obstacle/block"]
    assert [(t, frame, pytest.approx([p["x"], p["y"], p["z"]])) for t, frame, p in block] == [
        (0, "world", [-0.4, 0.5, 0.1]), (moved, "world", [0.4, 0.5, 0.1])]
    tf = [(t, x["translation"]["x"]) for topic, t, m in messages if topic == "/tf" for x in m["transforms"]
          if x["child_frame_id"] == "fBlock"]
    assert tf == [(0, pytest.approx(-0.4)), (moved, pytest.approx(0.4))]
    brick = [(t, e["id"], e["frame_id"], e["cubes"][0]["pose"]["position"]) for t, e in ents
             if e["id"].startswith("part/")]
    assert [(t, i, f) for t, i, f, _ in brick] == [(close, "part/brick", "flange"), (open_, "part/brick/1", "world")]
    assert brick[0][3]["z"] == pytest.approx(0.12)  # 100 mm (tGrip) + 20 mm (at) out of the flange
    assert [brick[1][3][k] for k in "xyz"] == pytest.approx([0.4, 0.2, 0.02], abs=1e-9)  # on the table at pPlace
    gone = [(t, d["id"]) for topic, t, m in messages if topic == "/scene" for d in m["deletions"]]
    assert gone == [(open_, "part/brick")]
