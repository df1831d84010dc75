"""Helpers called by the generated code, and the instructions that are not pure functions.

Every helper is named as the compiler writes it (`IX`, `CK`, `WAIT`...). Instructions are
`I_<lower-case name>(T, A, *args)`, with T the running task and A the unit (application or
library) whose program executes them; those in `ASYNC` are generators (`yield from`), because
they may block or hand over to the next task (5.4). Errors raise `Val3RuntimeError` with the
manual's code (12.1).
"""

from __future__ import annotations

import math
from typing import Any

from ..geometry.trsf import Trsf
from .builtins_bridge import format_num, operator
from ..language.runtime_errors import RUNTIME_CODES, Val3RuntimeError
from .values import (
    MAX_CONTAINER,
    Arr,
    CellList,
    Coll,
    FaultyIOPoint,
    IOPoint,
    Screen,
    clip_string,
    copy_value,
)

E = Val3RuntimeError


class SimLimit(Exception):
    """The simulator cannot go on with this task: `kind` "arm" (R002) or "notsim" (R004).
    `message` is the diagnostic's text (default: made by the machine from `what`)."""

    def __init__(self, kind: str, what: str, message: str = "") -> None:
        super().__init__(what)
        self.kind = kind
        self.what = what
        self.message = message


def ARM(name: str, *args: Any) -> Any:
    raise SimLimit("arm", name)


def NOTSIM(what: str) -> Any:
    raise SimLimit("notsim", what)


# ---- indices and containers (2.5.3) ------------------------------------------------------------


def IX(v: float, n: int) -> int:
    """2.5.3: indices are rounded to the nearest integer; 0 <= index < size (errors 21/20)."""
    if v < -0.5:
        raise E(21, f"index {_fmt(v)}")
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


def CKW(A, c: Coll, key: Any) -> str:
    """A collection key written to: created with the type's default when new (2.5.3)."""
    if key in c.d:
        return key
    if type(key) is not str or not key:
        raise E(70, "a collection key is a non-empty string")
    if len(c.d) >= MAX_CONTAINER:
        raise E(40, "a variable holds at most 9999 values (2.5.4)")
    c.d[key] = A.space.default(c.t, c.local, key)
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


CP = copy_value


def _fmt(v: Any) -> str:
    if isinstance(v, float) and v == int(v) and abs(v) < 1e15:
        return str(int(v))
    return repr(v)


# ---- operators ----------------------------------------------------------------------------------

_mod = operator("%", "num")
_cat = operator("+", "string")


def MOD(a: float, b: float) -> float:
    """3.2.2: remainder of the integer division, sign of the left operand; error 10 on zero."""
    if _mod is not None:
        return _mod(a, b)
    if b == 0:
        raise E(10, "modulo by zero")
    return math.fmod(a, b) + 0.0


def CAT(a: str, b: str) -> str:
    """3.4.2: concatenation limited to 128 bytes."""
    if _cat is not None:
        return _cat(a, b)
    return clip_string(a + b)


def DYN(op: str, a: Any, b: Any) -> Any:
    """An operator whose operand types were not known when compiling."""
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
        from . import geom

        return {"+": geom.JADD, "-": geom.JSUB, "<": geom.JLT, ">": geom.JGT}[op](a, b)
    raise E(70, f"operator {op} on these values")


# ---- inputs / outputs (3.5 - 3.7) ---------------------------------------------------------------


def _linked(io: Any, what: str) -> IOPoint:
    if type(io) is not IOPoint:
        if type(io) is FaultyIOPoint and io.link:
            _faulty(io)
        raise E(70, f"{what}: not an input/output")
    if not io.link:
        raise E(123, f"{io.kind} not linked to an input/output of the system")
    return io


def _faulty(io: IOPoint) -> None:
    """3.5.3: -2 the link matches no input/output of the system (error 123), -3 the device is in
    error (error 125, field bus error)."""
    if io.status == -2:
        raise E(123, f"{io.link} is not an input/output of the system (ioStatus -2)")
    raise E(125, f"the device of {io.link} is in error (ioStatus {io.status})")


def IOR(io: Any) -> bool:
    """The state of a dio (3.5.2)."""
    if type(io) is bool:
        return io
    if type(io) is not IOPoint or not io.link:
        _linked(io, "dio")
    return io.value


