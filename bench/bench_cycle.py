"""The standard SCARA cycle on every TS2 arm against Stäubli's published figure (issue 23).

The cycle Stäubli quotes for its TS2 range (2 kg; up 25 mm, across 300 mm, down 25 mm, and back):
up to 240, 220, 200 and 170 cycles per minute for the TS2-40, -60, -80 and -100, i.e. 0.250,
0.273, 0.300 and 0.353 s (docs/motion.md, "Accelerations", for the source and how sure it is).
Placement (not published): the 300 mm transfer perpendicular to the arm's X axis, centred on it at
62 % of the reach, the flange pointing down, j3 mid-stroke at the bottom points; every move a movej
(the fastest), blended where the path turns (joint blend) and stopping at the pick and place points
(the path turns back there). "Best blend": the fastest of a few leave/reach pairs (leave clipped to
half the 25 mm legs, reach up to half the transfer).

Printed per arm: the simulated cycle (val3check's motion queue, today's timing core), the reference
optimum on the same path (tests/motion/reference.py: the arm's own limits, an independent dense
integration — what exact timing will give), the published figure, and their ratios; the same with
the accelerations half and twice the model's (the range the reports are to give). Held-out goal:
simulated within 15 % of the published figure with best blend.

Run: python bench/bench_cycle.py [--arms TS2-40,TS2-60,TS2-80,TS2-100] [--at 0.62] [--ramp S]
Exit code 1 when an arm misses 15 %.
"""

from __future__ import annotations

import argparse
import itertools
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT / "robots"))

import dynamics  # noqa: E402
from motion import reference as ref  # noqa: E402

from val3check.motion.commands import MoveCommand, Target  # noqa: E402
from val3check.motion.mdesc import MDesc  # noqa: E402
from val3check.motion.queue import MotionQueue  # noqa: E402
from val3check.robot import load_robot  # noqa: E402

PUBLISHED_CPM = dynamics.PUBLISHED_CYCLES  # cycles per minute (robots/dynamics.py: the source)
GOAL = 0.15
UP, ACROSS = 25.0, 300.0
BLENDS = ((25.0, 25.0), (25.0, 75.0), (25.0, 150.0), (25.0, 300.0))  # (leave on the legs, reach on the transfer)


def pose(model, q) -> np.ndarray:
    T = np.eye(4)
    T[:3, :] = np.array(model.fk_matrix(list(q)))
    return T


def cycle_points(model, at: float, turn: float = 0.0):
    """Joint positions of pick, above pick, above place, place (righty): the transfer centred on
    X at `at` × the reach, turned by `turn` degrees from the perpendicular to X."""
    stroke = model.joint_limits[2]
    q_ref = np.array([0.0, 90.0, (stroke[0] + stroke[1]) / 2, 0.0])
    T = pose(model, q_ref)
    out = []
    u = np.array([np.sin(np.radians(turn)), np.cos(np.radians(turn))])
    for side, dz in ((-1, 0.0), (-1, UP), (1, UP), (1, 0.0)):
        Ti = T.copy()
        x, y = np.array([at * model.reach_mm, 0.0]) + side * ACROSS / 2 * u
        Ti[:3, 3] = [x, y, T[2, 3] + dz]
        out.append(np.array(model.ik(Ti, near=list(q_ref), config=("righty",))[0], dtype=float))
    return out


def simulate(model, pts, leave: float, reach: float):
    """One cycle from rest at the pick point and back: (duration, the queue's trajectory)."""
    pick, pick_up, place_up, place = pts
    q = MotionQueue(model, pick)
    corner = MDesc(blend="joint", leave=leave, reach=reach)
    transfer = MDesc(blend="joint", leave=reach, reach=leave)
    stop = MDesc(blend="off")
    for target, md in ((pick_up, corner), (place_up, transfer), (place, stop),
                       (place_up, corner), (pick_up, transfer), (pick, stop)):
        q.record(MoveCommand("movej", Target.joint(target), md), 0.0)
    t = q.wait_end_move(0.0)
    q.advance(t)
    return t, q.trajectory


def optimum_on(model, traj, lim: ref.Limits) -> float:
    """The reference optimum along the simulator's own path, rest to rest between its stops."""
    path = traj.path
    cuts = [0.0] + [s for s in path.stops_after(0.0) if 0.0 < s < path.end] + [path.end]
    total = 0.0
    for a, b in itertools.pairwise(cuts):
        if b - a > 1e-9:
            total += ref.profile_of_joint_path(model, path, a, b, lim, n_ik=4001, n=40001).duration
    return total


