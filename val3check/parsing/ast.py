"""Typed syntax tree of a VAL 3 program body (manual s7 chapter 2.2.5, expressions of chapters 3-9).

Every node has `line` and `col`: 1-based, in the `.pgx` FILE (mapped through the program's
`SourceMap`), at the node's first character. For a binary operation or an assignment that is
the start of the left operand; `op_line`/`op_col` locate the operator. Parentheses do not make
nodes: `(a + b) * c` starts at `a`. Nodes that end with a keyword (`endIf`, `endFor`...) and
single-token leaves also have `end_line`/`end_col`: the position just after their last
character (exclusive end, like Python's `ast`).

Nodes are plain slotted dataclasses built once by the parser; treat them as read-only.
Lists hold nodes in source order. A body only exists for code without syntax errors
(`ErrorExpr`/`ErrorStatement` are used internally during error recovery and never appear in
a body returned by `parse_code`).
"""

from __future__ import annotations

from ..light_dataclass import dataclass, field

TYPE_CHECKING = False  # not typing's: importing typing costs 3 ms at lint's start-up
if TYPE_CHECKING:
    from typing import Union

# ---------------------------------------------------------------- expressions


@dataclass(slots=True)
class Number:
    """Numeric constant (3.2.1). `text` as written; a folded unary minus gives `-3` and the
    position of the `-`."""

    value: float
    text: str
    line: int
    col: int
    end_line: int
    end_col: int


@dataclass(slots=True)
class String:
    """String constant (3.4): `value` without the quotes (VAL 3 has no escapes)."""

    value: str
    line: int
    col: int
    end_line: int
    end_col: int


@dataclass(slots=True)
class Bool:
    """`true` / `false` (3.1.1), any case."""

    value: bool
    line: int
    col: int
    end_line: int
    end_col: int


@dataclass(slots=True)
class Name:
    """A variable, constant (`flange`, `world`, `sfree`...), instruction or program name."""

    name: str
    line: int
    col: int
    end_line: int
    end_col: int


@dataclass(slots=True)
class LibraryName:
    """`alias:name`: data or program of a library (chapter 6)."""

    alias: str
    name: str
    line: int
    col: int
    end_line: int
    end_col: int


@dataclass(slots=True)
class SystemName:
    """An undocumented system instruction, `name` includes the `$` (`$movejSyncState`)."""

    name: str
    line: int
    col: int
    end_line: int
    end_col: int


@dataclass(slots=True)
class Index:
    """`base[i]`, `base[i, j]`, `base[i, j, k]`, `coll["key"]` (2.5.3)."""

    base: "Expr"
    indices: list["Expr"]
    line: int
    col: int


@dataclass(slots=True)
class Field:
    """`base.name` (2.5.3), e.g. `p.trsf.x`; `name_line`/`name_col` locate the field name."""

    base: "Expr"
    name: str
    line: int
    col: int
    name_line: int
    name_col: int


@dataclass(slots=True)
class CallExpr:
    """A function or instruction call: `sin(x)`, `lib:libLoad(s)`, `$system(1)`."""

    func: Union[Name, LibraryName, SystemName]
    args: list["Expr"]
    line: int
    col: int


@dataclass(slots=True)
class Unary:
    """`-x` (3.2.2) or `!x` (3.1.2 negation, 9.3.3 trsf inverse). Position of the operator."""

    op: str
    operand: "Expr"
    line: int
    col: int


@dataclass(slots=True)
class Binary:
    """`left op right`; `op` is one of: or and xor == != < > <= >= + - * / %
    (`and`/`or`/`xor` in lower case whatever the spelling)."""

    op: str
    left: "Expr"
    right: "Expr"
    line: int
    col: int
    op_line: int
    op_col: int


@dataclass(slots=True)
class Struct:
    """Structured value `{...}` (2.4.2); an empty field (`{100, -50, 200,,}`) is None.
    `{}` has no fields."""

    fields: list[Union["Expr", None]]
    line: int
    col: int


@dataclass(slots=True)
class AssignExpr:
    """`target = value` used inside an expression: `if(b1=b2)`, `cos(n=30)`, `x = y = 0`.

    Syntactically valid (the `=` operator, lowest precedence, 3.1.2) but forbidden in
    instruction parameters and conditions (3.1.2, 3.2.2, 3.4.2): a later rule reports it.
    `op_line`/`op_col` locate the `=`.
    """

    target: "Expr"
    value: "Expr"
    line: int
    col: int
    op_line: int
    op_col: int


@dataclass(slots=True)
class ErrorExpr:
    """Placeholder for a broken expression during error recovery (never in a returned body)."""

    line: int
    col: int


Expr = (
    Number | String | Bool | Name | LibraryName | SystemName | Index | Field | CallExpr | Unary | Binary
    | Struct | AssignExpr | ErrorExpr
)

# ---------------------------------------------------------------- statements


