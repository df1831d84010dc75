"""Global memory: default values, initial values from the data files, user types (chapter 7).

`TypeSpace` knows the types an application can name: the built-in ones and its user types,
each defined by the public globals of another application (7.2). It makes default values
(2.4: false, 0, "", the structured types' defaults, an undefined link for dio/aio/sio) and
converts the loader's `Data`/`Value` records into run-time values (`values.py`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from ..geometry.frames import Frame, Tool
from ..geometry.points import Point
from ..geometry.trsf import Trsf
from ..loading.model import Application, Container, Data, Value, Workspace
from ..loading.attribute_text import parse_father
from ..loading.types import DEFAULTS, arm_family, base_type, is_builtin
from .memory_budget import UNKNOWN_BYTES, VALUE_BYTES, MemoryBudgetExceeded

MAX_TYPE_NESTING = 64  # user types inside user types (real ones: 2 or 3)
TOO_MUCH = 1e15  # bytes: the price of what cannot be built
from .values import (
    ENUM_SPELLING,
    FAMILY_FIELDS,
    Arr,
    Coll,
    IOPoint,
    Screen,
    clip_string,
)


@dataclass
class UserType:
    name: str
    app: Application  # the application whose public globals are the fields (7.2)
    fields: dict[str, Data] = field(default_factory=dict)


def _num(fields: dict, key: str, default: float = 0.0) -> float:
    v = fields.get(key, default)
    return float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else default


def _trsf(fields: dict) -> Trsf:
    return Trsf(_num(fields, "x"), _num(fields, "y"), _num(fields, "z"), _num(fields, "rx"), _num(fields, "ry"),
                _num(fields, "rz"))




def resolve_fathers(cell, globals_: dict[str, Any]) -> None:
    """Link the frames, tools and points of the data files to their `fatherId` ("fPallet[0]",
    "world[0]", "flange[0]"): a frame or point to a frame, a tool to a tool. A reference that
    names nothing of the right type leaves the value without reference (its use raises
    162/163/164, as for a local)."""
    pending, cell.pending = cell.pending, []
    lower = None
    for obj, father in pending:
        want = Tool if type(obj) is Tool else Frame
        m = parse_father(father)
        found = None
        if m:
            name, idx = m
            low = name.lower()
            if low == "world" and name not in globals_:
                found = cell.world
            elif low == "flange" and name not in globals_:
                found = cell.flange
            else:
                c = globals_.get(name)
                if c is None:
                    if lower is None:
                        lower = {n.lower(): v for n, v in globals_.items()}
                    c = lower.get(low)
                if type(c) is Arr:
                    i = _flat(idx or "0", c.dims or (len(c.data),))
                    found = c.data[i] if i is not None else None
                elif type(c) is Coll and idx is not None:
                    found = c.d.get(idx.strip().strip('"'))
        obj.ref = found if type(found) is want else None


def _enum(value: Any, default: str) -> str:
    if isinstance(value, str):
        return ENUM_SPELLING.get(value.lower(), value)
    return default


class TypeSpace:
    """Types visible from one application, and value construction."""

    def __init__(self, ws: Workspace, app: Application, cell, cache: dict | None = None) -> None:
        self.ws = ws
        self.app = app
        self.cell = cell
        self._cache: dict[str, TypeSpace] = cache if cache is not None else {}
        self._users: dict[str, UserType | None] = {}
        self._costs: dict[str, float] = {}

    # ---- user types ---------------------------------------------------------------------------

    def user_type(self, name: str) -> UserType | None:
        if name in self._users:
            return self._users[name]
        found = None
        ref = self.app.types.get(name)
        if ref is None:  # case-insensitive, as the loader is lenient
            ref = next((r for n, r in self.app.types.items() if n.lower() == name.lower()), None)
        if ref is not None and ref.resolved and ref.resolved in self.ws.apps:
            tapp = self.ws.apps[ref.resolved]
            found = UserType(name, tapp, {n: d for n, d in tapp.data.items() if d.access != "private"})
        self._users[name] = found
        return found

    def space_of(self, app: Application) -> "TypeSpace":
        key = app.path
        if key == self.app.path:
            return self
        sp = self._cache.get(key)
        if sp is None:
            sp = self._cache[key] = TypeSpace(self.ws, app, self.cell, self._cache)
        return sp

    def value_cost(self, t: str, depth: int = 0) -> float:
        """Estimated Python bytes of one value of type `t` (user types: their fields; nested
        beyond MAX_TYPE_NESTING: more than any budget)."""
        b = base_type(t)
        if b in VALUE_BYTES:
            return VALUE_BYTES[b]
        if t in self._costs:
            return self._costs[t]
        ut = self.user_type(t)
        if ut is None:
            return UNKNOWN_BYTES
        if depth >= MAX_TYPE_NESTING:
            return TOO_MUCH
        sp = self.space_of(ut.app)
        cost = min(TOO_MUCH, UNKNOWN_BYTES + sum(math.prod(d.sizes or (1,)) * sp.value_cost(d.type, depth + 1)
                                                 for d in ut.fields.values()))
        self._costs[t] = cost
        return cost

    def _nest(self, t: str) -> None:
        """One more user type inside another: bounded, like the memory (a chain of 1000 types)."""
        if self.cell.nesting >= MAX_TYPE_NESTING:
            raise MemoryBudgetExceeded(f"user type {t}: values nested more than {MAX_TYPE_NESTING} user types deep"
                                       " are not simulated")
        self.cell.nesting += 1

    def reserve_globals(self, datas) -> None:  # noqa: ANN001
        """Price all the globals of an application at once, before the first is built: data
        files that ask for gigabytes are refused at once rather than after seconds of building."""
        if self.cell.budget is None:
            return
        total, biggest, name = 0.0, 0.0, ""
        for d in datas:
            if d.container is not Container.COLLECTION:
                cost = self.value_cost(d.type)
                if cost >= TOO_MUCH:
                    self._reserve(d.type, 1, f"the global {d.name}")
                price = math.prod(max(1, int(x)) for x in (d.sizes or (1,))) * cost
                total += price
                if price > biggest:
                    biggest, name = price, d.name
        self.cell.budget.reserve(total, f"the global data of {self.app.name} (the largest: {name}, about"
                                        f" {biggest / (1 << 20):,.0f} MB)")

    def _reserve(self, t: str, n: int, what: str) -> None:
        if self.cell.budget is not None:
            cost = self.value_cost(t)
            if cost >= TOO_MUCH:
                raise MemoryBudgetExceeded(f"{what}: user types nested more than {MAX_TYPE_NESTING} deep are not"
                                           " simulated")
            self.cell.budget.reserve(n * cost, what)

    def field_info(self, tname: str) -> dict[str, Data] | None:
        ut = self.user_type(tname)
        return ut.fields if ut else None

    # ---- values -------------------------------------------------------------------------------

    def default(self, t: str, local: bool = False, name: str = "", linked: bool | None = None) -> Any:
        """The default value of type `t` (2.4). A frame, tool or point of a global is linked to
        world/flange (`linked`, default: not `local`); those of locals and user-type fields have
        no reference (9.4.1, 9.5.1, 9.6.1); `local` marks the nodes of local variables (165)."""
        b = base_type(t)
        if b == "num":
            return 0.0
        if b == "bool":
            return False
        if b == "string":
            return ""
        if b in ("dio", "aio", "sio"):
            return IOPoint(b, "")
        if b == "screen":
            return Screen()
        if b in DEFAULTS:
            v = self.from_fields(t, {} if b == "joint" else dict(DEFAULTS[b]), {}, name, local)
            if b in ("frame", "tool", "point") and (not local if linked is None else linked):
                v.ref = self.cell.flange if b == "tool" else self.cell.world
            return v
        ut = self.user_type(t)
        if ut is None:
            return None
        sp = self.space_of(ut.app)
        self._nest(t)
        try:
            return {n: sp.container(d, in_user=True, local=local) for n, d in ut.fields.items()}
        finally:
            self.cell.nesting -= 1

    def from_fields(self, t: str, fields: dict, members: dict, name: str = "", local: bool = False) -> Any:
        """A value from a loader `Value.fields`/`members` (loading/types.py: flat fields, the
        manual's names). Frames, tools and points come without reference (`value_of` links
        them)."""
        b = base_type(t)
        if b in ("num", "bool", "string"):
            v = fields.get("value")
            if b == "num":
                return float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else 0.0
            if b == "bool":
                return bool(v) if isinstance(v, bool) else False
            return clip_string(v) if isinstance(v, str) else ""
        if b in ("dio", "aio", "sio"):
            return self.cell.io(b, str(fields.get("link") or ""))
        if b == "screen":
            return Screen()
        if b == "trsf":
            return _trsf(fields)
        if b == "frame":
            return Frame(_trsf(fields), None, name=name, local=local)
        if b == "tool":
            return Tool(_trsf(fields), None, gripper=self.cell.io("dio", str(fields.get("gripper") or "")),
                        otime=_num(fields, "otime"), ctime=_num(fields, "ctime"), name=name, local=local)
        if b == "point":
            p = Point(_trsf(fields), (), None, name=name, local=local)
            p.config = self._config(fields, self.family(t))
            return p
        if b == "config":
            return self._config(fields, self.family(t))
        if b == "joint":
            keys = [k for k in fields if k[:1] == "j" and k[1:].isdigit()] or list(FAMILY_FIELDS[self.family(t)]["joint"])
            return {k: _num(fields, k) for k in sorted(keys, key=lambda s: int(s[1:]))}
        if b == "mdesc":
            return {f: _enum(fields.get(f), d) if type(d) is str else _num(fields, f, d)
                    for f, d in DEFAULTS["mdesc"].items()}
        ut = self.user_type(t)
        if ut is None:
            return None
        sp = self.space_of(ut.app)
        out = {}
        self._nest(t)
        try:
            for n, d in ut.fields.items():
                out[n] = sp.container(members[n], d, in_user=True, local=local) if n in members else sp.container(
                    d, in_user=True, local=local)
        finally:
            self.cell.nesting -= 1
        return out

    def family(self, t: str) -> str:
        """The arm family of a value of type `t`: its own (`pointRs`, `jointRx`), or the arm
        of the run's (`point`, `joint`: RX/TX without an arm model)."""
        return arm_family(t) or getattr(self.cell, "arm_family", "Rx")

    @staticmethod
    def _config(fields: dict, family: str = "Rx") -> dict:
        keep = FAMILY_FIELDS[family]["config"]
        return {f: _enum(fields.get(f), d) for f, d in DEFAULTS["config"].items() if f in keep}

    def value_of(self, t: str, v: Value, name: str = "", in_user: bool = False, father: bool = True,
                 local: bool = False) -> Any:
        """A value of the data file. A frame, tool or point is linked to its `fatherId` once every
        global exists (`resolve_fathers`), else to world/flange, except in a user-type field
        (7.1, 9.4.1: no reference)."""
        obj = self.from_fields(t, v.fields, v.members, name, local)
        to = type(obj)
        if to is Frame or to is Tool or to is Point:
            if father and v.father:
                self.cell.pending.append((obj, v.father))
            elif not in_user:
                obj.ref = self.cell.flange if to is Tool else self.cell.world
        return obj

    def container(self, data: Data, shape: Data | None = None, in_user: bool = False, local: bool = False) -> Arr | Coll:
        """The container of a global (or of a user-type field): `data` gives the values,
        `shape` (default: `data`) the declaration. Unwritten indices take the defaults; for a
        user-type field, the type application's values are the defaults (7.1)."""
        shape = shape or data
        t = base_type(shape.type)
        vt = shape.type if arm_family(shape.type) else t  # `pointRs`: the values of its arm family
        dname = data.name
        if shape.container is Container.COLLECTION:
            return Coll(t, {v.key: self.value_of(vt, v, f"{dname}[{v.key}]", in_user, True, local) for v in data.values},
                        local)
        dims = tuple(max(1, int(s)) for s in (shape.sizes or (1,))) if data is shape else tuple(
            max(1, int(s)) for s in (data.sizes or shape.sizes or (1,)))
        n = 1
        for s in dims:
            n *= s
        self._reserve(t, n, f"the global {dname} ({' x '.join(map(str, dims))} values of {t})")
        given: dict[int, Value] = {}
        for v in data.values:
            idx = _flat(v.key, dims)
            if idx is not None:
                given[idx] = v
        defaults: dict[int, Value] = {}
        if data is not shape:  # a user-type field: the type application's values are defaults
            for v in shape.values:
                idx = _flat(v.key, dims)
                if idx is not None:
                    defaults[idx] = v
        values = []
        for i in range(n):
            name = dname if n == 1 else f"{dname}[{i}]"
            src = given.get(i)
            if src is not None:
                values.append(self.value_of(vt, src, name, in_user, True, local))
            elif i in defaults:  # the type application's value: its fatherId is not ours
                values.append(self.value_of(vt, defaults[i], name, in_user, False, local))
            else:
                values.append(self.default(vt, local, name, not (in_user or local)))
        return Arr(t, values, dims)

    def local_container(self, t: str, container: Container, sizes: tuple[int, ...], name: str = "") -> Arr | Coll:
        if container is Container.COLLECTION:
            return Coll(base_type(t), local=True)
        dims = tuple(max(1, int(s)) for s in (sizes or (1,)))
        n = 1
        for s in dims:
            n *= s
        bt = base_type(t)
        self._reserve(bt, n, f"the local {name} ({' x '.join(map(str, dims))} values of {bt})")
        return Arr(bt, [self.default(bt, True, name if n == 1 else f"{name}[{i}]") for i in range(n)], dims, local=True)


def _flat(key: str, dims: tuple[int, ...]) -> int | None:
    try:
        parts = [int(float(p)) for p in key.replace(",", " ").split()]
    except (ValueError, OverflowError):  # "1e400": no index (N014 in lint)
        return None
    if len(parts) != len(dims):
        if len(parts) == 1 and len(dims) == 1:
            pass
        else:
            return None
    idx = 0
    for p, s in zip(parts, dims):
        if not 0 <= p < s:
            return None
        idx = idx * s + p
    return idx


def is_user(t: str) -> bool:
    return not is_builtin(t)
