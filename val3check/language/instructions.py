"""The VAL 3 s7 instruction catalogue (``instructions.toml``) as Python objects.

Importing this module is cheap: the TOML is read on the first call of :func:`load_instructions`
and cached. The returned objects are frozen; do not mutate the returned dictionaries.
"""

from __future__ import annotations

import os
from functools import cache, cached_property, lru_cache

from ..light_dataclass import dataclass, field

TYPE_CHECKING = False  # not typing's: importing typing costs 3 ms at lint's start-up
if TYPE_CHECKING:
    from typing import Any, Iterable, Mapping, Sequence

CATALOGUE_PATH = os.path.join(os.path.dirname(os.path.abspath(__file__)), "instructions.toml")

ANY_TYPE = "*"
KINDS = frozenset({"function", "procedure", "library", "special"})
CONTAINERS = frozenset({"element", "array", "collection", "any"})
INDEX_RULES = frozenset({"none", "start", "required", "any"})
LIBRARY_PREFIXES = frozenset({"none", "optional", "required"})
SPECIAL_FORMS = frozenset({"task", "sync_task"})


class CatalogueError(ValueError):
    """The TOML does not follow the catalogue's schema."""


@dataclass(frozen=True)
class Param:
    name: str
    type: str
    container: str = "element"
    ref: bool = False
    optional: bool = False
    accepts: tuple[str, ...] = ()
    index: str | None = None
    variable: bool = False
    reevaluated: bool = False
    note: str = ""

    @property
    def is_any_type(self) -> bool:
        return self.type == ANY_TYPE

    @property
    def needs_variable(self) -> bool:
        """The argument must name a variable (not a constant nor an expression result)."""
        return self.ref or self.variable or self.container != "element"

    def accepts_type(self, type_name: str) -> bool:
        """Whether an argument of ``type_name`` fits (``"*"`` as an argument matches a ``*``)."""
        if self.type == ANY_TYPE:
            return type_name == ANY_TYPE or not self.accepts or type_name in self.accepts
        return self.type == type_name


@dataclass(frozen=True)
class Overload:
    returns: str
    params: tuple[Param, ...]
    section: str
    note: str = ""

    @cached_property  # asked at every call checked (calls._instruction)
    def min_arity(self) -> int:
        return sum(1 for p in self.params if not p.optional)

    @property
    def max_arity(self) -> int:
        return len(self.params)

    @property
    def returns_value(self) -> bool:
        return self.returns != "void"

    def accepts_arity(self, count: int) -> bool:
        return self.min_arity <= count <= len(self.params)

    def matches(self, arg_types: Sequence[str]) -> bool:
        """Whether arguments of these types (in order) select this overload."""
        if not self.accepts_arity(len(arg_types)):
            return False
        return all(p.accepts_type(t) for p, t in zip(self.params, arg_types))

    def signature(self, name: str) -> str:
        """The overload written the manual's way, e.g. ``num sioGet(sio siEntrée, num& nDonnées[])``."""
        parts = []
        for p in self.params:
            text = f"{p.type}{'&' if p.ref else ''} {p.name}"
            if p.container == "array":
                text += "[]"
            elif p.container == "collection":
                text += '[""]'
            parts.append(f"[{text}]" if p.optional else text)
        return f"{self.returns} {name}({', '.join(parts)})"


@dataclass(frozen=True)
class Instruction:
    name: str
    kind: str
    section: str
    summary: str
    overloads: tuple[Overload, ...]
    library_prefix: str = "none"
    special_form: str | None = None
    syntax: str | None = None
    yields: bool = False
    option: str | None = None
    controllers: tuple[str, ...] = ()
    note: str = ""
    sections: tuple[str, ...] = field(default=())

    def overloads_for(self, arg_types: Sequence[str]) -> list[Overload]:
        return [o for o in self.overloads if o.matches(arg_types)]

    def overloads_with_arity(self, count: int) -> list[Overload]:
        return [o for o in self.overloads if o.accepts_arity(count)]

    @property
    def returns_value(self) -> bool:
        """Some overload returns a value (the instruction may appear in an expression)."""
        return any(o.returns_value for o in self.overloads)


@dataclass(frozen=True)
class Erratum:
    spelling: str
    canonical: str
    sections: tuple[str, ...]
    note: str = ""


def _req(table: Mapping[str, Any], key: str, where: str) -> Any:
    if key not in table:
        raise CatalogueError(f"{where}: missing '{key}'")
    return table[key]


def _param(raw: Mapping[str, Any], where: str) -> Param:
    allowed = {"name", "type", "container", "ref", "optional", "accepts", "index", "variable", "reevaluated", "note"}
    unknown = set(raw) - allowed
    if unknown:
        raise CatalogueError(f"{where}: unknown keys {sorted(unknown)}")
    container = raw.get("container", "element")
    if container not in CONTAINERS:
        raise CatalogueError(f"{where}: container {container!r}")
    index = raw.get("index")
    if index is not None and index not in INDEX_RULES:
        raise CatalogueError(f"{where}: index {index!r}")
    return Param(
        name=_req(raw, "name", where),
        type=_req(raw, "type", where),
        container=container,
        ref=bool(raw.get("ref", False)),
        optional=bool(raw.get("optional", False)),
        accepts=tuple(raw.get("accepts", ())),
        index=index,
        variable=bool(raw.get("variable", False)),
        reevaluated=bool(raw.get("reevaluated", False)),
        note=raw.get("note", ""),
    )


