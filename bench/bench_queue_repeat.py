"""What a repeating motion command costs the motion queue (issue 29): a pick-and-place cycle of six
commands (blended movej and movel, a stop, a movec) recorded again and again from the same states,
with the scheduler's calls between them (advance and next_event at every event, waitEndMove at
the cycle's end), on a TX2-60. Prints the process time per command after a warm-up, best of
`--repeat` rounds, with the load average beside it (the machine is shared: compare two trees run
alternately, e.g. `python bench/bench_queue_repeat.py` from each checkout).

    python bench/bench_queue_repeat.py [--cycles 300] [--repeat 5]
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

from val3check.motion.commands import MoveCommand, Target
from val3check.motion.findings import Source
from val3check.motion.kin import ArmKin
from val3check.motion.mdesc import MDesc
from val3check.motion.queue import MotionQueue, QueueFull
from val3check.robot import load_robot

ROBOT = load_robot("TX2-60")
HOME = np.array([0.0, 20.0, 100.0, 0.0, 60.0, 0.0])
T_HOME = ArmKin(ROBOT).fk(HOME[None])[0]
BLEND = MDesc(blend="joint", leave=20.0, reach=20.0)
OFF = MDesc(blend="off")
SOURCE = Source("app/start.pgx", 1, 5, "start", "t")


def _point(dx=0.0, dy=0.0, dz=0.0) -> Target:
    T = T_HOME.copy()
    T[:3, 3] += [dx, dy, dz]
    return Target.point(T, ("ssame", "esame", "wsame"))


def _cycle() -> list[MoveCommand]:
    """One cycle, made afresh (the interpreter makes new values at every instruction)."""
    above = _point(dx=70.0, dy=30.0, dz=40.0)
    return [MoveCommand("movej", Target.joint(HOME), BLEND, source=SOURCE),
            MoveCommand("movel", above, BLEND, source=SOURCE),
            MoveCommand("movel", _point(dx=70.0, dy=30.0), OFF, source=SOURCE),
            MoveCommand("movel", above, BLEND, source=SOURCE),
            MoveCommand("movec", _point(dx=-20.0, dy=70.0, dz=30.0), BLEND, via=_point(dx=20.0, dy=60.0, dz=50.0),
                        source=SOURCE),
            MoveCommand("movel", _point(dx=-20.0, dy=70.0), OFF, source=SOURCE)]


def _run(q: MotionQueue, cycles: int, now: float) -> float:
    """`cycles` cycles: records ahead of the arm, the scheduler's calls at every event."""
    for _ in range(cycles):
        for k, move in enumerate(_cycle()):
            r = q.record(move, now)
            while isinstance(r, QueueFull):
                now = r.until
                q.advance(now)
                r = q.record(move, now)
            if k == 2:  # the rest recorded while the arm moves, as a program waiting on a signal would
                t = q.next_event(now)
                while t is not None and t < now + 0.3:
                    q.advance(t)
                    now = t
                    t = q.next_event(now)
        end = q.wait_end_move(now)
        t = q.next_event(now)
        while t is not None and t <= end:
            q.advance(t)
            now = t
            t = q.next_event(now)
        now = max(now, end)
        q.advance(now)
    return now


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cycles", type=int, default=300)
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    q = MotionQueue(ROBOT, HOME)
    now = _run(q, 20, 0.0)  # warm-up: the first cycles compute what the others reuse
    best = None
    for _ in range(args.repeat):
        t0 = time.process_time()
        now = _run(q, args.cycles, now)
        dt = time.process_time() - t0
        best = dt if best is None else min(best, dt)
    n = args.cycles * 6
    print(f"{best / n * 1e6:.1f} us per command (best of {args.repeat} x {n} commands; "
          f"load {os.getloadavg()[0]:.1f}); at {now:.1f} s simulated")


if __name__ == "__main__":
    main()
