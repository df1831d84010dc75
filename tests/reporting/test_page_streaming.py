"""Issue 29, fifth round: the page of a run written as it is made (page.pieces), its trajectory
sampled and packed a block of whole buckets at a time (run_trajectory.py), the arm timeline's spans
beyond the bound counted, never made. Each gives the bytes of the writer it replaces: those
writers (main 1ed7d98) are kept here as the references. And what the page's making holds is
counted: one block of samples at a time, each sample made once, the spans beyond the bound never
held."""

from __future__ import annotations

import base64
import gc
import json
import math
import struct
import weakref

import numpy as np
import pytest

from val3check.reporting import thinning
from val3check.reporting.html import from_run, pack, page, run_trajectory, series
from val3check.reporting.html.model import ARM_STATES, TASK_STATES, ModelError, check_model

from .runhelp import CELL, ROOT, pickplace


@pytest.fixture(autouse=True)
def _in_root(monkeypatch):
    monkeypatch.chdir(ROOT)  # the report's paths are relative to the current folder


@pytest.fixture(scope="module")
def run():
    return pickplace(20.0, cell=str(CELL))


# ---- the former writers (main 1ed7d98), kept as the references ----------------------------------------


def _former_trajectory(m):
    """from_run._trajectory: the whole run sampled at once."""
    dt = from_run.sample_period(m.end_s)
    times, q, v = (np.asarray(a, dtype=float) for a in m.sample(0.0, m.end_s, dt))
    speed = np.zeros(len(times))
    on = np.flatnonzero((v != 0.0).any(axis=1))
    if len(on):
        speed[on] = m.tcp_speed(times[on], q[on], v[on])
    return {"joints": run_trajectory.joints(m.scene), "times": series.doubles(series.rounded(times, 6)),
            "positions": [series.doubles(row) for row in np.round(q.T, 6) + 0.0],
            "velocities": [series.doubles(row) for row in np.round(v.T, 4) + 0.0],
            "tcp_speed": series.doubles(np.round(speed, 3) + 0.0)}


def _f32(values):
    if not isinstance(values, list):
        a = np.asarray(values, dtype=float)
        b = a.astype("<f4")
        if np.isfinite(b).all() or not np.isfinite(a).all():
            return base64.b64encode(b.tobytes()).decode("ascii")
        values = a.tolist()
    return base64.b64encode(struct.pack(f"<{len(values)}f", *values)).decode("ascii")


def _f64(values):
    if not isinstance(values, list):
        return base64.b64encode(np.asarray(values, dtype="<f8").tobytes()).decode("ascii")
    return base64.b64encode(struct.pack(f"<{len(values)}d", *values)).decode("ascii")


def _former_series(values, size):
    if not size:
        return {"v": _f32(values)}
    arr = series.floats(values)
    if arr is not None:
        if not (np.signbit(arr) & (arr == 0.0)).any():
            starts = np.arange(0, len(arr), size)
            return {"lo": _f32(np.minimum.reduceat(arr, starts)), "hi": _f32(np.maximum.reduceat(arr, starts))}
        values = arr.tolist()
    starts = range(0, len(values), size)
    return {"lo": _f32([min(values[a:a + size]) for a in starts]), "hi": _f32([max(values[a:a + size]) for a in starts])}


def _firsts(values, size):
    arr = series.floats(values)
    return values[::size] if arr is None else arr[::size]


def _former_packed(tr):
    if not tr or not tr.get("times"):
        return None
    times = tr["times"]
    n = len(times)
    size = 0 if n <= pack.FULL_RATE_MAX else math.ceil(n / pack.PLOT_BUCKETS)
    plot_times = _firsts(times, size) if size else times
    out = {"samples": n, "decimated": bool(size), "bucket": size or 1, "t": _f64(plot_times),
           "joints": [{"name": j["name"], "unit": j["unit"], "min": j.get("min"), "max": j.get("max"),
                       "speed": j.get("speed"), "pos": _former_series(tr["positions"][i], size),
                       "vel": _former_series(tr["velocities"][i], size)} for i, j in enumerate(tr["joints"])],
           "tcp": _former_series(tr["tcp_speed"], size) if tr.get("tcp_speed") is not None else None, "anim": None}
    if size:
        out["anim"] = {"t": _f64(plot_times), "q": [_f32(_firsts(row, size)) for row in tr["positions"]]}
    return out


