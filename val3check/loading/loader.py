"""Discovery of applications, loading of their files, libraries and user types."""

from __future__ import annotations

import errno
import os
from collections.abc import Callable

from ..confine import Refused, Roots, check, repository_root
from ..diagnostics import Diagnostic
from ..light_dataclass import dataclass, field
from ..rules import codes
from . import resolve as rs
from .bindings import bound_names
from .data_file import read_data_s6, read_data_s7
from .declaration import Sink
from .document_kind import check_root, classify, not_val3
from .libraries import LibraryResolution
from .model import Application, LibraryRef, Origin, Program, TypeRef, Workspace
from .program_file import read_programs
from .project_file import read_project
from .xmlread import Node, read_xml

# Folders never searched for applications (besides hidden ones such as .git).
SKIP_DIRS = frozenset({"node_modules", "__pycache__", "site-packages", "venv", "virtualenv", "bower_components"})

_EXT_PROJECT = ".pjx"
_EXT_PROGRAM = ".pgx"
_EXT_DATA = ".dtx"
_VAL3_EXTS = (_EXT_PROJECT, _EXT_PROGRAM, _EXT_DATA)


@dataclass
class LoadOptions:
    disk_roots: list[str] = field(default_factory=list)  # --disk-root DIR / config entry, searched after the defaults
    max_file_size: int = 16 * 1024 * 1024  # bytes; larger files get a diagnostic and are skipped
    # more folders that paths written in files may lead into (the run's roots, when a library
    # is loaded again by the simulator)
    extra_roots: list[str] = field(default_factory=list)
    # skip(path, is_folder): the configuration excludes it (val3check.exclusion); a folder walk
    # neither enters such a folder nor reads such a file
    skip: Callable[[str, bool], bool] | None = None
    # absolute path -> unsaved text to read instead of the file on disk (an editor's buffer,
    # `--stdin-filename`); read through the same gate (val3check.confine)
    overlay: dict[str, bytes] | None = None


_key = rs.path_key


def _keep_first(app: Application, table: dict, item, kind: str, sink: Sink) -> None:
    """Add a program or global to the application; one declared twice is F011, the first wins."""
    first = table.get(item.name)
    if first is None:
        table[item.name] = item
        return
    sink.diagnostics.append(Diagnostic(
        codes.DUPLICATE_FILE_DECLARATION,
        f"{kind} {item.name} is declared twice in application {app.name} (first in"
        f" {os.path.basename(first.origin.path)} line {first.origin.line}); the first one is used",
        item.origin.path, item.origin.line, item.origin.col,
    ))


_inside = rs.inside


def _stem(rel: str) -> str:
    """'Sub\\pick.pgx' -> 'pick': the program a listed file is named after, in lower case."""
    return os.path.splitext(rel.replace("\\", "/").rsplit("/", 1)[-1])[0].lower()


def _ext(path: str) -> str:
    """'.pjx' for 'App/App.pjx', and for 'App/.pjx' too: a project file without a name is still a
    project file (os.path.splitext sees no extension in a dot-file)."""
    base = os.path.basename(path)
    ext = os.path.splitext(base)[1]
    if not ext and base.startswith(".") and base.count(".") == 1:
        ext = base
    return ext.lower()


@dataclass
class _Folder:
    path: str
    projects: list[str]
    programs: list[str]


