"""`val3check sim` text summary: how the run ended, the tasks, runtime diagnostics, the user
page transcript (docs/sim.md)."""

from __future__ import annotations

from typing import Any

MAX_TRANSCRIPT_LINES = 40


def _s(us: int | None) -> str:
    return "-" if us is None else f"{us / 1_000_000:.3f} s"


def render(run: Any) -> str:
    r = run.result
    out = [f"val3check sim: {r.application} ({run.app_path})"]
    if r.robot:
        joints = ", ".join(f"{v:g}" for v in r.robot["initial_joints"])
        out.append(f"arm model: {r.robot['name']}, at {{{joints}}} (motion is not simulated)")
    out += [f"{r.end_message}, after {_s(r.sim_time_us)} of simulated time; {r.lines} VAL 3 lines executed", ""]
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
        ended = f", {t.end} at {_s(t.ended)}" if t.ended is not None else ""
        lib = f" [{t.library}]" if t.library else ""
        out.append(f"  {t.name:<{width}}  {t.program}(){lib}, {sched}: {state}{blocked}{at}{ended}")
    if r.destroyed:
        out.append(f"destroyed at the end, in this order: {', '.join(r.destroyed)}")
    out.append("")
    if run.diagnostics:
        out.append("runtime diagnostics:")
        for d in run.diagnostics:
            loc = f"{d.path}:{d.line}:{d.col}" if d.line else d.path
            who = f" [task {d.task}" + (f", {d.program}()" if d.program else "") + "]" if d.task else ""
            out.append(f"  {loc}: {d.code} {d.severity.label}: {d.message} at {round(d.time_us / 1e6, 6):.3f} s{who}")
        out.append("")
    if r.transcript:
        shown = r.transcript[-MAX_TRANSCRIPT_LINES:]
        skipped = len(r.transcript) - len(shown)
        out.append("user page transcript" + (f" (last {len(shown)} of {len(r.transcript)} entries)" if skipped else "") + ":")
        for e in shown:
            scr = f" <{e.screen}>" if e.screen else ""
            head = f"  {e.time_us / 1_000_000:9.3f}  {e.task:<{width}}  {e.kind}{scr}"
            out.append(f"{head} {e.text!r}" if e.text else head)
        out.append("")
    if r.io_log:
        out.append(f"I/O: {len(r.io_log)} events (--report json lists them)")
    return "\n".join(out).rstrip("\n") + "\n"
