"""`val3check server`: the LSP wiring (pygls 2), stdio. The work is done in `features.py`.

Full document synchronisation (the editor sends the whole text on each change: VAL 3 program
files are small), diagnostics pushed on open, change and save, cleared on close; hover,
definition and document symbols. Positions are UTF-16 code units, LSP's default encoding.

Messages are read by `wire.py`, not by pygls's reader: a broken frame is skipped and the
server goes on, and every request is answered (docs/fuzzing.md). pygls's document store is not
used: the session keeps the texts the editor sent, and reads nothing on a client's say-so.
"""

from __future__ import annotations

import functools
import logging
import sys
from typing import Any, BinaryIO

from lsprotocol import types as T
from pygls.io_ import StdoutWriter
from pygls.lsp.server import LanguageServer
from pygls.protocol import LanguageServerProtocol, default_converter, lsp_method
from pygls.workspace import TextDocument

from .. import __version__
from . import wire
from .features import Session

_KINDS = {"program": T.SymbolKind.Function, "parameter": T.SymbolKind.Variable, "local": T.SymbolKind.Variable,
          "global": T.SymbolKind.Variable, "library": T.SymbolKind.Module, "type": T.SymbolKind.Struct}


class _Protocol(LanguageServerProtocol):
    """pygls's protocol without its document store (which reads a file from disk when a change
    names a document it does not hold): the handlers get the notifications as they come."""

    def _user(self, method: str, params: Any):  # noqa: ANN202
        handler = self.fm.features.get(method)
        if handler is not None:
            yield handler, (params,), None

    @lsp_method(T.TEXT_DOCUMENT_DID_OPEN)
    def lsp_text_document__did_open(self, params: T.DidOpenTextDocumentParams):  # noqa: ANN201
        yield from self._user(T.TEXT_DOCUMENT_DID_OPEN, params)

    @lsp_method(T.TEXT_DOCUMENT_DID_CHANGE)
    def lsp_text_document__did_change(self, params: T.DidChangeTextDocumentParams):  # noqa: ANN201
        yield from self._user(T.TEXT_DOCUMENT_DID_CHANGE, params)

    @lsp_method(T.TEXT_DOCUMENT_DID_CLOSE)
    def lsp_text_document__did_close(self, params: T.DidCloseTextDocumentParams):  # noqa: ANN201
        yield from self._user(T.TEXT_DOCUMENT_DID_CLOSE, params)


def apply_changes(text: str, changes: list) -> str:
    """`text` after the changes of a didChange: whole texts, or ranges in UTF-16 units."""
    for change in changes:
        if isinstance(change, T.TextDocumentContentChangeWholeDocument):
            text = change.text
        else:  # a range, though the server asked for whole texts
            doc = TextDocument("untitled:change", source=text,
                               sync_kind=T.TextDocumentSyncKind.Incremental)
            doc.apply_change(change)
            text = doc.source
    return text


@functools.lru_cache(maxsize=1)
def _converter():  # noqa: ANN202
    """pygls's converter, made once: cattrs writes its (un)structuring code on first use, a
    tenth of a second that every server built in this process (the tests') would pay again."""
    return default_converter()


