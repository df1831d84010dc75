"""motion/ is pure: it stands on robot, geometry and language only (and loading for the static
reach check); interpretation never imports it, and it imports nothing of interpretation, the
simulation or the reports (the adapters where the interpreter meets motion are in simulation/)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_motion_imports_no_interpreter():
    modules = sorted(".".join(p.relative_to(ROOT).with_suffix("").parts).removesuffix(".__init__")
                     for p in (ROOT / "val3check" / "motion").rglob("*.py"))
    assert "val3check.motion.queue" in modules and "val3check.motion.timing" in modules
    code = ("import sys, importlib\n"
            f"for m in {modules!r}:\n    importlib.import_module(m)\n"
            "bad = sorted(m for m in sys.modules if m.split('.')[:2] in (['val3check', 'interpretation'],"
            " ['val3check', 'simulation'], ['val3check', 'reporting'], ['val3check', 'collision']))\n"
            "print('BAD', bad)\n")
    r = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert "BAD []" in r.stdout, r.stdout + r.stderr


def test_interpretation_does_not_import_motion():
    """(Every package's imports are checked against the layers by tests/test_architecture.py.)"""
    import ast

    for path in (ROOT / "val3check" / "interpretation").rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom):
                target = node.module or ""
                assert not (target.startswith("val3check.motion") or node.level and target.startswith("motion")
                            or node.level >= 2 and target.split(".")[0] == "motion"), (path, node.lineno)
            elif isinstance(node, ast.Import):
                assert not any(a.name.startswith("val3check.motion") for a in node.names), (path, node.lineno)
