"""Reading a TOML file that may be hostile: every failure is a `TomlError` at a line and column.

Every TOML file a user gives val3check (cell, scenario, sweep, configuration, robot file) is read
here. tomllib alone lets through, as something other than a TOMLDecodeError or not at all:

* an integer of more than 4,300 digits: Python's int-to-string limit raises a ValueError;
* tables or arrays nested hundreds deep: RecursionError (and our own walks would follow);
* a dotted key of thousands of parts (`a.a.a...`): tomllib takes quadratic time, a minute for
  80 KB, before it answers;
* integers beyond 64 bits, which TOML 1.0 says a reader must refuse (`float()` of one raises
  OverflowError later);
* bytes that are not UTF-8.

`loads` scans the text once before tomllib (linear: strings and comments skipped with `str.find`
and regular expressions that cannot backtrack) for nesting deeper than `MAX_DEPTH` and dotted keys
longer than `MAX_DEPTH` parts, then walks the data (iteratively) for integers beyond 64 bits.
"""

from __future__ import annotations

import re
from typing import Any

MAX_DEPTH = 64  # arrays and tables inside each other, or parts of a dotted key
_INT64 = 1 << 63
INT_DIGITS = 4300  # Python's int-to-string limit (sys.get_int_max_str_digits())

# What the scan stops at: the start of a string or a comment. Between two of them, brackets and
# dots are counted with str methods.
_STOP = re.compile(r"\"\"\"|'''|[\"'#]")
_BASIC_END = re.compile(r'\\.|["\n]', re.DOTALL)
_ML_BASIC_END = re.compile(r'\\.|"""', re.DOTALL)
_LITERAL_END = re.compile(r"['\n]")
_KEY_BREAK = re.compile(r"[=\[\]{},\n]")  # what ends a dotted key
_BRACKET = re.compile(r"[\[\]{}]")
_DIGITS = re.compile(r"[0-9][0-9_]*")


class TomlError(ValueError):
    """A TOML text that cannot be used: `line`, `col` (1-based; 0 when unknown) and `message`."""

    def __init__(self, line: int, col: int, message: str) -> None:
        super().__init__(f"{line}:{col}: {message}" if line else message)
        self.line, self.col, self.message = line, col, message


def decode(raw: bytes) -> str:
    """UTF-8 text (a leading byte-order mark is kept out), or TomlError at the first bad byte."""
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = raw.count(b"\n", 0, exc.start) + 1
        col = exc.start - (raw.rfind(b"\n", 0, exc.start) + 1) + 1
        raise TomlError(line, col, f"not UTF-8 (byte {exc.start})") from None


def load_bytes(raw: bytes, max_depth: int = MAX_DEPTH) -> tuple[dict, str]:
    """(data, text) of a TOML file's bytes; TomlError for anything that cannot be used."""
    text = decode(raw)
    return loads(text, max_depth), text


def loads(text: str, max_depth: int = MAX_DEPTH) -> dict:
    import tomllib

    _scan(text, max_depth)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        line, col, message = _decode_error(str(exc))
        raise TomlError(line, col, f"invalid TOML: {message}") from None
    except RecursionError:  # not reached after _scan; kept so that no input can raise it
        raise TomlError(0, 0, f"tables or arrays nested too deeply (at most {max_depth})") from None
    except ValueError:  # the int-to-string limit: an integer of more than 4,300 digits
        line, col = _long_integer(text)
        raise TomlError(line, col, f"an integer of more than {INT_DIGITS} digits: TOML integers are 64-bit "
                        f"(from -2^63 to 2^63 - 1)") from None
    _check_values(data, text, max_depth)
    return data


# ---- the scan before tomllib -----------------------------------------------------------------


def _position(text: str, i: int) -> tuple[int, int]:
    return text.count("\n", 0, i) + 1, i - (text.rfind("\n", 0, i) + 1) + 1


