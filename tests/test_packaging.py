"""Packaging (docs/architecture.md): `pip install val3check` brings what `lint` needs and
nothing else; `val3check[sim]` brings the robotics stack; `sim` without it says which extra to
install; lark is pinned to the range the shipped parser tables load with."""

from __future__ import annotations

import ast
import subprocess
import sys
import tomllib
from pathlib import Path

from val3check.testing import write_app

ROOT = Path(__file__).resolve().parent.parent
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
SIM_STACK = {"pin", "pinocchio", "numpy", "scipy", "python-fcl", "fcl", "trimesh", "mcap"}
# the packages of the lint layers (tests/test_architecture.py LINT_PATH)
LINT_PACKAGES = ("language", "loading", "parsing", "semantics", "rules")
LINT_MODULES = ("__init__.py", "__main__.py", "cli/__init__.py", "cli/common.py", "cli/lint_command.py", "diagnostics.py", "positions.py", "resources.py", "lint.py",
                "config.py", "exclusion.py", "suppression.py", "baseline.py", "fixes.py", "result.py")


def _name(requirement: str) -> str:
    for sep in "<>=![ ;":
        requirement = requirement.split(sep)[0]
    return requirement.strip().lower()


def test_the_base_install_has_no_robotics_stack():
    base = {_name(r) for r in PYPROJECT["project"]["dependencies"]}
    assert base == {"lark", "defusedxml", "pathspec"}
    extras = PYPROJECT["project"]["optional-dependencies"]
    assert {"pin", "numpy", "python-fcl", "trimesh"} <= {_name(r) for r in extras["sim"]}
    assert "val3check[sim]" in extras["test"]  # the README's test command installs everything


def test_the_lint_path_imports_only_the_base_dependencies():
    """Every module `lint` may load imports, besides val3check and the standard library, only
    the base dependencies (read from the code, as a light install would run it)."""
    package = ROOT / "val3check"
    files = [package / m for m in LINT_MODULES]
    for p in LINT_PACKAGES:
        files += sorted((package / p).rglob("*.py"))
    allowed = {"lark", "defusedxml", "pathspec"}
    found = set()
    for path in files:
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                found |= {a.name.split(".")[0] for a in node.names}
            elif isinstance(node, ast.ImportFrom) and not node.level and node.module:
                found.add(node.module.split(".")[0])
    # (CPython's own private modules, _sha2..., come with the interpreter)
    third_party = {m for m in found - set(sys.stdlib_module_names) - {"val3check", "__future__"} if m[0] != "_"}
    assert third_party <= allowed, third_party - allowed


def test_sim_without_the_extra_says_which_extra_to_install(tmp_path, monkeypatch, capsys):
    from val3check import cli
    from val3check.simulation import requirements

    real = requirements.find_spec
    monkeypatch.setattr(requirements, "find_spec", lambda m: None if m == "pinocchio" else real(m))
    folder = write_app(tmp_path, "begin\nend\n")
    assert cli.main(["sim", str(folder)]) == 2
    err = capsys.readouterr().err
    assert "missing: pin" in err and "pip install 'val3check[sim]'" in err


def _minor(version: str) -> tuple[int, int]:
    major, minor = version.split(".")[:2]
    return int(major), int(minor)


