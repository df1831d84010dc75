"""Where the editor's documents are, and the texts the server keeps (no protocol here).

Every URI scheme is answered: `file:` is a path on this machine; `untitled:` is a buffer
never saved, checked from its text alone as a `.pgx`, `.pjx` or `.dtx` without application
(its kind read from its root element), through an empty stand-in file in a private temporary
folder, so that the buffer goes through the same loader and file gate as a file on disk; any
other scheme (`http:`, `git:`, `vscode-vfs:`...) and any `file:` URI that names no local absolute
path is `elsewhere`: nothing is read, there is nothing to report and nothing to answer.

Texts of files the editor has not opened are kept within a byte budget (`Recent`), the most
recently used first; they are read again when needed.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from collections import OrderedDict
from dataclasses import dataclass
from urllib.parse import unquote_to_bytes, urlsplit

VAL3_EXTENSIONS = (".pjx", ".pgx", ".dtx")


@dataclass(frozen=True)
class Where:
    kind: str  # "file", "buffer" (untitled:) or "elsewhere"
    path: str = ""  # absolute path of a file


def locate(uri: str) -> Where:
    """What `uri` names. Never raises."""
    try:
        parts = urlsplit(uri)
    except ValueError:
        return Where("elsewhere")
    scheme = parts.scheme.lower()
    if scheme == "untitled":
        return Where("buffer")
    if scheme != "file" or parts.netloc not in ("", "localhost"):
        return Where("elsewhere")  # a remote file (a UNC host on POSIX) is not read either
    raw = unquote_to_bytes(parts.path)
    if not raw or b"\0" in raw:
        return Where("elsewhere")
    path = os.fsdecode(raw)
    if os.name == "nt" and len(path) > 2 and path[0] == "/" and path[2] == ":":
        path = path[1:]  # file:///C:/x
    if not os.path.isabs(path):
        return Where("elsewhere")
    return Where("file", os.path.normpath(path))


def buffer_extension(text: str) -> str:
    """The file kind of an untitled buffer from its root element (a program file by default)."""
    head = text[:4096]
    for tag, ext in (("<Project", ".pjx"), ("<Database", ".dtx"), ("<Programs", ".pgx")):
        if tag in head:
            return ext
    return ".pgx"


class Buffers:
    """Stand-in files for `untitled:` buffers: an empty file per buffer, in a private temporary
    folder made when the first buffer opens and removed with the last (`close`, `clear`)."""

    def __init__(self) -> None:
        self._folder: str | None = None
        self._paths: dict[str, str] = {}  # uri -> stand-in path
        self._count = 0

    def path(self, uri: str, text: str) -> str:
        """The stand-in file of buffer `uri` for a text like `text` (made if needed)."""
        ext = buffer_extension(text)
        old = self._paths.get(uri)
        if old is not None and old.endswith(ext):
            return old
        if old is not None:
            self._remove(old)
        if self._folder is None:
            self._folder = tempfile.mkdtemp(prefix="val3check-buffers-")
        self._count += 1
        folder = os.path.join(self._folder, str(self._count))  # one application per buffer
        os.mkdir(folder)
        path = os.path.join(folder, "untitled" + ext)
        with open(path, "wb"):
            pass  # the text is the editor's: given to the loader as unsaved text, never written
        self._paths[uri] = path
        return path

    def known(self, uri: str) -> str | None:
        return self._paths.get(uri)

    def uri_of(self, path: str) -> str | None:
        for uri, p in self._paths.items():
            if p == path:
                return uri
        return None

    def holds(self, path: str) -> bool:
        return self._folder is not None and path.startswith(self._folder + os.sep)

    def close(self, uri: str) -> None:
        path = self._paths.pop(uri, None)
        if path is not None:
            self._remove(path)
        if not self._paths:
            self.clear()

    def _remove(self, path: str) -> None:
        shutil.rmtree(os.path.dirname(path), ignore_errors=True)

    def clear(self) -> None:
        if self._folder is not None:
            shutil.rmtree(self._folder, ignore_errors=True)
        self._folder = None
        self._paths.clear()


class Recent:
    """Values kept within `budget` bytes (each weighs `size`), the least recently used dropped first."""

    def __init__(self, budget: int) -> None:
        self.budget = budget
        self.used = 0
        self._items: OrderedDict[str, tuple[object, int]] = OrderedDict()

    def get(self, key: str) -> object | None:
        item = self._items.get(key)
        if item is None:
            return None
        self._items.move_to_end(key)
        return item[0]

    def put(self, key: str, value: object, size: int) -> None:
        self.pop(key)
        if size > self.budget:
            return
        self._items[key] = (value, size)
        self.used += size
        while self.used > self.budget:
            _, (_, old) = self._items.popitem(last=False)
            self.used -= old

    def pop(self, key: str) -> None:
        item = self._items.pop(key, None)
        if item is not None:
            self.used -= item[1]

    def __len__(self) -> int:
        return len(self._items)
