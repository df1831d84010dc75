"""The MCAP trace (`val3check sim --trace`): size and write time for one and ten simulated minutes
of the bundled pick-and-place cell (fixtures/valid/PickPlace, TX2-60, its scenario, its cell),
the number of messages per topic, and how many numbers of the poses are written with more
decimals than docs/trace.md says (positions and lengths 1e-10 m, quaternion components 1e-12).
The figures of docs/trace.md come from here. Run: python bench/bench_trace.py
"""

from __future__ import annotations

import json
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from val3check.collision import read_cell  # noqa: E402
from val3check.config import Settings  # noqa: E402
from val3check.lint import run  # noqa: E402
from val3check.reporting.mcap_trace import trace_messages, write_trace  # noqa: E402
from val3check.reporting.sim_report import build_report  # noqa: E402
from val3check.robot import load_robot  # noqa: E402
from val3check.rules.catalogue import catalogue  # noqa: E402
from val3check.simulation import SimOptions, simulate  # noqa: E402
from val3check.simulation.scenario import load_scenario  # noqa: E402


def _decimals(x: float) -> int:
    """Decimals of a number as JSON writes it (Python's shortest repr)."""
    r = repr(float(x))
    if "e" in r:
        mant, exp = r.split("e")
        return (len(mant.split(".")[1]) if "." in mant else 0) - int(exp)
    return len(r.split(".")[1]) if "." in r else 0


def beyond(message, limit: int = 10, counts=None) -> dict:
    """{"pose numbers": n, "beyond": k} of a message's poses: rotation/orientation components
    against 12 decimals, every other number of a pose, size or length against `limit`."""
    counts = counts if counts is not None else {"pose numbers": 0, "beyond": 0}
    if isinstance(message, dict):
        for k, v in message.items():
            if k in ("rotation", "orientation"):
                beyond(v, 12, counts)
            elif k not in ("color", "colors", "timestamp", "lifetime", "indices", "metadata"):
                beyond(v, limit, counts)
    elif isinstance(message, list):
        for v in message:
            beyond(v, limit, counts)
    elif isinstance(message, float) or (isinstance(message, int) and not isinstance(message, bool)):
        counts["pose numbers"] += 1
        counts["beyond"] += _decimals(message) > limit
    return counts


def main() -> None:
    for minutes in (1, 10):
        lr = run([str(ROOT / "fixtures/valid/PickPlace")], Settings())
        ws = lr.workspace
        app = ws.apps[ws.targets[0]]
        result = simulate(ws, app, SimOptions(duration=60.0 * minutes, max_wall=600.0, robot=load_robot("tx2-60")),
                          load_scenario(str(ROOT / "fixtures/scenarios/pickplace.toml")))
        report = build_report(result, Settings(), catalogue(), "bench")
        cell = read_cell(str(ROOT / "fixtures/valid/PickPlace/val3check-cell.toml"))  # beside it: what `sim` finds
        with tempfile.TemporaryDirectory() as d:
            path = Path(d) / "run.mcap"
            t0, c0 = time.perf_counter(), time.process_time()
            write_trace(report, str(path), cell=cell)
            t1, c1 = time.perf_counter(), time.process_time()
            size = path.stat().st_size
        messages = list(trace_messages(report, cell)[0])
        per: dict[str, int] = {}
        counts = {"pose numbers": 0, "beyond": 0}
        for topic, _, data in messages:
            per[topic] = per.get(topic, 0) + 1
            if topic in ("/tf", "/tcp", "/scene"):
                beyond(json.loads(data), counts=counts)
        raw = sum(len(m[2]) for m in messages)
        ticks = per.get("/joint_states", 0)
        print(f"PickPlace {minutes} min: {size / 1e6:.2f} MB (JSON {raw / 1e6:.1f} MB before zstd), written in "
              f"{t1 - t0:.2f} s ({c1 - c0:.2f} s of CPU); {ticks} ticks of the arm; {counts['beyond']} of {counts['pose numbers']} numbers "
              "of the poses written beyond 1e-10 m / 1e-12; " + ", ".join(f"{t} {n}" for t, n in per.items()))


if __name__ == "__main__":
    main()
