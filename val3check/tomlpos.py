"""Where each key and value of a TOML document is: `tomllib` parses but keeps no positions.

`positions(text)` walks a document that `tomllib` has already accepted and records, for every key
path, the line and column of the key and of its value. Paths are tuples of keys and array indices,
as the parsed data is indexed: `("obstacle", 2, "size", 1)` is the second number of `size` in the
third `[[obstacle]]`. Columns count characters from 1. The walk is a small TOML lexer (strings,
comments, arrays over several lines, inline tables, dotted keys, `[table]` and `[[array]]`
headers); on anything it does not follow it stops, and lookups fall back to the nearest known
ancestor, so a position is always found. It is linear in the text: it stops at a key path deeper
than `MAX_PATH` (building ever longer paths would be quadratic; tomlfile refuses such documents).
"""

from __future__ import annotations

import bisect
import re

Path = tuple  # tuple[str | int, ...]
MAX_PATH = 200  # keys and indices in one path: deeper documents are refused by tomlfile anyway

_BARE = re.compile(r"[A-Za-z0-9_-]+")
_SCALAR = re.compile(r"[^,\]}#\r\n]+")
_ESC = {"b": "\b", "t": "\t", "n": "\n", "f": "\f", "r": "\r", '"': '"', "\\": "\\", "e": "\x1b"}


class Positions:
    """Line and column (1-based) of keys and values by path; `at(path)` for a diagnostic."""

    def __init__(self) -> None:
        self.keys: dict[Path, tuple[int, int]] = {}
        self.values: dict[Path, tuple[int, int]] = {}

    def at(self, path: Path, key: bool = False) -> tuple[int, int]:
        """Where to point for `path`: its value (or its key with key=True), else the closest
        ancestor that is known, else (1, 1)."""
        p = tuple(path)
        while p:
            first, second = (self.keys, self.values) if key else (self.values, self.keys)
            if p in first:
                return first[p]
            if p in second:
                return second[p]
            p = p[:-1]
        return (1, 1)


def positions(text: str) -> Positions:
    out = Positions()
    try:
        _Walker(text, out).document()
    except (_Stop, IndexError, ValueError, RecursionError):
        pass
    return out


class _Stop(Exception):
    pass


