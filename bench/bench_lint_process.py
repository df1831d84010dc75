"""`val3check lint` against pyflakes, whole process, side by side in one run (issue 29).

Each round starts `val3check lint` on a generated 20,000-line application and `python -m pyflakes`
on 60 modules of the standard library (email, asyncio, json, logging), one after the other, and
measures the CPU time of each child process (user + system, from the kernel: start-up, imports,
reading and checking, exit). Rounds alternate the two so that a busy neighbour slows both alike.
Lines are counted as `wc -l` counts them (every line of the files checked).

Both run with compiled bytecode, as an installed tool does: the children write their `.pyc` under
a temporary PYTHONPYCACHEPREFIX (PYTHONDONTWRITEBYTECODE is dropped for them) and a first round,
not counted, fills it. Without it, a checkout whose environment sets PYTHONDONTWRITEBYTECODE
compiles val3check's modules from source at every start (about 0.1 s) while pyflakes, installed
by pip, does not.

Run: python bench/bench_lint_process.py [--rounds 9]   (writes only into a temporary folder)
Goal: lint's lines per CPU second >= pyflakes', whole process (issue 29).
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import resource
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from generate import generate  # noqa: E402


def child_cpu(cmd: list[str], env: dict[str, str]) -> float:
    """CPU seconds (user + system) of one child process, whole process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False, env=env)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def stdlib_modules(count: int = 60) -> list[Path]:
    """The first `count` modules (sorted) of four pure-Python packages of the standard library."""
    import email

    stdlib = Path(email.__file__).resolve().parent.parent
    files = [p for pkg in ("email", "asyncio", "json", "logging") for p in sorted((stdlib / pkg).glob("*.py"))]
    return files[:count]


def lines_of(files: list[Path]) -> int:
    return sum(p.read_bytes().count(b"\n") for p in files)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=9)
    args = parser.parse_args()
    if importlib.util.find_spec("pyflakes") is None:
        print("pyflakes is not installed (pip install pyflakes): no comparison")
        return 2
    with tempfile.TemporaryDirectory() as tmp:
        app = Path(tmp) / "BigApp"
        generate(app)
        app_lines = lines_of([p for p in app.rglob("*") if p.is_file()])
        py = stdlib_modules()
        py_lines = lines_of(py)
        lint_cmd = [sys.executable, "-m", "val3check", "lint", str(app)]
        flakes_cmd = [sys.executable, "-m", "pyflakes", *map(str, py)]
        env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
        env["PYTHONPYCACHEPREFIX"] = str(Path(tmp) / "pycache")
        child_cpu(lint_cmd, env)  # warm-up: bytecode written, not counted
        child_cpu(flakes_cmd, env)
        lint, flakes = [], []
        for _ in range(args.rounds):
            lint.append(child_cpu(lint_cmd, env))
            flakes.append(child_cpu(flakes_cmd, env))
    load = ", ".join(f"{x:.1f}" for x in os.getloadavg())
    print(f"python {sys.version.split()[0]}, {args.rounds} rounds, CPU time of each whole process, "
          f"load average {load}")
    rows = (("val3check lint", app_lines, lint), ("pyflakes", py_lines, flakes))
    rates = {}
    for label, n, times in rows:
        best, med = min(times), statistics.median(times)
        rates[label] = (n / best, n / med)
        print(f"{label:15} {n:7,} lines  best {best:.3f} s  median {med:.3f} s  "
              f"-> {n / best:,.0f} lines/s (best), {n / med:,.0f} (median)")
    ratio_best = rates["val3check lint"][0] / rates["pyflakes"][0]
    ratio_med = rates["val3check lint"][1] / rates["pyflakes"][1]
    print(f"lint / pyflakes: {ratio_best:.2f} (best), {ratio_med:.2f} (median); goal >= 1.00: "
          f"{'met' if ratio_best >= 1 else 'NOT met'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
