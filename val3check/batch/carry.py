"""What travels with a case (docs/batch.md): the files its run reads, read through the file gate
(val3check/confine.py) with the roots that the run's own reader uses, so that a worker sees what
a single run sees and refuses what it refuses, without the refused bytes travelling:

- a symbolic link travels as a link, so that a link leading out of the application is refused in
  the case as in the single run (R030 for a `val3check-cell.toml` beside it);
- a file the run finds but refuses (outside its roots, too large) travels as a stand-in of the
  same size and no content, never its bytes;
- a file the gate refuses otherwise (missing, a FIFO, a device) does not travel.

The worker (worker.py) writes the files, the stand-ins and the links in its mirror.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field

from ..confine import Refused, Roots, read_bytes
from ..rules import codes

MAX_LINKS = 40  # as the kernel's own limit: more is a loop


@dataclass
class Bundle:
    files: dict[str, bytes] = field(default_factory=dict)  # absolute path -> bytes
    links: dict[str, str] = field(default_factory=dict)  # absolute path of a link -> its target, as written
    stubs: dict[str, int] = field(default_factory=dict)  # absolute path -> size: found and refused by the run

    def add(self, folder: str, name: str, roots: Roots, max_size: int) -> bytes | None:
        """Carry the file `name` (relative to `folder`, or absolute) as the run will open it; its
        bytes when the gate lets them through, else None (a stand-in or nothing travels)."""
        path = self.follow(folder, name)
        if path is None:  # a loop of links, or a name that is no path: refused in the case as in the run
            return None
        try:
            data = read_bytes(path, roots, max_size)
        except Refused as exc:
            if exc.code in (codes.FILE_TOO_LARGE, codes.PATH_OUTSIDE_ROOTS) and os.path.isfile(path):
                self.stubs[path] = os.path.getsize(path) if exc.code == codes.FILE_TOO_LARGE else 0
            return None
        self.files[path] = data
        return data

    def follow(self, folder: str, name: str) -> str | None:
        """The path `name` leads to, its links below `folder` noted on the way (the folder itself
        and those above it are taken as the loader took them: as folders)."""
        top = os.path.abspath(folder)
        try:
            todo = [p for p in os.path.normpath(os.path.join(top, name)).split(os.sep) if p]
            cur, hops = os.sep, 0
            while todo:
                part = todo.pop(0)
                if part == "..":
                    cur = os.path.dirname(cur)
                    continue
                nxt = os.path.join(cur, part)
                if part != "." and not (nxt == top or top.startswith(nxt.rstrip(os.sep) + os.sep)) \
                        and os.path.islink(nxt):
                    hops += 1
                    if hops > MAX_LINKS:
                        return None
                    target = os.readlink(nxt)
                    self.links[nxt] = target
                    todo = [p for p in target.split(os.sep) if p] + todo
                    cur = os.sep if os.path.isabs(target) else cur
                    continue
                cur = nxt if part != "." else cur
        except (OSError, ValueError):  # a NUL in the name, a folder that cannot be listed
            return None
        return cur

    def items(self) -> tuple[tuple, tuple, tuple]:
        return (tuple(sorted(self.files.items())), tuple(sorted(self.links.items())),
                tuple(sorted(self.stubs.items())))

    @classmethod
    def merged(cls, bundles: list[Bundle]) -> Bundle:
        out = cls()
        for b in bundles:
            out.files.update(b.files)
            out.links.update(b.links)
            out.stubs.update(b.stubs)
        return out
