"""`dataclass` and `field` for the lint path: the subset of the standard `dataclasses` that
val3check uses, without its cost.

`val3check lint` must start fast (a pre-commit hook): `dataclasses` imports `inspect` (and
through it `ast`, `dis`, `tokenize`...) and spends over a millisecond per class; the lint path
declares some eighty record classes, which made up a third of the start-up. This module makes
the same classes with one small `exec` each, for `__init__`; `__repr__`, `__eq__` and `__hash__`
are closures over the field names (compiled like `__init__`, they cost as much again).

Supported, with the standard meaning: `@dataclass`, `@dataclass(slots=True, frozen=True,
eq=False)`, fields from the class annotations in order, defaults, `field(default=...)` and
`field(default_factory=...)`; generated `__init__`, `__repr__`, `__eq__` (fields compared as a
tuple, same class only), `__hash__` (from the fields when frozen; None when eq and not frozen),
`__match_args__`; frozen classes refuse assignments (FrozenInstanceError, an AttributeError).
Not supported (not used here): inheritance of fields, `ClassVar`, `InitVar`, `__post_init__`,
ordering, `kw_only`, `dataclasses.replace`/`fields`, `field(repr=..., compare=...)`: classes that
need them keep the standard module. The simulation uses it too (some 4 M instructions saved per class).
"""

from __future__ import annotations

from operator import attrgetter
from types import FunctionType

__all__ = ["FrozenInstanceError", "dataclass", "field"]


class FrozenInstanceError(AttributeError):
    """Assignment to a field of a frozen record."""


class _Missing:
    __slots__ = ()

    def __repr__(self) -> str:
        return "MISSING"


MISSING = _Missing()


class _Field:
    __slots__ = ("default", "default_factory")

    def __init__(self, default: object, default_factory: object) -> None:
        self.default = default
        self.default_factory = default_factory


def field(*, default: object = MISSING, default_factory: object = MISSING) -> object:
    """A field's default value, or the function that makes it (`list`, `dict`...)."""
    if default is not MISSING and default_factory is not MISSING:
        raise ValueError("cannot specify both default and default_factory")
    return _Field(default, default_factory)


def _frozen_setattr(self, name, value):  # noqa: ANN001
    raise FrozenInstanceError(f"cannot assign to field {name!r}")


def _frozen_delattr(self, name):  # noqa: ANN001
    raise FrozenInstanceError(f"cannot delete field {name!r}")


def _init_code(frozen: bool, kinds: tuple[str, ...]):
    """The code of an `__init__` for fields of these kinds ("value" or "factory"), with the
    placeholder names `_p0_`, `_p1_`...: compiled once per shape (compiling is most of the cost
    of a record class, and the lint path declares some eighty). A plain default is not in the
    code: it is the function's `__defaults__`."""
    code = _INIT_CODES.get((frozen, kinds))
    if code is None:
        params, body = [], []
        for i, kind in enumerate(kinds):
            name = f"_p{i}_"
            params.append(name)
            value = f"_factory{name}() if {name} is MISSING else {name}" if kind == "factory" else name
            body.append(f"__object_setattr(self, {name!r}, {value})" if frozen else f"self.{name} = {value}")
        src = [f"def __init__(self, {', '.join(params)}):" if params else "def __init__(self):"]
        src += [f"    {line}" for line in body or ["pass"]]
        scope: dict = {"MISSING": MISSING}
        exec("\n".join(src), scope)  # noqa: S102 - source built above from placeholder names
        code = _INIT_CODES[(frozen, kinds)] = scope["__init__"].__code__
    return code


_INIT_CODES: dict = {}


def _make_init(names: list[str], kinds: tuple[str, ...], defaults: list, frozen: bool, scope: dict):
    """The `__init__` of fields `names`: the shape's code with the placeholders renamed."""
    code = _init_code(frozen, kinds)
    rename = {}
    for i, name in enumerate(names):
        rename[f"_p{i}_"] = name
        rename[f"_factory_p{i}_"] = f"_factory_{name}"
    code = code.replace(
        co_varnames=tuple(rename.get(n, n) for n in code.co_varnames),
        co_names=tuple(rename.get(n, n) for n in code.co_names),
        co_consts=tuple(rename.get(c, c) if type(c) is str else c for c in code.co_consts),
    )
    return FunctionType(code, scope, "__init__", tuple(defaults) or None)


