"""The collision package stays readable (issue 22): small modules, imports one way."""

from __future__ import annotations

import ast
import graphlib
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[2] / "val3check" / "collision"


def _imports(path: Path) -> set[str]:
    """The modules of the collision package a module imports (relative imports)."""
    out = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and node.level == 1:
            if node.module:
                out.add(node.module.split(".")[0])
            else:
                out.update(a.name for a in node.names)
    return out


def test_no_module_over_600_lines():
    long = {p.name: n for p in PACKAGE.glob("*.py") if (n := len(p.read_text(encoding="utf-8").splitlines())) > 600}
    assert long == {}


def test_no_import_cycle_in_the_collision_package():
    graph = {p.stem: _imports(p) for p in PACKAGE.glob("*.py") if p.stem != "__init__"}
    order = list(graphlib.TopologicalSorter(graph).static_order())  # CycleError on a cycle
    assert "checker" in order
    # only the package itself puts the checker together
    assert not [m for m, deps in graph.items() if "checker" in deps]
