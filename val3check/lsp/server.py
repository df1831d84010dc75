"""`val3check server`: the LSP wiring (pygls 2), stdio. The work is done in `features.py`.

Full document synchronisation (the editor sends the whole text on each change: VAL 3 program
files are small), diagnostics pushed on open, change and save, hover, definition and document
symbols. Positions are UTF-16 code units, LSP's default encoding.
"""

from __future__ import annotations

from lsprotocol import types as T
from pygls.lsp.server import LanguageServer
from pygls.uris import from_fs_path, to_fs_path

from .. import __version__
from .features import Session

_KINDS = {"program": T.SymbolKind.Function, "parameter": T.SymbolKind.Variable, "local": T.SymbolKind.Variable,
          "global": T.SymbolKind.Variable, "library": T.SymbolKind.Module, "type": T.SymbolKind.Struct}


def build() -> LanguageServer:
    server = LanguageServer("val3check", __version__, text_document_sync_kind=T.TextDocumentSyncKind.Full)
    session = Session()

    def publish(ls: LanguageServer, found: dict) -> None:
        for path, diags in found.items():
            ls.text_document_publish_diagnostics(T.PublishDiagnosticsParams(
                uri=from_fs_path(path),
                diagnostics=[T.Diagnostic(
                    range=T.Range(T.Position(d.line, d.character), T.Position(d.end_line, d.end_character)),
                    message=d.message, severity=T.DiagnosticSeverity(d.severity), code=d.code, source="val3check",
                ) for d in diags],
            ))
        while session.notes:
            ls.window_log_message(T.LogMessageParams(type=T.MessageType.Warning, message=session.notes.pop(0)))

    def text_of(ls: LanguageServer, uri: str) -> str:
        return ls.workspace.get_text_document(uri).source

    @server.feature(T.TEXT_DOCUMENT_DID_OPEN)
    def did_open(ls: LanguageServer, params: T.DidOpenTextDocumentParams) -> None:
        publish(ls, session.open(to_fs_path(params.text_document.uri), params.text_document.text))

    @server.feature(T.TEXT_DOCUMENT_DID_CHANGE)
    def did_change(ls: LanguageServer, params: T.DidChangeTextDocumentParams) -> None:
        uri = params.text_document.uri
        publish(ls, session.change(to_fs_path(uri), text_of(ls, uri)))

    @server.feature(T.TEXT_DOCUMENT_DID_SAVE)
    def did_save(ls: LanguageServer, params: T.DidSaveTextDocumentParams) -> None:
        uri = params.text_document.uri
        publish(ls, session.change(to_fs_path(uri), text_of(ls, uri)))

    @server.feature(T.TEXT_DOCUMENT_DID_CLOSE)
    def did_close(ls: LanguageServer, params: T.DidCloseTextDocumentParams) -> None:
        session.close(to_fs_path(params.text_document.uri))

    @server.feature(T.TEXT_DOCUMENT_HOVER)
    def hover(ls: LanguageServer, params: T.HoverParams) -> T.Hover | None:
        text = session.hover(to_fs_path(params.text_document.uri), params.position.line, params.position.character)
        if text is None:
            return None
        return T.Hover(contents=T.MarkupContent(kind=T.MarkupKind.Markdown, value=text))

    @server.feature(T.TEXT_DOCUMENT_DEFINITION)
    def definition(ls: LanguageServer, params: T.DefinitionParams) -> list[T.Location]:
        places = session.definition(to_fs_path(params.text_document.uri), params.position.line,
                                    params.position.character)
        return [T.Location(uri=from_fs_path(p.path), range=T.Range(T.Position(p.line, p.character),
                                                                    T.Position(p.line, p.character)))
                for p in places]

    @server.feature(T.TEXT_DOCUMENT_DOCUMENT_SYMBOL)
    def symbols(ls: LanguageServer, params: T.DocumentSymbolParams) -> list[T.DocumentSymbol]:
        def convert(s) -> T.DocumentSymbol:  # noqa: ANN001
            whole = T.Range(T.Position(s.line, 0), T.Position(max(s.end_line, s.line) + 1, 0))
            name = T.Range(T.Position(s.line, s.character), T.Position(s.line, s.character))
            return T.DocumentSymbol(name=s.name, detail=s.detail, kind=_KINDS[s.kind], range=whole,
                                    selection_range=name, children=[convert(c) for c in s.children])

        return [convert(s) for s in session.symbols(to_fs_path(params.text_document.uri))]

    return server


def main() -> None:
    build().start_io()
