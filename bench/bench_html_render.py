"""The page of a real run built in process: best of N of `render_run` on one run's report (issue 29).

    python bench/bench_html_render.py --duration 600 [--repeat 5] [--profile] [--out page.html] [--json]

Runs `val3check sim fixtures/valid/PickPlace --robot tx2-60 --scenario fixtures/scenarios/pickplace.toml
--report html` in this process, keeps the run's report, then builds its page `--repeat` times and
prints the best CPU time (and wall time) (the page is the same each time: it is checked). --profile: cProfile of one build.
--json: the JSON report (`sim_json.render`) instead of the page.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))


def report_of(duration: float):
    """The SimReport of the bundled pick-and-place for `duration` simulated seconds (CLI path)."""
    import tempfile

    import val3check.reporting.sim_render as sim_render
    from val3check.cli import main

    kept = []
    original = sim_render.sim_pieces

    def keep(fmt, report, **kw):
        kept.append(report)
        return [""]

    sim_render.sim_pieces = keep
    try:
        with tempfile.TemporaryDirectory() as d:
            main(["sim", str(ROOT / "fixtures/valid/PickPlace"), "--robot", "tx2-60", "--scenario",
                  str(ROOT / "fixtures/scenarios/pickplace.toml"), "--duration", str(duration), "--max-wall", "3600",
                  "--max-memory", "4096", "--report", "html", "-o", str(Path(d) / "r.html")])
    finally:
        sim_render.sim_pieces = original
    return kept[0]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=600.0)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--profile", action="store_true")
    ap.add_argument("--out", type=Path)
    ap.add_argument("--json", action="store_true", help="the JSON report instead of the page")
    a = ap.parse_args()
    from val3check.reporting.html.from_run import render_run
    from val3check.reporting.sim_json import render as render_json

    build = render_json if a.json else render_run

    report = report_of(a.duration)
    page, best, wall = None, float("inf"), float("inf")
    for _ in range(a.repeat):
        t0, w0 = time.process_time(), time.perf_counter()
        text = build(report)
        best, wall = min(best, time.process_time() - t0), min(wall, time.perf_counter() - w0)
        assert page is None or text == page, "the page changed from one build to the next"
        page = text
    print(f"{a.duration:g} s run: page {len(page.encode()) / 1e6:.2f} MB, {build.__module__}.{build.__name__} best of {a.repeat}: "
          f"{best:.3f} s CPU ({wall:.3f} s wall, load {os.getloadavg()[0]:.1f})")
    if a.out:
        a.out.write_text(page, encoding="utf-8")
    if a.profile:
        import cProfile
        import pstats

        pr = cProfile.Profile()
        pr.runcall(build, report)
        pstats.Stats(pr).sort_stats("cumulative").print_stats(35)


if __name__ == "__main__":
    main()
