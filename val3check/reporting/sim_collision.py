"""The collision section of the sim reports (docs/sim-report.md, docs/cell.md): `text(run)` for
sim_text.py, `section(run)` for sim_json.py. `run` is a SimReport; its result's `collision` is a
simulation.collision_run.CollisionRun or None."""

from __future__ import annotations

import bisect
import math
from typing import Any

from .thinning import MOTION_ROWS

CODES = {f"R0{n}" for n in range(30, 40)}
MAX_LINES = 30  # instructions listed in the text summary
# per-sample clearances of the JSON rows, in all (about 24 MB of JSON; the 1-hour cell's 5,000 rows
# hold 581,372): beyond, the rows keep their min_clearance without the samples (docs/sim-report.md)
CLEARANCE_SAMPLES = 1_000_000


def _where(run: Any, path: str, line: int) -> str:
    shown = run.display((path, line, 0, ""))
    return f"{shown[0]}:{line}" if shown else f"line {line}"


def _cell_line(run: Any, c: Any) -> str:
    if c.cell_path is None and c.cell_found == "disabled":
        return "collision: no cell (--cell none): the arm is checked against itself only"
    if c.cell_path is None:
        return ("collision: no cell file (--cell FILE, or val3check-cell.toml beside the application): "
                "the arm is checked against itself only")
    shown = run.display((c.cell_path, 0, 0, ""))[0]
    how = " (found beside the application)" if c.cell_found == "found" else ""
    if c.cell is None:
        return f"collision: the cell file {shown}{how} cannot be used (R030): the arm is checked against itself only"
    cell = c.cell
    parts = len({p.name for p in cell.parts})
    return (f"collision: cell {shown}{how}: {_n(len(cell.obstacles), 'obstacle')}, "
            f"{_n(len(cell.tools), 'tool solid')}, {_n(parts, 'part')}; margin {c.margin_mm:g} mm")


def _n(n: int, what: str) -> str:
    return f"{n} {what}{'s' if n != 1 else ''}"


def _by_instruction(run: Any) -> list[tuple[tuple, list[int]]]:
    """Motions grouped by the instruction that commanded them, in order of first start."""
    c = run.result.collision
    recs = run.result.motion.motions
    groups: dict[tuple, list[int]] = {}
    for i in sorted(c.by_motion, key=lambda i: c.by_motion[i].start):
        s = recs[i].source
        groups.setdefault((s.path, s.line, s.col, recs[i].kind), []).append(i)
    return list(groups.items())


def text(run: Any) -> list[str]:
    """Lines of the text summary: the cell, the closest approach per motion instruction, the
    contacts (their diagnostics are listed with the others)."""
    c = run.result.collision
    if c is None:
        return []
    out = [_cell_line(run, c)]
    groups = _by_instruction(run)
    with_cell = c.cell is not None and (c.cell.obstacles or c.cell.parts)
    if with_cell and groups:
        out.append("  closest approach to the cell per motion instruction:")
        for (path, line, _, kind), idx in groups[:MAX_LINES]:
            best = None
            for i in idx:
                m = c.by_motion[i].min_clearance
                if m is not None and (best is None or m.mm < best.mm):
                    best = m
            n = f", {len(idx)} motions" if len(idx) > 1 else ""
            if best is None:
                out.append(f"    {_where(run, path, line)} {kind}: nothing of the cell in reach{n}")
            elif best.mm <= 0.0:
                out.append(f"    {_where(run, path, line)} {kind}: contact, {best.body_a} with {best.body_b} "
                           f"({-best.mm:.1f} mm deep at {best.time:.3f} s){n}")
            else:
                out.append(f"    {_where(run, path, line)} {kind}: {best.mm:.1f} mm, {best.body_a} to {best.body_b} "
                           f"at {best.time:.3f} s{n}")
        if len(groups) > MAX_LINES:
            out.append(f"    ... {len(groups) - MAX_LINES} more (--report json lists every motion)")
    contacts = [x for x in c.contacts if x[1].kind != "self"]
    selfs = [x for x in c.contacts if x[1].kind == "self"]
    starts = sum(1 for r in c.by_motion.values() if r.starts_in_collision is not None)
    near = sum(1 for r in c.by_motion.values() if r.too_close)
    if not (contacts or selfs or starts or near or c.drops):
        out.append(f"  no contact over {len(c.by_motion)} motion{'s' if len(c.by_motion) != 1 else ''}")
    else:
        out.append(f"  {len(contacts)} contact(s) with the cell, {len(selfs)} self-collision(s), {starts} motion(s) "
                   f"starting in collision, {near} near miss(es), {len(c.drops)} part(s) left in collision "
                   "(diagnostics R031-R035)")
    out.append("")
    return out


