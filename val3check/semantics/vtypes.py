"""VAL 3 types and containers as the checker sees them (manual 2.3, chapters 3, 9, 10).

A `VType` is one type: a built-in one (`num`, `point`...: one shared object each, compared by
identity), a field value set (`shoulder`, `blend`...: the "enum" types of types.toml), a user
type (chapter 7: one object per type application, compared by identity), or `UNKNOWN`. UNKNOWN
stands for anything the checker cannot know (an undefined name, a type whose application was
not found, the result of a `$system()` call): every check accepts it, so that one root cause
gives one diagnostic and no cascade.

A `Val` is the result of typing an expression: its type, the container it designates (an
element, an array of 1-3 dimensions, a collection) and whether it names a variable (so that it
can be assigned or passed by reference, manual 2.6).

Arm-family spellings (`pointRx`, `jointRs`...) are the same types as `point`, `joint` (the
family is a property of declarations, checked elsewhere).
"""

from __future__ import annotations

from functools import cache

from ..language import types as lt
from ..loading.types import arm_family, base_type

TYPE_CHECKING = False  # not typing's: importing typing costs 3 ms at lint's start-up
if TYPE_CHECKING:  # pragma: no cover
    from typing import Any

    from ..loading.model import Application

# Type kinds.
BUILTIN = "builtin"
ENUM = "enum"
USER = "user"
UNKNOWN_KIND = "unknown"
VOID_KIND = "void"
LITERAL = "literal"  # a `{...}` value whose type comes from where it is used (2.4.2)


class VType:
    """One VAL 3 type. Built-in and user types are unique objects: compare with `is`."""

    __slots__ = ("_fields", "app", "key", "kind", "name", "structured")

    def __init__(self, name: str, kind: str, key: str | None = None, app: Application | None = None) -> None:
        self.name = name
        self.kind = kind
        self.key = key  # user types: the absolute path of the type's application
        self.app = app  # user types: the type's application
        self.structured = False
        self._fields: Any = None  # user types: filled lazily by symbols.user_fields

    @property
    def known(self) -> bool:
        return self.kind is not UNKNOWN_KIND

    def __repr__(self) -> str:
        return f"VType({self.name})"


UNKNOWN = VType("?", UNKNOWN_KIND)
VOID = VType("void", VOID_KIND)
STRUCT_LITERAL = VType("{...}", LITERAL)

# Built-in types (2.3.2, 2.3.3) and the value sets of fields (9.7.2, 10.5.1), from types.toml.
BUILTINS: dict[str, VType] = {}
for _name, _bt in lt.load_types().items():
    if _bt.kind in ("simple", "structured"):
        _t = VType(_name, BUILTIN)
        _t.structured = _bt.kind == "structured"
        BUILTINS[_name] = _t
    elif _bt.kind == "enum":
        BUILTINS[_name] = VType(_name, ENUM)

NUM = BUILTINS["num"]
BOOL = BUILTINS["bool"]
STRING = BUILTINS["string"]
DIO = BUILTINS["dio"]
AIO = BUILTINS["aio"]
SIO = BUILTINS["sio"]
SCREEN = BUILTINS["screen"]
TRSF = BUILTINS["trsf"]
FRAME = BUILTINS["frame"]
TOOL = BUILTINS["tool"]
POINT = BUILTINS["point"]
JOINT = BUILTINS["joint"]
CONFIG = BUILTINS["config"]
MDESC = BUILTINS["mdesc"]

# I/O link types: the manual gives them few operators and older VAL 3 versions more; a value
# check involving them is only reported when it cannot be right (see `assignable`).
IO_TYPES = frozenset({DIO, AIO, SIO, SCREEN})


def builtin(name: str) -> VType | None:
    """The built-in type of a name as written in files or the catalogue (`pointRx` -> point)."""
    t = BUILTINS.get(name)
    if t is not None:
        return t
    return BUILTINS.get(base_type(name))


def family_of(type_name: str) -> str | None:
    """ "Rx" / "Rs" for arm-family spellings, else None (manual 9.7.2, SRS files)."""
    return arm_family(type_name)


# ---------------------------------------------------------------------------------------------
# Containers


ELEMENT = 0
ARRAY = 1
COLLECTION = 2
CONTAINER_WORDS = ("element", "array", "collection")


