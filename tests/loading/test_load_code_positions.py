"""Program.code and Program.code_map: every character maps back to its file position."""

from __future__ import annotations

from .loadhelp import PGX_NS, XSI, write

from val3check.loading import load
from val3check.positions import Position


def _load_code(tmp_path, code_element: str, *, bom=False, crlf=False, before: str = ""):
    text = (
        '<?xml version="1.0" encoding="utf-8"?>\n'  # line 1
        f'<Programs {XSI} xmlns="{PGX_NS}">\n'  # line 2
        '  <Program name="start">\n'  # line 3
        f"{before}"
        f"{code_element}\n"
        "  </Program>\n"
        "</Programs>\n"
    )
    f = write(tmp_path / "A" / "start.pgx", text, bom=bom, crlf=crlf)
    ws, diags = load([str(f)])
    assert [d.code for d in diags] == ["F009"], diags
    prog = ws.apps[ws.targets[0]].programs["start"]
    return text, prog


def _file_char(text: str, pos: Position) -> str:
    """The character at a 1-based (line, col) of `text` (LF line ends)."""
    return text.split("\n")[pos.line - 1][pos.col - 1]


def _check_all(text: str, prog) -> None:
    """Every non-newline character of the code maps to the same character in the file."""
    for i, line in enumerate(prog.code.split("\n"), 1):
        for j, ch in enumerate(line, 1):
            pos = prog.code_map.to_file(i, j)
            got = _file_char(text, pos)
            assert got in (ch, "&"), (i, j, ch, pos, got)  # "&": the start of a reference


def test_cdata_on_the_same_line(tmp_path):
    text, prog = _load_code(tmp_path, "    <Code><![CDATA[begin\n  x = 1\nend]]></Code>")
    assert prog.code == "begin\n  x = 1\nend"
    assert prog.code_map.to_file(1, 1) == Position(4, 20)
    assert prog.code_map.to_file(2, 3) == Position(5, 3)
    assert prog.code_map.to_file(3, 1) == Position(6, 1)
    _check_all(text, prog)


def test_cdata_on_the_next_line(tmp_path):
    text, prog = _load_code(tmp_path, "    <Code>\n<![CDATA[begin\n  x = 1\nend]]>\n    </Code>")
    # the newline before the CDATA section is text of <Code>: code line 1 is empty
    assert prog.code == "\nbegin\n  x = 1\nend\n    "
    assert prog.code_map.to_file(2, 1) == Position(5, 10)
    assert prog.code_map.to_file(3, 3) == Position(6, 3)
    _check_all(text, prog)


def test_escaped_text_with_entities(tmp_path):
    code = "    <Code>begin\n  if len(s)&gt;4 and a&amp;&amp;b\n    x = &quot;&#233;&quot; // y\n  endIf\nend</Code>"
    text, prog = _load_code(tmp_path, code)
    assert prog.code == 'begin\n  if len(s)>4 and a&&b\n    x = "\u00e9" // y\n  endIf\nend'
    assert prog.code_map.to_file(1, 1) == Position(4, 11)
    line2 = "  if len(s)>4 and a&&b"
    gt = line2.index(">") + 1
    assert prog.code_map.to_file(2, gt) == Position(5, gt)  # the "&" of "&gt;"
    assert prog.code_map.to_file(2, gt + 1) == Position(5, gt + 4)  # "4", after "&gt;"
    amp = line2.index("&") + 1
    file_line = "  if len(s)&gt;4 and a&amp;&amp;b"
    assert prog.code_map.to_file(2, amp + 2) == Position(5, file_line.index("b") + 1)
    line3 = '    x = "\u00e9" // y'
    slash = line3.index("/") + 1
    assert prog.code_map.to_file(3, slash) == Position(6, "    x = &quot;&#233;&quot; // y".index("/") + 1)
    # lines without entities need no column map
    assert 0 not in prog.code_map.col_maps and 3 not in prog.code_map.col_maps
    _check_all(text, prog)


def test_mixed_cdata_and_escaped_text(tmp_path):
    text, prog = _load_code(tmp_path, "    <Code>begin\n  a = b &lt; c<![CDATA[ and d < e]]>\nend</Code>")
    assert prog.code == "begin\n  a = b < c and d < e\nend"
    col = prog.code.split("\n")[1].index("d") + 1
    assert prog.code_map.to_file(2, col) == Position(5, "  a = b &lt; c<![CDATA[ and d".index("d") + 1)
    _check_all(text, prog)


def test_crlf_and_bom(tmp_path):
    text, prog = _load_code(tmp_path, "    <Code><![CDATA[begin\n  x = 1\n  y = 2\nend]]></Code>", bom=True, crlf=True)
    assert prog.code == "begin\n  x = 1\n  y = 2\nend"  # CRLF -> LF
    assert prog.code_map.to_file(1, 1) == Position(4, 20)  # the BOM is not a column
    assert prog.code_map.to_file(3, 3) == Position(6, 3)
    _check_all(text.replace("\r\n", "\n"), prog)


