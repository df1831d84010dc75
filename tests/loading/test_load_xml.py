"""Secure XML reading: entities, DTDs, decoding, malformed files, file size."""

from __future__ import annotations

import os
import socket

import pytest
from loadhelp import PGX_NS, XSI, codes, make_app, pgx, pjx, write

from val3check.loading import LoadOptions, load
from val3check.confine import Roots
from val3check.loading.xmlread import read_xml

BILLION_LAUGHS = """<?xml version="1.0"?>
<!DOCTYPE lolz [
 <!ENTITY lol "lol">
 <!ENTITY lol1 "&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;">
 <!ENTITY lol2 "&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;">
 <!ENTITY lol3 "&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;">
 <!ENTITY lol4 "&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;">
 <!ENTITY lol5 "&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;">
 <!ENTITY lol6 "&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;">
 <!ENTITY lol7 "&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;">
 <!ENTITY lol8 "&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;">
 <!ENTITY lol9 "&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;">
]>
<Programs xmlns="http://www.staubli.com/robotics/VAL3/Program/2">
  <Program name="start"><Code>&lol9;</Code></Program>
</Programs>
"""


def _pgx_with_doctype(doctype: str, body: str = "begin\nend") -> str:
    return (
        '<?xml version="1.0"?>\n'
        f"{doctype}\n"
        f'<Programs xmlns="{PGX_NS}">\n'
        f'  <Program name="start"><Code>{body}</Code></Program>\n'
        "</Programs>\n"
    )


def _single(tmp_path, text: str | bytes, name: str = "start.pgx"):
    f = tmp_path / "P" / name
    f.parent.mkdir(parents=True, exist_ok=True)
    if isinstance(text, str):
        text = text.encode("utf-8")
    f.write_bytes(text)
    ws, diags = load([str(f)])
    return f, ws, diags


def test_billion_laughs_is_rejected_quickly(tmp_path):
    f, ws, diags = _single(tmp_path, BILLION_LAUGHS)
    f005 = codes(diags, "F005")
    assert len(f005) == 1
    assert (f005[0].path, f005[0].line, f005[0].col) == (str(f), 2, 1)  # the <!DOCTYPE that declares them
    assert "lol" in f005[0].message
    # nothing was loaded from the file
    app = ws.apps[ws.targets[0]]
    assert app.programs == {}


@pytest.mark.parametrize(
    "decl",
    [
        '<!DOCTYPE Programs [ <!ENTITY xxe SYSTEM "file:///etc/passwd"> ]>',
        '<!DOCTYPE Programs [ <!ENTITY xxe SYSTEM "/etc/passwd"> ]>',
        '<!DOCTYPE Programs [ <!ENTITY xxe SYSTEM "http://127.0.0.1:9/evil.xml"> ]>',
        '<!DOCTYPE Programs [ <!ENTITY % pe SYSTEM "http://127.0.0.1:9/evil.dtd"> %pe; ]>',
    ],
)
def test_external_entities_are_never_read(tmp_path, decl, monkeypatch):
    opened = []
    real_open = open

    def spy_open(file, *a, **k):  # noqa: ANN001
        opened.append(str(file))
        return real_open(file, *a, **k)

    def no_network(*a, **k):  # noqa: ANN001
        raise AssertionError("network access attempted")

    monkeypatch.setattr("builtins.open", spy_open)
    monkeypatch.setattr(socket, "create_connection", no_network)
    monkeypatch.setattr(socket.socket, "connect", no_network)
    f, ws, diags = _single(tmp_path, _pgx_with_doctype(decl, "&xxe;"))
    f005 = codes(diags, "F005")
    assert len(f005) == 1, diags
    assert f005[0].path == str(f) and f005[0].line == 2
    assert "root:" not in f005[0].message  # no content of /etc/passwd
    assert not any("passwd" in o for o in opened)


def test_external_dtd_is_not_fetched(tmp_path):
    f, ws, diags = _single(tmp_path, _pgx_with_doctype('<!DOCTYPE Programs SYSTEM "http://127.0.0.1:9/x.dtd">'))
    f005 = codes(diags, "F005")
    assert len(f005) == 1 and f005[0].line == 2


def test_doctype_without_entities_is_accepted(tmp_path):
    f, ws, diags = _single(tmp_path, _pgx_with_doctype("<!DOCTYPE Programs>"))
    assert codes(diags, "F005") == [] and codes(diags, "F004") == []
    assert ws.apps[ws.targets[0]].programs["start"].code == "begin\nend"


