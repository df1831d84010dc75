"""Every output of `val3check sim` on the bundled examples, written into one folder, so that a
refactoring can be held byte for byte against the outputs of main (issue 22):

    python bench/sim_outputs.py /tmp/before      # on main
    python bench/sim_outputs.py /tmp/after       # on the branch
    python bench/sim_outputs.py --compare /tmp/before /tmp/after

Each case writes its reports (text, JSON, HTML, JUnit), its MCAP trace, its standard output and
error and its exit code; the sweep writes its --out-dir tree with every case report. Paths in the
outputs are relative to the repository (the commands run there), so two checkouts compare equal.
Every run is given budgets that never cut (UNBOUNDED): under load, the default 60 s wall budget
cut a case's collision checks at a different motion in each run, and the outputs differed for
that reason alone.
"""

from __future__ import annotations

import argparse
import filecmp
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

PICK = ["fixtures/valid/PickPlace", "--scenario", "fixtures/scenarios/pickplace.toml"]
# (name, arguments, report kinds, with a trace)
CASES = [
    ("pickplace-tx2-60", PICK + ["--robot", "tx2-60"], ("json", "html", "junit", "text"), True),
    ("pickplace-tx2-60-nocell", PICK + ["--robot", "tx2-60", "--cell", "none"], ("json", "html", "text"), True),
    ("pickplace-tx2-60-cycles2", PICK + ["--robot", "tx2-60", "--cycles", "2"], ("json", "text"), False),
    ("pickplace-tx2-90", PICK + ["--robot", "tx2-90", "--duration", "20"], ("json", "html", "text"), True),
    ("pickplace-ts2-60", PICK + ["--robot", "ts2-60", "--duration", "20"], ("json", "html", "text"), True),
    ("pickplace-norobot", PICK + ["--robot", "none", "--duration", "20"], ("json", "html", "text"), True),
    ("cell-tx2-60", ["fixtures/valid/Cell", "--scenario", "fixtures/scenarios/cell.toml", "--robot", "tx2-60",
                     "--duration", "20"], ("json", "html", "junit", "text"), True),
    ("welder", ["fixtures/valid/controller/usr/usrapp/Welder", "--duration", "20"], ("json", "html", "text"), True),
    ("supervisor", ["fixtures/valid/Supervisor", "--duration", "5"], ("json", "text"), False),
    ("sorter", ["fixtures/valid/Sorter", "--duration", "5"], ("json", "text"), False),
    ("pallet", ["fixtures/valid/Pallet", "--duration", "5"], ("json", "text"), False),
    ("doc-pick", ["docs/examples/Cell/Apps/Pick", "--robot", "tx2-60", "--duration", "5"], ("json", "html", "text"),
     True),
]
UNBOUNDED = ["--max-wall", "3600", "--max-memory", "4096"]
SWEEP = ["--sweep", "fixtures/sweeps/pickplace.toml", "--duration", "20", "-j", "2",
         "--case-reports", "json,html,trace"]


def _run(args: list[str], out: Path, name: str) -> None:
    r = subprocess.run([sys.executable, "-m", "val3check", "sim", *args, *UNBOUNDED], check=False, cwd=ROOT, capture_output=True,
                       env={**os.environ, "NO_COLOR": "1", "COLUMNS": "100"})
    here = str(out).encode()  # the output folder's name is not part of the output
    (out / f"{name}.stdout").write_bytes(r.stdout.replace(here, b"OUT"))
    (out / f"{name}.stderr").write_bytes(r.stderr.replace(here, b"OUT"))
    (out / f"{name}.rc").write_text(f"{r.returncode}\n")


def generate(out: Path, only: str | None = None) -> None:
    """Run every case (those whose name contains `only`) into `out` (created)."""
    out = out.resolve()
    out.mkdir(parents=True, exist_ok=True)
    for name, args, kinds, trace in CASES:
        if only is not None and only not in name:
            continue
        for i, kind in enumerate(kinds):
            extra = ["--report", kind, "-o", str(out / f"{name}.{kind}")]
            if trace and i == 0:
                extra += ["--trace", str(out / f"{name}.mcap")]
            _run(args + extra, out, f"{name}.{kind}")
        print(name, flush=True)
    if only is None or only in "sweep":
        _run(SWEEP + ["--out-dir", str(out / "sweep")], out, "sweep")
        print("sweep", flush=True)


def compare(a: Path, b: Path, subset: bool = False) -> int:
    """Print every file that differs or exists on one side only (`subset`: only b's files are
    compared, b holding some of the cases); 1 when any does."""
    bad = 0
    names = {p.relative_to(b) for p in b.rglob("*") if p.is_file()}
    if not subset:
        names |= {p.relative_to(a) for p in a.rglob("*") if p.is_file()}
    names = sorted(names)
    for rel in names:
        pa, pb = a / rel, b / rel
        if not pa.exists() or not pb.exists():
            print(f"only in {'b' if pb.exists() else 'a'}: {rel}")
            bad = 1
        elif not filecmp.cmp(pa, pb, shallow=False):
            print(f"differs: {rel}")
            bad = 1
    print(f"{len(names)} files compared: {'differences' if bad else 'identical'}")
    return bad


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--compare", action="store_true", help="compare two folders written by this script")
    ap.add_argument("--only", help="only the cases whose name contains this")
    ap.add_argument("folders", nargs="+", type=Path)
    a = ap.parse_args()
    if a.compare:
        return compare(*a.folders, subset=a.only is not None)
    generate(a.folders[0], a.only)
    return 0


if __name__ == "__main__":
    sys.exit(main())
