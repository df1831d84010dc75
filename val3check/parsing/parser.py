"""Parse the code of a VAL 3 program into the typed tree of `val3check.parsing.ast`.

The grammar is `grammars/val3.lark`, compiled by Lark into LALR(1) tables. Building the tables
takes ~70 ms, so they are shipped pre-built in `_tables.py` (regenerate with
`python -m val3check.parsing.build_parser`); when the grammar file no longer matches them
(while editing the grammar) they are built from the grammar instead. Everything is built
lazily, on the first parse.

The tables are run by a small LALR driver of our own (`_Engine`) rather than by Lark's, for
speed (about 3x) and for line-based error recovery; it uses Lark's tables, Lark's terminal
definitions and Lark's tree-building callbacks (child filtering, `?rule` inlining, `[x]`
placeholders), with `_Builder` as the transformer that makes the ast nodes. Its lexer is
contextual where the grammar needs it: `to` and `step` are keywords only in a parser state that
accepts them (inside `for`); the other terminals never compete for the same text.

Syntax errors are diagnostics, never exceptions: F101 (syntax error, unterminated string), F102
(invalid character), F103 (invalid number), F104 (nesting too deep to analyse). After an error the parser
resynchronises on the next line and goes on, so that independent errors of other lines are
reported too; errors that could be consequences of an earlier one are not reported.
"""

from __future__ import annotations

import gc
import re
import threading
from operator import itemgetter
from typing import Any

from ..diagnostics import Diagnostic
from ..positions import SourceMap
from ..rules import codes
from . import ast as A

__all__ = ["parse_code", "parse_program", "scan_comments", "MAX_BLOCK_DEPTH", "MAX_EXPR_DEPTH"]

MAX_ERRORS = 10  # diagnostics reported per program
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
    # task creation (5.10) has its own syntax: the program is written as a call
    "taskcreate": "TASKCREATE", "taskcreatesync": "TASKCREATESYNC",
}
_CONTEXT_KEYWORDS = {"to": "TO", "step": "STEP"}

# The spelling the manual and the SRS editor use, for messages.
_SPELLING = {
    "BEGIN": "begin", "END": "end", "IF": "if", "ELSEIF": "elseIf", "ELSE": "else",
    "ENDIF": "endIf", "WHILE": "while", "ENDWHILE": "endWhile", "DO": "do", "UNTIL": "until",
    "FOR": "for", "ENDFOR": "endFor", "SWITCH": "switch", "CASE": "case", "DEFAULT": "default",
    "ENDSWITCH": "endSwitch", "BREAK": "break", "RETURN": "return", "CALL": "call",
    "TRUE": "true", "FALSE": "false", "AND": "and", "OR": "or", "XOR": "xor",
    "TO": "to", "STEP": "step", "TASKCREATE": "taskCreate", "TASKCREATESYNC": "taskCreateSync",
}
_OPENERS = {"IF", "WHILE", "DO", "FOR", "SWITCH"}
_CLOSERS = {"ENDIF", "ENDWHILE", "UNTIL", "ENDFOR", "ENDSWITCH"}
_CLOSER_OF = {"IF": "ENDIF", "WHILE": "ENDWHILE", "DO": "UNTIL", "FOR": "ENDFOR", "SWITCH": "ENDSWITCH"}
_OPENER_OF = {"ELSEIF": "IF", "ELSE": "IF", "ENDIF": "IF", "ENDWHILE": "WHILE", "UNTIL": "DO",
              "ENDFOR": "FOR", "CASE": "SWITCH", "DEFAULT": "SWITCH", "ENDSWITCH": "SWITCH"}
_STRUCTURAL = set(_OPENER_OF) | {"END", "BEGIN"}

_PUNCT = {
    "EQUAL": "'='", "PLUS": "'+'", "MINUS": "'-'", "BANG": "'!'", "LBRACE": "'{'",
    "_RBRACE": "'}'", "_LPAR": "'('", "_RPAR": "')'", "_LSQB": "'['", "_RSQB": "']'",
    "_COMMA": "','", "_DOT": "'.'", "_COLON": "':'", "QMARK": "'?'",
}
_EXPR_START = {"NAME", "SYSNAME", "NUMBER", "BADNUMBER", "STRING", "BADSTRING", "TRUE", "FALSE",
               "_LPAR", "MINUS", "BANG", "LBRACE", "ERROR"}
_STMT_START = {"CALL", "RETURN", "BREAK", "IF", "WHILE", "DO", "FOR", "SWITCH", "NAME", "SYSNAME",
               "TASKCREATE", "TASKCREATESYNC", "QMARK"}
