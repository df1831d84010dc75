"""Parse the code of a VAL 3 program into the typed tree of `val3check.parsing.ast`: the entry points.

The grammar is `grammars/val3.lark`, compiled by Lark into LALR(1) tables (`grammar.py`: shipped
pre-built in `_tables.py`, regenerated with `python -m val3check.parsing.build_parser`, built from
the grammar while it is edited). Everything is built lazily, on the first parse. The modules:

  tokens.py      reserved words, terminal names and spellings, `Tok`
  builder.py     the tree-building callback of each rule (ast nodes with file positions)
  descent.py     the fast path: a recursive descent for code without errors, the engine's trees
  fast_lexer.py  its tokenizer (the engine's tokens, from one findall)
  engine.py      the LALR driver over the tables (our own: about 3x Lark's), with its contextual
                 lexer (`to` and `step` are keywords only inside `for`) and line-based recovery;
                 it parses what the fast path leaves (syntax errors, very deep nesting)
  messages.py    syntax error messages in words
  comments.py    the `//` comments, with positions

Syntax errors are diagnostics, never exceptions: F101 (syntax error, unterminated string), F102
(invalid character), F103 (invalid number), F104 (nesting too deep to analyse). After an error the parser
resynchronises on the next line and goes on, so that independent errors of other lines are
reported too; errors that could be consequences of an earlier one are not reported.
"""

from __future__ import annotations

import gc
import _thread  # RLock without the threading module (1 ms of start-up)

from ..diagnostics import Diagnostic
from ..positions import SourceMap
from ..rules import codes
from . import ast as A
from .comments import scan_comments
from .engine import Context, Engine, Stop
from .tokens import MAX_BLOCK_DEPTH, clip

TYPE_CHECKING = False  # not typing's: importing typing costs 3 ms at lint's start-up
if TYPE_CHECKING:
    from typing import Any

__all__ = ["parse_code", "parse_program", "scan_comments", "MAX_BLOCK_DEPTH", "MAX_EXPR_DEPTH"]

MAX_EXPR_DEPTH = 100  # nested operations in one expression

_engine: Engine | None = None
_lock = _thread.RLock()  # one parse at a time (the builder holds per-parse state)


def get_engine() -> Engine:
    global _engine
    if _engine is None:
        with _lock:
            if _engine is None:
                _engine = Engine()
    return _engine


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
                f"could not parse this program (internal error: {exc.__class__.__name__}: {clip(str(exc), 80)})",
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
    body = engine.descent.parse(code) if engine.descent is not None else None
    if body is None:  # syntax errors, or code the fast path leaves to the engine
        return _parse_lalr(engine, code, source_map, path)
    return _checked(body, code, source_map, path)


def _parse_lalr(engine: Engine, code: str, source_map: SourceMap, path: str) -> tuple[A.ProgramBody | None, list[Diagnostic]]:
    builder = engine.builder
    ctx = Context(code, path, builder)
    body = None
    try:
        body = engine.parse(ctx)
    except Stop:
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
    return _checked(body, code, source_map, path)


def _checked(body: A.ProgramBody, code: str, source_map: SourceMap,
             path: str) -> tuple[A.ProgramBody | None, list[Diagnostic]]:
    """A parsed body, unless an expression is nested too deep; with its comments."""
    if len(code) > MAX_EXPR_DEPTH and max(map(len, code.split("\n"))) > MAX_EXPR_DEPTH:
        node = _expr_too_deep(body)
        if node is not None:
            return None, [Diagnostic(
                codes.TOO_DEEPLY_NESTED,
                f"expression nested more than {MAX_EXPR_DEPTH} deep: split it with intermediate variables",
                path, node.line, node.col)]
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
