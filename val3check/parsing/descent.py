"""A recursive-descent parser for code without syntax errors: the LALR engine's trees, faster.

It reads the grammar of `grammars/val3.lark` by hand, on the engine's own tokens (same master
regex, same keywords: `fast_lexer.py`), and builds each node with the same `Builder` callback and the same
children as the engine's reductions, so trees and positions are the same by construction (and
tests/parsing/test_descent.py compares them). It knows no error: at the first token it does not
expect, an invalid character, a bad number or string, blocks nested past MAX_BLOCK_DEPTH or
expressions nested past MAX_NESTING, it gives up (`Fallback`) and the caller parses the program
again with the engine, which reports and recovers. `to` and `step` are read from names where the
`for` header expects them: the engine's contextual lexer makes them keywords in those places only.
"""

from __future__ import annotations


from . import ast as A
from .builder import Builder
from .fast_lexer import Fallback, number_regex, pair_regex, tokenize
from .tokens import MAX_BLOCK_DEPTH, OPENERS

TYPE_CHECKING = False  # not typing's: importing typing costs 3 ms at lint's start-up
if TYPE_CHECKING:
    from typing import Any

MAX_NESTING = 50  # nested expressions handled here (deeper: the engine, without recursion)

# binary operators (terminal -> precedence, all left-associative); `=` (assign_expr) is below
# them and right-associative (see the grammar)
_PRECEDENCE = {"OR": 1, "AND": 2, "XOR": 3, "EQOP": 4, "RELOP": 5, "PLUS": 6, "MINUS": 6, "MULOP": 7}
_SLOT_END = frozenset({"_COMMA", "_RBRACE"})  # an empty field of a structure `{1,,2}`
_WORD_OPS = frozenset({"AND", "OR", "XOR"})
# what may follow an operand that is one token (no call, index or field after it)
_OPERAND_END = frozenset(_PRECEDENCE) | {"_NL", "_RPAR", "_RSQB", "_RBRACE", "_COMMA", "EQUAL", "NAME"}
_EXPR_END = frozenset({"_NL", "_RPAR", "_RSQB", "_RBRACE", "_COMMA", "NAME"})  # ... of a whole expression


class Descent:
    """The parser of one engine's builder and lexer."""

    def __init__(self, builder: Builder, lexer: str) -> None:
        """`lexer`: the engine's master regex (its pattern)."""
        self.builder = builder
        self.regex = pair_regex(lexer)
        self.number = number_regex(lexer).match
        self.known: dict[str, str] = {}

    def parse(self, code: str) -> Any:
        """The body of the program `code`, or None: not for this parser (the engine's job)."""
        try:
            types, toks = tokenize(code, self.regex, self.number, self.known)
            return _parse(types, toks, self.builder)
        except (Fallback, IndexError, RecursionError):
            return None


