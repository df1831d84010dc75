"""The language server in-process, for the hostile tests and the fuzz suite: bytes in (LSP
frames, well formed or not), the messages it wrote out. Deterministic: the server reads the
whole input, answering as it goes, then ends (code 1 without `exit`, as LSP says)."""

from __future__ import annotations

import io
import json
import re

_LENGTH = re.compile(rb"Content-Length: (\d+)\r\n(?:[^\r\n]+\r\n)*?\r\n")


class _Out(io.BytesIO):
    def close(self) -> None:  # `exit` closes the output stream: keep what was written
        pass


def frame(message: dict | bytes, length: bytes | None = None) -> bytes:
    body = message if isinstance(message, bytes) else json.dumps(message).encode("utf-8")
    return b"Content-Length: " + (str(len(body)).encode() if length is None else length) + b"\r\n\r\n" + body


def request(msg_id, method: str, params=None) -> bytes:  # noqa: ANN001
    return frame({"jsonrpc": "2.0", "id": msg_id, "method": method, "params": params})


def notification(method: str, params=None) -> bytes:  # noqa: ANN001
    return frame({"jsonrpc": "2.0", "method": method, "params": params})


def initialize(root_uri: str | None = None, msg_id: int = 0) -> bytes:
    return (request(msg_id, "initialize", {"processId": None, "rootUri": root_uri, "capabilities": {}})
            + notification("initialized", {}))


def frames_of(data: bytes) -> list[dict]:
    """The messages the server wrote: each must be a well-formed frame of JSON."""
    out, at = [], 0
    while at < len(data):
        m = _LENGTH.match(data, at)
        assert m, data[at:at + 200]
        n = int(m.group(1))
        body = data[m.end():m.end() + n]
        assert len(body) == n
        out.append(json.loads(body))
        at = m.end() + n
    return out


def run(*chunks: bytes, server=None):  # noqa: ANN001, ANN201
    """(exit code, messages written, server) of a session fed `chunks`."""
    from val3check.lsp.server import build, serve

    server = server or build()
    out = _Out()
    code = serve(server, io.BytesIO(b"".join(chunks)), out)
    return code, frames_of(out.getvalue()), server


def answers(messages: list[dict]) -> dict:
    """Responses by id (an id answered twice fails)."""
    found: dict = {}
    for m in messages:
        if "method" not in m:
            assert m.get("id") not in found or m.get("id") is None, f"answered twice: {m}"
            found[m.get("id")] = m
    return found


def published(messages: list[dict], uri: str) -> list[list[dict]]:
    """Every diagnostics list published for `uri`, in order."""
    return [m["params"]["diagnostics"] for m in messages
            if m.get("method") == "textDocument/publishDiagnostics" and m["params"]["uri"] == uri]
