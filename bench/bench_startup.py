"""Cold start of `val3check lint` on one small application, and of `val3check sim` on the bundled
pick-and-place for one simulated second, whole processes.

Goal for lint: under 150 ms (issue 11; issue 2 asked for 400 ms). Wall time is what a pre-commit
hook waits; the CPU time of the process (user + system) is shown too: on a shared machine it moves
less with the neighbours. Also prints the import-time budget (python -X importtime), the largest
imports first, and checks that no robotics package is imported on the lint path. For sim (issue
29): the fixed cost of a run (imports, lint, the arm, the collision set-up, the page) and which
heavy packages it imports (mcap only with --trace, trimesh only for meshes).

Both run with compiled bytecode, as an installed tool does: PYTHONDONTWRITEBYTECODE is dropped for
the children, which write their `.pyc` under a temporary PYTHONPYCACHEPREFIX, filled by a first
run that is not counted.
With --phases: the CPU of each phase of one sim process (the imports, lint, the arm, the run, the
record, the collision checks, the page), for 1 and 60 simulated seconds: what does not grow with
the run's length is its fixed cost (issue 29, docs/performance.md).
Run: python bench/bench_startup.py [--runs 15] [--phases]
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
APP = ROOT / "fixtures" / "valid" / "Cell"
FORBIDDEN = ("pinocchio", "trimesh", "fcl", "mcap", "numpy", "scipy")
HEAVY = FORBIDDEN + ("toppra", "dask", "distributed")
PICK = ["fixtures/valid/PickPlace", "--robot", "tx2-60", "--scenario", "fixtures/scenarios/pickplace.toml",
        "--duration", "1", "--max-wall", "900"]


def timed(cmd: list[str], env: dict[str, str], runs: int) -> tuple[list[float], list[float], int]:
    """Wall and CPU seconds (user + system, from the kernel) of `runs` runs of `cmd`, and its exit code."""
    times, cpu = [], []
    rc = 0
    for _ in range(runs):
        r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        rc = subprocess.run(cmd, check=False, capture_output=True, env=env, cwd=ROOT).returncode
        times.append(time.perf_counter() - t0)
        r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu.append(r1.ru_utime - r0.ru_utime + r1.ru_stime - r0.ru_stime)
    return times, cpu, rc


def imports(cmd: list[str], env: dict[str, str]) -> list[tuple[int, str]]:
    """(cumulative µs, name with its nesting indentation) of every module `cmd` imports."""
    r = subprocess.run([sys.executable, "-X", "importtime", *cmd[1:]], check=False, capture_output=True, text=True,
                       env=env, cwd=ROOT)
    rows = []
    for line in r.stderr.splitlines():
        if line.startswith("import time:") and "|" in line and "self" not in line:
            _, cumulative, name = line[len("import time:"):].split("|")
            rows.append((int(cumulative.strip()), name.rstrip()[1:]))  # keep the indentation: nesting
    return rows


def show_imports(rows: list[tuple[int, str]], n: int = 12) -> None:
    top = [row for row in rows if not row[1].startswith(" ")]
    total = sum(c for c, _ in top)
    print(f"import time, top-level modules: {total/1000:.0f} ms in all ({len(rows)} modules); largest:")
    for cumulative, name in sorted(top, reverse=True)[:n]:
        print(f"  {cumulative/1000:7.1f} ms  {name}")


# A sim process timing its phases with process_time (CPU), printed as JSON on the last line of stderr.
PHASES = r"""
import json, sys, time
t0 = time.process_time()
from val3check.cli import main
from val3check.interpretation.machine import Machine
from val3check.reporting import sim_render
from val3check.simulation import case, collision_run, run
spent = {"imports": time.process_time() - t0}
def timed(name, f):
    def w(*a, **k):
        t = time.process_time()
        try:
            return f(*a, **k)
        finally:
            spent[name] = spent.get(name, 0.0) + time.process_time() - t
    return w
for mod, attr in ((case, "lint_case"), (case, "choose_sim_robot"), (run, "build_machine"), (run, "collect"),
                  (collision_run, "check_run"), (sim_render, "render_sim")):
    setattr(mod, attr, timed(attr, getattr(mod, attr)))
for name in ("load_main", "run"):
    setattr(Machine, name, timed("Machine." + name, getattr(Machine, name)))