class Samples:
    """Per-sample values written on one line by sim_json: `a`, a float array rounded as `_num`
    rounds, NaN where `_num` gives null; made when read, a group of entries at a time (_Rounded)."""

    __slots__ = ("group", "index", "key")

    def __init__(self, group: "_Rounded", index: int, key: str) -> None:
        self.group, self.index, self.key = group, index, key

    @property
    def a(self) -> Any:
        return self.group.part(self.index, self.key)


GROUP_SAMPLES = 65_536  # per-sample clearances rounded at once (numpy): a group of entries, not the run's


class _Rounded:
    """The rounded `times` and `mm` of the reports, a group of consecutive reports (up to
    GROUP_SAMPLES samples) rounded at once when one of them is read, only the last group held:
    the report is written in order, so each group is rounded once."""

    def __init__(self, reports: list) -> None:
        self.reports = reports
        self.first = [0]  # each group's first report
        total = 0
        for k, r in enumerate(reports):
            n = len(r.times)
            if k > self.first[-1] and total + n > GROUP_SAMPLES:
                self.first.append(k)
                total = 0
            total += n
        self.first.append(len(reports))
        self.held: tuple[int, dict] | None = None

    def part(self, index: int, key: str) -> Any:
        g = bisect.bisect_right(self.first, index) - 1
        if self.held is None or self.held[0] != g:
            self.held = (g, self._round(g))
        return self.held[1][index, key]

    def _round(self, g: int) -> dict:
        import numpy as np

        from .html.series import rounded

        members = range(self.first[g], self.first[g + 1])
        reports = [self.reports[k] for k in members]
        cuts = np.cumsum([len(r.times) for r in reports])[:-1]
        out = {}
        for key, name, digits in (("times", "times", 6), ("mm", "clearance", 3)):
            a = np.concatenate([np.asarray(getattr(r, name), dtype=float) for r in reports])
            finite = np.isfinite(a)
            values = rounded(np.where(finite, a, 0.0), digits)
            values[~finite] = np.nan
            for k, part in zip(members, np.split(values, cuts)):
                out[k, key] = part
        return out


def _samples(entries: list[dict], reports: list) -> None:
    """Each entry's per-sample `clearance` (its report's `times` and `clearance`), rounded when
    written, a group of entries at once (numpy: Python's rounding, html/series.py)."""
    if not entries:
        return
    rounded = _Rounded(reports)
    for k, e in enumerate(entries):
        e["clearance"]["times"] = Samples(rounded, k, "times")
        e["clearance"]["mm"] = Samples(rounded, k, "mm")


def _num(x: float | None, digits: int = 3) -> float | None:
    return None if x is None or not math.isfinite(x) else round(float(x), digits) + 0.0


def _point(p) -> list[float]:
    return [_num(v) for v in p]


def _contact(c) -> dict | None:
    if c is None:
        return None
    return {"time": _num(c.time, 6), "body_a": c.body_a, "body_b": c.body_b, "point": _point(c.point),
            "depth_mm": _num(c.depth_mm), "kind": c.kind}


