"""The fast path's tokenizer: the engine's tokens of code without lexical errors, from one findall."""

from __future__ import annotations

import re

from .tokens import KEYWORDS

TYPE_CHECKING = False  # not typing's: importing typing costs 3 ms at lint's start-up
if TYPE_CHECKING:
    from typing import Any


class Fallback(Exception):
    """The code is not for this parser (it may have syntax errors): use the engine."""


# the terminals of a fixed spelling
_FIXED = {
    "(": "_LPAR", ")": "_RPAR", ",": "_COMMA", "[": "_LSQB", "]": "_RSQB", "{": "LBRACE", "}": "_RBRACE",
    ".": "_DOT", ":": "_COLON", "+": "PLUS", "-": "MINUS", "*": "MULOP", "/": "MULOP", "%": "MULOP",
    "=": "EQUAL", "==": "EQOP", "!=": "EQOP", "<": "RELOP", ">": "RELOP", "<=": "RELOP", ">=": "RELOP",
    "!": "BANG", "?": "QMARK",
}
_KNOWN_MAX = 50_000  # texts remembered by tokenize (names, numbers, strings) before starting over
_NAME_START = frozenset("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ_")


# The terminals tried first, the most frequent in VAL 3 code first (findall tries alternatives in
# order: NAME was sixth, behind five that fail on most characters; the findall took a fifth less).
# Moving one ahead of another changes no match when the two cannot match at the same place: their
# first characters differ. Where they may (EQOP `==`/`!=` and EQUAL `=`, BANG `!`; _NL and COMMENT,
# MULOP on `/`; NUMBER and BADNUMBER, _DOT) the grammar's order is kept (tests/parsing/test_descent.py).
FIRST = ("NAME", "_LPAR", "_RPAR", "_COMMA", "_NL", "EQOP", "EQUAL", "NUMBER", "_LSQB", "_RSQB", "PLUS", "MINUS",
         "RELOP", "LBRACE", "_RBRACE", "QMARK", "_COLON")


# A line end (with the blank and comment lines after it) as the grammar writes it, and the same
# with possessive repeats: what follows each repeat cannot start with what it would give back (a
# blank before `//` or a line end, a comment's character before a line end; the last blanks end
# the token), so the matches are the same, without backtracking over each line's indentation
# (findall 10 % faster).
NL_GRAMMAR = "(?:\\/\\/[^\n]*)?\n(?:[ \t\x0c\r]*(?:\\/\\/[^\n]*)?\n)*[ \t\x0c\r]*"
NL_POSSESSIVE = "(?:\\/\\/[^\n]*+)?\n(?:[ \t\x0c\r]*+(?:\\/\\/[^\n]*+)?\n)*+[ \t\x0c\r]*+"


def pair_regex(lexer: str, first: tuple[str, ...] = FIRST, possessive: bool = True) -> Any:
    """The engine's master regex (`[ \\t\\f\\r]*(?:(?P<T>...)|...)`) as one that finds (blanks,
    token text) pairs: the same alternatives, those named in `first` tried first (in that order),
    so the same matches; `possessive`: the line end's repeats possessive (NL_POSSESSIVE)."""
    named = _terminals(lexer)
    if possessive and named.get("_NL") == f"(?:{NL_GRAMMAR})":
        named["_NL"] = f"(?:{NL_POSSESSIVE})"
    order = [n for n in first if n in named] + [n for n in named if n not in first]
    regex = re.compile(f"([ \\t\\f\\r]*)({'|'.join(named[n] for n in order)})")
    if regex.groups != 2:
        raise ValueError("a terminal of the grammar has a capturing group")
    return regex


def number_regex(lexer: str) -> Any:
    """The NUMBER terminal of the engine's master regex alone: what tells a number from a bad one
    (BADNUMBER) in `tokenize`, without compiling the whole master regex (the engine's, made only
    when it parses)."""
    return re.compile(_terminals(lexer)["NUMBER"])


def _terminals(lexer: str) -> dict[str, str]:
    """The alternatives of the master regex, by terminal, in its order, without their names."""
    prefix = "[ \\t\\f\\r]*(?:"
    if not (lexer.startswith(prefix) and lexer.endswith(")")):
        raise ValueError("unexpected form of the master regex")
    inner = lexer[len(prefix):-1]
    pieces = re.split(r"\|(?=\(\?P<)", inner)
    named = {}
    for piece in pieces:
        m = re.match(r"\(\?P<([A-Za-z_0-9]+)>", piece)
        if m is None or m[1] in named:
            raise ValueError("unexpected form of the master regex")
        named[m[1]] = re.sub(r"\(\?P<[A-Za-z_0-9]+>", "(?:", piece)
    return named


def tokenize(code: str, regex: Any, number: Any, known: dict[str, str]) -> tuple[list[str], list[tuple]]:
    """The tokens of `code` as the engine makes them, (type, value, line, column) tuples, and
    their types in a list of their own; `to`/`step` stay names, comments are dropped, the last
    token is `$END`. `regex` is `pair_regex(...)`, `number` the `match` of `number_regex(...)`, `known`
    the type of the texts of a fixed type seen so far (punctuation, names, numbers, strings).
    Fallback on anything the engine would report (invalid character, bad number or string)."""
    toks: list[tuple] = []
    add = toks.append
    if len(known) > _KNOWN_MAX:
        known.clear()
    if not known:
        known.update(_FIXED)
    name_start = _NAME_START
    keywords = KEYWORDS
    line = 1
    base = -1  # the offset before the line's first character
    p = 0
    for blanks, value in regex.findall(code):
        start = p + len(blanks)
        p = start + len(value)
        t = known.get(value)
        if t is not None:
            add((t, value, line, start - base))
            continue
        if not value:  # EOF; characters skipped by findall (invalid) make the offsets wrong
            if p != len(code):
                raise Fallback
            add(("$END", "", line, start - base))
            return [t[0] for t in toks], toks
        c = value[0]
        if c in name_start:
            t = keywords.get(value.lower(), "NAME")
            add((t, value, line, start - base))
            known[value] = t
        elif "\n" in value:
            add(("_NL", value, line, start - base))
            line += value.count("\n")
            base = start + value.rindex("\n")
        elif c == '"':
            if len(value) < 2 or value[-1] != '"':
                raise Fallback  # BADSTRING
            add(("STRING", value, line, start - base))
            known[value] = "STRING"
        elif c == "/":
            continue  # a comment not followed by a line end
        elif c == "$":
            add(("SYSNAME", value, line, start - base))
            known[value] = "SYSNAME"
        else:  # NUMBER, or BADNUMBER when NUMBER does not match the text alone (the master regex
            # tries NUMBER first, and no terminal before it starts with a digit or a dot)
            m = number(value)
            if m is None or m.end() != len(value):
                raise Fallback
            add(("NUMBER", value, line, start - base))
            known[value] = "NUMBER"
    raise Fallback  # pragma: no cover - the master regex always ends with EOF
