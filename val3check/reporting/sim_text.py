"""`val3check sim` text summary (docs/sim.md): how the run ended, the cycle time and the motion
diagnostics first, then the other runtime diagnostics, the tasks, the user page transcript and
the first I/O events.

Times are simulated seconds, all written with three decimals (the JSON report has them to the
microsecond): one precision everywhere, so that no time reads earlier than another that came
before it, and the run's duration is never shorter than a time it reports.
"""

from __future__ import annotations

import statistics
from typing import Any

from . import sim_collision
from ._common import printable

MAX_TRANSCRIPT_LINES = 40
MAX_IO_LINES = 20
MOTION_CODES = {f"R0{n}" for n in range(10, 30)}


def fmt_time(us: int | None) -> str:
    """`1.504 s` (the module docstring)."""
    if us is None:
        return "-"
    return f"{seconds(us / 1_000_000)} s"


def seconds(s: float) -> str:
    return f"{s:.3f}"


def _where(run: Any, path: str, line: int, col: int) -> str:
    shown = run.display((path, line, col, ""))
    return f"{shown[0]}:{line}" if shown else f"line {line}"


def render(run: Any) -> str:
    r = run.result
    out = [f"val3check sim: {r.application} ({run.app_path})"]
    if r.robot:
        joints = ", ".join(f"{v:g}" for v in r.robot["initial_joints"])
        out.append(f"arm model: {r.robot['name']}, starting at {{{joints}}}")
    else:
        out.append("arm model: none (motion instructions need one: --robot NAME)")
    last = max([t.ended for t in r.tasks if t.ended is not None] + [r.sim_time_us])
    stop = f" (stop() ran until {fmt_time(last)})" if last > r.sim_time_us else ""
    out += [f"{r.end_message}, after {fmt_time(r.sim_time_us)} of simulated time{stop}; {r.lines} VAL 3 lines "
            f"executed", ""]
    m = r.motion
    if m is not None:
        out += _motion_summary(run, m)
    out += sim_collision.text(run)
    motion_diags = [d for d in run.diagnostics if d.code in MOTION_CODES]
    other = [d for d in run.diagnostics if d.code not in MOTION_CODES]
    if motion_diags:
        out.append("motion diagnostics:")
        out += [_diag(d) for d in motion_diags]
        out.append("")
    if other:
        out.append("runtime diagnostics:" if not motion_diags else "other runtime diagnostics:")
        out += [_diag(d) for d in other]
        out.append("")
    out.append("tasks:")
    width = max([len(t.name) for t in r.tasks] + [4])
    for t in r.tasks:
        sched = f"period {t.period:g} s" if t.period else f"priority {t.priority}"
        state = t.state_at_end_of_run
        if t.error:
            state = f"error {t.error}"
        where = run.display(t.position)
        at = f" at {where[0]}:{where[1]}:{where[2]}" if where and where[1] else ""
        blocked = f" in {t.blocked_on}" if t.blocked_on else ""
        ended = f", {t.end} at {fmt_time(t.ended)}" if t.ended is not None else ""
        lib = f" [{t.library}]" if t.library else ""
        out.append(f"  {t.name:<{width}}  {t.program}(){lib}, {sched}: {state}{blocked}{at}{ended}")
    if r.destroyed:
        out.append(f"destroyed at the end, in this order: {', '.join(r.destroyed)}")
    out.append("")
    if r.transcript:
        shown = r.transcript[-MAX_TRANSCRIPT_LINES:]
        skipped = len(r.transcript) - len(shown)
        out.append("user page transcript" + (f" (last {len(shown)} of {len(r.transcript)} entries)" if skipped else "") + ":")
        for e in shown:
            scr = f" <{e.screen}>" if e.screen else ""
            head = f"  {seconds(e.time_us / 1e6):>9}  {e.task:<{width}}  {e.kind}{scr}"
            out.append(f"{head} {e.text!r}" if e.text else head)
        out.append("")
    if r.io_log:
        shown = r.io_log[:MAX_IO_LINES]
        more = f" (first {len(shown)} of {len(r.io_log)}; --report json lists them all)" if len(r.io_log) > len(shown) else ""
        out.append(f"I/O log{more}:")
        for e in shown:
            names = run.link_names.get((e.kind, e.link), [])
            label = f"{e.link} ({', '.join(names)})" if names else e.link
            out.append(f"  {seconds(e.time_us / 1e6):>9}  {e.kind} {label} = {_value(e.value)}  [{e.source}]")
        out.append("")
    return "\n".join(out).rstrip("\n") + "\n"


def _value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return f"{v:g}"
    return repr(v)


def _diag(d) -> str:
    loc = f"{d.path}:{d.line}:{d.col}" if d.line else d.path
    who = f" [task {d.task}" + (f", {d.program}()" if d.program else "") + "]" if d.task else ""
    return printable(f"  {loc}: {d.code} {d.severity.label}: {d.message} (at {fmt_time(d.time_us)}){who}")


def _range(m, task: str) -> str:
    """" (2.41–3.52 s if the assumed accelerations are off by 2×)" when the model assumes them."""
    spread = m.acceleration_range
    r = spread.cycle_time(task) if spread is not None else None
    if r is None:
        return ""
    return f" ({seconds(r[0])}–{seconds(r[1])} s if the assumed accelerations are off by {spread.off_by:g}×)"


def _motion_summary(run: Any, m) -> list[str]:
    out = []
    for task in sorted(m.cycles):
        st = m.cycles[task]
        if st.marker is None:
            continue
        loop = f"the {st.kind} loop at {_where(run, *st.marker)}"
        t = st.times
        if not t:
            out.append(f"cycle of task {task}: {loop}, no complete cycle ({st.why})")
            continue
        out.append(f"cycle time of task {task} ({loop}): {st.count} cycle"
                   f"{'s' if st.count != 1 else ''}, min {seconds(min(t))} s, median {seconds(statistics.median(t))} s"
                   f"{_range(m, task)}, max {seconds(max(t))} s")
    cmds = [x for x in m.motions if x.id is not None]
    done = sum(1 for x in cmds if x.state == "done")
    failed = sum(1 for x in cmds if x.state == "failed")
    states = f"{done} done" + (f", {failed} not executable" if failed else "")
    out.append(f"arm: {len(cmds)} motion command{'s' if len(cmds) != 1 else ''} ({states}), moving "
               f"{seconds(m.busy_s)} s, idle {seconds(m.idle_s)} s")
    out.append("")
    return out