@dataclass(slots=True)
class Assign:
    """`target = value`; target is a Name, LibraryName, Index or Field (2.5.3).
    `op_line`/`op_col` locate the `=`."""

    target: Expr
    value: Expr
    line: int
    col: int
    op_line: int
    op_col: int


@dataclass(slots=True)
class ExprStatement:
    """An instruction call used as a statement: `movej(j, flange, m)`."""

    call: CallExpr
    line: int
    col: int


@dataclass(slots=True)
class Call:
    """`call prog(args)` / `call alias:prog(args)` (2.2.5). Position of the `call` keyword."""

    target: Union[Name, LibraryName]
    args: list[Expr]
    line: int
    col: int


@dataclass(slots=True)
class TaskCreate:
    """`taskCreate task, priority, prog(args)` (5.10): runs `prog(args)` in a new task."""

    task: Expr
    priority: Expr
    target: Union[Name, LibraryName]
    args: list[Expr]
    line: int
    col: int


@dataclass(slots=True)
class TaskCreateSync:
    """`taskCreateSync task, period, bOverrun, prog(args)` (5.10): a synchronous task."""

    task: Expr
    period: Expr
    overrun: Expr
    target: Union[Name, LibraryName]
    args: list[Expr]
    line: int
    col: int


@dataclass(slots=True)
class Print:
    """`? expr` (or `? a, b`): the s8 print statement (not in the s7 manual), shows the values.
    Position of the `?`."""

    values: list[Expr]
    line: int
    col: int


@dataclass(slots=True)
class Return:
    """`return` (2.2.5)."""

    line: int
    col: int


@dataclass(slots=True)
class Break:
    """`break` (2.2.5 switch). Parsed anywhere; only meaningful as a statement of a case."""

    line: int
    col: int


@dataclass(slots=True)
class Branch:
    """One `if cond` or `elseIf cond` and its statements; position of the keyword."""

    cond: Expr
    body: list["Statement"]
    line: int
    col: int


@dataclass(slots=True)
class If:
    """`if`/`elseIf`/`else`/`endIf` (2.2.5). `branches[0]` is the `if`; `orelse` is None when
    there is no `else` (else_line/else_col then 0). end_* = end of `endIf`."""

    branches: list[Branch]
    orelse: list["Statement"] | None
    line: int
    col: int
    else_line: int
    else_col: int
    end_line: int
    end_col: int


@dataclass(slots=True)
class While:
    """`while cond` ... `endWhile` (2.2.5). end_* = end of `endWhile`."""

    cond: Expr
    body: list["Statement"]
    line: int
    col: int
    end_line: int
    end_col: int


@dataclass(slots=True)
class DoUntil:
    """`do` ... `until cond` (2.2.5). `until_line`/`until_col` locate `until`."""

    body: list["Statement"]
    cond: Expr
    line: int
    col: int
    until_line: int
    until_col: int


@dataclass(slots=True)
class For:
    """`for counter = start to stop [step step]` ... `endFor` (2.2.5). The counter may be a
    name, an element or a field. `step` is None when omitted (1). end_* = end of `endFor`."""

    counter: Expr
    start: Expr
    stop: Expr
    step: Expr | None
    body: list["Statement"]
    line: int
    col: int
    end_line: int
    end_col: int


@dataclass(slots=True)
class Case:
    """`case v1, v2` and its statements, `break` statements included (2.2.5 switch)."""

    values: list[Expr]
    body: list["Statement"]
    line: int
    col: int

    @property
    def has_break(self) -> bool:
        """True when a `break` is one of the case's own statements (not nested in a block)."""
        return any(type(s) is Break for s in self.body)


@dataclass(slots=True)
class Default:
    """`default` and its statements (2.2.5 switch)."""

    body: list["Statement"]
    line: int
    col: int

    @property
    def has_break(self) -> bool:
        return any(type(s) is Break for s in self.body)


@dataclass(slots=True)
class Switch:
    """`switch subject` / `case` ... / `default` / `endSwitch` (2.2.5). end_* = end of
    `endSwitch`."""

    subject: Expr
    cases: list[Case]
    default: Default | None
    line: int
    col: int
    end_line: int
    end_col: int


@dataclass(slots=True)
class ErrorStatement:
    """Placeholder for a broken line during error recovery (never in a returned body)."""

    line: int
    col: int


Statement = (
    Assign | ExprStatement | Call | TaskCreate | TaskCreateSync | Print | Return | Break | If | While | DoUntil
    | For | Switch | ErrorStatement
)

# ---------------------------------------------------------------- program


@dataclass(slots=True)
class Comment:
    """A `//` comment (2.2.5). `text` is the whole comment from `//` to the end of the line
    (without the line end). `starts_line` is False when code precedes it on its line."""

    text: str
    line: int
    col: int
    starts_line: bool


