"""Issue 9: a fuzz suite of our own. Generated and mutated inputs must end cleanly (a diagnostic
or a result, never an exception) within budgets, through every phase: the XML reader, the loader,
the parser, the checker, configuration and scenario parsing, and `sim`.

Bounded for CI: each property runs VAL3CHECK_FUZZ_EXAMPLES examples (default 25, derandomized:
the same inputs on every run). `python bench/fuzz.py --minutes 10` runs the same properties for
longer with fresh random inputs (docs/fuzzing.md).
"""

from __future__ import annotations

import json
import os
import shutil
import tempfile
from pathlib import Path

import pytest
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
    MESSAGE,
    PROGRAM,
    SCENARIO,
    SCENARIO_SEED,
    SUB,
    TOML_TEXT,
    check_lint_result,
    check_lsp_output,
    check_sim,
    frame_piece,
    lint_files,
    lsp_operations,
    lsp_requests,
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


# ---- the language server (issue 21 M, N) -------------------------------------------------------------

_SENTINEL = b'{"jsonrpc": "2.0", "id": "sentinel", "method": "shutdown"}'


def _lsp(*chunks: bytes, server=None):  # noqa: ANN001, ANN202
    pytest.importorskip("pygls", reason="the lsp extra is not installed")
    from lsp_session import run

    return run(*chunks, server=server)


@given(st.lists(frame_piece(), max_size=8))
def test_language_server_recovers_from_any_framing(pieces):
    from lsp_session import initialize

    # the sentinel follows an empty line: a header left open by the pieces ends there
    code, messages, _server = _lsp(initialize(), *pieces, b"\r\n\r\n", b"Content-Length: %d\r\n\r\n" % len(_SENTINEL),
                                   _SENTINEL)
    answered = check_lsp_output(messages)
    assert "sentinel" in answered, messages[-3:]
    event(f"{len(messages)} messages out")


@given(st.lists(MESSAGE, max_size=8))
def test_language_server_answers_every_request(messages_in):
    from lsp_session import initialize

    data, asked = lsp_requests(messages_in)
    asked = {k: v for k, v in asked.items()}
    # `exit` ends the session: what follows it is not read
    cut = next((n for n, m in enumerate(messages_in, 1) if m["method"] == "exit"), None)
    code, messages, _server = _lsp(initialize(msg_id="init"), data)
    answered = check_lsp_output(messages)
    for n, method in asked.items():
        if cut is not None and n > cut:
            continue
        bad_version = messages_in[n - 1].get("jsonrpc", "2.0") != "2.0"
        assert n in answered or bad_version, (n, method, messages_in[n - 1])
        event("answered with an error" if "error" in answered.get(n, {"error": 1}) else "answered with a result")


@pytest.fixture(scope="module")
def lsp_workspace(tmp_path_factory):
    root = tmp_path_factory.mktemp("lspfuzz")
    (root / "ws" / ".git").mkdir(parents=True)
    app = write_app(root / "ws", "begin\n  nX = nX + 1\n  call sub(nX)\nend\n", globals_=["num nX"],
                    programs={"sub": {"params": ["num& x_n"], "code": "begin\n  x_n = 2\nend\n"}})
    outside = write_app(root / "outside", "begin\n  nSecretMarker = 1\nend\n", globals_=["num nSecretMarker"])
    os.symlink(outside / "start.pgx", root / "ws" / "link.pgx")
    return root / "ws", app, outside


def _uri(template: str, ws: Path, app: Path, outside: Path) -> str:
    if not template.startswith("{"):
        return template
    folder = {"{app}": app, "{outside}": outside, "{root}": ws}[template.split("/")[0]]
    return (folder / template.split("/", 1)[1]).as_uri()


@given(lsp_operations())
def test_language_server_takes_any_documents_and_positions(lsp_workspace, ops):
    from lsp_session import initialize, notification, request

    ws, app, outside = lsp_workspace
    chunks, asked = [initialize(ws.as_uri())], []
    for n, (kind, template, arg) in enumerate(ops, 1):
        uri = _uri(template, ws, app, outside)
        doc = {"uri": uri}
        if kind == "open":
            chunks.append(notification("textDocument/didOpen", {"textDocument": {**doc, "languageId": "val3",
                                                                                 "version": n, "text": arg}}))
        elif kind == "change":
            chunks.append(notification("textDocument/didChange", {"textDocument": {**doc, "version": n},
                                                                  "contentChanges": [{"text": arg}]}))
        elif kind in ("close", "save"):
            chunks.append(notification(f"textDocument/did{kind.title()}", {"textDocument": doc}))
        else:
            method = {"hover": "textDocument/hover", "definition": "textDocument/definition",
                      "symbols": "textDocument/documentSymbol"}[kind]
            params = {"textDocument": doc} if kind == "symbols" else {"textDocument": doc, "position": arg}
            chunks.append(request(n, method, params))
            asked.append(n)
        event(kind)
    code, messages, server = _lsp(*chunks)
    answered = check_lsp_output(messages)
    assert all(n in answered for n in asked)
    out = json.dumps(messages)
    assert "nSecretMarker" not in out and "root:" not in out  # nothing of the files outside the workspace
    assert not [m for m in messages if m.get("method") == "window/logMessage" and "could not" in m["params"]["message"]]
    assert server.session.buffers._folder is None  # the buffers' stand-ins removed at the end
