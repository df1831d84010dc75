"""Global memory: default values, initial values from the data files, user types (chapter 7).

`TypeSpace` knows the types an application can name: the built-in ones and its user types,
each defined by the public globals of another application (7.2). It makes default values
(2.4: false, 0, "", the structured types' defaults, an undefined link for dio/aio/sio) and
converts the loader's `Data`/`Value` records into run-time values (`values.py`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from ..loading.model import Application, Container, Data, Value, Workspace
from ..loading.types import DEFAULTS, base_type, is_builtin
from .values import (
    ENUM_SPELLING,
    JOINT_FIELDS,
    TRSF_FIELDS,
    Arr,
    Coll,
    IOPoint,
    Screen,
    clip_string,
)


class Cell:
    """The inputs/outputs of the simulated cell, one `IOPoint` per (kind, physical link)."""

    def __init__(self) -> None:
        self.points: dict[tuple[str, str], IOPoint] = {}

    def io(self, kind: str, link: str) -> IOPoint:
        if not link:
            return IOPoint(kind, "")  # 3.5.1: an undefined link
        key = (kind, link)
        p = self.points.get(key)
        if p is None:
            p = self.points[key] = IOPoint(kind, link)
        return p


@dataclass
class UserType:
    name: str
    app: Application  # the application whose public globals are the fields (7.2)
    fields: dict[str, Data] = field(default_factory=dict)


def _num(fields: dict, key: str, default: float = 0.0) -> float:
    v = fields.get(key, default)
    return float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else default


def _trsf(fields: dict) -> dict:
    return {k: _num(fields, k) for k in TRSF_FIELDS}


def _enum(value: Any, default: str) -> str:
    if isinstance(value, str):
        return ENUM_SPELLING.get(value.lower(), value)
    return default


class TypeSpace:
    """Types visible from one application, and value construction."""

    def __init__(self, ws: Workspace, app: Application, cell: Cell, cache: dict | None = None) -> None:
        self.ws = ws
        self.app = app
        self.cell = cell
        self._cache: dict[str, TypeSpace] = cache if cache is not None else {}
        self._users: dict[str, UserType | None] = {}

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

    def field_info(self, tname: str) -> dict[str, Data] | None:
        ut = self.user_type(tname)
        return ut.fields if ut else None

    # ---- values -------------------------------------------------------------------------------

    def default(self, t: str) -> Any:
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
            return self.from_fields(b, dict(DEFAULTS[b]), {})
        ut = self.user_type(t)
        if ut is None:
            return None
        sp = self.space_of(ut.app)
        return {n: sp.container(d) for n, d in ut.fields.items()}

    def from_fields(self, t: str, fields: dict, members: dict) -> Any:
        """A value from a loader `Value.fields`/`members` (types.py keys: tmax/rmax, ioLink)."""
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
            return {"trsf": _trsf(fields)}
        if b == "tool":
            return {"trsf": _trsf(fields), "gripper": self.cell.io("dio", str(fields.get("ioLink") or "")),
                    "otime": _num(fields, "otime"), "ctime": _num(fields, "ctime")}
        if b == "point":
            return {"trsf": _trsf(fields), "config": self._config(fields)}
        if b == "config":
            return self._config(fields)
        if b == "joint":
            keys = [k for k in fields if k[:1] == "j" and k[1:].isdigit()] or list(JOINT_FIELDS)
            return {k: _num(fields, k) for k in sorted(keys, key=lambda s: int(s[1:]))}
        if b == "mdesc":
            return {"accel": _num(fields, "accel", 100.0), "vel": _num(fields, "vel", 100.0),
                    "decel": _num(fields, "decel", 100.0), "tvel": _num(fields, "tmax", 9999.0),
                    "rvel": _num(fields, "rmax", 9999.0), "blend": _enum(fields.get("blend"), "joint"),
                    "leave": _num(fields, "leave", 50.0), "reach": _num(fields, "reach", 50.0)}
        ut = self.user_type(t)
        if ut is None:
            return None
        sp = self.space_of(ut.app)
        out = {}
        for n, d in ut.fields.items():
            out[n] = sp.container(members[n], d) if n in members else sp.container(d)
        return out

    @staticmethod
    def _config(fields: dict) -> dict:
        return {"shoulder": _enum(fields.get("shoulder"), "ssame"), "elbow": _enum(fields.get("elbow"), "esame"),
                "wrist": _enum(fields.get("wrist"), "wsame")}

    def value_of(self, t: str, v: Value) -> Any:
        return self.from_fields(t, v.fields, v.members)

    def container(self, data: Data, shape: Data | None = None) -> Arr | Coll:
        """The container of a global (or of a user-type field): `data` gives the values,
        `shape` (default: `data`) the declaration. Unwritten indices take the defaults; for a
        user-type field, the type application's values are the defaults (7.1)."""
        shape = shape or data
        t = base_type(shape.type)
        if shape.container is Container.COLLECTION:
            return Coll(t, {v.key: self.value_of(t, v) for v in data.values})
        dims = tuple(max(1, int(s)) for s in (shape.sizes or (1,))) if data is shape else tuple(
            max(1, int(s)) for s in (data.sizes or shape.sizes or (1,)))
        n = 1
        for s in dims:
            n *= s
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
            src = given.get(i) or defaults.get(i)
            values.append(self.value_of(t, src) if src is not None else self.default(t))
        return Arr(t, values, dims)

    def local_container(self, t: str, container: Container, sizes: tuple[int, ...]) -> Arr | Coll:
        if container is Container.COLLECTION:
            return Coll(base_type(t))
        dims = tuple(max(1, int(s)) for s in (sizes or (1,)))
        n = 1
        for s in dims:
            n *= s
        bt = base_type(t)
        return Arr(bt, [self.default(bt) for _ in range(n)], dims, local=True)


def _flat(key: str, dims: tuple[int, ...]) -> int | None:
    try:
        parts = [int(float(p)) for p in key.replace(",", " ").split()]
    except ValueError:
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
