"""The rule code map (`val3check/rules/codes.py`): one constant per rule code, one `rules/CODE.toml`
per constant, and the module that emits each code written beside it and true. A code is emitted
where its constant is written (a literal code is refused anywhere but in codes.py) other than to be
compared (`d.code == codes.DEADLOCK`, `code in {...}`)."""

from __future__ import annotations

import ast
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "val3check"
CODES = PACKAGE / "rules" / "codes.py"
_CODE = re.compile(r"^[FNTLSR]\d{3}$")
_ENTRY = re.compile(r'^([A-Z][A-Z0-9_]*) = "([FNTLSR]\d{3})" +# (.+)$')

# Modules that still write codes as literals: none, every module names a code by its constant.
LITERALS_LEFT: set[str] = set()
# Codes still emitted by more than one module; any other code has exactly one emitting module.
# F001, F014: the read gate (confine.py) and the loader's checks of what a project lists; F011: a
# declaration twice across files (loader) or a field twice in a value (data_file); F101: the
# engine's syntax errors and parser.py's last resort (an internal error); the semantics
# codes: left to the work on those files (issue 22); R003, R018: the arm port's waiting_reason names
# the rule of its wait; R006: each budget where it runs out; R037: the run without an arm model
# (run.py) could use collision_run's own helper, a file other work changes this session; R052: each
# chapter 11 instruction says which of its effects is not simulated.
KNOWN_SHARED = {
    "F001": {"confine.py", "loading/loader.py"},
    "F011": {"loading/data_file.py", "loading/loader.py"},
    "F014": {"confine.py", "loading/libraries.py", "loading/loader.py"},
    "F101": {"parsing/engine.py", "parsing/parser.py"},
    "L010": {"semantics/calls.py", "semantics/expressions.py", "semantics/statements.py"},
    "L011": {"semantics/expressions.py", "semantics/statements.py"},
    "L012": {"semantics/calls.py", "semantics/expressions.py", "semantics/statements.py"},
    "N006": {"semantics/expressions.py", "semantics/statements.py"},
    "R003": {"interpretation/deadlock.py", "simulation/moving_arm.py"},
    "R006": {"interpretation/machine.py", "simulation/collect.py", "simulation/folding.py"},
    "R018": {"interpretation/machine.py", "motion/findings.py", "simulation/moving_arm.py"},
    "R037": {"simulation/collision_run.py", "simulation/run.py"},
    "R052": {"simulation/alteration.py", "simulation/ch11_absolute.py",
             "simulation/ch11_compliance.py", "simulation/ch11_continuous.py"},
    "T006": {"semantics/calls.py", "semantics/statements.py"},
    "T007": {"semantics/calls.py", "semantics/statements.py"},
    "T011": {"semantics/calls.py", "semantics/expressions.py"},
    "T018": {"semantics/calls.py", "semantics/expressions.py", "semantics/statements.py"},
    "T022": {"semantics/calls.py", "semantics/statements.py"},
}


def _map() -> dict[str, tuple[str, set[str]]]:
    """codes.py: code -> (constant, modules its comment says emit it)."""
    out = {}
    for line in CODES.read_text(encoding="utf-8").splitlines():
        m = _ENTRY.match(line)
        if m:
            assert m.group(2) not in out, f"{m.group(2)} has two constants"
            out[m.group(2)] = (m.group(1), {s.strip() for s in m.group(3).split(",")})
    return out


def _toml_codes() -> set[str]:
    return {p.stem for p in (ROOT / "rules").glob("*.toml")}


def _uses() -> dict[str, dict[str, list[tuple[int, bool]]]]:
    """code -> module (relative to val3check/) -> [(line, emitted)] for every use of a code."""
    constant = {name: code for code, (name, _) in _map().items()}
    out: dict[str, dict[str, list[tuple[int, bool]]]] = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        if path == CODES or path.name == "_tables.py":
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        parent = {c: n for n in ast.walk(tree) for c in ast.iter_child_nodes(n)}
        imported = {a.asname or a.name for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)
                    and (n.module or "").endswith("rules.codes") for a in n.names}
        has_codes = any(isinstance(n, ast.ImportFrom) and (n.module or "").endswith("rules")
                        and any(a.name == "codes" for a in n.names) for n in ast.walk(tree))
        for node in ast.walk(tree):
            code = None
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and _CODE.match(node.value):
                code = node.value
            elif isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == "codes" \
                    and has_codes:
                code = constant.get(node.attr, f"codes.{node.attr}")
            elif isinstance(node, ast.Name) and node.id in imported:
                code = constant.get(node.id, node.id)
            if code is None:
                continue
            x, emitted = node, True
            while x in parent and not isinstance(x, ast.stmt):
                x = parent[x]
                if isinstance(x, (ast.Compare, ast.Set)):
                    emitted = False  # compared with, or one of a set of codes to compare with
                    break
            module = path.relative_to(PACKAGE).as_posix()
            out.setdefault(code, {}).setdefault(module, []).append((node.lineno, emitted))
    return out


def _emitters() -> dict[str, set[str]]:
    return {code: {m for m, uses in by.items() if any(e for _, e in uses)} for code, by in _uses().items()}


def test_one_constant_per_rule_file_and_one_rule_file_per_constant():
    assert set(_map()) == _toml_codes()


def test_every_code_used_is_a_rule_with_a_file():
    assert sorted(set(_uses()) - _toml_codes()) == []


def test_literal_codes_only_in_the_modules_left():
    with_literal = set()
    for path in PACKAGE.rglob("*.py"):
        if path == CODES:
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and _CODE.match(node.value):
                with_literal.add(path.relative_to(PACKAGE).as_posix())
    assert with_literal == LITERALS_LEFT


def test_every_code_has_one_emitting_module_written_in_the_map():
    emitters = _emitters()
    for code, (name, said) in sorted(_map().items()):
        found = emitters.get(code, set())
        assert found, f"{code} ({name}) is emitted nowhere"
        assert found == said, f"rules/codes.py: {name} = {code!r} is emitted by {sorted(found)}"
        assert len(found) == 1 or KNOWN_SHARED.get(code) == found, f"{code} emitted by {sorted(found)}"
    assert {c for c, m in emitters.items() if len(m) > 1} == set(KNOWN_SHARED)


def test_the_map_finds_an_emission_and_not_a_comparison(tmp_path):
    """The reader of uses tells an emitted code from a compared one (what the tests above rely on)."""
    uses = _uses()
    assert uses["F002"]["batch/carry.py"] and not any(e for _, e in uses["F002"]["batch/carry.py"])
    assert any(e for _, e in uses["R001"]["interpretation/machine.py"])
