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
