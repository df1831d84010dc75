"""The language server through a real LSP session over stdio (issue 16, editors): initialize,
didOpen with an error, diagnostics at the right range, hover, definition, document symbols,
didChange from unsaved text, shutdown. The client below speaks JSON-RPC with Content-Length
headers, as editors do; nothing of the server is imported."""

from __future__ import annotations

import json
import os
import queue
import shutil
import subprocess
import sys
import threading
from pathlib import Path
from urllib.parse import unquote, urlparse

import pytest

from val3check.testing import write_app

ROOT = Path(__file__).resolve().parent.parent
pytest.importorskip("pygls", reason="the lsp extra is not installed (pip install -e '.[test]')")


class Client:
    def __init__(self, cwd: Path) -> None:
        env = dict(os.environ, PYTHONPATH=str(ROOT))
        self.proc = subprocess.Popen([sys.executable, "-m", "val3check", "server"], cwd=cwd, env=env,
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        self.messages: queue.Queue = queue.Queue()
        self.next_id = 0
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self) -> None:
        out = self.proc.stdout
        while True:
            headers = {}
            while True:
                line = out.readline()
                if not line:
                    return
                if line in (b"\r\n", b"\n"):
                    break
                key, _, value = line.decode("ascii").partition(":")
                headers[key.strip().lower()] = value.strip()
            self.messages.put(json.loads(out.read(int(headers["content-length"]))))

    def send(self, message: dict) -> None:
        body = json.dumps({"jsonrpc": "2.0", **message}).encode("utf-8")
        self.proc.stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
        self.proc.stdin.flush()

    def notify(self, method: str, params: dict) -> None:
        self.send({"method": method, "params": params})

    def request(self, method: str, params: dict) -> object:
        self.next_id += 1
        self.send({"id": self.next_id, "method": method, "params": params})
        msg = self.wait(lambda m: m.get("id") == self.next_id and "method" not in m)
        assert "error" not in msg, msg
        return msg["result"]

    def wait(self, match, timeout: float = 60) -> dict:
        pending = []
        try:
            while True:
                msg = self.messages.get(timeout=timeout)
                if match(msg):
                    return msg
                pending.append(msg)
        finally:
            for m in pending:
                self.messages.put(m)

    def diagnostics(self, uri: str) -> list[dict]:
        msg = self.wait(lambda m: m.get("method") == "textDocument/publishDiagnostics" and m["params"]["uri"] == uri)
        return msg["params"]["diagnostics"]


def _uri(path: Path) -> str:
    return path.resolve().as_uri()


def _path(uri: str) -> Path:
    return Path(unquote(urlparse(uri).path))


START = 'begin\n  sText = "😀" + sMissing\n  call pick(nCount)\n  putln(lib:sName)\n  nCount = nCount + 1\nend\n'


@pytest.fixture
def cell(tmp_path):
    folder = write_app(tmp_path, START, name="Cell", globals_=["num nCount", "string sText"],
                       programs={"pick": {"params": ["num& x_nCount"], "locals": ["num l_nDone"],
                                          "code": "begin\n  l_nDone = x_nCount\nend\n"}})
    pjx = (folder / "Cell.pjx").read_text()
    (folder / "Cell.pjx").write_text(pjx.replace(
        "<Libraries />", '<Libraries>\n    <Library alias="lib" path="Disk://Lib/Lib.pjx" autoload="true" />\n  </Libraries>'))
    lib = write_app(tmp_path, "begin\nend\n", name="Lib", globals_=["string sName", "private num nHidden"])
    return folder, lib