_BINOPS = {"EQUAL", "EQOP", "RELOP", "PLUS", "MINUS", "MULOP", "AND", "OR", "XOR"}
_CLOSING = {"_RPAR": ("_LPAR", "')'", "'('"), "_RSQB": ("_LSQB", "']'", "'['"),
            "_RBRACE": ("LBRACE", "'}'", "'{'")}


class Tok(tuple):
    """A token: (type, value, line, column), `line`/`column` 1-based in the CODE text (not the
    file). The driver makes plain tuples (one per token: a tuple is much cheaper to make than
    an object) and the builder indexes them; error messages view them as Tok (`as_tok`)."""

    __slots__ = ()

    type = property(itemgetter(0))
    value = property(itemgetter(1))
    line = property(itemgetter(2))
    column = property(itemgetter(3))

    @property
    def end_line(self) -> int:
        return self[2]

    @property
    def end_column(self) -> int:
        return self[3] + len(self[1])

    def __repr__(self) -> str:
        return f"Tok({self[0]}, {self[1]!r}, {self[2]}:{self[3]})"


def as_tok(v: Any) -> Any:
    """A value of the parser's stack: a token (type, value, line, column) as a Tok, anything
    else (a node, a list, a builder tuple whose first item is not a string) as it is."""
    if v.__class__ is tuple and len(v) == 4 and v[0].__class__ is str:
        return Tok(v)
    return v


# ---------------------------------------------------------------- tree builder


def _clip(text: str, n: int = 30) -> str:
    """`text` shortened to `n` characters, invisible characters shown as U+XXXX."""
    text = text if len(text) <= n else text[: n - 3] + "..."
    if not text.isprintable():
        text = "".join(c if c.isprintable() else f"U+{ord(c):04X}" for c in text)
    return text


_WORD_OPS = frozenset({"AND", "OR", "XOR"})


