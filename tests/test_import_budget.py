"""`val3check lint` must start fast: it imports no robotics or numeric package."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
HEAVY = ("pinocchio", "trimesh", "fcl", "mcap", "numpy", "scipy", "example_robot_data", "dask", "distributed")


def test_lint_imports_nothing_heavy():
    code = (
        "import sys, runpy\n"
        "sys.argv = ['val3check', 'lint', 'fixtures/valid/Cell', '--format', 'json']\n"
        "try:\n    runpy.run_module('val3check', run_name='__main__')\nexcept SystemExit:\n    pass\n"
        f"heavy = sorted(m for m in sys.modules if m.split('.')[0] in {HEAVY!r})\n"
        "print('HEAVY', heavy, file=sys.stderr)\n"
    )
    r = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert "HEAVY []" in r.stderr, r.stderr


def test_lint_process_runs_without_the_cyclic_collector_and_main_leaves_it_alone(tmp_path):
    """`val3check lint` as a process keeps the collector off to the end and freezes what is left
    (cli._short_lived); `main(argv)` called by another program leaves its collector as it was."""
    code = (
        "import gc, sys, runpy\n"
        "sys.argv = ['val3check', 'lint', 'fixtures/valid/Cell']\n"
        "try:\n    runpy.run_module('val3check', run_name='__main__')\nexcept SystemExit:\n    pass\n"
        "print('GC', gc.isenabled(), gc.get_freeze_count() > 0, file=sys.stderr)\n"
        "from val3check.cli import main\n"
        "gc.enable()\n"
        "main(['lint', 'fixtures/valid/Cell'])\n"
        "print('MAIN', gc.isenabled(), file=sys.stderr)\n"
    )
    r = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert "GC False True" in r.stderr, r.stderr
    assert "MAIN True" in r.stderr, r.stderr


def test_lint_leaves_out_what_it_does_not_use():
    """Not the sim command's module, nor shutil (bz2, lzma) for argparse's terminal width, nor json
    unless an s8 application has user pages (cli._terminal_columns, loading.bindings), nor typing
    (annotations only: `if TYPE_CHECKING`), nor difflib unless a name is not found."""
    code = (
        "import sys, runpy\n"
        "sys.argv = ['val3check', 'lint', 'fixtures/valid/Cell']\n"
        "try:\n    runpy.run_module('val3check', run_name='__main__')\nexcept SystemExit:\n    pass\n"
        "print('LOADED', sorted(m for m in ('val3check.cli.sim_command', 'shutil', 'bz2', 'lzma', 'json',"
        " 'typing', 'difflib')"
        " if m in sys.modules), file=sys.stderr)\n"
    )
    r = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert "LOADED []" in r.stderr, r.stderr
