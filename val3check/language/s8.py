"""The s8 additions to the s7 catalogue (``s8.toml``): new forms of s7 instructions, new
instructions and statements, each with the version it appeared in and its source.

    forms("logMsg")         -> the s8 overloads of an s7 instruction (S8Form), () when none
    instruction("userPageSet") -> S8Instruction or None
    statement("print")      -> S8Statement (the `? expr` statement)

Read on first use and cached, like instructions.toml.
"""

from __future__ import annotations

import os
from functools import lru_cache

from ..light_dataclass import dataclass
from .instructions import CatalogueError, Instruction, Overload, Param, _instruction, _param

TYPE_CHECKING = False  # not typing's: importing typing costs 3 ms at lint's start-up
if TYPE_CHECKING:
    from typing import Any

CATALOGUE_PATH = os.path.join(os.path.dirname(os.path.abspath(__file__)), "s8.toml")


@dataclass(frozen=True, slots=True)
class S8Form:
    """An overload s8 adds to the s7 instruction `name`. `params_known` False: only the number
    of arguments is known (its parameters are placeholders; the arguments are not checked)."""

    name: str
    overload: Overload
    since: str
    source: str
    params_known: bool = True


@dataclass(frozen=True, slots=True)
class S8Instruction:
    """An instruction of s8 that s7 does not have. `instruction` is None when its parameters are
    not public (`params_known = false`): its calls are then not checked."""

    name: str
    instruction: Instruction | None
    since: str
    source: str
    summary: str


@dataclass(frozen=True, slots=True)
class S8Statement:
    name: str
    syntax: str
    since: str
    source: str


@dataclass(frozen=True, slots=True)
class S8Catalogue:
    forms: dict[str, tuple[S8Form, ...]]  # lower-case s7 instruction name -> forms
    instructions: dict[str, S8Instruction]  # lower-case name
    statements: dict[str, S8Statement]


def _forms(raw: dict[str, Any]) -> dict[str, tuple[S8Form, ...]]:
    out: dict[str, tuple[S8Form, ...]] = {}
    for name, entries in raw.items():
        forms = []
        for i, ov in enumerate(entries):
            where = f"s8.forms.{name}[{i}]"
            known = ov.get("params_known", True)
            for key in ("returns", "params" if known else "arity", "since", "source"):
                if key not in ov:
                    raise CatalogueError(f"{where}: missing '{key}'")
            if known:
                params = tuple(_param(p, f"{where}.params[{j}]") for j, p in enumerate(ov["params"]))
            else:  # placeholders: any value, not checked
                params = tuple(Param(f"arg{j + 1}", "*") for j in range(int(ov["arity"])))
            forms.append(S8Form(name, Overload(ov["returns"], params, "s8", ov.get("note", "")), ov["since"],
                                ov["source"], bool(known)))
        out[name.lower()] = tuple(forms)
    return out


def _instructions(raw: dict[str, Any]) -> dict[str, S8Instruction]:
    out = {}
    for name, entry in raw.items():
        for key in ("since", "source"):
            if key not in entry:
                raise CatalogueError(f"s8.instructions.{name}: missing '{key}'")
        ins = _instruction(name, entry) if entry.get("params_known", True) else None
        out[name.lower()] = S8Instruction(name, ins, entry["since"], entry["source"], entry.get("summary", ""))
    return out


@lru_cache(maxsize=None)
def load_s8() -> S8Catalogue:
    from .compiled import load_toml

    raw = load_toml("s8.toml")
    statements = {k: S8Statement(k, v["syntax"], v["since"], v["source"]) for k, v in raw.get("statements", {}).items()}
    return S8Catalogue(_forms(raw.get("forms", {})), _instructions(raw.get("instructions", {})), statements)


def forms(name: str) -> tuple[S8Form, ...]:
    return load_s8().forms.get(name.lower(), ())


def instruction(name: str) -> S8Instruction | None:
    return load_s8().instructions.get(name.lower())


def statement(name: str) -> S8Statement:
    return load_s8().statements[name]
