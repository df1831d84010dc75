"""Issue 29, fourth round: the reports written from arrays as they go (sim_json's pieces, the
page model's series, `html --model-out`) give the bytes of the writers they replace. Those
writers are kept here as the references: lists of Python objects, written whole."""

from __future__ import annotations

import io
import json
import math

import numpy as np
import pytest

from val3check.motion import trajectory as trajectory_module
from val3check.reporting import sim_collision, sim_json
from val3check.reporting._common import _ESCAPED, visible_data
from val3check.reporting.html import page, series
from val3check.simulation import arm_record

from .runhelp import CELL, ROOT, pickplace


@pytest.fixture(autouse=True)
def _in_root(monkeypatch):
    monkeypatch.chdir(ROOT)  # the report's paths are relative to the current folder


@pytest.fixture(scope="module")
def run():
    return pickplace(20.0, cell=str(CELL))[1]


# ---- the JSON report: the writer of main 1403bb1, kept as the reference --------------------------------


def _old_num(x, digits):
    return None if x is None or not math.isfinite(x) else round(float(x), digits) + 0.0


def _old_rows(a, digits):
    r = np.round(np.asarray(a, dtype=float), digits) + 0.0
    return [sim_json.Raw("[" + ", ".join(map(repr, row)) + "]") for row in r.tolist()]


def _old_scalar(v):
    if type(v) is sim_json.Raw:
        return v
    if v is None:
        return "null"
    if v is True:
        return "true"
    if v is False:
        return "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return sim_json.number(v)
    return json.dumps(v, ensure_ascii=True)


def _old_flat(v):
    return isinstance(v, list) and all(not isinstance(x, (list, dict)) for x in v) and all(
        not isinstance(x, str) or type(x) is sim_json.Raw for x in v) and not (v and type(v[0]) is sim_json.Raw)


def _old_dumps(obj, indent=0):
    pad, inner = "  " * indent, "  " * (indent + 1)
    if isinstance(obj, dict):
        if not obj:
            return "{}"
        items = [f"{inner}{json.dumps(str(k), ensure_ascii=True)}: {_old_dumps(obj[k], indent + 1)}" for k in sorted(obj)]
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(obj, list):
        if not obj:
            return "[]"
        if _old_flat(obj):
            return "[" + ", ".join(_old_scalar(x) for x in obj) + "]"
        return "[\n" + ",\n".join(inner + _old_dumps(x, indent + 1) for x in obj) + "\n" + pad + "]"
    return _old_scalar(obj)


def _fresh(run) -> str:
    """The JSON report as main 1403bb1 wrote it: every row and sample a Python object first."""
    def walk(v):
        if isinstance(v, sim_json.Rows):
            return _old_rows(v.a, v.digits)
        if isinstance(v, sim_json.Lazy):
            return [walk(x) for x in v.make()]
        if isinstance(v, dict):
            return {k: walk(x) for k, x in v.items()}
        if isinstance(v, list):
            return [walk(x) for x in v]
        return v

    rep = walk(sim_json.report(run))
    by_motion = run.result.collision.by_motion
    for e in rep["collision"]["motions"]:
        if "clearance" in e:
            r = by_motion[e["motion"]]
            e["clearance"] = {"times": [_old_num(x, 6) for x in r.times.tolist()],
                              "mm": [_old_num(x, 3) for x in r.clearance.tolist()]}
    return _old_dumps(rep) + "\n"


@pytest.mark.parametrize("ticks", [None, 700])
def test_the_json_report_is_the_text_of_the_writer_it_replaces(run, monkeypatch, ticks):
    if ticks is not None:  # thinned: every k ticks
        monkeypatch.setattr(sim_json, "JSON_TICKS", ticks)
    text = sim_json.render(run)
    data = json.loads(text)
    assert sum(len(s["positions"]) for s in data["motion"]["trajectory"]["segments"]) > 500
    assert sum(len(m.get("clearance", {}).get("mm", [])) for m in data["collision"]["motions"]) > 500
    assert text == _fresh(run)
    assert ("thinned" in data["motion"]["trajectory"]) == (ticks is not None)


