"""The parsing package stays made of small modules with one job (the brief: no hand-written module
over 600 lines; each says what it is for in its first line)."""

from __future__ import annotations

from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[2] / "val3check" / "parsing"
GENERATED = {"_tables.py"}
MODULES = sorted(p for p in PACKAGE.glob("*.py") if p.name not in GENERATED)


@pytest.mark.parametrize("path", MODULES, ids=lambda p: p.name)
def test_small_module_with_a_purpose(path):
    text = path.read_text(encoding="utf-8")
    assert text.count("\n") <= 600, f"{path.name}: split it by job"
    first = text.splitlines()[0]
    assert first.startswith('"""') and len(first) > 20, f"{path.name}: one line saying what it is for"


def test_the_split_modules_exist():
    assert {"parser.py", "engine.py", "descent.py", "fast_lexer.py", "builder.py", "messages.py",
            "tokens.py", "grammar.py", "comments.py"} <= {p.name for p in MODULES}
