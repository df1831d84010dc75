"""Built-in VAL 3 types, their fields and default values, and arm-specific type names.

Files name the geometric types after the arm family (`pointRx`, `jointRs`...); code and the
manual use `point`, `joint`, `config`. `base_type` maps the first to the second.
"""

from __future__ import annotations


from ..language.types import load_families, load_types

TYPE_CHECKING = False  # not typing's: importing typing costs 3 ms at lint's start-up
if TYPE_CHECKING:
    from typing import Any

# Manual 2.3.2 (types simples) and 2.3.3 (types structurés). `trsf` is spelled `trs` in one
# place of the French manual; `trsf` everywhere else and in files.
SIMPLE_TYPES: tuple[str, ...] = ("bool", "num", "string", "dio", "aio", "sio", "screen")
STRUCTURED_TYPES: tuple[str, ...] = ("trsf", "frame", "tool", "point", "joint", "config", "mdesc")
BUILTIN_TYPES: tuple[str, ...] = SIMPLE_TYPES + STRUCTURED_TYPES

# Arm-family spellings found in files (srs-project-files.md, "Arm-specific type names").
ARM_SUFFIXES: tuple[str, ...] = ("Rx", "Rs")
_ARM_BASES = ("point", "joint", "config")
ARM_TYPES: dict[str, str] = {f"{b}{s}": b for b in _ARM_BASES for s in ARM_SUFFIXES}
# Lower-case lookup: files and old tools are not consistent about case (`pointRX`).
_BY_LOWER: dict[str, str] = {t.lower(): t for t in BUILTIN_TYPES}
_BY_LOWER.update({k.lower(): v for k, v in ARM_TYPES.items()})
# s6 also knows "...Vrb" sections (jointVrb, pointVrb, configVrb): same fields.
_BY_LOWER.update({f"{b}vrb": b for b in _ARM_BASES})


def base_type(name: str) -> str:
    """`pointRx`/`pointRs` -> `point`, `jointRx`/`jointRs` -> `joint`, `configRx`/`configRs`
    -> `config`; a built-in type name -> itself (canonical spelling); anything else (a user
    type) is returned unchanged."""
    return _BY_LOWER.get(name.lower(), name)


def arm_family(name: str) -> str | None:
    """ "Rx" for `pointRx`, "Rs" for `jointRs`...; None for types that do not depend on the arm."""
    low = name.lower()
    for base in _ARM_BASES:
        if low.startswith(base) and len(low) == len(base) + 2:
            suffix = name[len(base) :]
            if suffix.lower() in ("rx", "rs"):
                return suffix[0].upper() + suffix[1].lower()
    return None


def is_builtin(name: str) -> bool:
    return name.lower() in _BY_LOWER


def is_user_type(name: str) -> bool:
    return not is_builtin(name)


# ---------------------------------------------------------------------------------------------
# Fields and defaults, from language/types.toml (the one source of the type facts). A value's
# fields are flat, as data files write them: a point's are x..rz and shoulder, elbow, wrist.
# Values are converted: num -> float, bool -> bool, others -> str. Keys are the manual's field
# names (mdesc `tvel`, tool `gripper`); the files' spellings (`tmax`, `ioLink`) are aliases.


def _literal(text: str | None) -> Any:
    """A simple type's default as types.toml writes it (`false`, `0`, `""`)."""
    return {"false": False, "true": True, '""': ""}.get(text or "", 0.0)


def _flat_defaults(type_name: str) -> dict[str, Any]:
    types = load_types()
    out: dict[str, Any] = {}
    for f in types[type_name].fields:
        ft = types.get(f.type)
        if ft is not None and ft.kind == "structured":
            out.update(_flat_defaults(f.type))
        elif f.type == "num":
            out[f.name] = float(f.default or 0)
        else:
            out[f.name] = f.default
    return out


def _defaults() -> dict[str, dict[str, Any]]:
    out: dict[str, dict[str, Any]] = {}
    for name, bt in load_types().items():
        if bt.kind == "simple":
            # 2.4.1 false, 0, ""; 3.5-3.7, 4.2: an undefined link
            out[name] = {"link": ""} if name in ("dio", "aio", "sio", "screen") else {"value": _literal(bt.default)}
        elif bt.kind == "structured":
            out[name] = _flat_defaults(name)
    return out


def _aliases() -> dict[str, dict[str, str]]:
    out: dict[str, dict[str, str]] = {}
    for name, bt in load_types().items():
        found = {a.lower(): f.name for f in bt.fields for a in f.aliases}
        if found:
            out[name] = found
    return out


DEFAULTS: dict[str, dict[str, Any]] = _defaults()
# Field spellings accepted in files -> the key used in Value.fields (`tmax` -> `tvel`).
FIELD_ALIASES: dict[str, dict[str, str]] = _aliases()
# 9.7.2 and 10.5.1: the values of the config fields and of blend, lower case.
CONFIG_VALUES: dict[str, tuple[str, ...]] = {
    f.name: tuple(v.lower() for v in load_types()[f.type].values) for f in load_types()["config"].fields}
BLEND_VALUES: tuple[str, ...] = tuple(v.lower() for v in load_types()["blend"].values)

# Which fields are numbers (converted to float) and which are booleans.
BOOL_FIELDS: frozenset[tuple[str, str]] = frozenset({("bool", "value")})


def defaults(type_name: str) -> dict[str, Any]:
    """A fresh dict of the fields of a built-in type with their defaults; {} for user types.
    A type of the RS/TS family (`jointRs`, `pointRs`, `configRs`) has the fields of that family
    only: j1..j4, the shoulder (types.toml [families], 9.7.2)."""
    d = DEFAULTS.get(base_type(type_name))
    if d is None:
        return {}
    out = dict(d)
    if arm_family(type_name) == "Rs":
        fam = load_families()["Rs"]
        base = base_type(type_name)
        if base == "joint":
            out = {k: v for k, v in out.items() if k in fam.joint_fields}
        else:
            for k in CONFIG_VALUES:
                if k not in fam.config_fields:
                    out.pop(k, None)
    return out


def field_key(type_name: str, field: str) -> str:
    """The key of `field` in Value.fields for a value of `type_name` (`tmax` -> `tvel`)."""
    aliases = FIELD_ALIASES.get(base_type(type_name), {})
    return aliases.get(field.lower(), field)


def field_kind(type_name: str, field: str) -> str:
    """ "num", "bool" or "str": how the field's text is converted."""
    base = base_type(type_name)
    default = DEFAULTS.get(base, {}).get(field)
    if isinstance(default, bool):
        return "bool"
    if isinstance(default, float):
        return "num"
    if base == "joint" and field[:1] == "j" and field[1:].isdigit():
        return "num"  # joint has one field per axis (manual 9.2.1): j7, j8 on extra axes
    return "str"
