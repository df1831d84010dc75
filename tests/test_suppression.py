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