def test_undefined_entity_reference_is_f005(tmp_path):
    text = pgx("start", "x").replace("<![CDATA[x]]>", "begin &nbsp; end")
    f, ws, diags = _single(tmp_path, text)
    f005 = codes(diags, "F005")
    assert len(f005) == 1
    assert f005[0].line == 4 and "&nbsp;" in f005[0].message


def test_predefined_entities_and_char_refs_are_fine(tmp_path):
    text = pgx("start", "x").replace("<![CDATA[x]]>", "a&lt;b&gt;c&amp;d&quot;e&apos;f&#233;&#x41;")
    f, ws, diags = _single(tmp_path, text)
    assert [d for d in diags if d.code != "F009"] == []
    assert ws.apps[ws.targets[0]].programs["start"].code == "a<b>c&d\"e'féA"


def test_invalid_utf8_position(tmp_path):
    data = pgx("start", "begin\n  // caf\u00e9 ok\n  // bad: @ here\nend").encode("utf-8")
    data = data.replace(b"@", b"\xff")
    f, ws, diags = _single(tmp_path, data)
    f003 = codes(diags, "F003")
    assert len(f003) == 1
    d = f003[0]
    # line 6 of the file: "  // bad: \xff here"
    assert (d.line, d.col) == (6, 11)
    assert "0xFF" in d.message


def test_invalid_utf8_position_counts_code_points_and_crlf(tmp_path):
    data = "<a>\r\n\u00e9\u00e9\u00e9".encode("utf-8") + b"\xc3(" + b"</a>"
    f = tmp_path / "x.pgx"
    f.write_bytes(data)
    res = read_xml(str(f), 1 << 20, Roots.user_given())
    assert res.root is None
    assert [(d.code, d.line, d.col) for d in res.diagnostics] == [("F003", 2, 4)]


def test_bom_and_crlf_are_accepted(tmp_path):
    f = write(tmp_path / "A" / "start.pgx", pgx("start", "begin\n  x=1\nend"), bom=True, crlf=True)
    ws, diags = load([str(f)])
    prog = ws.apps[ws.targets[0]].programs["start"]
    assert prog.code == "begin\n  x=1\nend"
    assert prog.origin.line == 3


def test_lone_cr_line_ends(tmp_path):
    f = write(tmp_path / "A" / "start.pgx", pgx("start", "begin\n  x=1\nend").replace("\n", "\r"))
    ws, diags = load([str(f)])
    prog = ws.apps[ws.targets[0]].programs["start"]
    assert prog.code == "begin\n  x=1\nend"
    assert prog.code_map.to_file(3, 1).line == 6


@pytest.mark.parametrize(
    "text, line, col, words",
    [
        (
            '<?xml version="1.0"?>\n<Programs>\n  <Program name="a">\n</Programs>\n',
            4,
            3,
            "does not match the open element <Program>",
        ),
        ('<?xml version="1.0"?>\n<Programs>\n  <Program name="a">\n    <Code>begin', 4, 16, "truncated"),
        ('<?xml version="1.0"?>\n<Programs>\n  <Program name="a" name="b"/>\n</Programs>\n', 3, 21, "twice"),
        ('<?xml version="1.0"?>\n<Programs>\n  <Code>if a < b</Code>\n</Programs>\n', 3, 15, "&lt;"),
        ('<?xml version="1.0"?>\n<Programs/>\n<Programs/>\n', 3, 1, "after the end of the root element"),
        ('<?xml version="1.0"?>\n<Programs>\n  <Code><![CDATA[begin\n', 3, 9, "CDATA"),
    ],
)
def test_malformed_xml(tmp_path, text, line, col, words):
    f = tmp_path / "start.pgx"
    f.write_text(text)
    res = read_xml(str(f), 1 << 20, Roots.user_given())
    assert res.root is None
    [d] = res.diagnostics
    assert d.code == "F004"
    assert (d.line, d.col) == (line, col), d
    assert words in d.message


def test_empty_file(tmp_path):
    f, ws, diags = _single(tmp_path, b"")
    f004 = codes(diags, "F004")
    assert len(f004) == 1 and f004[0].line == 0 and "empty" in f004[0].message


def test_truncated_project_reported_and_loading_goes_on(tmp_path):
    good = make_app(tmp_path / "Good")
    bad = write(tmp_path / "Bad" / "Bad.pjx", pjx()[:120])
    write(tmp_path / "Bad" / "start.pgx", pgx("start"))
    ws, diags = load([str(tmp_path)])
    assert [d.code for d in diags if d.path == str(bad)] == ["F004"]
    assert str(good) in ws.targets