def test_lark_is_pinned_to_the_range_the_shipped_tables_are_made_with():
    """The shipped tables are plain data made with one Lark version; Lark builds them again from
    the grammar while it is being edited: the pin is the range they are made and tested with."""
    import lark

    from val3check.parsing import _tables
    from val3check.parsing.builder import Builder
    from val3check.parsing.grammar import build_from_grammar, grammar_text
    from val3check.parsing.tables import compile_tables

    (spec,) = [r for r in PYPROJECT["project"]["dependencies"] if _name(r) == "lark"]
    low, high = (_minor(v) for v in spec.split(">=")[1].split(",<"))
    assert low <= _minor(lark.__version__) < high
    assert low <= _minor(_tables.LARK_VERSION) < high
    # the installed Lark builds the tables the parser runs (the fallback while editing the
    # grammar; tests/parsing/test_tables.py compares them byte for byte)
    built = compile_tables(build_from_grammar(grammar_text()), frozenset(dir(Builder)))
    assert (len(built["STATES"]), len(built["RULES"])) == (len(_tables.STATES), len(_tables.RULES))
    # and linting runs on the shipped tables without importing Lark
    code = ("import sys\nfrom val3check.parsing import grammar\ngrammar.load_tables()\n"
            "print('LARK', 'lark' in sys.modules)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, timeout=60).stdout
    assert "LARK False" in out


# a light install as `pip install val3check` leaves it: the sim extra's modules cannot be found
_LIGHT = """import sys
from importlib.abc import MetaPathFinder
from val3check.simulation.requirements import SIM_MODULES

class Absent(MetaPathFinder):
    def __init__(self, finders):
        self.finders = finders

    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in SIM_MODULES:
            return None
        for f in self.finders:
            spec = f.find_spec(name, path, target) if hasattr(f, "find_spec") else None
            if spec is not None:
                return spec
        return None

sys.meta_path[:] = [Absent(list(sys.meta_path))]
from val3check.cli import main
sys.exit(main(sys.argv[1:]))
"""


def _light(*argv: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-c", _LIGHT, *argv], capture_output=True, text=True, cwd=cwd, timeout=120,
                          check=False)


def test_a_light_install_says_which_extra_sim_and_reach_need_without_a_traceback(tmp_path):
    """Issue 28 item 1: on a lint-only install `sim` (one run, a batch of arms, a sweep, the Dask
    executor) and `reach` name the extra and exit 2; `--init-scenario` needs no extra and works;
    never a traceback."""
    folder = write_app(tmp_path, "begin\n  movej(jHome, tTool, mDesc)\nend\n",
                       globals_=["joint jHome", "tool tTool", "mdesc mDesc"])
    for argv in ((("sim", str(folder), "--robot", "tx2-60")), ("sim", str(folder), "--report", "html", "-o", "r.html"),
                 ("sim", str(folder), "--robot", "tx2-60", "--robot", "tx2-90"),
                 ("sim", str(folder), "--robot", "tx2-60", "--sweep", "monitor_speed=50,100"),
                 ("sim", str(folder), "--robot", "tx2-60", "--robot", "tx2-90", "--executor", "dask"),
                 ("reach", str(folder), "--robot", "tx2-60")):
        r = _light(*argv, cwd=tmp_path)
        assert r.returncode == 2 and "Traceback" not in r.stderr, (argv, r.stderr)
        assert f"val3check {argv[0]} needs" in r.stderr and "pip install 'val3check[sim]'" in r.stderr, r.stderr
        assert "missing: numpy, pin" in r.stderr
    r = _light("sim", str(folder), "--init-scenario", "s.toml", cwd=tmp_path)
    assert r.returncode == 0 and (tmp_path / "s.toml").is_file(), r.stderr
    assert _light("lint", str(folder), cwd=tmp_path).returncode == 0


# import name -> distribution, where they differ (lsprotocol comes with pygls)
_DIST_OF = {"pinocchio": "pin", "fcl": "python-fcl", "distributed": "dask", "lsprotocol": "pygls"}
# declared but imported only by a dependency: trimesh's mesh operations use scipy
_NEEDED_BY_A_DEPENDENCY = {"scipy"}


def _third_party_imports() -> set[str]:
    names = set()
    for path in (ROOT / "val3check").rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                names.update(a.name.split(".")[0] for a in node.names)
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                names.add(node.module.split(".")[0])
    return {_DIST_OF.get(n, n) for n in names
            if n != "val3check" and not n.startswith("_") and n not in sys.stdlib_module_names}


def test_the_declared_dependencies_are_the_imported_ones():
    # what the code imports is declared (base or an extra), and the sim extra holds nothing the
    # code no longer uses (issue 23: toppra replaced by motion/timing's own solver)
    project = PYPROJECT["project"]
    declared = {_name(r) for r in project["dependencies"]}
    for extra in ("sim", "lsp", "dask"):
        declared |= {_name(r) for r in project["optional-dependencies"][extra]}
    imported = _third_party_imports()
    assert imported <= declared, imported - declared
    sim = {_name(r) for r in project["optional-dependencies"]["sim"]}
    assert sim - _NEEDED_BY_A_DEPENDENCY <= imported, sim - imported
    assert "toppra" not in declared | imported