class _Builder:
    """Tree-building callbacks, one per grammar rule or alias (Lark calls them through its
    child filters with the list of the rule's kept children: tokens and nodes).

    Positions: `setup()` gives, for each code line, the file line and the column offset, so
    that the common case (code copied verbatim from a CDATA block) maps with two list reads;
    lines with a column map (escaped XML text) go through `SourceMap.to_file`.
    """

    def __init__(self) -> None:
        self.setup("", SourceMap())

    def setup(self, code: str, source_map: SourceMap) -> None:
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
        self.sm = source_map

    def fpos(self, line: int, col: int) -> tuple[int, int]:
        """Code (line, col) -> file (line, col)."""
        k = line - 1
        if k in self.col_maps or not 0 <= k < len(self.lines):
            p = self.sm.to_file(line, col)
            return p.line, p.col
        return self.lines[k], self.offs[k] + col

    def tend(self, t) -> tuple[int, int]:
        """The file (line, col) just after a token."""
        return self.fpos(t[2], t[3] + len(t[1]))

    def tpos(self, t) -> tuple[int, int]:
        """The file (line, col) of a token (tokens are tuples: type, value, line, column)."""
        k = t[2] - 1
        if k in self.col_maps:
            return self.fpos(t[2], t[3])
        return self.lines[k], self.offs[k] + t[3]

    def _span(self, t) -> tuple[int, int, int, int]:
        line, column, n = t[2], t[3], len(t[1])
        k = line - 1
        if k in self.col_maps:
            ln, c = self.fpos(line, column)
            el, ec = self.fpos(line, column + n)
            return ln, c, el, ec
        ln = self.lines[k]
        c = self.offs[k] + column
        return ln, c, ln, c + n

    # leaves ----------------------------------------------------------

    def name(self, c):
        t = c[0]
        v = t[1]
        k = t[2] - 1
        if k in self.col_maps:
            return A.Name(v, *self._span(t))
        ln = self.lines[k]
        col = self.offs[k] + t[3]
        return A.Name(v, ln, col, ln, col + len(v))

    def lib_name(self, c):
        a, n = c
        ln, k, _, _ = self._span(a)
        _, _, el, ec = self._span(n)
        return A.LibraryName(a[1], n[1], ln, k, el, ec)

    def sys_name(self, c):
        t = c[0]
        return A.SystemName(t[1], *self._span(t))

    def number(self, c):
        t = c[0]
        text = t[1]
        try:
            value = float(text)
        except ValueError:  # BADNUMBER, already reported
            value = float("nan")
        return A.Number(value, text, *self._span(t))

    def string(self, c):
        t = c[0]
        v = t[1]
        return A.String(v[1:-1] if t[0] == "STRING" else v[1:], *self._span(t))

    def true(self, c):
        return A.Bool(True, *self._span(c[0]))

    def false(self, c):
        return A.Bool(False, *self._span(c[0]))

    def error_expr(self, c):
        t = c[0]
        return A.ErrorExpr(*self.tpos(t))

    # expressions -----------------------------------------------------

    def struct(self, c):
        t = c[0]
        fields = c[1:]
        if len(fields) == 1 and fields[0] is None:
            fields = []
        return A.Struct(fields, *self.tpos(t))

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
        return A.Field(base, t[1], base.line, base.col, *self.tpos(t))

    def unary(self, c):
        t, operand = c
        ln, k = self.tpos(t)
        if t[1] == "-" and type(operand) is A.Number and not operand.text.startswith("-"):
            # fold `-3` into a constant (3.2.1: `[-]<digits>...`)
            return A.Number(-operand.value, "-" + operand.text, ln, k, operand.end_line, operand.end_col)
        return A.Unary(t[1], operand, ln, k)

    def binary(self, c):
        left, t, right = c
        op = t[1]
        if t[0] in _WORD_OPS:
            op = op.lower()
        return A.Binary(op, left, right, left.line, left.col, *self.tpos(t))

    def assign_expr(self, c):
        target, t, value = c
        return A.AssignExpr(target, value, target.line, target.col, *self.tpos(t))

    # statements ------------------------------------------------------

    def block(self, c):
        return c

    def assign(self, c):
        target, t, value = c
        return A.Assign(target, value, target.line, target.col, *self.tpos(t))

    def expr_stmt(self, c):
        call = c[0]
        return A.ExprStatement(call, call.line, call.col)

    def call_stmt(self, c):
        t, target, args = c
        return A.Call(target, args if args is not None else [], *self.tpos(t))

    def task_create(self, c):
        t, task, priority, target, args = c
        return A.TaskCreate(task, priority, target, args if args is not None else [],
                            *self.tpos(t))

    def task_create_sync(self, c):
        t, task, period, overrun, target, args = c
        return A.TaskCreateSync(task, period, overrun, target, args if args is not None else [],
                                *self.tpos(t))

    def print_stmt(self, c):
        t, values = c
        return A.Print(values, *self.tpos(t))

    def return_stmt(self, c):
        t = c[0]
        return A.Return(*self.tpos(t))

    def break_stmt(self, c):
        t = c[0]
        return A.Break(*self.tpos(t))

    def error_stmt(self, c):
        t = c[0]
        return A.ErrorStatement(*self.tpos(t))

    def if_stmt(self, c):
        t, cond, body = c[0], c[1], c[2]
        end = c[-1]
        orelse = c[-2]
        ln, k = self.tpos(t)
        branches = [A.Branch(cond, body, ln, k)]
        branches.extend(c[3:-2])
        el, ec = self.tend(end)
        if orelse is None:
            return A.If(branches, None, ln, k, 0, 0, el, ec)
        ol, oc, obody = orelse
        return A.If(branches, obody, ln, k, ol, oc, el, ec)

    def elseif_clause(self, c):
        t, cond, body = c
        return A.Branch(cond, body, *self.tpos(t))

    def else_clause(self, c):
        t, body = c
        ln, k = self.tpos(t)
        return (ln, k, body)

    def while_stmt(self, c):
        t, cond, body, end = c
        ln, k = self.tpos(t)
        el, ec = self.tend(end)
        return A.While(cond, body, ln, k, el, ec)

    def do_stmt(self, c):
        t, body, u, cond = c
        ln, k = self.tpos(t)
        ul, uc = self.tpos(u)
        return A.DoUntil(body, cond, ln, k, ul, uc)

    def for_header(self, c):
        if len(c) == 1:  # ERROR (recovery)
            e = A.ErrorExpr(*self.tpos(c[0]))
            return (e, e, e, None)
        counter, _eq, start, _to, stop, _step, step = c
        return (counter, start, stop, step)

    def for_stmt(self, c):
        t, (counter, start, stop, step), body, end = c
        ln, k = self.tpos(t)
        el, ec = self.tend(end)
        return A.For(counter, start, stop, step, body, ln, k, el, ec)

    def case_clause(self, c):
        t = c[0]
        return A.Case(c[1:-1], c[-1], *self.tpos(t))

    def default_clause(self, c):
        t, body = c
        return A.Default(body, *self.tpos(t))

    def switch_stmt(self, c):
        t, subject = c[0], c[1]
        end = c[-1]
        default = c[-2]
        ln, k = self.tpos(t)
        el, ec = self.tend(end)
        return A.Switch(subject, c[2:-2], default, ln, k, el, ec)

    def start(self, c):
        b, stmts, e = c
        ln, k = self.tpos(b)
        el, ec = self.tend(e)
        return A.ProgramBody(stmts, [], ln, k, el, ec)


