"""`lint --fix` / `--diff` (issue 16 item 9): certain fixes, everything else byte for byte."""

from __future__ import annotations

import pytest
from support import lint
from test_cli_conventions import val3check

from val3check.fixes import plan
from val3check.rules.catalogue import catalogue
from val3check.testing import PGX_NS, PJX_NS, XSI, code_position, write_app, write_files

BOM = b"\xef\xbb\xbf"


def _pgx(code: str, locals_: str, newline: str = "\r\n", cdata: bool = True) -> bytes:
    body = f"<Code><![CDATA[{code}]]></Code>" if cdata else f"<Code>{code}</Code>"
    text = (f'<?xml version="1.0" encoding="utf-8"?>\n<Programs {XSI} xmlns="{PGX_NS}">\n'
            f'  <Program name="start" access="public">\n    <Locals>\n{locals_}    </Locals>\n'
            f"    {body}\n  </Program>\n</Programs>\n")
    return BOM + text.replace("\n", newline).encode("utf-8")


def _app(tmp_path, pgx: bytes, pjx_newline: str = "\r\n", indent: str = "\t", extra: dict | None = None):
    pjx = (f'<?xml version="1.0" encoding="utf-8"?>\n<Project xmlns="{PJX_NS}">\n'
           f'{indent}<Parameters version="s7.11" stackSize="5000" millimeterUnit="true"/>\n'
           f"{indent}<Programs>\n{indent}{indent}<Program file='start.pgx'/>\n{indent}</Programs>\n"
           f'{indent}<Database>\n{indent}{indent}<Data file="App.dtx"/>\n{indent}</Database>\n</Project>')
    dtx = (f'<?xml version="1.0" encoding="utf-8"?>\n<Database {XSI} xmlns="http://www.staubli.com/robotics/VAL3/Data/2">'
           f'\n  <Datas>\n    <Data name="nCount" access="public" xsi:type="array" type="num" size="1" />\n'
           f"  </Datas>\n</Database>\n")
    files = {"App/App.pjx": pjx.replace("\n", pjx_newline).encode(), "App/App.dtx": dtx, "App/start.pgx": pgx}
    files.update(extra or {})
    write_files(tmp_path, files)
    return tmp_path / "App"


LOCALS = ('      <Local name="l_used" type="num" xsi:type="array" size="1" />\n'
          '      <Local name="l_gone" type="num" xsi:type="array" size="1" />\n')


def test_fix_keeps_every_other_byte_bom_crlf_cdata(tmp_path):
    code = "begin\n  l_used = ncount + 1 // a comment about ncount\n  nCount = l_used\nend"
    folder = _app(tmp_path, _pgx(code, LOCALS))
    before = (folder / "start.pgx").read_bytes()
    r = val3check("lint", "App", "--fix", "--fail-on", "info", "--ignore", "S010", cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "fixed 2 findings in 1 file" in r.stderr
    after = (folder / "start.pgx").read_bytes()
    expected = before.replace(b'      <Local name="l_gone" type="num" xsi:type="array" size="1" />\r\n', b"")
    expected = expected.replace(b"l_used = ncount + 1", b"l_used = nCount + 1")  # the comment keeps its text
    assert after == expected
    assert after.startswith(BOM) and after.count(b"\r\n") == before.count(b"\r\n") - 1
    # a second run has nothing to fix
    r = val3check("lint", "App", "--diff", cwd=tmp_path)
    assert r.returncode == 0 and r.stdout == ""


def test_fix_in_escaped_code_and_an_element_with_a_closing_tag(tmp_path):
    code = "begin&#13;&#10;  if nCount &lt; 1 and ncount &gt; 0&#13;&#10;    nCount = 2&#13;&#10;  endIf&#13;&#10;end"
    locals_ = '      <Local name="l_gone" type="num" xsi:type="array" size="1"></Local>\n'
    folder = _app(tmp_path, _pgx(code, locals_, newline="\n", cdata=False))
    before = (folder / "start.pgx").read_bytes()
    fixes = plan(lint([folder], cwd=tmp_path).findings)
    assert fixes.count == 2 and not fixes.not_fixed
    expected = before.replace(locals_.encode(), b"").replace(b"and ncount &gt;", b"and nCount &gt;")
    assert fixes.result(str(folder / "start.pgx")) == expected


def test_an_unlisted_program_file_is_a_suggestion_never_a_fix(tmp_path):
    # issue 25 class 7: listing a backup (with a syntax error) would make a clean application fail
    # to load; listing a dead program changes what the controller loads
    from val3check.testing import program_file

    extra = {"App/pick_old.pgx": program_file("pick_old", "begin\n  if\nend\n"),
             "App/Sub/extra.pgx": program_file("extra", "begin\nend\n")}
    folder = _app(tmp_path, _pgx("begin\n  nCount = 1\nend", ""), extra=extra)
    before = (folder / "App.pjx").read_bytes()
    r = val3check("lint", "App", "--diff", cwd=tmp_path)
    assert "App.pjx" not in r.stdout
    r = val3check("lint", "App", "--fix", cwd=tmp_path)
    assert (folder / "App.pjx").read_bytes() == before
    found = [d for d in lint([folder], cwd=tmp_path).result.diagnostics if d.code == "F012"]
    assert len(found) == 2 and all(d.path.endswith("pick_old.pgx") or d.path.endswith("extra.pgx") for d in found)
    assert any('add <Program file="Sub/extra.pgx" /> to <Programs> in App.pjx' in d.message for d in found)
    assert all("never done by --fix" in d.message for d in found)


def test_fix_respects_selection_and_suppression(tmp_path):
    folder = _app(tmp_path, _pgx("begin\n  // val3check: ignore[N006]\n  nCount = ncount\nend", LOCALS))
    before = (folder / "start.pgx").read_bytes()
    r = val3check("lint", "App", "--fix", "--ignore", "S001", cwd=tmp_path)
    assert "fixed 0 findings" in r.stderr and (folder / "start.pgx").read_bytes() == before


FIXABLE = [r for r in catalogue().values() if r.fix]


def test_the_fixable_rules():
    assert sorted(r.code for r in FIXABLE) == ["N006", "S001"]


@pytest.mark.parametrize("rule", FIXABLE, ids=lambda r: r.code)
def test_every_bad_example_of_a_fixable_rule_is_fixed(tmp_path, rule):
    for i, ex in enumerate(rule.bad):
        root = tmp_path / str(i)
        if ex.code is not None:
            target = write_app(root, ex.code, globals_=ex.globals, locals_=ex.locals, programs=ex.programs,
                               version=ex.version)
        else:
            write_files(root, ex.files)
            target = root / ex.target
        found = [d for d in lint([target], cwd=root).findings if d.code == rule.code]
        assert found
        fixes = plan(found)
        assert fixes.count and not fixes.not_fixed, fixes.not_fixed
        fixes.write()
        assert not [d for d in lint([target], cwd=root).result.diagnostics if d.code == rule.code]
    assert code_position(1, 1)  # (the helper the rule examples use)