def _outside(text: str):
    """(start, end) spans of the text outside strings and comments, in order (linear)."""
    i, n = 0, len(text)
    while i < n:
        m = _STOP.search(text, i)
        if m is None:
            yield i, n
            return
        yield i, m.start()
        t, i = m.group(), m.end()
        if t == "#":
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif t == "'''":
            j = text.find("'''", i)
            i = n if j < 0 else j + 3
        elif t == '"""':
            while True:
                e = _ML_BASIC_END.search(text, i)
                if e is None:
                    i = n
                    break
                i = e.end()
                if e.group() == '"""':
                    break
        elif t == "'":
            e = _LITERAL_END.search(text, i)
            i = n if e is None else e.end()
        else:
            while True:
                e = _BASIC_END.search(text, i)
                if e is None:
                    i = n
                    break
                i = e.end()
                if e.group() in ('"', "\n"):
                    break
        # up to two more quotes may close a multi-line string: they are part of it
        while t in ('"""', "'''") and i < n and text[i] == t[0]:
            i += 1


def _scan(text: str, max_depth: int) -> None:
    """TomlError at the first bracket nested deeper than `max_depth`, or the first dotted key of
    more parts (dots counted between two of `= [ ] { } ,` and newlines, strings skipped)."""
    depth, dots, key_start = 0, 0, 0
    for start, end in _outside(text):
        for m in _BRACKET.finditer(text, start, end):
            depth += 1 if m.group() in "[{" else -1
            if depth > max_depth:
                line, col = _position(text, m.start())
                raise TomlError(line, col, f"tables or arrays nested too deeply (at most {max_depth})")
        pieces = _KEY_BREAK.split(text[start:end])  # each break is one character
        counts = [p.count(".") for p in pieces]
        counts[0] += dots
        if max(counts) > max_depth:
            k = next(i for i, c in enumerate(counts) if c > max_depth)
            at = key_start if k == 0 else start + sum(len(p) + 1 for p in pieces[:k])
            line, col = _position(text, at)
            raise TomlError(line, col, f"a dotted key of more than {max_depth} parts: nested too deeply")
        dots = counts[-1]
        if len(pieces) > 1:
            key_start = end - len(pieces[-1])


def _long_integer(text: str) -> tuple[int, int]:
    for start, end in _outside(text):
        for m in _DIGITS.finditer(text, start, end):
            if m.end() - m.start() > INT_DIGITS:
                return _position(text, m.start())
    return 0, 0


def _decode_error(message: str) -> tuple[int, int, str]:
    """tomllib's "Invalid value (at line 3, column 5)" as (3, 5, "Invalid value"), on one line."""
    m = re.search(r"\(at line (\d+), column (\d+)\)", message)
    text = re.sub(r"\s*\(at (?:line \d+, column \d+|end of document)\)", "", message) or "invalid TOML"
    text = "".join(c if c.isprintable() else repr(c)[1:-1] for c in text)[:200]
    return (int(m.group(1)), int(m.group(2)), text) if m else (0, 0, text)


# ---- the walk after tomllib --------------------------------------------------------------------


def _check_values(data: dict, text: str, max_depth: int) -> None:
    stack: list[tuple[Any, tuple]] = [(data, ())]
    while stack:
        value, path = stack.pop()
        if isinstance(value, dict):
            items = value.items()
        elif isinstance(value, list):
            items = enumerate(value)
        else:
            if isinstance(value, int) and not isinstance(value, bool) and not -_INT64 <= value < _INT64:
                _fail(text, path, f"the integer {_digits(value)} is beyond 64 bits: TOML integers are from "
                      f"-2^63 to 2^63 - 1")
            continue
        if len(path) >= max_depth:
            _fail(text, path, f"tables or arrays nested too deeply (at most {max_depth})")
        stack.extend((v, path + (k,)) for k, v in items)


def _digits(value: int) -> str:
    text = hex(value)
    return text if len(text) <= 24 else f"{text[:20]}... ({value.bit_length()} bits)"


def _fail(text: str, path: tuple, message: str) -> None:
    from .tomlpos import positions

    line, col = positions(text).at(path)
    raise TomlError(line, col, message)