# ---------------------------------------------------------------- the grammar and its tables


def grammar_text() -> str | None:
    """The grammar file's text (line ends normalised), or None when it cannot be read."""
    import os

    from ..resources import resource_path

    try:
        with open(os.path.join(resource_path("grammars"), "val3.lark"), encoding="utf-8") as f:
            return f.read().replace("\r\n", "\n")
    except OSError:
        return None


def grammar_hash(text: str) -> str:
    from ..resources import sha256_hex

    return sha256_hex(text.encode("utf-8"))


def build_from_grammar(text: str, transformer: Any = None):
    """A Lark parser built from the grammar text (slow: ~70 ms)."""
    from lark import Lark

    return Lark(text, **LARK_OPTIONS, transformer=transformer)


def load_tables() -> dict:
    """The parse tables (tables.compile_tables): the shipped ones when they match the
    grammar file, else computed from the grammar file itself with Lark (while editing it)."""
    text = grammar_text()
    try:
        from . import _tables

        if text is None or _tables.GRAMMAR_SHA256 == grammar_hash(text):
            return {k: getattr(_tables, k) for k in ("LEXER", "STATES", "RULES", "START", "END")}
    except Exception:  # missing or incompatible tables: fall back on the grammar
        if text is None:
            raise
    from .tables import compile_tables

    return compile_tables(build_from_grammar(text), frozenset(dir(_Builder)))  # type: ignore[arg-type]


# ---------------------------------------------------------------- the engine


def _lone(children: list) -> Any:
    if len(children) != 1:  # pragma: no cover - a grammar change Lark would build a Tree for
        raise ValueError(f"a ?rule alternative kept {len(children)} children")
    return children[0]


def _reducer(builder: "_Builder", plan: tuple):
    """The function of one rule: children as the LALR driver pops them -> the node.

    It does what Lark's tree builder does (tables.compile_tables), written out as straight
    code: e.g. `call: callee _LPAR [args] _RPAR` without args becomes
    `lambda c: builder.call([c[0], None])`."""
    callback, expand1, include, nones = plan
    fn = getattr(builder, callback) if callback is not None else None
    if fn is None and expand1:  # `?rule: _LPAR expr _RPAR`: the lone kept child itself
        fn = _lone
    if include is None and not nones and not expand1:
        return fn if fn is not None else list
    parts: list[str] = []  # items of the kept list, in order; "*" marks an inlined child list
    for i, inline, before in include or ():
        parts.extend(["None"] * before)
        parts.append(f"*c[{i}]" if inline else f"c[{i}]")
    parts.extend(["None"] * nones)
    if include and include[0][1] and not include[0][2]:
        # `__x_star: __x_star item`: extend the left child's own list (left recursion, linear)
        body = [f"f = c[{include[0][0]}]"] + [f"f.append({p})" if not p.startswith("*") else f"f.extend({p[1:]})"
                                               for p in parts[1:]]
    else:
        body = [f"f = [{', '.join(parts)}]"]
    if expand1:
        body.append("if len(f) == 1: return f[0]")
    body.append("return fn(f)" if fn is not None else "return f")
    src = "def reduce(c):\n" + "".join(f"    {line}\n" for line in body)
    scope: dict = {"fn": fn}
    exec(src, scope)  # noqa: S102 - source built above from the shipped tables
    return scope["reduce"]


class _Stop(Exception):
    """Internal: parsing ends here (an error that cannot be recovered from)."""


