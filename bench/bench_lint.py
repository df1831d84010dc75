"""Throughput of load + parse (and of the whole `lint` pipeline) on a generated application.

Goal (issue 2): at least 20,000 VAL 3 lines per second for load + parse on the 2-core CI machine.
Run: python bench/bench_lint.py   (writes only into a temporary folder)
"""

from __future__ import annotations

import statistics
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from generate import generate  # noqa: E402

from val3check.config import Settings  # noqa: E402
from val3check.lint import run  # noqa: E402
from val3check.loading import load  # noqa: E402
from val3check.parsing.parser import parse_program  # noqa: E402


def main() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp) / "BigApp"
        lines = generate(folder)
        load_parse, whole = [], []
        for _ in range(5):
            t0 = time.perf_counter()
            ws, diags = load([str(folder)])
            errors = []
            for app in ws.apps.values():
                for prog in app.programs.values():
                    errors.extend(parse_program(prog))
            load_parse.append(time.perf_counter() - t0)
            assert not errors and not diags, (errors[:3], diags[:3])
            t0 = time.perf_counter()
            outcome = run([str(folder)], Settings())
            whole.append(time.perf_counter() - t0)
            assert not outcome.result.diagnostics, outcome.result.diagnostics[:3]
        best, med = min(load_parse), statistics.median(load_parse)
        print(f"application: {lines} code lines in {len(ws.apps[ws.targets[0]].programs)} programs")
        print(f"load+parse: median {med*1000:.0f} ms, best {best*1000:.0f} ms -> {lines/med:,.0f} lines/s (median), {lines/best:,.0f} lines/s (best); goal >= 20,000")
        wmed = statistics.median(whole)
        print(f"whole lint pipeline (load, parse, checks, no report): median {wmed*1000:.0f} ms -> {lines/wmed:,.0f} lines/s")


if __name__ == "__main__":
    main()