def test_the_json_report_is_written_as_it_is_made(run, monkeypatch):
    monkeypatch.setattr(sim_json, "ROWS_BLOCK", 16)
    pieces = list(sim_json.pieces(run))
    text = "".join(pieces)
    assert text == sim_json.render(run) and len(text) > 500_000
    # no piece is the report, a section or a whole trajectory: at most a block of rows or one motion
    assert max(map(len, pieces)) < 20_000 and len(pieces) > 500


def test_per_sample_values_are_written_as_python_rounds_them():
    class Checked:  # what sim_collision reads of a MotionReport
        def __init__(self, times, mm):
            self.times, self.clearance = np.array(times, dtype=float), np.array(mm, dtype=float)

    odd = [0.0, -0.0, 1e-7, 4.9e-5, 5e-5, 0.0004995, 2.0000005, -1.2345675, 1e17, -3e20, math.inf, -math.inf,
           math.nan, 0.1 + 0.2, 123456.7890125]
    reports = [Checked(odd, odd[::-1]), Checked([], []), Checked([0.5], [math.nan])]
    entries = [{"clearance": {}} for _ in reports]
    sim_collision._samples(entries, reports)
    for e, r in zip(entries, reports):
        got = sim_json.dumps(e["clearance"])
        want = _old_dumps({"times": [_old_num(x, 6) for x in r.times.tolist()],
                           "mm": [_old_num(x, 3) for x in r.clearance.tolist()]})
        assert got == want


def test_rows_are_written_block_by_block_as_one_list(monkeypatch):
    a = np.arange(-30, 30, dtype=float).reshape(20, 3) / 7 + 1e-9
    for block in (1, 3, 20, 4096):
        monkeypatch.setattr(sim_json, "ROWS_BLOCK", block)
        for indent in (0, 3):
            assert sim_json.dumps({"q": sim_json.Rows(a, 4)}, indent) == _old_dumps({"q": _old_rows(a, 4)}, indent)
    assert sim_json.dumps({"q": sim_json.Rows(np.zeros((0, 6)), 4)}) == _old_dumps({"q": []})


# ---- the trajectory's segments, sampled in groups ---------------------------------------------------------


def _old_segments(tr, t_end, dt):
    """Trajectory.segments of main 1403bb1: one sample per segment."""
    out, last = [], -1
    for a, b in tr.moving(t_end):
        k0 = max(math.floor(a / dt + 1e-9), last + 1)
        k1 = math.ceil(b / dt - 1e-9)
        if k1 < k0:
            continue
        if out and k0 == last + 1:
            k_prev, qp, vp = out.pop()
            _, q, v = tr.sample(k0 * dt, k1 * dt, dt)
            out.append((k_prev, np.vstack([qp, q]), np.vstack([vp, v])))
        else:
            _, q, v = tr.sample(k0 * dt, k1 * dt, dt)
            out.append((k0, q, v))
        last = k1
    return out


@pytest.mark.parametrize("block", [1, 7, 300, 10**9])
@pytest.mark.parametrize("dt", [0.004, 0.012])
def test_segments_sampled_together_are_the_segments_sampled_one_by_one(run, monkeypatch, block, dt):
    m = run.result.motion
    want = _old_segments(m.trajectory, m.end_s, dt)
    monkeypatch.setattr(trajectory_module, "_SEGMENT_BLOCK", block)
    got = m.trajectory.segments(m.end_s, dt)
    assert len(got) == len(want) > 5
    for (k, q, v), (k_, q_, v_) in zip(got, want):
        assert k == k_ and q.tobytes() == q_.tobytes() and v.tobytes() == v_.tobytes()


# ---- the TCP speed: one product per run of motions with one tool ------------------------------------------


