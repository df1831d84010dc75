"""The motion core stands on robot, geometry and language only: interpretation never imports it,
and it imports nothing of interpretation (the errors module comes in through geometry)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_motion_imports_no_interpreter():
    code = ("import sys\n"
            "import val3check.motion.queue, val3check.motion.records, val3check.motion.cycle, val3check.motion.reach\n"
            "bad = sorted(m for m in sys.modules if m.startswith('val3check.interpretation')"
            " and m not in ('val3check.interpretation', 'val3check.interpretation.errors'))\n"
            "print('BAD', bad)\n")
    r = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert "BAD []" in r.stdout, r.stdout + r.stderr


def test_interpretation_does_not_import_motion():
    for path in (ROOT / "val3check" / "interpretation").rglob("*.py"):
        text = path.read_text(encoding="utf-8")
        assert "from ..motion" not in text and "val3check.motion" not in text, path
