"""The compiler checks never raise, whatever tree they get, and stay quiet on valid fixtures."""

from __future__ import annotations

import random
from pathlib import Path

from .checkhelp import collect, write_app

from val3check.loading import load
from val3check.parsing import ast as A
from val3check.parsing.parser import parse_program
from val3check.semantics.checker import check_application

FIXTURES = Path(__file__).resolve().parents[2] / "fixtures"
NAMES = ["nX", "sA", "nArr", "nGrid", "sColl", "pA", "jA", "trA", "diA", "u", "pick", "movej", "size", "insert",
         "world", "flange", "righty", "off", "joint", "zz", "taskCreate", "call", "x_p", "l_a", "lib", "io", "start"]
FIELDS = ["x", "trsf", "config", "shoulder", "j1", "vel", "nope", "gripper"]
OPS = ["or", "and", "xor", "==", "!=", "<", ">", "<=", ">=", "+", "-", "*", "/", "%"]


def _expr(rng: random.Random, depth: int):
    k = rng.randrange(14 if depth > 0 else 6)
    if k == 0:
        return A.Number(1.0, "1", 1, 1, 1, 2)
    if k == 1:
        return A.String("s", 1, 1, 1, 3)
    if k == 2:
        return A.Bool(True, 1, 1, 1, 5)
    if k in (3, 4):
        return A.Name(rng.choice(NAMES), 1, 1, 1, 3)
    if k == 5:
        return A.LibraryName(rng.choice(["lib", "io", "zz"]), rng.choice(NAMES), 1, 1, 1, 5)
    d = depth - 1
    if k == 6:
        return A.Index(_expr(rng, d), [_expr(rng, d) for _ in range(rng.randrange(1, 4))], 1, 1)
    if k == 7:
        return A.Field(_expr(rng, d), rng.choice(FIELDS), 1, 1, 1, 3)
    if k == 8:
        func = rng.choice([A.Name(rng.choice(NAMES), 1, 1, 1, 2), A.LibraryName("lib", rng.choice(NAMES), 1, 1, 1, 2),
                           A.SystemName("$x", 1, 1, 1, 2)])
        return A.CallExpr(func, [_expr(rng, d) for _ in range(rng.randrange(0, 4))], 1, 1)
    if k == 9:
        return A.Unary(rng.choice(["-", "!"]), _expr(rng, d), 1, 1)
    if k in (10, 11):
        return A.Binary(rng.choice(OPS), _expr(rng, d), _expr(rng, d), 1, 1, 1, 2)
    if k == 12:
        return A.Struct([rng.choice([None, _expr(rng, d)]) for _ in range(rng.randrange(0, 8))], 1, 1)
    return A.AssignExpr(_expr(rng, d), _expr(rng, d), 1, 1, 1, 2)


def _stmt(rng: random.Random, depth: int):
    k = rng.randrange(11 if depth > 0 else 5)
    e = lambda: _expr(rng, 4)
    body = lambda: [_stmt(rng, depth - 1) for _ in range(rng.randrange(0, 3))]
    target = lambda: rng.choice([A.Name(rng.choice(NAMES), 1, 1, 1, 2), A.LibraryName("lib", "x", 1, 1, 1, 2)])
    if k == 0:
        return A.Assign(e(), e(), 1, 1, 1, 2)
    if k == 1:
        return A.ExprStatement(A.CallExpr(A.Name(rng.choice(NAMES), 1, 1, 1, 2), [e() for _ in range(2)], 1, 1), 1, 1)
    if k == 2:
        return A.Call(target(), [e() for _ in range(rng.randrange(0, 3))], 1, 1)
    if k == 3:
        return A.TaskCreate(e(), e(), target(), [e()], 1, 1)
    if k == 4:
        return A.TaskCreateSync(e(), e(), e(), target(), [], 1, 1)
    if k == 5:
        return A.If([A.Branch(e(), body(), 1, 1)], rng.choice([None, body()]), 1, 1, 0, 0, 1, 1)
    if k == 6:
        return A.While(e(), body(), 1, 1, 1, 1)
    if k == 7:
        return A.DoUntil(body(), e(), 1, 1, 1, 1)
    if k == 8:
        return A.For(e(), e(), e(), rng.choice([None, e()]), body(), 1, 1, 1, 1)
    if k == 9:
        return A.Switch(e(), [A.Case([e(), e()], body(), 1, 1)], rng.choice([None, A.Default(body(), 1, 1)]), 1, 1, 1, 1)
    return rng.choice([A.Return(1, 1), A.Break(1, 1), A.ErrorStatement(1, 1)])


def test_random_trees_never_raise(tmp_path):
    progs = {"pick": {"params": ["num& x_p", "num x_a[]"], "locals": ["num l_a[3]"]}}
    folder = write_app(tmp_path, "begin\nend", globals_=["num nX", "string sA", "num nArr[3]", "num nGrid[2,2]",
                                                         'string sColl[""]', "point pA", "joint jA", "trsf trA",
                                                         "dio diA", "Part u"], programs=progs)
    ws, _ = load([str(folder)])
    app = ws.apps[ws.targets[0]]
    rng = random.Random(1234)
    for _ in range(300):
        for program in app.programs.values():
            program.body = A.ProgramBody([_stmt(rng, 3) for _ in range(6)])
        for d in check_application(ws, app):
            assert d.code[0] in "NTL" and d.message


def test_valid_fixtures_have_no_compiler_findings():
    for app in sorted(p for p in (FIXTURES / "valid").iterdir() if p.is_dir()):
        assert collect(app) == [], app.name


def test_broken_fixtures_do_not_raise():
    ws, _ = load([str(FIXTURES / "broken")])
    for app in ws.apps.values():
        for program in app.programs.values():
            parse_program(program)
        check_application(ws, app)
