"""The `text` format: layout, caret position, colour, summary and statistics."""

from __future__ import annotations

import re

from val3check.diagnostics import Severity
from val3check.reporting import render

ANSI = re.compile(r"\x1b\[[0-9;]*m")


def caret_under(output: str, source_display: str) -> str:
    """The characters of the displayed source line that the caret run underlines."""
    lines = output.splitlines()
    i = next(k for k, ln in enumerate(lines) if ln.endswith(source_display))
    src, carets = lines[i], lines[i + 1]
    start = carets.index("^")
    end = len(carets)
    assert set(carets[start:]) == {"^"}
    return src[start:end]


def test_layout_exact(workdir, make_result, d):
    (workdir / "start.pgx").write_text("begin\n  while true\n  endWhile\nend\n", encoding="utf-8")
    result = make_result([d("F101", "unexpected 'endWhile'", "start.pgx", 3, 3, 3, 11)], files=["a.pgx", "start.pgx"])
    assert render("text", result) == (
        "start.pgx:3:3: F101 [error] unexpected 'endWhile'\n"
        "  |\n"
        "3 |   endWhile\n"
        "  |   ^^^^^^^^\n"
        "\n"
        "Found 1 error in 1 file (2 files checked).\n"
    )


def test_single_caret_without_end(workdir, make_result, d):
    (workdir / "a.pgx").write_text("x = 1\n", encoding="utf-8")
    out = render("text", make_result([d("S301", "unused", "a.pgx", 1, 5)]))
    assert out.splitlines()[1:4] == ["  |", "1 | x = 1", "  |     ^"]


def test_gutter_width_follows_line_number(workdir, make_result, d):
    (workdir / "a.pgx").write_text("\n" * 11 + "foo\n", encoding="utf-8")
    out = render("text", make_result([d("S301", "unused", "a.pgx", 12, 1)]))
    assert out.splitlines()[1:4] == ["   |", "12 | foo", "   | ^"]


def test_tabs_keep_caret_aligned(workdir, make_result, d):
    source = "\tif x <\tfoo and\tbar"
    (workdir / "a.pgx").write_text(source + "\n", encoding="utf-8")
    col_foo = source.index("foo") + 1
    col_bar = source.index("bar") + 1
    result = make_result([d("S301", "foo", "a.pgx", 1, col_foo, 1, col_foo + 3), d("S301", "bar", "a.pgx", 1, col_bar)])
    out = render("text", result)
    assert "\t" not in out
    displayed = [ln for ln in out.splitlines() if ln.startswith("1 |")][0][len("1 | ") :]
    assert displayed == source.expandtabs(4)
    assert caret_under(out.split("\n\n")[0], displayed) == "foo"
    assert caret_under(out.split("\n\n")[1], displayed) == "b"


def test_non_ascii_before_column(workdir, make_result, d):
    source = "  // héhé ünïcode: target"
    (workdir / "a.pgx").write_text(source + "\n", encoding="utf-8")
    col = source.index("target") + 1
    out = render("text", make_result([d("S301", "x", "a.pgx", 1, col, 1, col + 6)]))
    assert caret_under(out, source) == "target"


def test_bom_and_crlf(workdir, make_result, d):
    (workdir / "a.pgx").write_bytes("\ufeffbegin\r\n  call x()\r\nend\r\n".encode("utf-8"))
    out = render("text", make_result([d("F101", "bad call", "a.pgx", 2, 3, 2, 7), d("F101", "first", "a.pgx", 1, 1)]))
    assert "1 | begin\n  | ^\n" in out
    assert "\r" not in out
    assert caret_under(out.split("\n\n")[1], "  call x()") == "call"


def test_invalid_utf8_is_replaced(workdir, make_result, d):
    (workdir / "a.pgx").write_bytes(b"ab\xffcd\n")
    out = render("text", make_result([d("S301", "x", "a.pgx", 1, 4)]))
    assert "1 | ab\ufffdcd\n  |    ^\n" in out


def test_control_characters_are_neutralised(workdir, make_result, d):
    (workdir / "a.pgx").write_text("a\x1b[31mb\n", encoding="utf-8")
    out = render("text", make_result([d("S301", "x", "a.pgx", 1, 7)]))
    assert "\x1b" not in out
    assert caret_under(out, "a\u241b[31mb") == "b"  # ESC shown as its Control Picture


def test_whole_file_and_missing_file_have_no_snippet(workdir, make_result, d):
    result = make_result(
        [d("F001", "cannot read this file", "gone.pgx"), d("F101", "oops", "missing.pgx", 4, 2)],
        files=["gone.pgx", "missing.pgx"],
    )
    out = render("text", result)
    assert out == (
        "gone.pgx: F001 [error] cannot read this file\n"
        "\n"
        "missing.pgx:4:2: F101 [error] oops\n"
        "\n"
        "Found 2 errors in 2 files (2 files checked).\n"
    )