class _Engine:
    """LALR(1) driver over Lark's tables, with its own lexer and line-based error recovery."""

    def __init__(self) -> None:
        self.builder = _Builder()
        tables = load_tables()
        # rules[k]: (number of children, rule name, callback); callback None for `?rule: other`
        # (the value passes through unchanged: only the state changes)
        rules = [(size, origin, None if plan is None else _reducer(self.builder, plan))
                 for origin, size, plan in tables["RULES"]]
        # actions[state][symbol]: int = shift to (or goto) that state; tuple = reduce
        self.actions: list[dict[str, Any]] = [
            {sym: (act if act >= 0 else rules[-1 - act]) for sym, act in row.items()} for row in tables["STATES"]]
        self.start_state = tables["START"]
        self.end_state = tables["END"]
        self.unit_memo: dict[tuple[int, int, str], int] = {}
        self.expected = [frozenset(k for k in acts if k.isupper()) for acts in self.actions]
        self.regex = re.compile(tables["LEXER"])

    # -------------------------------------------------------------- driver

    def parse(self, ctx: "_Context") -> Any:
        text = ctx.code
        match = self.regex.match
        actions = self.actions
        end_state = self.end_state
        keywords = KEYWORDS
        ctx_keywords = _CONTEXT_KEYWORDS
        openers = _OPENERS
        closers = _CLOSERS
        unit_memo = self.unit_memo
        state_stack = [self.start_state]
        value_stack: list = []
        ctx.state_stack = state_stack
        ctx.value_stack = value_stack
        pos = 0
        line = 1
        line_start = 0
        depth = 0
        state = state_stack[-1]  # the top of state_stack, kept in a local
        while True:
            m = match(text, pos)
            if m is None:
                # no terminal matches: an invalid character
                p = pos
                while text[p] in " \t\f\r":
                    p += 1
                ch = text[p]
                col = p - line_start + 1
                ctx.report(codes.INVALID_CHARACTER, _char_message(ch), line, col, line, col + 1)
                pos = self._recover(ctx, None, line, col, p)
                state = state_stack[-1]
                continue
            ttype = m.lastgroup
            start, pos = m.span(ttype)
            value = text[start:pos]
            if ttype == "NAME":
                low = value.lower()
                kw = keywords.get(low)
                if kw is not None:
                    ttype = kw
                    if kw in openers:
                        depth += 1
                        if depth > MAX_BLOCK_DEPTH and ctx.deep_token is None:
                            ctx.deep_token = Tok((kw, value, line, start - line_start + 1))
                    elif kw in closers:
                        depth -= 1
                elif low in ctx_keywords and ctx_keywords[low] in actions[state]:
                    ttype = ctx_keywords[low]
                tok = (ttype, value, line, start - line_start + 1)
            elif ttype == "_NL":
                tok = (ttype, value, line, start - line_start + 1)
                line += value.count("\n")
                line_start = start + value.rindex("\n") + 1
            elif ttype == "COMMENT":
                continue
            else:
                if ttype == "EOF":
                    ttype = "$END"
                col = start - line_start + 1
                tok = (ttype, value, line, col)
                if ttype == "BADSTRING":
                    ctx.report(codes.SYNTAX_ERROR, "unterminated string: a string ends with '\"' on the same line",
                               line, col, line, col + len(value))
                elif ttype == "BADNUMBER":
                    ctx.report(codes.INVALID_NUMBER, _number_message(value), line, col, line, col + len(value))

            # feed the token to the LALR automaton
            while True:
                act = actions[state].get(ttype)
                if act is None:
                    pos = self._recover(ctx, Tok(tok), tok[2], tok[3], pos)
                    state = state_stack[-1]
                    break
                if act.__class__ is int:
                    state_stack.append(act)
                    value_stack.append(tok)
                    state = act
                    break
                size, origin, callback = act
                if callback is None:  # unit rules: only the state changes; chains are memoised
                    key = (state_stack[-2], state, ttype)
                    state = unit_memo.get(key)
                    if state is None:
                        state = unit_memo[key] = self._unit_chain(key)
                    state_stack[-1] = state
                    continue
                if size == 1:  # the most common reduction (leaves): replace the tops in place
                    value_stack[-1] = callback([value_stack[-1]])
                    state = state_stack[-1] = actions[state_stack[-2]][origin]
                    continue  # (a one-symbol rule never completes the start rule)
                else:
                    if size:
                        children = value_stack[-size:]
                        del value_stack[-size:]
                        del state_stack[-size:]
                    else:
                        children = []
                    value_stack.append(callback(children))
                state = actions[state_stack[-1]][origin]
                state_stack.append(state)
                if state == end_state and ttype == "$END":
                    return value_stack[-1]

    def _unit_chain(self, key: tuple[int, int, str]) -> int:
        """The state reached from `top` (above `below`) by the unit reductions that the
        lookahead triggers."""
        below, state, ttype = key
        actions = self.actions
        while True:
            act = actions[state].get(ttype)
            if act.__class__ is not tuple or act[2] is not None:
                return state
            state = actions[below][act[1]]

    def accepts(self, state_stack: list[int]) -> frozenset[str]:
        """The terminals that can really come next (LALR lookahead sets of merged states are
        wider): each candidate is tried on a copy of the state stack."""
        actions = self.actions
        end_state = self.end_state
        out = set()
        for t in self.expected[state_stack[-1]]:
            states = list(state_stack)
            while True:
                act = actions[states[-1]].get(t)
                if act is None:
                    break
                if act.__class__ is int:
                    out.add(t)
                    break
                size, origin = act[0], act[1]
                if size:
                    del states[-size:]
                states.append(actions[states[-1]][origin])
                if states[-1] == end_state and t == "$END":
                    out.add(t)
                    break
        return frozenset(out)

    @staticmethod
    def _feed(actions, end_state, state_stack, value_stack, tok) -> bool:
        """Feed one token (error recovery); False when the automaton rejects it."""
        ttype = tok.type
        while True:
            act = actions[state_stack[-1]].get(ttype)
            if act is None:
                return False
            if act.__class__ is int:
                state_stack.append(act)
                value_stack.append(tok)
                return True
            size, origin, callback = act
            if callback is None:
                state_stack[-1] = actions[state_stack[-2]][origin]
                continue
            if size:
                children = value_stack[-size:]
                del value_stack[-size:]
                del state_stack[-size:]
            else:
                children = []
            value_stack.append(callback(children))
            new_state = actions[state_stack[-1]][origin]
            state_stack.append(new_state)
            if new_state == end_state and ttype == "$END":
                return True

    # -------------------------------------------------------------- errors

    def _recover(self, ctx: "_Context", bad: Tok | None, line: int, col: int, pos: int) -> int:
        """Report a syntax error at `bad` (None: an invalid character, already reported), then
        resynchronise: skip the rest of the line and bring the automaton to a state that
        accepts the line end, by popping states until an ERROR placeholder (an expression, a
        statement or a `for` header) can complete the line. Returns the position to lex from.
        Raises _Stop when the parse cannot go on usefully."""
        state_stack = ctx.state_stack
        value_stack = ctx.value_stack
        if bad is not None:
            expected = self.accepts(state_stack)
            msg = _syntax_message(ctx, bad, expected, value_stack)
            if msg.structural and ctx.recovered:
                raise _Stop  # probably a consequence of an earlier error and its recovery
            if bad.type in ("_NL", "$END"):
                ctx.report(codes.SYNTAX_ERROR, msg.text, line, col)
            else:
                ctx.report(codes.SYNTAX_ERROR, msg.text, line, col, line, col + len(bad.value))
            if msg.structural or bad.type == "$END":
                raise _Stop
        if len(ctx.diags) >= MAX_ERRORS:
            raise _Stop

        text = ctx.code
        nl_consumed = bad is not None and bad.type == "_NL"
        if not nl_consumed:
            nl = text.find("\n", pos)
            pos = nl if nl >= 0 else len(text)
        nl_tok = bad if nl_consumed else Tok(("_NL", "\n", line, col))
        err_tok = Tok(("ERROR", "", line, col))
        actions = self.actions
        end_state = self.end_state
        feed = self._feed
        for n_pop in range(min(len(state_stack) - 1, 100) + 1):
            keep = len(state_stack) - n_pop
            for seq in ((nl_tok,), (err_tok, nl_tok)):
                states, values = state_stack[:keep], value_stack[: keep - 1]
                if not all(feed(actions, end_state, states, values, t) for t in seq):
                    continue
                # it works: do it for real; the lexer reads the line end next, unless the
                # error was at the line end itself
                states, values = state_stack[:keep], value_stack[: keep - 1]
                for t in seq if nl_consumed else seq[:-1]:
                    feed(actions, end_state, states, values, t)
                state_stack[:] = states
                value_stack[:] = values
                ctx.recovered = True
                return pos
        raise _Stop


