"""Recall of the compiler checks on planted errors, and precision on the unmutated inputs (issue 3).

For every application of the valid fixtures (and of /tmp/realapps when that folder exists: real
public applications collected locally, not part of the repository), `plant.py` makes mutants
with ONE known error each; every mutant is linted in-process and counts as found when a finding
with the expected code and severity is at the planted line and column of the mutated file.

Run:  python bench/bench_recall.py [--per-kind N] [--seed S] [--root DIR ...] [--misses]
Writes only into a temporary folder (a copy of each root); the inputs are never modified.
"""

from __future__ import annotations

import argparse
import os
import shutil
import sys
import tempfile
import time
from collections import Counter, defaultdict
from dataclasses import dataclass, field
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
sys.path.insert(0, str(HERE))

from plant import KINDS, Mutant, plant_workspace  # noqa: E402

from val3check.config import Settings  # noqa: E402
from val3check.diagnostics import Severity  # noqa: E402
from val3check.lint import run  # noqa: E402
from val3check.loading import load  # noqa: E402

FIXTURES = HERE.parent / "fixtures" / "valid"
REALAPPS = Path("/tmp/realapps")


@dataclass
class Outcome:
    mutant: Mutant
    found: bool
    reported: str = ""  # what was reported instead, for misses
    bad: bool = False  # the mutated file did not read back as planned (a bug of plant.py)


@dataclass
class RootResult:
    root: str
    precision_errors: list = field(default_factory=list)  # error findings on the unmutated input
    outcomes: list[Outcome] = field(default_factory=list)
    apps: int = 0
    skipped_files: int = 0


def real_path(path: str) -> str:
    return os.path.realpath(os.path.abspath(path))


def _errors(diags) -> list:
    return [d for d in diags if d.severity is not None and d.severity >= Severity.ERROR]


def bench_root(root: Path, per_kind: int | None, seed: int, clean_only: bool) -> RootResult:
    root_s = real_path(str(root))
    res = RootResult(root=str(root))
    base = run([root_s], Settings())
    res.precision_errors = _errors(base.result.diagnostics)
    dirty = {real_path(d.path) for d in res.precision_errors} if clean_only else set()
    ws, _ = load([root_s])
    with tempfile.TemporaryDirectory(prefix="val3recall-") as tmp:
        copy = os.path.join(tmp, os.path.basename(root_s))
        shutil.copytree(root_s, copy, symlinks=True)
        # An application folder given alone: its libraries (Disk://) are next to the original.
        settings = Settings()
        if any(name.lower().endswith(".pjx") for name in os.listdir(root_s)):
            settings = Settings(disk_roots=[os.path.dirname(root_s)])
        for key in sorted(ws.targets):
            app = ws.apps[key]
            if not real_path(app.path).startswith(root_s + os.sep):
                continue
            res.apps += 1
            res.skipped_files += sum(1 for p in app.programs.values() if real_path(p.origin.path) in dirty)
            mutants = plant_workspace(ws, app, per_kind=per_kind, seed=seed, skip_files=dirty)
            app_copy = os.path.join(copy, os.path.relpath(real_path(app.path), root_s))
            for m in mutants:
                res.outcomes.append(lint_mutant(m, root_s, copy, app_copy, settings))
    return res


