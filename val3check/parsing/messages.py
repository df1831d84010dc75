"""Syntax error messages in words: what was found, what was expected, which block is open."""

from __future__ import annotations

import re

from .builder import Builder
from .tokens import (BINOPS, CLOSER_OF, CLOSING, EXPR_START, KEYWORDS, OPENER_OF, OPENERS, PUNCT, SPELLING,
                     STMT_START, STRUCTURAL, Tok, as_tok, clip)


def _describe(tok: Tok) -> str:
    """A found token, in words."""
    t = tok.type
    if t == "NAME":
        return f"name '{clip(tok.value)}'"
    if t == "SYSNAME":
        return f"system name '{clip(tok.value)}'"
    if t in ("NUMBER", "BADNUMBER"):
        return f"number '{clip(tok.value)}'"
    if t in ("STRING", "BADSTRING"):
        return f"string {clip(tok.value)}"
    if t == "_NL":
        return "end of line"
    if t == "$END":
        return "end of the program"
    return f"'{clip(tok.value)}'"


def _expected_order(t: str) -> tuple[int, str]:
    order = ["EQUAL", "_LPAR", "_RPAR", "_RSQB", "_RBRACE", "_COMMA", "TO", "STEP", "_NL", "$END"]
    return (order.index(t) if t in order else len(order), t)


def _expected_words(expected: frozenset[str] | set[str]) -> list[str]:
    exp = set(expected) - {"ERROR", "BADNUMBER", "BADSTRING", "COMMENT"}
    words: list[str] = []
    if exp >= {"IF", "WHILE", "CALL"}:
        words.append("a statement")
        exp -= STMT_START
    elif exp >= {"NAME", "NUMBER", "STRING"}:
        words.append("an expression")
        exp -= EXPR_START
    if exp & {"EQOP", "RELOP", "MULOP", "AND", "OR"}:
        words.append("an operator")
        exp -= BINOPS
    for t in sorted(exp, key=_expected_order):
        if t == "_NL":
            words.append("the end of the line")
        elif t == "$END":
            words.append("the end of the program")
        elif t in SPELLING:
            words.append(f"'{SPELLING[t]}'")
        elif t in PUNCT:
            words.append(PUNCT[t])
        elif t == "NAME":
            words.append("a name")
        elif t == "SYSNAME":
            words.append("a system instruction name")
        elif t == "NUMBER":
            words.append("a number")
        elif t == "STRING":
            words.append("a string")
        elif t == "EQOP":
            words.append("'==' or '!='")
        elif t == "RELOP":
            words.append("a comparison")
        elif t == "MULOP":
            words.append("'*', '/' or '%'")
        else:
            words.append(t.lower().strip("_"))
    return words


def _join(words: list[str]) -> str:
    if not words:
        return "something else"
    if len(words) == 1:
        return words[0]
    return ", ".join(words[:-1]) + " or " + words[-1]


class _Message:
    def __init__(self, text: str, structural: bool) -> None:
        self.text = text
        self.structural = structural  # stop after this error: the block structure is unclear


