"""The VAL 3 s7 language as data: the instruction catalogue, built-in types, constants, operators.

The facts live in ``instructions.toml`` and ``types.toml`` beside this file (taken from the VAL 3
s7 reference manual, section numbers included); ``instructions.py`` and ``types.py`` load them
lazily into frozen dataclasses.
"""

from __future__ import annotations

from .instructions import Instruction, Overload, Param, load_instructions, lookup
from .types import BuiltinType, Constant, Operator, find_operator, load_constants, load_operators, load_types, resolve_type

__all__ = [
    "BuiltinType",
    "Constant",
    "Instruction",
    "Operator",
    "Overload",
    "Param",
    "find_operator",
    "load_constants",
    "load_instructions",
    "load_operators",
    "load_types",
    "lookup",
    "resolve_type",
]
