"""The language server against hostile or broken clients (issue 21 M and N, issue 28 item 8):
what it reads, what it keeps, which URIs it answers, how it frames and answers every request,
a document that cannot be encoded, and the diagnostics of a closed document. In-process
(tests/lsp_session.py), except the framing through the real `val3check server` process."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from lsp_session import answers, frame, initialize, notification, published, request, run

from val3check.testing import write_app

pytest.importorskip("pygls", reason="the lsp extra is not installed (pip install -e '.[test]')")
ROOT = Path(__file__).resolve().parent.parent
POS = {"line": 0, "character": 0}


def _open(uri: str, text: str) -> bytes:
    return notification("textDocument/didOpen", {"textDocument": {"uri": uri, "languageId": "val3", "version": 1,
                                                                  "text": text}})


def _at(text: str, word: str) -> dict:
    lines = text.split("\n")
    n = next(i for i, line in enumerate(lines) if word in line)
    return {"line": n, "character": lines[n].index(word) + 1}


@pytest.fixture
def workspace(tmp_path):
    """A repository `ws` with an application, and beside it (outside) a secret VAL 3 program."""
    ws = tmp_path / "ws"
    (ws / ".git").mkdir(parents=True)
    app = write_app(ws, "begin\n  nCount = nCount + 1\n  call pick()\nend\n", name="Cell", globals_=["num nCount"],
                    programs={"pick": {"code": "begin\nend\n"}})
    secret = write_app(tmp_path / "outside", "begin\n  nSecret = 1\nend\n", name="Secret", globals_=["num nSecret"])
    return ws, app, secret


# ---- N: what is read, what is kept ---------------------------------------------------------------

def test_files_outside_the_workspace_are_not_read_for_hover_or_symbols(workspace):
    ws, app, secret = workspace
    os.symlink(secret / "start.pgx", ws / "link.pgx")  # a link in the workspace leading out
    os.symlink("/etc/passwd", ws / "passwd.pgx")
    targets = [(secret / "start.pgx").as_uri(), (ws / "link.pgx").as_uri(), (ws / "passwd.pgx").as_uri(),
               "file:///etc/passwd", "file:///proc/self/environ", "file:///dev/zero"]
    text = (secret / "start.pgx").read_text()
    chunks = [initialize(ws.as_uri())]
    for i, uri in enumerate(targets):
        chunks += [request(10 + i, "textDocument/hover", {"textDocument": {"uri": uri}, "position": _at(text, "nSecret")}),
                   request(20 + i, "textDocument/documentSymbol", {"textDocument": {"uri": uri}}),
                   request(30 + i, "textDocument/definition", {"textDocument": {"uri": uri},
                                                               "position": _at(text, "nSecret")})]
    # inside the workspace, a file the editor has not opened is answered
    chunks.append(request(40, "textDocument/documentSymbol", {"textDocument": {"uri": (app / "pick.pgx").as_uri()}}))
    _code, messages, server = run(*chunks)
    got = answers(messages)
    for i in range(len(targets)):
        assert got[10 + i]["result"] is None and got[20 + i]["result"] == [] and got[30 + i]["result"] == [], targets[i]
    assert [s["name"] for s in got[40]["result"]] == ["pick"]
    session = server.session
    assert session.texts == {}  # nothing the editor did not open is held as a document
    assert not any("Secret" in str(k) for k in session.read._items)


def test_texts_of_unopened_files_are_kept_within_a_byte_budget(workspace):
    ws, _app, _secret = workspace
    from val3check.lsp import features

    filler = "begin\n" + "".join(f"  // {'x' * 90} {i}\n" for i in range(600)) + "end\n"  # about 60 KB
    programs = {f"p{i}": {"code": filler} for i in range(8)}
    big = write_app(ws, "begin\nend\n", name="Big", programs=programs)
    from val3check.lsp.server import build

    server = build()
    server.session.read = features.Recent(150_000)
    uris = [(big / f"p{i}.pgx").as_uri() for i in range(8)]
    chunks = [initialize(ws.as_uri())]
    for i, uri in enumerate(uris):
        chunks.append(request(i + 1, "textDocument/hover", {"textDocument": {"uri": uri},
                                                            "position": {"line": 8, "character": 5}}))
    _code, messages, server = run(*chunks, server=server)
    assert all("error" not in m for m in answers(messages).values())
    session = server.session
    assert session.texts == {}
    assert 0 < session.read.used <= 150_000 and 0 < len(session.read) < 8
    assert 0 < session.unopened.used <= features.UNOPENED_BUDGET


# ---- N: every URI scheme -------------------------------------------------------------------------

def test_an_untitled_buffer_is_checked_from_its_text(workspace):
    ws, _app, _secret = workspace
    from val3check.testing import program_file

    text = program_file("start", "begin\n  if true\n    nX = 1\n  endFor\nend\n")
    uri = "untitled:Untitled-1"
    _code, messages, server = run(initialize(ws.as_uri()), _open(uri, text),
                                  request(1, "textDocument/documentSymbol", {"textDocument": {"uri": uri}}),
                                  request(2, "textDocument/hover", {"textDocument": {"uri": uri},
                                                                    "position": _at(text, "if true")}),
                                  request(3, "textDocument/documentSymbol",
                                          {"textDocument": {"uri": "untitled:Untitled-2"}}),  # never opened
                                  notification("textDocument/didClose", {"textDocument": {"uri": uri}}))
    first, last = published(messages, uri)
    errors = [d for d in first if d["severity"] == 1]
    assert [d["code"] for d in errors] == ["F101"]
    assert errors[0]["range"]["start"]["line"] == text.split("\n").index("  endFor")
    assert not [d for d in first if d["code"] in ("F001", "F008")]  # a buffer has no folder to look in
    assert last == []
    got = answers(messages)
    assert [s["name"] for s in got[1]["result"]] == ["start"]
    assert "error" not in got[2] and got[3]["result"] == []
    assert server.session.buffers._folder is None  # its stand-in removed with it


@pytest.mark.parametrize("uri", ["http://example.com/start.pgx", "https://x/y.pgx", "vscode-vfs://github/a/b.pgx",
                                 "git:/ws/start.pgx?ref", "file://otherhost/share/start.pgx", "file:start.pgx",
                                 "file:///tmp/a%00b.pgx", "file:", "", "not a uri"])
def test_every_uri_scheme_is_answered(workspace, uri):
    ws, app, _secret = workspace
    text = (app / "start.pgx").read_text()
    _code, messages, _server = run(
        initialize(ws.as_uri()), _open(uri, text),
        request(1, "textDocument/hover", {"textDocument": {"uri": uri}, "position": _at(text, "nCount")}),
        request(2, "textDocument/definition", {"textDocument": {"uri": uri}, "position": _at(text, "nCount")}),
        request(3, "textDocument/documentSymbol", {"textDocument": {"uri": uri}}),
        notification("textDocument/didChange", {"textDocument": {"uri": uri, "version": 2},
                                                "contentChanges": [{"text": text}]}),
        notification("textDocument/didSave", {"textDocument": {"uri": uri}}),
        notification("textDocument/didClose", {"textDocument": {"uri": uri}}),
        request(4, "textDocument/hover", {"textDocument": {"uri": (app / "start.pgx").as_uri()},
                                          "position": _at(text, "nCount")}))
    got = answers(messages)
    assert [got[i].get("result") for i in (1, 2, 3)] == [None, [], []], got
    assert "num nCount" in got[4]["result"]["contents"]["value"]  # and the server goes on
    assert not [m for m in messages if m.get("method") == "window/showMessage"], messages


# ---- N: every request gets an answer ---------------------------------------------------------------

def test_every_request_gets_an_answer(workspace):
    ws, app, _secret = workspace
    text = (app / "start.pgx").read_text()
    deep = b'{"jsonrpc": "2.0", "id": 7, "method": "textDocument/hover", "params": ' + b"[" * 100_000 + b"]" * 100_000 + b"}"
    hover = {"textDocument": {"uri": (app / "start.pgx").as_uri()}, "position": _at(text, "nCount")}
    _code, messages, _server = run(
        request(1, "textDocument/hover", hover),  # before initialize
        initialize(ws.as_uri()),
        request(2, "textDocument/hover", {"textDocument": {"uri": 5}}),  # invalid params
        request(3, "textDocument/hover", {"textDocument": {"uri": "file:///x.pgx"},
                                          "position": {"line": -1, "character": 0}}),
        request(4, "textDocument/hover", "params that are a string"),
        request(5, "no/suchMethod", {}),
        frame(b'{"jsonrpc": "2.0", "id": 6, "method": '),  # not JSON
        frame(deep),
        frame(b"[" * 100_000 + b"]" * 100_000),
        frame(b'[{"jsonrpc": "2.0", "id": 8, "method": "shutdown"}]'),  # a batch: LSP has none
        frame(b'{"jsonrpc": "2.0", "id": {"a": 1}, "method": "shutdown"}'),
        frame(b'{"jsonrpc": "1.0", "id": 9, "method": "shutdown"}'),
        frame(b'\xff\xfe{"jsonrpc": "2.0", "id": 10}'),
        frame(b'{"jsonrpc": "2.0", "id": 11, "method": "textDocument/hover", "params": {"n": ' + b"9" * 5000 + b"}}"),
        request(12, "textDocument/hover", hover),
        request(13, "shutdown"),
        request(14, "textDocument/hover", hover),
        notification("exit"))
    got = answers(messages)
    codes = {k: v.get("error", {}).get("code") for k, v in got.items()}
    assert codes[1] == -32002  # not initialized
    assert codes[2] == codes[3] == codes[4] == -32602
    assert codes[5] == -32601
    assert codes[7] == -32600 and "nests deeper" in got[7]["error"]["message"]
    assert codes[9] == -32600
    assert "num nCount" in got[12]["result"]["contents"]["value"]
    assert codes[13] is None and codes[14] == -32600  # after shutdown
    # what could not be tied to an id: the broken JSON, the deep array, the batch, the bad id,
    # the bytes that are not UTF-8, the 5000-digit number (more than Python parses)
    nulls = [m["error"]["code"] for m in messages if "method" not in m and m.get("id") is None]
    assert sorted(nulls) == sorted([-32700, -32700, -32600, -32600, -32700, -32700])
    assert _code == 0


# ---- M: framing, and a document that cannot be encoded ----------------------------------------------

@pytest.mark.parametrize("header", [b"Content-Length: abc", b"Content-Length: -5", b"Content-Length: 1e3",
                                    b"Content-Length: 99999999999999", b"Content-Type: text/plain", b"garbage",
                                    b"Content-Length: 10"])
def test_bad_framing_is_skipped_and_the_server_goes_on(workspace, header):
    ws, app, _secret = workspace
    bad = b'{"jsonrpc": "2.0", "id": 1, "method": "shutdown"}'
    hover = {"textDocument": {"uri": (app / "start.pgx").as_uri()},
             "position": _at((app / "start.pgx").read_text(), "nCount")}
    _code, messages, _server = run(initialize(ws.as_uri()), header + b"\r\n\r\n" + bad,
                                   request(2, "textDocument/hover", hover))
    got = answers(messages)
    assert "num nCount" in got[2]["result"]["contents"]["value"]
    if header.startswith(b"Content-Length: ") and header != b"Content-Length: 10":
        assert got[1]["error"]["code"] == -32700  # the request whose header was wrong is answered too


def test_framing_through_the_server_process(workspace):
    """The real `val3check server` over pipes: after `Content-Length: abc` it answers again."""
    ws, app, _secret = workspace
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    proc = subprocess.Popen([sys.executable, "-m", "val3check", "server"], cwd=ws, env=env, stdin=subprocess.PIPE,
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
    hover = {"textDocument": {"uri": (app / "start.pgx").as_uri()},
             "position": _at((app / "start.pgx").read_text(), "nCount")}
    out, _ = proc.communicate(initialize(ws.as_uri()) + b"Content-Length: abc\r\n\r\n"
                              + b'{"jsonrpc": "2.0", "id": 1, "method": "shutdown"}'
                              + request(2, "textDocument/hover", hover) + request(3, "shutdown")
                              + notification("exit"), timeout=120)
    from lsp_session import frames_of

    got = answers(frames_of(out))
    assert got[1]["error"]["code"] == -32700
    assert "num nCount" in got[2]["result"]["contents"]["value"]
    assert proc.returncode == 0


def test_a_lone_surrogate_in_one_document_leaves_the_others_checked(workspace):
    ws, app, _secret = workspace
    start, dtx = app / "start.pgx", app / "Cell.dtx"
    bad_text = start.read_text().replace("nCount + 1", "nCount + 1 // \ud800")
    other = write_app(ws, "begin\n  nY = 1\nend\n", name="Other")
    _code, messages, _server = run(initialize(ws.as_uri()), _open(start.as_uri(), bad_text),
                                   _open(dtx.as_uri(), dtx.read_text()),
                                   _open((other / "start.pgx").as_uri(), (other / "start.pgx").read_text()))
    bad = published(messages, start.as_uri())
    assert [d["code"] for d in bad[-1]] == ["F003"]  # the bad document, at its place
    assert bad[-1][0]["range"]["start"]["line"] == bad_text.split("\n").index(
        next(x for x in bad_text.split("\n") if "\ud800" in x))
    assert published(messages, dtx.as_uri()) == [[]]
    assert [d["code"] for d in published(messages, (other / "start.pgx").as_uri())[-1]] == ["N001"]
    assert not [m for m in messages if m.get("method") in ("window/showMessage", "window/logMessage")
                and "could not" in m["params"]["message"]]


# ---- issue 28 item 8: closing a document -------------------------------------------------------------

def test_closing_a_document_clears_its_diagnostics_and_rechecks_its_application(workspace):
    ws, app, _secret = workspace
    start, dtx = app / "start.pgx", app / "Cell.dtx"
    edited = start.read_text().replace("nCount + 1", "nMissing + 1")
    renamed = dtx.read_text().replace("nCount", "nTotal")
    _code, messages, _server = run(
        initialize(ws.as_uri()),
        _open(start.as_uri(), start.read_text()),
        _open(dtx.as_uri(), renamed),  # unsaved: start() now uses an undeclared nCount
        notification("textDocument/didClose", {"textDocument": {"uri": dtx.as_uri()}}),
        notification("textDocument/didChange", {"textDocument": {"uri": start.as_uri(), "version": 2},
                                                "contentChanges": [{"text": edited}]}),
        notification("textDocument/didClose", {"textDocument": {"uri": start.as_uri()}}))
    on_start = [[d["code"] for d in diags] for diags in published(messages, start.as_uri())]
    # opened clean; broken by the .dtx's unsaved text; clean again when the .dtx closes unsaved;
    # broken by its own unsaved text; cleared when it closes
    assert on_start == [[], ["N001", "N001"], [], ["N001"], []]
    assert published(messages, dtx.as_uri())[-1] == []