def _former_page_data(model):
    tasks, details = pack._states(model.get("tasks", []), TASK_STATES)
    arm_rows, _ = pack._states([{"name": "arm", "segments": model.get("arm_timeline", [])}], ARM_STATES)
    return {
        "duration": model["verdict"]["simulated_duration"], "traj": _former_packed(model.get("trajectory")),
        "motions": [{"id": m["id"], "kind": m["kind"], "line": m.get("line"), "start": m["start"], "end": m["end"],
                     "vel": m.get("vel"), "tvel": m.get("tvel")} for m in model.get("motions", [])],
        "task_states": list(TASK_STATES), "arm_states": list(ARM_STATES), "tasks": tasks, "details": details,
        "arm": arm_rows[0]["segs"] if model.get("arm_timeline") else [], "io": pack._io(model.get("io", [])),
        "diags": [{"time": d.get("time"), "severity": d["severity"], "code": d["code"], "task": d.get("task"),
                   "line": d.get("line"), "message": d["message"]} for d in model.get("diagnostics", [])],
        "cycles": [{"task": c["task"], "label": c.get("label") or c["task"],
                    "it": [[it["start"], it["duration"], 1 if it.get("complete", True) else 0] for it in c["iterations"]]}
                   for c in model.get("cycles", [])],
        "scene": model.get("scene"),
    }


def _former_motions(m: dict) -> str:
    motions = m.get("motions", [])
    if not motions:
        body = '<p class="empty">No motion in this run.</p>'
    else:
        moving = sum(mo["end"] - mo["start"] for mo in motions)
        clear = [mo for mo in motions if mo.get("min_clearance") is not None]
        closest = min(clear, key=lambda mo: mo["min_clearance"]) if clear else None
        summary = f"{page._plural(len(motions), 'motion')}, {page._s(moving)} moving"
        if closest:
            summary += (f"; smallest clearance {page._num(closest['min_clearance'])} mm"
                        f"{' to ' + page._e(closest['clearance_to']) if closest.get('clearance_to') else ''} (motion {closest['id']})")
        rows = []
        for mo in motions:
            speed = []
            if mo.get("vel") is not None:
                speed.append(f"vel {mo['vel']:g} %")
            if mo.get("tvel") is not None:
                speed.append(f"tvel {mo['tvel']:g} mm/s")
            clearance = page._num(mo.get("min_clearance"))
            if mo.get("clearance_to") and mo.get("min_clearance") is not None:
                clearance += f' <span class="muted">{page._e(mo["clearance_to"])}</span>'
            rows.append(
                f'<tr><td class="n">{page._time_button(mo["start"], mo["end"], str(mo["id"]), True)}</td>'
                f'<td class="nw">{page._source(mo)}</td><td>{page._e(mo.get("task") or "")}</td>'
                f'<td><code>{page._e(mo["kind"])}</code></td><td>{page._e(mo.get("target") or "")}</td>'
                f'<td class="n">{mo["start"]:.3f}</td><td class="n">{mo["end"]:.3f}</td>'
                f'<td class="n">{(mo["end"] - mo["start"]) if mo.get("duration") is None else mo["duration"]:.3f}</td>'
                f'<td>{page._e(mo.get("dominant_limit") or "–")}</td><td class="nw">{page._e(", ".join(speed))}</td>'
                f'<td class="n">{clearance}</td></tr>')
        body = (f'<p>{summary}. The number zooms the timelines on the motion.</p>'
                '<div class="scroll tall"><table class="data motions"><thead><tr>'
                '<th scope="col">#</th><th scope="col">program:line</th><th scope="col">task</th><th scope="col">kind</th>'
                '<th scope="col">target</th><th scope="col">start (s)</th><th scope="col">end (s)</th>'
                '<th scope="col">duration (s)</th><th scope="col">dominant limit</th><th scope="col">speed</th>'
                f'<th scope="col">clearance (mm)</th></tr></thead><tbody>{"".join(rows)}</tbody></table></div>')
    return f'<section id="motions" aria-labelledby="motions-h"><h2 id="motions-h">Motions</h2>{body}</section>'