def _parse(types: list[str], toks: list[tuple], b: Builder) -> Any:  # noqa: C901 - one grammar
    """The grammar, rule by rule; the builder callbacks get the children the engine gives them."""
    pos = 0
    nesting = 0  # expressions being read
    depth = 0  # blocks open
    openers = OPENERS
    precedence = _PRECEDENCE
    slot_end = _SLOT_END
    b_name, b_lib_name, b_sys_name = b.name, b.lib_name, b.sys_name
    b_number, b_string, b_true, b_false = b.number, b.string, b.true, b.false
    b_field, b_unary, b_binary = b.field, b.unary, b.binary
    # The hot leaves and operations are made here as the builder makes them (tests compare):
    # lines of code without a column map map with two list reads.
    lines, offs, col_maps = b.lines, b.offs, b.col_maps
    Name, Number, Binary, Assign = A.Name, A.Number, A.Binary, A.Assign
    CallExpr, ExprStatement, Index = A.CallExpr, A.ExprStatement, A.Index
    word_ops = _WORD_OPS
    operand_end = _OPERAND_END
    expr_end = _EXPR_END

    def expect(ttype: str) -> tuple:
        nonlocal pos
        if types[pos] != ttype:
            raise Fallback
        pos += 1
        return toks[pos - 1]

    def word(spelling: str) -> tuple | None:
        """The contextual keyword `to`/`step` (a name token) when it comes next."""
        nonlocal pos
        if types[pos] == "NAME" and toks[pos][1].lower() == spelling:
            pos += 1
            return toks[pos - 1]
        return None

    # ------------------------------------------------------------ expressions

    def expr() -> Any:
        # ?expr: or_expr | or_expr EQUAL expr -> assign_expr
        nonlocal pos, nesting
        t = types[pos]
        if (t == "NAME" or t == "NUMBER") and types[pos + 1] in expr_end:
            # `f(a, 1)`, `x = 0`: the most common expressions (leaf() written out)
            tok = toks[pos]
            k = tok[2] - 1
            if k not in col_maps:
                pos += 1
                v = tok[1]
                ln = lines[k]
                col = offs[k] + tok[3]
                if t == "NAME":
                    return Name(v, ln, col, ln, col + len(v))
                return Number(float(v), v, ln, col, ln, col + len(v))
            return leaf()
        nesting += 1
        if nesting > MAX_NESTING:
            raise Fallback
        left = operation(1)
        if types[pos] == "EQUAL":
            t = toks[pos]
            pos += 1
            left = b.assign_expr([left, t, expr()])
        nesting -= 1
        return left

    def leaf() -> Any:
        """The NAME or NUMBER token at `pos`, alone, as Builder.name or Builder.number makes it."""
        nonlocal pos
        tok = toks[pos]
        pos += 1
        k = tok[2] - 1
        if k in col_maps:
            return b_name([tok]) if tok[0] == "NAME" else b_number([tok])
        v = tok[1]
        ln = lines[k]
        col = offs[k] + tok[3]
        if tok[0] == "NAME":
            return Name(v, ln, col, ln, col + len(v))
        return Number(float(v), v, ln, col, ln, col + len(v))

    def operation(lowest: int) -> Any:
        # or_expr ... mul_expr: binary operators by precedence climbing, left-associative
        nonlocal pos
        t = types[pos]
        if (t == "NAME" or t == "NUMBER") and types[pos + 1] in operand_end:
            left = leaf()
        else:
            left = unary()
        while True:
            p = precedence.get(types[pos])
            if p is None or p < lowest:
                return left
            t = toks[pos]
            pos += 1
            r = types[pos]
            after = types[pos + 1]
            if (r == "NAME" or r == "NUMBER") and after in operand_end and precedence.get(after, 0) <= p:
                right = leaf()  # `a + 1 ...`: no operator binding tighter follows
            else:
                right = operation(p + 1)
            k = t[2] - 1
            if k in col_maps:  # Builder.binary
                left = b_binary([left, t, right])
            else:
                left = Binary(t[1].lower() if t[0] in word_ops else t[1], left, right, left.line, left.col,
                              lines[k], offs[k] + t[3])

    def unary() -> Any:
        # ?unary: postfix | (MINUS | BANG) unary
        nonlocal pos, nesting
        t = types[pos]
        if t == "MINUS" or t == "BANG":
            tok = toks[pos]
            pos += 1
            nesting += 1
            if nesting > MAX_NESTING:
                raise Fallback
            node = b_unary([tok, unary()])
            nesting -= 1
            return node
        # ?postfix: primary | postfix _LSQB args _RSQB | postfix _DOT NAME: the lvalue's tail
        return lvalue_tail(primary())

    def primary() -> Any:
        nonlocal pos
        t = types[pos]
        if t == "NAME":
            t = types[pos + 1]
            if t == "_LPAR":
                return call(leaf())
            if t == "_COLON":
                pos += 1
                return library(toks[pos - 1], True)
            return leaf()
        tok = toks[pos]
        pos += 1
        if t == "NUMBER":
            return b_number([tok])
        if t == "STRING":
            return b_string([tok])
        if t == "_LPAR":
            node = expr()
            expect("_RPAR")
            return node
        if t == "SYSNAME":
            if types[pos] != "_LPAR":
                raise Fallback
            return call(b_sys_name([tok]))
        if t == "TRUE":
            return b_true([tok])
        if t == "FALSE":
            return b_false([tok])
        if t == "LBRACE":
            return struct(tok)
        raise Fallback

    def library(alias: tuple, value: bool) -> Any:
        """After `alias`, at `:`: `alias:name` (a value when `value`), `alias:name(...)` or
        `alias:$name(...)` (calls)."""
        nonlocal pos
        pos += 1
        t = types[pos]
        n = toks[pos]
        pos += 1
        if t == "NAME":
            node = b_lib_name([alias, n])
            if types[pos] == "_LPAR":
                return call(node)
            if value:
                return node
        elif t == "SYSNAME" and types[pos] == "_LPAR":
            return call(b_lib_name([alias, n]))
        raise Fallback

    def call(callee: Any) -> Any:
        # call: callee _LPAR [args] _RPAR (Builder.call)
        nonlocal pos
        pos += 1
        if types[pos] == "_RPAR":
            pos += 1
            return CallExpr(callee, [], callee.line, callee.col)
        node = CallExpr(callee, args(), callee.line, callee.col)
        if types[pos] != "_RPAR":
            raise Fallback
        pos += 1
        return node

    def args() -> list:
        # args: expr (_COMMA expr)*
        nonlocal pos
        out = [expr()]
        while types[pos] == "_COMMA":
            pos += 1
            out.append(expr())
        return out

    def struct(lbrace: tuple) -> Any:
        # struct: LBRACE [expr] (_COMMA [expr])* _RBRACE
        nonlocal pos
        fields: list = [lbrace, None if types[pos] in slot_end else expr()]
        while types[pos] == "_COMMA":
            pos += 1
            fields.append(None if types[pos] in slot_end else expr())
        expect("_RBRACE")
        return b.struct(fields)

    def prog_ref() -> Any:
        # prog_ref: NAME -> name | NAME _COLON NAME -> lib_name
        nonlocal pos
        tok = expect("NAME")
        if types[pos] == "_COLON":
            pos += 1
            return b_lib_name([tok, expect("NAME")])
        return b_name([tok])

    def call_args() -> list | None:
        # _LPAR [args] _RPAR after a program reference
        nonlocal pos
        expect("_LPAR")
        if types[pos] == "_RPAR":
            pos += 1
            return None
        out = args()
        expect("_RPAR")
        return out

    # ------------------------------------------------------------ statements

    def block() -> list:
        # block: (statement _NL)*
        nonlocal pos, depth
        out: list = []
        while True:
            t = types[pos]
            s = statements.get(t)
            if s is None:
                return out
            if t in openers:  # the engine counts the blocks opened (F104 past MAX_BLOCK_DEPTH)
                depth += 1
                if depth > MAX_BLOCK_DEPTH:
                    raise Fallback
                out.append(s(toks[pos]))
                depth -= 1
            else:
                out.append(s(toks[pos]))
            if types[pos] != "_NL":
                raise Fallback
            pos += 1

    def name_statement(tok: tuple) -> Any:
        # assign: lvalue EQUAL expr | expr_stmt: call
        nonlocal pos
        pos += 1
        t = types[pos]
        if t == "_LPAR":
            pos -= 1
            node = call(leaf())
            return ExprStatement(node, node.line, node.col)  # Builder.expr_stmt
        if t == "_COLON":
            t = types[pos + 1]
            n = toks[pos + 1]
            pos += 2
            if t == "SYSNAME" and types[pos] == "_LPAR":
                return b.expr_stmt([call(b_lib_name([tok, n]))])
            if t != "NAME":
                raise Fallback
            target = b_lib_name([tok, n])
            if types[pos] == "_LPAR":
                return b.expr_stmt([call(target)])
        else:
            k = tok[2] - 1
            if k in col_maps:
                target = b_name([tok])
            else:  # Builder.name
                v = tok[1]
                ln = lines[k]
                col = offs[k] + tok[3]
                target = Name(v, ln, col, ln, col + len(v))
        t = types[pos]
        if t == "_LSQB" or t == "_DOT":
            target = lvalue_tail(target)
        eq = toks[pos]
        if eq[0] != "EQUAL":
            raise Fallback
        pos += 1
        k = eq[2] - 1
        if k in col_maps:
            return b.assign([target, eq, expr()])
        return Assign(target, expr(), target.line, target.col, lines[k], offs[k] + eq[3])  # Builder.assign

    def lvalue_tail(target: Any) -> Any:
        # ?lvalue: ... | lvalue _LSQB args _RSQB -> index | lvalue _DOT NAME -> field (and postfix's)
        nonlocal pos
        while True:
            t = types[pos]
            if t == "_LSQB":
                pos += 1
                target = Index(target, args(), target.line, target.col)  # Builder.index
                expect("_RSQB")
            elif t == "_DOT":
                pos += 1
                target = b_field([target, expect("NAME")])
            else:
                return target

    def sys_statement(tok: tuple) -> Any:
        nonlocal pos
        pos += 1
        if types[pos] != "_LPAR":
            raise Fallback
        return b.expr_stmt([call(b_sys_name([tok]))])

    def call_statement(tok: tuple) -> Any:
        # call_stmt: CALL prog_ref _LPAR [args] _RPAR
        nonlocal pos
        pos += 1
        target = prog_ref()
        return b.call_stmt([tok, target, call_args()])

    def last_clause(keyword: str, make: Any) -> Any:
        # [else_clause] / [default_clause]: KEYWORD _NL block, or None when absent
        nonlocal pos
        if types[pos] != keyword:
            return None
        t = toks[pos]
        pos += 1
        expect("_NL")
        return make([t, block()])

    def if_statement(tok: tuple) -> Any:
        # if_stmt: IF expr _NL block elseif_clause* [else_clause] ENDIF
        nonlocal pos
        pos += 1
        c: list = [tok, expr()]
        expect("_NL")
        c.append(block())
        while types[pos] == "ELSEIF":
            t = toks[pos]
            pos += 1
            cond = expr()
            expect("_NL")
            c.append(b.elseif_clause([t, cond, block()]))
        c.append(last_clause("ELSE", b.else_clause))
        c.append(expect("ENDIF"))
        return b.if_stmt(c)

    def while_statement(tok: tuple) -> Any:
        # while_stmt: WHILE expr _NL block ENDWHILE
        nonlocal pos
        pos += 1
        cond = expr()
        expect("_NL")
        body = block()
        return b.while_stmt([tok, cond, body, expect("ENDWHILE")])

    def do_statement(tok: tuple) -> Any:
        # do_stmt: DO _NL block UNTIL expr
        nonlocal pos
        pos += 1
        expect("_NL")
        body = block()
        until = expect("UNTIL")
        return b.do_stmt([tok, body, until, expr()])

    def for_statement(tok: tuple) -> Any:
        # for_stmt: FOR for_header _NL block ENDFOR
        # for_header: lvalue EQUAL expr TO expr [STEP expr]
        nonlocal pos
        pos += 1
        n = expect("NAME")
        if types[pos] == "_COLON":
            pos += 1
            counter = b_lib_name([n, expect("NAME")])
        else:
            counter = b_name([n])
        counter = lvalue_tail(counter)
        eq = expect("EQUAL")
        start = expr()
        to = word("to")
        if to is None:
            raise Fallback
        stop = expr()
        step_tok = word("step")
        step = expr() if step_tok is not None else None
        header = b.for_header([counter, eq, start, to, stop, step_tok, step])
        expect("_NL")
        body = block()
        return b.for_stmt([tok, header, body, expect("ENDFOR")])

    def switch_statement(tok: tuple) -> Any:
        # switch_stmt: SWITCH expr _NL case_clause* [default_clause] ENDSWITCH
        # case_clause: CASE expr (_COMMA expr)* _NL block
        nonlocal pos
        pos += 1
        c: list = [tok, expr()]
        expect("_NL")
        while types[pos] == "CASE":
            case = [toks[pos]]
            pos += 1
            case.extend(args())
            expect("_NL")
            case.append(block())
            c.append(b.case_clause(case))
        c.append(last_clause("DEFAULT", b.default_clause))
        c.append(expect("ENDSWITCH"))
        return b.switch_stmt(c)

    def task_statement(tok: tuple) -> Any:
        # task_create: TASKCREATE expr _COMMA expr _COMMA prog_ref _LPAR [args] _RPAR
        # task_create_sync: TASKCREATESYNC expr _COMMA expr _COMMA expr _COMMA prog_ref ...
        nonlocal pos
        pos += 1
        c: list = [tok, expr()]
        expect("_COMMA")
        c.append(expr())
        expect("_COMMA")
        if tok[0] == "TASKCREATESYNC":
            c.append(expr())
            expect("_COMMA")
        c.append(prog_ref())
        c.append(call_args())
        return b.task_create(c) if tok[0] == "TASKCREATE" else b.task_create_sync(c)

    def print_statement(tok: tuple) -> Any:
        # print_stmt: QMARK args
        nonlocal pos
        pos += 1
        return b.print_stmt([tok, args()])

    def return_statement(tok: tuple) -> Any:
        nonlocal pos
        pos += 1
        return b.return_stmt([tok])

    def break_statement(tok: tuple) -> Any:
        nonlocal pos
        pos += 1
        return b.break_stmt([tok])

    statements = {
        "NAME": name_statement, "SYSNAME": sys_statement, "CALL": call_statement, "IF": if_statement,
        "WHILE": while_statement, "DO": do_statement, "FOR": for_statement, "SWITCH": switch_statement,
        "TASKCREATE": task_statement, "TASKCREATESYNC": task_statement, "QMARK": print_statement,
        "RETURN": return_statement, "BREAK": break_statement,
    }

    # start: _NL? BEGIN _NL block END _NL?
    if types[0] == "_NL":
        pos = 1
    begin = expect("BEGIN")
    expect("_NL")
    body = block()
    end = expect("END")
    if types[pos] == "_NL":
        pos += 1
    expect("$END")
    return b.start([begin, body, end])
