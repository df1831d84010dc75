"""The LALR(1) driver over the tables: lexer, shifts and reductions, line-based error recovery."""

from __future__ import annotations

import re

from ..diagnostics import Diagnostic
from ..rules import codes
from .builder import Builder
from .grammar import load_tables
from .messages import char_message, number_message, syntax_message
from .descent import Descent
from .tokens import CLOSERS, CONTEXT_KEYWORDS, KEYWORDS, MAX_BLOCK_DEPTH, OPENERS, Tok

TYPE_CHECKING = False  # not typing's: importing typing costs 3 ms at lint's start-up
if TYPE_CHECKING:
    from typing import Any

MAX_ERRORS = 10  # diagnostics reported per program


def _lone(children: list) -> Any:
    if len(children) != 1:  # pragma: no cover - a grammar change Lark would build a Tree for
        raise ValueError(f"a ?rule alternative kept {len(children)} children")
    return children[0]


def _reducer(builder: "Builder", plan: tuple):
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


class Stop(Exception):
    """Internal: parsing ends here (an error that cannot be recovered from)."""


class Engine:
    """LALR(1) driver over Lark's tables, with its own lexer and line-based error recovery."""

    def __init__(self) -> None:
        self.builder = Builder()
        tables = load_tables()
        self.start_state = tables["START"]
        self.end_state = tables["END"]
        self.unit_memo: dict[tuple[int, int, str], int] = {}
        self.lexer = tables["LEXER"]  # the master regex, compiled on first use (self.regex)
        # the fast path for code without errors (None: the tables alone, as tests compare them)
        self.descent: Descent | None = Descent(self.builder, self.lexer)
        self._tables = tables
        # self.regex, self.actions, self.expected: made on first use (__getattr__)

    def __getattr__(self, name: str) -> Any:
        """The automaton and the master regex, made on first use: code without errors never needs
        them (the fast path parses it), and making them is about 5 ms of lint's start-up (a
        function per rule, 1 ms to compile the regex)."""
        if name == "regex":
            self.regex = re.compile(self.lexer)
            return self.regex
        if name not in ("actions", "expected") or "_tables" not in self.__dict__:
            raise AttributeError(name)
        tables = self.__dict__.pop("_tables")
        # rules[k]: (number of children, rule name, callback); callback None for `?rule: other`
        # (the value passes through unchanged: only the state changes)
        rules = [(size, origin, None if plan is None else _reducer(self.builder, plan))
                 for origin, size, plan in tables["RULES"]]
        # actions[state][symbol]: int = shift to (or goto) that state; tuple = reduce
        self.actions: list[dict[str, Any]] = [
            {sym: (act if act >= 0 else rules[-1 - act]) for sym, act in row.items()} for row in tables["STATES"]]
        self.expected = [frozenset(k for k in acts if k.isupper()) for acts in self.actions]
        return getattr(self, name)

    # -------------------------------------------------------------- driver

    def parse(self, ctx: "Context") -> Any:
        text = ctx.code
        match = self.regex.match
        actions = self.actions
        end_state = self.end_state
        keywords = KEYWORDS
        ctx_keywords = CONTEXT_KEYWORDS
        openers = OPENERS
        closers = CLOSERS
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
                ctx.report(codes.INVALID_CHARACTER, char_message(ch), line, col, line, col + 1)
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
                    ctx.report(codes.INVALID_NUMBER, number_message(value), line, col, line, col + len(value))

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

    def _recover(self, ctx: "Context", bad: Tok | None, line: int, col: int, pos: int) -> int:
        """Report a syntax error at `bad` (None: an invalid character, already reported), then
        resynchronise: skip the rest of the line and bring the automaton to a state that
        accepts the line end, by popping states until an ERROR placeholder (an expression, a
        statement or a `for` header) can complete the line. Returns the position to lex from.
        Raises Stop when the parse cannot go on usefully."""
        state_stack = ctx.state_stack
        value_stack = ctx.value_stack
        if bad is not None:
            expected = self.accepts(state_stack)
            msg = syntax_message(ctx.builder, bad, expected, value_stack)
            if msg.structural and ctx.recovered:
                raise Stop  # probably a consequence of an earlier error and its recovery
            if bad.type in ("_NL", "$END"):
                ctx.report(codes.SYNTAX_ERROR, msg.text, line, col)
            else:
                ctx.report(codes.SYNTAX_ERROR, msg.text, line, col, line, col + len(bad.value))
            if msg.structural or bad.type == "$END":
                raise Stop
        if len(ctx.diags) >= MAX_ERRORS:
            raise Stop

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
        raise Stop


# ---------------------------------------------------------------- per-parse state


class Context:
    """What one parse needs besides the engine: the code, the diagnostics so far."""

    def __init__(self, code: str, path: str, builder: Builder) -> None:
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
