"""Issue 9: a fuzz suite of our own. Generated and mutated inputs must end cleanly (a diagnostic
or a result, never an exception) within budgets, through every phase: the XML reader, the loader,
the parser, the checker, configuration and scenario parsing, and `sim`.

Bounded for CI: each property runs VAL3CHECK_FUZZ_EXAMPLES examples (default 25, derandomized:
the same inputs on every run). `python bench/fuzz.py --minutes 10` runs the same properties for
longer with fresh random inputs (docs/fuzzing.md).
"""

from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path

from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from .fuzzing import (
    CELL,
    CELL_SEED,
    CELL_TOKENS,
    CONFIG,
    GLOBALS,
    LOCALS,
    MESH_TOKENS,
    PROGRAM,
    SCENARIO,
    SCENARIO_SEED,
    SUB,
    TOML_TEXT,
    check_lint_result,
    check_sim,
    lint_files,
    mesh_seeds,
    mutated,
    mutated_app,
    toml_text,
)
from val3check.testing import write_app

EXAMPLES = int(os.environ.get("VAL3CHECK_FUZZ_EXAMPLES", "25"))
LONG = os.environ.get("VAL3CHECK_FUZZ_LONG") == "1"
settings.register_profile(
    "val3check-ci", max_examples=EXAMPLES, deadline=None, database=None, derandomize=not LONG,
    suppress_health_check=list(HealthCheck), print_blob=True,
)
settings.load_profile("val3check-ci")


@given(st.binary(max_size=2000))
def test_xml_reader_takes_any_bytes(data):
    from val3check.confine import Roots
    from val3check.loading.xmlread import read_xml

    with tempfile.NamedTemporaryFile(suffix=".pgx", delete=False) as fh:
        fh.write(data)
    try:
        res = read_xml(fh.name, 1 << 20, Roots.user_given())
        assert (res.root is None) == bool(res.diagnostics) or res.root is not None
        assert all(d.code in ("F001", "F002", "F003", "F004", "F005") for d in res.diagnostics)
    finally:
        os.unlink(fh.name)


@given(mutated_app())
def test_loader_and_checker_take_mutated_real_applications(app):
    name, files = app
    run, tmp = lint_files({f"{name}/{k}": v for k, v in files.items()})
    for code in sorted({d.code[:2] for d in run.result.diagnostics}) or ["clean"]:
        event(f"findings {code}")
    shutil.rmtree(tmp)


@given(st.one_of(st.text(max_size=500), st.lists(st.sampled_from(
    ["begin", "end", "if", "endIf", "while", "endWhile", "for", "to", "endFor", "switch", "case", "endSwitch",
     "call", "x", "lib:y", "1e999", "9" * 50, '"s', "(", ")", "[", "]", "{", "}", ",", ".", "=", "==", "<", "+",
     "and", "\n", "// c\n", "\x00", "é"]), max_size=200).map(" ".join)))
def test_parser_takes_any_text(code):
    from val3check.parsing.parser import parse_code
    from val3check.positions import SourceMap

    body, diags = parse_code(code, SourceMap.identity(code), "t.pgx")
    for d in diags:
        assert d.code.startswith("F10") and d.line >= 1 and d.col >= 1


@given(PROGRAM, SUB)
def test_checker_takes_generated_programs(code, sub):
    tmp = Path(tempfile.mkdtemp(prefix="val3fuzz"))
    try:
        folder = write_app(tmp, code, globals_=GLOBALS, locals_=LOCALS,
                           programs={"sub": {"params": ["num& x_n"], "code": sub}})
        from val3check.config import Settings
        from val3check.lint import run

        result = run([str(folder)], Settings())
        check_lint_result(result, tmp)
    finally:
        shutil.rmtree(tmp)


@given(PROGRAM, SUB)
def test_sim_ends_within_budgets_on_generated_programs(code, sub):
    from val3check.config import Settings
    from val3check.lint import run

    tmp = Path(tempfile.mkdtemp(prefix="val3fuzz"))
    try:
        folder = write_app(tmp, code, globals_=GLOBALS, locals_=LOCALS,
                           programs={"sub": {"params": ["num& x_n"], "code": sub}})
        lr = run([str(folder)], Settings())
        errs = sorted({d.code for d in lr.result.diagnostics if d.severity is not None and d.severity.label == "error"})
        if errs:
            event(f"not run: lint error {errs[0]}")
            return  # sim refuses applications with lint errors
        ws = lr.workspace
        result = check_sim(ws, ws.apps[ws.targets[0]])
        event(f"ran: {result.end_reason}")
    finally:
        shutil.rmtree(tmp)


