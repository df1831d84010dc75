"""`// val3check: ignore[CODE]` comments."""

from __future__ import annotations

from support import lint

from val3check.testing import write_app


def codes(tmp_path):
    return [d.code for d in lint([tmp_path / "Example"], cwd=tmp_path).result.diagnostics]


def test_comment_on_the_line_before_suppresses(tmp_path):
    write_app(tmp_path, "begin\n  // val3check: ignore[F101]\n  n = 1 +\nend\n")
    assert "F101" not in codes(tmp_path)


def test_trailing_comment_suppresses_its_line(tmp_path):
    write_app(tmp_path, "begin\n  n = 1 + // val3check: ignore[F1]\nend\n")
    assert "F101" not in codes(tmp_path)


def test_other_code_does_not_suppress(tmp_path):
    write_app(tmp_path, "begin\n  // val3check: ignore[L001]\n  n = 1 +\nend\n")
    assert "F101" in codes(tmp_path)


def test_bare_ignore_suppresses_everything_on_the_next_line(tmp_path):
    write_app(tmp_path, "begin\n  // val3check: ignore\n\n  n = 1 +\nend\n")
    assert "F101" not in codes(tmp_path)


def test_suppression_does_not_reach_further_lines(tmp_path):
    write_app(tmp_path, "begin\n  // val3check: ignore[F101]\n  n = 1\n  n = 1 +\nend\n")
    assert "F101" in codes(tmp_path)


def findings(tmp_path, settings=None):
    return [(d.code, d.line, d.col) for d in lint([tmp_path / "Example"], settings, cwd=tmp_path).result.diagnostics]


def test_unknown_code_is_reported_at_the_comment(tmp_path):
    write_app(tmp_path, "begin\n  // val3check: ignore[S015, Q12]\n  nX = nX\nend\n", globals_=["num nX"])
    got = findings(tmp_path)
    assert ("S020", 5, 3) in got  # line 2 of the code is line 5 of the file; the comment starts at column 3
    assert not [g for g in got if g[0] in ("S015", "S021")]  # S015 is suppressed; Q12 is S020's, not S021's


def test_unused_suppression(tmp_path):
    write_app(tmp_path, "begin\n  // val3check: ignore[S015]\n  nX = 1\nend\n", globals_=["num nX"])
    assert ("S021", 5, 3) in findings(tmp_path)
    write_app(tmp_path, "begin\n  // val3check: ignore\n  nX = 1\nend\n", globals_=["num nX"])
    got = lint([tmp_path / "Example"], cwd=tmp_path).result.diagnostics
    assert [d.message for d in got if d.code == "S021"] == [
        "unused suppression: no finding of every rule on line 5 and 6; remove the comment"]


def test_a_suppression_for_a_rule_not_selected_is_not_unused(tmp_path):
    from val3check.config import Settings

    write_app(tmp_path, "begin\n  // val3check: ignore[S015]\n  nX = nX\nend\n", globals_=["num nX"])
    assert findings(tmp_path, Settings(select=["F", "S02"])) == []


def test_no_unused_suppression_in_a_program_that_does_not_parse(tmp_path):
    write_app(tmp_path, "begin\n  // val3check: ignore[S015]\n  nX = 1\n  if true\nend\n", globals_=["num nX"])
    got = findings(tmp_path)
    assert [g[0] for g in got] == ["F101"]