class Loader(LibraryResolution):
    def __init__(self, options: LoadOptions) -> None:
        self.options = options
        self.ws = Workspace()
        self.diags: list[Diagnostic] = []
        self.claimed: set[str] = set()  # program files listed by a loaded project
        self.failed: set[str] = set()  # project files that could not be loaded
        self.lines_read = 0
        self.bytes_read = 0
        # Where paths written in files may lead (val3check.confine): grows with each target.
        self.roots = Roots([*options.disk_roots, *options.extra_roots])
        self.ws.roots = self.roots
        self.repos: list[str] = []  # repository roots of the targets (git top level, else the target)
        self.index = rs.RepositoryIndex(SKIP_DIRS)
        self.ws.repos = self.repos  # the same list: it grows with each target
        self.ws.repository_index = self.index
        self._real_folders: dict[str, str] = {}  # application folder -> its real path
        self.excluded = 0  # folders and files a walk skipped because the configuration excludes them

    # -- reading ------------------------------------------------------------------------------

    def _read(self, path: str) -> Node | None:
        res = read_xml(path, self.options.max_file_size, self.roots, self.options.overlay)
        self.diags.extend(res.diagnostics)
        self.lines_read += res.lines
        self.bytes_read += res.size
        if res.size and (_ext(path) in _VAL3_EXTS or (res.root is not None and classify(res.root) is not None)):
            # only files read as VAL 3 are ever quoted in a report (source excerpts)
            self.ws.quotable.add(os.path.abspath(path))
        return res.root

    def _allow_target(self, path: str) -> None:
        """A path the user named: its folder and its repository become roots."""
        folder = path if os.path.isdir(path) else os.path.dirname(path)
        for f in (folder, os.path.dirname(os.path.realpath(path)) if not os.path.isdir(path) else None):
            if f is None:
                continue
            self.roots.add(f)
            repo = repository_root(f)
            self.roots.add(repo)
            if repo not in self.repos:
                self.repos.append(repo)

    def _add_target(self, key: str) -> None:
        if key not in self.ws.targets:
            self.ws.targets.append(key)
        app = self.ws.apps.get(key)
        if app is not None and app.layout != "pgx-only":
            # its Disk:// folder (the controller's usr/usrapp) and its controller tree
            self.roots.add(os.path.dirname(app.folder))
            ctrl = rs.controller_usrapp(app.folder)
            if ctrl is not None:
                self.roots.add(ctrl)

    # -- projects -----------------------------------------------------------------------------

    def load_project(self, pjx: str) -> Application | None:
        pjx = os.path.abspath(pjx)
        if pjx in self.ws.apps:
            return self.ws.apps[pjx]
        if pjx in self.failed:
            return None
        root = self._read(pjx)
        layout = None
        if root is not None:
            layout, d = check_root(root, "project", pjx)
            self.diags.extend(d)
        if root is None or layout is None:
            self.failed.add(pjx)
            return None
        sink = Sink(pjx, self.diags)
        pf = read_project(root, sink)
        stem = os.path.basename(pjx)[: -len(_ext(pjx)) or None]
        app = Application(
            name=stem or os.path.basename(os.path.dirname(pjx)),  # `.pjx`: a project without a name
            path=pjx,
            layout=layout,
            version=pf.version,
            stack_size=pf.stack_size,
            millimeter_unit=pf.millimeter_unit,
        )
        app.files.append(pjx)
        self.ws.apps[pjx] = app
        folder = os.path.dirname(pjx)
        seen: dict[str, Node] = {}
        seen_text: dict[tuple[str, str], Node] = {}  # the same entry written again: no file system work
        for kind, entries in (("program", pf.programs), ("data", pf.data)):
            for rel, node in entries:
                first = seen_text.setdefault((kind, rel.replace("\\", "/")), node)
                if first is not node:
                    sink.add(codes.DUPLICATE_FILE_DECLARATION, node, f"{kind} file '{rel}' is listed twice (first on line {first.line}); read once")
                    continue
                path = self._listed_file(rel, node, folder, kind, sink)
                if path is None:
                    app.unread.add(kind)
                    if kind == "program":
                        app.unread_programs.add(_stem(rel))
                    continue
                k = _key(path)
                if k in seen:
                    sink.add(
                        codes.DUPLICATE_FILE_DECLARATION,
                        node,
                        f"{kind} file '{rel}' is listed twice (first on line {seen[k].line}); read once",
                    )
                    continue
                seen[k] = node
                if kind == "program":
                    self.claimed.add(k)
                    read = self._read_program_file(app, path)
                else:
                    read = self._read_data_file(app, path)
                if not read:
                    app.unread.add(kind)
                    if kind == "program":
                        app.unread_programs.add(_stem(rel))
        app.ui_names, bindings = bound_names(folder, self.options.max_file_size)
        app.files.extend(bindings)
        for alias, path, auto, node in pf.libraries:
            if alias in app.libraries:
                first = app.libraries[alias].origin
                sink.add(
                    codes.DUPLICATE_FILE_DECLARATION,
                    node,
                    f"library alias {alias} is declared twice (first on line {first.line}); the first is used",
                )
                continue
            app.libraries[alias] = LibraryRef(alias, path, auto, Origin(pjx, node.line, node.col))
        for name, path, node in pf.types:
            if name in app.types:
                first = app.types[name].origin
                sink.add(
                    codes.DUPLICATE_FILE_DECLARATION,
                    node,
                    f"user type {name} is declared twice (first on line {first.line}); the first is used",
                )
                continue
            app.types[name] = TypeRef(name, path, Origin(pjx, node.line, node.col))
        return app

    def _listed_file(self, rel: str, node: Node, folder: str, kind: str, sink: Sink) -> str | None:
        path = rs.find_path(folder, rel)
        if path is not None and os.path.isfile(path):
            top = self._real_folders.get(folder)
            if top is None:
                top = self._real_folders[folder] = os.path.realpath(folder)
            if not _inside(path, folder, top):
                # A project lists its own files; reading (and quoting) a file elsewhere on the
                # machine because a project names it would leak it into reports.
                sink.add(
                    codes.LISTED_FILE_OUTSIDE_APPLICATION,
                    node,
                    f"{kind} file '{rel}' listed here is outside the application folder: not read",
                )
                self.claimed.add(_key(path))  # listed, so not "unlisted" (F012) either
                return None
            return path
        if path is not None and os.path.isdir(path):
            sink.add(codes.FILE_NOT_FOUND, node, f"{kind} file '{rel}' listed here is a folder, not a file")
        elif path is not None and os.path.lexists(path):
            try:
                check(path, Roots.user_given())
                why = "cannot be read"
            except Refused as exc:
                why = exc.reason
            sink.add(codes.FILE_NOT_FOUND, node, f"{kind} file '{rel}' listed here: {why}")
        else:
            sink.add(codes.FILE_NOT_FOUND, node, f"{kind} file '{rel}' listed here was not found")
        return None

    def _read_member(self, app: Application, path: str, kind: str) -> tuple[Node, str] | None:
        """Read one file listed by the project; its root and layout, or None if unreadable."""
        app.files.append(path)
        root = self._read(path)
        if root is None:
            return None
        layout, d = check_root(root, kind, path)
        self.diags.extend(d)
        return None if layout is None else (root, layout)

    def _read_program_file(self, app: Application, path: str) -> bool:
        """False when the file could not be read at all."""
        read = self._read_member(app, path, "programs")
        if read is None:
            return False
        root, _ = read
        sink = Sink(path, self.diags)
        for prog in read_programs(root, sink):
            self._add_program(app, prog, sink)
        return True

    def _add_program(self, app: Application, prog: Program, sink: Sink) -> None:
        _keep_first(app, app.programs, prog, "program", sink)

    def _read_data_file(self, app: Application, path: str) -> bool:
        """False when the file could not be read at all."""
        read = self._read_member(app, path, "data")
        if read is None:
            return False
        root, layout = read
        sink = Sink(path, self.diags)
        datas = read_data_s6(root, sink) if layout == "s6" else read_data_s7(root, sink)
        for data in datas:
            _keep_first(app, app.data, data, "global", sink)
        return True

    # -- .pgx without project -----------------------------------------------------------------

    def load_pgx_only(self, folder: str, files: list[str], unreadable_project: bool = False) -> Application:
        """The .pgx files of a folder (or one given alone) as an application without project."""
        folder = os.path.abspath(folder)
        app = self.ws.apps.get(folder)
        if app is None:
            app = Application(
                name=os.path.basename(folder) or folder,
                path=folder,
                layout="pgx-only",
                globals_known=False,
            )
            self.ws.apps[folder] = app
            self.diags.append(
                Diagnostic(
                    codes.NO_PROJECT_FILE,
                    (
                        "the project file (.pjx) could not be read, so the programs are checked without it"
                        if unreadable_project
                        else "no project file (.pjx)"
                    )
                    + ": global data, libraries and user types are unknown; undefined-name checks are"
                    " relaxed and the application parameters (version, stack size, length unit) take"
                    " their defaults",
                    folder,
                )
            )
        for f in files:
            f = os.path.abspath(f)
            if f in app.files:
                continue
            self._read_program_file(app, f)
        return app

    def _project_listing(self, pjx: str, target: str) -> bool:
        """Does this project list `target` among its programs or data? (no diagnostics)"""
        res = read_xml(pjx, self.options.max_file_size, self.roots, self.options.overlay)
        if res.root is None or classify(res.root) is None or classify(res.root)[0] != "project":
            return False
        pf = read_project(res.root, Sink(pjx))
        folder = os.path.dirname(pjx)
        want = _key(target)
        for rel, _node in pf.programs + pf.data:
            p = rs.find_path(folder, rel)
            if p is not None and _key(p) == want:
                return True
        return False

    # -- discovery ----------------------------------------------------------------------------

    def add_path(self, raw: str) -> None:
        if not raw:
            self.diags.append(Diagnostic(codes.FILE_NOT_FOUND, "an empty path was given: name a file or folder", "."))
            return
        path = os.path.abspath(raw)
        self._allow_target(path)
        if not os.path.lexists(path):
            self.diags.append(Diagnostic(codes.FILE_NOT_FOUND, "file or folder not found", path))
            return
        try:
            os.stat(path)
        except OSError as exc:
            reason = (
                "too many levels of symbolic links" if exc.errno == errno.ELOOP else (exc.strerror or str(exc)).lower()
            )
            self.diags.append(Diagnostic(codes.FILE_NOT_FOUND, f"cannot open: {reason}", path))
            return
        if os.path.isdir(path):
            self._add_folder(path)
        else:
            self._add_file(path)

    def _add_file(self, path: str) -> None:
        ext = _ext(path)
        if ext == _EXT_PROJECT:
            app = self.load_project(path)
            if app is not None:
                self._add_target(app.path)
            return
        if ext in (_EXT_PROGRAM, _EXT_DATA):
            self._add_member_file(path, ext)
            return
        # Any other name: look at the content.
        res = read_xml(path, self.options.max_file_size, self.roots, self.options.overlay)
        if res.root is None:
            if any(
                d.code in (codes.FILE_NOT_FOUND, codes.FILE_TOO_LARGE, codes.PATH_OUTSIDE_ROOTS)
                for d in res.diagnostics
            ):
                self.diags.extend(res.diagnostics)  # not read at all: say why
                return
            # A file named on the command line that is not even XML (a README, a script...):
            # what it is not matters, not where its XML would break (issue 16 item 10).
            self.diags.append(not_val3(path, None))
            return
        got = classify(res.root)
        if got is not None and got[0] == "project":
            app = self.load_project(path)
            if app is not None:
                self._add_target(app.path)
        elif got is not None:
            self._add_member_file(path, _EXT_PROGRAM if got[0] == "programs" else _EXT_DATA)
        else:
            self.diags.append(not_val3(path, res.root))

    def _add_member_file(self, path: str, ext: str) -> None:
        """A .pgx (or .dtx) given directly.

        If a project file in the same folder lists it, the whole application is loaded and
        becomes the target (its globals, libraries and types are needed to check the file);
        otherwise a .pgx is loaded alone as a "pgx-only" application (globals unknown).
        """
        folder = os.path.dirname(path)
        found = False
        for name in rs.listdir(folder):
            if _ext(name) != _EXT_PROJECT:
                continue
            pjx = os.path.join(folder, name)
            if os.path.isfile(pjx) and self._project_listing(pjx, path):
                app = self.load_project(pjx)
                if app is not None:
                    self._add_target(app.path)
                    found = True
        if found:
            return
        if ext == _EXT_DATA:
            self.diags.append(
                Diagnostic(
                    codes.NO_APPLICATION_FOUND,
                    "no VAL 3 application found for this data file: no .pjx in its folder lists it;"
                    " give the application folder or its .pjx",
                    path,
                )
            )
            return
        app = self.load_pgx_only(folder, [path])
        self._add_target(app.path)

    def _walk(self, top: str) -> list[_Folder]:
        out: list[_Folder] = []
        visited: set[tuple[int, int]] = set()
        stack = [top]
        while stack:
            folder = stack.pop()
            try:
                st = os.stat(folder)
            except OSError:
                continue
            ident = (st.st_dev, st.st_ino)
            if ident in visited:
                continue  # a symbolic link back to a folder already searched
            visited.add(ident)
            try:
                names = sorted(os.listdir(folder))
            except OSError as exc:
                reason = "permission denied" if isinstance(exc, PermissionError) else (exc.strerror or str(exc)).lower()
                self.diags.append(Diagnostic(codes.FILE_NOT_FOUND, f"cannot list the folder: {reason}", folder))
                continue
            projects, programs, subdirs = [], [], []
            skip = self.options.skip
            for n in names:
                p = os.path.join(folder, n)
                e = _ext(n)
                if os.path.isdir(p):
                    if n.startswith(".") or n in SKIP_DIRS or os.path.isfile(os.path.join(p, "pyvenv.cfg")):
                        continue
                    if skip is not None and skip(p, True):
                        self.excluded += 1
                        continue
                    if not self.roots.allows(p):
                        self._outside(p, "folder")
                        continue
                    subdirs.append(p)
                elif e in (_EXT_PROJECT, _EXT_PROGRAM):
                    if skip is not None and skip(p, False):
                        self.excluded += 1
                        continue
                    # a FIFO or device, or a link that leads out: reading it reports it (F001, F014)
                    if os.path.exists(p):
                        (projects if e == _EXT_PROJECT else programs).append(p)
            if projects or programs:
                out.append(_Folder(folder, projects, programs))
            stack.extend(reversed(subdirs))  # pre-order, sorted
        return out

    def _outside(self, path: str, what: str) -> None:
        self.diags.append(
            Diagnostic(
                codes.PATH_OUTSIDE_ROOTS,
                f"symbolic link to a {what} outside the folders being checked and the configured roots: not followed",
                path,
            )
        )

    def _add_folder(self, top: str) -> None:
        before = self.excluded
        folders = self._walk(top)
        if not folders:
            if self.excluded > before:
                return  # everything here is excluded: nothing to check, nothing wrong
            self.diags.append(
                Diagnostic(
                    codes.NO_APPLICATION_FOUND,
                    "no VAL 3 application (.pjx project or .pgx program file) found in this folder",
                    top,
                )
            )
            return
        loaded: dict[str, list[str]] = {}
        for f in folders:
            if not f.projects:
                continue
            main = rs.project_in_folder(f.path)
            chosen = [main] if main is not None else f.projects
            keys = []
            for pjx in chosen:
                app = self.load_project(pjx)
                if app is not None:
                    keys.append(app.path)
            loaded[f.path] = keys
        app_folders = [path for path, keys in loaded.items() if keys]
        for f in folders:
            keys = loaded.get(f.path)
            free = [p for p in f.programs if _key(p) not in self.claimed]
            owner = self._owning_project(f.path, app_folders, loaded)
            if owner is not None:
                # Inside an application folder: program files its project does not list are
                # not part of the application (the controller never loads them).
                for k in keys or ():
                    self._add_target(k)
                for p in free:
                    rel = os.path.relpath(p, os.path.dirname(owner)).replace(os.sep, "/")
                    self.diags.append(
                        Diagnostic(
                            codes.PROGRAM_FILE_NOT_LISTED,
                            f"program file not listed in {os.path.basename(owner)}: it is not part of the"
                            " application and is not checked; if it belongs to the application, add"
                            f' <Program file="{rel}" /> to <Programs> in {os.path.basename(owner)} (never done by'
                            " --fix: it would change what the controller loads), else delete it",
                            p,
                        )
                    )
                continue
            # No project here or above, or none could be read: the programs alone.
            if free:
                app = self.load_pgx_only(f.path, free, unreadable_project=bool(f.projects))
                self._add_target(app.path)

    @staticmethod
    def _owning_project(folder: str, app_folders: list[str], loaded: dict[str, list[str]]) -> str | None:
        """The project of the nearest application folder that contains `folder` (or is it)."""
        best = None
        for candidate in app_folders:
            if folder == candidate or folder.startswith(candidate.rstrip(os.sep) + os.sep):
                if best is None or len(candidate) > len(best):
                    best = candidate
        return loaded[best][0] if best is not None else None

    # -- libraries and user types -------------------------------------------------------------


def load_paths(paths: list[str], options: LoadOptions) -> tuple[Workspace, list[Diagnostic], Loader]:
    loader = Loader(options)
    for p in paths:
        try:
            loader.add_path(p)
        except (OSError, ValueError) as exc:  # pragma: no cover - a race with the file system
            reason = getattr(exc, "strerror", None) or str(exc)
            loader.diags.append(Diagnostic(codes.FILE_NOT_FOUND, f"cannot read: {reason}", os.path.abspath(p)))
    loader.resolve_all()
    loader.ws.excluded = loader.excluded
    return loader.ws, loader.diags, loader
