"""Run-time values of the virtual controller.

Representation (chosen for speed of the generated code, see `compiler/`):

- `num` is a Python float, `bool` a bool, `string` a str (at most 128 UTF-8 bytes, 3.4.1);
- the geometry of chapter 9 uses the types of `val3check.geometry` (its docstring): a `trsf` is
  a `Trsf` (mutable, fields x..rz); a `frame`/`tool` is a `Frame`/`Tool` *node* whose `ref` is
  its reference node (shared: a variable holds one node for its whole life, `=` copies INTO it,
  `ch09_geometry.NASG`); a `point` is a `Point` (trsf, ref) whose `config` is the dict below.
  Globals are linked to their data file's `fatherId` (world/flange by default), locals and
  user-type fields have no reference (9.4.1, 9.5.1, 9.6.1). Their fields are read as
  attributes (`p.trsf.x`) and written by name (`p["trsf"]`, the geometry classes' item access);
- the other built-in structured values (2.3.3) are plain dicts of their fields: a `joint`
  ``{j1..j6}``, a `config` ``{shoulder, elbow, wrist}``, an mdesc ``{accel, vel, decel, tvel, rvel,
  blend, leave, reach}``; enum fields (`sfree`, `joint`...) are strings.
  `chapters/ch09_geometry.py` converts joint and config dicts to the geometry's tuples at the
  instruction boundary;
- a user-type value (chapter 7) is a dict of field name -> container, since every field of a
  user type has its own container (7.1);
- `dio`/`aio`/`sio` values are links (3.5.1): the variable holds the `IOPoint` object of the
  physical input/output, shared by every variable linked to it; `screen` values are `Screen`s;
- containers (2.3.4): `Arr` for arrays of 1 to 3 dimensions (a global "element" is an array
  of size 1), `Coll` for collections (keys iterated in alphabetical = code point order, 2.5.6).
"""

from __future__ import annotations

from typing import Any

from ..geometry.frames import Frame, Tool, copy_node
from ..geometry.points import Point
from ..geometry.trsf import Trsf
from ..language.runtime_errors import Val3RuntimeError
from ..language.types import load_families, load_types
from ..loading.types import base_type

MAX_CONTAINER = 9999  # 2.5.4: insert/append/resize limit a variable to 9999 values
MAX_STRING_BYTES = 128  # 3.4.1

# The built-in structured types and the value sets of their fields, from language/types.toml
# (the one source of the type facts).
STRUCT_FIELDS: dict[str, dict[str, str]] = {
    name: {f.name: f.type for f in bt.fields} for name, bt in load_types().items() if bt.kind == "structured"}
# Literal order of the fields ({a, b, ...} initialisers, 2.4.2).
STRUCT_ORDER: dict[str, tuple[str, ...]] = {t: tuple(f) for t, f in STRUCT_FIELDS.items()}
# A field's name or a spelling of data files (mdesc `tmax` for `tvel`) -> the field's name.
FIELD_NAMES: dict[str, dict[str, str]] = {
    name: {**{a: f.name for f in bt.fields for a in f.aliases}, **{f.name: f.name for f in bt.fields}}
    for name, bt in load_types().items() if bt.kind == "structured"}
# The value a field of a new variable takes (numbers, enum values, a dio's link name).
FIELD_DEFAULTS: dict[str, dict[str, Any]] = {
    name: {f.name: f.default for f in bt.fields if f.default is not None}
    for name, bt in load_types().items() if bt.kind == "structured"}
JOINT_FIELDS = tuple(STRUCT_FIELDS["joint"])
# The fields of joint and config values on each arm family (types.toml [families]: RX/TX arms
# j1..j6 and shoulder, elbow, wrist; RS/TS arms j1..j4 and shoulder, 9.7.2).
FAMILY_FIELDS: dict[str, dict[str, tuple[str, ...]]] = {
    name: {"joint": fam.joint_fields, "config": fam.config_fields} for name, fam in load_families().items()}
ENUMS: dict[str, tuple[str, ...]] = {name: bt.values for name, bt in load_types().items() if bt.kind == "enum"}
ENUM_CONSTANTS: dict[str, str] = {v.lower(): t for t, vs in ENUMS.items() for v in vs}
ENUM_SPELLING: dict[str, str] = {v.lower(): v for vs in ENUMS.values() for v in vs}
# VAL 3 types whose values are geometry objects (fields read as attributes)
OBJECT_TYPES = frozenset({"trsf", "frame", "tool", "point"})
# ... and those whose variables keep their identity (`=` copies into them)
NODE_TYPES = frozenset({"frame", "tool", "point"})


def clip_string(s: str) -> str:
    """3.4.1/3.4.2: a string holds at most 128 bytes of UTF-8 (cut on a character boundary)."""
    if len(s) <= 32:
        return s
    b = s.encode("utf-8")
    if len(b) <= MAX_STRING_BYTES:
        return s
    return b[:MAX_STRING_BYTES].decode("utf-8", "ignore")


