"""The `val3check.reporting` entry point."""

from __future__ import annotations

import subprocess
import sys

import pytest

from val3check import reporting


def test_formats():
    assert reporting.FORMATS == ("text", "concise", "json", "sarif", "junit", "github")


def test_unknown_format(make_result):
    with pytest.raises(ValueError, match="unknown output format 'xml'"):
        reporting.render("xml", make_result([]))


@pytest.mark.parametrize("fmt", reporting.FORMATS)
def test_every_format_renders(fmt, make_result, d, workdir):
    result = make_result([d("F101", "x", "a.pgx", 1, 1), d("F001", "y", "b.pgx")], files=["a.pgx", "b.pgx"])
    out = reporting.render(fmt, result, color=True, statistics=True)
    assert isinstance(out, str) and out.endswith("\n")


def test_import_is_lazy():
    code = (
        "import sys\n"
        "before = set(sys.modules)\n"
        "import val3check.reporting\n"
        "new = set(sys.modules) - before\n"
        "heavy = ('json', 'xml.etree.ElementTree', 'hashlib', 'urllib.parse')\n"
        "print(sorted(m for m in new if m.startswith('val3check.reporting.') or m in heavy))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"