sys.argv = ["val3check", *sys.argv[1:]]
try:
    rc = main()
finally:
    spent["total"] = time.process_time()
    sys.stderr.write("\n" + json.dumps(spent) + "\n")
sys.exit(rc)
"""


def phases(env: dict[str, str], tmp: str, runs: int) -> None:
    """CPU per phase of the sim of PICK for 1 and 60 simulated seconds (best of `runs` each)."""
    import json

    rows = {}
    for duration in ("1", "60"):
        args = [a if a != "1" else duration for a in PICK]
        cmd = [sys.executable, "-c", PHASES, "sim", *args, "--report", "html", "-o", str(Path(tmp) / "p.html")]
        best = None
        for _ in range(runs):
            r = subprocess.run(cmd, check=False, capture_output=True, text=True, env=env, cwd=ROOT)
            spent = json.loads(r.stderr.strip().splitlines()[-1])
            best = spent if best is None or spent["total"] < best["total"] else best
        rows[duration] = best
    print("\nCPU per phase of one sim process (ms, the run of least total CPU), 1 s and 60 s simulated:")
    for name in rows["60"]:
        a, b = rows["1"].get(name, 0.0) * 1000, rows["60"].get(name, 0.0) * 1000
        print(f"  {name:18s} {a:7.0f} {b:7.0f}")
    print("  (run_case holds lint_case, choose_sim_robot, build_machine, the Machine's load and run, collect and "
          "check_run; render_sim is the page)")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=15)
    ap.add_argument("--phases", action="store_true", help="only the CPU per phase of the 1 s and 60 s sim")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
        env.update(PYTHONPATH=str(ROOT), PYTHONPYCACHEPREFIX=str(Path(tmp) / "pycache"))
        if args.phases:
            timed([sys.executable, "-m", "val3check", "sim", *PICK, "-o", str(Path(tmp) / "w.html")], env, 1)  # .pyc
            phases(env, tmp, max(1, args.runs // 5))
            print(f"load average {', '.join(f'{x:.1f}' for x in os.getloadavg())} on {os.cpu_count()} cores")
            return
        cmd = [sys.executable, "-m", "val3check", "lint", str(APP)]
        timed(cmd, env, 1)  # warm the .pyc files once
        times, cpu, rc = timed(cmd, env, args.runs)
        print(f"val3check lint {APP.relative_to(ROOT)}: exit {rc}, wall median {statistics.median(times)*1000:.0f} ms "
              f"(best {min(times)*1000:.0f}, max {max(times)*1000:.0f}), CPU median {statistics.median(cpu)*1000:.0f} "
              f"ms (best {min(cpu)*1000:.0f}) over {len(times)} runs; goal < 150 ms")
        rows = imports(cmd, env)
        show_imports(rows)
        heavy = [name.strip() for _, name in rows if name.strip().split(".")[0] in FORBIDDEN]
        print("robotics stack imported on the lint path:", ", ".join(heavy) if heavy else "none")

        page = str(Path(tmp) / "r.html")
        sim = [sys.executable, "-m", "val3check", "sim", *PICK, "--report", "html", "-o", page]
        timed(sim, env, 1)
        runs = max(3, args.runs // 3)
        times, cpu, rc = timed(sim, env, runs)
        print(f"\nval3check sim {' '.join(PICK[:1])} (tx2-60, its cell, 1 simulated second, HTML report): exit {rc}, "
              f"CPU median {statistics.median(cpu)*1000:.0f} ms (best {min(cpu)*1000:.0f}), wall median "
              f"{statistics.median(times)*1000:.0f} ms over {runs} runs")
        rows = imports(sim, env)
        show_imports(rows)
        for label, extra in (("HTML report", []), ("with --trace", ["--trace", str(Path(tmp) / "t.mcap")])):
            found = sorted({name.strip().split(".")[0] for _, name in imports(sim + extra, env)} & set(HEAVY)) \
                if extra else sorted({name.strip().split(".")[0] for _, name in rows} & set(HEAVY))
            print(f"heavy packages imported by sim ({label}): {', '.join(found) or 'none'}")
    print(f"load average {', '.join(f'{x:.1f}' for x in os.getloadavg())} on {os.cpu_count()} cores")


if __name__ == "__main__":
    main()