class IOPoint:
    """A physical input/output of the simulated cell (3.5-3.7), identified by its link.

    `kind` is "dio", "aio" or "sio". `value` is a bool (dio) or a float (aio). `driven` is True
    when the scenario drives it (an input): writing it is error 122. For sio: `rx` holds the
    bytes received and not read yet, `tx` what the program sent; `eos` is the end-of-string
    character (sioCtrl "endOfString"), `timeout` the communication timeout (0 = none).
    """

    __slots__ = ("kind", "link", "value", "driven", "rx", "tx", "eos", "timeout", "closed", "params", "status",
                 "description", "integer")

    def __init__(self, kind: str, link: str) -> None:
        self.kind = kind
        self.link = link
        self.value: Any = False if kind == "dio" else 0.0
        self.driven = False
        self.rx: bytearray = bytearray()
        self.tx: bytearray = bytearray()
        self.eos = 13
        self.timeout = 0.0
        self.closed = False
        self.params: dict[str, Any] = {}
        self.status = 0  # ioStatus() of a linked one (3.5.3), from the scenario's [io] table
        self.description = ""
        self.integer = False  # an integer analog output: aioSet() rounds (3.6.2)

    @property
    def linked(self) -> bool:
        return bool(self.link)

    def __repr__(self) -> str:  # pragma: no cover - debugging aid
        return f"IOPoint({self.kind}, {self.link!r})"


class FaultyIOPoint(IOPoint):
    """An input/output that does not work (ioStatus -2: not installed, -3: device in error,
    3.5.3): the scenario's [io] table turns an `IOPoint` into this class, so that the fast
    `type(io) is IOPoint` test of the generated code sends every use of it to the slow path,
    which raises the runtime error (123 / 125)."""

    __slots__ = ()


def is_io(v: Any) -> bool:
    return type(v) is IOPoint or type(v) is FaultyIOPoint


class Screen:
    """A user page of the pendant (chapter 4): 14 lines of 40 columns and a title."""

    __slots__ = ("name", "lines", "x", "y", "title", "mode")

    ROWS, COLS = 14, 40

    def __init__(self, name: str = "") -> None:
        self.name = name
        self.lines = [[" "] * self.COLS for _ in range(self.ROWS)]
        self.x = 0
        self.y = 0
        self.title = ""
        self.mode = 0

    def cls(self) -> None:
        self.lines = [[" "] * self.COLS for _ in range(self.ROWS)]
        self.x = self.y = 0

    def _newline(self) -> None:
        self.x = 0
        self.y += 1
        if self.y >= self.ROWS:  # 4.3 put: at the end of the page the page scrolls up one line
            self.lines.pop(0)
            self.lines.append([" "] * self.COLS)
            self.y = self.ROWS - 1

    def write(self, text: str, newline: bool) -> None:
        for ch in text:
            if ch == "\n":
                self._newline()
                continue
            if self.x >= self.COLS:  # 4.3: at the end of a line the display goes on with the next
                self._newline()  # (when the next character comes: a full last line does not scroll)
            self.lines[self.y][self.x] = ch
            self.x += 1
        if newline:
            self._newline()

    def text(self) -> list[str]:
        return ["".join(row).rstrip() for row in self.lines]


class Arr:
    """An array (2.3.4). 1-D arrays keep their values in `data`; `off` > 0 for the part of an
    array passed from an index (2.6.3: `call f(a[23])` gives f the values from index 23 on).
    2-D/3-D arrays keep a flat row-major `data` and their sizes in `dims`.
    `local` arrays cannot change size (insert/delete/append/resize, 2.5.4-2.5.5)."""

    __slots__ = ("t", "data", "dims", "off", "local")

    def __init__(self, t: str, data: list, dims: tuple[int, ...] | None = None, off: int = 0, local: bool = False) -> None:
        self.t = t
        self.data = data
        self.dims = dims if dims is not None and len(dims) > 1 else None
        self.off = off
        self.local = local

    @property
    def ndim(self) -> int:
        return len(self.dims) if self.dims else 1

    def size(self) -> int:
        return len(self.data) - self.off

    def view(self, index: int) -> "Arr":
        return Arr(self.t, self.data, None, self.off + index, self.local)

    def fill_strings(self, items: list[str]) -> int:
        """Write `items` from the start of a 1-D string array, clearing the rest; a global
        array grows as needed (libList 6.7, ioBusStatus 8.1). Returns the room written to."""
        for i in range(self.off, len(self.data)):
            self.data[i] = ""
        room = self.size()
        if len(items) > room and not self.local and self.dims is None:
            self.data.extend("" for _ in range(len(items) - room))
            room = self.size()
        for i, text in enumerate(items[:room]):
            self.data[self.off + i] = text
        return room