def test_crlf_escaped_text(tmp_path):
    text, prog = _load_code(tmp_path, "    <Code>begin\n  a = b &gt; c\nend</Code>", crlf=True)
    assert prog.code == "begin\n  a = b > c\nend"
    assert prog.code_map.to_file(2, 11) == Position(5, 14)


def test_columns_count_code_points(tmp_path):
    text, prog = _load_code(
        tmp_path, '    <Description>\u00e9\u00e9</Description><Code><![CDATA[begin\n  s = "\u00e9" x\nend]]></Code>'
    )
    start = "    <Description>\u00e9\u00e9</Description><Code><![CDATA[".__len__() + 1
    assert prog.code_map.to_file(1, 1) == Position(4, start)
    assert prog.code_map.to_file(2, 10) == Position(5, 10)  # "x" after a 1-code-point "é"
    assert prog.description == "\u00e9\u00e9"
    _check_all(text, prog)


def test_char_reference_newline_in_code(tmp_path):
    text, prog = _load_code(tmp_path, "    <Code>begin&#13;&#10;  x = 1&#10;end</Code>")
    assert prog.code == "begin\n  x = 1\nend"
    assert prog.code_map.to_file(2, 3) == Position(4, "    <Code>begin&#13;&#10;  x".index("x") + 1)
    assert prog.code_map.to_file(3, 1) == Position(4, "    <Code>begin&#13;&#10;  x = 1&#10;e".index("e", 30) + 1)


def test_empty_code(tmp_path):
    text, prog = _load_code(tmp_path, "    <Code></Code>")
    assert prog.code == ""
    assert prog.code_map.to_file(1, 1).line == 4


def test_s6_code_escaped(tmp_path):
    text = (
        '<?xml version="1.0" encoding="utf-8" ?>\n'
        '<programList xmlns="ProgramNameSpace" >\n'
        '  <program name="stop" public="false" >\n'
        "    <description />\n"
        "    <paramSection/>\n"
        "    <localSection/>\n"
        "    <source>\n"
        "      <code>begin\n"
        "  popUpMsg(&quot;done&quot;)\n"
        "end\n"
        "\n"
        "      </code>\n"
        "    </source>\n"
        "  </program>\n"
        "</programList>\n"
    )
    f = write(tmp_path / "A" / "stop.pgx", text, crlf=True)
    ws, diags = load([str(f)])
    prog = ws.apps[ws.targets[0]].programs["stop"]
    assert prog.code == 'begin\n  popUpMsg("done")\nend\n\n      '
    assert prog.code_map.to_file(1, 1) == Position(8, 13)
    assert prog.code_map.to_file(2, 12) == Position(9, 12)  # the '"' from "&quot;"
    assert prog.code_map.to_file(2, 13) == Position(9, 18)  # "d" after "&quot;"
    assert prog.code_map.to_file(3, 1) == Position(10, 1)
    assert prog.access == "private"


def test_cdata_sections_map_like_character_by_character():
    # a CDATA section is mapped in one piece (speed): same text and positions as expat's chunks
    from val3check.loading.xmlread import parse

    for data, text, starts, maps in [
        (b"<Code><![CDATA[begin\r\n  x = 1\r\nend]]></Code>", "begin\n  x = 1\nend", [(1, 16), (2, 1), (3, 1)], {}),
        (b"<Code>\n  <![CDATA[begin\n  x = 1\n]]><![CDATA[  y = 2\nend]]></Code>",
         "\n  begin\n  x = 1\n  y = 2\nend", [(1, 1), (2, 1), (3, 1), (4, 13), (5, 1)],
         {1: [1, 2, 12, 13, 14, 15, 16]}),
        (b"<Code>  pre &gt; <![CDATA[begin\n\n\nend]]> post\nz</Code>", "  pre > begin\n\n\nend post\nz",
         [(1, 7), (2, 1), (3, 1), (4, 1), (5, 1)],
         {0: [7, 8, 9, 10, 11, 12, 13, 17, 27, 28, 29, 30, 31], 3: [1, 2, 3, 7, 8, 9, 10, 11]}),
        (b"<Code><![CDATA[\n]]></Code>", "\n", [(1, 1), (2, 1)], {}),
    ]:
        root, diags = parse(data, "t.pgx")
        assert not diags and root.text == text
        assert [(p.line, p.col) for p in root.smap.line_starts] == starts
        assert root.smap.col_maps == maps


def test_shared_line_starts_are_the_positions_of_those_lines(monkeypatch):
    """`positions.line_starts` reuses the Position(k, 1) of lines seen before, and past its
    cap makes them anew: the same list either way."""
    from val3check import positions

    monkeypatch.setattr(positions, "_LINE_STARTS", [positions.Position(0, 1)])
    monkeypatch.setattr(positions, "_LINE_STARTS_MAX", 30)
    for first, stop in ((5, 9), (1, 3), (7, 25), (20, 45), (40, 60), (3, 3), (31, 32)):
        assert positions.line_starts(first, stop) == [positions.Position(k, 1) for k in range(first, stop)]
    assert len(positions._LINE_STARTS) == 31
