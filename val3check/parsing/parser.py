"""Parse the code of a VAL 3 program into the typed tree of `val3check.parsing.ast`.

The grammar is `grammars/val3.lark` (LALR(1), contextual lexer). Building the LALR tables from
it takes ~70 ms, so the tables are shipped pre-built in `_tables.py` (regenerate with
`python -m val3check.parsing.build_parser`); when the grammar file no longer matches them
(while editing the grammar) the parser is built from the grammar instead. Everything is built
lazily, on the first parse.

Syntax errors are diagnostics, never exceptions: F101 (syntax error), F102 (invalid character,
unterminated string), F103 (invalid number), F104 (nesting too deep). After an error the parser
resynchronises on the next line and goes on, so that independent errors of other lines are
reported too; errors that could be consequences of an earlier one are not reported.
"""

from __future__ import annotations

import hashlib
import re
import threading
from typing import Any

from ..diagnostics import Diagnostic
from ..positions import SourceMap
from . import ast as A

__all__ = ["parse_code", "parse_program", "scan_comments", "MAX_BLOCK_DEPTH", "MAX_EXPR_DEPTH"]

MAX_ERRORS = 10  # syntax errors reported per program
MAX_BLOCK_DEPTH = 64  # nested if/while/do/for/switch blocks
MAX_EXPR_DEPTH = 100  # nested operations in one expression

# Lark options; build_parser.py uses the same ones.
LARK_OPTIONS: dict[str, Any] = dict(parser="lalr", lexer="contextual", maybe_placeholders=True)

# Reserved words (manual 2.2.5, 3.1), any case -> terminal name. `to` and `step` are not here:
# they are keywords only inside `for` (see the grammar).
KEYWORDS = {
    "begin": "BEGIN", "end": "END",
    "if": "IF", "elseif": "ELSEIF", "else": "ELSE", "endif": "ENDIF",
    "while": "WHILE", "endwhile": "ENDWHILE",
    "do": "DO", "until": "UNTIL",
    "for": "FOR", "endfor": "ENDFOR",
    "switch": "SWITCH", "case": "CASE", "default": "DEFAULT", "endswitch": "ENDSWITCH",
    "break": "BREAK", "return": "RETURN", "call": "CALL",
    "true": "TRUE", "false": "FALSE",
    "and": "AND", "or": "OR", "xor": "XOR",
}

# The spelling the manual and the SRS editor use, for messages.
_SPELLING = {
    "BEGIN": "begin", "END": "end", "IF": "if", "ELSEIF": "elseIf", "ELSE": "else",
    "ENDIF": "endIf", "WHILE": "while", "ENDWHILE": "endWhile", "DO": "do", "UNTIL": "until",
    "FOR": "for", "ENDFOR": "endFor", "SWITCH": "switch", "CASE": "case", "DEFAULT": "default",
    "ENDSWITCH": "endSwitch", "BREAK": "break", "RETURN": "return", "CALL": "call",
    "TRUE": "true", "FALSE": "false", "AND": "and", "OR": "or", "XOR": "xor",
    "TO": "to", "STEP": "step",
}
_OPENERS = {"IF", "WHILE", "DO", "FOR", "SWITCH"}
_CLOSER_OF = {"IF": "ENDIF", "WHILE": "ENDWHILE", "DO": "UNTIL", "FOR": "ENDFOR", "SWITCH": "ENDSWITCH"}
_OPENER_OF = {"ELSEIF": "IF", "ELSE": "IF", "ENDIF": "IF", "ENDWHILE": "WHILE", "UNTIL": "DO",
              "ENDFOR": "FOR", "CASE": "SWITCH", "DEFAULT": "SWITCH", "ENDSWITCH": "SWITCH"}
_STRUCTURAL = set(_OPENER_OF) | {"END", "BEGIN"}
_CLOSERS = {"ENDIF", "ENDWHILE", "UNTIL", "ENDFOR", "ENDSWITCH"}

_PUNCT = {
    "EQUAL": "'='", "PLUS": "'+'", "MINUS": "'-'", "BANG": "'!'", "LBRACE": "'{'",
    "_RBRACE": "'}'", "_LPAR": "'('", "_RPAR": "')'", "_LSQB": "'['", "_RSQB": "']'",
    "_COMMA": "','", "_DOT": "'.'", "_COLON": "':'",
}
_EXPR_START = {"NAME", "SYSNAME", "NUMBER", "BADNUMBER", "STRING", "BADSTRING", "TRUE", "FALSE",
               "_LPAR", "MINUS", "BANG", "LBRACE"}