# ---------------------------------------------------------------- per-parse state


class _Context:
    """What one parse needs besides the engine: the code, the diagnostics so far."""

    def __init__(self, code: str, path: str, builder: _Builder) -> None:
        self.code = code
        self.path = path
        self.builder = builder
        self.diags: list[Diagnostic] = []
        self.error_lines: set[int] = set()  # code lines that already have an error
        self.recovered = False  # a broken line was skipped: the block structure may be off
        self.deep_token: Tok | None = None  # the opener that went past MAX_BLOCK_DEPTH
        self.state_stack: list = []
        self.value_stack: list = []

    def report(self, code: str, message: str, line: int, col: int,
               end_line: int | None = None, end_col: int | None = None) -> None:
        """Report at a code position, unless the line already has an error."""
        if line in self.error_lines:
            return
        fl, fc = self.builder.fpos(line, col)
        fel = fec = None
        if end_line is not None and end_col is not None:
            fel, fec = self.builder.fpos(end_line, end_col)
        self.diags.append(Diagnostic(code, message, self.path, fl, fc, fel, fec))
        self.error_lines.add(line)


_engine: _Engine | None = None
_lock = threading.RLock()  # one parse at a time (the builder holds per-parse state)


def get_engine() -> _Engine:
    global _engine
    if _engine is None:
        with _lock:
            if _engine is None:
                _engine = _Engine()
    return _engine


# ---------------------------------------------------------------- comments

_COMMENT_SCAN = re.compile(r'"[^"\n]*"?|//[^\n]*')