def IOW(T, io: Any, v: bool) -> bool:
    """`dio = bool` (3.5.2): writes the output; error 123 unlinked, 122 on an input."""
    _linked(io, "dio")
    if io.driven:
        raise E(122, f"write to the input {io.link}")
    v = bool(v)
    if io.status == 1:  # 3.5.3: locked by the operator, writing has no effect
        return v
    if io.value is not v:
        io.value = v
        T.M.output_changed(T, io)
    return v


# ---- waiting and handing over (5.4, 5.10) --------------------------------------------------------


class JUMP(BaseException):
    """taskResume(name, n) (5.10): resume at instruction `t` of sequence `b` of the program the
    task stopped in (caught by that sequence's dispatch loop, compiler.py). A BaseException, so
    that the `except Exception` of the lines it goes through does not take it for an error."""

    __slots__ = ("b", "t")

    def __init__(self, b: int, t: int) -> None:
        super().__init__(b, t)
        self.b = b
        self.t = t


def FAIL(T, e: BaseException, skippable: bool, ctx: tuple | None = None):
    """A line failed: the task stops there (5.2). Returns the taskResume jump: 0 runs the line
    again, 1 goes on after it, others resume in the line's sequence `ctx` (compiler.py)."""
    T.M.task_failed(T, e, skippable)
    T.jumpctx = ctx
    yield
    return T.jump


def YIELD(T):
    T.state = "yield"
    yield


def DELAY(T, s: float):
    """5.10 delay: the task waits `s` seconds; 0 or less hands over to the next task."""
    if not s > 0:
        T.state = "yield"
        yield
        return
    T.wake = T.M.wake_time(T, s)
    T.state = "delay"
    yield
    T.wake = None


def WAIT(T, fn, tdep: bool):
    """5.10 wait: the condition is evaluated again at each turn; no hand-over when it is
    already true. While it waits, the scheduler evaluates `T.cond` itself and resumes the task
    only when it is true (with True), or with None when it raised (evaluated again here, so
    that the error stops the task at its line)."""
    if fn():
        return
    T.tdep = tdep
    T.wake = None
    T.cond = fn
    while True:
        T.state = "wait"
        ok = yield
        if ok or fn():
            break
    T.cond = None
    T.tdep = False


def WATCH(T, fn, s: float, tdep: bool):
    """5.10 watch: wait for the condition at most `s` seconds; true if it became true."""
    if fn():
        return True
    T.tdep = tdep
    T.wake = T.M.wake_time(T, s) if s > 0 else T.M.now
    T.cond = fn
    result = False
    while True:
        T.state = "wait"
        ok = yield
        if ok or fn():
            result = True
            break
        if T.M.now >= T.wake:
            break
    T.cond = None
    T.wake = None
    T.tdep = False
    return result


def SETMUTEX(T, pair):
    """5.10 setMutex: wait until the bool is false, then set it true."""
    c, k = pair
    if c[k]:
        yield from WAIT(T, lambda: not c[k], False)
    c[k] = True


# ---- user page (chapter 4) -----------------------------------------------------------------------


def _screen(T, args: tuple) -> tuple[Screen, tuple]:
    if args and type(args[0]) is Screen:
        return args[0], args[1:]
    return T.M.page, args


def _text(v: Any) -> str:
    if type(v) is float:
        return format_num(v)
    if type(v) is bool:
        return "true" if v else "false"
    return str(v)


def PAGE(T, kind: str, *args: Any) -> None:
    scr, rest = _screen(T, args)
    text = _text(rest[0]) if rest else ""
    if kind == "title":
        scr.title = text
    else:
        scr.write(text, kind == "putln")
    T.M.transcript_add(T, kind, text, scr)


def GET(T, *args: Any):
    """4.3 get: wait for a key press (scripted in the scenario); returns its code."""
    scr, rest = _screen(T, args)
    pair, vtype = (rest[0], rest[1]) if len(rest) >= 2 else (None, None)
    M = T.M
    # 4.2.3: only the screen displayed on the pendant is told of the keys pressed
    yield from WAIT(T, (lambda: M.page is scr and M.key_available()), False)
    key = M.take_key()
    code = float(key.code)
    if pair is not None and key.code != 255 and key.text is not None:  # Esc leaves it unchanged
        c, k = pair
        if vtype == "num":
            try:
                c[k] = float(key.text)
            except ValueError:
                raise E(70, f"get: {key.text!r} is not a number") from None
        else:
            c[k] = clip_string(key.text)
    shown = key.text if key.text is not None else ""
    M.transcript_add(T, "get", f"{shown}[{key.code}]", scr)
    return code


