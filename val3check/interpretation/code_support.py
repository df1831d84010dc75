"""Helpers the generated code calls that are not instructions: indices and collection keys
(2.5.3), copies (7.3, 2.6.1), operators whose operand types were not known when compiling, a
line that fails (5.2) and taskResume's jumps (5.10), pure built-ins with outputs.

Names are as the compiler writes them (`IX`, `CK`...): short, because they appear on every
line of the generated code. `register` puts them in the registry's namespace.
"""

from __future__ import annotations

from sys import _getframe
from typing import Any

from ..geometry.trsf import Trsf
from ..language.runtime_errors import Val3RuntimeError
from .chapters.ch03_simple_types import CAT, IOR, MOD
from .chapters.ch09_geometry import JADD, JGT, JLT, JSUB
from .scheduler import JUMP
from .values import MAX_CONTAINER, Arr, CellList, Coll, IOPoint, copy_value

E = Val3RuntimeError


def number_text(v: Any) -> str:
    """A number in a message: without ".0" when it is an integer."""
    if isinstance(v, float) and v == int(v) and abs(v) < 1e15:
        return str(int(v))
    return repr(v)


# ---- indices and containers (2.5.3) ------------------------------------------------------------


def IX(v: float, n: int) -> int:
    """2.5.3: indices are rounded to the nearest integer; 0 <= index < size (errors 21/20)."""
    if v < -0.5:
        raise E(21, f"index {number_text(v)}")
    i = int(v + 0.5)
    if i >= n:
        raise E(20, f"index {i} for size {n}")
    return i


def AI1(a: Arr, v: float) -> int:
    off = a.off
    return off + IX(v, len(a.data) - off)


def AI2(a: Arr, i: float, j: float) -> int:
    d = a.dims
    if d is None or len(d) != 2:
        raise E(70, "2 indices for an array that does not have 2 dimensions")
    return IX(i, d[0]) * d[1] + IX(j, d[1])


def AI3(a: Arr, i: float, j: float, k: float) -> int:
    d = a.dims
    if d is None or len(d) != 3:
        raise E(70, "3 indices for an array that does not have 3 dimensions")
    return (IX(i, d[0]) * d[1] + IX(j, d[1])) * d[2] + IX(k, d[2])


def CK(c: Coll, key: Any) -> str:
    if key in c.d:
        return key
    raise E(20, f'no key "{key}" in the collection')


def CKW(unit, c: Coll, key: Any) -> str:
    """A collection key written to: created with the type's default when new (2.5.3)."""
    if key in c.d:
        return key
    if type(key) is not str or not key:
        raise E(70, "a collection key is a non-empty string")
    if len(c.d) >= MAX_CONTAINER:
        raise E(40, "a variable holds at most 9999 values (2.5.4)")
    c.d[key] = unit.space.default(c.t, c.local, key)
    return key


def VIEW(a: Arr, v: float) -> Arr:
    """2.6.3: `a[i]` passed for an array parameter: the part of the 1-D array from index i."""
    if a.dims is not None:
        raise E(70, "only a 1-D array can be passed from an index")
    return a.view(IX(v, a.size()))


def ELEMARR(c: Any, k: Any, t: str) -> Arr:
    """An element (a by-reference or by-value parameter, a boxed local) passed where an array is
    expected: a one-value array that aliases it (2.6.2, 2.6.3)."""
    return Arr(t, CellList(c, k), local=True)


def ASG(c: Any, k: Any, v: Any) -> Any:
    c[k] = v
    return v


# ---- operators whose operand types were not known when compiling --------------------------------


def DYN(op: str, a: Any, b: Any) -> Any:
    if isinstance(a, IOPoint) and a.kind == "dio":
        a = IOR(a)
    if isinstance(b, IOPoint) and b.kind == "dio":
        b = IOR(b)
    if op == "==":
        return a == b
    if op == "!=":
        return a != b
    if type(a) is float and type(b) is float:
        if op == "+":
            return a + b
        if op == "-":
            return a - b
        if op == "*":
            return a * b
        if op == "/":
            return a / b
        if op == "%":
            return MOD(a, b)
        if op == "<":
            return a < b
        if op == ">":
            return a > b
        if op == "<=":
            return a <= b
        if op == ">=":
            return a >= b
    if type(a) is str and type(b) is str and op == "+":
        return CAT(a, b)
    if op == "*" and type(a) is Trsf and type(b) is Trsf:
        return a * b
    if type(a) is dict and type(b) is dict and op in ("+", "-", "<", ">") and "j1" in a:  # joint (9.2.2)
        return {"+": JADD, "-": JSUB, "<": JLT, ">": JGT}[op](a, b)
    raise E(70, f"operator {op} on these values")


# ---- a line that fails (5.2) and taskResume's jumps (5.10) -------------------------------------------


def FAIL(task, e: BaseException, skippable: bool, ctx: tuple | None = None):
    """A line failed: the task stops there (5.2). Returns the taskResume jump: 0 runs the line
    again, 1 goes on after it, others resume in the line's sequence `ctx` (compiler/)."""
    task.machine.task_failed(task, e, skippable)
    task.jumpctx = ctx
    yield
    return task.jump


# ---- pure built-ins with by-reference outputs or array parameters -----------------------------------


def BREF(b, *args: Any) -> Any:
    """Call a pure built-in with by-reference outputs (builtins/__init__.py convention)."""
    vals = []
    for i, (a, p) in enumerate(zip(args, b.params)):
        if p.endswith("[]"):
            vals.append(list(a.data[a.off:]))
        elif i in b.outputs:
            vals.append(a[0][a[1]])
        else:
            vals.append(a)
    r = b.func(*vals)
    if not b.outputs:
        return r
    for j, i in enumerate(b.outputs):
        a, out = args[i], r[j + 1]
        if b.params[i].endswith("[]"):
            a.data[a.off:a.off + len(out)] = list(out)[: a.size()]
        else:
            a[0][a[1]] = out
    return r[0]


def register(registry) -> None:
    registry.helpers(FRAME=_getframe, E=E, JUMP=JUMP, IX=IX, AI1=AI1, AI2=AI2, AI3=AI3, CK=CK, CKW=CKW, VIEW=VIEW, ELEMARR=ELEMARR,
                     ASG=ASG, CP=copy_value, DYN=DYN, FAIL=FAIL, BREF=BREF)