def syntax_message(builder: Builder, tok: Tok, expected: frozenset[str], value_stack: list) -> _Message:
    """Say what was found and what was expected, in words, like a compiler would."""
    value_stack = [as_tok(v) for v in value_stack]
    t = tok.type
    found = _describe(tok)
    # keyword tokens still on the stack: the blocks and clauses not closed yet
    blocks = [v for v in value_stack if v.__class__ is Tok and v.type in OPENERS | {"ELSE", "DEFAULT"}]
    inner = blocks[-1] if blocks else None
    opener = next((b for b in reversed(blocks) if b.type in OPENERS), None)
    top = value_stack[-1] if value_stack and value_stack[-1].__class__ is Tok else None

    def line_of(b: Tok) -> int:
        return builder.fpos(b.line, b.column)[0]

    def opened(b: Tok, before: str = "") -> str:
        return (f"the '{SPELLING[b.type]}' opened on line {line_of(b)} is not closed "
                f"(expected '{SPELLING[CLOSER_OF[b.type]]}'{before})")

    # beginning and end of the program
    if "BEGIN" in expected:
        if t == "$END":
            return _Message("empty program: expected 'begin'", True)
        return _Message(f"unexpected {found}: a program starts with 'begin'", True)
    if any(v.__class__ is Tok and v.type == "END" for v in value_stack[-2:]):
        return _Message(f"unexpected {found} after 'end': the program ends with 'end'", True)
    if top is not None and top.type == "BEGIN" and t != "$END":
        return _Message(f"unexpected {found} after 'begin': statements start on the next line", False)

    # block structure (2.2.5)
    if t in STRUCTURAL or t == "$END":
        if t in ("END", "$END"):
            if opener is not None:
                if t == "END":
                    return _Message(f"unexpected 'end': {opened(opener, ' before it')}", True)
                return _Message(f"unexpected end of the program: {opened(opener)}", True)
            if t == "$END":
                return _Message("missing 'end' at the end of the program", True)
            return _Message(f"unexpected {found}: expected {_join(_expected_words(expected))}", True)
        if inner is not None and inner.type == "ELSE" and t in ("ELSE", "ELSEIF"):
            return _Message(f"unexpected {found}: the 'if' already has an 'else' on line {line_of(inner)}", True)
        if inner is not None and inner.type == "DEFAULT" and t in ("CASE", "DEFAULT"):
            return _Message(f"unexpected {found}: the 'switch' already has a 'default' on line {line_of(inner)}", True)
        want = OPENER_OF.get(t)
        if opener is None:
            if want is not None:
                return _Message(f"'{tok.value}' without '{SPELLING[want]}'", True)
            return _Message(f"unexpected {found}: expected {_join(_expected_words(expected))}", True)
        if expected and expected <= {"CASE", "DEFAULT", "ENDSWITCH"}:
            return _Message(f"unexpected {found}: expected 'case', 'default' or 'endSwitch' "
                            f"in the 'switch' of line {line_of(opener)}", True)
        if opener.type == want or (top is not None and top.type not in OPENERS and tok.line == top.line):
            # right block, wrong place: `if x endIf`
            return _Message(f"unexpected {found}: expected {_join(_expected_words(expected))}", True)
        return _Message(f"unexpected {found}: {opened(opener)}", True)
    if expected and expected <= {"CASE", "DEFAULT", "ENDSWITCH"}:
        where = f" of line {line_of(opener)}" if opener is not None else ""
        return _Message(f"unexpected {found}: the statements of a 'switch'{where} go in its 'case' "
                        "or 'default' clauses (expected 'case', 'default' or 'endSwitch')", True)

    # inside a line
    if t == "_NL":
        if top is not None and expected and expected - {"ERROR"} <= {"NAME"}:
            what = {"CALL": "a program name", "FOR": "the counter variable", "_DOT": "a field name"}
            return _Message(f"expected {what.get(top.type, 'a name')} after '{top.value}'", False)
        if "NAME" in expected and top is not None:
            if top.type in ("IF", "ELSEIF", "WHILE", "UNTIL"):
                return _Message(f"expected a condition after '{top.value}'", False)
            return _Message(f"expected an expression after '{top.value}'", False)
        for closing, (opening, cname, oname) in CLOSING.items():
            if closing in expected:
                for v in reversed(value_stack):
                    if v.__class__ is Tok and v.type == opening:
                        fl, fc = builder.fpos(v.line, v.column)
                        return _Message(f"missing {cname}: the {oname} at line {fl}, column {fc} "
                                        "is not closed", False)
        if top is not None and top.type in ("NAME", "SYSNAME") and {"EQUAL", "_LPAR"} <= expected:
            return _Message("incomplete statement: expected '=' (assignment) or '(' (call) "
                            f"after '{clip(top.value)}'", False)
    if (top is not None and top.type == "NAME" and t in ("NAME", "NUMBER", "STRING", "_LPAR")
            and len(value_stack) >= 2 and value_stack[-2].__class__ is Tok and value_stack[-2].type == "_NL"):
        # `whlie x`: a misspelt keyword at the start of a line
        import difflib

        close = difflib.get_close_matches(top.value.lower(), list(KEYWORDS), n=1, cutoff=0.75)
        if close:
            return _Message(f"unexpected {found} after '{clip(top.value)}': did you mean "
                            f"'{SPELLING[KEYWORDS[close[0]]]}'?", False)
    for i, v in enumerate(value_stack[:-1]):
        if (v.__class__ is Tok and v.type in ("TASKCREATE", "TASKCREATESYNC")
                and value_stack[i + 1].__class__ is Tok and value_stack[i + 1].type == "_LPAR"):
            form = ('taskCreate "name", priority, program(...)' if v.type == "TASKCREATE"
                    else 'taskCreateSync "name", period, bOverrun, program(...)')
            return _Message(f"unexpected {found}: '{v.value}' takes its arguments without "
                            f"parentheses: {form}", False)
    if t == "EQOP" and "EQUAL" in expected and "NAME" not in expected:
        return _Message(f"unexpected {found}: a statement cannot be a comparison "
                        "(to assign a value, write '=')", False)
    if t in ("TRUE", "FALSE", "AND", "OR", "XOR", "CALL", "RETURN", "BREAK") or t in OPENERS:
        found = f"keyword {found}"
    return _Message(f"unexpected {found}: expected {_join(_expected_words(expected))}", False)


_CHAR_HINTS = {
    "'": "strings are written between double quotes",
    ";": "VAL 3 has one statement per line and no ';'",
    "&": "the logical operators are 'and', 'or', 'xor' and '!'",
    "|": "the logical operators are 'and', 'or', 'xor' and '!'",
    "#": "comments start with '//'",
}


def char_message(ch: str) -> str:
    shown = ch if ch.isprintable() else f"U+{ord(ch):04X}"
    hint = _CHAR_HINTS.get(ch)
    if hint is None and ch.isalpha():
        hint = "names use the letters a-z, A-Z, digits and '_' (manual 2.5.1)"
    return f"invalid character '{shown}'" + (f": {hint}" if hint else "")


def number_message(text: str) -> str:
    if re.fullmatch(r"(?:[0-9]+\.?[0-9]*|\.[0-9]+)[eE][+-]?", text):
        why = "the exponent has no digits"
    elif text[:2].lower() in ("0x", "0b"):
        why = "hexadecimal and binary constants are not VAL 3 numbers (manual 3.2.1)"
    elif re.match(r"[0-9]+[A-Za-z_]", text) and not re.match(r"[0-9]+[eE][+-]?[0-9]", text):
        why = "a number cannot be followed by letters, and a name starts with a letter"
    else:
        why = "numbers are written <digits>[.<digits>][e[-]<digits>] (manual 3.2.1)"
    return f"invalid number '{clip(text)}': {why}"