_STMT_START = {"CALL", "RETURN", "BREAK", "IF", "WHILE", "DO", "FOR", "SWITCH"}
_BINOPS = {"EQUAL", "EQOP", "RELOP", "PLUS", "MINUS", "MULOP", "AND", "OR", "XOR"}
_CLOSING = {"_RPAR": ("_LPAR", "')'", "'('"), "_RSQB": ("_LSQB", "']'", "'['"),
            "_RBRACE": ("LBRACE", "'}'", "'{'")}


# ---------------------------------------------------------------- per-parse state


class _Context:
    """What one parse needs: the code, the position mapping, the diagnostics so far."""

    def __init__(self, code: str, source_map: SourceMap, path: str) -> None:
        self.code = code
        self.sm = source_map
        self.path = path
        self.diags: list[Diagnostic] = []
        self.error_lines: set[int] = set()  # code lines that already have an error
        self.n_syntax = 0  # F101 reported
        self.stopped = False
        self.depth = 0
        self.deep_token: Any = None  # the opener that went past MAX_BLOCK_DEPTH
        n_lines = code.count("\n") + 1
        starts = source_map.line_starts
        if starts:
            lines = [p.line for p in starts[:n_lines]]
            offs = [p.col - 1 for p in starts[:n_lines]]
            if len(lines) < n_lines:  # past the map: SourceMap.to_file keeps the last line start
                lines.extend([lines[-1]] * (n_lines - len(lines)))
                offs.extend([offs[-1]] * (n_lines - len(offs)))
        else:
            lines = list(range(1, n_lines + 1))
            offs = [0] * n_lines
        self.lines = lines
        self.offs = offs
        self.col_maps = source_map.col_maps

    def fpos(self, line: int, col: int) -> tuple[int, int]:
        """Code (line, col) -> file (line, col)."""
        k = line - 1
        if self.col_maps and k in self.col_maps or not 0 <= k < len(self.lines):
            p = self.sm.to_file(line, col)
            return p.line, p.col
        return self.lines[k], self.offs[k] + col

    def report(self, code: str, message: str, line: int, col: int,
               end_line: int | None = None, end_col: int | None = None) -> None:
        fl, fc = self.fpos(line, col)
        fel = fec = None
        if end_line is not None and end_col is not None:
            fel, fec = self.fpos(end_line, end_col)
        self.diags.append(Diagnostic(code, message, self.path, fl, fc, fel, fec))
        self.error_lines.add(line)


_local = threading.local()


def _ctx() -> _Context:
    return _local.ctx


# ---------------------------------------------------------------- lexer callbacks


def _on_name(tok):
    """Rename reserved words (any case) to their keyword terminal; count block nesting."""
    kw = KEYWORDS.get(tok.value.lower())
    if kw is not None:
        tok.type = kw
        if kw in _OPENERS:
            ctx = _local.ctx
            ctx.depth += 1
            if ctx.depth > MAX_BLOCK_DEPTH and ctx.deep_token is None:
                ctx.deep_token = tok
        elif kw in _CLOSERS:
            _local.ctx.depth -= 1
    return tok


def _on_badstring(tok):
    ctx = _local.ctx
    if tok.line not in ctx.error_lines:
        ctx.report("F102", "unterminated string: a string ends with '\"' on the same line",
                   tok.line, tok.column, tok.end_line, tok.end_column)
    return tok


def _on_badnumber(tok):
    ctx = _local.ctx
    text = tok.value
    if text[:2].lower() in ("0x", "0b"):
        why = "hexadecimal and binary constants are not VAL 3 numbers (manual 3.2.1)"
    elif text[:1].isdigit() and re.match(r"[0-9]+[A-Za-z_]", text):
        why = "a number cannot be followed by letters; names start with a letter"
    else:
        why = "numbers are written <digits>[.<digits>][e[-]<digits>] (manual 3.2.1)"
    if tok.line not in ctx.error_lines:
        ctx.report("F103", f"invalid number '{_clip(text)}': {why}",
                   tok.line, tok.column, tok.end_line, tok.end_column)
    return tok