class CellList:
    """The values list of a one-value array that aliases one element of another container: an
    element passed by reference (2.6.2) and handed on to an array parameter (2.6.3) keeps
    its reference semantics, so the callee's writes reach the caller's variable."""

    __slots__ = ("c", "k")

    def __init__(self, c: Any, k: Any) -> None:
        self.c = c
        self.k = k

    def __len__(self) -> int:
        return 1

    def __getitem__(self, i: Any) -> Any:
        if type(i) is slice:
            return [self.c[self.k]][i]
        if i != 0 and i != -1:
            raise IndexError(i)
        return self.c[self.k]

    def __setitem__(self, i: Any, v: Any) -> None:
        if type(i) is slice:
            vals = [self.c[self.k]]
            vals[i] = v
            if len(vals) != 1:
                raise Val3RuntimeError(70, "an element passed as an array keeps one value")
            self.c[self.k] = vals[0]
            return
        if i != 0 and i != -1:
            raise IndexError(i)
        self.c[self.k] = v

    def __iter__(self):
        yield self.c[self.k]


class Coll:
    """A collection (2.3.4): values identified by a non-empty string key. `local` for a local
    variable's (its new values are local: no reference frame, 9.4.1)."""

    __slots__ = ("t", "d", "local")

    def __init__(self, t: str, d: dict | None = None, local: bool = False) -> None:
        self.t = t
        self.d = d if d is not None else {}
        self.local = local

    def keys(self) -> list[str]:
        return sorted(self.d)


def copy_point(p: Point, local: bool | None = None) -> Point:
    """A new point equal to `p` (same reference frame, config dict copied)."""
    q = Point(p.trsf.copy(), (), p.ref, local=p.local if local is None else local)
    c = p.config
    q.config = dict(c) if type(c) is dict else c
    return q


def copy_value(v: Any) -> Any:
    """Deep copy for `=` (7.3: after `=` the left variable is a copy of the right one). A frame
    or tool node copy keeps the same reference node (9.4.3)."""
    tv = type(v)
    if tv is float or tv is bool or tv is str:
        return v
    if tv is dict:
        return {k: copy_value(x) for k, x in v.items()}
    if tv is Trsf:
        return v.copy()
    if tv is Point:
        return copy_point(v)
    if tv is Frame or tv is Tool:
        return copy_node(v)
    if tv is Arr:
        return Arr(v.t, [copy_value(x) for x in v.data[v.off:]], v.dims, 0, v.local)
    if tv is Coll:
        return Coll(v.t, {k: copy_value(x) for k, x in v.d.items()}, v.local)
    return v  # IOPoint, Screen: links are shared


def copy_local(v: Any) -> Any:
    """The copy a by-value parameter gets (2.6.1): frames, tools and points become local
    variables of the callee (same reference, 9.4.1; a global cannot be linked to them, 165)."""
    tv = type(v)
    if tv is Point:
        return copy_point(v, True)
    if tv is Frame or tv is Tool:
        return copy_node(v, local=True)
    return copy_value(v)


def copy_globals(values: dict[str, Any]) -> dict[str, Any]:
    """Copy a unit's globals (libSave snapshots, libLoad of one): like `copy_value`, but the
    references between the copied frames, tools and points are kept among the copies."""
    memo: dict[int, Any] = {}
    made: list[Any] = []

    def cp(v: Any) -> Any:
        tv = type(v)
        if tv is Frame or tv is Tool or tv is Point:
            n = memo.get(id(v))
            if n is None:
                n = copy_value(v)
                n.name = v.name
                memo[id(v)] = n
                made.append(n)
            return n
        if tv is Arr:
            return Arr(v.t, [cp(x) for x in v.data[v.off:]], v.dims, 0, v.local)
        if tv is Coll:
            return Coll(v.t, {k: cp(x) for k, x in v.d.items()}, v.local)
        if tv is dict:
            return {k: cp(x) for k, x in v.items()}
        return copy_value(v)

    out = {name: cp(v) for name, v in values.items()}
    for n in made:
        r = n.ref
        if r is not None and id(r) in memo:
            n.ref = memo[id(r)]
    return out


def store(c: Any, k: Any, v: Any) -> None:
    """`c[k] = copy of v`; a frame, tool or point place keeps its node (copied into)."""
    old = c[k] if type(c) is not dict or k in c else None
    to = type(old)
    if to is Frame or to is Tool:
        from ..geometry.frames import assign

        assign(old, v)
        return
    if to is Point:
        from ..geometry.points import assign as passign

        passign(old, v)
        old.config = dict(v.config) if type(v.config) is dict else v.config
        return
    c[k] = copy_value(v)


def type_error(detail: str) -> Val3RuntimeError:
    return Val3RuntimeError(70, detail)


def canonical_type(name: str) -> str:
    """Built-in spelling (`pointRx` -> `point`); user type names unchanged."""
    return base_type(name)
