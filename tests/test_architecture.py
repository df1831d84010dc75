"""The layers of docs/architecture.md: which package may import which, read from every
module's imports (function-level and TYPE_CHECKING imports included), and the table of the
document itself; the run's reports in their own, stricter layer; no import cycle inside a
package; no private name imported from another package; nothing registers itself on import."""

from __future__ import annotations

import ast
import re
import subprocess
import sys
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parent.parent / "val3check"
ARCHITECTURE = PACKAGE.parent / "docs" / "architecture.md"

# Layer of each top-level package or module of val3check (docs/architecture.md).
LAYER_OF = {
    "": "base", "diagnostics": "base", "positions": "base", "resources": "base", "rules": "base",
    "language": "language",
    "loading": "loading",
    "parsing": "parsing",
    "semantics": "semantics",
    "light_dataclass": "base", "confine": "base", "tomlfile": "base", "tomlpos": "base", "excerpt": "base", "lengths": "base",
    "lint": "lint", "config": "lint", "suppression": "lint", "result": "lint", "exclusion": "lint", "baseline": "lint", "fixes": "lint",
    "geometry": "geometry",
    "robot": "robot",
    "interpretation": "interpretation",
    "motion": "motion", "collision": "collision",
    "simulation": "simulation",
    "reporting": "reporting",
    "batch": "batch",
    "lsp": "lsp",
    "cli": "cli", "__main__": "cli", "testing": "cli",
}
_BELOW_INTERPRETATION = {"base", "language", "loading", "parsing", "semantics", "geometry", "robot"}
_BELOW_SIMULATION = _BELOW_INTERPRETATION | {"interpretation", "motion", "collision", "lint"}
# What each layer may import (besides itself).
ALLOWED = {
    "base": set(),
    "language": {"base"},
    "loading": {"base", "language"},
    "parsing": {"base", "language", "loading"},
    "semantics": {"base", "language", "loading", "parsing"},
    "lint": {"base", "language", "loading", "parsing", "semantics"},
    "geometry": {"base", "language"},
    "robot": {"base", "language", "geometry"},
    "interpretation": _BELOW_INTERPRETATION,
    # pure: never the interpreter (its adapters are in simulation/); loading for the static reach check
    "motion": {"base", "language", "loading", "geometry", "robot"},
    "collision": _BELOW_INTERPRETATION | {"interpretation"},
    "simulation": _BELOW_SIMULATION,
    "reporting": _BELOW_SIMULATION | {"simulation"},
    # many cases of `sim`, on all cores or a cluster: runs simulations and writes their reports
    "batch": _BELOW_SIMULATION | {"simulation", "reporting"},
    # the language server: the lint pipeline and what it stands on, never the simulator
    "lsp": {"base", "language", "loading", "parsing", "semantics", "lint"},
    "cli": set(LAYER_OF.values()),
}
# The lint pipeline: what `val3check lint` may load (it installs without the sim extra).
LINT_PATH = ALLOWED["lint"] | {"lint"}

# The run's reports: a stricter layer inside reporting/. They read the run's record and nothing
# else: the base layer, the lint pipeline (display paths), the records of simulation/ and each
# other, never robot/, geometry/, motion/, collision/ or the interpreter.
RUN_REPORTS = {f"val3check.reporting.{m}" for m in (
    "sim_report", "sim_text", "sim_json", "sim_junit", "sim_collision", "sim_render", "sim_verdict", "mcap_trace",
    "progress", "thinning",
    "html.from_run", "html.from_sim", "html.page", "html.pack", "html.model", "html.series", "html.excerpts",
    "html.run_trajectory")}
