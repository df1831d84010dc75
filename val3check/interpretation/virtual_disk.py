"""The controller's disk for the file instructions of the system library (`$fileOpen`...).

VAL 3 s7 has no file instruction; real applications call the system library's ones, `$fileOpen`,
`$fileGet`, `$fileSet`, `$fileClose`, `$fileExists`, `$delete`, `$copy`, `$rename` (a public
description of the CS8 "Expansion" add-on lists them with their signatures; Stäubli's own
AdventOfCode2021_VAL3 helpers read their input with `$fileOpen(sPath, "r")`, `$fileGet(nHandle,
sLine, 1)` and `$fileClose(nHandle)`). The simulator runs them on this disk, which lives in
memory: it holds the files the scenario gives (`[[files]]`, docs/scenario.md) and what the
application writes, and never reads nor writes the user's disk. Paths are those of 6.6 ("Chemin
d'accès": `racine://Chemin/Nom`, the root Disk by default), compared without case.

What the public description leaves open is decided here and documented in docs/sim.md: a handle
is a number from 0 (at most 10 files open at once, as the description says), -1 when the file
cannot be opened; modes are "r" (read), "w" (write from empty), "a" (append); text is read line
by line (a line ends at "\\n", a "\\r" before it is dropped; at most 128 bytes of it, 3.4.1) and
written one line per string, each followed by "\\n".
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from .values import clip_string

MAX_OPEN = 10  # "Au plus 10 fichiers ouverts en même temps" (the Expansion add-on's description)
MAX_BYTES = 64 * 1024 * 1024  # what the run's files may hold in all: writes beyond it are refused
_ROOT = re.compile(r"^([A-Za-z][A-Za-z0-9_\-]*):/+(.*)$")
_PART = re.compile(r"^[^/\\:*?\"<>|\x00-\x1f]{1,128}$")


def disk_key(path: str) -> str | None:
    """The key of a path on the disk ("disk://dir/name.txt"), None when it is not a path."""
    if not isinstance(path, str):
        return None
    text = path.strip().replace("\\", "/")
    m = _ROOT.match(text)
    root, rest = (m.group(1), m.group(2)) if m else ("Disk", text)
    parts = [p for p in rest.split("/") if p not in ("", ".")]
    if not parts or any(p == ".." or not _PART.match(p) for p in parts):
        return None
    return f"{root.lower()}://" + "/".join(parts).lower()


@dataclass
class OpenFile:
    key: str
    mode: str  # "r", "w", "a"
    pos: int = 0


@dataclass
class VirtualDisk:
    files: dict[str, bytearray] = field(default_factory=dict)  # key -> content
    names: dict[str, str] = field(default_factory=dict)  # key -> the path as first written
    handles: dict[int, OpenFile] = field(default_factory=dict)

    def size(self) -> int:
        return sum(len(b) for b in self.files.values())

    def put(self, path: str, data: bytes) -> bool:
        """A file the scenario gives (False: not a path, or the disk would be full)."""
        key = disk_key(path)
        if key is None or self.size() + len(data) > MAX_BYTES:
            return False
        self.files[key] = bytearray(data)
        self.names.setdefault(key, path)
        return True

    def exists(self, path: str) -> bool:
        key = disk_key(path)
        return key is not None and (key in self.files or any(k.startswith(key + "/") for k in self.files))

    def open(self, path: str, mode: str) -> int:
        key = disk_key(path)
        mode = mode.strip().lower() if isinstance(mode, str) else ""
        if key is None or mode not in ("r", "w", "a") or len(self.handles) >= MAX_OPEN:
            return -1
        if mode == "r" and key not in self.files:
            return -1
        if mode == "w" or key not in self.files:
            self.files[key] = bytearray()
            self.names.setdefault(key, path)
        handle = next(h for h in range(MAX_OPEN + 1) if h not in self.handles)
        self.handles[handle] = OpenFile(key, mode, len(self.files[key]) if mode == "a" else 0)
        return handle

    def close(self, handle) -> bool:
        return self.handles.pop(_handle(handle), None) is not None

    def read_lines(self, handle, count: int) -> list[str] | None:
        """Up to `count` lines from the file's position; None when the handle is not open for reading."""
        f = self.handles.get(_handle(handle))
        if f is None or f.mode != "r":
            return None
        data = self.files.get(f.key, bytearray())
        out = []
        while len(out) < count and f.pos < len(data):
            end = data.find(b"\n", f.pos)
            line = bytes(data[f.pos:len(data) if end < 0 else end])
            f.pos = len(data) if end < 0 else end + 1
            out.append(clip_string(line.rstrip(b"\r").decode("utf-8", "ignore")))
        return out

    def read_bytes(self, handle, count: int) -> list[int] | None:
        f = self.handles.get(_handle(handle))
        if f is None or f.mode != "r":
            return None
        data = self.files.get(f.key, bytearray())
        chunk = bytes(data[f.pos:f.pos + max(0, count)])
        f.pos += len(chunk)
        return list(chunk)

    def write(self, handle, data: bytes) -> bool:
        f = self.handles.get(_handle(handle))
        if f is None or f.mode == "r" or self.size() + len(data) > MAX_BYTES:
            return False
        buf = self.files.setdefault(f.key, bytearray())
        buf[f.pos:f.pos + len(data)] = data
        f.pos += len(data)
        return True

    def delete(self, path: str) -> bool:
        """A file, or a folder and what it holds."""
        key = disk_key(path)
        if key is None or any(f.key == key or f.key.startswith(key + "/") for f in self.handles.values()):
            return False
        gone = [k for k in self.files if k == key or k.startswith(key + "/")]
        for k in gone:
            del self.files[k]
            self.names.pop(k, None)
        return bool(gone)

    def copy(self, src: str, dst: str, move: bool = False) -> bool:
        a, b = disk_key(src), disk_key(dst)
        if a is None or b is None or a not in self.files or (not move and self.size() + len(self.files[a]) > MAX_BYTES):
            return False
        if move and any(f.key == a for f in self.handles.values()):
            return False
        self.files[b] = bytearray(self.files[a])
        self.names[b] = dst
        if move and a != b:
            del self.files[a]
            self.names.pop(a, None)
        return True


def _handle(v) -> int:
    try:
        return int(v)
    except (TypeError, ValueError, OverflowError):
        return -1