def _former_cycles(m: dict) -> str:
    cycles = m.get("cycles", [])
    if not cycles or not any(c["iterations"] for c in cycles):
        body = '<p class="empty">No loop iteration recorded.</p>'
    else:
        parts = []
        for ci, c in enumerate(cycles):
            its = c["iterations"]
            done = [it["duration"] for it in its if it.get("complete", True)]
            stats = (f"{len(done)} complete: min {page._s(min(done))}, mean {page._s(sum(done) / len(done))}, max {page._s(max(done))}"
                     if done else "no complete iteration")
            rows = "".join(
                f'<tr><td class="n">{page._time_button(it["start"], it["start"] + it["duration"], str(k + 1), True)}</td>'
                f'<td class="n">{it["start"]:.3f}</td><td class="n">{it["duration"]:.3f}</td>'
                f'<td>{"" if it.get("complete", True) else "cut by the end of the run"}</td></tr>'
                for k, it in enumerate(its))
            where = page._where(c.get("path"), c.get("line"), None)
            parts.append(
                f'<h3>Task {page._e(c["task"])}: {page._e(c.get("label") or "")} <span class="muted">{page._e(where)}</span></h3>'
                f'<p>{stats}.</p><div class="figure cyclebars" data-cycle="{ci}" role="img" '
                f'aria-label="Duration of each iteration of the loop of task {page._e(c["task"])}"></div>'
                '<details><summary>Iterations</summary><table class="data"><thead><tr><th scope="col">#</th>'
                '<th scope="col">start (s)</th><th scope="col">duration (s)</th><th scope="col">note</th></tr></thead>'
                f'<tbody>{rows}</tbody></table></details>')
        body = "".join(parts)
    return f'<section id="cycles" aria-labelledby="cycles-h"><h2 id="cycles-h">Cycle time per loop iteration</h2>{body}</section>'


def _former_render(model):
    """page.render: the whole page as one string."""
    check_model(model)
    former = {"motions": _former_motions, "cycles": _former_cycles}
    sections = "".join(former.get(sid, fn)(model) for sid, _, fn in page.SECTIONS)
    body = (f"{page._header(model)}{page._nav([(sid, title) for sid, title, _ in page.SECTIONS])}"
            f'<main id="main">{page._timebar(model) if page._has_time(model) else ""}{sections}</main>'
            '<footer><p>This page is self-contained: it loads nothing, from the network or from disk. '
            'Its plots and 3D view need JavaScript; the tables above do not.</p></footer>'
            '<noscript><p class="empty">JavaScript is off: the plots, timelines and the 3D view are not drawn.</p></noscript>')
    css = page._asset("report.css")
    script = "\n".join(page._asset(name) for name in page.SCRIPTS)
    data = page._data_json(_former_page_data(model))
    data = data.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")
    csp = ("default-src 'none'; "
           f"script-src '{page._sha256(script)}'; style-src '{page._sha256(css)}'; img-src data:; "
           "base-uri 'none'; form-action 'none'")
    tool = model.get("tool") or {}
    values = {"csp": csp, "generator": page._e(f"{tool.get('name', 'val3check')} {tool.get('version', '')}".strip()),
              "title": page._e(f"{model.get('title') or model['application']['name']}: simulation report"),
              "css": css, "body": body, "data": data, "script": script}
    out, pos, template = [], 0, page._asset("page.html")
    while True:
        start = template.find("{{", pos)
        if start < 0:
            out.append(template[pos:])
            break
        end = template.index("}}", start)
        out += [template[pos:start], values[template[start + 2:end]]]
        pos = end + 2
    return "".join(out)


