"""The parsing package is made of modules with one job each, and each says what it is for in its
first line (their length: tests/test_architecture.py)."""

from __future__ import annotations

from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[2] / "val3check" / "parsing"
MODULES = sorted(p for p in PACKAGE.glob("*.py") if p.name != "_tables.py")  # _tables.py: generated


@pytest.mark.parametrize("path", MODULES, ids=lambda p: p.name)
def test_one_line_purpose(path):
    first = path.read_text(encoding="utf-8").splitlines()[0]
    assert first.startswith('"""') and len(first) > 20, f"{path.name}: one line saying what it is for"


def test_the_jobs_of_the_parser_have_their_modules():
    assert {"parser.py", "engine.py", "descent.py", "fast_lexer.py", "builder.py", "messages.py",
            "tokens.py", "grammar.py", "comments.py"} <= {p.name for p in MODULES}
