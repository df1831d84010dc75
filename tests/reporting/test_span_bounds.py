"""The arm timeline, the I/O changes and the parts' spans of a long run are bounded
(reporting/thinning.py ARM_SPANS, IO_EVENTS, PART_SPANS): the HTML page and the trace hold the
first ones, and say so (the page's limitations, the trace's metadata), as the task timelines do."""

from __future__ import annotations

import json

from mcap.reader import make_reader

from val3check.reporting import thinning
from val3check.reporting.html.from_run import model_from_run
from val3check.reporting.mcap_trace import write_trace

from .runhelp import CELL, pickplace


def _trace(report, path) -> tuple[list, dict]:
    """The trace's messages as (topic, JSON) and its val3check metadata."""
    write_trace(report, str(path))
    with open(path, "rb") as f:
        reader = make_reader(f)
        messages = [(ch.topic, json.loads(m.data)) for _, ch, m in reader.iter_messages()]
        (meta,) = [m for m in reader.iter_metadata() if m.name == "val3check"]
    return messages, meta.metadata


def _note(page: dict, what: str) -> list[str]:
    return [x for x in page["limitations"] if what in x]


def test_the_arm_timeline_holds_its_first_spans_and_says_so(monkeypatch):
    result, report = pickplace(20.0)
    whole = model_from_run(report)["arm_timeline"]
    assert not _note(model_from_run(report), "moving and idle spans")  # a short run: all of them
    keep = len(whole) // 2
    monkeypatch.setattr(thinning, "ARM_SPANS", keep)
    page = model_from_run(report)
    (note,) = _note(page, "moving and idle spans")
    assert note == (f"A long run: the arm timeline holds the first {keep} of {len(whole)} moving and idle spans "
                    f"(up to {whole[keep]['start']:g} s).")
    assert page["arm_timeline"] == whole[:keep]


def test_the_io_changes_are_the_first_ones_and_say_so(tmp_path, monkeypatch):
    result, report = pickplace(20.0)
    total = len(result.io_log)
    assert total >= 2 and not _note(model_from_run(report), "I/O changes")
    whole = model_from_run(report)["io"]
    keep = total // 2
    monkeypatch.setattr(thinning, "IO_EVENTS", keep)
    page = model_from_run(report)
    until = result.io_log[keep].time_us / 1e6
    (note,) = _note(page, "I/O changes")
    assert f"the I/O log holds the first {keep} of {total} I/O changes (up to {until:g} s)" in note
    assert page["io"] == whole[:keep]
    messages, meta = _trace(report, tmp_path / "t.mcap")
    assert len([m for topic, m in messages if topic == "/io"]) == keep
    assert f"the first {keep} of {total} I/O changes" in meta["io_thinned"]


def test_the_parts_are_drawn_for_their_first_spans_and_say_so(tmp_path, monkeypatch):
    result, report = pickplace(20.0, str(CELL))
    spans = result.motion.cell_timeline.parts
    total = len(spans)
    assert total >= 2 and not _note(model_from_run(report), "part spans")

    def drawn(page):
        return [s for p in page["scene"]["parts"] for s in p["spans"]]

    def sent(messages):
        return [e for topic, m in messages if topic == "/scene" for e in m["entities"] if e["id"].startswith("part/")]

    whole = drawn(model_from_run(report))
    whole_sent = sent(_trace(report, tmp_path / "whole.mcap")[0])
    assert len(whole) == len(whole_sent) == total
    keep = total // 2
    monkeypatch.setattr(thinning, "PART_SPANS", keep)
    page = model_from_run(report)
    (note,) = _note(page, "part spans")
    assert f"the parts drawn are the first {keep} of {total} part spans (up to {spans[keep].start:g} s)" in note
    assert sorted(drawn(page), key=lambda s: s["start"]) == sorted(whole, key=lambda s: s["start"])[:keep]
    messages, meta = _trace(report, tmp_path / "t.mcap")
    assert sent(messages) == whole_sent[:keep]
    assert f"the first {keep} of {total} part spans" in meta["parts_thinned"]
