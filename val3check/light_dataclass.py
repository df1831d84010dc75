"""`dataclass` and `field` for the lint path: the subset of the standard `dataclasses` that
val3check uses, without its cost.

`val3check lint` must start fast (a pre-commit hook): `dataclasses` imports `inspect` (and
through it `ast`, `dis`, `tokenize`...) and spends over a millisecond per class; the lint path
declares some eighty record classes, which made up a third of the start-up. This module makes
the same classes with one small `exec` each, for `__init__`; `__repr__`, `__eq__` and `__hash__`
are closures over the field names (compiled like `__init__`, they cost as much again).

Supported, with the standard meaning: `@dataclass`, `@dataclass(slots=True, frozen=True,
eq=False)`, fields from the class annotations in order, defaults, `field(default=...)`,
`field(default_factory=...)`, `field(repr=False, compare=False)`; generated `__init__` (calling
`__post_init__` when the class has one), `__repr__`, `__eq__` (fields compared as a tuple, same
class only), `__hash__` (from the fields when frozen; None when eq and not frozen),
`__match_args__`; frozen classes refuse assignments (FrozenInstanceError, an AttributeError), and
pickle and copy when slotted (`__getstate__`/`__setstate__`, as the standard module's).
`dataclasses.fields`, `replace`, `asdict` and `is_dataclass` work on them: `__dataclass_fields__`
and `__dataclass_params__` are made by the standard module at their first read only.
Not supported (not used here): inheritance of fields, `ClassVar`, `InitVar`, ordering, `kw_only`,
a class without a docstring (the standard module writes one from the signature): classes that
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
    __slots__ = ("default", "default_factory", "repr", "compare")

    def __init__(self, default: object, default_factory: object, repr: bool = True, compare: bool = True) -> None:
        self.default = default
        self.default_factory = default_factory
        self.repr = repr
        self.compare = compare


def field(*, default: object = MISSING, default_factory: object = MISSING, repr: bool = True,  # noqa: A002
          compare: bool = True) -> object:
    """A field's default value, or the function that makes it (`list`, `dict`...); `repr`: shown
    by `__repr__`; `compare`: part of `__eq__` and `__hash__`."""
    if default is not MISSING and default_factory is not MISSING:
        raise ValueError("cannot specify both default and default_factory")
    return _Field(default, default_factory, repr, compare)


class _Standard:
    """`__dataclass_fields__` or `__dataclass_params__`, made by the standard module at the first
    read (dataclasses.fields, replace, asdict...) and then kept on the class: a run that never
    asks never imports it."""

    def __init__(self, name: str, spec: list, params: tuple) -> None:
        self.name, self.spec, self.params = name, spec, params

    def __get__(self, obj: object, owner: type) -> object:
        import dataclasses as dc

        if self.name == "__dataclass_params__":
            value: object = dc._DataclassParams(True, True, *self.params)
        else:
            value = {}
            for name, typ, default, factory, rep, cmp in self.spec:
                f = dc.field(default=dc.MISSING if default is MISSING else default,
                             default_factory=dc.MISSING if factory is MISSING else factory, repr=rep, compare=cmp)
                f.name, f.type, f._field_type = name, typ, dc._FIELD
                value[name] = f
        setattr(owner, self.name, value)
        return value


def _frozen_setattr(self, name, value):  # noqa: ANN001
    raise FrozenInstanceError(f"cannot assign to field {name!r}")


def _frozen_delattr(self, name):  # noqa: ANN001
    raise FrozenInstanceError(f"cannot delete field {name!r}")


def _init_code(frozen: bool, kinds: tuple[str, ...], post: bool = False):
    """The code of an `__init__` for fields of these kinds ("value" or "factory"), with the
    placeholder names `_p0_`, `_p1_`...: compiled once per shape (compiling is most of the cost
    of a record class, and the lint path declares some eighty). A plain default is not in the
    code: it is the function's `__defaults__`. `post`: it ends by calling `__post_init__`."""
    code = _INIT_CODES.get((frozen, kinds, post))
    if code is None:
        params, body = [], []
        for i, kind in enumerate(kinds):
            name = f"_p{i}_"
            params.append(name)
            value = f"_factory{name}() if {name} is MISSING else {name}" if kind == "factory" else name
            body.append(f"__object_setattr(self, {name!r}, {value})" if frozen else f"self.{name} = {value}")
        if post:
            body.append("self.__post_init__()")
        src = [f"def __init__(self, {', '.join(params)}):" if params else "def __init__(self):"]
        src += [f"    {line}" for line in body or ["pass"]]
        scope: dict = {"MISSING": MISSING}
        exec("\n".join(src), scope)  # noqa: S102 - source built above from placeholder names
        code = _INIT_CODES[(frozen, kinds, post)] = scope["__init__"].__code__
    return code


_INIT_CODES: dict = {}


def _make_init(names: list[str], kinds: tuple[str, ...], defaults: list, frozen: bool, scope: dict,
               post: bool = False):
    """The `__init__` of fields `names`: the shape's code with the placeholders renamed."""
    code = _init_code(frozen, kinds, post)
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
    annotations = cls.__dict__.get("__annotations__", {})
    names = [n for n in annotations]
    scope: dict = {"MISSING": MISSING, "__object_setattr": object.__setattr__}
    kinds, defaults, spec = [], [], []
    for name in names:
        default = cls.__dict__.get(name, MISSING)
        factory, shown, compared = MISSING, True, True
        if isinstance(default, _Field):
            default, factory, shown, compared = default.default, default.default_factory, default.repr, default.compare
        spec.append((name, annotations[name], default, factory, shown, compared))
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
    scope["__init__"] = _make_init(names, tuple(kinds), defaults, frozen, scope, hasattr(cls, "__post_init__"))
    scope["__repr__"] = _repr(tuple([s[0] for s in spec if s[4]]))
    if eq:
        values = _values(tuple([s[0] for s in spec if s[5]]))
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
    body_dict["__dataclass_fields__"] = _Standard("__dataclass_fields__", spec, (eq, False, False, frozen))
    body_dict["__dataclass_params__"] = _Standard("__dataclass_params__", spec, (eq, False, False, frozen))
    if frozen:
        body_dict["__setattr__"] = _frozen_setattr
        body_dict["__delattr__"] = _frozen_delattr
    if slots and frozen:  # pickling and copying set the fields through these, as the standard module's
        body_dict["__getstate__"] = _getstate(tuple(names))
        body_dict["__setstate__"] = _setstate(tuple(names))
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
        if key in ("__init__", "__repr__", "__eq__", "__hash__", "__match_args__", "__setattr__", "__delattr__",
                   "__dataclass_fields__", "__dataclass_params__"):
            setattr(cls, key, value)
    return cls


def _getstate(names: tuple[str, ...]):  # noqa: ANN202
    def __getstate__(self) -> list:  # noqa: N807
        return [getattr(self, n) for n in names]

    return __getstate__


def _setstate(names: tuple[str, ...]):  # noqa: ANN202
    def __setstate__(self, state: list) -> None:  # noqa: N807
        for name, value in zip(names, state):
            object.__setattr__(self, name, value)

    return __setstate__


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
