"""What the language server knows, without the protocol: diagnostics of the open documents,
hover, definition and document symbols. `server.py` only translates to and from LSP.

The program being edited is checked in the context of its application from the unsaved text
of every open document (the loader's overlay, read through the same file gate as files on
disk), with the configuration found from its folder, as `val3check lint` would. Positions here
are 0-based lines and UTF-16 code units, as LSP counts them by default; val3check's own columns
count code points and are converted with the text of the line.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from pathlib import Path

from ..confine import Roots
from ..diagnostics import Diagnostic, Severity
from ..lint import LintRun, run
from ..loading.model import Application, Container, Data, Local, Parameter, Program, Workspace
from ..rules import codes
from .documents import VAL3_EXTENSIONS, Buffers, Recent, locate

# what is kept for files the editor has not opened: their checks, weighed by the bytes of the
# files each read, and their texts
UNOPENED_BUDGET = 16 * 1024 * 1024
READ_BUDGET = 32 * 1024 * 1024
MAX_READ = 16 * 1024 * 1024  # as `max-file-size` by default
# findings about the files an untitled buffer names (it has no folder to find them in)
BUFFER_CONTEXT_CODES = frozenset({codes.FILE_NOT_FOUND, codes.NO_APPLICATION_FOUND})
_WORD = re.compile(r"\$?[A-Za-z_][A-Za-z0-9_]*(?::[A-Za-z_][A-Za-z0-9_]*)?")
SEVERITY = {Severity.ERROR: 1, Severity.WARNING: 2, Severity.INFO: 3}  # LSP DiagnosticSeverity


@dataclass
class EditorDiagnostic:
    line: int  # 0-based; UTF-16 columns
    character: int
    end_line: int
    end_character: int
    severity: int  # 1 error, 2 warning, 3 information
    code: str
    message: str


@dataclass
class Place:
    path: str
    line: int  # 0-based, UTF-16
    character: int


@dataclass
class Symbol:
    name: str
    kind: str  # "program", "parameter", "local", "global", "library", "type"
    detail: str
    line: int
    character: int
    end_line: int
    children: list["Symbol"] = field(default_factory=list)


def utf16(text: str, codepoints: int) -> int:
    """UTF-16 code units of the first `codepoints` characters of `text`."""
    head = text[:codepoints]
    return len(head) + sum(1 for ch in head if ord(ch) > 0xFFFF) + max(0, codepoints - len(text))


def codepoints(text: str, units: int) -> int:
    """Characters of `text` that the first `units` UTF-16 code units hold."""
    n = 0
    for i, ch in enumerate(text):
        n += 2 if ord(ch) > 0xFFFF else 1
        if n > units:
            return i
    return len(text)


def _declared(container: Container, sizes: tuple[int, ...], dims: int = 0) -> str:
    if container is Container.COLLECTION:
        return '[""]'
    if dims:
        return "[" + "," * (dims - 1) + "]"
    if sizes and any(s != 1 for s in sizes):
        return "[" + ",".join(str(s) for s in sizes) + "]"
    return ""


class Session:
    """The open documents of an editor and what the last check of each application found.

    Documents are named by their URI (documents.py); a file the editor has not opened is only
    read when it lies in the workspace folders or the configured roots (`roots`), through the
    file gate of `val3check.confine`, and what is read of such files is kept within a budget."""

    def __init__(self) -> None:
        self.texts: dict[str, str] = {}  # open document (absolute path; a buffer's stand-in) -> unsaved text
        self.uris: dict[str, str] = {}  # open document path -> the editor's URI for it
        self.runs: dict[str, LintRun] = {}  # open document path -> the last check of its application
        self.configured: dict[str, list[str]] = {}  # open document path -> the disk roots of its configuration
        self.folders: list[str] = []  # the workspace folders
        self.folder_uris: list[str] = []
        self.unopened = Recent(UNOPENED_BUDGET)  # checks made for files not opened
        self.read = Recent(READ_BUDGET)  # texts of files not opened, by (real path, mtime, size)
        self.buffers = Buffers()
        self.notes: list[str] = []  # configuration problems, for the editor's log

    # -- documents --------------------------------------------------------------------------

    def set_folders(self, uris: list[str]) -> None:
        self.folder_uris = list(uris)
        self.folders = [w.path for w in map(locate, uris) if w.kind == "file"]

    def roots(self, *more: str) -> Roots:
        """Where files the editor has not opened may be read: the workspace folders and the
        configured roots (`disk-roots` of the open documents' configurations)."""
        return Roots([*self.folders, *(r for rs in self.configured.values() for r in rs), *more])

    def path_of(self, uri: str) -> str | None:
        """The file of `uri` (a buffer's stand-in when it is open), or None (nothing to read)."""
        where = locate(uri)
        if where.kind == "file":
            return where.path
        return self.buffers.known(uri) if where.kind == "buffer" else None

    def text_of(self, uri: str) -> str | None:
        """The text of open document `uri`, None when it is not open."""
        path = self.path_of(uri)
        return self.texts.get(path) if path is not None else None

    def uri_of(self, path: str) -> str:
        if path in self.uris:
            return self.uris[path]
        return self.buffers.uri_of(path) or Path(path).as_uri()

    def open(self, uri: str, text: str) -> dict[str, list[EditorDiagnostic]]:
        """Diagnostics by URI of the open documents that the check of `uri`'s application covers."""
        where = locate(uri)
        if where.kind == "elsewhere":
            return {}
        path = where.path if where.kind == "file" else self.buffers.path(uri, text)
        self.texts[path] = text
        self.uris[path] = uri
        self.unopened = Recent(UNOPENED_BUDGET)  # a check of a file not opened may have read this one
        return self.check(path)

    def change(self, uri: str, text: str) -> dict[str, list[EditorDiagnostic]]:
        return self.open(uri, text)

    def close(self, uri: str) -> dict[str, list[EditorDiagnostic]]:
        """An empty list for the closed document (it is no longer checked: LSP clients keep what
        was published last), and the diagnostics of the open documents of its application,
        checked again without its unsaved text."""
        path = self.path_of(uri)
        out: dict[str, list[EditorDiagnostic]] = {uri: []}
        if path is None or path not in self.texts:
            return out
        outcome = self.runs.pop(path, None)
        for table in (self.texts, self.uris, self.configured):
            table.pop(path, None)
        if locate(uri).kind == "buffer":
            self.buffers.close(uri)
        self.unopened = Recent(UNOPENED_BUDGET)
        if outcome is not None:
            files = _files(outcome)
            for other in [p for p in self.texts if p in files]:
                if self.uri_of(other) not in out:  # not covered by the check of another one
                    out.update(self.check(other))
        return out

    def _settings(self, path: str):  # noqa: ANN202
        from ..config import ConfigError, Settings, find_config, load_settings

        if self.buffers.holds(path):
            return Settings()
        try:
            found = find_config(os.path.dirname(path), warn=self.notes.append)
            return load_settings(found) if found else Settings()
        except ConfigError as exc:
            self.notes.append(str(exc))
            return Settings()

    def _run(self, path: str) -> LintRun | None:
        """Lint the application of `path` from the unsaved texts (None when `path` is not a VAL 3
        file on disk)."""
        if not path.lower().endswith(VAL3_EXTENSIONS) or not os.path.isfile(path):
            return None
        settings = self._settings(path)
        if path in self.texts:
            self.configured[path] = list(settings.disk_roots)
        # a lone surrogate (which no file can hold) becomes bytes that are not UTF-8: that
        # document gets F003 at its place, and no other document is affected
        overlay = {p: t.encode("utf-8", "surrogatepass") for p, t in self.texts.items()}
        return run([path], settings, overlay=overlay)

    def check(self, path: str) -> dict[str, list[EditorDiagnostic]]:
        """Diagnostics by URI of every open document of the application of open document `path`
        (an empty list clears a document's old ones)."""
        outcome = self._run(path)
        if outcome is None:
            return {self.uri_of(path): []}
        files = _files(outcome)
        out: dict[str, list[EditorDiagnostic]] = {p: [] for p in self.texts if p in files or p == path}
        for p in out:
            self.runs[p] = outcome
        buffer = self.buffers.holds(path)
        for raw, shown in zip(outcome.findings, outcome.result.diagnostics):
            where = os.path.abspath(raw.path)
            if buffer and raw.code in BUFFER_CONTEXT_CODES:
                continue  # a buffer has no folder: the files it names cannot be looked for
            if buffer and where == os.path.dirname(path):
                where = path  # a lone program's application is its folder
            if where in out:
                out[where].append(self._diagnostic(raw, shown.severity or Severity.ERROR, where))
        return {self.uri_of(p): diags for p, diags in out.items()}

    def _lines(self, path: str, roots: Roots | None = None) -> list[str]:
        text = self.texts.get(path)
        if text is None:
            text = self._read(path, roots or self.roots())
        elif text.startswith("\ufeff"):
            text = text[1:]
        return [x[:-1] if x.endswith("\r") else x for x in re.split(r"\n|\r(?!\n)", text.replace("\r\n", "\n"))]

    def _read(self, path: str, roots: Roots) -> str:
        """The text of a file the editor has not opened, through the file gate; "" if refused."""
        from ..confine import Refused, check, read_bytes

        try:
            real = check(path, roots)
            st = os.stat(real)
        except (Refused, OSError, ValueError):
            return ""
        key = f"{real}\0{st.st_mtime_ns}\0{st.st_size}"
        text = self.read.get(key)
        if text is None:
            try:
                data = read_bytes(real, roots, MAX_READ)
            except Refused:
                return ""
            text = data.decode("utf-8-sig", "replace")
            self.read.put(key, text, len(data))
        return text

    def _diagnostic(self, d: Diagnostic, severity: Severity, path: str) -> EditorDiagnostic:
        lines = self._lines(path)

        def text(n: int) -> str:
            return lines[n - 1] if 0 < n <= len(lines) else ""

        if d.line < 1:  # the whole file: its first line
            return EditorDiagnostic(0, 0, 0, len(text(1)), SEVERITY[severity], d.code, d.message)
        line = text(d.line)
        if d.col < 1:  # the whole line
            start = len(line) - len(line.lstrip())
            return EditorDiagnostic(d.line - 1, utf16(line, start), d.line - 1, utf16(line, len(line)),
                                    SEVERITY[severity], d.code, d.message)
        end_line = d.end_line if d.end_line and d.end_line >= d.line else d.line
        end_col = d.end_col if d.end_col and (end_line > d.line or d.end_col > d.col) else d.col + 1
        return EditorDiagnostic(d.line - 1, utf16(line, d.col - 1), end_line - 1, utf16(text(end_line), end_col - 1),
                                SEVERITY[severity], d.code, d.message)

    # -- what is under the cursor -----------------------------------------------------------

    def _context(self, path: str) -> tuple[Workspace, Application] | None:
        outcome = self.runs.get(path)
        if outcome is None and path in self.texts:
            self.check(path)
            outcome = self.runs.get(path)
        if outcome is None:
            outcome = self._unopened_run(path)
        if outcome is None:
            return None
        ws = outcome.workspace
        for key in ws.targets:
            app = ws.apps[key]
            if any(os.path.abspath(f) == path for f in app.files):
                return ws, app
        for app in ws.apps.values():
            if any(os.path.abspath(f) == path for f in app.files):
                return ws, app
        return None

    def _unopened_run(self, path: str) -> LintRun | None:
        """The check of a file the editor has not opened, if it may be read (a VAL 3 file in the
        workspace folders or the configured roots); a few are kept."""
        from ..confine import Refused, check

        if not path.lower().endswith(VAL3_EXTENSIONS):
            return None
        try:
            check(path, self.roots())
        except Refused:
            return None
        outcome = self.unopened.get(path)
        if outcome is None:
            outcome = self._run(path)
            if outcome is not None:
                self.unopened.put(path, outcome, max(1, sum(_size(f) for f in _files(outcome))))
        return outcome

    @staticmethod
    def _program_at(app: Application, path: str, line: int) -> Program | None:
        """The program whose `<Program>` element holds file `line` (1-based)."""
        best = None
        for p in app.programs.values():
            if os.path.abspath(p.origin.path) == path and p.origin.line <= line:
                if best is None or p.origin.line > best.origin.line:
                    best = p
        return best

    def _word(self, path: str, line0: int, character: int) -> tuple[str, int, int] | None:
        lines = self._lines(path)
        if not 0 <= line0 < len(lines):
            return None
        text = lines[line0]
        at = codepoints(text, character)
        for m in _WORD.finditer(text):
            if m.start() <= at <= m.end():
                return m.group(), m.start(), at
        return None

    def _resolve(self, uri: str, line0: int, character: int):  # noqa: ANN202, C901
        """(kind, object, application) of the name under the cursor, or None."""
        path = self.path_of(uri)
        found = self._context(path) if path is not None else None
        if found is None:
            return None
        word = self._word(path, line0, character)
        if word is None:
            return None
        ws, app = found
        text, start, at = word
        if text.startswith("$"):
            return None
        if ":" in text:
            alias, name = text.split(":", 1)
            ref = app.libraries.get(alias) or next((r for a, r in app.libraries.items() if a.lower() == alias.lower()), None)
            lib = ws.apps.get(ref.resolved) if ref is not None and ref.resolved else None
            if at <= start + len(alias):
                return ("library", ref, lib) if ref is not None else None
            if lib is None:
                return None
            return self._in_application(lib, name, None, public_only=True)
        program = self._program_at(app, path, line0 + 1)
        hit = self._in_application(app, text, program)
        if hit is not None:
            return hit
        from ..language.instructions import lookup

        ins = lookup(text)
        if ins is not None:
            return "instruction", ins, None
        return None

    @staticmethod
    def _in_application(app: Application, name: str, program: Program | None, public_only: bool = False):  # noqa: ANN205
        low = name.lower()
        if program is not None:
            for p in program.parameters:
                if p.name.lower() == low:
                    return "parameter", (p, program), app
            for x in program.locals:
                if x.name.lower() == low:
                    return "local", (x, program), app
        for n, d in app.data.items():
            if n.lower() == low and (not public_only or d.access != "private"):
                return "global", d, app
        for n, p in app.programs.items():
            if n.lower() == low and (not public_only or p.access != "private"):
                return "program", p, app
        return None

    def hover(self, uri: str, line0: int, character: int) -> str | None:
        """Markdown: the declaration and type of the name under the cursor, or an instruction's
        signatures and manual section."""
        hit = self._resolve(uri, line0, character)
        if hit is None:
            return None
        kind, obj, app = hit
        if kind == "instruction":
            sigs = []
            for o in obj.overloads:
                params = ", ".join(f"{p.type}{'&' if p.ref else ''} {p.name}" for p in o.params)
                sigs.append(f"{o.returns} {obj.name}({params})" if o.returns != "void" else f"{obj.name}({params})")
            sections = ", ".join(dict.fromkeys([obj.section, *obj.sections])) if obj.sections else obj.section
            body = "```val3\n" + "\n".join(sigs) + "\n```\n\n" + (obj.summary or "")
            return body.rstrip() + f"\n\nVAL 3 reference manual, section {sections}."
        if kind == "library":
            where = os.path.basename(obj.resolved) if obj.resolved else "not found"
            return f"```val3\n{obj.alias}: library {obj.path}\n```\n\nLibrary declared in the project ({where})."
        if kind in ("parameter", "local"):
            item, program = obj
            if kind == "parameter":
                p: Parameter = item
                decl = f"{p.type}{'&' if p.by_reference else ''} {p.name}{_declared(p.container, (), p.dimensions)}"
                what = f"parameter of {program.name}()" + (", by reference" if p.by_reference else ", by value")
            else:
                x: Local = item
                decl = f"{x.type} {x.name}{_declared(x.container, x.sizes)}"
                what = f"local of {program.name}()"
            return f"```val3\n{decl}\n```\n\n{what} ({_at(item.origin.path, item.origin.line)})"
        if kind == "global":
            d: Data = obj
            decl = f"{d.access} {d.type} {d.name}{_declared(d.container, d.sizes)}"
            extra = f"; linked to {d.link}" if d.link else ""
            return (
                f"```val3\n{decl}\n```\n\nglobal of {app.name} ({_at(d.origin.path, d.origin.line)}, "
                f"{len(d.values)} value{'s' if len(d.values) != 1 else ''} written{extra})"
            )
        if kind == "program":
            p: Program = obj
            params = ", ".join(
                f"{x.type}{'&' if x.by_reference else ''} {x.name}{_declared(x.container, (), x.dimensions)}"
                for x in p.parameters
            )
            desc = f"\n\n{p.description.strip()}" if p.description.strip() else ""
            return (
                f"```val3\n{p.access} program {p.name}({params})\n```\n\nprogram of {app.name} "
                f"({_at(p.origin.path, p.origin.line)}){desc}"
            )
        return None

    def definition(self, uri: str, line0: int, character: int) -> list[Place]:
        """Where the name under the cursor is declared (paths: `uri_of` gives their URIs)."""
        hit = self._resolve(uri, line0, character)
        if hit is None:
            return []
        kind, obj, _app = hit
        if kind == "instruction":
            return []
        if kind == "library":
            return [Place(obj.resolved, 0, 0)] if obj.resolved else []
        origin = obj[0].origin if kind in ("parameter", "local") else obj.origin
        # the file was read by the check: within its roots (the loader's), which the gate applies again
        path = self.path_of(uri)
        found = self._context(path) if path is not None else None
        loaded = found[0].roots.folders if found is not None and found[0].roots is not None else []
        lines = self._lines(os.path.abspath(origin.path), self.roots(*loaded))
        text = lines[origin.line - 1] if 0 < origin.line <= len(lines) else ""
        return [Place(os.path.abspath(origin.path), max(origin.line - 1, 0), utf16(text, max(origin.col - 1, 0)))]

    def symbols(self, uri: str) -> list[Symbol]:
        """The programs of a .pgx (with their parameters and locals), the globals of a .dtx,
        the libraries and user types of a .pjx."""
        path = self.path_of(uri)
        found = self._context(path) if path is not None else None
        if found is None:
            return []
        _ws, app = found
        out: list[Symbol] = []
        mine = [p for p in app.programs.values() if os.path.abspath(p.origin.path) == path]
        for p in sorted(mine, key=lambda p: p.origin.line):
            last = p.code_map.line_starts[-1].line if p.code_map.line_starts else p.origin.line
            sym = Symbol(p.name, "program", f"{p.access} program", p.origin.line - 1, p.origin.col - 1, last - 1)
            for x in p.parameters:
                sym.children.append(
                    Symbol(
                        x.name,
                        "parameter",
                        f"{x.type}{'&' if x.by_reference else ''}",
                        x.origin.line - 1,
                        x.origin.col - 1,
                        x.origin.line - 1,
                    )
                )
            for x in p.locals:
                sym.children.append(
                    Symbol(x.name, "local", x.type, x.origin.line - 1, x.origin.col - 1, x.origin.line - 1)
                )
            out.append(sym)
        for d in app.data.values():
            if os.path.abspath(d.origin.path) == path:
                out.append(
                    Symbol(
                        d.name, "global", f"{d.access} {d.type}", d.origin.line - 1, d.origin.col - 1, d.origin.line - 1
                    )
                )
        if os.path.abspath(app.path) == path:
            for ref in app.libraries.values():
                out.append(
                    Symbol(ref.alias, "library", ref.path, ref.origin.line - 1, ref.origin.col - 1, ref.origin.line - 1)
                )
            for ref in app.types.values():
                out.append(
                    Symbol(ref.name, "type", ref.path, ref.origin.line - 1, ref.origin.col - 1, ref.origin.line - 1)
                )
        return out


def _files(outcome: LintRun) -> set[str]:
    return {os.path.abspath(f) for app in outcome.workspace.apps.values() for f in app.files}


def _size(path: str) -> int:
    try:
        return os.stat(path).st_size
    except (OSError, ValueError):
        return 0


def _at(path: str, line: int) -> str:
    return f"{os.path.basename(path)}:{line}"
