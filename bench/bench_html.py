"""The HTML report: size and build time of the page for a one-minute and a ten-minute run.

Goal (issue 15): a self-contained page under 5 MB for a one-minute run at 4 ms (15,001 samples
x 6 joints). First the synthetic pick-and-place cell (tests/synthetic_run.py; the
ten-minute one repeats its trajectory ten times, 150,001 samples, which the page keeps as min/max
buckets, pack.py), then real runs of fixtures/valid/PickPlace on a TX2-60 with its scenario for
one and ten simulated minutes, as `val3check sim --report html` builds them (from_run.py).
With --browser, also the time Chromium takes to load and draw the pages.
Run: python bench/bench_html.py [--browser]
"""

from __future__ import annotations

import copy
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))

from synthetic_run import synthetic_model  # noqa: E402
from val3check.reporting.html import render  # noqa: E402
from val3check.reporting.html.pack import page_data  # noqa: E402


def _longer(model: dict, reps: int) -> dict:
    long = copy.deepcopy(model)
    tr = long["trajectory"]
    n = len(tr["times"])
    tr["times"] = [round(k * 0.004, 6) for k in range(n * reps)]
    for key in ("positions", "velocities"):
        tr[key] = [col * reps for col in tr[key]]
    tr["tcp_speed"] = tr["tcp_speed"] * reps
    long["verdict"]["simulated_duration"] = tr["times"][-1]
    return long


def main() -> None:
    t0 = time.perf_counter()
    model = synthetic_model(duration=60.0)
    t1 = time.perf_counter()
    page = render(model)
    t2 = time.perf_counter()
    size = len(page.encode("utf-8"))
    n = len(model["trajectory"]["times"])
    script = sum(len((ROOT / "val3check/reporting/html/assets" / f).read_bytes())
                 for f in ("core.js", "plot.js", "lanes.js", "view3d.js", "main.js"))
    import json
    data = len(json.dumps(page_data(model), separators=(",", ":")))
    print(f"one minute at 4 ms: {n} samples x {len(model['trajectory']['joints'])} joints, "
          f"{len(model['motions'])} motions, {len(model['io'])} I/O events")
    print(f"  page {size / 1e6:.2f} MB (goal < 5 MB): data {data / 1e6:.2f} MB, script {script / 1e3:.0f} kB; "
          f"model {t1 - t0:.2f} s, render {t2 - t1:.2f} s")
    long = _longer(model, 10)
    t3 = time.perf_counter()
    long_page = render(long)
    t4 = time.perf_counter()
    print(f"ten minutes ({len(long['trajectory']['times'])} samples, decimated to min/max buckets): "
          f"page {len(long_page.encode('utf-8')) / 1e6:.2f} MB, render {t4 - t3:.2f} s")
    pages = [("one minute", page), ("ten minutes", long_page)]
    pages += real_runs()
    if "--browser" in sys.argv:
        import browser_client

        why = browser_client.skip_reason()
        if why:
            print(f"browser: skipped ({why})")
            return
        with tempfile.TemporaryDirectory() as d, browser_client.Chromium() as chromium:
            for name, text in pages:
                path = Path(d) / "report.html"
                path.write_text(text, encoding="utf-8")
                t5 = time.perf_counter()
                loaded = chromium.open(path)
                t6 = time.perf_counter()
                print(f"Chromium, {name}: loaded and drawn in {t6 - t5:.2f} s, console errors: {len(loaded.console_errors)}")
                loaded.page.close()


def real_runs() -> list[tuple[str, str]]:
    """The report of real runs of the bundled pick-and-place cell, one and ten simulated minutes."""
    from val3check.config import Settings
    from val3check.lint import run
    from val3check.reporting.html.from_run import model_from_run
    from val3check.reporting.sim_report import build_report
    from val3check.robot import load_robot
    from val3check.rules.catalogue import catalogue
    from val3check.simulation import SimOptions, simulate
    from val3check.simulation.scenario import load_scenario

    out = []
    for minutes in (1, 10):
        lr = run([str(ROOT / "fixtures/valid/PickPlace")], Settings())
        ws = lr.workspace
        app = ws.apps[ws.targets[0]]
        t0 = time.perf_counter()
        result = simulate(ws, app, SimOptions(duration=60.0 * minutes, max_wall=600.0, robot=load_robot("tx2-60")),
                          load_scenario(str(ROOT / "fixtures/scenarios/pickplace.toml")))
        t1 = time.perf_counter()
        report = build_report(result, Settings(), catalogue(), "bench")
        model = model_from_run(report)
        t2 = time.perf_counter()
        text = render(model)
        t3 = time.perf_counter()
        print(f"PickPlace, real run of {minutes} min: {len(model['trajectory']['times'])} samples, "
              f"{len(model['motions'])} motions, {len(model['io'])} I/O events, "
              f"{sum(len(t['segments']) for t in model['tasks'])} task segments: page {len(text.encode()) / 1e6:.2f} MB; "
              f"simulation {t1 - t0:.2f} s, model {t2 - t1:.2f} s, render {t3 - t2:.2f} s")
        out.append((f"PickPlace {minutes} min", text))
    return out


if __name__ == "__main__":
    main()
