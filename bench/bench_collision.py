"""Collision-checking figures (issue 14) on a pick-and-place cell, on one core:

1. the cell: a TX2-60, 10 obstacles (a table, a conveyor, a pallet placed in a program frame, two
   light-curtain posts, two fence walls, a sensor, and two meshes of at least 5,000 triangles
   made with trimesh and read back from STL through the cell file reader), a gripper (body and two
   jaws on tool tGripper) and a part it carries from the conveyor to a 3 x 3 pallet;
2. a representative joint trajectory on the 4 ms clock: movej between approach points (trapezoid
   profiles at the arm's nominal speeds and accelerations, 60 %) and movel approaches and
   retreats (500 mm/s), nine pick-and-place cycles; the checker gets every motion, the close/open
   events, and the pallet frame;
3. figures: simulated seconds of motion checked per wall second (goal: at least 100), and
   distance queries per second of the arm (links, tool, part) against the whole cell, each query
   measuring every pair the checker watches exactly.

4. the real run: `val3check sim fixtures/valid/PickPlace --robot tx2-60 --scenario
   fixtures/scenarios/pickplace.toml` (60 simulated s) with the cell found beside it, collision
   checks on and off: simulated seconds per wall second of the whole run (interpreter, motion and
   checks), and the checks' own share.

The cycle is collision-free by construction (the table, conveyor and pallet top are touched only
by the part at pick and place); the run fails if a contact is reported.

Run: python bench/bench_collision.py [--cycles 9]
Exit code 1 when a figure is missed.
"""

from __future__ import annotations

import argparse
import math
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

from val3check.collision import CollisionChecker, MotionSpan, arm_model, read_cell  # noqa: E402
from val3check.collision.measure import Probe  # noqa: E402
from val3check.collision.path import ArmPath  # noqa: E402
from val3check.robot import load_robot  # noqa: E402

DT = 0.004
TOOL = (0.0, 0.0, 150.0, 0.0, 0.0, 0.0)  # tGripper: TCP 150 mm out of the flange
PALLET = (260.0, 110.0, -200.0, 0.0, 0.0, 0.0)  # fPallet on the table top
PICK = (350.0, -300.0, -160.0)  # part centre on the conveyor, TCP there
PITCH = 70.0
APPROACH = 120.0

CELL = """\
version = 1
description = "bench: pick from a conveyor, place on a 3 x 3 pallet"
margin_mm = 5

[[obstacle]]
name = "table"
shape = "box"
size = [500, 1300, 40]
at = {{ x = 500, z = -220 }}

[[obstacle]]
name = "conveyor"
shape = "box"
size = [200, 600, 40]
at = {{ x = 350, y = -400, z = -200 }}

[[obstacle]]
name = "pallet"
shape = "box"
size = [220, 220, 20]
frame = "fPallet"
at = {{ x = 100, y = 100, z = 10 }}

[[obstacle]]
name = "fixture"
shape = "mesh"
file = "fixture.stl"
at = {{ x = 680, y = 0, z = -140 }}

[[obstacle]]
name = "machine"
shape = "mesh"
file = "machine.stl"
at = {{ x = -150, y = 620, z = -100 }}

[[obstacle]]
name = "post left"
shape = "cylinder"
radius = 30
length = 1500
at = {{ x = 820, y = 700, z = 375 }}

[[obstacle]]
name = "post right"
shape = "cylinder"
radius = 30
length = 1500
at = {{ x = 820, y = -700, z = 375 }}

[[obstacle]]
name = "fence back"
shape = "box"
size = [20, 1800, 1800]
at = {{ x = -650, z = 525 }}

[[obstacle]]
name = "fence side"
shape = "box"
size = [1400, 20, 1800]
at = {{ x = 50, y = -950, z = 525 }}

[[obstacle]]
name = "sensor"
shape = "sphere"
radius = 40
at = {{ x = 300, y = -650, z = 60 }}

[[tool]]
name = "body"
tool = "flange"
shape = "cylinder"
radius = 45
length = 100
at = {{ z = 50 }}

[[tool]]
name = "jaw left"
tool = "tGripper"
shape = "box"
size = [15, 30, 50]
at = {{ x = -27.5, z = -25 }}

[[tool]]
name = "jaw right"
tool = "tGripper"
shape = "box"
size = [15, 30, 50]
at = {{ x = 27.5, z = -25 }}

[[part]]
name = "brick"
tool = "tGripper"
grasp = "close"
shape = "box"
size = [40, 40, 40]
at = {{ z = 0 }}
"""


def write_cell(folder: Path) -> Path:
    import trimesh

    fixture = trimesh.creation.icosphere(subdivisions=4, radius=60.0)  # 5,120 triangles
    machine = trimesh.creation.cylinder(radius=120.0, height=550.0, sections=1400)  # 5,600 triangles
    fixture.export(folder / "fixture.stl")
    machine.export(folder / "machine.stl")
    path = folder / "val3check-cell.toml"
    path.write_text(CELL.format(), encoding="utf-8")
    return path