# ---- serial lines and sockets (3.7) --------------------------------------------------------------


def _sio(io: Any) -> IOPoint:
    io = _linked(io, "sio")
    if io.kind != "sio":
        raise E(70, "not a sio")
    return io


def _sio_wait(T, io: IOPoint, ready):
    """Wait for received data; returns False on the sio timeout (sioCtrl "timeout")."""
    if ready():
        return True
    if io.timeout > 0:
        return (yield from WATCH(T, ready, io.timeout, False))
    yield from WAIT(T, ready, False)
    return True


def SIOR(T, io: Any, want: str):
    """3.7.2 `num = sio` reads one byte; `string = sio` reads up to the end-of-string
    character or 128 bytes."""
    io = _sio(io)
    if want == "num":
        ok = yield from _sio_wait(T, io, lambda: len(io.rx) > 0)
        if not ok:
            raise E(125, f"timeout reading {io.link}")
        b = io.rx.pop(0)
        return float(b)

    def complete() -> bool:
        return io.eos in io.rx or len(io.rx) >= 128

    ok = yield from _sio_wait(T, io, complete)
    if not ok:
        raise E(125, f"timeout reading {io.link}")
    if io.eos in io.rx[:129]:
        n = io.rx.index(io.eos)
        raw = bytes(io.rx[:n])
        del io.rx[: n + 1]
    else:
        raw = bytes(io.rx[:128])
        del io.rx[:128]
    return clip_string(raw.decode("utf-8", "ignore"))


def SIOW(T, io: Any, v: Any, vtype: str):
    """3.7.2 `sio = string` writes the UTF-8 text and the end-of-string character; `sio = num`
    writes the nearest integer modulo 256 and returns it."""
    io = _sio(io)
    if vtype == "string":
        data = v.encode("utf-8") + bytes([io.eos])
        result = v
    else:
        b = int(math.floor(v + 0.5)) % 256
        data = bytes([b])
        result = float(b)
    T.M.sio_sent(T, io, data)
    if False:  # pragma: no cover - keeps this a generator
        yield
    return result


# ---- variables: size, insert, delete... (2.5.4 - 2.5.6) --------------------------------------------


def SIZE(c: Any, idx: tuple | None) -> float:
    if c is None or type(c) is tuple:
        return 1.0
    if type(c) is Coll:
        return float(len(c.d))
    if c.dims is not None:
        raise E(70, "size() of a 2-D or 3-D array needs the dimension")
    n = c.size()
    if idx is not None:
        return float(n - IX(idx[0], n))
    return float(n)


def SIZE2(c: Any, dim: float) -> float:
    n = int(math.floor(dim + 0.5))
    if type(c) is Arr:
        dims = c.dims or (c.size(),)
        return float(dims[n - 1]) if 1 <= n <= len(dims) else 0.0
    if type(c) is Coll:
        return float(len(c.d)) if n == 1 else 0.0
    return 1.0 if n == 1 else 0.0


def ISDEF(c: Any, idx: tuple | None) -> bool:
    if idx is None or c is None or type(c) is tuple:
        return True
    if type(c) is Coll:
        return idx[0] in c.d
    v = idx
    dims = c.dims or (c.size(),)
    if len(v) != len(dims):
        return False
    return all(-0.5 <= x and int(x + 0.5) < d for x, d in zip(v, dims))


def _growable(c: Any, what: str) -> Arr:
    if type(c) is not Arr:
        raise E(70, f"{what}: not an array")
    if c.local:
        raise E(70, f"{what} cannot change the size of a local array (2.5.4)")
    if c.dims is not None:
        raise E(70, f"{what} works on 1-D arrays only (use resize)")
    return c