def _instruction(name: str, raw: Mapping[str, Any]) -> Instruction:
    where = f"instructions.{name}"
    kind = _req(raw, "kind", where)
    if kind not in KINDS:
        raise CatalogueError(f"{where}: kind {kind!r}")
    section = _req(raw, "section", where)
    overloads = []
    for i, ov in enumerate(_req(raw, "overloads", where)):
        ow = f"{where}.overloads[{i}]"
        params = tuple(_param(p, f"{ow}.params[{j}]") for j, p in enumerate(_req(ov, "params", ow)))
        seen_optional = False
        for p in params:
            if seen_optional and not p.optional:
                raise CatalogueError(f"{ow}: a required parameter follows an optional one")
            seen_optional = seen_optional or p.optional
        overloads.append(Overload(returns=_req(ov, "returns", ow), params=params, section=ov.get("section", section), note=ov.get("note", "")))
    if not overloads:
        raise CatalogueError(f"{where}: no overload")
    prefix = raw.get("library_prefix", "none")
    if prefix not in LIBRARY_PREFIXES:
        raise CatalogueError(f"{where}: library_prefix {prefix!r}")
    special = raw.get("special_form")
    if (kind == "special") != (special is not None) or (special is not None and special not in SPECIAL_FORMS):
        raise CatalogueError(f"{where}: special_form {special!r} with kind {kind!r}")
    sections = tuple(dict.fromkeys([section, *(o.section for o in overloads)]))
    return Instruction(
        name=name,
        kind=kind,
        section=section,
        summary=raw.get("summary", ""),
        overloads=tuple(overloads),
        library_prefix=prefix,
        special_form=special,
        syntax=raw.get("syntax"),
        yields=bool(raw.get("yields", False)),
        option=raw.get("option"),
        controllers=tuple(raw.get("controllers", ())),
        note=raw.get("note", ""),
        sections=sections,
    )


@lru_cache(maxsize=None)
def load_raw() -> dict[str, Any]:
    """The parsed TOML document, as is."""
    from .compiled import load_toml

    return load_toml("instructions.toml")


@cache
def entries() -> dict[str, tuple[str, Mapping[str, Any]]]:
    """Every s7 instruction's catalogue entry (its spelling, its table), by lower-case name: what
    `lookup` builds an Instruction from, when first asked (a lint run asks a few dozen of 300)."""
    result: dict[str, tuple[str, Mapping[str, Any]]] = {}
    for name, raw in load_raw()["instructions"].items():
        key = name.lower()
        if key in result:
            raise CatalogueError(f"instructions.{name}: same lower-case name as {result[key][0]}")
        result[key] = (name, raw)
    return result


_BUILT: dict[str, Instruction] = {}  # by lower-case name: one Instruction each, however asked for


@lru_cache(maxsize=None)
def load_instructions() -> dict[str, Instruction]:
    """Every s7 instruction, keyed by lower-case name (``Instruction.name`` keeps the spelling)."""
    return {key: lookup(key) for key in entries()}  # type: ignore[misc]


def lookup(name: str) -> Instruction | None:
    """The instruction of this name, whatever its case (VAL 3 source and the manual vary)."""
    key = name.lower()
    ins = _BUILT.get(key)
    if ins is None:
        entry = entries().get(key)
        if entry is None:
            return None
        ins = _BUILT.setdefault(key, _instruction(*entry))  # the first made, should two threads race
    return ins


@cache
def yielding_instructions() -> frozenset[str]:
    """The instructions (lower-case) that may hand over to the next task (`yields`, manual 5.4)."""
    return frozenset(k for k, (_, raw) in entries().items() if raw.get("yields", False))


@lru_cache(maxsize=None)
def load_errata() -> dict[str, Erratum]:
    """Spellings seen in the manual that are not instructions, keyed by lower-case spelling."""
    return {
        spelling.lower(): Erratum(spelling, raw["canonical"], tuple(raw.get("sections", ())), raw.get("note", ""))
        for spelling, raw in load_raw().get("errata", {}).items()
    }


def language_facts() -> Mapping[str, Any]:
    """The [language] table: facts about calls in general (e.g. ``function_as_statement``)."""
    return load_raw().get("language", {})


def statement_keywords() -> Mapping[str, Any]:
    """The control statements of 2.2.5 (not calls), for reference."""
    return load_raw().get("statements", {})


def iter_overloads() -> Iterable[tuple[Instruction, Overload]]:
    for instruction in load_instructions().values():
        for overload in instruction.overloads:
            yield instruction, overload
