"""The interpreter's own instructions in a `val3check sim` run (issue 29): callgrind collects only
while the innermost of `Scheduler.loop` and the arm's entry points below is the interpreter's,
so the count is what the loop spends outside the arm (its own share of a cycle), load-free.

    valgrind --tool=callgrind --collect-atstart=no --callgrind-out-file=/tmp/cg.out \\
        python bench/interp_instructions.py sim fixtures/valid/PickPlace --robot tx2-60 \\
        --scenario fixtures/scenarios/pickplace.toml --duration 600 --report html -o /tmp/r.html

valgrind prints "Collected : N". The arm's entry points: MovingArm's advance, next_time,
end_motion, motion_done, has_room, record and context, and chapter 10's _point, _tool, _source,
_check_family and check_defined. The wrapper costs about 2,600 instructions per crossing into the
arm and back (calibrated with a no-op): compare counts of the same run before and after, and see
"crossings" printed at the end. The cyclic collector is off during the loop. Needs gcc and valgrind's headers (the toggle is a client request,
compiled into a small library in a temporary folder). Outside valgrind the toggles do nothing.
"""

from __future__ import annotations

import ctypes
import functools
import gc
import subprocess
import sys
import tempfile
from pathlib import Path

_TOGGLE_C = "#include <valgrind/callgrind.h>\nvoid toggle(void) { CALLGRIND_TOGGLE_COLLECT; }\n"


def _toggle():
    folder = Path(tempfile.mkdtemp(prefix="val3check-cg-"))
    (folder / "toggle.c").write_text(_TOGGLE_C)
    subprocess.run(["gcc", "-O2", "-shared", "-fPIC", "-o", str(folder / "toggle.so"), str(folder / "toggle.c")],
                   check=True)
    return ctypes.CDLL(str(folder / "toggle.so")).toggle


def main(argv: list[str]) -> None:
    toggle = _toggle()
    from val3check.cli import main as cli_main
    from val3check.geometry import frames
    from val3check.interpretation.machine import Machine
    from val3check.interpretation.scheduler import Scheduler
    from val3check.simulation import ch10_motion
    from val3check.simulation.moving_arm import MovingArm

    stack: list[bool] = []  # is the innermost wrapped function the interpreter's
    crossings = [0]

    def wrap(fn, interp: bool):
        @functools.wraps(fn)
        def wrapper(*args, **kwargs):
            flip = (stack[-1] if stack else False) != interp
            if flip:
                toggle()
                crossings[0] += 1
            stack.append(interp)
            try:
                return fn(*args, **kwargs)
            finally:
                stack.pop()
                if flip:
                    toggle()
        return wrapper

    loop = wrap(Scheduler.loop, True)

    def loop_without_collector(*args, **kwargs):
        """The loop with the cyclic collector off: where a collection falls (inside the arm or
        not) would move the count by tens of millions."""
        enabled = gc.isenabled()
        gc.disable()
        try:
            return loop(*args, **kwargs)
        finally:
            if enabled:
                gc.enable()

    Scheduler.loop = loop_without_collector
    for name in ("advance", "next_time", "end_motion", "motion_done", "has_room", "record", "context"):
        setattr(MovingArm, name, wrap(getattr(MovingArm, name), False))
    for name in ("_point", "_tool", "_source", "_check_family"):
        setattr(ch10_motion, name, wrap(getattr(ch10_motion, name), False))
    ch10_motion.geo_frames = type("Frames", (), {"check_defined": staticmethod(wrap(frames.check_defined, False)),
                                                 "root_pose": staticmethod(frames.root_pose)})
    for name in ("loop_passes", "line_running"):
        setattr(Machine, name, wrap(getattr(Machine, name), True))
    try:
        cli_main(argv)
    except SystemExit:
        pass
    print(f"crossings into the arm and back: {crossings[0]}", file=sys.stderr)


if __name__ == "__main__":
    main(sys.argv[1:])
