"""The HTML report: size and build time of the page for a one-minute and a ten-minute run.

Goal (issue 15): a self-contained page under 5 MB for a one-minute run at 4 ms (15,001 samples
x 6 joints). The runs are the synthetic pick-and-place cell (val3check/reporting/html/synthetic.py);
the ten-minute one repeats its trajectory ten times (150,001 samples), which the page keeps as
min/max buckets (pack.py). With --browser, also the time Chromium takes to load and draw it.
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

from val3check.reporting.html import render, synthetic_model  # noqa: E402
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
    if "--browser" in sys.argv:
        import browser_client

        why = browser_client.skip_reason()
        if why:
            print(f"browser: skipped ({why})")
            return
        with tempfile.TemporaryDirectory() as d, browser_client.Chromium() as chromium:
            for name, text in (("one minute", page), ("ten minutes", long_page)):
                path = Path(d) / "report.html"
                path.write_text(text, encoding="utf-8")
                t5 = time.perf_counter()
                loaded = chromium.open(path)
                t6 = time.perf_counter()
                print(f"Chromium, {name}: loaded and drawn in {t6 - t5:.2f} s, console errors: {len(loaded.console_errors)}")
                loaded.page.close()


if __name__ == "__main__":
    main()