def INSERT(T, A, c: Any, idx: tuple | None) -> bool:
    """2.5.4 insert: a default value at an index of a 1-D array, or at a new collection key."""
    if type(c) is Coll:
        key = idx[0] if idx else ""
        if type(key) is not str or not key:
            raise E(70, "a collection key is a non-empty string")
        if key in c.d:
            return False
        if len(c.d) >= MAX_CONTAINER:
            raise E(40, "a variable holds at most 9999 values (2.5.4)")
        c.d[key] = A.space.default(c.t, c.local, key)
        return True
    a = _growable(c, "insert")
    if idx is None:
        raise E(70, "insert needs an index")
    n = a.size()
    if idx[0] < -0.5:
        raise E(21, f"index {_fmt(idx[0])}")
    i = int(idx[0] + 0.5)
    if i > n:
        raise E(20, f"index {i} for size {n}")
    if len(a.data) >= MAX_CONTAINER:
        raise E(40, "a variable holds at most 9999 values (2.5.4)")
    a.data.insert(a.off + i, A.space.default(a.t))
    return True


def DELETE(T, c: Any, idx: tuple | None) -> bool:
    """2.5.4 delete: remove a value; an array keeps at least one."""
    if type(c) is Coll:
        key = idx[0] if idx else ""
        if key not in c.d:
            raise E(20, f'no key "{key}" in the collection')
        del c.d[key]
        return True
    a = _growable(c, "delete")
    if idx is None:
        raise E(70, "delete needs an index")
    i = IX(idx[0], a.size())
    if len(a.data) <= 1:
        raise E(70, "an array keeps at least one value (2.5.4)")
    del a.data[a.off + i]
    return True


def APPEND(T, A, c: Any) -> None:
    """2.5.5 append: a default value at the end of a 1-D array."""
    a = _growable(c, "append")
    if len(a.data) >= MAX_CONTAINER:
        raise E(40, "a variable holds at most 9999 values (2.5.5)")
    a.data.append(A.space.default(a.t))


def RESIZE(T, A, c: Any, dim: float, size: float) -> None:
    """2.5.5 resize: values are created or removed at the end of the given dimension."""
    if type(c) is not Arr:
        raise E(70, "resize: not an array")
    if c.local:
        raise E(70, "resize cannot change the size of a local array (2.5.5)")
    dims = list(c.dims or (c.size(),))
    d = int(math.floor(dim + 0.5))
    n = int(math.floor(size + 0.5))
    if not 1 <= d <= len(dims):
        raise E(70, f"resize: dimension {d}")
    if n < 1:
        raise E(70, f"resize: size {n}")
    new = list(dims)
    new[d - 1] = n
    total = 1
    for x in new:
        total *= x
    if total > MAX_CONTAINER:
        raise E(40, "a variable holds at most 9999 values (2.5.5)")
    if len(dims) == 1:
        if n < len(c.data):
            del c.data[n:]
        else:
            c.data.extend(A.space.default(c.t) for _ in range(n - len(c.data)))
        return
    old = c.data
    out = []
    if len(dims) == 2:
        for i in range(new[0]):
            for j in range(new[1]):
                out.append(old[i * dims[1] + j] if i < dims[0] and j < dims[1] else A.space.default(c.t))
    else:
        for i in range(new[0]):
            for j in range(new[1]):
                for k in range(new[2]):
                    inside = i < dims[0] and j < dims[1] and k < dims[2]
                    out.append(old[(i * dims[1] + j) * dims[2] + k] if inside else A.space.default(c.t))
    c.data[:] = out
    c.dims = tuple(new)


def _coll(c: Any, what: str) -> Coll:
    if type(c) is not Coll:
        raise E(70, f"{what}: not a collection")
    return c


def CFIRST(c: Any, key: Any) -> str:
    keys = _coll(c, "first").keys()
    return keys[0] if keys else ""


def CLAST(c: Any, key: Any) -> str:
    keys = _coll(c, "last").keys()
    return keys[-1] if keys else ""


def CNEXT(c: Any, key: Any) -> str:
    """2.5.6 next: the following key in alphabetical order, "" after the last."""
    keys = _coll(c, "next").keys()
    if key is None:
        return keys[0] if keys else ""
    for k in keys:
        if k > key:
            return k
    return ""


def CPREV(c: Any, key: Any) -> str:
    keys = _coll(c, "prev").keys()
    if key is None:
        return keys[-1] if keys else ""
    for k in reversed(keys):
        if k < key:
            return k
    return ""


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


def help_text(code: float) -> str:
    n = int(code)
    extra = {-1: "no task of this name was created by this library or application",
             0: "the task is suspended without runtime error", 1: "the task is running"}
    return extra.get(n) or RUNTIME_CODES.get(n, "")
