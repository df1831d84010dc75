"""`Compiled.loops_at`: the loops a Python line of a compiled program runs in, memoised per line
(what `Machine.loop_passes` reads at each motion command)."""

from __future__ import annotations

from val3check.interpretation.compiler.structures import Compiled, LoopSite


def _program(loops: list[LoopSite]) -> Compiled:
    return Compiled("p", None, [], {}, "p.pgx", "<val3 1:p>", 0, loops=loops)


def test_loops_at_each_line_are_the_loops_that_span_it_outermost_first_asked_again_or_not():
    outer = LoopSite("while", 3, 3, 10, 40, "_l1")
    inner = LoopSite("for", 5, 5, 15, 30, "_l2")
    after = LoopSite("do", 9, 3, 50, 60, "_l3")
    c = _program([outer, inner, after])
    expected = {9: (), 10: (outer,), 14: (outer,), 15: (outer, inner), 30: (outer, inner), 31: (outer,), 40: (outer,),
                41: (), 50: (after,), 60: (after,), 61: ()}
    for _ in range(2):  # the second time from the memo
        for line in range(0, 70):
            scan = tuple(s for s in c.loops if s.py_first <= line <= s.py_last)
            assert c.loops_at(line) == scan
        for line, want in expected.items():
            assert c.loops_at(line) == want


def test_each_program_keeps_its_own_memo():
    a = _program([LoopSite("while", 1, 1, 2, 8, "_l1")])
    b = _program([])
    assert a.loops_at(5) == (a.loops[0],)
    assert b.loops_at(5) == ()