RECORDS = {"val3check.simulation", "val3check.simulation.result", "val3check.simulation.arm_record"}
REPORT_HELPERS = {"val3check.reporting", "val3check.reporting._common", "val3check.reporting.junit",
                  "val3check.reporting.html"}


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _imports(path: Path) -> list[tuple[str, str | None, int]]:
    """(module imported, name imported from it or None, line) for every val3check import."""
    module = _module_name(path)
    package = module.split(".") if path.name == "__init__.py" else module.split(".")[:-1]
    out = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            out += [(a.name, None, node.lineno) for a in node.names if a.name.split(".")[0] == "val3check"]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[:len(package) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target.split(".")[0] == "val3check":
                out += [(target, a.name, node.lineno) for a in node.names]
    return out


def _modules() -> dict[str, Path]:
    return {_module_name(p): p for p in PACKAGE.rglob("*.py") if p.name != "_tables.py"}


def _top(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else ""


def _resolve(target: str, name: str | None, modules: dict[str, Path]) -> str:
    """`from val3check.x import y`: the module val3check.x.y when y is one, else val3check.x."""
    if name is not None and f"{target}.{name}" in modules:
        return f"{target}.{name}"
    return target


def test_every_module_has_a_layer():
    assert sorted({_top(m) for m in _modules()} - set(LAYER_OF)) == []


def test_imports_follow_the_layers():
    modules = _modules()
    bad = []
    for module, path in sorted(modules.items()):
        layer = LAYER_OF[_top(module)]
        for target, name, line in _imports(path):
            other = LAYER_OF.get(_top(_resolve(target, name, modules)))
            if other is not None and other != layer and other not in ALLOWED[layer]:
                bad.append(f"{path.relative_to(PACKAGE.parent)}:{line}: {layer} imports {other} ({target})")
    assert bad == []


@pytest.mark.parametrize("package", sorted(p.name for p in PACKAGE.iterdir() if (p / "__init__.py").exists()))
def test_no_import_cycle_inside_a_package(package):
    modules = _modules()
    graph: dict[str, set[str]] = {}
    for module, path in modules.items():
        if _top(module) == package:
            graph[module] = {t for t in (_resolve(tg, n, modules) for tg, n, _ in _imports(path))
                             if _top(t) == package and t != module and t in modules}
    assert graph, package
    assert _cycles(graph) == []


def test_the_run_s_reports_read_only_the_run_s_record():
    """docs/architecture.md, "run reports": what each of them imports."""
    modules = _modules()
    assert RUN_REPORTS <= set(modules) and RECORDS <= set(modules)
    allowed_layers = ALLOWED["lint"] | {"lint"}
    bad = []
    for module in sorted(RUN_REPORTS):
        for target, name, line in _imports(modules[module]):
            t = _resolve(target, name, modules)
            if t in RUN_REPORTS or t in RECORDS or t in REPORT_HELPERS or LAYER_OF.get(_top(t)) in allowed_layers:
                continue
            bad.append(f"{module}:{line}: {t}")
    assert bad == []


def test_the_run_s_reports_load_nothing_of_the_arm_s_packages():
    """At run time too: importing every run report loads no module of robot/, geometry/,
    motion/, collision/ or the interpreter (what they show of the arm is in the record)."""
    code = ("import sys, importlib\n"
            f"for m in {sorted(RUN_REPORTS)!r}:\n    importlib.import_module(m)\n"
            "print('LOADED', sorted({m.split('.')[1] for m in sys.modules if m.startswith('val3check.')}))\n")
    r = subprocess.run([sys.executable, "-c", code], check=False, cwd=PACKAGE.parent, capture_output=True, text=True,
                       timeout=60)
    line = next(x for x in r.stdout.splitlines() if x.startswith("LOADED"))
    loaded = set(eval(line[len("LOADED "):]))  # noqa: S307 - our own output
    assert "reporting" in loaded and not loaded & {"robot", "geometry", "motion", "collision", "interpretation"}


def _doc_table() -> dict[str, tuple[set[str], str]]:
    """docs/architecture.md's layer table: row name -> (names in backquotes of its packages and
    modules, `dir/` or `file.py` without the suffix; what it may also import)."""
    rows = {}
    text = ARCHITECTURE.read_text(encoding="utf-8")
    layers = text[text.index("\n## Layers\n"):text.index("\n## ", text.index("\n## Layers\n") + 1)]
    for line in layers.splitlines():
        m = re.match(r"^\| ([a-z ]+) \| (.+) \| (.+) \|$", line)
        if m and m.group(1) != "layer":
            rows[m.group(1)] = (set(re.findall(r"`((?:html/)?[a-z_]+)(?:/|\.py)`", m.group(2))), m.group(3))
    return rows


def test_the_layer_table_of_the_document_is_the_test_s():
    """docs/architecture.md's table puts each package in its layer, says what each layer may
    import (with what those may import in turn: the test's ALLOWED), and names every run report."""
    rows = _doc_table()
    row_of = {"lint": "lint pipeline", "lsp": "editor"}
    layer_of_row = {v: k for k, v in row_of.items()}
    for package, layer in LAYER_OF.items():
        if package and package != "__main__":
            assert package in rows[row_of.get(layer, layer)][0], f"docs/architecture.md: {package} not in {layer}"
    for row, (_, imports) in rows.items():
        layer = layer_of_row.get(row, row)
        if layer in ("cli", "run reports"):
            continue
        todo = [layer_of_row.get(n.strip(), n.strip()) for n in imports.split(",") if n.strip() != "–"]
        closure: set[str] = set()
        while todo:
            n = todo.pop()
            if n not in closure:
                closure.add(n)
                todo += [layer_of_row.get(x.strip(), x.strip()) for x in rows[row_of.get(n, n)][1].split(",")
                         if x.strip() != "–"]
        assert closure == ALLOWED[layer], (row, closure ^ ALLOWED[layer])
    named = {n.replace("/", ".") for n in rows["run reports"][0]}
    assert {m.removeprefix("val3check.reporting.") for m in RUN_REPORTS} <= named


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components of more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    found: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                found.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def test_the_cycle_finder_finds_cycles():
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]


def _private_imports() -> list[tuple[str, str, str, int]]:
    """(importing module, imported-from module, name, line) of every private name (`_x`)
    imported from another module (a private module, `_tables`, holds only data to import)."""
    modules = _modules()
    out = []
    for module, path in modules.items():
        for target, name, line in _imports(path):
            if name and name.startswith("_") and not name.startswith("__") and f"{target}.{name}" not in modules:
                if not target.rsplit(".", 1)[-1].startswith("_") and target != module:
                    out.append((module, target, name, line))
    return out


def _package(module: str, modules: dict[str, Path]) -> str:
    return module if modules[module].name == "__init__.py" else module.rsplit(".", 1)[0]


def test_no_private_name_is_imported_from_another_package():
    modules = _modules()
    bad = [f"{m}:{line}: {name} from {t}" for m, t, name, line in _private_imports()
           if t in modules and _package(m, modules) != _package(t, modules)]
    assert bad == []


def test_interpretation_imports_no_private_name_of_another_module():
    bad = [f"{m}:{line}: {name} from {t}" for m, t, name, line in _private_imports()
           if _top(m) == "interpretation"]
    assert bad == []


def test_lint_loads_nothing_above_the_lint_pipeline():
    """What `val3check lint` imports stays in its layers: it installs and runs without the sim
    extra (pinocchio, numpy...) and without the interpreter."""
    code = (
        "import sys, runpy\n"
        "sys.argv = ['val3check', 'lint', 'fixtures/valid/Cell', '--format', 'json']\n"
        "try:\n    runpy.run_module('val3check', run_name='__main__')\nexcept SystemExit:\n    pass\n"
        "print('MODULES', sorted(m for m in sys.modules if m.startswith('val3check')), file=sys.stderr)\n"
    )
    r = subprocess.run([sys.executable, "-c", code], cwd=PACKAGE.parent, capture_output=True, text=True, timeout=60)
    line = next(x for x in r.stderr.splitlines() if x.startswith("MODULES"))
    loaded = eval(line[len("MODULES "):])  # noqa: S307 - our own output
    layers = {LAYER_OF[_top(m)] for m in loaded}
    # the command line and its report formats are the only modules above the pipeline it loads
    assert layers - LINT_PATH <= {"cli", "reporting"}, layers
    assert not [m for m in loaded if _top(m) == "reporting" and "sim" in m or _top(m) in ("interpretation",
                                                                                              "simulation", "motion")]


def test_nothing_registers_on_import():
    """Importing every chapter module leaves no instruction anywhere: registration is the
    explicit `register(registry)` that val3check.simulation makes."""
    from val3check.interpretation.registry import Registry
    from val3check.simulation import run

    empty = Registry()
    assert empty.namespace() == {}
    registry = run.build_registry()
    for module in run.INTERPRETER_MODULES + run.MOTION_MODULES:
        assert callable(module.register)
        assert not any(isinstance(v, Registry) for v in vars(module).values()), module.__name__
    assert registry.handler("movej") is not None and registry.handler("taskStatus") is not None


def test_one_junit_writer():
    """Every JUnit XML document (lint, sim, the batch summary) is written by reporting/junit.py."""
    writers = sorted(str(p.relative_to(PACKAGE)) for p in PACKAGE.rglob("*.py")
                     if re.search(r"""["'<]testsuites?\b|["']testcase["']""", p.read_text(encoding="utf-8")))
    # batch/explore/report.py: merged from main after this test, left to its own work (issue 22)
    assert writers == ["batch/explore/report.py", "reporting/junit.py"]


def test_reporting_reads_the_run_s_record_not_the_arm_s_packages():
    """Every module of reporting/, not only the run reports: nothing of robot/, geometry/,
    motion/, collision/ or the interpreter, and of simulation/ only the run's records (the page of
    a JSON report gets its arm and cell rebuilt by simulation/report_scene.py, from cli/)."""
    modules = _modules()
    bad = []
    for module, path in sorted(modules.items()):
        if _top(module) != "reporting":
            continue
        for target, name, line in _imports(path):
            t = _resolve(target, name, modules)
            layer = LAYER_OF.get(_top(t))
            if layer in ("robot", "geometry", "motion", "collision", "interpretation") or \
                    layer == "simulation" and t not in RECORDS:
                bad.append(f"{module}:{line}: {t}")
    assert bad == []


def test_no_hand_written_module_is_over_600_lines():
    root = PACKAGE.parent
    long = set()
    for path in PACKAGE.rglob("*.py"):
        lines = path.read_text(encoding="utf-8").splitlines()
        # generated tables say so in their first lines ("GENERATED: do not edit")
        if len(lines) > 600 and not any("GENERATED: do not edit" in line for line in lines[:3]):
            long.add(str(path.relative_to(root)))
    assert sorted(long) == []