def lint_mutant(m: Mutant, root: str, copy: str, app_copy: str, settings: Settings) -> Outcome:
    dest = os.path.join(copy, os.path.relpath(real_path(m.path), root))
    with open(dest, "rb") as f:
        original = f.read()
    try:
        with open(dest, "w", encoding=m.encoding, errors="surrogateescape", newline="") as f:
            f.write(m.text)
        outcome = run([app_copy], settings)
    finally:
        with open(dest, "wb") as f:
            f.write(original)
    # The mutated program must read back as planned.
    app = outcome.workspace.apps.get(os.path.abspath(app_copy))
    prog = app.programs.get(m.program) if app is not None else None
    if prog is None or prog.code != m.mutated_code:
        return Outcome(m, False, "mutated file did not read back as planned", bad=True)
    at = prog.code_map.to_file(m.code_line, m.code_col) if m.code_line else None
    if at is not None and (at.line, at.col) != (m.line, m.col):
        return Outcome(m, False, f"expected position {m.line}:{m.col} but the code maps to {at.line}:{at.col}",
                       bad=True)
    want = Severity.parse(m.severity)
    here = [d for d in outcome.result.diagnostics if real_path(d.path) == real_path(dest)]
    for d in here:
        if d.code == m.code and d.line == m.line and d.col == m.col and d.severity == want:
            return Outcome(m, True)
    same_line = [f"{d.code}@{d.col}[{d.severity.label}]" for d in here if d.line == m.line]
    same_code = [f"{d.code}@{d.line}:{d.col}" for d in here if d.code == m.code and d.line != m.line]
    what = ", ".join(same_line) or "nothing on the line"
    if same_code:
        what += "; " + m.code + " elsewhere: " + ", ".join(same_code[:3])
    return Outcome(m, False, what)


def report(res: RootResult, show_misses: bool) -> tuple[int, int]:
    print(f"\n== {res.root}: {res.apps} applications, {len(res.outcomes)} mutants"
          + (f", {res.skipped_files} programs skipped (error findings before mutation)" if res.skipped_files else ""))
    per = defaultdict(lambda: [0, 0])
    bad = [o for o in res.outcomes if o.bad]
    for o in res.outcomes:
        if o.bad:
            continue
        per[o.mutant.kind][0] += 1
        per[o.mutant.kind][1] += o.found
    print(f"{'kind':34} {'code':5} {'planted':>7} {'found':>6} {'recall':>7}")
    total = found = 0
    for kind in KINDS:
        n, k = per.get(kind, (0, 0))
        total += n
        found += k
        rate = f"{100 * k / n:6.1f}%" if n else "     -"
        print(f"{kind:34} {KINDS[kind][0]:5} {n:7} {k:6} {rate}")
    rate = f"{100 * found / total:6.1f}%" if total else "     -"
    print(f"{'overall':40} {total:7} {found:6} {rate}")
    if bad:
        print(f"{len(bad)} mutants did not read back as planned (plant.py bug): not counted")
    errs = res.precision_errors
    counts = Counter(d.code for d in errs)
    print(f"precision: {len(errs)} error-severity findings on the unmutated input"
          + (f" ({', '.join(f'{c} x{n}' for c, n in sorted(counts.items()))})" if errs else ""))
    misses = [o for o in res.outcomes if not o.found]
    if show_misses and misses:
        print("misses:")
        for o in misses:
            m = o.mutant
            print(f"  {m.kind} {m.code} {os.path.relpath(m.path, real_path(res.root))}:{m.line}:{m.col}: "
                  f"{m.before!r} -> {m.after!r}: {o.reported}")
    return total, found


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--per-kind", type=int, default=10, help="mutants per kind and application (0: every site)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--root", action="append", help="folder of applications (default: fixtures/valid, /tmp/realapps)")
    ap.add_argument("--misses", action="store_true", help="list every miss (default: when at most 60)")
    args = ap.parse_args(argv)
    roots: list[tuple[Path, bool]] = []
    if args.root:
        roots = [(Path(r), True) for r in args.root]
    else:
        roots.append((FIXTURES, False))
        if REALAPPS.is_dir():
            roots.append((REALAPPS, True))
    t0 = time.perf_counter()
    fixture_errors = 0
    for root, clean_only in roots:
        res = bench_root(root, args.per_kind or None, args.seed, clean_only)
        misses = sum(1 for o in res.outcomes if not o.found)
        report(res, args.misses or misses <= 60)
        if root == FIXTURES:
            fixture_errors = len(res.precision_errors)
    print(f"\n{time.perf_counter() - t0:.1f} s")
    return 1 if fixture_errors else 0


if __name__ == "__main__":
    sys.exit(main())
