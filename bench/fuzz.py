"""The long fuzz run (issues 9 and 21): the properties of tests/hostile/test_hostile_fuzz*.py with
fresh random inputs, round after round, for a time budget; then how many inputs each property ran
and what failed. The properties cover the XML reader, the loader and checker, the parser, `sim`,
configurations, scenarios, any TOML text, cell files, meshes, the language server, sweep files and
the batch. CI runs the same properties on 25 fixed inputs each (docs/fuzzing.md).

Run: python bench/fuzz.py --minutes 10 [--examples 200] [-k sim]   (-k language_server: the LSP server;
     -k "cell or mesh": the cell files)
     (writes only into temporary folders; exit code 1 when an input failed)
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import time
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SUITES = sorted(str(p.relative_to(ROOT)) for p in (ROOT / "tests" / "hostile").glob("test_hostile_fuzz*.py"))
_TEST = re.compile(r"::(test_\w+):")
_COUNTS = re.compile(r"- (\d+) passing, (\d+) failing, and (\d+) invalid")


def one_round(examples: int, keyword: str | None, timeout: float) -> tuple[dict, int, str]:
    env = dict(os.environ, VAL3CHECK_FUZZ_LONG="1", VAL3CHECK_FUZZ_EXAMPLES=str(examples),
               PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    cmd = [sys.executable, "-m", "pytest", *SUITES, "-q", "-p", "no:cacheprovider", "--hypothesis-show-statistics",
           "-x"]
    if keyword:
        cmd += ["-k", keyword]
    r = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True, timeout=timeout)
    stats: dict[str, tuple[int, int, int]] = {}
    name = None
    for line in r.stdout.splitlines():
        m = _TEST.search(line)
        if m:
            name = m.group(1)
            continue
        m = _COUNTS.search(line)
        if m and name:
            old = stats.get(name, (0, 0, 0))
            stats[name] = tuple(a + int(b) for a, b in zip(old, m.groups()))  # generate (and shrink) phases
    return stats, r.returncode, r.stdout + r.stderr


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--minutes", type=float, default=10.0, help="wall-clock budget (default: 10)")
    ap.add_argument("--examples", type=int, default=200, help="inputs per property and round (default: 200)")
    ap.add_argument("-k", dest="keyword", help="only the properties matching this pytest -k expression")
    args = ap.parse_args()
    deadline = time.monotonic() + args.minutes * 60
    totals: dict[str, list[int]] = defaultdict(lambda: [0, 0, 0])
    rounds, failed_output = 0, ""
    start = time.monotonic()
    while time.monotonic() < deadline and not failed_output:
        stats, code, output = one_round(args.examples, args.keyword, max(60.0, deadline - time.monotonic() + 600))
        rounds += 1
        for name, (ok, bad, invalid) in stats.items():
            t = totals[name]
            t[0] += ok
            t[1] += bad
            t[2] += invalid
        if code != 0:
            failed_output = output
        print(f"round {rounds}: {sum(s[0] for s in stats.values())} inputs passed "
              f"({time.monotonic() - start:.0f} s)", flush=True)
    elapsed = time.monotonic() - start
    print(f"\n{rounds} rounds in {elapsed / 60:.1f} min")
    width = max((len(n) for n in totals), default=10)
    for name, (ok, bad, invalid) in sorted(totals.items()):
        print(f"  {name:<{width}}  {ok:>7} passed  {bad:>3} failed  {invalid:>6} invalid (discarded by hypothesis)")
    print(f"  {'total':<{width}}  {sum(t[0] for t in totals.values()):>7} passed")
    if failed_output:
        print("\nFAILED: the falsifying input and its traceback:\n")
        print(failed_output[-20000:])
        return 1
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