class _PostLex:
    """Lets the contextual lexer read a NAME in every state, so that `and`, `or`, `xor` (read
    as names, then renamed) are found after an expression too."""

    always_accept = ("NAME",)

    def process(self, stream):
        return stream


# ---------------------------------------------------------------- tree builder


def _clip(text: str, n: int = 30) -> str:
    return text if len(text) <= n else text[: n - 3] + "..."


class _Builder:
    """Lark callbacks, one per grammar rule (or alias): build the ast nodes during parsing.

    Each callback receives the list of the rule's kept children (tokens and nodes)."""

    # leaves ----------------------------------------------------------

    def name(self, c):
        t = c[0]
        fp = _local.ctx.fpos
        l, k = fp(t.line, t.column)
        el, ec = fp(t.end_line, t.end_column)
        return A.Name(t.value, l, k, el, ec)

    def lib_name(self, c):
        a, n = c
        fp = _local.ctx.fpos
        l, k = fp(a.line, a.column)
        el, ec = fp(n.end_line, n.end_column)
        return A.LibraryName(a.value, n.value, l, k, el, ec)

    def sys_name(self, c):
        t = c[0]
        fp = _local.ctx.fpos
        l, k = fp(t.line, t.column)
        el, ec = fp(t.end_line, t.end_column)
        return A.SystemName(t.value, l, k, el, ec)

    def number(self, c):
        t = c[0]
        fp = _local.ctx.fpos
        l, k = fp(t.line, t.column)
        el, ec = fp(t.end_line, t.end_column)
        try:
            value = float(t.value)
        except ValueError:  # BADNUMBER, already reported
            value = float("nan")
        return A.Number(value, t.value, l, k, el, ec)

    def string(self, c):
        t = c[0]
        fp = _local.ctx.fpos
        l, k = fp(t.line, t.column)
        el, ec = fp(t.end_line, t.end_column)
        v = t.value
        return A.String(v[1:-1] if t.type == "STRING" else v[1:].rstrip("\r"), l, k, el, ec)

    def true(self, c):
        t = c[0]
        fp = _local.ctx.fpos
        l, k = fp(t.line, t.column)
        el, ec = fp(t.end_line, t.end_column)
        return A.Bool(True, l, k, el, ec)

    def false(self, c):
        t = c[0]
        fp = _local.ctx.fpos
        l, k = fp(t.line, t.column)
        el, ec = fp(t.end_line, t.end_column)
        return A.Bool(False, l, k, el, ec)

    def error_expr(self, c):
        t = c[0]
        return A.ErrorExpr(*_local.ctx.fpos(t.line, t.column))

    # expressions -----------------------------------------------------

    def struct(self, c):
        t = c[0]
        fields = c[1:]
        if len(fields) == 1 and fields[0] is None:
            fields = []
        return A.Struct(fields, *_local.ctx.fpos(t.line, t.column))

    def args(self, c):
        return c

    def call(self, c):
        f, args = c
        return A.CallExpr(f, args if args is not None else [], f.line, f.col)

    def index(self, c):
        base, args = c
        return A.Index(base, args, base.line, base.col)

    def field(self, c):
        base, t = c
        return A.Field(base, t.value, base.line, base.col, *_local.ctx.fpos(t.line, t.column))

    def unary(self, c):
        t, operand = c
        l, k = _local.ctx.fpos(t.line, t.column)
        if t.value == "-" and type(operand) is A.Number and not operand.text.startswith("-"):
            # fold `-3` into a constant (3.2.1: `[-]<digits>...`)
            return A.Number(-operand.value, "-" + operand.text, l, k, operand.end_line, operand.end_col)
        return A.Unary(t.value, operand, l, k)

    def binary(self, c):
        left, t, right = c
        op = t.value
        if t.type in ("AND", "OR", "XOR"):
            op = op.lower()
        return A.Binary(op, left, right, left.line, left.col, *_local.ctx.fpos(t.line, t.column))

    def assign_expr(self, c):
        target, t, value = c
        return A.AssignExpr(target, value, target.line, target.col, *_local.ctx.fpos(t.line, t.column))

    # statements ------------------------------------------------------

    def block(self, c):
        return c

    def assign(self, c):
        target, t, value = c
        return A.Assign(target, value, target.line, target.col, *_local.ctx.fpos(t.line, t.column))

    def expr_stmt(self, c):
        call = c[0]
        return A.ExprStatement(call, call.line, call.col)

    def call_stmt(self, c):
        t, target, args = c
        return A.Call(target, args if args is not None else [], *_local.ctx.fpos(t.line, t.column))

    def return_stmt(self, c):
        t = c[0]
        return A.Return(*_local.ctx.fpos(t.line, t.column))

    def break_stmt(self, c):
        t = c[0]
        return A.Break(*_local.ctx.fpos(t.line, t.column))

    def error_stmt(self, c):
        t = c[0]
        return A.ErrorStatement(*_local.ctx.fpos(t.line, t.column))

    def if_stmt(self, c):
        fp = _local.ctx.fpos
        t, cond, body = c[0], c[1], c[2]
        end = c[-1]
        orelse = c[-2]
        l, k = fp(t.line, t.column)
        branches = [A.Branch(cond, body, l, k)]
        branches.extend(c[3:-2])
        el, ec = fp(end.end_line, end.end_column)
        if orelse is None:
            return A.If(branches, None, l, k, 0, 0, el, ec)
        ol, oc, obody = orelse
        return A.If(branches, obody, l, k, ol, oc, el, ec)

    def elseif_clause(self, c):
        t, cond, body = c
        return A.Branch(cond, body, *_local.ctx.fpos(t.line, t.column))

    def else_clause(self, c):
        t, body = c
        l, k = _local.ctx.fpos(t.line, t.column)
        return (l, k, body)

    def while_stmt(self, c):
        fp = _local.ctx.fpos
        t, cond, body, end = c
        l, k = fp(t.line, t.column)
        el, ec = fp(end.end_line, end.end_column)
        return A.While(cond, body, l, k, el, ec)

    def do_stmt(self, c):
        fp = _local.ctx.fpos
        t, body, u, cond = c
        l, k = fp(t.line, t.column)
        ul, uc = fp(u.line, u.column)
        return A.DoUntil(body, cond, l, k, ul, uc)

    def for_header(self, c):
        if len(c) == 1:  # ERROR (recovery)
            e = A.ErrorExpr(*_local.ctx.fpos(c[0].line, c[0].column))
            return (e, e, e, None)
        counter, _eq, start, _to, stop, _step, step = c
        return (counter, start, stop, step)

    def for_stmt(self, c):
        fp = _local.ctx.fpos
        t, (counter, start, stop, step), body, end = c
        l, k = fp(t.line, t.column)
        el, ec = fp(end.end_line, end.end_column)
        return A.For(counter, start, stop, step, body, l, k, el, ec)

    def case_clause(self, c):
        t = c[0]
        return A.Case(c[1:-1], c[-1], *_local.ctx.fpos(t.line, t.column))

    def default_clause(self, c):
        t, body = c
        return A.Default(body, *_local.ctx.fpos(t.line, t.column))

    def switch_stmt(self, c):
        fp = _local.ctx.fpos
        t, subject = c[0], c[1]
        end = c[-1]
        default = c[-2]
        l, k = fp(t.line, t.column)
        el, ec = fp(end.end_line, end.end_column)
        return A.Switch(subject, c[2:-2], default, l, k, el, ec)

    def start(self, c):
        fp = _local.ctx.fpos
        b, stmts, e = c
        l, k = fp(b.line, b.column)
        el, ec = fp(e.end_line, e.end_column)
        return A.ProgramBody(stmts, [], l, k, el, ec)