@given(st.one_of(CONFIG.map(toml_text), st.text(max_size=300)))
def test_configuration_is_a_setting_or_a_config_error(text):
    from val3check.config import ConfigError, load_settings

    tmp = Path(tempfile.mkdtemp(prefix="val3fuzz"))
    try:
        for name in ("val3check.toml", "pyproject.toml"):
            p = tmp / name
            p.write_text(text if name == "val3check.toml" else "[tool.val3check]\n" + text, encoding="utf-8")
            try:
                load_settings(str(p))
                event("accepted")
            except ConfigError:
                event("ConfigError")
    finally:
        shutil.rmtree(tmp)


_APP_WITH_IO = "begin\n  delay(0.2)\n  diY = diX\n  putln(toString(\"\", aiX))\nend\n"


@given(st.one_of(SCENARIO.map(toml_text), st.text(max_size=300), TOML_TEXT, mutated(SCENARIO_SEED, CELL_TOKENS)))
def test_scenario_is_applied_or_refused_and_the_run_ends(text):
    from val3check.config import Settings
    from val3check.simulation.scenario import ScenarioError, load_scenario
    from val3check.lint import run

    from interpretation.simsupport import build

    tmp = Path(tempfile.mkdtemp(prefix="val3fuzz"))
    try:
        folder = build(tmp, _APP_WITH_IO, globals_=["dio diX", "dio diY", "aio aiX", "sio siX", "num nX"],
                       links={"diX": "BasicIO-1\\%I0", "diY": "BasicIO-1\\%Q0", "aiX": "AI-0", "siX": "Serial-0"})
        (tmp / "sc.toml").write_bytes(text if isinstance(text, bytes) else text.encode("utf-8", "surrogatepass"))
        lr = run([str(folder)], Settings())
        ws = lr.workspace
        try:
            scenario = load_scenario(str(tmp / "sc.toml"))
            result = check_sim(ws, ws.apps[ws.targets[0]], scenario=scenario)
            event(f"ran: {result.end_reason}")
        except ScenarioError:
            event("refused (ScenarioError)")
    finally:
        shutil.rmtree(tmp)


# ---- issue 21: TOML texts, cell files, meshes --------------------------------------------------------

@given(TOML_TEXT)
def test_toml_reader_gives_data_or_a_positioned_error(text):
    from val3check.tomlfile import TomlError, loads

    try:
        loads(text)
        event("accepted")
    except TomlError as exc:
        assert exc.line >= 0 and exc.col >= 0 and exc.message and "\n" not in exc.message
        event("TomlError")


@given(st.one_of(CELL.map(toml_text), mutated(CELL_SEED, CELL_TOKENS), TOML_TEXT.map(str.encode)))
def test_cell_file_is_a_cell_or_positioned_problems(data):
    from val3check.collision import CellError, read_cell

    from .meshfiles import obj, stl_binary

    tmp = Path(tempfile.mkdtemp(prefix="val3fuzz"))
    try:
        (tmp / "m.stl").write_bytes(stl_binary())
        (tmp / "m.obj").write_bytes(obj())
        (tmp / "cell.toml").write_bytes(data if isinstance(data, bytes) else data.encode("utf-8", "surrogatepass"))
        try:
            cell = read_cell(tmp / "cell.toml")
            for o in cell.obstacles:
                assert all(0 < v <= 1e6 for v in o.shape.size)
            event("accepted")
        except CellError as exc:
            for path, line, col, message in exc.problems:
                assert line >= 0 and col >= 0 and message and len(message) < 2000, message
                assert all(c.isprintable() for c in message), message
            event("CellError")
    finally:
        shutil.rmtree(tmp)


_MESH_SEEDS = mesh_seeds()


@given(st.sampled_from(sorted(_MESH_SEEDS)).flatmap(lambda k: st.tuples(st.just(k), mutated(_MESH_SEEDS[k], MESH_TOKENS))))
def test_mesh_file_is_a_mesh_or_a_problem(kind_and_data):
    from val3check.collision.meshes import MeshProblem, load_mesh

    kind, data = kind_and_data
    tmp = Path(tempfile.mkdtemp(prefix="val3fuzz"))
    try:
        path = tmp / f"m.{kind.split('.')[-1]}"
        path.write_bytes(data)
        try:
            mesh = load_mesh(path, path.name, (1.0, 1.0, 1.0), solid=False, roots=[tmp])
            assert len(mesh.faces) > 0 and abs(mesh.vertices).max() <= 1e6
            event(f"{kind}: loaded")
        except MeshProblem as exc:
            assert path.name in str(exc)
            event(f"{kind}: MeshProblem")
    finally:
        shutil.rmtree(tmp)
