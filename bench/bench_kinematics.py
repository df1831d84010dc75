"""Kinematics figures of the Stäubli arm models (issues 5 and 13), on one core:

1. round trip FK -> IK -> FK over 100,000 random joint positions inside the limits, on every arm
   (31: 22 six-axis, 9 SCARA), every branch the closed form returns (all eight where they exist on
   a six-axis arm, both elbow branches of a SCARA): worst position error below 1e-6 mm, worst
   orientation error below 1e-9 rad, and the starting joint position found every time among the
   solutions of RobotModel.ik();
2. at least 50,000 forward-kinematics evaluations per second (TX2-60 and TS2-60);
3. at least 10,000 full inverse-kinematics solves (all branches, limits, turns) per second.

Run: python bench/bench_kinematics.py [--n 100000] [--arms TX2-60,RX160,TS2-60]
Exit code 1 when a figure is missed.
"""

from __future__ import annotations

import argparse
import math
import random
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from val3check.robot import load_robot, names  # noqa: E402
from val3check.robot.ik import opw_ik  # noqa: E402
from val3check.robot.kinematics import pose_error  # noqa: E402
from val3check.robot.scara import scara_ik  # noqa: E402

DEG = math.pi / 180.0


def round_trip(robot, n: int, seed: int) -> dict:
    rng = random.Random(seed)
    lim = robot.joint_limits
    solver = robot.opw or robot.scara
    scara = robot.family == "scara"
    worst_p = worst_a = worst_j = 0.0
    missed = 0
    branches = {}
    for _ in range(n):
        q = [rng.uniform(lo, hi) for lo, hi in lim]
        T = robot.fk_matrix(q)
        hint = robot._internal(q)
        raw = scara_ik(solver, T, hint)[0] if scara else opw_ik(solver, T, hint)
        branches[len(raw)] = branches.get(len(raw), 0) + 1
        for s in raw:
            dp, da = pose_error(solver.fk(s), T)
            if dp > worst_p:
                worst_p = dp
            if da > worst_a:
                worst_a = da
        sols = robot.ik(T, near=q)
        d = max(abs(a - b) for a, b in zip(sols[0], q)) if sols else math.inf
        if d > 1e-6:
            missed += 1
        worst_j = max(worst_j, d)
    return {"pos": worst_p, "ang": worst_a, "joint": worst_j, "missed": missed, "branches": branches}


def pinocchio_check(robot, n: int, seed: int) -> tuple[float, float]:
    """FK(IK(pose)) with pinocchio's forward kinematics, as an outside referee."""
    rng = random.Random(seed)
    wp = wa = 0.0
    for _ in range(n):
        q = [rng.uniform(lo, hi) for lo, hi in robot.joint_limits]
        T = robot.fk_pinocchio(q)
        for s in robot.ik(T):
            dp, da = pose_error(robot.fk_pinocchio(s), T)
            wp, wa = max(wp, dp), max(wa, da)
    return wp, wa


def rate(fn, items, min_time: float = 1.0) -> float:
    count, start = 0, time.perf_counter()
    while True:
        for it in items:
            fn(it)
        count += len(items)
        elapsed = time.perf_counter() - start
        if elapsed >= min_time:
            return count / elapsed


def rates(arm: str) -> bool:
    robot = load_robot(arm)
    rng = random.Random(1)
    qs = [[rng.uniform(lo, hi) for lo, hi in robot.joint_limits] for _ in range(20_000)]
    poses = [robot.fk(q) for q in qs]
    mats = [robot.fk_matrix(q) for q in qs]
    fk_m = rate(robot.fk_matrix, qs)
    fk_t = rate(robot.fk, qs)
    ik_t = rate(robot.ik, poses)
    ik_m = rate(robot.ik, mats)
    ik_near = rate(lambda i: robot.ik(poses[i], near=qs[i]), range(len(qs)))
    print()
    print(f"Rates on one core ({arm}, closed form, pure Python):")
    print(f"  forward kinematics -> 3x4 matrix          {fk_m:>10,.0f} /s")
    print(f"  forward kinematics -> VAL 3 trsf          {fk_t:>10,.0f} /s   (goal 50,000)")
    print(f"  inverse kinematics, trsf in, all branches {ik_t:>10,.0f} /s   (goal 10,000)")
    print(f"  inverse kinematics, matrix in             {ik_m:>10,.0f} /s")
    print(f"  inverse kinematics with near (9.6.3)      {ik_near:>10,.0f} /s")
    try:
        fk_p = rate(robot.fk_pinocchio, qs[:5000])
        print(f"  forward kinematics by pinocchio -> 3x4    {fk_p:>10,.0f} /s")
    except ImportError:
        pass
    return fk_t >= 50_000 and ik_t >= 10_000


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", type=int, default=100_000, help="random joint positions per arm (default 100,000)")
    ap.add_argument("--arms", default="", help="comma-separated arm names (default: every arm)")
    args = ap.parse_args()
    arms = [a.strip() for a in args.arms.split(",") if a.strip()] or names()

    print(f"Round trip FK -> IK -> FK, {args.n:,} random joint positions per arm, every branch")
    print(f"{'arm':<13} {'worst pos mm':>13} {'worst rot rad':>14} {'worst joint':>12} {'missed':>7}  branches per pose")
    ok = True
    t0 = time.perf_counter()
    all_p = all_a = 0.0
    for i, name in enumerate(arms):
        robot = load_robot(name)
        r = round_trip(robot, args.n, 1000 + i)
        all_p, all_a = max(all_p, r["pos"]), max(all_a, r["ang"])
        dist = ", ".join(f"{k}: {v}" for k, v in sorted(r["branches"].items(), reverse=True))
        print(f"{name:<13} {r['pos']:>13.2e} {r['ang']:>14.2e} {r['joint']:>12.2e} {r['missed']:>7}  {dist}")
        ok &= r["pos"] < 1e-6 and r["ang"] < 1e-9 and r["missed"] == 0
    print(f"worst over all arms: {all_p:.2e} mm, {all_a:.2e} rad ({time.perf_counter() - t0:.0f} s); worst joint in deg "
          "(mm for a SCARA's axis 3)")

    try:
        import pinocchio  # noqa: F401

        wp = wa = 0.0
        for i, name in enumerate(arms):
            p, a = pinocchio_check(load_robot(name), max(1, args.n // 100), 5000 + i)
            wp, wa = max(wp, p), max(wa, a)
        print(f"same round trip judged by pinocchio's FK ({max(1, args.n // 100):,} poses per arm): {wp:.2e} mm, {wa:.2e} rad")
        ok &= wp < 1e-6 and wa < 1e-9
    except ImportError:
        print("pinocchio not installed: its cross-check is skipped")

    for arm in ("TX2-60", "TS2-60"):
        ok &= rates(arm)
    print()
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