def _former_arm_timeline(moving, end, limits):
    segs, t = [], 0.0
    for a, b in moving:
        a, b = min(a, end), min(b, end)
        if a > t:
            segs.append({"start": from_run._r(t), "end": from_run._r(a), "state": "idle"})
        if b > a:
            segs.append({"start": from_run._r(a), "end": from_run._r(b), "state": "moving"})
        t = max(t, b)
    if t < end:
        segs.append({"start": from_run._r(t), "end": from_run._r(end), "state": "idle"})
    items = list(segs)
    if len(items) <= thinning.ARM_SPANS:
        return items
    limits.append(f"A long run: the arm timeline holds the first {thinning.ARM_SPANS} of {len(items)} moving and "
                  f"idle spans (up to {items[thinning.ARM_SPANS]['start']:g} s).")
    return items[:thinning.ARM_SPANS]


# ---- the same bytes -------------------------------------------------------------------------------------

# (full-rate samples, plot buckets, block samples): full rate; buckets of 8 and of 7 samples with
# blocks of 96 and 98 and a short last bucket; a block of one bucket
SHAPES = [(30_000, 15_000, 16_384), (1_000, 700, 100), (1_000, 715, 100), (1_000, 715, 7)]


@pytest.mark.parametrize("full, buckets, block", SHAPES)
def test_the_page_written_as_it_goes_is_the_former_page(run, monkeypatch, full, buckets, block):
    result, report = run
    monkeypatch.setattr(pack, "FULL_RATE_MAX", full)
    monkeypatch.setattr(pack, "PLOT_BUCKETS", buckets)
    monkeypatch.setattr(run_trajectory, "BLOCK_SAMPLES", block)
    model = from_run.model_from_run(report)
    assert len(model["trajectory"]["times"]) == 5001
    former = dict(model, trajectory=_former_trajectory(result.motion))
    for key in ("times", "tcp_speed"):
        assert model["trajectory"][key] == former["trajectory"][key]  # the model's series, block by block
    for key in ("positions", "velocities"):
        assert model["trajectory"][key] == former["trajectory"][key]
    want = _former_render(former)
    pieces = list(from_run.page_pieces(report))
    assert "".join(pieces) == want == page.render(model) == from_run.render_run(report)
    assert isinstance(from_run.model_from_run(report, packed=True)["trajectory"], series.Packed)
    assert pack.page_data(model) == _former_page_data(model)


def test_the_data_written_value_by_value_is_the_former_json():
    """A value whose JSON may hold a character `visible` rewrites is walked alone: the same text
    as walking the whole data (test_report_writers)."""
    for text in ("plain", "a\x00b", "tâche \x1b[31m", "</script><!--", "\ud83d"):
        model = {"version": 1, "application": {"name": "A"}, "verdict": {"counts": {}, "end_reason": "end",
                                                                         "simulated_duration": 1.0},
                 "diagnostics": [{"code": "V1", "severity": "info", "message": text, "time": 0.5}],
                 "io": [{"time": 0.25, "kind": "dio", "link": text, "value": True, "names": [text]}]}
        data = page._data_json(_former_page_data(model))
        data = data.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")
        assert "".join(page._data(model)) == data


@pytest.mark.parametrize("bound", [1, 2, 5, 10_000])
def test_the_arm_timeline_counts_the_spans_beyond_its_bound(run, monkeypatch, bound):
    result, _ = run
    m = result.motion
    monkeypatch.setattr(thinning, "ARM_SPANS", bound)
    moving = m.trajectory.moving(m.end_s)
    end = from_run._r(result.sim_time_us / 1e6)
    want, got = [], []
    assert from_run._arm_timeline(moving, end, got) == _former_arm_timeline(moving, end, want)
    assert got == want and bool(got) == (bound < 10_000)


def test_the_first_of_a_bound_are_the_first_of_an_iterable_and_of_a_list():
    for n in (0, 3, 4, 5, 50):
        items = [{"start": 0.5 * k} for k in range(n)]
        for source in (items, iter(items), (x for x in items)):
            assert thinning.first(source, 4, "w", "things", lambda s: s["start"]) == (
                (items, None) if n <= 4 else
                (items[:4], f"a long run: w the first 4 of {n} things (up to {items[4]['start']:g} s)"))