def scan_comments(code: str, source_map: SourceMap | None = None) -> list[A.Comment]:
    """Every `//` comment of `code` (outside strings), with file positions. Works on code with
    syntax errors too: the lint driver can read suppression comments there."""
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


def _describe(tok: Tok) -> str:
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
    return f"'{_clip(tok.value)}'"


def _expected_order(t: str) -> tuple[int, str]:
    order = ["EQUAL", "_LPAR", "_RPAR", "_RSQB", "_RBRACE", "_COMMA", "TO", "STEP", "_NL", "$END"]
    return (order.index(t) if t in order else len(order), t)


def _expected_words(expected: frozenset[str] | set[str]) -> list[str]:
    exp = set(expected) - {"ERROR", "BADNUMBER", "BADSTRING", "COMMENT"}
    words: list[str] = []
    if exp >= {"IF", "WHILE", "CALL"}:
        words.append("a statement")
        exp -= _STMT_START
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


def _syntax_message(ctx: _Context, tok: Tok, expected: frozenset[str], value_stack: list) -> _Message:
    """Say what was found and what was expected, in words, like a compiler would."""
    value_stack = [as_tok(v) for v in value_stack]
    t = tok.type
    found = _describe(tok)
    # keyword tokens still on the stack: the blocks and clauses not closed yet
    blocks = [v for v in value_stack if v.__class__ is Tok and v.type in _OPENERS | {"ELSE", "DEFAULT"}]
    inner = blocks[-1] if blocks else None
    opener = next((b for b in reversed(blocks) if b.type in _OPENERS), None)
    top = value_stack[-1] if value_stack and value_stack[-1].__class__ is Tok else None

    def line_of(b: Tok) -> int:
        return ctx.builder.fpos(b.line, b.column)[0]

    def opened(b: Tok, before: str = "") -> str:
        return (f"the '{_SPELLING[b.type]}' opened on line {line_of(b)} is not closed "
                f"(expected '{_SPELLING[_CLOSER_OF[b.type]]}'{before})")

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
    if t in _STRUCTURAL or t == "$END":
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
        want = _OPENER_OF.get(t)
        if opener is None:
            if want is not None:
                return _Message(f"'{tok.value}' without '{_SPELLING[want]}'", True)
            return _Message(f"unexpected {found}: expected {_join(_expected_words(expected))}", True)
        if expected and expected <= {"CASE", "DEFAULT", "ENDSWITCH"}:
            return _Message(f"unexpected {found}: expected 'case', 'default' or 'endSwitch' "
                            f"in the 'switch' of line {line_of(opener)}", True)
        if opener.type == want or (top is not None and top.type not in _OPENERS and tok.line == top.line):
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
        for closing, (opening, cname, oname) in _CLOSING.items():
            if closing in expected:
                for v in reversed(value_stack):
                    if v.__class__ is Tok and v.type == opening:
                        fl, fc = ctx.builder.fpos(v.line, v.column)
                        return _Message(f"missing {cname}: the {oname} at line {fl}, column {fc} "
                                        "is not closed", False)
        if top is not None and top.type in ("NAME", "SYSNAME") and {"EQUAL", "_LPAR"} <= expected:
            return _Message("incomplete statement: expected '=' (assignment) or '(' (call) "
                            f"after '{_clip(top.value)}'", False)
    if (top is not None and top.type == "NAME" and t in ("NAME", "NUMBER", "STRING", "_LPAR")
            and len(value_stack) >= 2 and value_stack[-2].__class__ is Tok and value_stack[-2].type == "_NL"):
        # `whlie x`: a misspelt keyword at the start of a line
        import difflib

        close = difflib.get_close_matches(top.value.lower(), list(KEYWORDS), n=1, cutoff=0.75)
        if close:
            return _Message(f"unexpected {found} after '{_clip(top.value)}': did you mean "
                            f"'{_SPELLING[KEYWORDS[close[0]]]}'?", False)
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
    if t in ("TRUE", "FALSE", "AND", "OR", "XOR", "CALL", "RETURN", "BREAK") or t in _OPENERS:
        found = f"keyword {found}"
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


def _number_message(text: str) -> str:
    if re.fullmatch(r"(?:[0-9]+\.?[0-9]*|\.[0-9]+)[eE][+-]?", text):
        why = "the exponent has no digits"
    elif text[:2].lower() in ("0x", "0b"):
        why = "hexadecimal and binary constants are not VAL 3 numbers (manual 3.2.1)"
    elif re.match(r"[0-9]+[A-Za-z_]", text) and not re.match(r"[0-9]+[eE][+-]?[0-9]", text):
        why = "a number cannot be followed by letters, and a name starts with a letter"
    else:
        why = "numbers are written <digits>[.<digits>][e[-]<digits>] (manual 3.2.1)"
    return f"invalid number '{_clip(text)}': {why}"


