"""Parse-only benchmark: lines per second on a generated, realistic VAL 3 program.

    python bench/bench_parse.py [--lines N | --app] [--repeat R] [--profile] [--engine-only]

Prints the parser construction time (first use), then the CPU time and lines per CPU second of
R parses (best of R, default 5) of an N-line program (default 20,000 lines), for the parser as it
runs (the recursive-descent fast path; the LALR engine for code with errors) and for the LALR
engine alone (the parser before the fast path), alternating, with the cyclic garbage collector
off while timing (as during a parse). `--app`: the programs of the generated application that
bench_lint_process.py lints, in place of the one program. `--engine-only`: the engine alone.
"""

from __future__ import annotations

import argparse
import gc
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

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


def app_programs() -> list[tuple[str, object, str]]:
    """(code, source map, path) of every program of the application bench_lint_process.py lints
    (bench/generate.py, written into a temporary folder and loaded as lint loads it)."""
    import tempfile
    from pathlib import Path

    from generate import generate

    from val3check.loading import load

    with tempfile.TemporaryDirectory() as tmp:
        generate(Path(tmp) / "BigApp")
        ws, _ = load([tmp])
    return [(p.code, p.code_map, p.origin.path) for app in ws.apps.values() for p in app.programs.values()
            if p.code is not None]


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--lines", type=int, default=20000)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--profile", action="store_true")
    ap.add_argument("--engine-only", action="store_true")
    ap.add_argument("--app", action="store_true", help="the programs of bench_lint_process.py's application")
    args = ap.parse_args()

    t0 = time.perf_counter()
    from val3check.parsing import parser as P
    from val3check.positions import SourceMap

    t1 = time.perf_counter()
    engine = P.get_engine()
    t2 = time.perf_counter()
    print(f"import val3check.parsing.parser: {1000 * (t1 - t0):.1f} ms (lark imported lazily)")
    print(f"parser construction (first use, lark import included): {1000 * (t2 - t1):.1f} ms")

    if args.app:
        inputs = app_programs()
        what = f"the generated application ({len(inputs)} programs)"
    else:
        code = make_program(args.lines)
        inputs = [(code, SourceMap.identity(code, first_line=10, first_col=20), "bench.pgx")]
        what = "one program"
    n = sum(code.count("\n") + 1 for code, _, _ in inputs)
    chars = sum(len(code) for code, _, _ in inputs)
    descent = engine.descent
    if args.engine_only:
        engine.descent = None
    if args.profile:
        import cProfile
        import pstats

        cProfile.runctx("for c, sm, path in inputs: P.parse_code(c, sm, path)", globals(), locals(),
                        "/tmp/bench_parse.prof")
        pstats.Stats("/tmp/bench_parse.prof").sort_stats("tottime").print_stats(25)
        return 0
    paths = [("engine alone", None)] if args.engine_only else [("parser", descent), ("engine alone", None)]
    best = {label: float("inf") for label, _ in paths}
    trees: dict = {}
    for _ in range(args.repeat):  # the paths alternate: a busy neighbour slows both alike
        for label, fast in paths:
            engine.descent = fast
            trees.pop(label, None)
            gc.collect()
            gc.disable()  # the parser's time, not the collector's passes over earlier trees
            t = time.process_time()
            results = [P.parse_code(code, sm, path) for code, sm, path in inputs]
            best[label] = min(best[label], time.process_time() - t)
            gc.enable()
            assert all(body is not None and not diags for body, diags in results), results[0][1][:3]
            trees[label] = results
    engine.descent = descent
    print(f"{what}: {n:,} code lines, {chars:,} characters; CPU time, best of {args.repeat}:")
    for label, _ in paths:
        print(f"  {label:13} {1000 * best[label]:5.0f} ms = {n / best[label]:,.0f} lines per CPU second")
    if len(paths) == 2:
        assert trees["parser"] == trees["engine alone"]
        print(f"  speed-up {best['engine alone'] / best['parser']:.2f}x (same trees)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