def build() -> LanguageServer:
    server = LanguageServer("val3check", __version__, text_document_sync_kind=T.TextDocumentSyncKind.Full,
                            protocol_cls=_Protocol, converter_factory=_converter)
    session = Session()
    server.session = session  # type: ignore[attr-defined]

    def log(ls: LanguageServer, message: str, kind: T.MessageType = T.MessageType.Warning) -> None:
        ls.window_log_message(T.LogMessageParams(type=kind, message=message))

    def publish(ls: LanguageServer, uri: str, work) -> None:  # noqa: ANN001
        try:
            found = work()
        except Exception as exc:  # noqa: BLE001 - one document's check fails: said, and the others go on
            log(ls, f"val3check could not check {uri}: {type(exc).__name__}: {exc}", T.MessageType.Error)
            found = {}
        for doc, diags in found.items():
            ls.text_document_publish_diagnostics(T.PublishDiagnosticsParams(
                uri=doc,
                diagnostics=[T.Diagnostic(
                    range=T.Range(T.Position(d.line, d.character), T.Position(d.end_line, d.end_character)),
                    message=d.message, severity=T.DiagnosticSeverity(d.severity), code=d.code, source="val3check",
                ) for d in diags],
            ))
        while session.notes:
            log(ls, session.notes.pop(0))

    @server.feature(T.INITIALIZE)
    def initialize(ls: LanguageServer, params: T.InitializeParams) -> None:
        folders = [f.uri for f in params.workspace_folders or []]
        if not folders and params.root_uri:
            folders = [params.root_uri]
        elif not folders and params.root_path:
            from pathlib import Path

            folders = [Path(params.root_path).absolute().as_uri()] if params.root_path.strip() else []
        session.set_folders(folders)

    @server.feature(T.WORKSPACE_DID_CHANGE_WORKSPACE_FOLDERS)
    def folders_changed(ls: LanguageServer, params: T.DidChangeWorkspaceFoldersParams) -> None:
        gone = {f.uri for f in params.event.removed}
        current = [u for u in session.folder_uris if u not in gone] + [f.uri for f in params.event.added]
        session.set_folders(current)

    @server.feature(T.TEXT_DOCUMENT_DID_OPEN)
    def did_open(ls: LanguageServer, params: T.DidOpenTextDocumentParams) -> None:
        doc = params.text_document
        publish(ls, doc.uri, lambda: session.open(doc.uri, doc.text))

    @server.feature(T.TEXT_DOCUMENT_DID_CHANGE)
    def did_change(ls: LanguageServer, params: T.DidChangeTextDocumentParams) -> None:
        uri = params.text_document.uri
        old = session.text_of(uri)
        if old is None:
            log(ls, f"didChange of a document that is not open: ignored ({uri})")
            return
        publish(ls, uri, lambda: session.change(uri, apply_changes(old, params.content_changes)))

    @server.feature(T.TEXT_DOCUMENT_DID_SAVE)
    def did_save(ls: LanguageServer, params: T.DidSaveTextDocumentParams) -> None:
        uri = params.text_document.uri
        text = session.text_of(uri)
        if text is not None:
            publish(ls, uri, lambda: session.change(uri, text))

    @server.feature(T.TEXT_DOCUMENT_DID_CLOSE)
    def did_close(ls: LanguageServer, params: T.DidCloseTextDocumentParams) -> None:
        uri = params.text_document.uri
        publish(ls, uri, lambda: session.close(uri))

    @server.feature(T.TEXT_DOCUMENT_HOVER)
    def hover(ls: LanguageServer, params: T.HoverParams) -> T.Hover | None:
        text = session.hover(params.text_document.uri, params.position.line, params.position.character)
        if text is None:
            return None
        return T.Hover(contents=T.MarkupContent(kind=T.MarkupKind.Markdown, value=text))

    @server.feature(T.TEXT_DOCUMENT_DEFINITION)
    def definition(ls: LanguageServer, params: T.DefinitionParams) -> list[T.Location]:
        places = session.definition(params.text_document.uri, params.position.line, params.position.character)
        return [T.Location(uri=session.uri_of(p.path), range=T.Range(T.Position(p.line, p.character),
                                                                      T.Position(p.line, p.character)))
                for p in places]

    @server.feature(T.TEXT_DOCUMENT_DOCUMENT_SYMBOL)
    def symbols(ls: LanguageServer, params: T.DocumentSymbolParams) -> list[T.DocumentSymbol]:
        def convert(s) -> T.DocumentSymbol:  # noqa: ANN001
            whole = T.Range(T.Position(s.line, 0), T.Position(max(s.end_line, s.line) + 1, 0))
            name = T.Range(T.Position(s.line, s.character), T.Position(s.line, s.character))
            return T.DocumentSymbol(name=s.name, detail=s.detail, kind=_KINDS[s.kind], range=whole,
                                    selection_range=name, children=[convert(c) for c in s.children])

        return [convert(s) for s in session.symbols(params.text_document.uri)]

    @server.feature(T.SHUTDOWN)
    def shutdown(ls: LanguageServer, params: None) -> None:
        session.buffers.clear()

    return server