def best_cycle(model, pts):
    """The fastest blend: (simulated duration, leave, reach, trajectory)."""
    best = None
    for leave, reach in BLENDS:
        t, traj = simulate(model, pts, leave, reach)
        if best is None or t < best[0]:
            best = (t, leave, reach, traj)
    return best


def rule_model(name: str, ramp_ref: float):
    """The catalogue arm with the SCARA rule's speeds and ramp for this reference ramp."""
    model = load_robot(name)
    speeds, ramp = dynamics.scara(model.reach_mm, ramp_ref)
    return model.with_assumptions({"nominal_speeds": list(speeds), "ramp_s": ramp})


def fit(arms, at: float) -> int:
    """Fit the SCARA rule's reference ramp to the published cycles (robots/dynamics.py): the
    optimum of each arm's cycle (on the path of its best blend) over a grid of ramps, interpolated
    in log-log; the ramp where the mean of log(optimum / published) is 0; the same on three arms
    to predict the fourth."""
    grid = np.geomspace(0.02, 0.09, 9)
    table = {}
    for name in arms:
        pts = cycle_points(rule_model(name, dynamics.SCARA_RAMP_REF_S), at)
        _, _, _, traj = best_cycle(rule_model(name, dynamics.SCARA_RAMP_REF_S), pts)
        row = []
        for g in grid:
            m = rule_model(name, float(g))
            row.append(optimum_on(m, traj, ref.Limits.of(m)))
        table[name] = np.log(np.array(row) / (60.0 / PUBLISHED_CPM[name]))
        print(f"{name}: optimum / published over ramps {grid[0]:.3f}..{grid[-1]:.3f} s: "
              + " ".join(f"{np.exp(x):.3f}" for x in table[name]))

    def solve(names):
        mean = np.mean([table[n] for n in names], axis=0)
        return float(np.exp(np.interp(0.0, mean, np.log(grid))))

    best = solve(arms)
    print(f"\nreference ramp (at {dynamics.SCARA_REACH_REF:g} mm) fitted on {', '.join(arms)}: {best:.4f} s")
    for name in arms:
        r = np.exp(np.interp(np.log(best), np.log(grid), table[name]))
        others = [n for n in arms if n != name]
        loo = solve(others)
        r_loo = np.exp(np.interp(np.log(loo), np.log(grid), table[name]))
        print(f"  {name}: optimum / published {r:.3f}; fitted on the other three ({loo:.4f} s): {r_loo:.3f}")
    return 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--arms", default=",".join(PUBLISHED_CPM))
    ap.add_argument("--at", type=float, default=0.62, help="centre of the transfer, fraction of the reach")
    ap.add_argument("--fit", action="store_true", help="fit the SCARA rule's ramp (robots/dynamics.py) to the figures")
    ap.add_argument("--ramp", type=float, default=None,
                    help="every joint at nominal speed in this many seconds (the accelerations issue 23 had: 0.25)")
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    if args.fit:
        return fit([a.strip() for a in args.arms.split(",")], args.at)
    print(f"TS2 standard cycle (up {UP:g}, across {ACROSS:g}, down {UP:g} mm, and back), transfer centred at "
          f"{100 * args.at:g} % of the reach; seconds")
    print(f"{'arm':8s} {'published':>9s} {'simulated':>9s} {'optimum':>8s} {'sim/pub':>8s} {'opt/pub':>8s} "
          f"{'optimum, accel ×2 … ×½':>22s}  best blend; accelerations")
    missed = 0
    for name in args.arms.split(","):
        model = load_robot(name.strip())
        if args.ramp is not None:
            model = model.with_assumptions({"ramp_s": args.ramp})
        pub = 60.0 / PUBLISHED_CPM[model.name]
        pts = cycle_points(model, args.at)
        sim, leave, reach, traj = best_cycle(model, pts)
        opt = optimum_on(model, traj, ref.Limits.of(model))
        lo = optimum_on(model, traj, ref.Limits.of(model, accel=200, decel=200))  # twice the accelerations
        hi = optimum_on(model, traj, ref.Limits.of(model, accel=50, decel=50))  # half
        missed += abs(sim / pub - 1) > GOAL
        acc = ", ".join(f"{a:g}" for a in model.accelerations)
        print(f"{model.name:8s} {pub:9.3f} {sim:9.3f} {opt:8.3f} {sim / pub:8.2f} {opt / pub:8.2f} "
              f"{lo:10.3f} – {hi:.3f}  leave {leave:g} reach {reach:g}; {acc}")
    print(f"{time.perf_counter() - t0:.0f} s; goal: simulated within {100 * GOAL:g} % of the published cycle: "
          f"{'met' if not missed else f'{missed} missed'}")
    return 1 if missed else 0


if __name__ == "__main__":
    sys.exit(main())
