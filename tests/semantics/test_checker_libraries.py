"""L codes: library interfaces (chapter 6) and user types (chapter 7), on copies of the fixtures."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from .checkhelp import collect

FIXTURES = Path(__file__).resolve().parents[2] / "fixtures" / "valid"


@pytest.fixture()
def tree(tmp_path):
    for name in ("Cell", "CellLib", "Sorter", "Part"):
        shutil.copytree(FIXTURES / name, tmp_path / name)
    return tmp_path


def _plant(path: Path, before: str, lines: str) -> None:
    text = path.read_text(encoding="utf-8-sig")
    assert before in text
    path.write_text(text.replace(before, lines + before, 1), encoding="utf-8")


def test_fixtures_are_clean(tree):
    assert collect(tree / "Cell") == []
    assert collect(tree / "Sorter") == []


def test_library_interface(tree):
    _plant(tree / "Cell" / "stop.pgx", "  putln(sState)\n",
           "  nTotal = lib:nY\n  nTotal = lib:nLogIdx\n  call lib:init()\n  call lib:nX()\n  nTotal = lib:init\n"
           "  call lib:Init(1)\n  if isDefined(lib:nZZ)\n    nTotal = lib:nCycles\n  endIf\n  call lib:nope(2)\n"
           "  nTotal = other:nX\n  call lib:init(\"x\")\n  lib:init(1)\n")
    found = [f[0] for f in collect(tree / "Cell")]
    assert found == ["L010", "L011", "T005", "L012", "L012", "N006", "L010", "N005", "T006", "T018"]


def test_user_type_fields(tree):
    _plant(tree / "Sorter" / "stop.pgx", "  bRunning = false\n",
           "  part.nWeigth = 1\n  part.nRevision = 2\n  l_nVal = part.nDims[1] + part.trGrip.z\n  l_nVal = partBin.nWeight\n"
           "  part = partBin[1]\n  part = l_nVal\n  l_nVal = part.trGrip.q\n  insert(part.nDims[1])\n  resize(part.nDims, 1, 4)\n"
           "  if part == partBin[0]\n  endIf\n  call measure(partBin[2])\n  call measure(l_nVal)\n")
    found = [f[0] for f in collect(tree / "Sorter")]
    assert found == ["L013", "L013", "T025", "T003", "T012", "T001", "T006"]  # partBin: a 1-D array of several values


def test_unresolved_library_and_type_are_not_checked(tree):
    shutil.rmtree(tree / "CellLib")
    shutil.rmtree(tree / "Part")
    _plant(tree / "Cell" / "stop.pgx", "  putln(sState)\n", "  nTotal = lib:anything + 1\n  call lib:whatever(1, 2)\n")
    _plant(tree / "Sorter" / "stop.pgx", "  bRunning = false\n", "  part.anything = 3\n  l_nVal = part.x.y\n")
    assert collect(tree / "Cell") == []
    assert collect(tree / "Sorter") == []


def test_library_system_instruction_is_not_an_interface_symbol(tmp_path):
    from support import lint

    from val3check.testing import write_app

    write_app(tmp_path, "begin\nend", name="Lib")
    app = write_app(tmp_path, "begin\n  lib:$libOpen()\n  nX = lib:$count(1)\n  nX = lib:nMissing\nend",
                    name="App", globals_=["num nX"])
    pjx = app / "App.pjx"
    pjx.write_text(pjx.read_text().replace(
        "<Libraries />", '<Libraries>\n    <Library alias="lib" path="Disk://Lib/Lib.pjx" />\n  </Libraries>'))
    found = [(d.code, d.line) for d in lint([app], cwd=tmp_path).result.diagnostics if d.code[0] in "FLNT"]
    assert found == [("L010", 7)]  # only the data symbol that really is missing
