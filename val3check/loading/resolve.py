"""Find files on disk the way a controller would: case-insensitively, with `\\` or `/`.

Library and user-type paths (manual 6.6, "Chemin d'accès": `racine://Chemin/Nom`, "Par défaut,
la racine est Disk et le chemin vide") are resolved by `resolve_library`:

- `Disk://X` (or any other root such as `USB0://`): X relative to the folder that contains the
  application folder (the controller's `usr/usrapp`), then to each `--disk-root`, then to the
  `usr/usrapp` folder of the controller tree that holds the application, if any;
- `./X`, `../X`: relative to the folder of the declaring `.pjx`;
- a bare `X` or `X/Y.pjx`: relative to the `.pjx` folder first, then as `Disk://X`;
- a path that names a folder means the application of that name inside it (`<dir>/<dir>.pjx`,
  or the only `.pjx` there); a path without extension that is not a folder gets `.pjx`.

Confinement (`val3check.confine`): a candidate is used only when it is a `.pjx` file that lies,
symbolic links resolved, inside the run's allowed roots; a candidate outside them is never
opened (nor are the folders on the way listed), and the caller reports the path as written.
When the path leads nowhere, `RepositoryIndex` looks for the application by name in the
repository (issue 11 item 5: repositories do not mirror `usr/usrapp`).
"""

from __future__ import annotations

import os
import re

from ..confine import Roots
from ..light_dataclass import dataclass

_ROOT = re.compile(r"^([A-Za-z][A-Za-z0-9_\-]*):/+(.*)$")


def path_key(path: str) -> str:
    """The same file's key whatever the spelling of its path (case on case-insensitive systems)."""
    return os.path.normcase(os.path.abspath(path))


def inside(path: str, folder: str, top: str | None = None) -> bool:
    """`path` is in `folder` or below it, symbolic links resolved (`top`: the folder's real path)."""
    real, top = os.path.realpath(path), top or os.path.realpath(folder)
    return os.path.commonpath([real, top]) == top


def listdir(folder: str) -> list[str]:
    """Sorted names in a folder; [] when it cannot be listed."""
    try:
        return sorted(os.listdir(folder))
    except OSError:
        return []


def find_path(base: str, rel: str) -> str | None:
    """`rel` (with `/` or `\\`) under `base`, each component matched exactly first, then
    ignoring case; the existing path, absolute and normalised, or None."""
    rel = rel.replace("\\", "/")
    if rel.startswith("/"):
        cur = "/"
    else:
        cur = base
    for comp in rel.split("/"):
        if comp in ("", "."):
            continue
        if comp == "..":
            cur = os.path.dirname(cur.rstrip("/")) or "/"
            continue
        nxt = os.path.join(cur, comp)
        if os.path.lexists(nxt):
            cur = nxt
            continue
        low = comp.lower()
        match = next((n for n in listdir(cur) if n.lower() == low), None)
        if match is None:
            return None
        cur = os.path.join(cur, match)
    return os.path.abspath(cur)


def project_in_folder(folder: str) -> str | None:
    """The application in a folder: `<folder>.pjx` (any case), else the only .pjx there."""
    names = [n for n in listdir(folder) if n.lower().endswith(".pjx") and os.path.isfile(os.path.join(folder, n))]
    want = os.path.basename(os.path.normpath(folder)).lower() + ".pjx"
    for n in names:
        if n.lower() == want:
            return os.path.abspath(os.path.join(folder, n))
    if len(names) == 1:
        return os.path.abspath(os.path.join(folder, names[0]))
    return None


def controller_usrapp(folder: str) -> str | None:
    """The `<ctrl>/usr/usrapp` folder that contains `folder`, if any."""
    cur = os.path.abspath(folder)
    while True:
        parent = os.path.dirname(cur)
        if parent == cur:
            return None
        if os.path.basename(cur).lower() == "usrapp" and os.path.basename(parent).lower() == "usr":
            return cur
        cur = parent


def _is_project_file(path: str) -> bool:
    return path.lower().endswith(".pjx") and os.path.isfile(path)


def _as_project(candidate: str | None) -> str | None:
    if candidate is None:
        return None
    if os.path.isdir(candidate):
        return project_in_folder(candidate)
    if _is_project_file(candidate):
        return candidate
    return None


def _leads_inside(base: str, rel: str, roots: Roots) -> bool:
    """Where `rel` leads from `base`, judged on the text alone (nothing outside is touched)."""
    if roots.anywhere:
        return True
    rel = rel.replace("\\", "/")
    target = os.path.normpath(rel if rel.startswith("/") else os.path.join(os.path.realpath(base), rel))
    return roots.holds(target)


@dataclass(slots=True)
class Resolution:
    """Where a Library/Type path leads. `path`: the library's .pjx (inside the roots), or None.
    `outside`: a candidate exists but lies outside the roots; it was not opened."""

    path: str | None = None
    outside: bool = False


