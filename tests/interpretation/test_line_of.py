"""`Compiled.line_of`: the Python line a frame of a compiled program is at, kept by instruction
offset for the program's own code (what `Machine.line_running` and `loop_passes` read at each
motion command and tool action), asked of the frame for any other code."""

from __future__ import annotations

import sys

from val3check.interpretation.compiler.structures import Compiled
from val3check.robot import load_robot

from .simsupport import sim

SOURCE = """def P_p(T):
    a = 1
    yield sys._getframe()
    b = 2
    yield sys._getframe()
    c = (lambda: sys._getframe())()
    yield c
    yield sys._getframe()
"""


def _program() -> Compiled:
    ns = {"sys": sys}
    exec(compile(SOURCE, "<val3 1:p>", "exec"), ns)
    return Compiled("p", ns["P_p"], [], {}, "p.pgx", "<val3 1:p>", 0)


def test_each_offset_of_the_program_gives_its_own_line_asked_again_or_not():
    c = _program()
    for _ in range(2):  # the second time from what was kept
        gen = c.func(None)
        lines = []
        for frame in gen:
            lines.append((c.line_of(frame), frame.f_lineno, frame.f_code is c.func.__code__))
        assert [(got, want) for got, want, _ in lines] == [(3, 3), (5, 5), (6, 6), (8, 8)]
    # the lambda's frame (other code, other offsets) was asked of the frame, not kept
    assert lines[2][2] is False
    assert sorted(c._lines.values()) == [3, 5, 8]


def test_a_program_without_code_and_each_program_keep_their_own_lines():
    a, b = _program(), _program()
    frame = next(a.func(None))
    assert a.line_of(frame) == 3
    assert b.line_of(frame) == 3  # b's code is another object: asked of the frame
    assert b._lines == {}
    failing = Compiled("q", None, [], {}, "q.pgx", "<val3 1:q>", 0)
    assert failing.line_of(frame) == 3 and failing._lines == {}


def test_at_keeps_by_offset_the_position_and_loops_of_the_frames_line():
    c = _program()
    c.pos = {3: (10, 3), 5: (11, 3), 6: (12, 5)}
    for _ in range(2):  # the second time from what was kept
        assert [c.at(f)[0] for f in c.func(None)] == [("p.pgx", 10, 3, "p"), ("p.pgx", 11, 3, "p"),
                                                      ("p.pgx", 12, 5, "p"), None]
    assert len(c._at) == 3  # the lambda's frame (other code) is not kept


def test_a_long_run_reads_the_same_lines_as_the_frames_give(tmp_path, monkeypatch):
    """Every position and loop read during a run with motions in nested loops and calls (kept by
    offset) equals what the frame's f_lineno gives, computed afresh."""
    asked = []
    kept = Compiled.at

    def checked(self, frame):
        got = kept(self, frame)
        asked.append((got, self._at_line(frame.f_lineno)))
        return got

    monkeypatch.setattr(Compiled, "at", checked)
    code = """begin
  for l_i = 1 to 40
    l_n = l_i % 3
    while l_n < 3
      call step(l_n)
      l_n = l_n + 1
    endWhile
    open(flange)
  endFor
end"""
    step = """begin
  movej({0, 0, 90, 0, 90, 0}, flange, mD)
  if x_n == 1
    movej({10, 0, 90, 0, 90, 0}, flange, mD)
  endIf
end"""
    res = sim(tmp_path, code, globals_=["mdesc mD"], locals_=["num l_i", "num l_n"],
              programs={"step": {"params": ["num x_n"], "code": step}}, duration=400.0, robot=load_robot("tx2-60"))
    assert not [d for d in res.diagnostics if d.severity is not None and d.severity.label == "error"]
    assert len(asked) > 300
    assert all(got == want for got, want in asked)