# ---- what is held --------------------------------------------------------------------------------------


def test_the_page_samples_the_run_a_block_at_a_time_each_sample_once(run, monkeypatch):
    """Every sample of the page's clock is made once, in blocks of at most BLOCK_SAMPLES, and no
    block's arrays are alive when the next is made: what the page holds of the trajectory does not
    grow with the run."""
    result, report = run
    m = result.motion
    monkeypatch.setattr(pack, "FULL_RATE_MAX", 1_000)
    monkeypatch.setattr(pack, "PLOT_BUCKETS", 700)
    monkeypatch.setattr(run_trajectory, "BLOCK_SAMPLES", 100)
    asked, alive = [], []
    sample = type(m).sample

    def counted(self, t0=0.0, t1=None, dt=0.004):
        gc.collect()
        alive.append(sum(r() is not None for r in held))
        out = sample(self, t0, t1, dt)
        asked.append(len(out[0]))
        held.extend(weakref.ref(a) for a in out)
        return out

    held: list = []
    monkeypatch.setattr(type(m), "sample", counted)
    traj = from_run.model_from_run(report, packed=True)["trajectory"]
    assert sum(asked) == traj.samples == 5001 and max(asked) == 96 and len(asked) == 53  # 8-sample buckets
    assert alive == [0] * len(asked)
    # the packed data holds each series' buckets, not its samples
    data = traj.data
    assert data["decimated"] and len(base64.b64decode(data["joints"][0]["pos"]["lo"])) == 4 * math.ceil(5001 / 8)
    page_text = from_run.render_run(report)
    assert len(asked) == 2 * 53 and json.dumps(data, sort_keys=True, separators=(",", ":")) in page_text


def test_a_block_spans_at_most_block_s_of_the_run(run, monkeypatch):
    result, _ = run
    m = result.motion
    monkeypatch.setattr(run_trajectory, "BLOCK_S", 1.0)  # 250 ticks of 4 ms
    asked = []
    sample = type(m).sample

    def counted(self, *a):
        out = sample(self, *a)
        asked.append(len(out[0]))
        return out

    monkeypatch.setattr(type(m), "sample", counted)
    traj = run_trajectory.packed(m, 0.004, 5001)
    assert max(asked) == 250 and sum(asked) == 5001 and traj.samples == 5001


def test_the_tcp_speed_of_a_block_reads_the_motions_of_its_window(run):
    """The TCP speed of a block, given only the motions whose tool its samples may use, is the
    speed computed with every motion: to the bit, for windows across and between motions."""
    result, _ = run
    m = result.motion
    times, q, v = m.sample(0.0, m.end_s, 0.004)
    tcp = run_trajectory._TcpSpeed(m)
    assert tcp.window and len(tcp.uses) > 5
    for lo, hi in ((0, 40), (0, 5001), (1200, 1260), (3000, 4100), (4990, 5001)):
        t, a, b = times[lo:hi], q[lo:hi], v[lo:hi]
        assert tcp(t, a, b).tobytes() == m.tcp_speed(t, a, b).tobytes()


def test_a_block_check_model_would_refuse_gives_the_model_s_series(run, monkeypatch):
    """A value check_model refuses (not finite): the page's trajectory falls back to the model's
    series, so that check_model names the value at fault."""
    _, report = run
    blocks = run_trajectory._blocks

    def bad(*a):
        for k, (t, q, v, s) in enumerate(blocks(*a)):
            if k == 0:
                q = q.copy()
                q[2][7] = math.nan
            yield t, q, v, s

    monkeypatch.setattr(run_trajectory, "_blocks", bad)
    model = from_run.model_from_run(report, packed=True)
    assert isinstance(model["trajectory"], dict)
    with pytest.raises(ModelError, match=r"trajectory\.positions\[2\]\[7\]"):
        list(from_run.page_pieces(report))
