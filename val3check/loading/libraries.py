"""Libraries and user types of the loaded applications (manual chapters 6 and 7): where each
declared path leads (resolve.py), the guess by name in the repository when it leads nowhere
(F016), what is reported when nothing is found (L001, L002, L003, F014), and circular references
(L004, L005).

`LibraryResolution` is a part of `loader.Loader` (it uses its roots, repositories and reader).
"""

from __future__ import annotations

import itertools
import os

from ..diagnostics import Diagnostic, Severity
from ..light_dataclass import dataclass, field
from ..rules import codes
from . import resolve as rs
from .model import Application, LibraryRef, TypeRef


def is_io(ref: LibraryRef | TypeRef) -> bool:
    """The controller's own I/O library (L003): never looked for by name."""
    return isinstance(ref, LibraryRef) and (ref.alias.lower() == "io" or rs.library_name(ref.path).lower() == "io")


@dataclass(slots=True)
class LibraryFound:
    """Where a library path leads (`find_library`): `path` the library's .pjx or None; `guessed`
    when it was found by name in the repository (F016); `candidates` the applications of that
    name in the repository; `outside`: a candidate lies outside the roots (not opened)."""

    path: str | None
    guessed: bool = False
    candidates: list[str] = field(default_factory=list)
    outside: bool = False


def find_library(path_text: str, app_path: str, disk_roots: list[str], roots, repos: list[str],
                 index: rs.RepositoryIndex | None, by_name: bool = True) -> LibraryFound:
    """The one resolution of a library or user type path, for lint (a project's Library and Type
    entries) and for the simulator (libLoad, autoloaded libraries): the path as a controller
    reads it (resolve.locate_library: the application's Disk:// folder, each --disk-root, the
    controller tree's usr/usrapp), else, `by_name`, the only application of that name in the
    repositories that hold the declaring project (issue 11 item 5: a guess, F016)."""
    located = rs.locate_library(path_text, app_path, disk_roots, roots)
    if located.path is not None:
        return LibraryFound(located.path, outside=located.outside)
    candidates = _in_repository(app_path, path_text, roots, repos, index) if by_name and index is not None else []
    if len(candidates) == 1:
        return LibraryFound(candidates[0], True, candidates, located.outside)
    return LibraryFound(None, False, candidates, located.outside)


def _in_repository(app_path: str, path_text: str, roots, repos: list[str], index: rs.RepositoryIndex) -> list[str]:
    """Applications named like the library in the repositories that hold the declaring project
    (issue 11 item 5), other than that project."""
    name = rs.library_name(path_text)
    out: list[str] = []
    for repo in repos:
        if not roots.holds(os.path.realpath(app_path)) or not rs.inside(app_path, repo):
            continue
        for cand in index.find(repo, name):
            if rs.path_key(cand) != rs.path_key(app_path) and roots.allows(cand) and cand not in out:
                out.append(cand)
    return out


class LibraryResolution:
    """Resolves the Library and Type references of every loaded application, loading the
    applications they lead to (a part of loader.Loader)."""

    def resolve_all(self) -> None:
        queue = list(self.ws.apps.values())
        i = 0
        while i < len(queue):
            app = queue[i]
            i += 1
            if app.layout == "pgx-only":
                continue
            for ref in app.libraries.values():
                lib = self._resolve(app, ref, "library")
                if lib is not None and lib not in queue:
                    queue.append(lib)
            for tref in app.types.values():
                lib = self._resolve(app, tref, "type")
                if lib is not None and lib not in queue:
                    queue.append(lib)
        self.diags.extend(cycle_findings(self.ws.apps, "library"))
        self.diags.extend(cycle_findings(self.ws.apps, "type"))

    def _resolve(self, app: Application, ref: LibraryRef | TypeRef, kind: str) -> Application | None:
        found = find_library(ref.path, app.path, self.options.disk_roots, self.roots, self.repos, self.index,
                             by_name=not is_io(ref))
        resolved = found.path
        if found.guessed:
            ref.guessed = self._shown(resolved)
            o = ref.origin
            what = f"library {ref.alias}" if isinstance(ref, LibraryRef) else f"user type {ref.name}"
            self.diags.append(Diagnostic(
                codes.LIBRARY_FOUND_IN_REPOSITORY,
                f"{what}: '{ref.path}' is not at its Disk:// place; using the application found by name in"
                f" the repository: {ref.guessed} (a guess: the findings that depend on it are at most"
                " warnings)",
                o.path, o.line, o.col,
            ))
        if resolved is None:
            if found.outside and len(found.candidates) < 2:
                self.diags.append(self._outside_ref(ref))
            else:
                self.diags.append(self._not_found(ref, kind, found.candidates))
            return None
        ref.resolved = resolved
        if resolved in self.ws.apps:
            return None
        return self.load_project(resolved)

    @staticmethod
    def _shown(path: str) -> str:
        """As reports show paths: relative to the current folder when inside it."""
        rel = os.path.relpath(path)
        return (path if rel == ".." or rel.startswith(".." + os.sep) else rel).replace(os.sep, "/")

    def _outside_ref(self, ref: LibraryRef | TypeRef) -> Diagnostic:
        o = ref.origin
        if isinstance(ref, LibraryRef):
            what, tail = f"library {ref.alias}", f"uses of {ref.alias}: symbols are not checked"
        else:
            what, tail = f"user type {ref.name}", "its fields are not checked"
        return Diagnostic(
            codes.PATH_OUTSIDE_ROOTS,
            f"{what}: the path '{ref.path}' leads outside the application and the configured roots (its"
            f" repository, --disk-root, disk-roots): not read; {tail}",
            o.path, o.line, o.col,
        )

    def _not_found(self, ref: LibraryRef | TypeRef, kind: str, candidates: list[str] = ()) -> Diagnostic:
        o = ref.origin
        stem = rs.library_name(ref.path)
        where = (
            "relative to the project folder"
            if ref.path.startswith(("./", "../", ".\\", "..\\"))
            else "in the folder that contains the application folder, in each --disk-root and in the controller's usr/usrapp"
        )
        if candidates:
            where += (
                f"; {len(candidates)} applications named {stem} in the repository: "
                + ", ".join(self._shown(c) for c in candidates[:10])
                + (", ..." if len(candidates) > 10 else "")
                + " (name the right folder with --disk-root)"
            )
        if isinstance(ref, LibraryRef):
            if ref.alias.lower() == "io" or stem.lower() == "io":
                return Diagnostic(
                    codes.IO_LIBRARY_NOT_CHECKED,
                    f"library {ref.alias} ('{ref.path}') is the controller's own I/O library: its"
                    f" contents come from the controller's configuration, so {ref.alias}: symbols are not checked",
                    o.path,
                    o.line,
                    o.col,
                )
            return Diagnostic(
                codes.LIBRARY_NOT_FOUND,
                f"library {ref.alias} not found: '{ref.path}' (searched {where}); uses of"
                f" {ref.alias}: symbols are not checked",
                o.path,
                o.line,
                o.col,
            )
        return Diagnostic(
            codes.USER_TYPE_NOT_FOUND,
            f"user type {ref.name} not found: '{ref.path}' (searched {where}); its fields are not checked",
            o.path,
            o.line,
            o.col,
        )


