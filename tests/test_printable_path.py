"""`lint.printable_path`: the fast path (printable text returned as is) escapes what the regex does."""

from __future__ import annotations

import re

from val3check.lint import _UNPRINTABLE, printable_path


def _by_regex(text: str) -> str:
    return re.sub(_UNPRINTABLE, lambda m: f"\\x{ord(m.group()) & 0xFF:02x}", text)


def test_every_character_is_escaped_as_the_regex_escapes_it():
    chars = [*map(chr, range(0x3000)), *map(chr, range(0xD800, 0xE000)), "\U0001f600", "\ufeff", "\u2028"]
    for c in chars:
        for text in (c, f"dir/{c}.pjx"):
            assert printable_path(text) == _by_regex(text), repr(text)


def test_control_characters_and_undecodable_bytes():
    assert printable_path("a\x1b[31mb") == "a\\x1b[31mb"
    assert printable_path("caf\udce9/x") == "caf\\xe9/x"
    assert printable_path("été/App.pjx") == "été/App.pjx"
