"""One length-unit module (issue 22): the inch, the metre and the application's unit are converted
with the constants of `val3check/lengths.py`, never with a literal of their own."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from val3check import lengths

PACKAGE = Path(__file__).resolve().parent.parent / "val3check"
# Packages whose 1000 is always a metre: the URDF and pinocchio are in metres, VAL 3 in millimetres.
METRE_PACKAGES = ("robot",)


def _numbers(path: Path) -> list[tuple[float, int]]:
    return [(n.value, n.lineno) for n in ast.walk(ast.parse(path.read_text(encoding="utf-8")))
            if isinstance(n, ast.Constant) and type(n.value) in (int, float)]


def test_the_units():
    assert lengths.INCH_MM == 25.4 and lengths.M_MM * lengths.MM_M == 1.0
    assert lengths.app_mm(True) == 1.0 and lengths.app_mm(False) == 25.4


@pytest.mark.parametrize("value", [25.4, 0.0254, 1 / 25.4])
def test_no_inch_written_twice(value):
    bad = [f"{p.relative_to(PACKAGE)}:{line}" for p in PACKAGE.rglob("*.py") if p.name != "lengths.py"
           for v, line in _numbers(p) if v == value]
    assert bad == []


def _scalings(path: Path, values: tuple[float, ...]) -> list[int]:
    """Lines of `x * v` or `x / v` for a literal v of `values`, or `v if ... else ...` (a scale)."""
    out = []
    for n in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        operands = [n.left, n.right] if isinstance(n, ast.BinOp) and isinstance(n.op, (ast.Mult, ast.Div)) else \
            [n.body, n.orelse] if isinstance(n, ast.IfExp) else []
        if any(isinstance(o, ast.Constant) and o.value in values for o in operands):
            out.append(n.lineno)
    return out


def test_no_metre_converted_by_hand():
    bad = [f"{p.relative_to(PACKAGE)}:{line}" for package in METRE_PACKAGES for p in (PACKAGE / package).rglob("*.py")
           for line in _scalings(p, (1000, 0.001))]
    assert bad == []


def test_each_unit_is_defined_once():
    names = {"INCH_MM", "M_MM", "MM_M", "MM"}
    bad = [f"{p.relative_to(PACKAGE)}:{n.lineno}" for p in PACKAGE.rglob("*.py") if p.name != "lengths.py"
           for n in ast.walk(ast.parse(p.read_text(encoding="utf-8"))) if isinstance(n, ast.Assign)
           and any(isinstance(t, ast.Name) and t.id in names for t in n.targets)]
    assert bad == []