def test_line_beyond_end_of_file(workdir, make_result, d):
    (workdir / "a.pgx").write_text("one line\n", encoding="utf-8")
    out = render("text", make_result([d("F101", "oops", "a.pgx", 9, 1)]))
    assert out.startswith("a.pgx:9:1: F101 [error] oops\n\nFound")


def test_no_column_underlines_the_line(workdir, make_result, d):
    (workdir / "a.pgx").write_text("begin\n    x = 1  \nend\n", encoding="utf-8")
    out = render("text", make_result([d("S301", "whole line", "a.pgx", 2, 0)]))
    assert out.splitlines()[0] == "a.pgx:2: S301 [warning] whole line"
    assert caret_under(out, "    x = 1  ".rstrip()) == "x = 1"


def test_multiline_span_underlines_to_end_of_line(workdir, make_result, d):
    (workdir / "a.pgx").write_text("  if a\n  endIf\n", encoding="utf-8")
    out = render("text", make_result([d("F101", "block", "a.pgx", 1, 3, 2, 8)]))
    assert caret_under(out, "  if a") == "if a"


def test_file_read_once(workdir, make_result, d, monkeypatch):
    (workdir / "a.pgx").write_text("a\nb\nc\n", encoding="utf-8")
    from val3check import confine

    opened = []
    real_read = confine.read_bytes

    def counting_read(path, *args, **kwargs):
        if str(path).endswith("a.pgx"):
            opened.append(path)
        return real_read(path, *args, **kwargs)

    monkeypatch.setattr(confine, "read_bytes", counting_read)
    render("text", make_result([d("S301", "x", "a.pgx", n, 1) for n in (1, 2, 3)]))
    assert len(opened) == 1


def test_colour(workdir, make_result, d):
    (workdir / "a.pgx").write_text("x = 1\n", encoding="utf-8")
    result = make_result([d("S301", "unused", "a.pgx", 1, 1), d("F101", "bad", "a.pgx", 1, 3)])
    plain = render("text", result)
    coloured = render("text", result, color=True)
    assert "\x1b" not in plain
    assert "\x1b[31m" in coloured and "\x1b[33m" in coloured  # error red, warning yellow
    assert ANSI.sub("", coloured) == plain
    assert "\x1b" not in render("text", result, color=False, statistics=True)


def test_summary_wording(make_result, d):
    assert render("text", make_result([], files=["a", "b", "c", "d", "e"])) == "All checks passed (5 files checked).\n"
    assert render("text", make_result([], files=["a"])) == "All checks passed (1 file checked).\n"
    result = make_result(
        [
            d("F101", "e1", "x.pgx", 1, 1),
            d("F101", "e2", "x.pgx", 2, 1),
            d("F101", "e3", "y.pgx", 1, 1),
            d("S301", "w", "y.pgx", 3, 1),
        ],
        files=["x.pgx", "y.pgx", "z1", "z2", "z3"],
    )
    assert render("text", result).endswith("\nFound 3 errors, 1 warning in 2 files (5 files checked).\n")
    result = make_result([d("N201", "i", "x.pgx", 1, 1), d("N201", "i2", "x.pgx", 1, 2)], files=["x.pgx"])
    assert render("text", result).endswith("\nFound 2 info in 1 file (1 file checked).\n")


def test_severity_comes_from_the_diagnostic(make_result, d):
    out = render("text", make_result([d("F101", "demoted", "x.pgx", severity=Severity.WARNING)]))
    assert out.startswith("x.pgx: F101 [warning] demoted\n")
    assert "Found 1 warning in 1 file" in out


def test_statistics(workdir, make_result, d):
    (workdir / "a.pgx").write_text("x\n" * 5, encoding="utf-8")
    diagnostics = [d("S301", "w", "a.pgx", n, 1) for n in (1, 2, 3)]
    diagnostics += [d("F101", "e", "a.pgx", n, 1) for n in (4, 5)]
    diagnostics += [d("N201", "i", "a.pgx", 1, 1), d("F001", "unreadable", "b.pgx"), d("X999", "unknown", "b.pgx")]
    out = render("text", make_result(diagnostics), statistics=True)
    assert out == (
        "3  S301  [warning]  unused-variable\n"
        "2  F101  [error]    syntax-error\n"
        "1  F001  [error]    file-unreadable\n"
        "1  N201  [info]     bad-name\n"
        "1  X999  [warning]\n"
        "\n"
        "Found 3 errors, 4 warnings, 1 info in 2 files (2 files checked).\n"
    )


def test_statistics_without_findings(make_result):
    assert render("text", make_result([], files=["a"]), statistics=True) == "All checks passed (1 file checked).\n"