def section(run: Any) -> dict | None:
    """The JSON `collision` section (docs/sim-report.md)."""
    c = run.result.collision
    if c is None:
        return None
    cell = None
    if c.cell_path is not None:
        shown = run.display((c.cell_path, 0, 0, ""))[0]
        cl = c.cell
        cell = {"path": shown, "found": c.cell_found, "usable": cl is not None,
                "obstacles": [o.name for o in cl.obstacles] if cl else [],
                "tools": [t.name for t in cl.tools] if cl else [],
                "parts": sorted({p.name for p in cl.parts}) if cl else [],
                "margin_mm": _num(cl.margin_mm) if cl else None, "touch_mm": _num(cl.touch_mm) if cl else None}
    with_cell = c.cell is not None and bool(c.cell.obstacles or c.cell.parts)
    recs = run.result.motion.motions
    motions = []
    sampled: list[tuple[dict, Any]] = []
    found = omitted = samples = bare = 0
    for i in sorted(c.by_motion):
        r = c.by_motion[i]
        # a long run (thinning.py): the first rows, and later the motions with a finding (as many)
        finding = bool(r.contacts or r.too_close or r.starts_in_collision is not None)
        if i >= MOTION_ROWS and not (finding and found < MOTION_ROWS):
            omitted += 1
            continue
        found += i >= MOTION_ROWS
        s = recs[i].source
        where = run.display((s.path, s.line, s.col, ""))
        m = r.min_clearance
        entry = {
            "motion": i, "path": where[0] if where else None, "line": s.line or None, "column": s.col or None,
            "task": s.task or None, "start": _num(r.start, 6), "end": _num(r.end, 6),
            "min_clearance": None if m is None else {
                "mm": _num(m.mm), "time": _num(m.time, 6), "body_a": m.body_a, "body_b": m.body_b,
                "point_a": _point(m.point_a), "point_b": _point(m.point_b)},
            "too_close": bool(r.too_close),
            "starts_in_collision": _contact(r.starts_in_collision),
            "contacts": [_contact(x) for x in r.contacts],
            "checks": r.checks,
        }
        if with_cell and not bare and samples + len(r.times) <= CLEARANCE_SAMPLES:
            samples += len(r.times)
            entry["clearance"] = {}  # from the arrays, as the report is written (_samples)
            sampled.append((entry, r))
        elif with_cell:  # a long run: this row and the next ones without their samples
            bare += 1
        motions.append(entry)
    _samples([e for e, _ in sampled], [r for _, r in sampled])
    mins = [r.min_clearance.mm for r in c.by_motion.values() if r.min_clearance is not None]
    out = {
        "cell": cell,
        "summary": {
            "motions": len(c.by_motion),
            "contacts": sum(1 for _, x in c.contacts if x.kind != "self"),
            "self_collisions": sum(1 for _, x in c.contacts if x.kind == "self"),
            "starts_in_collision": sum(1 for r in c.by_motion.values() if r.starts_in_collision is not None),
            "near_misses": sum(1 for r in c.by_motion.values() if r.too_close),
            "parts_left_in_collision": len(c.drops),
            "min_clearance_mm": _num(min(mins)) if mins else None,
            "checks": c.checks,
        },
        "motions": motions,
        "drops": [{"time": _num(d.time, 6), "part": d.part, "obstacle": d.obstacle, "point": _point(d.point),
                   "depth_mm": _num(d.depth_mm)} for d in c.drops],
    }
    if bare:
        out["clearance_omitted"] = {"count": bare, "kept": len(sampled), "samples": samples,
                                    "why": f"a long run: the per-sample clearances of the first {len(sampled)} rows "
                                           f"({samples} samples, at most {CLEARANCE_SAMPLES}); every row keeps its "
                                           "min_clearance"}
    if omitted:
        out["motions_omitted"] = {"count": omitted, "why": f"a long run: the rows of the first {MOTION_ROWS} motions, "
                                                          "then of the motions with a contact or a near miss"}
    return out
