"""Parse-only benchmark: lines per second on a generated, realistic VAL 3 program.

    python bench/bench_parse.py [--lines N] [--repeat R] [--profile]

Prints the parser construction time (first use), then lines/s for R parses of an N-line
program (default 20,000 lines, best of 3).
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
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--profile", action="store_true")
    args = ap.parse_args()

    t0 = time.perf_counter()
    from val3check.parsing import parser as P
    from val3check.positions import SourceMap

    t1 = time.perf_counter()
    P.get_engine()
    t2 = time.perf_counter()
    print(f"import val3check.parsing.parser: {1000 * (t1 - t0):.1f} ms (lark imported lazily)")
    print(f"parser construction (first use, lark import included): {1000 * (t2 - t1):.1f} ms")

    code = make_program(args.lines)
    n = code.count("\n")
    sm = SourceMap.identity(code, first_line=10, first_col=20)
    if args.profile:
        import cProfile
        import pstats

        cProfile.runctx("P.parse_code(code, sm, 'bench.pgx')", globals(), locals(), "/tmp/bench_parse.prof")
        pstats.Stats("/tmp/bench_parse.prof").sort_stats("tottime").print_stats(25)
        return 0
    best = float("inf")
    for _ in range(args.repeat):
        t = time.perf_counter()
        body, diags = P.parse_code(code, sm, "bench.pgx")
        best = min(best, time.perf_counter() - t)
        assert body is not None and not diags, diags[:3]
    print(f"{n} lines, {len(code)} chars: best {1000 * best:.0f} ms = {n / best:,.0f} lines/s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
