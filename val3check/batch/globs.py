"""The globs of a batch (`val3check sim 'apps/*'`, a sweep's `applications`), expanded inside
their roots (docs/batch.md, "Globs"):

- the folder a pattern starts from (its part before the first `*`, `?` or `[`) must lie inside
  the roots before anything is listed: a sweep's `"/**/*.pjx"` is refused at its line, and no
  pattern ever lists /proc, /sys or /dev;
- `**` goes down real folders only, never through a symbolic link (three links to `.` cannot
  make it endless); a link that a name or `*` matches is followed for that one step, and a match
  or a folder that leads outside the roots (symbolic links resolved) is an error naming it;
- names starting with a dot match only a pattern part starting with one, as with `glob.glob`;
- at most MAX_FOLDERS folders are listed: a pattern that needs more is an error.
"""

from __future__ import annotations

import fnmatch
import os
import re

from ..confine import Roots, is_special, repository_root

MAX_FOLDERS = 20_000
_MAGIC = re.compile(r"[*?\[]")


class GlobError(Exception):
    """A pattern that leads outside its roots or lists too much (a usage error)."""


def has_magic(pattern: str) -> bool:
    return bool(_MAGIC.search(pattern))


def _parts(pattern: str) -> tuple[str, list[str]]:
    """(the literal folder a pattern starts from, "" for the current one; the parts after it)."""
    parts = pattern.replace(os.sep, "/").split("/")
    absolute = pattern.startswith(("/", os.sep))
    parts = [p for p in parts if p not in ("", ".")] if not absolute else [p for p in parts[1:] if p != ""]
    i = next((k for k, p in enumerate(parts) if has_magic(p)), len(parts))
    base = os.path.join(*parts[:i]) if i else ""
    if absolute:
        base = os.sep + base
    return base, parts[i:]


def start_of(pattern: str) -> str:
    """The folder a pattern starts from (its part before the first `*`, `?` or `[`)."""
    return _parts(pattern)[0] or "."


def default_roots(pattern: str) -> Roots:
    """The roots of a pattern typed on the command line: the repository holding the folder it
    starts from (its git top level, else that folder)."""
    base, _ = _parts(pattern)
    return Roots([repository_root(base or ".")])


def expand_glob(pattern: str, roots: Roots | None = None, where: str = "") -> list[str]:
    """The paths `pattern` matches, sorted, written as the pattern writes them (relative stays
    relative); GlobError when it leads outside `roots` (default: default_roots; `where` names
    them in the message) or lists more than MAX_FOLDERS folders."""
    roots = roots if roots is not None else default_roots(pattern)
    where = where or _where(roots)
    base, parts = _parts(pattern)
    _inside(base or ".", roots, where, start=True)
    found: set[str] = set()
    listed = 0
    todo: list[tuple[str, int]] = [(base, 0)]
    seen: set[tuple[str, int]] = set()
    while todo:
        path, i = todo.pop()
        if (path, i) in seen:
            continue
        seen.add((path, i))
        if i == len(parts):
            _inside(path, roots, where)
            found.add(path)
            continue
        part, last = parts[i], i == len(parts) - 1
        if not has_magic(part):
            nxt = os.path.join(path, part) if path else part
            if os.path.lexists(nxt) and (last or os.path.isdir(nxt)):
                todo.append((nxt, i + 1))
            continue
        folder = path or "."
        if not os.path.isdir(folder) or is_special(os.path.realpath(folder)):
            continue
        _inside(folder, roots, where)
        listed += 1
        if listed > MAX_FOLDERS:
            raise GlobError(f"lists more than {MAX_FOLDERS} folders (at most that many are walked): name fewer")
        try:
            with os.scandir(folder) as it:
                entries = sorted((e.name, e.is_dir(follow_symlinks=False), e.is_symlink()) for e in it)
        except OSError:
            continue  # a folder that cannot be listed matches nothing, as with glob.glob
        if part == "**":
            todo.append((path, i + 1))  # no folder at all
            todo += [(os.path.join(path, name) if path else name, i) for name, real_dir, link in entries
                     if real_dir and not link and not name.startswith(".")]
            continue
        for name, _, _ in entries:
            if name.startswith(".") and not part.startswith("."):
                continue
            if fnmatch.fnmatch(name, part):
                nxt = os.path.join(path, name) if path else name
                if last or os.path.isdir(nxt):
                    todo.append((nxt, i + 1))
    return sorted(found)


def _inside(path: str, roots: Roots, where: str, start: bool = False) -> None:
    """Checked before a folder is listed and for each match, symbolic links resolved."""
    if roots.allows(path) and not is_special(os.path.realpath(path)):
        return
    from ..lint import display_path

    if start:
        raise GlobError(f"leads outside {where} (it starts in {display_path(path)}): nothing there is listed")
    raise GlobError(f"{display_path(path)} leads outside {where}: not followed")


def _where(roots: Roots) -> str:
    from ..lint import printable_path

    return ", ".join(printable_path(r) for r in roots.folders) or "the folders named"