class Val:
    """The result of typing an expression.

    t       its type
    c       ELEMENT, ARRAY or COLLECTION: what the expression designates as written
    dims    1-3 for arrays
    elem    may it be used where one value is expected: True; False when it certainly cannot
            (a collection, a 2-D/3-D array, a 1-D array declared with several values); None when
            unknown (a 1-D array parameter: its size is the caller's)
    var     it names a variable (assignable, passable by reference): a variable, an element of
            it, a field of it, a library's data
    root    the Symbol of the variable it starts from (None for values)
    start   `a[i]` on a 1-D array: may also stand for "the array from index i" (2.6.3)
    indexed one value taken out of a container with [] (`a[i, j]`, `c["k"]`)
    field   reached through a field (`u.tab`): not the root variable's own container
    """

    __slots__ = ("c", "dims", "elem", "field", "indexed", "root", "start", "t", "var")

    def __init__(self, t: VType, c: int = ELEMENT, dims: int = 0, elem: bool | None = True, var: bool = False,
                 root: Any = None, start: bool = False, indexed: bool = False, field: bool = False) -> None:
        self.t = t
        self.c = c
        self.dims = dims
        self.elem = elem
        self.var = var
        self.root = root
        self.start = start
        self.indexed = indexed
        self.field = field

    def __repr__(self) -> str:
        return f"Val({self.t.name}, {CONTAINER_WORDS[self.c]}{self.dims or ''}, var={self.var})"


def value(t: VType) -> Val:
    """An element value that is not a variable (a constant, a result)."""
    return _VALUES.get(t) or Val(t)


_VALUES: dict[VType, Val] = {t: Val(t) for t in (*BUILTINS.values(), UNKNOWN, VOID, STRUCT_LITERAL)}
UNKNOWN_VAL = _VALUES[UNKNOWN]


def describe(v: Val) -> str:
    """`num`, `num array`, `num 2-D array`, `string collection`, `element of a num 2-D array`:
    for messages. A 1-D array with one value is an element (2.3.4)."""
    if v.c == ARRAY and v.elem is True and v.dims <= 1:
        return v.t.name
    if v.indexed == 2 and v.dims > 1:
        return f"element of a {v.t.name} {v.dims}-D array"
    if v.indexed == 3:
        return f"element of a {v.t.name} collection"
    if v.c == ARRAY:
        return f"{v.t.name} array" if v.dims <= 1 else f"{v.t.name} {v.dims}-D array"
    if v.c == COLLECTION:
        return f"{v.t.name} collection"
    return v.t.name


# ---------------------------------------------------------------------------------------------
# Operators (types.toml [[operators]], chapters 3, 9 and 10)


@cache
def _operator_table() -> dict[tuple, VType]:
    out: dict[tuple, VType] = {}
    for o in lt.load_operators():
        res = BUILTINS.get(o.result, UNKNOWN)
        out[(o.op, *o.operands)] = res
    return out


def binary_result(op: str, left: VType, right: VType) -> VType | None:
    """The result type of `left op right`, or None when the manual defines no such operator."""
    return _operator_table().get((op, left.name, right.name))


def unary_result(op: str, operand: VType) -> VType | None:
    """`-x` ("neg") and `!x`; None when undefined."""
    return _operator_table().get(("neg" if op == "-" else op, operand.name))


def comparable(left: VType, right: VType) -> bool | None:
    """Whether `==` is defined between the two types (True), certainly not (False), or the
    manual does not say (None: value sets, I/O links with bool)."""
    if not left.known or not right.known:
        return None
    if binary_result("==", left, right) is not None:
        return True
    if left.kind == ENUM or right.kind == ENUM:
        return None
    if left in IO_TYPES or right in IO_TYPES:
        if {left, right} <= {DIO, BOOL}:
            return True
        # An input read as a number or a bool: older versions accept more than s7 lists.
        return None if {left, right} <= _IO_SCALARS else False
    return False