def test_wrong_root_and_namespace(tmp_path):
    html = write(tmp_path / "Web" / "Web.pjx", "<html><body>hello</body></html>\n")
    ws, diags = load([str(html)])
    [d] = diags
    assert d.code == "F006" and d.line == 1 and "<html>" in d.message
    foreign = write(tmp_path / "F" / "F.pjx", '<Project xmlns="http://example.com/other/Project/3"/>')
    ws, diags = load([str(foreign)])
    assert [d.code for d in diags] == ["F006"]
    # a program file given as project
    prog = write(tmp_path / "G" / "G.pjx", pgx("start"))
    ws, diags = load([str(prog)])
    assert [d.code for d in diags] == ["F006"] and "program file" in diags[0].message


def test_unknown_namespace_version_is_fine(tmp_path):
    app = make_app(tmp_path / "App")
    app.write_text(app.read_text().replace("Project/3", "Project/4"))
    (tmp_path / "App" / "start.pgx").write_text(pgx("start").replace("Program/2", "Program/7"))
    ws, diags = load([str(app)])
    assert diags == []
    assert set(ws.apps[str(app)].programs) == {"start", "stop"}


def test_too_large_file_is_skipped(tmp_path):
    app = make_app(tmp_path / "App")
    big = tmp_path / "App" / "start.pgx"
    with open(big, "wb") as fh:  # 50 MB, sparse
        fh.truncate(50 * 1024 * 1024)
    ws, diags = load([str(app)])
    f002 = codes(diags, "F002")
    assert len(f002) == 1 and f002[0].path == str(big) and f002[0].line == 0
    assert "50.0 MB" in f002[0].message
    assert set(ws.apps[str(app)].programs) == {"stop"}


def test_max_file_size_option(tmp_path):
    app = make_app(tmp_path / "App")
    ws, diags = load([str(app)], LoadOptions(max_file_size=100))
    assert [d.path for d in diags] == [str(app)]  # the project cannot be read: nothing else is
    assert codes(diags, "F002") == diags and ws.targets == []
    ws, diags = load([str(app)], LoadOptions(max_file_size=300))  # the project is 356 bytes
    assert [d.code for d in diags] == ["F002"]
    ws, diags = load([str(app.parent / "start.pgx")], LoadOptions(max_file_size=300))
    assert diags == [] or [d.code for d in diags] == ["F009"]
    ws, diags = load([str(app)], LoadOptions(max_file_size=10_000))
    assert diags == []


def test_utf16_with_bom_is_accepted(tmp_path):
    f = tmp_path / "A" / "start.pgx"
    f.parent.mkdir()
    f.write_bytes(pgx("start", "begin\nend").replace('encoding="utf-8"', 'encoding="utf-16"').encode("utf-16"))
    ws, diags = load([str(f)])
    assert ws.apps[ws.targets[0]].programs["start"].code == "begin\nend"


def test_declared_encoding_is_ignored_in_favour_of_utf8(tmp_path):
    f = write(
        tmp_path / "A" / "start.pgx", pgx("start", "begin\n  // \u00e9t\u00e9\nend").replace("utf-8", "iso-8859-1")
    )
    ws, diags = load([str(f)])
    assert "\u00e9t\u00e9" in ws.apps[ws.targets[0]].programs["start"].code


@pytest.mark.skipif(os.geteuid() == 0 if hasattr(os, "geteuid") else True, reason="root reads everything")
def test_unreadable_file(tmp_path):  # pragma: no cover - depends on the user
    app = make_app(tmp_path / "App")
    f = tmp_path / "App" / "start.pgx"
    f.chmod(0)
    try:
        ws, diags = load([str(app)])
    finally:
        f.chmod(0o644)
    assert [(d.code, d.path) for d in diags] == [("F001", str(f))]
    assert "permission" in diags[0].message


def test_xsi_prefix_must_be_declared(tmp_path):
    text = f'<Programs xmlns="{PGX_NS}"><Program name="a" xsi:type="x"><Code>begin</Code></Program></Programs>'
    f, ws, diags = _single(tmp_path, text)
    assert [d.code for d in codes(diags, "F004")] == ["F004"]
    assert "xmlns:xsi" in codes(diags, "F004")[0].message
    assert XSI  # the helper's declaration is the fix