# ---------------------------------------------------------------- building the Lark parser

_build_lock = threading.Lock()
_parser: Any = None


def grammar_text() -> str | None:
    """The grammar file's text (line ends normalised), or None when it cannot be read."""
    from ..resources import resource_dir

    try:
        with open(resource_dir("grammars") / "val3.lark", encoding="utf-8") as f:
            return f.read().replace("\r\n", "\n")
    except OSError:
        return None


def grammar_hash(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def _runtime_options() -> dict[str, Any]:
    return dict(
        transformer=_Builder(),
        postlex=_PostLex(),
        # NAME must be the LAST key: Lark (1.3.1) chains a user callback after its keyword
        # callback (here for `to`/`step`) with a lambda that reads the loop variable late, so
        # only the last key's chain runs as it should.
        lexer_callbacks={"BADSTRING": _on_badstring, "BADNUMBER": _on_badnumber, "NAME": _on_name},
    )


def build_from_grammar(text: str):
    """A Lark parser built from the grammar text (slow: ~70 ms)."""
    from lark import Lark

    return Lark(text, **LARK_OPTIONS, **_runtime_options())


def _load_shipped():
    from lark import Lark

    from . import _tables

    return Lark._load_from_dict(_tables.DATA, _tables.MEMO, **_runtime_options())


def get_parser():
    """The Lark parser, built on first use: from the shipped tables when they match the grammar
    file, else from the grammar file itself."""
    global _parser
    if _parser is None:
        with _build_lock:
            if _parser is None:
                text = grammar_text()
                parser = None
                try:
                    from . import _tables

                    if text is None or _tables.GRAMMAR_SHA256 == grammar_hash(text):
                        parser = _load_shipped()
                except Exception:  # missing/incompatible tables: fall back on the grammar
                    if text is None:
                        raise
                if parser is None:
                    parser = build_from_grammar(text)  # type: ignore[arg-type]
                _parser = parser
    return _parser


# ---------------------------------------------------------------- comments

_COMMENT_SCAN = re.compile(r'"[^"\n]*"?|//[^\n]*')


def scan_comments(code: str, source_map: SourceMap | None = None) -> list[A.Comment]:
    """Every `//` comment of `code` (outside strings), with file positions. Works on code with
    syntax errors too (the lint driver reads suppression comments there)."""
    sm = source_map if source_map is not None else SourceMap()
    out: list[A.Comment] = []
    line = 1
    line_start = 0
    pos = 0
    for m in _COMMENT_SCAN.finditer(code):
        text = m.group()
        if text[0] == '"':
            continue
        start = m.start()
        nl = code.count("\n", pos, start)
        if nl:
            line += nl
            line_start = code.rindex("\n", 0, start) + 1
        pos = start
        col = start - line_start + 1
        starts_line = not code[line_start:start].strip()
        p = sm.to_file(line, col)
        out.append(A.Comment(text.rstrip("\r"), p.line, p.col, starts_line))
    return out


# ---------------------------------------------------------------- error messages


def _describe(tok) -> str:
    """A found token, in words."""
    t = tok.type
    if t == "NAME":
        return f"name '{_clip(tok.value)}'"
    if t == "SYSNAME":
        return f"system name '{_clip(tok.value)}'"
    if t in ("NUMBER", "BADNUMBER"):
        return f"number '{_clip(tok.value)}'"
    if t in ("STRING", "BADSTRING"):
        return f"string {_clip(tok.value)}"
    if t == "_NL":
        return "end of line"
    if t == "$END":
        return "end of the program"
    if t in KEYWORDS.values() or t in ("TO", "STEP"):
        return f"'{tok.value}'"
    return f"'{tok.value}'"


def _expected_words(expected: set[str]) -> list[str]:
    exp = set(expected) - {"ERROR", "BADNUMBER", "BADSTRING", "COMMENT", "WS"}
    words: list[str] = []
    if exp >= {"IF", "WHILE", "CALL"}:
        words.append("a statement")
        exp -= _STMT_START | {"NAME", "SYSNAME"}
    elif exp >= {"NAME", "NUMBER", "STRING"}:
        words.append("an expression")
        exp -= _EXPR_START
    if exp & {"EQOP", "RELOP", "MULOP", "AND", "OR"}:
        words.append("an operator")
        exp -= _BINOPS
    for t in sorted(exp, key=_expected_order):
        if t == "_NL":
            words.append("the end of the line")
        elif t == "$END":
            words.append("the end of the program")
        elif t in _SPELLING:
            words.append(f"'{_SPELLING[t]}'")
        elif t in _PUNCT:
            words.append(_PUNCT[t])
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
            words.append(t.lower())
    return words


def _expected_order(t: str) -> tuple[int, str]:
    order = ["EQUAL", "_LPAR", "_RPAR", "_RSQB", "_RBRACE", "_COMMA", "TO", "STEP", "_NL", "$END"]
    return (order.index(t) if t in order else len(order), t)


def _join(words: list[str]) -> str:
    if not words:
        return "something else"
    if len(words) == 1:
        return words[0]
    return ", ".join(words[:-1]) + " or " + words[-1]


def _open_blocks(value_stack: list) -> list:
    """Keyword tokens still on the parser stack: the blocks (and clauses) not yet closed."""
    out = []
    for v in value_stack:
        if getattr(v, "type", None) in _OPENERS or getattr(v, "type", None) in ("ELSE", "DEFAULT", "BEGIN"):
            out.append(v)
    return out


def _token_before(value_stack: list):
    """The last token shifted, when the top of the stack is a token."""
    if value_stack:
        v = value_stack[-1]
        if hasattr(v, "type") and hasattr(v, "column"):
            return v
    return None


class _Message:
    def __init__(self, text: str, structural: bool, tok=None):
        self.text = text
        self.structural = structural  # stop after this error: the block structure is unknown
        self.tok = tok  # where to report, when not at the found token


def _syntax_message(tok, expected: set[str], value_stack: list) -> _Message:
    ctx = _local.ctx
    t = tok.type
    found = _describe(tok)
    blocks = _open_blocks(value_stack)
    inner = blocks[-1] if blocks else None
    opener = None
    for b in reversed(blocks):
        if b.type in _OPENERS:
            opener = b
            break

    def line_of(b) -> int:
        return ctx.fpos(b.line, b.column)[0]

    def opened(b) -> str:
        return f"the '{_SPELLING[b.type]}' opened on line {line_of(b)} is not closed (expected '{_SPELLING[_CLOSER_OF[b.type]]}')"

    # beginning and end of the program
    if "BEGIN" in expected:
        if t == "$END":
            return _Message("empty program: expected 'begin'", True)
        return _Message(f"unexpected {found}: a program starts with 'begin'", True)
    top = _token_before(value_stack)
    if top is not None and top.type == "END" and t not in expected:
        return _Message(f"unexpected {found} after 'end': the program ends with 'end'", True)
    if top is not None and top.type == "BEGIN" and t != "_NL":
        return _Message(f"unexpected {found} after 'begin': statements start on the next line", False)

    # block structure (2.2.5)
    if t in _STRUCTURAL or t == "$END":
        if t in ("END", "$END"):
            if opener is not None:
                where = "'end'" if t == "END" else "the end of the program"
                return _Message(f"unexpected {found}: {opened(opener)} before {where}", True)
            if t == "$END":
                return _Message("missing 'end' at the end of the program", True)
            return _Message(f"unexpected {found}: expected {_join(_expected_words(expected))}", True)
        want = _OPENER_OF.get(t)
        if inner is not None and inner.type == "ELSE" and t in ("ELSE", "ELSEIF"):
            return _Message(f"unexpected {found}: the 'if' already has an 'else' on line {line_of(inner)}", True)
        if inner is not None and inner.type == "DEFAULT" and t in ("CASE", "DEFAULT"):
            return _Message(f"unexpected {found}: the 'switch' already has a 'default' on line {line_of(inner)}", True)
        if opener is None:
            if want is not None:
                return _Message(f"'{tok.value}' without '{_SPELLING[want]}'", True)
            return _Message(f"unexpected {found}: expected {_join(_expected_words(expected))}", True)
        if opener.type == "SWITCH" and expected <= {"CASE", "DEFAULT", "ENDSWITCH"}:
            return _Message(f"unexpected {found}: expected 'case', 'default' or 'endSwitch' in the 'switch' of line {line_of(opener)}", True)
        return _Message(f"unexpected {found}: {opened(opener)}", True)
    if expected and expected <= {"CASE", "DEFAULT", "ENDSWITCH"}:
        where = f" of line {line_of(opener)}" if opener is not None else ""
        return _Message(f"unexpected {found}: a 'switch'{where} holds 'case' or 'default' clauses (expected 'case', 'default' or 'endSwitch')", True)

    # inside a line
    if t in ("_NL", "$END") or (t in _STMT_START and "NAME" in expected):
        if expected & {"NAME", "NUMBER"} and top is not None:
            what = "a condition" if top.type in ("IF", "ELSEIF", "WHILE", "UNTIL") else "an expression"
            return _Message(f"expected {what} after '{top.value}'", False)
        for closing, (opening, cname, oname) in _CLOSING.items():
            if closing in expected:
                for v in reversed(value_stack):
                    if getattr(v, "type", None) == opening:
                        fl, fc = ctx.fpos(v.line, v.column)
                        return _Message(f"missing {cname}: the {oname} at line {fl}, column {fc} is not closed", False)
        if top is not None and top.type in ("NAME", "SYSNAME") and "EQUAL" in expected:
            return _Message(f"incomplete statement: expected '=' (assignment) or '(' (call) after '{_clip(top.value)}'", False)
        if top is not None and "NAME" in expected and top.type in _SPELLING:
            return _Message(f"expected an expression after '{top.value}'", False)
    if t == "EQOP" and "EQUAL" in expected and "NAME" not in expected:
        return _Message(f"unexpected {found}: a statement cannot be a comparison (to assign a value, write '=')", False)
    return _Message(f"unexpected {found}: expected {_join(_expected_words(expected))}", False)


_CHAR_HINTS = {
    "'": "strings are written between double quotes",
    ";": "VAL 3 has one statement per line and no ';'",
    "&": "the logical operators are 'and', 'or', 'xor' and '!'",
    "|": "the logical operators are 'and', 'or', 'xor' and '!'",
    "#": "comments start with '//'",
}


def _char_message(ch: str) -> str:
    shown = ch if ch.isprintable() else f"U+{ord(ch):04X}"
    hint = _CHAR_HINTS.get(ch)
    if hint is None and ch.isalpha():
        hint = "names use the letters a-z, A-Z, digits and '_' (manual 2.5.1)"
    return f"invalid character '{shown}'" + (f": {hint}" if hint else "")


# ---------------------------------------------------------------- error handling and recovery


def _on_error(e) -> bool:
    """Lark's on_error hook: report `e`, then resynchronise on the next line. Returns False to
    stop parsing."""
    from lark.exceptions import UnexpectedCharacters, UnexpectedToken
    from lark.lexer import Token

    ctx = _local.ctx
    ip = e.interactive_parser
    ps = ip.parser_state
    expected = {s for s in ps.parse_conf.states[ps.position] if s.isupper()}
    if isinstance(e, UnexpectedCharacters):
        line, col = e.line, e.column
        ch = ctx.code[e.pos_in_stream] if e.pos_in_stream < len(ctx.code) else ""
        if line not in ctx.error_lines:
            ctx.report("F102", _char_message(ch), line, col, line, col + 1)
        bad = None
    elif isinstance(e, UnexpectedToken):
        bad = e.token
        line, col = bad.line or 1, bad.column or 1
        msg = _syntax_message(bad, expected, ps.value_stack)
        if msg.structural and ctx.n_syntax:
            return False  # probably a consequence of an earlier error
        if line not in ctx.error_lines:
            end_line = getattr(bad, "end_line", None) if bad.type not in ("_NL", "$END") else None
            end_col = getattr(bad, "end_column", None) if end_line else None
            ctx.report("F101", msg.text, line, col, end_line, end_col)
            ctx.n_syntax += 1
        if msg.structural or bad.type == "$END":
            return False
    else:
        return False
    if len(ctx.diags) >= MAX_ERRORS:
        return False

    # Skip the rest of the broken line (the lexer then reads its line end), and put the parser
    # in a state that accepts a line end: pop states until an ERROR placeholder (an expression,
    # a statement or a `for` header) can complete the line.
    lex_state = ip.lexer_thread.state
    text = lex_state.text.text if hasattr(lex_state.text, "text") else lex_state.text
    nl_consumed = bad is not None and bad.type == "_NL"
    if not nl_consumed:
        p = lex_state.line_ctr.char_pos
        nl = text.find("\n", p)
        if nl < 0:
            nl = len(text)
        if nl > p:
            lex_state.line_ctr.feed(text[p:nl])
    nl_tok = bad if nl_consumed else Token("_NL", "\n", 0, line, col)
    err_tok = Token("ERROR", "", 0, line, col, line, col)
    stack_len = len(ps.state_stack)
    for n_pop in range(min(stack_len - 1, 80) + 1):
        for seq in ((nl_tok,), (err_tok, nl_tok)):
            trial = ps.copy(deepcopy_values=False)
            if n_pop:
                del trial.state_stack[-n_pop:]
                del trial.value_stack[-n_pop:]
            try:
                for tk in seq:
                    trial.feed_token(tk)
            except UnexpectedToken:
                continue
            # apply to the real parser state
            if n_pop:
                del ps.state_stack[-n_pop:]
                del ps.value_stack[-n_pop:]
            for tk in seq[:-1]:
                ps.feed_token(tk)
            if nl_consumed:
                ps.feed_token(nl_tok)
            return True
    return False


# ---------------------------------------------------------------- depth checks


def _expr_too_deep(body: A.ProgramBody):
    """The first node nested more than MAX_EXPR_DEPTH levels inside a statement, or None."""
    stack: list[tuple[Any, int]] = [(s, 0) for s in reversed(body.statements)]
    stmt_types = (A.Assign, A.ExprStatement, A.Call, A.Return, A.Break, A.If, A.While,
                  A.DoUntil, A.For, A.Switch, A.Branch, A.Case, A.Default)
    while stack:
        node, depth = stack.pop()
        if type(node) in stmt_types:
            depth = 0
        elif depth > MAX_EXPR_DEPTH:
            return node
        for ch in reversed(A.children(node)):
            stack.append((ch, depth + 1))
    return None


# ---------------------------------------------------------------- entry points


def parse_code(code: str, source_map: SourceMap, path: str) -> tuple[A.ProgramBody | None, list[Diagnostic]]:
    """Parse a program's code (`begin` ... `end`). Returns the body (None when the code has
    syntax errors) and the diagnostics, with positions in the file `path` through `source_map`.
    Never raises."""
    try:
        ctx = _Context(code, source_map, path)
    except Exception as exc:  # noqa: BLE001 - a broken source map must not stop the run
        return None, [Diagnostic("F101", f"could not parse this program ({exc.__class__.__name__})", path, 0, 0)]
    prev = getattr(_local, "ctx", None)
    _local.ctx = ctx
    body = None
    try:
        try:
            parser = get_parser()
            body = parser.parse(code, on_error=_on_error)
        except RecursionError:
            ctx.diags.append(Diagnostic("F104", "the program is nested too deeply to be analysed", path, 1, 1))
        except MemoryError:
            ctx.diags.append(Diagnostic("F104", "the program is too large to be analysed", path, 1, 1))
        except Exception as exc:  # noqa: BLE001
            from lark.exceptions import UnexpectedInput

            if not isinstance(exc, UnexpectedInput):
                ctx.diags.append(Diagnostic("F101", f"could not parse this program (internal error: {exc.__class__.__name__}: {_clip(str(exc), 80)})", path, 1, 1))
            elif not ctx.diags:  # stopped without a report: should not happen
                ctx.diags.append(Diagnostic("F101", "syntax error", path, *ctx.fpos(getattr(exc, "line", 1) or 1, getattr(exc, "column", 1) or 1)))
        if ctx.diags or not isinstance(body, A.ProgramBody):
            if not ctx.diags:
                ctx.diags.append(Diagnostic("F101", "could not parse this program", path, 1, 1))
            return None, sorted(ctx.diags, key=Diagnostic.sort_key)
        if ctx.deep_token is not None:
            t = ctx.deep_token
            ctx.report("F104", f"blocks nested more than {MAX_BLOCK_DEPTH} deep", t.line, t.column)
            return None, ctx.diags
        if len(code) > MAX_EXPR_DEPTH and max(map(len, code.split("\n"))) > MAX_EXPR_DEPTH:
            node = _expr_too_deep(body)
            if node is not None:
                ctx.diags.append(Diagnostic("F104", f"expression nested more than {MAX_EXPR_DEPTH} deep", path, node.line, node.col))
                return None, ctx.diags
        body.comments = scan_comments(code, source_map)
        return body, []
    except Exception as exc:  # noqa: BLE001 - never raise
        return None, [Diagnostic("F101", f"could not parse this program (internal error: {exc.__class__.__name__})", path, 1, 1)]
    finally:
        _local.ctx = prev


def parse_program(program) -> list[Diagnostic]:
    """Parse `program.code` and set `program.body`. A missing code element (None) is the
    loader's to report: nothing to do."""
    if program.code is None:
        return []
    body, diags = parse_code(program.code, program.code_map, program.origin.path)
    program.body = body
    return diags
