"""The walk the checks share (semantics.program_nodes): it gives each check exactly the nodes a
walk of its own would give, in the same order."""

from __future__ import annotations

import sys
from pathlib import Path

from val3check.loading import load
from val3check.parsing import ast as A
from val3check.parsing.parser import parse_program
from val3check.semantics import patterns_usage
from val3check.semantics.program_nodes import ProgramNodes, program_walks

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))

from generate import generate  # noqa: E402


def _bodies(folders: list[Path]) -> list[A.ProgramBody]:
    bodies = []
    for folder in folders:
        ws, _ = load([str(folder)])
        for key in ws.targets:
            for p in ws.apps[key].programs.values():
                parse_program(p)
                if p.body is not None:
                    bodies.append(p.body)
    return bodies


def _ids(nodes) -> list[int]:  # noqa: ANN001
    return [id(n) for n in nodes]


def test_every_subtree_is_the_slice_its_own_walk_gives(tmp_path):
    generate(tmp_path / "Big", min_lines=1500)
    bodies = _bodies([*sorted((ROOT / "fixtures" / "valid").iterdir()), tmp_path / "Big"])
    assert len(bodies) > 30
    kinds_seen = set()
    for body in bodies:
        walk = ProgramNodes(body)
        order = A.nodes(body)
        assert _ids(walk.order) == _ids(order)
        for node in order:
            kinds_seen.add(type(node))
            children = A.children(node)
            assert A.last_child(node) is (children[-1] if children else None)
            assert _ids(walk.under(node)) == _ids(A.nodes(node)), type(node).__name__
        for node in reversed(order):  # against the order of the walk
            assert _ids(walk.under(node)) == _ids(A.nodes(node)), type(node).__name__
        for kind in {type(n) for n in order}:
            assert _ids(walk.of(kind)) == _ids(n for n in order if type(n) is kind)
    # the structures whose last child decides where a subtree ends
    assert {A.While, A.DoUntil, A.For, A.If, A.Switch, A.Binary, A.CallExpr, A.Index} <= kinds_seen


def test_gather_reads_the_walk_as_a_walk_of_its_own_would():
    for body in _bodies(sorted((ROOT / "fixtures" / "valid").iterdir())):
        order = A.nodes(body)
        facts = patterns_usage.gather(ProgramNodes(body))
        assert facts.names == {n.name for n in order if type(n) is A.Name}
        assert _ids(facts.loops) == _ids(n for n in order if type(n) in (A.While, A.DoUntil))
        assert _ids(facts.binaries) == _ids(n for n in order if type(n) is A.Binary)
        assert _ids(facts.assigns) == _ids(n for n in order if type(n) is A.Assign)
        assert _ids(facts.strings) == _ids(n for n in order if type(n) is A.String)


def test_program_walks_skip_the_programs_that_did_not_parse(tmp_path):
    ws, _ = load([str(ROOT / "fixtures" / "valid" / "Cell")])
    app = ws.apps[ws.targets[0]]
    for p in app.programs.values():
        parse_program(p)
    first = next(iter(app.programs))
    app.programs[first].body = None
    walks = program_walks(app)
    assert set(walks) == set(app.programs) - {first} and walks


def test_scope_without_case_answers_the_first_local_then_the_first_parameter(tmp_path):
    """patterns_usage.Scope.type_of(ci=True), from maps made once per program: the first local
    whose name differs only by case, else the first such parameter, else the global."""
    from val3check.testing import write_app

    folder = write_app(tmp_path, "begin\nend\n", globals_=["bool bFlag"], locals_=["num nCount", "string NCOUNT"],
                       programs={"sub": {"params": ["num x_nPar", "string X_NPAR"], "locals": ["num nCount"]}})
    ws, _ = load([str(folder)])
    app = ws.apps[ws.targets[0]]
    resolver = patterns_usage.Resolver(ws, app)
    start = patterns_usage.Scope(resolver, app.programs["start"])
    assert start.type_of("ncount") is None  # exact spelling only by default
    assert start.type_of("ncount", ci=True) == "num" and start.type_of("NCOUNT", ci=True) == "string"
    assert start.type_of("bflag", ci=True) == "bool" and start.type_of("nothing", ci=True) is None
    sub = patterns_usage.Scope(resolver, app.programs["sub"])
    assert sub.type_of("x_npar", ci=True) == "num" and sub.type_of("NCOUNT", ci=True) == "num"


def test_last_child_skips_empty_fields_and_absent_parts():
    from val3check.parsing.parser import parse_code
    from val3check.positions import SourceMap

    code = ("begin\n  p = {1, , 2, }\n  q = {, }\n  if a\n  endIf\n  for i = 0 to 3\n  endFor\n"
            "  switch n\n    case 1\n    break\n  endSwitch\n  f()\nend")
    body, diags = parse_code(code, SourceMap.identity(code), "t.pgx")
    assert body is not None and not diags
    walk = ProgramNodes(body)
    for node in walk.order:
        children = A.children(node)
        assert A.last_child(node) is (children[-1] if children else None), type(node).__name__
        assert _ids(walk.under(node)) == _ids(A.nodes(node))
    structs = walk.of(A.Struct)
    assert [f is None for f in structs[0].fields] == [False, True, False, True]
    assert A.last_child(structs[1]) is None