class _Walker:
    def __init__(self, text: str, out: Positions) -> None:
        self.s = text
        self.i = 0
        self.out = out
        self.starts = [0] + [m.end() for m in re.finditer(r"\n", text)]
        self.aot: dict[Path, int] = {}  # array-of-tables path -> number of elements so far

    # ---- positions --------------------------------------------------------------------------------

    def pos(self, i: int) -> tuple[int, int]:
        line = bisect.bisect_right(self.starts, i)
        return line, i - self.starts[line - 1] + 1

    # ---- lexing helpers ---------------------------------------------------------------------------

    def peek(self, n: int = 1) -> str:
        return self.s[self.i:self.i + n]

    def blanks(self) -> None:
        """Spaces and tabs."""
        s, i = self.s, self.i
        while i < len(s) and s[i] in " \t":
            i += 1
        self.i = i

    def blanks_lines(self) -> None:
        """Spaces, newlines and comments (between statements and inside arrays)."""
        s = self.s
        while self.i < len(s):
            c = s[self.i]
            if c in " \t\r\n":
                self.i += 1
            elif c == "#":
                j = s.find("\n", self.i)
                self.i = len(s) if j < 0 else j
            else:
                break

    def expect(self, c: str) -> None:
        if self.s[self.i:self.i + len(c)] != c:
            raise _Stop
        self.i += len(c)

    # ---- keys -------------------------------------------------------------------------------------

    def simple_key(self) -> tuple[str, int]:
        start = self.i
        c = self.peek()
        if c == '"':
            return self.basic_string(), start
        if c == "'":
            self.i += 1
            j = self.s.index("'", self.i)
            k = self.s[self.i:j]
            self.i = j + 1
            return k, start
        m = _BARE.match(self.s, self.i)
        if not m:
            raise _Stop
        self.i = m.end()
        return m.group(0), start

    def dotted_key(self) -> list[tuple[str, int]]:
        parts = [self.simple_key()]
        while len(parts) <= MAX_PATH:
            self.blanks()
            if self.peek() != ".":
                return parts
            self.i += 1
            self.blanks()
            parts.append(self.simple_key())
        raise _Stop

    def basic_string(self) -> str:
        self.expect('"')
        out = []
        s = self.s
        while True:
            c = s[self.i]
            if c == '"':
                self.i += 1
                return "".join(out)
            if c == "\\":
                e = s[self.i + 1]
                if e in _ESC:
                    out.append(_ESC[e])
                    self.i += 2
                elif e in "uU":
                    n = 4 if e == "u" else 8
                    out.append(chr(int(s[self.i + 2:self.i + 2 + n], 16)))
                    self.i += 2 + n
                else:
                    raise _Stop
                continue
            if c == "\n":
                raise _Stop
            out.append(c)
            self.i += 1

    # ---- document ---------------------------------------------------------------------------------

    def document(self) -> None:
        table: Path = ()
        while True:
            self.blanks_lines()
            if self.i >= len(self.s):
                return
            if self.peek(2) == "[[":
                start = self.i
                self.i += 2
                self.blanks()
                keys = self.dotted_key()
                self.blanks()
                self.expect("]]")
                table = self.resolve([k for k, _ in keys], array=True)
                self.out.keys[table] = self.pos(start)
                self.out.keys.setdefault(table[:-1], self.pos(keys[-1][1]))
            elif self.peek() == "[":
                start = self.i
                self.i += 1
                self.blanks()
                keys = self.dotted_key()
                self.blanks()
                self.expect("]")
                table = self.resolve([k for k, _ in keys], array=False)
                self.out.keys.setdefault(table, self.pos(start))
            else:
                self.keyval(table)
            self.blanks()
            if self.peek() == "#":
                self.blanks_lines()
            elif self.i < len(self.s) and self.peek() not in "\r\n":
                raise _Stop

    def resolve(self, keys: list[str], array: bool) -> Path:
        """The data path of a header: intermediate arrays of tables mean their last element."""
        if len(keys) > MAX_PATH:
            raise _Stop
        path: Path = ()
        for n, k in enumerate(keys):
            path = path + (k,)
            last = n == len(keys) - 1
            if last and array:
                count = self.aot.get(path, 0)
                self.aot[path] = count + 1
                path = path + (count,)
            elif path in self.aot:
                path = path + (self.aot[path] - 1,)
        return path

    def keyval(self, table: Path) -> None:
        keys = self.dotted_key()
        if len(table) + len(keys) > MAX_PATH:
            raise _Stop
        path = table
        for k, start in keys:
            path = path + (k,)
            self.out.keys.setdefault(path, self.pos(start))
        self.blanks()
        self.expect("=")
        self.blanks()
        self.value(path)

    def value(self, path: Path) -> None:
        if len(path) > MAX_PATH:
            raise _Stop
        self.out.values[path] = self.pos(self.i)
        s = self.s
        c = self.peek()
        if s.startswith('"""', self.i):
            j = self.i + 3
            while True:
                j = s.index('"""', j)
                if s[j - 1] == "\\" and not _even_backslashes(s, j - 1):
                    j += 1
                    continue
                break
            while s.startswith('"', j + 3):  # up to two quotes may close the content
                j += 1
            self.i = j + 3
        elif s.startswith("'''", self.i):
            j = s.index("'''", self.i + 3)
            while s.startswith("'", j + 3):
                j += 1
            self.i = j + 3
        elif c == '"':
            self.basic_string()
        elif c == "'":
            self.i = s.index("'", self.i + 1) + 1
        elif c == "[":
            self.i += 1
            n = 0
            while True:
                self.blanks_lines()
                if self.peek() == "]":
                    self.i += 1
                    return
                self.value(path + (n,))
                n += 1
                self.blanks_lines()
                if self.peek() == ",":
                    self.i += 1
        elif c == "{":
            self.i += 1
            while True:
                self.blanks()
                if self.peek() == "}":
                    self.i += 1
                    return
                self.keyval(path)
                self.blanks()
                if self.peek() == ",":
                    self.i += 1
        else:
            m = _SCALAR.match(s, self.i)
            if not m:
                raise _Stop
            self.i = m.start() + len(m.group(0).rstrip(" \t"))


def _even_backslashes(s: str, j: int) -> bool:
    """True when the run of backslashes ending at s[j] has an even length."""
    n = 0
    while j >= 0 and s[j] == "\\":
        n += 1
        j -= 1
    return n % 2 == 0