# ---- a trajectory like the motion planner's: trapezoid profiles on the 4 ms clock ---------------------


def trapezoid(length: float, v: float, a: float) -> tuple[float, callable]:
    """Duration and s(t) (0..length) of a trapezoid profile (triangle when too short)."""
    if length <= 0.0:
        return 0.0, lambda t: 0.0
    ta = v / a
    if a * ta * ta > length:  # triangle
        ta = math.sqrt(length / a)
        v = a * ta
    tc = (length - a * ta * ta) / v
    T = 2 * ta + tc

    def s(t: float) -> float:
        t = min(max(t, 0.0), T)
        if t < ta:
            return 0.5 * a * t * t
        if t < ta + tc:
            return 0.5 * a * ta * ta + v * (t - ta)
        r = T - t
        return length - 0.5 * a * r * r

    return T, s


def movej(robot, q0, q1, t0: float, ratio: float = 0.6):
    q0, q1 = np.asarray(q0, float), np.asarray(q1, float)
    d = np.abs(q1 - q0)
    k = int(np.argmax(d / np.asarray(robot.nominal_speeds)))
    v = robot.nominal_speeds[k] * ratio
    a = robot.accelerations[k] * ratio
    T, s = trapezoid(float(d[k]), v, a)
    n = max(1, int(math.ceil(T / DT)))
    times = t0 + np.arange(n + 1) * DT
    frac = np.array([s(min(i * DT, T)) / d[k] if d[k] > 0 else 1.0 for i in range(n + 1)])
    return times, q0 + frac[:, None] * (q1 - q0)


def movel(robot, q0, p0, p1, t0: float, v: float = 500.0, a: float = 2500.0):
    L = math.dist(p0[:3], p1[:3])
    T, s = trapezoid(L, v, a)
    n = max(1, int(math.ceil(T / DT)))
    times = t0 + np.arange(n + 1) * DT
    Q, q = [], list(q0)
    for i in range(n + 1):
        f = s(min(i * DT, T)) / L if L > 0 else 1.0
        p = [p0[j] + f * (p1[j] - p0[j]) for j in range(3)] + list(p0[3:])
        q = robot.solve(p, None, q, tool=TOOL)
        Q.append(q)
    return times, np.array(Q)