def _try(base: str, rel: str, roots: Roots, res: Resolution) -> str | None:
    for r in (rel, None if rel.lower().endswith(".pjx") else rel.rstrip("/\\") + ".pjx"):
        if r is None:
            continue
        if not _leads_inside(base, r, roots):
            res.outside = True  # never opened, nor are the folders on the way listed
            continue
        found = _as_project(find_path(base, r))
        if found is None:
            continue
        if not roots.allows(found):  # a symbolic link that leads out
            res.outside = True
            continue
        return found
    return None


def disk_bases(pjx_path: str, disk_roots: list[str]) -> list[str]:
    pjx_dir = os.path.dirname(os.path.abspath(pjx_path))
    app_parent = os.path.dirname(pjx_dir)
    bases = [app_parent] + [os.path.abspath(r) for r in disk_roots]
    ctrl = controller_usrapp(pjx_dir)
    if ctrl is not None:
        bases.append(ctrl)
    # Last resort: a project checked on its own from deep inside a repository (a user type
    # under `App/Types/T/`) names `Disk://App/...` relative to a folder further up (inside
    # the roots only: the walk stops at the repository).
    ancestor = os.path.dirname(app_parent)
    while ancestor and ancestor != os.path.dirname(ancestor):
        bases.append(ancestor)
        ancestor = os.path.dirname(ancestor)
    return bases


def locate_library(path_text: str, pjx_path: str, disk_roots: list[str], roots: Roots) -> Resolution:
    """Where the `.pjx` named by a Library/Type path is, confined to `roots`."""
    res = Resolution()
    text = path_text.strip().replace("\\", "/")
    pjx_dir = os.path.dirname(os.path.abspath(pjx_path))
    bases_disk = disk_bases(pjx_path, disk_roots)
    m = _ROOT.match(text)
    if m:
        rel, bases = m.group(2), bases_disk
    elif text.startswith(("./", "../")) or text in (".", ".."):
        rel, bases = text, [pjx_dir]
    elif text.startswith("/"):
        rel, bases = text, ["/"]
    else:
        rel, bases = text, [pjx_dir] + bases_disk
    if not rel.strip("/"):
        return res
    seen: set[str] = set()
    for base in bases:
        if base in seen:
            continue
        seen.add(base)
        if not roots.anywhere and not rel.startswith("/") and not roots.holds(os.path.realpath(base)):
            continue  # a folder above the repository (the last-resort ancestors): not searched
        found = _try(base, rel, roots, res)
        if found is not None:
            res.path = os.path.abspath(found)
            return res
    return res


def resolve_library(path_text: str, pjx_path: str, disk_roots: list[str], roots: Roots) -> str | None:
    """The absolute path of the `.pjx` named by a Library/Type path (inside `roots`), or None."""
    return locate_library(path_text, pjx_path, disk_roots, roots).path


def library_name(path_text: str) -> str:
    """The application a Library/Type path names: its last component without `.pjx`."""
    tail = path_text.strip().replace("\\", "/").rstrip("/").rsplit("/", 1)[-1]
    tail = tail.rsplit(":", 1)[-1]
    return tail[:-4] if tail.lower().endswith(".pjx") else tail


class RepositoryIndex:
    """The applications of a repository by name (issue 11 item 5), walked once per root.

    A `.pjx` whose stem is the name, in any folder of the repository except hidden ones,
    `node_modules`, virtual environments and the like; symbolic links are not followed, so the
    search stays inside the repository. The walk is bounded (`MAX_FOLDERS`)."""

    MAX_FOLDERS = 50_000

    def __init__(self, skip: frozenset[str]) -> None:
        self.skip = skip
        self._by_root: dict[str, dict[str, list[str]]] = {}

    def _index(self, root: str) -> dict[str, list[str]]:
        found = self._by_root.get(root)
        if found is not None:
            return found
        found = {}
        seen = 0
        for folder, dirs, files in os.walk(root):
            seen += 1
            if seen > self.MAX_FOLDERS:
                break
            dirs[:] = sorted(d for d in dirs if not d.startswith(".") and d not in self.skip
                             and not os.path.isfile(os.path.join(folder, d, "pyvenv.cfg")))
            for f in sorted(files):
                if f.lower().endswith(".pjx"):
                    p = os.path.join(folder, f)
                    if os.path.isfile(p) and not os.path.islink(p):
                        found.setdefault(f[:-4].lower(), []).append(os.path.abspath(p))
        self._by_root[root] = found
        return found

    def find(self, root: str, name: str) -> list[str]:
        """The projects named `name` (any case) in the repository at `root`, sorted."""
        if not name or not _NAME_OK.match(name):
            return []
        return sorted(self._index(root).get(name.lower(), []))


_NAME_OK = re.compile(r"^[^/\\:*?\"<>|]{1,255}$")
