"""`val3check lint --fix` / `--diff`: the fixes that are certain, written byte for byte.

Two rules have one (their rule files say so under `fix`):

- N006 (name-case-mismatch): the name is written as it is declared. val3check found no
  declaration with the written case, only one with another case, so the rewritten name means
  what the controller means whether it compares names with or without case.
- S001 (unused-local): the `<Local>` element is removed (its whole line when it is alone on it):
  the program never mentions the local.

A fix never changes what the controller loads: adding a program file that sits unlisted beside an
application (F012) to its project would load a backup or a dead program into the controller, so
F012 only suggests it in its message (as ruff keeps unsafe fixes apart from safe ones). Nor is a
fix made from a guess (a library found by name, F016): such findings carry none.

Everything else in the file stays as it was, byte for byte: the encoding mark, line endings,
CDATA sections, escapes, blanks. An edit is made only where the bytes are what the finding
says (the name at its column, a `<Local name="...">` element at its position); the edited file
must still be well-formed XML, or none of its edits is made. Files that are not UTF-8 (UTF-16
with a byte-order mark) are not edited.
"""

from __future__ import annotations

import bisect
import difflib
import os
import re

from .diagnostics import Diagnostic
from .light_dataclass import dataclass, field

MAX_SIZE = 64 * 1024 * 1024
_IDENT = re.compile(r"[A-Za-z0-9_]")


@dataclass(slots=True)
class Edit:
    start: int  # byte offsets in the file
    end: int
    text: bytes
    code: str


@dataclass(slots=True)
class FixPlan:
    edits: dict[str, list[Edit]] = field(default_factory=dict)  # absolute path -> edits
    originals: dict[str, bytes] = field(default_factory=dict)
    not_fixed: list[tuple[Diagnostic, str]] = field(default_factory=list)  # and why

    @property
    def count(self) -> int:
        return sum(len(e) for e in self.edits.values())

    def result(self, path: str) -> bytes:
        data = self.originals[path]
        out, at = [], 0
        for e in sorted(self.edits[path], key=lambda e: (e.start, e.end)):
            out += [data[at:e.start], e.text]
            at = e.end
        out.append(data[at:])
        return b"".join(out)

    def diff(self, shown) -> str:  # noqa: ANN001
        """A unified diff of every file changed; `shown(path)` names a file as reports do."""
        chunks = []
        for path in sorted(self.edits):
            old = self.originals[path].decode("utf-8", "surrogateescape").splitlines(keepends=True)
            new = self.result(path).decode("utf-8", "surrogateescape").splitlines(keepends=True)
            name = shown(path)
            chunks.append("".join(difflib.unified_diff(old, new, f"a/{name}", f"b/{name}")))
        return "".join(c if c.endswith("\n") else c + "\n\\ No newline at end of file\n" for c in chunks if c)

    def write(self) -> None:
        """Each changed file replaced at once (a temporary file renamed over it), its mode kept."""
        for path in sorted(self.edits):
            tmp = path + ".val3check-fix"
            mode = os.stat(path).st_mode & 0o7777
            with open(tmp, "wb") as fh:
                fh.write(self.result(path))
            os.chmod(tmp, mode)
            os.replace(tmp, path)


_LINE_END = re.compile(rb"\n|\r(?!\n)")  # as expat counts lines: LF, CRLF or a lone CR


class _File:
    """A file's bytes with the positions of its lines (as expat counts them)."""

    def __init__(self, data: bytes) -> None:
        self.data = data
        self.bom = 3 if data.startswith(b"\xef\xbb\xbf") else 0
        self.starts = [0] + [m.end() for m in _LINE_END.finditer(data)]

    def line_of(self, offset: int) -> int:
        """The 1-based line holding byte `offset`."""
        return bisect.bisect_right(self.starts, offset)

    def line_span(self, line: int) -> tuple[int, int, int]:
        """(start, end of its text, start of the next line) of 1-based `line`, in bytes."""
        start = self.starts[line - 1] + (self.bom if line == 1 else 0)
        nxt = self.starts[line] if line < len(self.starts) else len(self.data)
        end = nxt
        while end > start and self.data[end - 1] in (0x0A, 0x0D):
            end -= 1
        return start, end, nxt

    def line_text(self, line: int) -> str:
        start, end, _ = self.line_span(line)
        return self.data[start:end].decode("utf-8")

    def offset(self, line: int, col: int) -> int:
        """Byte offset of 1-based code-point column `col` of `line`."""
        start, _, _ = self.line_span(line)
        return start + len(self.line_text(line)[: col - 1].encode("utf-8"))


