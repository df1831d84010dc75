"""Issue 9: odd file names (item 11) and diagnostics that misled: each says what is wrong, where."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from support import lint

from val3check.testing import write_app

ROOT = Path(__file__).resolve().parent.parent.parent


def val3check(*args, cwd, timeout=60, env_extra=None):
    env = dict(os.environ, PYTHONPATH=str(ROOT), **(env_extra or {}))
    return subprocess.run([sys.executable, "-m", "val3check", *args], capture_output=True, cwd=cwd, env=env,
                          timeout=timeout)


def clean(r, codes=(0, 1, 2)):
    out, err = r.stdout.decode("utf-8", "replace"), r.stderr.decode("utf-8", "replace")
    assert r.returncode in codes, (r.returncode, out[-2000:], err[-2000:])
    assert "Traceback" not in err and "internal error" not in out + err, out + err
    return out, err


def _one(tmp_path, code="begin\nend\n", **kw):
    folder = write_app(tmp_path, code, **kw)
    return folder / "start.pgx"


def _codes(tmp_path, folder="Example"):
    return [(d.code, d.line, d.col, d.message) for d in lint([tmp_path / folder], cwd=tmp_path).result.diagnostics]


# ---- item 11: names that are not UTF-8, control characters --------------------------------------

@pytest.mark.skipif(sys.platform in ("win32", "darwin"), reason="file names must be free bytes")
@pytest.mark.parametrize("fmt", ["text", "json", "sarif", "junit", "github"])
def test_file_names_that_are_not_utf8(tmp_path, fmt):
    folder = write_app(tmp_path, "begin\n  if true\nend\n")
    bad = os.path.join(os.fsencode(tmp_path), b"Caf\xe9-\xff")
    os.rename(os.fsencode(folder), bad)
    for output in (None, "report.out"):
        r = val3check("lint", "--format", fmt, *(["-o", output] if output else []), ".", cwd=tmp_path,
                      env_extra={"LC_ALL": "C.UTF-8", "PYTHONIOENCODING": "utf-8:strict"})
        out, err = clean(r, (1,))
        text = (tmp_path / output).read_text(encoding="utf-8") if output else out
        if fmt in ("json", "sarif"):
            json.loads(text)
        assert "Caf\\xe9-\\xff" in text.replace("\\\\", "\\").replace("%5C", "\\")


@pytest.mark.skipif(sys.platform in ("win32", "darwin"), reason="file names must be free bytes")
def test_sim_of_an_application_in_a_folder_that_is_not_utf8(tmp_path):
    folder = write_app(tmp_path, "begin\n  nX = 1 / nZ\nend\n", globals_=["num nX", "num nZ"])
    bad = os.path.join(os.fsencode(tmp_path), b"\xe9t\xe9")
    os.rename(os.fsencode(folder), bad)
    for extra in ([], ["--report", "json", "-o", "run.json"]):
        r = val3check("sim", os.fsdecode(bad), *extra, cwd=tmp_path,
                      env_extra={"LC_ALL": "C.UTF-8", "PYTHONIOENCODING": "utf-8:strict"})
        clean(r, (1,))
    assert json.loads((tmp_path / "run.json").read_text(encoding="utf-8"))["diagnostics"]


def test_control_characters_in_paths_never_reach_the_terminal(tmp_path):
    write_app(tmp_path / "x\x1b[31mred\x07", "begin\n  if true\nend\n")
    r = val3check("lint", ".", cwd=tmp_path)
    out, err = clean(r, (1,))
    assert "\x1b" not in out + err and "\x07" not in out + err
    assert "x\\x1b[31mred\\x07/Example/start.pgx" in out
    r = val3check("sim", "nowhere\x1b[2J", cwd=tmp_path)
    out, err = clean(r, (2,))
    assert "\x1b" not in out + err


# ---- misleading XML diagnostics ------------------------------------------------------------------

def test_cdata_end_inside_a_string_is_reported_where_it_is(tmp_path):
    _one(tmp_path, 'begin\n  sX = "a]]>b"\n  sX = "c"\nend\n', globals_=["string sX"])
    (code, line, col, msg), = [x for x in _codes(tmp_path) if x[0] == "F004"]
    assert (line, col) == (5, 10) and "ends the CDATA section" in msg


@pytest.mark.parametrize("char", ["\x00", "\x01", "\x07", "\x1b"])
def test_control_characters_are_named(tmp_path, char):
    pgx = _one(tmp_path, 'begin\n  sX = "aXb"\nend\n', globals_=["string sX"])
    pgx.write_bytes(pgx.read_bytes().replace(b"aXb", b"a" + char.encode() + b"b"))
    (code, line, col, msg), = [x for x in _codes(tmp_path) if x[0] == "F004"]
    assert (line, col) == (5, 10) and f"U+{ord(char):04X}" in msg and "bare '<'" not in msg


@pytest.mark.parametrize("encoding", ["utf-32", "utf-32-le", "utf-32-be", "utf-16"])
def test_utf32_and_utf16_files(tmp_path, encoding):
    pgx = _one(tmp_path, "begin\n  if true\nend\n")
    text = pgx.read_text(encoding="utf-8")
    bom = {"utf-32-le": b"\xff\xfe\x00\x00", "utf-32-be": b"\x00\x00\xfe\xff"}.get(encoding, b"")
    pgx.write_bytes(bom + text.encode(encoding))
    found = _codes(tmp_path)
    assert [(c, ln) for c, ln, _, _ in found] == [("F101", 6)], found  # read as text, not as UTF-16


def test_second_code_element_and_elements_inside_code(tmp_path):
    pgx = _one(tmp_path, "begin\nend\n")
    text = pgx.read_text()
    pgx.write_text(text.replace("</Program>", "<Code><![CDATA[begin\n  x = \nend]]></Code>\n  </Program>"))
    assert [(c, ln) for c, ln, _, _ in _codes(tmp_path)] == [("F015", 6)]
    pgx.write_text(text.replace("]]></Code>", "]]><b>bold</b></Code>"))
    assert [(c, ln, col) for c, ln, col, _ in _codes(tmp_path)] == [("F015", 5, 7)]


def test_long_attribute_values_are_cut_in_messages(tmp_path):
    folder = write_app(tmp_path, "begin\n  nX = 1\nend\n", globals_=["num nX"])
    dtx = folder / "Example.dtx"
    dtx.write_text(dtx.read_text().replace('size="1" />', f'size="1"><Value key="0" value="{"x" * 100000}" /></Data>'))
    (msg,) = [m for c, _, _, m in _codes(tmp_path) if c == "F007"]
    assert len(msg) < 300 and "100000 characters" in msg


def test_user_type_values_nested_deep_in_a_data_file(tmp_path):
    folder = write_app(tmp_path, "begin\nend\n")
    deep = ('<Value key="0"><Field name="f" xsi:type="array" type="T" size="1">' * 3000
            + "</Field></Value>" * 3000)
    dtx = folder / "Example.dtx"
    dtx.write_text(dtx.read_text().replace(
        "<Datas>\n", f'<Datas>\n    <Data name="u" access="public" xsi:type="array" type="T" size="1">{deep}</Data>\n'))
    found = _codes(tmp_path)
    assert any(c == "F007" and "nested more than 16 deep" in m for c, _, _, m in found), found


def test_a_megabyte_line_with_thousands_of_findings_is_shown_in_windows(tmp_path):
    folder = write_app(tmp_path, "begin\n  call sub()\nend\n", programs={"sub": {"code": "begin\nend\n"}})
    pgx = folder / "sub.pgx"
    params = "".join(f'<Parameter name="p{i}" type="num" xsi:type="element"/>' for i in range(5000))
    pgx.write_text(pgx.read_text().replace(
        "<Code>", f'<Parameters xmlns="http://www.staubli.com/robotics/VAL3/Param/1">{params}</Parameters><Code>'))
    r = val3check("lint", "Example", cwd=tmp_path)
    out, _ = clean(r, (0, 1))
    assert max(len(line) for line in out.splitlines()) < 1200 and "…" in out
