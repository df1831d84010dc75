"""The bytecodes each function of the interpreter runs during `Scheduler.loop` (issue 29): a
load-free count by function, to find where the interpreter's share of a cycle goes (callgrind's
counts, bench/interp_instructions.py, have no Python names). Tracing slows the run about 30x:

    python bench/interp_opcodes.py 120      # the bundled pick-and-place, 120 simulated seconds

Prints the total and the 45 functions that run the most bytecodes, with their calls (a
generator's resumptions count as calls). A bytecode is not an instruction: a call into C (math,
numpy, a frame's locals) is one bytecode; compare with the instruction counts.
"""

from __future__ import annotations

import collections
import re
import sys

WATCHED = re.compile(r"interpretation/|ch09|ch10_motion|<val3|geometry/|io_cell|waiting|recorder|clock")


def main(duration: str) -> None:
    from val3check.cli import main as cli_main
    from val3check.interpretation.scheduler import Scheduler

    counts: collections.Counter = collections.Counter()
    calls: collections.Counter = collections.Counter()
    active = [False]

    def tracer(frame, event, arg):
        code = frame.f_code
        if not active[0] or not WATCHED.search(code.co_filename):
            return None
        key = (code.co_filename.split("val3check/")[-1], code.co_name)
        if event == "call":
            calls[key] += 1
        frame.f_trace_opcodes = True

        def local(frame, event, arg):
            if event == "opcode":
                counts[key] += 1
            return local
        return local

    loop = Scheduler.loop

    def traced_loop(self, *args, **kwargs):
        active[0] = True
        try:
            return loop(self, *args, **kwargs)
        finally:
            active[0] = False

    Scheduler.loop = traced_loop
    sys.settrace(tracer)
    try:
        cli_main(["sim", "fixtures/valid/PickPlace", "--robot", "tx2-60", "--scenario", "fixtures/scenarios/pickplace.toml",
                  "--duration", duration, "--max-wall", "3600", "--report", "text", "-o", "/dev/null"])
    except SystemExit:
        pass
    finally:
        sys.settrace(None)
    total = sum(counts.values())
    print("bytecodes in the loop's interpreter functions:", total)
    for key, n in counts.most_common(45):
        print(f"{n:9d} {n / total * 100:5.1f}%  calls {calls[key]:7d}  {key[0]}:{key[1]}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "120")