def cycle_plan(robot, cycles: int):
    """(motions, events): motions as (label, times, joints), events as (time, instruction)."""
    down = (180.0, 0.0, 0.0)
    home = robot.solve((350.0, 0.0, 50.0, *down), None, [0, 30, 90, 0, 60, 0], tool=TOOL)
    t = 0.0
    q = np.asarray(home, float)
    plan: list = []
    for i in range(cycles):
        r, c = divmod(i, 3)
        slot = (PALLET[0] + 40 + PITCH * c, PALLET[1] + 40 + PITCH * r, PALLET[2] + 20 + 20)
        for target, what in ((PICK, "close"), (slot, "open")):
            above = (target[0], target[1], target[2] + APPROACH, *down)
            at = (target[0], target[1], target[2], *down)
            qa = robot.solve(above, None, list(q), tool=TOOL)
            times, Q = movej(robot, q, qa, t)
            plan.append(("movej", times, Q))
            t, q = float(times[-1]), Q[-1]
            times, Q = movel(robot, q, above, at, t)
            plan.append(("movel down", times, Q))
            t, q = float(times[-1]), Q[-1]
            plan.append((what, t))
            t += 0.2  # ctime / otime
            times, Q = movel(robot, q, at, above, t)
            plan.append(("movel up", times, Q))
            t, q = float(times[-1]), Q[-1]
    times, Q = movej(robot, q, home, t)
    plan.append(("movej home", times, Q))
    return plan


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cycles", type=int, default=9)
    args = ap.parse_args(argv)
    robot = load_robot("TX2-60")
    arm = arm_model(robot)
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        cell = read_cell(write_cell(Path(tmp)))
        t_cell = time.perf_counter() - t0
    tris = [len(o.shape.mesh.faces) for o in cell.obstacles if o.shape.kind == "mesh"]
    plan = cycle_plan(robot, args.cycles)
    # three runs, the fastest counts (the machine is shared: the others measure the neighbours)
    runs = []
    for _ in range(3):
        checker = CollisionChecker(arm, cell, frames={"fPallet": PALLET}, tools={"tGripper": TOOL})
        motion_s = 0.0
        reports = []
        drops = []
        t0, c0 = time.perf_counter(), time.process_time()
        for i, step in enumerate(plan):
            if len(step) == 2:
                drops += checker.gripper("tGripper", step[0], step[1])
                continue
            label, times, Q = step
            reports.append(checker.check_motion(MotionSpan(i, label=label), times, Q))
            motion_s += float(times[-1] - times[0])
        runs.append((time.perf_counter() - t0, time.process_time() - c0))
    wall = min(r[0] for r in runs)
    cpu = min(r[1] for r in runs)
    contacts = [r for r in reports if r.first_contact or r.starts_in_collision]
    samples = sum(len(r.times) for r in reports)
    rate = motion_s / wall
    print(f"cell: {len(cell.obstacles)} obstacles (meshes of {', '.join(str(n) for n in tris)} triangles), "
          f"{len(cell.tools)} tool solids, {len(cell.parts)} part; read in {t_cell * 1000:.0f} ms")
    print(f"trajectory: {len(reports)} motions, {samples} samples, {motion_s:.2f} s of motion "
          f"({args.cycles} cycles)")
    print(f"checked: {rate:.0f} simulated s per wall s (best of 3: {wall * 1000:.0f} ms wall, {cpu * 1000:.0f} ms CPU, "
          f"{motion_s / cpu:.0f} simulated s per CPU s; "
          f"{checker.measurements} pair measurements, {checker.measurements / samples:.2f} per sample)")
    closest = min((r for r in reports if r.min_clearance), key=lambda r: r.min_clearance.mm)
    m = closest.min_clearance
    print(f"closest: {m.mm:.2f} mm between {m.body_a} and {m.body_b} at {m.time:.3f} s ({closest.motion.label})")
    print(f"contacts: {len(contacts)}, parts left inside something: {len(drops)}")

    # distance queries: every watched pair measured exactly, at configurations of the trajectory
    checker2 = CollisionChecker(arm, cell, frames={"fPallet": PALLET}, tools={"tGripper": TOOL})
    Qall = np.concatenate([s[2] for s in plan if len(s) == 3])
    sel = Qall[:: max(1, len(Qall) // 2000)]
    checker2.check_motion(MotionSpan(0), np.arange(len(sel)) * DT, sel)  # sets up the scene
    world = checker2.world
    watches = world.watches()
    n0 = checker2.measurements
    t0 = time.perf_counter()
    for k in range(len(sel)):
        # one configuration: the links' poses, then every watch measured exactly from its bodies
        probe = Probe(world, ArmPath(arm, np.zeros(1), sel[k:k + 1], None), checker2.backend)
        for w in watches:
            w.a.placed = -1.0
            if w.b is not None:
                w.b.placed = -1.0
            probe.measure(w, 0.0, math.inf)
    dwall = time.perf_counter() - t0
    qps = len(sel) / dwall
    pairs = (checker2.measurements - n0) / dwall
    print(f"distance queries (arm, tool and part against the cell, {len(watches)} watched pairs of groups): "
          f"{qps:.0f} per second ({pairs:.0f} fcl distance calls per second)")
    ok = rate >= 100.0 and not contacts and not drops and min(tris) >= 5000 and len(cell.obstacles) == 10
    ok = real_run() and ok
    print("OK" if ok else "MISSED")
    return 0 if ok else 1


def real_run() -> bool:
    """PickPlace for 60 simulated s, with and without the collision checks (best of 3 each)."""
    from val3check.config import Settings
    from val3check.lint import run
    from val3check.simulation import SimOptions, simulate
    from val3check.simulation.collision_run import choose_cell
    from val3check.simulation.scenario import load_scenario

    app_dir = ROOT / "fixtures" / "valid" / "PickPlace"
    lr = run([str(app_dir)], Settings())
    ws = lr.workspace
    app = ws.apps[ws.targets[0]]
    scenario = load_scenario(str(ROOT / "fixtures" / "scenarios" / "pickplace.toml"))
    robot = load_robot("TX2-60")
    cell, found = choose_cell(None, app.path)
    walls = {}
    for on in (False, True, False, True, False, True):
        opts = SimOptions(duration=60.0, robot=robot, collisions=on, cell=cell if on else None, cell_found=found)
        t0 = time.perf_counter()
        result = simulate(ws, app, opts, scenario)
        w = time.perf_counter() - t0
        walls[on] = min(walls.get(on, math.inf), w)
        if on:
            c = result.collision
    sim_s = result.sim_time_us / 1e6
    moving = result.motion.busy_s
    bad = [d for d in result.diagnostics if d.code.startswith("R03")]
    mins = [r.min_clearance.mm for r in c.by_motion.values() if r.min_clearance is not None]
    print(f"real run (PickPlace, {sim_s:.0f} simulated s, {moving:.1f} s of motion, {len(c.by_motion)} motions, "
          f"cell {Path(cell).name} ({found}): {len(c.cell.obstacles)} obstacles, {len(c.cell.tools)} tool solids):")
    print(f"  collision checks off: {sim_s / walls[False]:.0f} simulated s per wall s ({walls[False]:.2f} s wall)")
    print(f"  collision checks on:  {sim_s / walls[True]:.0f} simulated s per wall s ({walls[True]:.2f} s wall; the "
          f"checks {walls[True] - walls[False]:.2f} s, {c.checks} queries, {moving / max(walls[True] - walls[False], 1e-9):.0f} "
          f"s of motion per wall s of checking)")
    print(f"  findings R030-R039: {len(bad)}; closest approach {min(mins):.1f} mm")
    return not bad and sim_s / walls[True] >= 10.0


if __name__ == "__main__":
    sys.exit(main())