def _process(cls: type, slots: bool, frozen: bool, eq: bool) -> type:
    names = [n for n in cls.__dict__.get("__annotations__", {})]
    scope: dict = {"MISSING": MISSING, "__object_setattr": object.__setattr__}
    kinds, defaults = [], []
    for name in names:
        default = cls.__dict__.get(name, MISSING)
        factory = MISSING
        if isinstance(default, _Field):
            default, factory = default.default, default.default_factory
        if factory is not MISSING:
            scope[f"_factory_{name}"] = factory
            kinds.append("factory")
            defaults.append(MISSING)
        elif default is not MISSING:
            kinds.append("value")
            defaults.append(default)
        else:
            if defaults:
                raise TypeError(f"non-default argument {name!r} follows default argument")
            kinds.append("value")
    scope["__init__"] = _make_init(names, tuple(kinds), defaults, frozen, scope)
    scope["__repr__"] = _repr(tuple(names))
    if eq:
        values = _values(tuple(names))
        scope["__eq__"] = _eq(values)
        if frozen:
            scope["__hash__"] = _hash(values)

    body_dict = dict(cls.__dict__)
    for method in ("__init__", "__repr__", "__eq__", "__hash__"):
        if method in scope:
            body_dict[method] = scope[method]
            scope[method].__qualname__ = f"{cls.__qualname__}.{method}"
    if eq and not frozen:
        body_dict["__hash__"] = None  # like dataclasses: mutable and compared by value
    body_dict["__match_args__"] = tuple(names)
    if frozen:
        body_dict["__setattr__"] = _frozen_setattr
        body_dict["__delattr__"] = _frozen_delattr
    if slots:
        body_dict["__slots__"] = tuple(names)
        for name in names:
            body_dict.pop(name, None)  # a class attribute would hide the slot
        body_dict.pop("__dict__", None)
        body_dict.pop("__weakref__", None)
        new = type(cls)(cls.__name__, cls.__bases__, body_dict)
        new.__qualname__ = cls.__qualname__
        return new
    for name in names:
        default = body_dict.get(name)
        if isinstance(default, _Field):  # keep plain defaults as class attributes, like dataclasses
            if default.default is MISSING:
                delattr(cls, name)
            else:
                setattr(cls, name, default.default)
    for key, value in body_dict.items():
        if key in ("__init__", "__repr__", "__eq__", "__hash__", "__match_args__", "__setattr__", "__delattr__"):
            setattr(cls, key, value)
    return cls


def _values(names: tuple[str, ...]):  # noqa: ANN202
    """The fields of a record as a tuple, as the standard module compares and hashes them."""
    if len(names) > 1:
        return attrgetter(*names)
    if names:
        one = attrgetter(names[0])
        return lambda o: (one(o),)
    return lambda o: ()


def _repr(names: tuple[str, ...]):  # noqa: ANN202
    def __repr__(self) -> str:  # noqa: N807
        return f"{self.__class__.__qualname__}({', '.join(f'{n}={getattr(self, n)!r}' for n in names)})"

    return __repr__


def _eq(values):  # noqa: ANN001, ANN202
    def __eq__(self, other: object) -> bool:  # noqa: N807
        if other.__class__ is self.__class__:
            return values(self) == values(other)
        return NotImplemented

    return __eq__


def _hash(values):  # noqa: ANN001, ANN202
    def __hash__(self) -> int:  # noqa: N807
        return hash(values(self))

    return __hash__


def dataclass(cls: type | None = None, *, slots: bool = False, frozen: bool = False, eq: bool = True):
    """Make `cls` a record class (see the module docstring)."""

    def wrap(c: type) -> type:
        return _process(c, slots, frozen, eq)

    return wrap if cls is None else wrap(cls)