class _Writer(StdoutWriter):
    """pygls's writer; `exit` closes it, which leaves the caller's stream open."""

    def close(self) -> None:
        self._stdout.flush()


def serve(server: LanguageServer, stdin: BinaryIO, stdout: BinaryIO) -> int:
    """Answer the messages of `stdin` on `stdout` until `exit` or the end of the input; the
    exit code: 0 after shutdown and exit, 1 otherwise (LSP 3.17, `exit`)."""
    # every problem is answered to the editor or logged to it (window/logMessage); pygls's
    # own log would repeat it on standard error
    logging.getLogger("pygls").setLevel(logging.CRITICAL)
    protocol = server.protocol
    protocol.set_writer(_Writer(stdout))
    frames, gate = wire.Frames(stdin), wire.Gate()

    def send(message: dict) -> None:
        stdout.write(wire.frame(message))
        stdout.flush()

    def note(message: str) -> None:
        if gate.initialized and not gate.shut_down:
            protocol.notify(T.WINDOW_LOG_MESSAGE, T.LogMessageParams(type=T.MessageType.Warning,
                                                                      message=f"val3check server: {message}"))
        else:
            print(f"val3check server: {message}", file=sys.stderr, flush=True)

    try:
        while True:
            item = frames.next()
            if item is None:
                return 0 if gate.shut_down else 1
            if isinstance(item, wire.Problem):
                answer = gate.answer_problem(item)
                if answer is not None:
                    send(answer)
                else:
                    note(item.reason)
                continue
            checked = gate.check(item)
            if checked.answer is not None:
                send(checked.answer)
            if checked.note and (checked.answer is None or checked.answer["id"] is None):
                note(checked.note)  # what the client cannot tie to a request of its own
            if checked.message is not None:
                _deliver(protocol, gate, checked.message, send, note)
    except SystemExit as exc:  # `exit`
        return exc.code if isinstance(exc.code, int) else 0
    except (BrokenPipeError, ConnectionResetError):
        return 1
    finally:
        server.session.buffers.clear()  # type: ignore[attr-defined]


def _deliver(protocol: LanguageServerProtocol, gate: wire.Gate, value: dict, send, note) -> None:  # noqa: ANN001
    method, request = value.get("method"), "id" in value and "method" in value
    try:
        message = protocol.structure_message(value)
    except Exception as exc:  # noqa: BLE001 - the params do not fit the method
        cause = exc.__cause__ or exc
        why = f"{method}: invalid params ({_reason(cause)})"
        if request:
            send(wire.error(value.get("id"), wire.INVALID_PARAMS, why))
        else:
            note(why)
        return
    if request and getattr(message, "id", None) is None:
        send(wire.error(value.get("id"), wire.INVALID_REQUEST, f"{method} is a notification: it takes no id"))
        return
    if method == T.INITIALIZE:
        gate.initialized = True
    elif method == T.SHUTDOWN:
        gate.shut_down = True
    try:
        protocol.handle_message(message)
    except Exception as exc:  # noqa: BLE001 - pygls answers a handler's errors; this is a last guard
        if request:
            send(wire.error(value.get("id"), wire.INTERNAL_ERROR, f"{method}: {type(exc).__name__}: {exc}"))
        else:
            note(f"{method}: {type(exc).__name__}: {exc}")


def _reason(exc: BaseException) -> str:
    """The first leaf of a cattrs validation error: what did not fit, and where."""
    notes = getattr(exc, "__notes__", None) or []
    subs = getattr(exc, "exceptions", None)
    if subs:
        return _reason(subs[0])
    text = f"{type(exc).__name__}: {exc}"
    return (f"{notes[0]}: " if notes else "") + text[:200]


def main() -> int:
    return serve(build(), sys.stdin.buffer, sys.stdout.buffer)
