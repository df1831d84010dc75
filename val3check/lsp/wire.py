"""LSP's base protocol read defensively: frames from a byte stream that may be broken or
hostile, and the JSON-RPC checks every message passes before pygls sees it (docs/fuzzing.md).

A message is `Content-Length: N` (other headers ignored), an empty line, then N bytes of UTF-8
JSON. A header block that is not that (a length of `abc` or `-5`, more than `MAX_BODY`, no
length at all, a block longer than `MAX_HEADER`) is reported and skipped: reading resumes at
the next `Content-Length:` of the stream, so one bad frame costs that message only. Nothing
here reads more than `MAX_BODY` plus `MAX_HEADER` bytes ahead.

Every request gets an answer: -32700 when its body is not JSON (or not UTF-8), -32600 when it
is not a JSON-RPC request or nests deeper than `MAX_DEPTH`, -32602 when its params do not fit
the method (`Checked.invalid_params`), -32002 before `initialize`, -32600 after `shutdown`.
JSON-RPC 2.0 section 5.1: the id is null when it cannot be read; the id of a message too deep
to parse is read from its top level when it is there.
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass
from typing import Any, BinaryIO

MAX_BODY = 64 * 1024 * 1024  # a whole document in a didOpen, JSON-escaped
MAX_HEADER = 8 * 1024  # bytes of one header block
MAX_DEPTH = 64  # LSP's own messages nest about ten deep
SALVAGE = 1024 * 1024  # the id of a message that cannot be parsed is looked for in its first megabyte

PARSE_ERROR, INVALID_REQUEST, METHOD_NOT_FOUND, INVALID_PARAMS, INTERNAL_ERROR = -32700, -32600, -32601, -32602, -32603
SERVER_NOT_INITIALIZED = -32002

_LENGTH = re.compile(rb"content-length[ \t]*:", re.I)
_END = re.compile(rb"\r?\n\r?\n")
_DIGITS = re.compile(rb"[ \t]*(\d{1,12})[ \t]*")


@dataclass
class Problem:
    """A frame that was skipped, and why; `salvaged`: the JSON object found in the bytes
    skipped, when there was one (the body of a message whose header was wrong)."""

    reason: str
    salvaged: Any = None


class Frames:
    """The bodies of the messages of `stream` (a binary file: `read1` or `read`), in order."""

    def __init__(self, stream: BinaryIO) -> None:
        self._read = getattr(stream, "read1", None) or stream.read
        self.buf = bytearray()
        self.eof = False
        self._scanned = 0  # the bytes of `buf` already searched for a header, less a margin
        self._bad_header: str | None = None  # the header just skipped: its body is what follows

    def _more(self) -> bool:
        if self.eof:
            return False
        chunk = self._read(65536)
        if not chunk:
            self.eof = True
            return False
        self.buf += chunk
        return True

    def next(self) -> bytes | Problem | None:
        """The next body, a Problem (a frame skipped), or None at the end of the stream."""
        while True:
            m = _LENGTH.search(self.buf, max(0, self._scanned - 32))
            if m is None:
                self._scanned = len(self.buf)
                if (self._bad_header is not None and self.buf[-64:].rstrip()[-1:] == b"}"
                        and _object(bytes(self.buf)) is not None):
                    return self._skip(len(self.buf), "")  # the whole body of the bad frame is here
                if self.eof:
                    if bytes(self.buf).strip() or self._bad_header is not None:
                        return self._skip(len(self.buf), "bytes that are not a message at the end of the stream")
                    return None
                if len(self.buf) > SALVAGE + 65536:  # too long to hold a request worth answering
                    return self._skip(len(self.buf) - 64, "bytes that are not a message header")
                self._more()
                continue
            start = _header_start(self.buf, m.start())
            if start > 0:
                if not bytes(self.buf[:start]).strip() and self._bad_header is None:
                    self._drop(start)  # blank lines between messages
                    continue
                return self._skip(start, "bytes that are not a message header")
            if self._bad_header is not None:
                return self._skip(0, "")  # the frame whose header was wrong had no body
            end = _END.search(self.buf, m.end(), MAX_HEADER + 4)
            if end is None:
                if len(self.buf) > MAX_HEADER or self.eof:
                    return self._skip(m.end(), "a header block that does not end (no empty line)")
                self._more()
                continue
            value = bytes(self.buf[m.end():end.start()]).split(b"\n", 1)[0].rstrip(b"\r")
            digits = _DIGITS.fullmatch(value)
            if digits is None or int(digits.group(1)) > MAX_BODY:
                shown = value.strip()[:40].decode("ascii", "replace")
                why = (f"Content-Length {shown!r} is more than {MAX_BODY} bytes" if digits
                       else f"Content-Length {shown!r} is not a number of bytes")
                self._skip(end.end(), why, header=True)  # reported with its body, what follows
                continue
            length = int(digits.group(1))
            while len(self.buf) < end.end() + length and self._more():
                pass
            if len(self.buf) < end.end() + length:
                return self._skip(len(self.buf), f"the stream ended {end.end() + length - len(self.buf)} bytes"
                                  " before the end of the last message")
            body = bytes(self.buf[end.end():end.end() + length])
            self._drop(end.end() + length)
            self._bad_header = None
            return body

    def _drop(self, n: int) -> bytes:
        dropped = bytes(self.buf[:n])
        del self.buf[:n]
        self._scanned = max(0, self._scanned - n)
        return dropped

    def _skip(self, n: int, reason: str, header: bool = False) -> Problem:
        skipped = self._drop(n)
        salvaged = None
        if self._bad_header is not None and not header:
            reason = self._bad_header  # the body of the frame whose header was wrong
            salvaged = _object(skipped)
        self._bad_header = reason if header else None
        return Problem(reason + ": skipped", salvaged)


_HEADER_LINE = re.compile(rb"[A-Za-z0-9-]+[ \t]*:[^\r\n]*\r?\n")


def _header_start(buf: bytearray, at: int) -> int:
    """Where the header block holding the `Content-Length` at `at` starts: other header lines
    (`Content-Type: ...`) may come first."""
    start = at
    while start > 0 and at - start < MAX_HEADER:
        nl = buf.rfind(b"\n", 0, start - 1)
        line = bytes(buf[nl + 1:start])
        if not _HEADER_LINE.fullmatch(line):
            break
        start = nl + 1
    return start


def _object(data: bytes) -> Any:
    """The JSON object `data` starts with (the body of a frame whose header was wrong, maybe
    followed by the start of the next frame), else None."""
    text = data[:SALVAGE].decode("utf-8", "ignore").lstrip()
    if not text.startswith("{"):
        return None
    try:
        value = json.JSONDecoder().raw_decode(text)[0]
    except RecursionError:
        value = top_level(text)
    except ValueError:
        return None
    return value if isinstance(value, dict) else None


def deeper_than(value: Any, limit: int = MAX_DEPTH) -> bool:
    """Whether the arrays and objects of a parsed JSON `value` nest deeper than `limit`."""
    level = [value]
    for _ in range(limit):
        level = [x for v in level for x in (v.values() if isinstance(v, dict) else v if isinstance(v, list) else ())
                 if isinstance(x, (dict, list))]
        if not level:
            return False
    return True


def top_level(text: str) -> Any:
    """`text` parsed with every array or object below the top level replaced by null (linear,
    no recursion): what can be read of a message nested too deeply. None if not JSON, or
    longer than `SALVAGE`."""
    if len(text) > SALVAGE:
        return None
    out = []
    depth = 0
    in_string = escaped = False
    start = 0
    for i, ch in enumerate(text):
        if in_string:
            if escaped:
                escaped = False
            elif ch == "\\":
                escaped = True
            elif ch == '"':
                in_string = False
        elif ch == '"':
            in_string = True
        elif ch in "[{":
            depth += 1
            if depth == 2:
                out.append(text[start:i])
                out.append("null")
        elif ch in "]}":
            depth -= 1
            if depth == 1:
                start = i + 1
    if depth >= 2:
        return None
    out.append(text[start:])
    try:
        return json.loads("".join(out))
    except (ValueError, RecursionError):
        return None


def _valid_id(value: Any) -> bool:
    return (isinstance(value, int) and not isinstance(value, bool)) or isinstance(value, str)


def error(msg_id: Any, code: int, message: str) -> dict:
    return {"jsonrpc": "2.0", "id": msg_id if _valid_id(msg_id) else None, "error": {"code": code, "message": message}}


@dataclass
class Checked:
    """A message that passed the checks (`message`), or the answer to send instead (`answer`,
    None for a notification, which is never answered), and what to log (`note`)."""

    message: dict | None = None
    answer: dict | None = None
    note: str = ""


class Gate:
    """The JSON-RPC checks, and the state they need (initialized, shut down)."""

    def __init__(self) -> None:
        self.initialized = False
        self.shut_down = False

    def check(self, body: bytes) -> Checked:
        try:
            text = body.decode("utf-8")
        except UnicodeDecodeError as exc:
            return Checked(answer=error(None, PARSE_ERROR, f"the message is not UTF-8 (byte {exc.start})"),
                           note="a message that is not UTF-8")
        try:
            value = json.loads(text)
        except RecursionError:
            value = None
        except ValueError as exc:
            why = f"the message is not JSON: {str(exc)[:120]}"
            return Checked(answer=error(None, PARSE_ERROR, why), note=why)
        if value is None or deeper_than(value):
            head = top_level(text)
            head = head if isinstance(head, dict) else {}
            why = f"the message nests deeper than {MAX_DEPTH} levels: not read"
            if "method" in head:  # a request is answered with its id; a notification is not answered
                return Checked(answer=error(head.get("id"), INVALID_REQUEST, why) if "id" in head else None, note=why)
            return Checked(answer=error(None, PARSE_ERROR, why), note=why)
        return self.check_value(value)

    def check_value(self, value: Any) -> Checked:
        if not isinstance(value, dict):
            why = "a JSON-RPC message is an object" + (" (LSP has no batches)" if isinstance(value, list) else "")
            return Checked(answer=error(None, INVALID_REQUEST, why), note=why)
        method, has_id = value.get("method"), "id" in value
        if "method" not in value:  # a response to the server (which sends no requests)
            if has_id and _valid_id(value["id"]) and value.get("jsonrpc") == "2.0":
                return Checked(message=value)
            return Checked(note="a message without a method: ignored")
        request = has_id
        if request and not _valid_id(value["id"]):
            why = "the id of a request is a number or a string"
            return Checked(answer=error(None, INVALID_REQUEST, why), note=why)
        msg_id = value.get("id")
        if value.get("jsonrpc") != "2.0" or not isinstance(method, str):
            why = "not a JSON-RPC 2.0 message (\"jsonrpc\": \"2.0\", a string method)"
            return Checked(answer=error(msg_id, INVALID_REQUEST, why) if request else None, note=why)
        if "params" in value and not isinstance(value["params"], (dict, list)) and value["params"] is not None:
            why = f"{method}: params must be an object or an array"
            return Checked(answer=error(msg_id, INVALID_PARAMS, why) if request else None, note=why)
        if self.shut_down and method != "exit":
            why = f"{method}: the server is shutting down"
            return Checked(answer=error(msg_id, INVALID_REQUEST, why) if request else None, note=why)
        if not self.initialized and method not in ("initialize", "exit"):
            why = f"{method}: the server is not initialized yet"
            return Checked(answer=error(msg_id, SERVER_NOT_INITIALIZED, why) if request else None, note=why)
        return Checked(message=value)

    def answer_problem(self, problem: Problem) -> dict | None:
        """The answer to a request whose frame was skipped, when its body could be read."""
        found = problem.salvaged
        if isinstance(found, dict) and "method" in found and _valid_id(found.get("id")):
            return error(found["id"], PARSE_ERROR, problem.reason)
        return None


def frame(message: dict) -> bytes:
    body = json.dumps(message, ensure_ascii=True, separators=(",", ":")).encode("ascii")
    return b"Content-Length: %d\r\n\r\n" % len(body) + body
