"""`val3check reach` output: the points and joints the arm cannot reach, or reaches only near a
singularity or a joint limit (val3check/motion/reach.py), as text or JSON (version 1)."""

from __future__ import annotations

import json
import os


def render_text(report) -> str:
    probs = report.problems()
    out = [f"val3check reach: {report.app} with {report.robot}; tools: {', '.join(report.tools)}",
           f"checked {report.points} point(s) x {len(report.tools)} tool(s) and {report.joints} joint position(s)"]
    if not probs:
        out.append("every point and joint is reachable, away from singularities and joint limits")
        return "\n".join(out) + "\n"
    out.append("")
    for e in probs:
        path = os.path.relpath(e.path) if e.path else "?"
        out.append(f"{path}:{e.line}:{e.col}: [{e.severity}] {e.status}: {e.message}")
    counts: dict[str, int] = {}
    for e in probs:
        counts[e.status] = counts.get(e.status, 0) + 1
    out.append("")
    out.append(", ".join(f"{n} {k}" for k, n in counts.items()))
    return "\n".join(out) + "\n"


def render_json(report) -> str:
    return json.dumps(report.as_dict(), indent=2, ensure_ascii=False, sort_keys=False) + "\n"