def _old_tcp_speed(kinematics, flange, tool_uses, times, positions, velocities):
    """arm_record.tcp_speed of main 1403bb1: one product per motion."""
    h = arm_record.TCP_STEP_S
    ahead = positions + h * velocities
    starts = [t for t, _ in tool_uses]
    tools = [tool for _, tool in tool_uses]
    idx = np.maximum(np.searchsorted(np.asarray(starts, dtype=float), times, side="right") - 1, 0)
    out = np.zeros(len(times))
    moving = np.flatnonzero(~np.all(ahead == positions, axis=1))
    for b in range(0, len(moving), arm_record.BLOCK):
        rows = moving[b:b + arm_record.BLOCK]
        P = kinematics.link_poses_many(np.concatenate([positions[rows], ahead[rows]]), (flange,))[flange]
        P0, P1 = P[:len(rows)], P[len(rows):]
        at = idx[rows]
        cuts = np.flatnonzero(np.diff(at)) + 1
        for lo, hi in zip([0, *cuts.tolist()], [*cuts.tolist(), len(rows)]):
            tool = tools[int(at[lo])]
            p = np.array([0.0, 0.0, 0.0, 1.0]) if tool is None else np.asarray(tool, dtype=float)[:, 3]
            out[rows[lo:hi]] = np.linalg.norm((P1[lo:hi] @ p - P0[lo:hi] @ p)[:, :3], axis=1) / h
    return out


def test_the_tcp_speed_of_runs_of_one_tool_is_the_speed_motion_by_motion(run):
    m = run.result.motion
    times, q, v = m.sample(0.0, m.end_s, 0.004)
    uses = [(mo.start, mo.tool_in_flange) for mo in m.motions if mo.start is not None and mo.kind != "connection"]
    kin, flange = m.scene.kinematics, m.scene.flange_frame
    got = arm_record.tcp_speed(kin, flange, uses, times, q, v)
    assert got.tobytes() == _old_tcp_speed(kin, flange, uses, times, q, v).tobytes() and got.max() > 100
    # each input of the grouping changed in turn: a motion's tool (by value, not by object), no tool
    for k in (3, 10):
        other = np.array(uses[k][1], dtype=float)
        other[2, 3] += 50.0
        for tool in (other, None):
            changed = uses[:k] + [(uses[k][0], tool)] + uses[k + 1:]
            new = arm_record.tcp_speed(kin, flange, changed, times, q, v)
            assert new.tobytes() == _old_tcp_speed(kin, flange, changed, times, q, v).tobytes()
            during = (times >= uses[k][0]) & (times < uses[k + 1][0])
            assert not np.array_equal(new[during], got[during]) and np.array_equal(new[~during], got[~during])


# ---- the page's data, and the model written from arrays -------------------------------------------------


def _visible_json(data):
    return json.dumps(visible_data(data), separators=(",", ":"), sort_keys=True, ensure_ascii=True, allow_nan=False)


def test_the_page_data_is_walked_whenever_a_string_may_need_it():
    for c in sorted(_ESCAPED):
        data = {"a": ["x" + chr(c) + "y", 1.5], chr(c): {"t": [0.0, 1.0]}}
        assert page._data_json(data) == _visible_json(data) != json.dumps(data, separators=(",", ":"),
                                                                           sort_keys=True)
    for text in ("plain", "é ✓ \U0001f600", "\ud83d\ude00", "a\\u0001b", "tab\tand\nline", "\\b\\f\\r"):
        data = {"s": [text], text: 1}
        assert page._data_json(data) == _visible_json(data)


def test_html_escapes_are_remembered_by_their_text():
    import html

    from val3check.reporting._common import visible

    for text in ("a<b", "a\x00b", "tâche \x1b[31m", "a<b", "", None, 42, "a\x00b"):
        want = html.escape(visible("" if text is None else str(text)), quote=True)
        assert page._e(text) == want


def _as_lists(v):
    if isinstance(v, series.array):
        return v.tolist()
    if isinstance(v, dict):
        return {k: _as_lists(x) for k, x in v.items()}
    if isinstance(v, list):
        return [_as_lists(x) for x in v]
    return v


