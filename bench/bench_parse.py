"""Parse-only benchmark: lines per second on a generated, realistic VAL 3 program.

    python bench/bench_parse.py [--lines N] [--repeat R] [--profile] [--engine-only]

Prints the parser construction time (first use), then the CPU time and lines per CPU second of
R parses of an N-line program (default 20,000 lines, best of R = 5), for the parser as it runs
(the recursive-descent fast path, the LALR engine for code with errors) and for the LALR engine
alone (the parser before the fast path). `--engine-only`: the engine alone, for profiling it.
"""

from __future__ import annotations

import argparse
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

BLOCK = """\
  // pick the part {i} and place it on the pallet
  nIndex = nIndex + 1
  if (nIndex >= size(pPallet)) or bReset
    nIndex = 0
    putln("pallet full: " + toString("", nCount))
  elseIf nIndex == 3
    call logEvent("third", nIndex)
  else
    nCount = nCount + 1
  endIf
  for l_i = 0 to nRows - 1 step 1
    for l_j = 0 to nCols - 1
      pTarget.trsf.x = l_i * nPitchX + trOffset.x
      pTarget.trsf.y = l_j * nPitchY - trOffset.y
      movej(appro(pTarget, {{0, 0, -50, 0, 0, 0}}), tGripper, mFast)
      movel(pTarget, tGripper, mSlow)
      waitEndMove()
      call gripper:close(tGripper)
    endFor
  endFor
  while !isSettled() and (nTimeout > 0)
    delay(0.05)
    nTimeout = nTimeout - 0.05
  endWhile
  switch nMode
    case 1, 2
      sMsg = "manual"
    break
    case 3
      sMsg = "auto"
    break
    default
      sMsg = "unknown"
    break
  endSwitch
  do
    nKey = get()
  until (nKey == 270) or (nKey == 271)
  pPlace[l_k] = compose(pPlace[0], fPallet, {l_k * 10.5, 0, 0, 0, 0, 0})
  jDest = {90, -45.5, 1e2, 0, .5, 0}
  bOk = (nErr == 0) xor bForce
  nDist = distance(here(tGripper, world), pTarget) // mm
  $movejSyncState()
"""


def make_program(n_lines: int) -> str:
    out = ["begin"]
    i = 0
    while len(out) < n_lines - 1:
        out.extend(BLOCK.replace("{i}", str(i)).splitlines())
        i += 1
    out.append("end")
    return "\n".join(out) + "\n"


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--lines", type=int, default=20000)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--profile", action="store_true")
    ap.add_argument("--engine-only", action="store_true")
    args = ap.parse_args()

    t0 = time.perf_counter()
    from val3check.parsing import parser as P
    from val3check.positions import SourceMap

    t1 = time.perf_counter()
    engine = P.get_engine()
    t2 = time.perf_counter()
    print(f"import val3check.parsing.parser: {1000 * (t1 - t0):.1f} ms (lark imported lazily)")
    print(f"parser construction (first use, lark import included): {1000 * (t2 - t1):.1f} ms")

    code = make_program(args.lines)
    n = code.count("\n")
    sm = SourceMap.identity(code, first_line=10, first_col=20)
    descent = engine.descent
    if args.engine_only:
        engine.descent = None
    if args.profile:
        import cProfile
        import pstats

        cProfile.runctx("P.parse_code(code, sm, 'bench.pgx')", globals(), locals(), "/tmp/bench_parse.prof")
        pstats.Stats("/tmp/bench_parse.prof").sort_stats("tottime").print_stats(25)
        return 0
    paths = [("engine alone", None)] if args.engine_only else [("parser", descent), ("engine alone", None)]
    best = {label: float("inf") for label, _ in paths}
    trees = {}
    for _ in range(args.repeat):  # the paths alternate: a busy neighbour slows both alike
        for label, fast in paths:
            engine.descent = fast
            t = time.process_time()
            body, diags = P.parse_code(code, sm, "bench.pgx")
            best[label] = min(best[label], time.process_time() - t)
            assert body is not None and not diags, diags[:3]
            trees[label] = body
    engine.descent = descent
    print(f"{n} lines, {len(code)} chars, CPU time, best of {args.repeat}:")
    for label, _ in paths:
        print(f"  {label:13} {1000 * best[label]:5.0f} ms = {n / best[label]:,.0f} lines per CPU second")
    if len(paths) == 2:
        assert trees["parser"] == trees["engine alone"]
        print(f"  speed-up {best['engine alone'] / best['parser']:.2f}x (same tree)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
