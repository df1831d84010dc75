"""The task timelines of a long run are bounded (reporting/thinning.py TASK_CHANGES): the HTML
page's timelines and the trace's /tasks hold the first changes, and both say so."""

from __future__ import annotations

import json

from mcap.reader import make_reader

from val3check.reporting import thinning
from val3check.reporting.html.from_run import model_from_run
from val3check.reporting.mcap_trace import write_trace

from .runhelp import pickplace


def test_the_timelines_and_the_trace_hold_the_first_changes_and_say_so(tmp_path, monkeypatch):
    result, report = pickplace(20.0)
    total = len(result.task_states)
    page = model_from_run(report)
    assert not any("task state changes" in x for x in page["limitations"])  # a short run: all of them
    whole = sum(len(t["segments"]) for t in page["tasks"])
    keep = total // 2
    monkeypatch.setattr(thinning, "TASK_CHANGES", keep)
    page = model_from_run(report)
    until = result.task_states[keep].time_us / 1e6
    (note,) = [x for x in page["limitations"] if "task state changes" in x]
    assert f"the first {keep} of {total} task state changes (up to {until:g} s)" in note
    segments = [s for t in page["tasks"] for s in t["segments"]]
    assert 0 < len(segments) < whole and max(s["end"] for s in segments) <= until
    path = tmp_path / "t.mcap"
    write_trace(report, str(path))
    with open(path, "rb") as f:
        reader = make_reader(f)
        tasks = [m for _, ch, m in reader.iter_messages() if ch.topic == "/tasks"]
        (meta,) = [m for m in reader.iter_metadata() if m.name == "val3check"]
    assert len(tasks) == keep
    assert max(json.loads(m.data)["timestamp"]["sec"] + json.loads(m.data)["timestamp"]["nsec"] / 1e9
               for m in tasks) < until
    assert "task state changes" in meta.metadata["tasks_thinned"]
