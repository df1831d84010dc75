"""The MCAP trace (`val3check sim --trace`): size and write time for one and ten simulated minutes
of the bundled pick-and-place cell (fixtures/valid/PickPlace, TX2-60, its scenario), and the
number of messages per topic. Run: python bench/bench_trace.py
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from val3check.config import Settings  # noqa: E402
from val3check.lint import run  # noqa: E402
from val3check.reporting.mcap_trace import trace_messages, write_trace  # noqa: E402
from val3check.reporting.sim_report import build_report  # noqa: E402
from val3check.robot import load_robot  # noqa: E402
from val3check.rules.catalogue import catalogue  # noqa: E402
from val3check.simulation import SimOptions, simulate  # noqa: E402
from val3check.simulation.scenario import load_scenario  # noqa: E402


def main() -> None:
    for minutes in (1, 10):
        lr = run([str(ROOT / "fixtures/valid/PickPlace")], Settings())
        ws = lr.workspace
        app = ws.apps[ws.targets[0]]
        result = simulate(ws, app, SimOptions(duration=60.0 * minutes, max_wall=600.0, robot=load_robot("tx2-60")),
                          load_scenario(str(ROOT / "fixtures/scenarios/pickplace.toml")))
        report = build_report(result, Settings(), catalogue(), "bench")
        with tempfile.TemporaryDirectory() as d:
            path = Path(d) / "run.mcap"
            t0 = time.perf_counter()
            write_trace(report, str(path))
            t1 = time.perf_counter()
            size = path.stat().st_size
        messages = list(trace_messages(report)[0])
        per: dict[str, int] = {}
        for topic, _, _ in messages:
            per[topic] = per.get(topic, 0) + 1
        raw = sum(len(m[2]) for m in messages)
        print(f"PickPlace {minutes} min: {size / 1e6:.2f} MB (JSON {raw / 1e6:.1f} MB before zstd), written in "
              f"{t1 - t0:.2f} s; " + ", ".join(f"{t} {n}" for t, n in per.items()))


if __name__ == "__main__":
    main()
