"""The pure built-in instructions of VAL 3, as plain Python functions, for the interpreter.

Values: VAL 3 `num` -> `float`, `bool` -> `bool`, `string` -> `str`, an array -> `list` of its
elements (for an array parameter, the elements from the given start index to the end).

Registry: `PURE[name]` is a `Builtin` for the instruction spelled `name` as in the manual
("toString", "roundUp", "ln", "getDisplayLen"...); `lookup(name)` ignores case, as VAL 3 does.

Calling convention (the same for every entry):
  * the interpreter evaluates ALL the arguments, in the manual's parameter order, and calls
    `builtin.func(*args)`; a by-reference (`&`) parameter is passed as its CURRENT value (a
    list for an array) -- the function needs it, e.g. toNum leaves nValeur unchanged when its
    report is false, toBinary needs the size of nOctetDonnées;
  * when `builtin.outputs` is empty, the function returns the instruction's value;
  * otherwise it returns a tuple `(value, out_1, ..., out_k)` and the interpreter writes
    `out_i` to the variable passed as parameter number `outputs[i-1]` (0-based). An array output
    is a list of the same length as the list passed in: element j is written to the array's
    element (start index + j);
  * a failure raises `Val3RuntimeError(code, detail)` (manual 12.1) before anything is written.

`params` gives the parameter types ("num", "bool", "string", "num[]" for an array of num): it
tells apart the overloads that are NOT here -- `insert`/`delete` on containers (2.5.4) share
their names with the string ones, and `abs(joint)` (9.2.3) with `abs(num)`: call PURE["insert"]
only when the arguments match `params`.

`OPERATORS` holds the operators of chapter 3 that can fail or truncate, keyed by
(operator, operand type): "/" and "%" on nums (error 10 on zero) and "+" on strings (128 bytes).
`format_num_default` is how `put`/`putln` display a num.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from val3check.interpretation.builtins import bits, numeric, strings
from val3check.interpretation.builtins.strings import format_num_default
from val3check.light_dataclass import dataclass


@dataclass(frozen=True)
class Builtin:
    """A pure instruction: `func(*args)`; `outputs` are the 0-based indices of the by-reference
    parameters written from the returned tuple's items 1, 2, ... (see the module docstring)."""

    name: str
    func: Callable[..., Any]
    params: tuple[str, ...]
    returns: str
    section: str
    outputs: tuple[int, ...] = ()


def _table(*entries: Builtin) -> dict[str, Builtin]:
    return {b.name: b for b in entries}


_N, _B, _S, _NA = "num", "bool", "string", "num[]"

PURE: dict[str, Builtin] = _table(
    # 3.2.3
    Builtin("sin", numeric.sin, (_N,), _N, "3.2.3"),
    Builtin("asin", numeric.asin, (_N,), _N, "3.2.3"),
    Builtin("cos", numeric.cos, (_N,), _N, "3.2.3"),
    Builtin("acos", numeric.acos, (_N,), _N, "3.2.3"),
    Builtin("tan", numeric.tan, (_N,), _N, "3.2.3"),
    Builtin("atan", numeric.atan, (_N,), _N, "3.2.3"),
    Builtin("abs", numeric.abs_, (_N,), _N, "3.2.3"),
    Builtin("sqrt", numeric.sqrt, (_N,), _N, "3.2.3"),
    Builtin("exp", numeric.exp, (_N,), _N, "3.2.3"),
    Builtin("power", numeric.power, (_N, _N), _N, "3.2.3"),
    Builtin("ln", numeric.ln, (_N,), _N, "3.2.3"),
    Builtin("log", numeric.log, (_N,), _N, "3.2.3"),
    Builtin("roundUp", numeric.round_up, (_N,), _N, "3.2.3"),
    Builtin("roundDown", numeric.round_down, (_N,), _N, "3.2.3"),
    Builtin("round", numeric.round_, (_N,), _N, "3.2.3"),
    Builtin("min", numeric.min_, (_N, _N), _N, "3.2.3"),
    Builtin("max", numeric.max_, (_N, _N), _N, "3.2.3"),
    Builtin("limit", numeric.limit, (_N, _N, _N), _N, "3.2.3"),
    Builtin("sel", numeric.sel, (_B, _N, _N), _N, "3.2.3"),
    # 3.3.3
    Builtin("bNot", bits.b_not, (_N,), _N, "3.3.3"),
    Builtin("bAnd", bits.b_and, (_N, _N), _N, "3.3.3"),
    Builtin("bOr", bits.b_or, (_N, _N), _N, "3.3.3"),
    Builtin("bXor", bits.b_xor, (_N, _N), _N, "3.3.3"),
    Builtin("toBinary", bits.to_binary, (_NA, _N, _S, _NA), _N, "3.3.3", outputs=(3,)),
    Builtin("fromBinary", bits.from_binary, (_NA, _N, _S, _NA), _N, "3.3.3", outputs=(3,)),
    # 3.4.3
    Builtin("toString", strings.to_string, (_S, _N), _S, "3.4.3"),
    Builtin("toNum", strings.to_num, (_S, _N, _B), _S, "3.4.3", outputs=(1, 2)),
    Builtin("chr", strings.chr_, (_N,), _S, "3.4.3"),
    Builtin("asc", strings.asc, (_S, _N), _N, "3.4.3"),
    Builtin("left", strings.left, (_S, _N), _S, "3.4.3"),
    Builtin("right", strings.right, (_S, _N), _S, "3.4.3"),
    Builtin("mid", strings.mid, (_S, _N, _N), _S, "3.4.3"),
    Builtin("insert", strings.insert, (_S, _S, _N), _S, "3.4.3"),
    Builtin("delete", strings.delete, (_S, _N, _N), _S, "3.4.3"),
    Builtin("replace", strings.replace, (_S, _S, _N, _N), _S, "3.4.3"),
    Builtin("find", strings.find, (_S, _S), _N, "3.4.3"),
    Builtin("len", strings.len_, (_S,), _N, "3.4.3"),
    # 4.3
    Builtin("getDisplayLen", strings.get_display_len, (_S,), _N, "4.3"),
)

_BY_LOWER: dict[str, Builtin] = {name.lower(): b for name, b in PURE.items()}

OPERATORS: dict[tuple[str, str], Callable[..., Any]] = {
    ("/", "num"): numeric.divide,
    ("%", "num"): numeric.modulo,
    ("+", "string"): strings.concat,
}


def lookup(name: str) -> Builtin | None:
    """The pure instruction of this name, whatever its case, or None."""
    return _BY_LOWER.get(name.lower())


__all__ = ["OPERATORS", "PURE", "Builtin", "format_num_default", "lookup"]
