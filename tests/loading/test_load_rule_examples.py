"""The catalogue examples of the loader's rules (F001-F011, L001-L005) behave, at load level.

The project-wide example runner lints each example with the whole tool; this test checks the
part the loader owns, so that a loader change that breaks an example fails here first.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from val3check.loading import load
from val3check.rules.catalogue import load_rule

RULES = Path(__file__).resolve().parents[2] / "rules"
LOADER_CODES = [f"F{n:03d}" for n in range(1, 12)] + [f"L{n:03d}" for n in range(1, 6)]
NO_BAD_EXAMPLE = {"F002", "F003"}  # need a >16 MB file / invalid bytes: see the explanations


def _examples():
    for code in LOADER_CODES:
        rule = load_rule(RULES / f"{code}.toml")
        for kind, examples in (("bad", rule.bad), ("good", rule.good)):
            for i, ex in enumerate(examples):
                yield pytest.param(code, kind, ex, id=f"{code}-{kind}{i}")


def _run(tmp_path: Path, code: str, ex) -> list[str]:
    for rel, text in ex.files.items():
        p = tmp_path / rel
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text, encoding="utf-8")
    target = os.path.normpath(tmp_path / ex.target)
    ws, diags = load([target])
    out = []
    for d in diags:
        if d.code == code:
            out.append(f"{Path(os.path.relpath(d.path, tmp_path)).as_posix()}:{d.line}:{d.col}")
    return sorted(out)


@pytest.mark.parametrize("code", LOADER_CODES)
def test_every_rule_has_examples(code):
    rule = load_rule(RULES / f"{code}.toml")
    assert rule.good
    assert rule.bad or code in NO_BAD_EXAMPLE


@pytest.mark.parametrize("code, kind, ex", list(_examples()))
def test_example(tmp_path, code, kind, ex):
    got = _run(tmp_path, code, ex)
    if kind == "bad":
        assert got == sorted(ex.expect)
    else:
        assert got == []
