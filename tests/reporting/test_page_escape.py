"""The page escapes text as html.escape(quote=True) does, without importing the `html` module."""

from __future__ import annotations

import html
import random

from val3check.reporting._common import visible
from val3check.reporting.html.page import _escaped


def test_escaped_is_html_escape_of_the_visible_text():
    texts = ["", "plain", "a&b<c>d\"e'f", "&amp;", "<<>>", "'\"'", "tôle & vis < 3 mm", "\x00\x1b[1m&"]
    texts += ["".join(chr(c) for c in range(128))]
    rng = random.Random(29)
    alphabet = "&<>\"'ab \x00\x7féü€"
    texts += ["".join(rng.choice(alphabet) for _ in range(rng.randrange(30))) for _ in range(500)]
    for t in texts:
        assert _escaped(t) == html.escape(visible(t), quote=True), repr(t)
