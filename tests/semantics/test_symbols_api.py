"""The symbol table and expression typing exposed for other rules (semantics.symbols, checker)."""

from __future__ import annotations

from pathlib import Path

from val3check.loading import load
from val3check.parsing import ast as A
from val3check.parsing.parser import parse_program
from val3check.semantics import symbols
from val3check.semantics import vtypes as vt
from val3check.semantics.checker import program_typer

FIXTURES = Path(__file__).resolve().parents[2] / "fixtures" / "valid"


def _load(name: str):
    ws, _ = load([str(FIXTURES / name)])
    app = ws.apps[ws.targets[0]]
    for p in app.programs.values():
        parse_program(p)
    return ws, app


def test_scope_resolution_order_and_case_fallback():
    ws, app = _load("Cell")
    table = symbols.build(ws, app)
    scope = table.scope(app.programs["place"])
    assert scope.lookup("x_pTarget").kind == symbols.PARAM
    assert scope.lookup("l_pDepose").kind == symbols.LOCAL
    assert scope.lookup("l_pDepose").type is vt.POINT  # pointRx is a point
    assert scope.lookup("jDest").kind == symbols.GLOBAL
    assert scope.lookup("jdest") is None and scope.lookup_ci("jdest").name == "jDest"
    assert symbols.resolve_name(scope, "WORLD").kind == symbols.CONSTANT
    assert symbols.resolve_name(scope, "nowhere") is None


def test_library_interface_and_user_type_fields():
    ws, app = _load("Cell")
    lib = symbols.build(ws, app).library("lib")
    assert lib.data_symbol("nX")[0].type is vt.NUM and lib.data_symbol("nX")[1] == ""
    assert lib.data_symbol("sLog")[1] == "private"
    assert lib.program("init")[0].name == "init"
    assert symbols.build(ws, app).library("nope") is None

    ws, app = _load("Sorter")
    table = symbols.build(ws, app)
    part = table.globals["part"].type
    assert part.kind == vt.USER and part.name == "Part"
    fields = symbols.user_fields(table.registry, part)
    assert fields["nDims"].container == vt.ARRAY and fields["nRevision"].decl.access == "private"


def test_program_typer_types_any_expression_of_a_program():
    ws, app = _load("Cell")
    program = app.programs["place"]
    typer = program_typer(ws, app, program)
    assign = next(s for s in program.body.statements if type(s) is A.Assign and type(s.target) is A.Field)
    assert typer.typeof(assign.target).t is vt.NUM  # l_pDepose.trsf.z
    assert typer.typeof(assign.value).t is vt.NUM  # l_pDepose.trsf.z + lib:nX
    assert typer.typeof(assign.target).var and typer.typeof(assign.target).root.name == "l_pDepose"
    assert typer.ctx.diags == []


def test_resolve_an_ast_name_to_its_declaration():
    ws, app = _load("Cell")
    table = symbols.build(ws, app)
    scope = table.scope(app.programs["start"])
    names = [n for s in app.programs["start"].body.statements for n in A.walk(s) if type(n) in (A.Name, A.LibraryName)]
    by_text = {(n.alias + ":" if type(n) is A.LibraryName else "") + n.name: symbols.resolve(scope, n) for n in names}
    assert by_text["l_nLoad"].kind == symbols.LOCAL and by_text["l_nLoad"].decl.name == "l_nLoad"
    assert by_text["bStop"].kind == symbols.GLOBAL
    assert by_text["lib:bReady"].kind == symbols.LIBDATA
    assert by_text["lib:init"].name == "init"  # a Program of the library
    assert by_text["cycle"].name == "cycle"  # the program of taskCreate
    assert by_text["lib:libLoad"] is None  # an instruction
