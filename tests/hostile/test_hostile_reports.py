"""Issue 21 P and I (reports): strings a program builds with chr() (NUL, ESC, BEL, DEL) reach
every report visibly and validly: escapes ("\\x00") in the HTML page and its data (a raw
control character is a parse error in HTML) and in JUnit XML (XML 1.0 cannot hold them), Control
Pictures in the text report (columns kept); `val3check html` on deep or
malformed JSON says so (exit 2)."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET

import pytest
from interpretation.simsupport import sim

from val3check.config import Settings
from val3check.reporting._common import printable, visible
from val3check.reporting.sim_render import render_sim
from val3check.reporting.sim_report import build_report
from val3check.rules.catalogue import catalogue

CODE = ('begin\n  l_s = "a" + chr(0) + "b" + chr(27) + "[31mred" + chr(7) + chr(127)\n  putln(l_s)\n'
        '  logMsg(l_s)\n  popUpMsg(l_s)\n  call nope(l_s)\nend\n')
RAW = "a\x00b\x1b[31mred\x07\x7f"


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    programs = {"nope": {"params": ["string x_s"], "code": "begin\n  x_s = x_s + chr(1)\n  taskCreate x_s, 10, nope(x_s)\nend\n"}}
    result = sim(tmp_path_factory.mktemp("ctl"), CODE, locals_=["string l_s"], programs=programs, duration=0.5)
    assert any(e[3] == RAW for e in result.transcript)  # the program did build those strings
    return build_report(result, Settings(), catalogue(), "test")


def _controls(text: str) -> list[str]:
    return [c for c in text if (ord(c) < 0x20 and c not in "\t\n") or 0x7F <= ord(c) < 0xA0]


def test_html_page_shows_them_as_escapes(report):
    page = render_sim("html", report)
    assert _controls(page) == []
    assert "a\\x00b\\x1b[31mred\\x07\\x7f" in page  # the transcript, in static HTML
    assert "\\u0000" not in page and "\\u001b" not in page  # nor in the page's JSON data


def test_junit_is_valid_xml_with_escapes(report):
    text = render_sim("junit", report)
    assert _controls(text) == []
    ET.fromstring(text.split("\n", 1)[1])  # parses: no character XML 1.0 forbids
    assert "\\x01" in text  # the task name built with chr(1), in the failure's message


def test_text_report_shows_control_pictures(report):
    text = render_sim("text", report)
    assert _controls(text) == []


def test_json_report_escapes_them(report):
    text = render_sim("json", report)
    assert _controls(text) == [] and RAW in [e["text"] for e in json.loads(text)["transcript"]]


def test_the_mappings():
    assert printable("a\x00\x1b\x7f\t") == "a\u2400\u241b\u2421\t"
    assert printable("a\nb") == "a\u240ab" and printable("a\nb", keep_newlines=True) == "a\nb"
    assert visible("a\x00\x1b\x7f\x9b\t\n") == "a\\x00\\x1b\\x7f\\x9b\t\n"
    assert visible("\udcff\ud800\ufffe") == "\\xff\\ud800\\ufffe"  # an undecodable byte as itself


# ---- val3check html ------------------------------------------------------------------------------------

@pytest.mark.parametrize("content,fragment", [
    ("[" * 100_000 + "]" * 100_000, "nested too deeply"),
    ('{"version": 1, "application": 5}', "report model"),
    ("\xff", "not JSON"),
])
def test_render_command_refuses_bad_models(tmp_path, capsys, content, fragment):
    from val3check.cli import main as cli_main

    (tmp_path / "m.json").write_bytes(content.encode("latin-1"))
    assert cli_main(["html", str(tmp_path / "m.json"), "-o", str(tmp_path / "x.html")]) == 2
    assert fragment in capsys.readouterr().err and not (tmp_path / "x.html").exists()


def test_render_command_refuses_models_of_the_wrong_types(tmp_path, capsys):
    from synthetic_run import synthetic_model
    from val3check.cli import main as cli_main

    model = synthetic_model(duration=2.0)
    model["io"] = [{"link": {"a": 1}, "kind": "dio", "time": 0, "value": True, "names": 5}]
    (tmp_path / "m.json").write_text(json.dumps(model))
    assert cli_main(["html", str(tmp_path / "m.json"), "-o", str(tmp_path / "b.html")]) == 2
    err = capsys.readouterr().err
    assert "not a report model the page can show" in err or "report model:" in err