def test_a_model_with_arrays_is_written_as_json_writes_its_lists(monkeypatch):
    model = {"b": [series.array("d", [1.5, -0.0, 1e-7, 2.5e20]), series.array("d")],
             "a": {"times": series.array("d", [0.1 * k for k in range(50)]), "x": [[series.array("d", [3.0])]]},
             "text": "f00d 0 \u00e9", "n": None, "odd": series.array("d", [math.nan, math.inf, -math.inf])}
    for block in (1, 7, 65_536):
        monkeypatch.setattr(series, "_BLOCK", block)
        fh = io.StringIO()
        series.dump_json(model, fh)
        want = io.StringIO()
        json.dump(_as_lists(model), want, sort_keys=True, indent=1)
        assert fh.getvalue() == want.getvalue()


def test_html_model_out_of_a_json_report_is_written_from_arrays(run, tmp_path):
    from val3check.cli import main
    from val3check.reporting.html import model_from_sim_report
    from val3check.simulation.report_scene import ReportScene

    report = tmp_path / "run.json"
    report.write_text(sim_json.render(run), encoding="utf-8")
    assert main(["html", "--sim-report", str(report), "--model-out", str(tmp_path / "m.json"),
                 "-o", str(tmp_path / "p.html")]) == 0
    model = model_from_sim_report(json.loads(report.read_text(encoding="utf-8")), ReportScene())
    tr = model["trajectory"]
    assert isinstance(tr["times"], series.array) and all(isinstance(r, series.array) for r in tr["positions"])
    want = io.StringIO()
    json.dump(_as_lists(model), want, sort_keys=True, indent=1)
    assert (tmp_path / "m.json").read_text(encoding="utf-8") == want.getvalue() + "\n"
    # the page of the model read back (lists) is the page of the model of arrays
    assert main(["html", str(tmp_path / "m.json"), "-o", str(tmp_path / "again.html")]) == 0
    assert (tmp_path / "again.html").read_bytes() == (tmp_path / "p.html").read_bytes()


def test_display_paths_are_remembered_by_path_and_current_folder(run, monkeypatch, tmp_path):
    from val3check.lint import display_path

    app = str(ROOT / "fixtures/valid/PickPlace/pick.pgx")
    other = str(ROOT / "fixtures/valid/PickPlace/start.pgx")
    assert run.display((app, 3, 1, "pick")) == ("fixtures/valid/PickPlace/pick.pgx", 3, 1, "pick")
    assert run.display((other, 3, 1, "")) == ("fixtures/valid/PickPlace/start.pgx", 3, 1, "")
    monkeypatch.chdir(tmp_path)  # the current folder is part of the key: an absolute path now
    assert run.display((app, 3, 1, "pick")) == (display_path(app), 3, 1, "pick")
    assert display_path(app) != "fixtures/valid/PickPlace/pick.pgx"


def test_the_per_sample_clearances_are_bounded_and_said(run, monkeypatch):
    full = json.loads(sim_json.render(run))["collision"]
    assert "clearance_omitted" not in full  # a short run: every row with its samples
    sizes = [len(m["clearance"]["mm"]) for m in full["motions"]]
    bound = sum(sizes[:5]) + sizes[5] - 1  # the sixth row no longer fits
    monkeypatch.setattr(sim_collision, "CLEARANCE_SAMPLES", bound)
    cut = json.loads(sim_json.render(run))["collision"]
    assert [("clearance" in m) for m in cut["motions"]] == [k < 5 for k in range(len(sizes))]
    assert cut["motions"][:5] == full["motions"][:5]
    assert [m["min_clearance"] for m in cut["motions"]] == [m["min_clearance"] for m in full["motions"]]
    said = cut["clearance_omitted"]
    assert said["count"] == len(sizes) - 5 and said["kept"] == 5 and said["samples"] == sum(sizes[:5])
    assert f"first 5 rows ({sum(sizes[:5])} samples, at most {bound})" in said["why"]