# ---------------------------------------------------------------- depth check


def _expr_too_deep(body: A.ProgramBody):
    """The first statement with an expression nested more than MAX_EXPR_DEPTH levels."""
    stmt_types = (
        A.Assign,
        A.ExprStatement,
        A.Call,
        A.TaskCreate,
        A.TaskCreateSync,
        A.Print,
        A.Return,
        A.Break,
        A.If,
        A.While,
        A.DoUntil,
        A.For,
        A.Switch,
        A.Branch,
        A.Case,
        A.Default,
    )
    stack: list[tuple[Any, int, Any]] = [(s, 0, s) for s in reversed(body.statements)]
    while stack:
        node, depth, stmt = stack.pop()
        if type(node) in stmt_types:
            depth = 0
            stmt = node
        elif depth > MAX_EXPR_DEPTH:
            return stmt
        for ch in reversed(A.children(node)):
            stack.append((ch, depth + 1, stmt))
    return None


# ---------------------------------------------------------------- entry points


def parse_code(code: str, source_map: SourceMap, path: str) -> tuple[A.ProgramBody | None, list[Diagnostic]]:
    """Parse a program's code (`begin` ... `end`). Returns the body (None when the code has
    syntax errors) and the diagnostics, positioned in the file `path` through `source_map`.
    Never raises."""
    try:
        with _lock:
            return _parse_locked(code, source_map, path)
    except Exception as exc:  # noqa: BLE001 - never raise
        return None, [
            Diagnostic(
                codes.SYNTAX_ERROR,
                f"could not parse this program (internal error: {exc.__class__.__name__}: {_clip(str(exc), 80)})",
                path,
                1,
                1,
            )
        ]


def _parse_locked(code: str, source_map: SourceMap, path: str) -> tuple[A.ProgramBody | None, list[Diagnostic]]:
    gc_enabled = gc.isenabled()
    gc.disable()  # the parse allocates many small acyclic objects: the cyclic GC only slows it
    try:
        return _parse_nogc(code, source_map, path)
    finally:
        if gc_enabled:
            gc.enable()


def _parse_nogc(code: str, source_map: SourceMap, path: str) -> tuple[A.ProgramBody | None, list[Diagnostic]]:
    engine = get_engine()
    builder = engine.builder
    builder.setup(code, source_map)
    ctx = _Context(code, path, builder)
    body = None
    try:
        body = engine.parse(ctx)
    except _Stop:
        pass
    except RecursionError:
        ctx.diags.append(
            Diagnostic(
                codes.TOO_DEEPLY_NESTED, "the program is nested too deeply to be analysed", path, *builder.fpos(1, 1)
            )
        )
    except MemoryError:
        ctx.diags.append(
            Diagnostic(codes.TOO_DEEPLY_NESTED, "the program is too large to be analysed", path, *builder.fpos(1, 1))
        )
    finally:
        ctx.state_stack = ctx.value_stack = []
    if ctx.diags or not isinstance(body, A.ProgramBody):
        if not ctx.diags:
            ctx.diags.append(Diagnostic(codes.SYNTAX_ERROR, "could not parse this program", path, *builder.fpos(1, 1)))
        return None, sorted(ctx.diags, key=Diagnostic.sort_key)
    if ctx.deep_token is not None:
        t = ctx.deep_token
        ctx.report(
            codes.TOO_DEEPLY_NESTED,
            f"blocks nested more than {MAX_BLOCK_DEPTH} deep: split the program into sub-programs",
            t.line,
            t.column,
        )
        return None, ctx.diags
    if len(code) > MAX_EXPR_DEPTH and max(map(len, code.split("\n"))) > MAX_EXPR_DEPTH:
        node = _expr_too_deep(body)
        if node is not None:
            ctx.diags.append(
                Diagnostic(
                    codes.TOO_DEEPLY_NESTED,
                    f"expression nested more than {MAX_EXPR_DEPTH} deep: split it with intermediate variables",
                    path,
                    node.line,
                    node.col,
                )
            )
            return None, ctx.diags
    body.comments = scan_comments(code, source_map)
    return body, []


def parse_program(program: Any) -> list[Diagnostic]:
    """Parse `program.code` and set `program.body` (None when there are syntax errors). A
    missing code element (`code is None`) is the loader's to report: nothing to do."""
    if program.code is None:
        return []
    body, diags = parse_code(program.code, program.code_map, program.origin.path)
    program.body = body
    return diags