def test_a_session(cell):
    folder, lib = cell
    client = Client(folder.parent)
    try:
        init = client.request("initialize", {"processId": os.getpid(), "rootUri": _uri(folder.parent),
                                             "capabilities": {}})
        caps = init["capabilities"]
        assert caps["hoverProvider"] and caps["definitionProvider"] and caps["documentSymbolProvider"]
        assert init["serverInfo"]["name"] == "val3check"
        client.notify("initialized", {})

        start = folder / "start.pgx"
        uri = _uri(start)
        text = start.read_text(encoding="utf-8")
        client.notify("textDocument/didOpen", {"textDocument": {"uri": uri, "languageId": "val3", "version": 1,
                                                                "text": text}})
        diags = client.diagnostics(uri)
        assert [(d["code"], d["severity"], d["source"]) for d in diags] == [("N001", 1, "val3check")]
        # line 2 of the code is line 5 of the file (0-based 4); sMissing follows an emoji, two UTF-16 units
        line = text.split("\n")[4]
        col = line.index("sMissing")  # code points
        assert diags[0]["range"] == {"start": {"line": 4, "character": col + 1},
                                     "end": {"line": 4, "character": col + 1 + len("sMissing")}}

        def at(word: str, nth: int = 0, offset: int = 1) -> dict:
            lines = text.split("\n")
            hits = [(n, ln.index(word)) for n, ln in enumerate(lines) if word in ln]
            n, c = hits[nth]
            units = len(lines[n][:c].encode("utf-16-le")) // 2
            return {"textDocument": {"uri": uri}, "position": {"line": n, "character": units + offset}}

        hover = client.request("textDocument/hover", at("nCount = nCount"))
        assert "num nCount" in hover["contents"]["value"] and "global of Cell" in hover["contents"]["value"]
        hover = client.request("textDocument/hover", at("putln"))
        assert "putln(string sTexte)" in hover["contents"]["value"] and "section 4.3" in hover["contents"]["value"]
        hover = client.request("textDocument/hover", at("sName"))
        assert "string sName" in hover["contents"]["value"] and "global of Lib" in hover["contents"]["value"]

        where = client.request("textDocument/definition", at("pick"))
        assert [_path(w["uri"]) for w in where] == [(folder / "pick.pgx").resolve()]
        assert where[0]["range"]["start"]["line"] == 2  # the <Program> element
        where = client.request("textDocument/definition", at("sName"))
        assert _path(where[0]["uri"]) == (lib / "Lib.dtx").resolve()
        where = client.request("textDocument/definition", at("lib:", offset=0))
        assert _path(where[0]["uri"]) == (lib / "Lib.pjx").resolve()

        pick = folder / "pick.pgx"
        client.notify("textDocument/didOpen", {"textDocument": {"uri": _uri(pick), "languageId": "val3", "version": 1,
                                                                "text": pick.read_text()}})
        assert client.diagnostics(_uri(pick)) == []
        assert [d["code"] for d in client.diagnostics(uri)] == ["N001"]  # its application's open documents too
        symbols = client.request("textDocument/documentSymbol", {"textDocument": {"uri": _uri(pick)}})
        assert [(s["name"], [c["name"] for c in s["children"]]) for s in symbols] == [("pick", ["x_nCount", "l_nDone"])]

        # an unsaved change fixes the error: checked from the editor's text, not the disk
        fixed = text.replace(" + sMissing", "")
        client.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": 2},
                                                 "contentChanges": [{"text": fixed}]})
        assert client.diagnostics(uri) == []
        assert "sMissing" in start.read_text()  # the file on disk is untouched
        # and one in the library document breaks the use in start(): the library's unsaved text counts
        lib_dtx = lib / "Lib.dtx"
        client.notify("textDocument/didOpen", {"textDocument": {"uri": _uri(lib_dtx), "languageId": "xml",
                                                                "version": 1,
                                                                "text": lib_dtx.read_text().replace("sName", "sTitle")}})
        client.diagnostics(_uri(lib_dtx))
        client.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": 3},
                                                 "contentChanges": [{"text": fixed}]})
        assert [d["code"] for d in client.diagnostics(uri)] == ["L010"]

        assert client.request("shutdown", None) is None
        client.notify("exit", None)
        assert client.proc.wait(timeout=30) == 0
    finally:
        if client.proc.poll() is None:
            client.proc.kill()


def test_without_the_extra_the_server_says_which_to_install(tmp_path, monkeypatch, capsys):
    from val3check import cli, lsp

    monkeypatch.setattr(lsp, "missing_packages", lambda: ["pygls"])
    assert cli.main(["server"]) == 2
    assert "pip install 'val3check[lsp]'" in capsys.readouterr().err


_NVIM_CHECK = """
vim.wait(60000, function() return #vim.diagnostic.get(0) > 0 end, 100)
local out = { vim.bo.filetype }
for _, d in ipairs(vim.diagnostic.get(0)) do
  table.insert(out, string.format("%d:%d %s", d.lnum + 1, d.col + 1, d.message))
end
io.stdout:write(table.concat(out, "\\n") .. "\\n")
vim.cmd("qa!")
"""


@pytest.mark.skipif(shutil.which("nvim") is None, reason="Neovim is not installed")
def test_the_neovim_snippet_for_older_versions(tmp_path):
    """docs/editors.md's init.lua for Neovim 0.7 to 0.10, in the Neovim installed (Debian 12: 0.7.2)."""
    import re

    text = (ROOT / "docs" / "editors.md").read_text(encoding="utf-8")
    block = re.search(r"Neovim 0\.7 to 0\.10;[^\n]*-->\n```lua\n(.*?)```", text, re.S).group(1)
    (tmp_path / "init.lua").write_text(block)
    (tmp_path / "check.lua").write_text(_NVIM_CHECK)
    repo = tmp_path / "cell"
    (repo / ".git").mkdir(parents=True)
    write_app(repo, "begin\n  nY = 1\nend\n", globals_=["num nX"])
    env = dict(os.environ, PATH=str(Path(sys.executable).parent) + os.pathsep + os.environ["PATH"],
               PYTHONPATH=str(ROOT), XDG_CONFIG_HOME=str(tmp_path), XDG_DATA_HOME=str(tmp_path),
               XDG_STATE_HOME=str(tmp_path))
    r = subprocess.run(["nvim", "--headless", "-u", str(tmp_path / "init.lua"), "Example/start.pgx",
                        "-c", f"luafile {tmp_path / 'check.lua'}"], cwd=repo, env=env, capture_output=True,
                       text=True, timeout=120)
    lines = r.stdout.strip().splitlines()
    assert lines[:1] == ["val3"], r.stdout + r.stderr
    assert any(line.startswith("5:3 undefined variable nY") for line in lines[1:]), r.stdout + r.stderr