@dataclass(slots=True)
class ProgramBody:
    """`begin` ... `end`: position of `begin`; end_* = end of `end`. `comments` lists every
    comment of the code, in order, including those before `begin` and after `end`."""

    statements: list[Statement]
    comments: list[Comment] = field(default_factory=list)
    line: int = 1
    col: int = 1
    end_line: int = 1
    end_col: int = 1


# Child fields of each node class, in source order (used by `walk`).
_CHILDREN: dict[type, tuple[str, ...]] = {
    Number: (), String: (), Bool: (), Name: (), LibraryName: (), SystemName: (), ErrorExpr: (),
    Index: ("base", "indices"),
    Field: ("base",),
    CallExpr: ("func", "args"),
    Unary: ("operand",),
    Binary: ("left", "right"),
    Struct: ("fields",),
    AssignExpr: ("target", "value"),
    Assign: ("target", "value"),
    ExprStatement: ("call",),
    Call: ("target", "args"),
    TaskCreate: ("task", "priority", "target", "args"),
    TaskCreateSync: ("task", "period", "overrun", "target", "args"),
    Print: ("values",),
    Return: (), Break: (), ErrorStatement: (),
    Branch: ("cond", "body"),
    If: ("branches", "orelse"),
    While: ("cond", "body"),
    DoUntil: ("body", "cond"),
    For: ("counter", "start", "stop", "step", "body"),
    Case: ("values", "body"),
    Default: ("body",),
    Switch: ("subject", "cases", "default"),
    ProgramBody: ("statements",),
}


def children(node: object) -> list:
    """The direct child nodes of `node`, in source order (None fields skipped)."""
    out: list = []
    for name in _CHILDREN.get(type(node), ()):
        value = getattr(node, name)
        if value is None:
            continue
        if type(value) is list:
            out.extend(v for v in value if v is not None)
        else:
            out.append(value)
    return out


def last_child(node: object) -> object | None:
    """`children(node)[-1]` (None when there is none), without making the list: finding the
    end of a subtree (semantics.program_nodes) steps down the last children only."""
    for name in reversed(_CHILDREN.get(type(node), ())):
        value = getattr(node, name)
        if value is None:
            continue
        if type(value) is list:
            for v in reversed(value):
                if v is not None:
                    return v
        else:
            return value
    return None


def _pusher(cls: type, fields: tuple[str, ...]):
    """A function that pushes the children of a `cls` node on a stack, last child first (so
    that popping gives them in source order). Generated once per class: `walk` is the hot loop
    of the pattern rules. Only Struct.fields (empty fields) and If.orelse/For.step/Switch.default
    (absent parts) may hold None."""
    lines = ["def push(n, append, extend):"]
    for name in reversed(fields):
        kind = _FIELD_KINDS.get((cls, name), "node")
        if kind == "list":
            lines.append(f"    extend(n.{name}[::-1])")
        elif kind == "holes":
            lines.append(f"    extend([x for x in n.{name}[::-1] if x is not None])")
        elif kind == "optional":
            lines.append(f"    v = n.{name}")
            lines.append("    if v is not None:")
            lines.append("        extend(v[::-1]) if v.__class__ is list else append(v)")
        else:
            lines.append(f"    append(n.{name})")
    if not fields:
        lines.append("    pass")
    scope: dict = {}
    exec("\n".join(lines), scope)  # noqa: S102 - code built from this module's own field names
    return scope["push"]


# How each child field holds its nodes: "list" (never None inside), "holes" (a list that may
# hold None: the empty fields of a structured value), "optional" (None, a node or a list);
# every other field holds one node.
_FIELD_KINDS = {
    (Index, "indices"): "list", (CallExpr, "args"): "list", (Struct, "fields"): "holes",
    (Call, "args"): "list", (TaskCreate, "args"): "list", (TaskCreateSync, "args"): "list", (Print, "values"): "list",
    (Branch, "body"): "list", (If, "branches"): "list", (If, "orelse"): "optional", (While, "body"): "list",
    (DoUntil, "body"): "list", (For, "step"): "optional", (For, "body"): "list", (Case, "values"): "list",
    (Case, "body"): "list", (Default, "body"): "list", (Switch, "cases"): "list", (Switch, "default"): "optional",
    (ProgramBody, "statements"): "list",
}
_PUSH = {cls: _pusher(cls, fields) for cls, fields in _CHILDREN.items() if fields}


def nodes(node: object) -> list:
    """Every node under `node` (itself included), depth first, in source order, as a list.
    Iterative: safe on any depth."""
    out = [node]
    stack: list = []
    append, extend, pop, add = stack.append, stack.extend, stack.pop, out.append
    push = _PUSH
    f = push.get(node.__class__)
    if f is not None:
        f(node, append, extend)
    while stack:
        n = pop()
        add(n)
        f = push.get(n.__class__)
        if f is not None:
            f(n, append, extend)
    return out


def walk(node: object):
    """Every node under `node` (itself included), depth first, in source order."""
    return iter(nodes(node))