def _edges(apps: dict[str, Application], app: Application, kind: str) -> list[tuple[LibraryRef | TypeRef, str]]:
    refs = app.libraries.values() if kind == "library" else app.types.values()
    return [(r, r.resolved) for r in refs if r.resolved is not None and r.resolved in apps]


def cycle_findings(apps: dict[str, Application], kind: str) -> list[Diagnostic]:
    """Manual 6.6: "Il ne peut pas y avoir de références circulaires entre les librairies."
    Each reference (`kind`: "library" or "type") that belongs to a cycle is reported at its
    declaration, once (L004, L005)."""
    out: list[Diagnostic] = []
    # Tarjan's strongly connected components, iterative, deterministic (insertion order).
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    on_stack: set[str] = set()
    stack: list[str] = []
    comp_of: dict[str, int] = {}
    comps: list[list[str]] = []
    counter = 0
    for start in apps:
        if start in index:
            continue
        work = [(start, 0)]
        while work:
            v, pi = work.pop()
            if pi == 0:
                index[v] = low[v] = counter
                counter += 1
                stack.append(v)
                on_stack.add(v)
            succ = [w for _, w in _edges(apps, apps[v], kind)]
            recurse = False
            for j in range(pi, len(succ)):
                w = succ[j]
                if w not in index:
                    work.append((v, j + 1))
                    work.append((w, 0))
                    recurse = True
                    break
                if w in on_stack:
                    low[v] = min(low[v], index[w])
            if recurse:
                continue
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on_stack.discard(w)
                    comp_of[w] = len(comps)
                    comp.append(w)
                    if w == v:
                        break
                comps.append(comp)
            if work:
                parent = work[-1][0]
                low[parent] = min(low[parent], low[v])
    for key, app in apps.items():
        for ref, target in _edges(apps, app, kind):
            if comp_of.get(target) != comp_of.get(key):
                continue
            comp = comps[comp_of[key]]
            if len(comp) == 1 and target != key:
                continue
            path = _cycle_path(apps, key, target, comp_of, kind)
            names = " -> ".join(apps[k].name for k in path)
            o = ref.origin
            guesses = _guesses_on(apps, path, kind)
            if kind == "library":
                msg = (
                    f"circular library reference: {names} (manual 6.6: if library A uses"
                    " library B, library B cannot use library A)"
                )
            else:
                label = ref.name  # type: ignore[union-attr]
                msg = f"circular user type: type {label} ends up containing itself ({names})"
            if guesses:  # a cycle through a library found by name may not exist on the controller
                msg += (
                    f" [found by guessing (F016): {', '.join(guesses)}; if that is not the right"
                    " application, there is no cycle, so this is at most a warning]"
                )
            out.append(
                Diagnostic(
                    codes.CIRCULAR_LIBRARY if kind == "library" else codes.CIRCULAR_USER_TYPE,
                    msg,
                    o.path,
                    o.line,
                    o.col,
                    at_most=Severity.WARNING if guesses else None,
                )
            )
    return out


def _guesses_on(apps: dict[str, Application], path: list[str], kind: str) -> list[str]:
    """Where the references of a cycle found by guessing (F016) lead, in order."""
    out = []
    for a, b in itertools.pairwise(path):
        for ref, target in _edges(apps, apps[a], kind):
            if target == b and ref.guessed and ref.guessed not in out:
                out.append(ref.guessed)
    return out


def _cycle_path(apps: dict[str, Application], start: str, first: str, comp_of: dict[str, int], kind: str) -> list[str]:
    """Shortest path start -> first -> ... -> start inside the component (BFS)."""
    if first == start:
        return [start, start]
    prev: dict[str, str] = {first: start}
    frontier = [first]
    while frontier:
        nxt = []
        for v in frontier:
            for _, w in _edges(apps, apps[v], kind):
                if comp_of.get(w) != comp_of.get(start):
                    continue
                if w == start:
                    path = [start]
                    cur = v
                    chain = []
                    while cur != start:
                        chain.append(cur)
                        cur = prev[cur]
                    return path + chain[::-1] + [start]
                if w not in prev:
                    prev[w] = v
                    nxt.append(w)
        frontier = nxt
    return [start, first, start]  # pragma: no cover