def assignable(target: VType, val: VType) -> bool | None:
    """Whether a value of type `val` can be stored in a variable of type `target` (the `=`
    operators of chapters 3, 9, 10 and 7.3), and so passed by value to a parameter.

    True: yes; False: certainly not; None: the manual does not say (I/O link types and value
    sets in combinations the manual does not list): no error.
    """
    if target is val:
        return True
    if not target.known or not val.known:
        return None
    if val.kind == LITERAL:
        return target.structured or None
    if target.kind == USER or val.kind == USER:
        # 7.3: '=' between two variables of the same user type only. Two applications may
        # declare the same type name with their own paths: not reported.
        if target.kind == val.kind and target.name.lower() == val.name.lower():
            return None
        return False
    if binary_result("=", target, val) is not None:
        return True
    if target.kind == ENUM or val.kind == ENUM:
        return None
    if target in IO_TYPES or val in IO_TYPES:
        # Reading an input as a bool/num (older versions accept it), aio/sio/screen links: the
        # s7 manual lists few operators; only pairs that cannot make sense are refused.
        if {target, val} <= _IO_SCALARS or (target, val) in _IO_LENIENT:
            return None
        return False
    return False


_IO_SCALARS = frozenset({DIO, AIO, BOOL, NUM})
_IO_LENIENT = frozenset({(SIO, SIO), (SCREEN, SCREEN)})


def same_type(a: VType, b: VType) -> bool:
    """For variables passed by reference: the same type, or one that cannot be told apart (an
    unknown type, a user type of the same name declared through another path)."""
    if a is b or not a.known or not b.known:
        return True
    return a.kind == USER and b.kind == USER and a.name.lower() == b.name.lower()


def condition_ok(t: VType) -> bool:
    """A condition of if/elseIf/while/until/wait (2.2.5): a bool (a dio reads as its state)."""
    return t is BOOL or t is DIO or not t.known


def is_num_like(t: VType) -> bool:
    return t is NUM or t is AIO or not t.known


# ---------------------------------------------------------------------------------------------
# Built-in structured types: fields (types.toml) and literals (2.4.2)


@cache
def builtin_fields(type_name: str) -> dict[str, tuple[str, VType]]:
    """Field name (and file alias) -> (canonical field name, field type)."""
    bt = lt.load_types().get(type_name)
    out: dict[str, tuple[str, VType]] = {}
    if bt is None:
        return out
    for f in bt.fields:
        ft = BUILTINS.get(f.type, UNKNOWN)
        out[f.name] = (f.name, ft)
        for a in f.aliases:
            out.setdefault(a, (f.name, ft))
    return out


def field_of(t: VType, name: str) -> tuple[str, VType, bool] | None:
    """(canonical name, type, exact spelling) of a field of a built-in structured type; None
    when the type has no such field. `joint` has one field per axis (9.2.1): `j1`..`j9`."""
    fields = builtin_fields(t.name)
    hit = fields.get(name)
    if hit is not None:
        return hit[0], hit[1], True
    if t is JOINT and len(name) == 2 and name[0] in "jJ" and name[1] in "123456789":
        return name, NUM, name[0] == "j"
    low = name.lower()
    for k, (canon, ft) in fields.items():
        if k.lower() == low:
            return canon, ft, False
    return None


def literal_arity(t: VType) -> tuple[int, int] | None:
    """(min, max) number of fields of a `{...}` value of built-in type `t` (2.4.2), or None
    when not checked. Fewer fields are allowed: 2.4.2 writes `pPosition.trsf = {100, -50,
    200,,}` (5 entries for 6 fields; missing and empty fields are 0). joint has one field per
    axis (9.2.1: extra axes add fields)."""
    if t is JOINT:
        return None
    n = len(lt.load_types()[t.name].fields) if t.structured else 0
    return (0, n) if n else None


def literal_field_types(t: VType) -> list[VType]:
    bt = lt.load_types().get(t.name)
    if bt is None:
        return []
    if t is JOINT:
        return [NUM] * 9
    return [BUILTINS.get(f.type, UNKNOWN) for f in bt.fields]


# ---------------------------------------------------------------------------------------------
# Constants (types.toml [constants])


@cache
def constants() -> dict[str, VType]:
    """Named constants keyed by lower-case name: true/false, world, flange, the configuration
    values, the blend values (case-insensitive like keywords)."""
    return {name.lower(): BUILTINS.get(c.type, UNKNOWN) for name, c in lt.load_constants().items()}


# `world` and `flange` are variables in s6 data files and always-defined references in s7:
# passing them by reference is not reported.
CONSTANT_VARIABLES = frozenset({"world", "flange"})
