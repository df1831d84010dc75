"""Built-in VAL 3 types, their fields and default values, and arm-specific type names.

Files name the geometric types after the arm family (`pointRx`, `jointRs`...); code and the
manual use `point`, `joint`, `config`. `base_type` maps the first to the second.
"""

from __future__ import annotations

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
# Fields and defaults. Values are already converted: num -> float, bool -> bool, others -> str.

_TRSF: dict[str, Any] = {"x": 0.0, "y": 0.0, "z": 0.0, "rx": 0.0, "ry": 0.0, "rz": 0.0}
# Manual 9.7.2: shoulder/elbow/wrist take righty|lefty|ssame|sfree, epositive|enegative|esame|
# efree, wpositive|wnegative|wsame|wfree. The manual does not say which value a new point gets;
# SRS files omit the fields when unchanged and generated s6 files write ssame/esame/wsame, so
# that is the default used here.
_CONFIG: dict[str, Any] = {"shoulder": "ssame", "elbow": "esame", "wrist": "wsame"}

CONFIG_VALUES: dict[str, tuple[str, ...]] = {
    "shoulder": ("righty", "lefty", "ssame", "sfree"),
    "elbow": ("epositive", "enegative", "esame", "efree"),
    "wrist": ("wpositive", "wnegative", "wsame", "wfree"),
}
# Manual 10.5.1: blend is off, joint or Cartesian.
BLEND_VALUES: tuple[str, ...] = ("off", "joint", "cartesian")

DEFAULTS: dict[str, dict[str, Any]] = {
    # Manual 2.4.1: "La valeur d'initialisation est false pour un bool, 0 pour un num et ""
    # (chaîne vide) pour une chaîne."
    "bool": {"value": False},
    "num": {"value": 0.0},
    "string": {"value": ""},
    # Manual 3.5-3.7, 4.2: "La valeur d'initialisation par défaut ... est un lien indéfini."
    "dio": {"link": ""},
    "aio": {"link": ""},
    "sio": {"link": ""},
    "screen": {"link": ""},
    # Manual 9.3.1: "Par défaut, une variable de type trsf est initialisée à {0,0,0,0,0,0}."
    "trsf": dict(_TRSF),
    # Manual 9.4.1: one field, trsf; the reference frame comes from fatherId.
    "frame": dict(_TRSF),
    # Manual 9.5.1: "Par défaut, la sortie d'un outil est la sortie valve1 du système, les temps
    # d'ouverture et de fermeture sont à 0, et l'outil de base est flange."
    "tool": {**_TRSF, "ioLink": "valve1", "otime": 0.0, "ctime": 0.0},
    # Manual 9.6.1: trsf + config.
    "point": {**_TRSF, **_CONFIG},
    # Manual 9.2.1: "Par défaut, chaque champ d'une variable de type joint est initialisé à 0."
    "joint": {f"j{i}": 0.0 for i in range(1, 7)},
    "config": dict(_CONFIG),
    # Manual 10.5.1: "Par défaut, une variable de type mdesc est initialisée avec
    # {100,100,100,9999,9999,joint,50,50}." Files write tvel/rvel as tmax/rmax.
    "mdesc": {
        "accel": 100.0,
        "vel": 100.0,
        "decel": 100.0,
        "tmax": 9999.0,
        "rmax": 9999.0,
        "blend": "joint",
        "leave": 50.0,
        "reach": 50.0,
    },
}

# Field spellings accepted in files (and used by the manual) -> the key used in Value.fields.
FIELD_ALIASES: dict[str, dict[str, str]] = {
    "mdesc": {"tvel": "tmax", "rvel": "rmax"},
    "tool": {"iolink": "ioLink", "gripper": "ioLink"},
}

# Which fields are numbers (converted to float) and which are booleans.
BOOL_FIELDS: frozenset[tuple[str, str]] = frozenset({("bool", "value")})


def defaults(type_name: str) -> dict[str, Any]:
    """A fresh dict of the fields of a built-in type with their defaults; {} for user types."""
    d = DEFAULTS.get(base_type(type_name))
    return dict(d) if d is not None else {}


def field_key(type_name: str, field: str) -> str:
    """The key of `field` in Value.fields for a value of `type_name` (`tvel` -> `tmax`)."""
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
