"""Throughput of `val3check sim` (issue 4 and issue 12 goals, on the 2-core CI machine):

1. at least 200,000 VAL 3 lines executed per second on arithmetic/array loops;
2. an I/O-driven application that spends most of its time waiting: at least 1,000 s of
   simulated time per second of wall time;
3. the pick-and-place cell fixtures/valid/PickPlace (blended joint and Cartesian motions, open
   and close, a loop and waits on its cell, fixtures/scenarios/pickplace.toml) on a TX2-60,
   run and written as the JSON report with its 4 ms trajectory: at least 100 simulated s per
   wall s, and at least 200 motion commands planned per second. Wall-clock and CPU time of the
   process are printed (the machine is shared); the goal is checked on CPU time.

Run: python bench/bench_sim.py   (writes only into a temporary folder)
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))

from val3check.testing import write_app  # noqa: E402

from val3check.config import Settings  # noqa: E402
from val3check.simulation.scenario import load_scenario  # noqa: E402
from val3check.simulation import SimOptions, simulate  # noqa: E402
from val3check.lint import run  # noqa: E402

LOOPS = """begin
  nSum = 0
  for l_i = 0 to 299999
    l_j = l_i % 100
    nA[l_j] = nA[l_j] + l_i * 2
    if nA[l_j] > 1000000
      nA[l_j] = nA[l_j] - 1000000
    endIf
    nSum = nSum + nA[l_j] / 3
  endFor
  putln(nSum)
end
"""

# A cell controller: a PLC task polls a sensor every 50 ms and drives a conveyor; the main task
# waits for parts; the scenario brings a part every 2 s and the cell reacts to the outputs.
IO_START = """begin
  taskCreate "plc", 10, plc()
  while true
    wait(diPart == true)
    doClamp = true
    wait(diClamped == true)
    nParts = nParts + 1
    delay(0.5)
    doClamp = false
    wait(diPart == false)
  endWhile
end
"""
IO_PLC = """begin
  while true
    doConveyor = (diPart == false)
    nPolls = nPolls + 1
    delay(0.05)
  endWhile
end
"""


def _app(tmp: Path, code: str, name: str, **kw):
    folder = write_app(tmp, code, name=name, **kw)
    return folder


def _links(folder: Path, links: dict[str, str]) -> None:
    import re

    dtx = next(folder.glob("*.dtx"))
    text = dtx.read_text(encoding="utf-8")
    for var, link in links.items():
        text = re.sub(rf'(<Data name="{var}" [^>]*?) />', lambda m: f'{m.group(1)}><Value key="0" link="{link}" /></Data>', text)
    dtx.write_text(text, encoding="utf-8")


def _sim(folder: Path, duration: float, scenario=None):
    lr = run([str(folder)], Settings())
    ws = lr.workspace
    app = ws.apps[ws.targets[0]]
    t0 = time.perf_counter()
    result = simulate(ws, app, SimOptions(duration=duration, max_wall=600, max_lines=10**9), scenario)
    return result, time.perf_counter() - t0


def main() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        folder = _app(tmp, LOOPS, "Loops", globals_=["num nSum", "num nA[100]"], locals_=["num l_i", "num l_j"])
        rates = []
        for _ in range(3):
            result, wall = _sim(folder, 1000.0)
            rates.append(result.lines / wall)
        best = max(rates)
        print(f"arithmetic/array loops: {result.lines} lines in {result.lines / best:.3f} s wall: "
              f"{best:,.0f} lines/s (goal 200,000) {'OK' if best >= 200_000 else 'TOO SLOW'}")

        folder = _app(tmp, IO_START, "Cell", globals_=["dio diPart", "dio diClamped", "dio doClamp", "dio doConveyor",
                                                        "num nParts", "num nPolls"],
                      programs={"plc": {"code": IO_PLC}})
        _links(folder, {"diPart": "BasicIO-1\\%I0", "diClamped": "BasicIO-1\\%I1", "doClamp": "BasicIO-1\\%Q0",
                        "doConveyor": "BasicIO-1\\%Q1"})
        duration = 3600.0
        events = "\n".join(f"[[events]]\nat = {t + 1}\nset = {{ diPart = true }}\n[[events]]\nat = {t + 2}\n"
                           f"set = {{ diPart = false }}\n" for t in range(0, int(duration), 2))
        sc = tmp / "cell.toml"
        sc.write_text("[inputs]\ndiPart = false\ndiClamped = false\n\n[[reactions]]\nwhen = \"doClamp\"\nbecomes = true\n"
                      "after = 0.2\nset = { diClamped = true }\n\n[[reactions]]\nwhen = \"doClamp\"\nbecomes = false\n"
                      "after = 0.1\nset = { diClamped = false }\n\n" + events, encoding="utf-8")
        result, wall = _sim(folder, duration, load_scenario(str(sc)))
        ratio = result.sim_time_us / 1e6 / wall
        print(f"I/O-driven cell: {result.sim_time_us / 1e6:.0f} s simulated in {wall:.3f} s wall: "
              f"{ratio:,.0f} simulated s per wall s (goal 1,000) {'OK' if ratio >= 1000 else 'TOO SLOW'}; "
              f"{len(result.io_log)} I/O events, end: {result.end_reason}")


def pick_and_place(duration: float = 600.0) -> None:
    from val3check.reporting.sim_json import render
    from val3check.reporting.sim_report import build_report
    from val3check.robot import load_robot
    from val3check.rules.catalogue import catalogue

    lr = run([str(ROOT / "fixtures" / "valid" / "PickPlace")], Settings())
    ws = lr.workspace
    app = ws.apps[ws.targets[0]]
    robot = load_robot("TX2-60")
    scenario = load_scenario(str(ROOT / "fixtures" / "scenarios" / "pickplace.toml"))
    simulate(ws, app, SimOptions(duration=10.0, robot=robot), scenario)  # warm-up: imports (numpy, pinocchio...)
    w0, c0 = time.perf_counter(), time.process_time()
    result = simulate(ws, app, SimOptions(duration=duration, max_wall=600, robot=robot), scenario)
    w1, c1 = time.perf_counter(), time.process_time()
    text = render(build_report(result, None, catalogue(), "bench"))
    w2, c2 = time.perf_counter(), time.process_time()
    m = result.motion
    commands = sum(1 for r in m.motions if r.id is not None)
    cycles = m.cycles["robot"]
    speed_wall, speed_cpu = duration / (w2 - w0), duration / (c2 - c0)
    rate = commands / (c1 - c0)
    print(f"pick-and-place cell (TX2-60): {duration:.0f} s simulated, {commands} motion commands, {cycles.count} "
          f"cycles; run {w1 - w0:.2f} s wall / {c1 - c0:.2f} s CPU, JSON report with the 4 ms trajectory "
          f"({len(text) / 1e6:.1f} MB) {w2 - w1:.2f} s wall / {c2 - c1:.2f} s CPU: {speed_wall:,.0f} simulated s per "
          f"wall s, {speed_cpu:,.0f} per CPU s (goal 100) {'OK' if speed_cpu >= 100 else 'TOO SLOW'}; "
          f"{rate:,.0f} commands planned per CPU s (goal 200) {'OK' if rate >= 200 else 'TOO SLOW'}")


if __name__ == "__main__":
    main()
    pick_and_place()
