"""Chapter 2: instructions on variables of any type (2.5.4 - 2.5.6): size, isDefined, insert,
delete, append, resize, first, last, next, prev, getData.

Their first argument is a variable of any type and container, not a value: the compiler writes
each call itself (inline forms, compiler/calls.py) and calls the helpers below with the
variable's container and index.
"""

from __future__ import annotations

import math
import re
from typing import Any

from ...language.runtime_errors import Val3RuntimeError
from ..code_support import IX, number_text
from ..values import MAX_CONTAINER, Arr, Coll, store

E = Val3RuntimeError


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


def INSERT(task, unit, c: Any, idx: tuple | None) -> bool:
    """2.5.4 insert: a default value at an index of a 1-D array, or at a new collection key."""
    if type(c) is Coll:
        key = idx[0] if idx else ""
        if type(key) is not str or not key:
            raise E(70, "a collection key is a non-empty string")
        if key in c.d:
            return False
        if len(c.d) >= MAX_CONTAINER:
            raise E(40, "a variable holds at most 9999 values (2.5.4)")
        c.d[key] = unit.space.default(c.t, c.local, key)
        return True
    a = _growable(c, "insert")
    if idx is None:
        raise E(70, "insert needs an index")
    n = a.size()
    if idx[0] < -0.5:
        raise E(21, f"index {number_text(idx[0])}")
    i = int(idx[0] + 0.5)
    if i > n:
        raise E(20, f"index {i} for size {n}")
    if len(a.data) >= MAX_CONTAINER:
        raise E(40, "a variable holds at most 9999 values (2.5.4)")
    a.data.insert(a.off + i, unit.space.default(a.t))
    return True


def DELETE(task, c: Any, idx: tuple | None) -> bool:
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


def APPEND(task, unit, c: Any) -> None:
    """2.5.5 append: a default value at the end of a 1-D array."""
    a = _growable(c, "append")
    if len(a.data) >= MAX_CONTAINER:
        raise E(40, "a variable holds at most 9999 values (2.5.5)")
    a.data.append(unit.space.default(a.t))


def RESIZE(task, unit, c: Any, dim: float, size: float) -> None:
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
    default = unit.space.default
    if len(dims) == 1:
        if n < len(c.data):
            del c.data[n:]
        else:
            c.data.extend(default(c.t) for _ in range(n - len(c.data)))
        return
    old = c.data
    out = []
    if len(dims) == 2:
        for i in range(new[0]):
            for j in range(new[1]):
                out.append(old[i * dims[1] + j] if i < dims[0] and j < dims[1] else default(c.t))
    else:
        for i in range(new[0]):
            for j in range(new[1]):
                for k in range(new[2]):
                    inside = i < dims[0] and j < dims[1] and k < dims[2]
                    out.append(old[(i * dims[1] + j) * dims[2] + k] if inside else default(c.t))
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


_GETDATA_NAME = re.compile(r"^\s*(?:([A-Za-z]\w*):)?([A-Za-z]\w*)\s*(?:\[\s*([^\]]*)\])?\s*$")


def GETDATA(task, unit, spec: str, c: Any, idx: Any, t: str) -> float:
    """2.5.4 getData: copy the values of the variable named `spec` (of the same type) into the
    variable; -1 no such variable, -2 library not loaded, -3 index, -4 type or container."""
    m = _GETDATA_NAME.match(spec)
    if not m:
        return -1.0
    alias, name, index = m.groups()
    if alias:
        if alias not in unit.aliases or unit.aliases[alias] is None:
            return -2.0
        src = unit.aliases[alias].public_global(name)
    else:
        src = unit.globals.get(name)
    if src is None:
        return -1.0
    if getattr(src, "t", None) != t:
        return -4.0
    if type(src) is Coll:
        if index is None or c is not None and type(c) is not Coll:
            return -4.0
        key = index.strip().strip('"')
        if key not in src.d:
            return -3.0
        vals = [src.d[key]]
    else:
        start = 0
        if index:
            try:
                start = int(float(index))
            except ValueError:
                return -3.0
            if not 0 <= start < len(src.data):
                return -3.0
        vals = src.data[start:] if src.dims is None else src.data[start:start + 1]
        if c is None or type(c) is not Arr:
            vals = vals[:1]
    if c is None:  # an element: idx is the (container, key) pair
        cc, kk = idx
        store(cc, kk, vals[0])
        return 1.0
    if type(c) is Coll:
        key = idx[0] if idx else None
        if key is None or key not in c.d:
            return -3.0
        store(c.d, key, vals[0])
        return 1.0
    dst_start = c.off
    if idx is not None:
        dst_start = c.off + IX(idx[0], len(c.data) - c.off) if c.dims is None else c.off
    room = len(c.data) - dst_start
    n = min(room, len(vals)) if c.dims is None else 1
    for i in range(n):
        store(c.data, dst_start + i, vals[i])
    return float(n)


def register(registry) -> None:
    registry.inline("size", "isDefined", "insert", "delete", "append", "resize", "first", "last", "next", "prev",
                    "getData", chapter=__name__)
    registry.helpers(SIZE=SIZE, SIZE2=SIZE2, ISDEF=ISDEF, INSERT=INSERT, DELETE=DELETE, APPEND=APPEND, RESIZE=RESIZE,
                     CFIRST=CFIRST, CLAST=CLAST, CNEXT=CNEXT, CPREV=CPREV, GETDATA=GETDATA)
