"""VAL 3 s7 built-in types, named constants and operators (``types.toml``) as Python objects.

Importing this module is cheap: the TOML is read on first use and cached.
"""

from __future__ import annotations

import os
from functools import lru_cache

from ..light_dataclass import dataclass

TYPE_CHECKING = False  # not typing's: importing typing costs 3 ms at lint's start-up
if TYPE_CHECKING:
    from typing import Any, Mapping

TYPES_PATH = os.path.join(os.path.dirname(os.path.abspath(__file__)), "types.toml")

TYPE_KINDS = frozenset({"simple", "structured", "enum", "pseudo"})
UNARY_OPERATORS = frozenset({"!", "neg"})
BINARY_OPERATORS = frozenset({"=", "==", "!=", "<", ">", "<=", ">=", "+", "-", "*", "/", "%", "and", "or", "xor"})


class TypesError(ValueError):
    """The TOML does not follow the schema."""


@dataclass(frozen=True)
class FieldSpec:
    name: str
    type: str
    aliases: tuple[str, ...] = ()
    note: str = ""
    default: Any = None  # a number, an enum value, a dio's link name; None: its type's defaults


@dataclass(frozen=True)
class BuiltinType:
    name: str
    kind: str
    section: str
    summary: str = ""
    prefix: str | None = None
    default: str | None = None
    fields: tuple[FieldSpec, ...] = ()
    values: tuple[str, ...] = ()
    reference: str | None = None
    note: str = ""

    @property
    def is_structured(self) -> bool:
        return self.kind == "structured"

    def field(self, name: str) -> FieldSpec | None:
        """A field by its name or a file alias (``tmax`` for ``tvel``)."""
        for f in self.fields:
            if f.name == name or name in f.aliases:
                return f
        return None


@dataclass(frozen=True)
class Family:
    name: str
    arms: str
    section: str
    joint_fields: tuple[str, ...]
    config_fields: tuple[str, ...]
    note: str = ""


@dataclass(frozen=True)
class TypeAlias:
    name: str
    type: str
    family: str


@dataclass(frozen=True)
class Constant:
    name: str
    type: str
    section: str
    note: str = ""


@dataclass(frozen=True)
class Operator:
    op: str
    operands: tuple[str, ...]
    result: str
    section: str
    note: str = ""

    @property
    def unary(self) -> bool:
        return len(self.operands) == 1

    @property
    def assignment(self) -> bool:
        return self.op == "="


@dataclass(frozen=True)
class RemovedOperator:
    op: str
    operands: tuple[str, ...]
    section: str
    since: str
    replacement: str = ""


@lru_cache(maxsize=None)
def load_raw() -> dict[str, Any]:
    from .compiled import load_toml

    return load_toml("types.toml")


@lru_cache(maxsize=None)
def load_types() -> dict[str, BuiltinType]:
    """Built-in types (and the catalogue's pseudo-types), keyed by exact name."""
    result = {}
    for name, raw in load_raw()["types"].items():
        kind = raw.get("kind")
        if kind not in TYPE_KINDS:
            raise TypesError(f"types.{name}: kind {kind!r}")
        if "section" not in raw:
            raise TypesError(f"types.{name}: missing section")
        result[name] = BuiltinType(
            name=name,
            kind=kind,
            section=raw["section"],
            summary=raw.get("summary", ""),
            prefix=raw.get("prefix"),
            default=raw.get("default"),
            fields=tuple(
                FieldSpec(f["name"], f["type"], tuple(f.get("aliases", ())), f.get("note", ""), f.get("default"))
                for f in raw.get("fields", ())
            ),
            values=tuple(raw.get("values", ())),
            reference=raw.get("reference"),
            note=raw.get("note", ""),
        )
    return result


def data_type_names() -> frozenset[str]:
    """Names a variable may be declared with: simple and structured types (not enums, not pseudo)."""
    return frozenset(n for n, t in load_types().items() if t.kind in ("simple", "structured"))


@lru_cache(maxsize=None)
def load_families() -> dict[str, Family]:
    return {
        name: Family(
            name=name,
            arms=raw["arms"],
            section=raw["section"],
            joint_fields=tuple(raw["joint_fields"]),
            config_fields=tuple(raw["config_fields"]),
            note=raw.get("note", ""),
        )
        for name, raw in load_raw()["families"].items()
    }


@lru_cache(maxsize=None)
def load_aliases() -> dict[str, TypeAlias]:
    """Arm-family type names of SRS files (``pointRx`` ...), keyed by exact name."""
    return {name: TypeAlias(name, raw["type"], raw["family"]) for name, raw in load_raw()["aliases"].items()}


def resolve_type(name: str) -> tuple[str, str | None] | None:
    """``(built-in type, arm family or None)`` for a type name as written in code or files.

    Exact spelling first, then case-insensitively (files and hand-written code vary).
    """
    types, aliases = load_types(), load_aliases()
    for table_name in (name, *(n for n in (*types, *aliases) if n.lower() == name.lower())):
        if table_name in aliases:
            alias = aliases[table_name]
            return alias.type, alias.family
        if table_name in types:
            return table_name, None
    return None


@lru_cache(maxsize=None)
def load_constants() -> dict[str, Constant]:
    """Named constants (``true``, ``world``, ``righty``, ``off``...), keyed by exact name."""
    return {
        name: Constant(name, raw["type"], raw["section"], raw.get("note", "")) for name, raw in load_raw()["constants"].items()
    }


@lru_cache(maxsize=None)
def load_operators() -> tuple[Operator, ...]:
    result = []
    for i, raw in enumerate(load_raw()["operators"]):
        op, operands = raw["op"], tuple(raw["operands"])
        if len(operands) == 1 and op not in UNARY_OPERATORS or len(operands) == 2 and op not in BINARY_OPERATORS:
            raise TypesError(f"operators[{i}]: {op!r} with {len(operands)} operand(s)")
        result.append(Operator(op, operands, raw["result"], raw["section"], raw.get("note", "")))
    return tuple(result)


@lru_cache(maxsize=None)
def load_removed_operators() -> tuple[RemovedOperator, ...]:
    return tuple(
        RemovedOperator(r["op"], tuple(r["operands"]), r["section"], r["since"], r.get("replacement", ""))
        for r in load_raw().get("removed_operators", ())
    )


@lru_cache(maxsize=None)
def _operator_index() -> dict[tuple[str, tuple[str, ...]], Operator]:
    return {(o.op, o.operands): o for o in load_operators()}


def find_operator(op: str, *operand_types: str) -> Operator | None:
    """The operator applying to these operand types (after alias resolution), or None."""
    resolved = []
    for t in operand_types:
        r = resolve_type(t)
        resolved.append(r[0] if r else t)
    return _operator_index().get((op, tuple(resolved)))


def operators_of(type_name: str) -> tuple[Operator, ...]:
    """Every operator that takes ``type_name`` as an operand."""
    return tuple(o for o in load_operators() if type_name in o.operands)


def language_facts() -> Mapping[str, Any]:
    return load_raw().get("language", {})