def _read(path: str) -> bytes | None:
    from .confine import Refused, Roots, read_bytes

    try:
        data = read_bytes(path, Roots.user_given(), MAX_SIZE)
    except Refused:
        return None
    if data.startswith((b"\xff\xfe", b"\xfe\xff")):
        return None
    try:
        data.decode("utf-8")
    except UnicodeDecodeError:
        return None
    return data


def _rename(d: Diagnostic, f: _File) -> Edit | str:
    written, declared = d.fix[1], d.fix[2]
    before = d.fix[3] if len(d.fix) > 3 else ""
    after = d.fix[4] if len(d.fix) > 4 else ""
    if d.line < 1 or d.line >= len(f.starts) + 1 or written.lower() != declared.lower():
        return "the name is not where the finding says"
    text = f.line_text(d.line)
    stop = d.end_col - 1 if d.end_line == d.line and d.end_col else len(text)
    for m in re.finditer(re.escape(written), text[: max(stop, d.col - 1 + len(written))]):
        p = m.start()
        if p < d.col - 1:
            continue
        if (p > 0 and _IDENT.match(text[p - 1])) or (m.end() < len(text) and _IDENT.match(text[m.end()])):
            continue
        if before and (p == 0 or text[p - 1] != before):
            continue
        if after and text[m.end():m.end() + 1] != after:
            continue
        start = f.offset(d.line, p + 1)
        return Edit(start, start + len(written.encode("utf-8")), declared.encode("utf-8"), d.code)
    return "the name is not where the finding says"


def _remove_element(d: Diagnostic, f: _File) -> Edit | str:
    name = d.fix[1]
    if d.line < 1 or d.line > len(f.starts) or d.col < 1:
        return "the element is not where the finding says"
    at = f.offset(d.line, d.col)
    m = re.compile(rb"<([A-Za-z_][\w.-]*)\b").match(f.data, at)
    if m is None:
        return "the element is not where the finding says"
    tag = m.group(1)
    close = f.data.find(b">", at)
    if close < 0:
        return "the element is not closed"
    element = f.data[at:close + 1]
    if not re.search(rb"""\bname\s*=\s*(["'])""" + re.escape(name.encode()) + rb"\1", element):
        return "the element does not declare that name"
    end = close + 1
    if not element.endswith(b"/>"):
        # its closing tag must be the next tag: anything else means it holds other elements (and
        # looking no further than the next '<' keeps a file of unclosed elements linear)
        nxt_tag = f.data.find(b"<", end)
        closing = re.compile(rb"</" + re.escape(tag) + rb"\s*>").match(f.data, nxt_tag) if nxt_tag >= 0 else None
        if closing is None:
            return "the element holds other elements"
        end = closing.end()
    start_line, _, _ = f.line_span(d.line)
    end_line = f.line_of(end)  # the line holding the end of the element
    _, text_end, nxt = f.line_span(end_line)
    if not f.data[start_line:at].strip() and not f.data[end:text_end].strip():
        return Edit(start_line, nxt, b"", d.code)  # alone on its lines: they go with it
    return Edit(at, end, b"", d.code)


def plan(findings: list[Diagnostic]) -> FixPlan:
    """The edits that fix `findings` (paths as on disk) whose fix is certain."""
    from .loading.xmlread import parse

    fp = FixPlan()
    files: dict[str, _File | None] = {}

    def file_of(path: str) -> _File | None:
        if path not in files:
            data = _read(path)
            files[path] = _File(data) if data is not None else None
        return files[path]

    per_file: dict[str, list[Edit]] = {}
    for d in findings:
        if not d.fix:
            continue
        kind = d.fix[0]
        f = file_of(d.path)
        if f is None:
            fp.not_fixed.append((d, "the file is not UTF-8 or cannot be read"))
            continue
        made = _rename(d, f) if kind == "rename" else _remove_element(d, f) if kind == "remove-element" else "unknown fix"
        if isinstance(made, str):
            fp.not_fixed.append((d, made))
        else:
            per_file.setdefault(d.path, []).append(made)
    for path, edits in sorted(per_file.items()):
        edits.sort(key=lambda e: (e.start, e.end))
        kept: list[Edit] = []
        for e in edits:
            if kept and e.start < kept[-1].end:
                continue  # overlapping: the next run fixes it
            if kept and (e.start, e.end, e.text) == (kept[-1].start, kept[-1].end, kept[-1].text):
                continue
            kept.append(e)
        fp.originals[path] = files[path].data
        fp.edits[path] = kept
        root, _problems = parse(_strip_bom(fp.result(path)), path)
        if root is None:  # never leave a file that does not read (should not happen)
            fp.not_fixed += [(d, "the fixed file would not be well-formed XML") for d in findings if d.path == path]
            del fp.edits[path]
    return fp


def _strip_bom(data: bytes) -> bytes:
    return data[3:] if data.startswith(b"\xef\xbb\xbf") else data
