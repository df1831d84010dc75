"""The cases of a batch: applications × arms × scenarios × cells × overrides, each carrying
its inputs.

A case is self-contained: the bytes of every file its run reads (the application, its
libraries and user types, the controller tree's arm.cfx, the scenario, the cell, a robot file)
travel with it, so that a worker needs no shared disk (docs/batch.md). Applications are found
the way `val3check lint` finds them (folders, controller trees), after globs are expanded."""

from __future__ import annotations

import hashlib
import itertools
import math
import os
import re
from dataclasses import dataclass, field
from typing import Any

from ..confine import Refused, Roots, read_bytes
from ..lint import discover, display_path
from .carry import Bundle
from .globs import GlobError, expand_glob, has_magic
from .sweep import MAX_CASES, Entry, Overrides, Sweep, SweepError, case_count

class CaseError(Exception):
    """A batch that cannot be made (usage error, exit code 2)."""


class TooManyCases(CaseError):
    """More than MAX_CASES cases: found before any case is made."""


@dataclass(frozen=True)
class RunOptions:
    """The single-run options every case starts from (`sim --duration`, `--max-wall`...)."""

    duration: float = 60.0
    max_wall: float = 60.0
    max_lines: int = 50_000_000
    max_memory_mb: float = 512.0
    cycles: int | None = None
    fail_on: str = "error"
    reports: bool = True  # render each case's reports and send them back (only --out-dir writes them)
    case_reports: tuple[str, ...] = ("json",)  # which (outputs.KINDS): --case-reports


@dataclass(frozen=True)
class Case:
    app: str  # display path of the application (its .pjx, or folder)
    app_name: str
    arm: str  # --robot as given; "" for the default (the controller tree's arm.cfx, else none)
    scenario: str  # display path, "" for none
    cell: str  # display path; "none" (--cell none); "" for the default (the cell beside the application, if any)
    overrides: Overrides
    # what the worker needs
    app_path: str  # absolute
    scenario_path: str | None
    cell_path: str | None
    robot_path: str | None  # absolute, when --robot names a file (URDF, arm.cfx, robot TOML)
    cwd: str  # the folder display paths are relative to
    settings: Any  # val3check.config.Settings
    options: RunOptions
    files: tuple[tuple[str, bytes], ...] = field(repr=False, default=())  # absolute path, bytes
    links: tuple[tuple[str, str], ...] = field(repr=False, default=())  # absolute path, target (carry.py)
    stubs: tuple[tuple[str, int], ...] = field(repr=False, default=())  # absolute path, size: found, refused

    def key(self) -> tuple:
        """The order of the summary: application, arm, scenario, cell, overrides."""
        ov = self.overrides
        return (self.app, self.arm, self.scenario, self.cell,
                tuple((k, v) for k, v in sorted(ov.as_dict().items())))

    def label(self) -> str:
        parts = [self.app, self.arm or "default arm", self.scenario or "no scenario"]
        if self.cell:
            parts.append(self.cell)
        if self.overrides.label():
            parts.append(self.overrides.label())
        return " | ".join(parts)

    def name(self) -> str:
        """A file name for the case's outputs: readable parts made safe (letters, digits, `._-`,
        never a leading dot, no separator), then 8 hex digits of the full key so that two cases
        never share a name (two applications of the same name in different folders)."""
        def stem(p: str) -> str:
            return os.path.splitext(os.path.basename(p))[0] if p else ""

        parts = [self.app_name, stem(self.arm) if self.robot_path else self.arm, stem(self.scenario), stem(self.cell),
                 self.overrides.label().replace(" ", "-")]
        readable = "__".join(safe_name(p) for p in parts if p)[:80]
        digest = hashlib.sha256(repr(self.key()).encode("utf-8", "backslashreplace")).hexdigest()[:8]
        return f"{readable or 'case'}__{digest}"


def safe_name(text: str) -> str:
    out = re.sub(r"[^A-Za-z0-9._-]+", "_", text).strip("._-")
    return out or "_"


def expand(patterns: list[str]) -> list[str]:
    """Paths typed on the command line with their globs expanded (`**` included) inside their
    repository (globs.py), in order, without repeats; a glob that matches nothing is an error (a
    typo must not make an empty batch that passes). A path that exists is taken as it is."""
    out: list[str] = []
    for p in patterns:
        try:
            found = expand_glob(p) if has_magic(p) and not os.path.lexists(p) else [p]
        except GlobError as exc:
            raise CaseError(f"{display_path(p)}: {exc}") from None
        if not found:
            raise CaseError(f"{display_path(p)}: no file or folder matches this pattern")
        out += [f for f in found if f not in out]
    return out


def sweep_apps(sweep: Sweep, entry: Entry) -> list[str]:
    """The paths a sweep's application entry names, its globs expanded inside the sweep's roots
    (checked before anything is listed); SweepError at the entry's line."""
    path = sweep.resolve(entry)
    try:
        if has_magic(entry.value) and not os.path.lexists(path):
            found = expand_glob(path, Roots(sweep.roots()), "the repository of the sweep file"
                                if len(sweep.roots()) == 1 else "the folder of the sweep file")
        else:
            found = [sweep.path_of(entry)] if os.path.lexists(path) else []
    except GlobError as exc:
        raise SweepError(sweep.path, entry.line, entry.col, f"{entry.value}: {exc}") from None
    if not found:
        raise SweepError(sweep.path, entry.line, entry.col, f"{entry.value}: no file or folder matches this pattern"
                         if has_magic(entry.value) else f"{entry.value}: no such file or folder")
    return found


def check_sweep_app(sweep: Sweep, entry: Entry) -> None:
    """An application entry that leads outside the sweep's roots (for a glob: the folder it
    starts from), at its line, before any entry is expanded."""
    from .globs import start_of

    path = sweep.resolve(entry)
    sweep.check_inside(entry, start_of(path) if has_magic(entry.value) and not os.path.lexists(path) else path)


@dataclass
class _App:
    path: str
    name: str
    bundle: Bundle


def find_apps(paths: list[str], settings) -> list[_App]:  # noqa: ANN001
    """Every application under `paths` (folders, controller trees, .pjx files), sorted by display
    path. A target that another target uses as a library or user type is not a case."""
    if not paths:
        return []
    for p in paths:
        if not os.path.exists(p):
            raise CaseError(f"{display_path(p)}: no such file or folder")
    found = discover(paths, settings)
    ws = found.workspace
    used: set[str] = set()
    for app in found.targets:
        used |= {r.resolved for r in list(app.libraries.values()) + list(app.types.values()) if r.resolved}
    apps = []
    for app in found.targets:
        if app.path in used:
            continue
        apps.append(_App(app.path, app.name, _bundle(ws, app, settings.max_file_size)))
    # a project file the loader could not read is a case too (not run, with the loader's reason),
    # never silently left out of the batch
    known = {a.path for a in found.targets} | used
    for d in found.found:
        if d.path.lower().endswith(".pjx") and d.path not in known and os.path.isfile(d.path):
            known.add(d.path)
            bundle = Bundle()
            bundle.add(os.path.dirname(d.path), os.path.basename(d.path), Roots.user_given(), settings.max_file_size)
            apps.append(_App(d.path, os.path.splitext(os.path.basename(d.path))[0], bundle))
    if not apps:
        raise CaseError(f"no application found in {', '.join(display_path(p) for p in paths)}")
    return sorted(apps, key=lambda a: display_path(a.path))


def _bundle(ws, app, max_size: int) -> Bundle:  # noqa: ANN001
    """The files of `app`, of its libraries and user types (transitively), the arm.cfx of its
    controller tree and the cell file beside it with its meshes: what a worker writes before it
    loads the application (carry.py)."""
    from ..collision.cellfile import CELL_FILE_NAME, MAX_CELL_BYTES
    from ..robot.catalog import find_arm_cfx

    paths: set[str] = set()
    todo, seen = [app], set()
    while todo:
        a = todo.pop()
        if a.path in seen:
            continue
        seen.add(a.path)
        paths.update(a.files)
        for ref in list(a.libraries.values()) + list(a.types.values()):
            if ref.resolved and ref.resolved in ws.apps:
                todo.append(ws.apps[ref.resolved])
    cfx = find_arm_cfx(app.path)
    if cfx is not None:
        paths.add(str(cfx))
    bundle = Bundle()
    for p in sorted(paths):  # files the loader read (a regular file each), read again through the gate
        bundle.add(os.path.dirname(p), os.path.basename(p), Roots.user_given(), max_size)
    # the cell the single run finds beside the application (collision.cellfile.find_cell), confined
    # to the application's folder as its reader confines it: a link leading out travels as a link
    _add_cell(bundle, app.folder, CELL_FILE_NAME, Roots([app.folder]), MAX_CELL_BYTES, app.folder)
    return bundle


def _add_cell(bundle: Bundle, folder: str, name: str, roots: Roots, max_size: int, app_folder: str) -> str | None:
    """Carry a cell file and the meshes it names; the path its reader opens, when it may."""
    if bundle.add(folder, name, roots, max_size) is None:
        return None
    path = bundle.follow(folder, name)
    _add_meshes(bundle, bundle.files[path], path, app_folder)
    return path


def _add_meshes(bundle: Bundle, cell_bytes: bytes, cell_path: str, app_folder: str) -> None:
    """The mesh files a cell file names (its `file` keys), each carried as its reader opens it:
    relative to the cell file's folder, inside that folder or the application's
    (collision.meshes.resolve_mesh_path). A file it refuses travels as a link or a stand-in (or
    not at all), and the case's run says why, as the single run does."""
    from ..collision.meshes import MAX_MESH_BYTES

    from .. import tomlfile

    try:
        data = tomlfile.load_bytes(cell_bytes)[0]
    except tomlfile.TomlError:
        return  # the case's run reports the cell file as the single run would
    names, todo = [], [data]
    while todo:  # iterative: a hostile file must not exhaust the stack
        v = todo.pop()
        if isinstance(v, dict):
            if isinstance(v.get("file"), str):
                names.append(v["file"])
            todo.extend(v.values())
        elif isinstance(v, list):
            todo.extend(v)
    folder = os.path.dirname(cell_path)
    roots = Roots([folder, app_folder])
    for name in sorted(set(names)):
        bundle.add(folder, name, roots, MAX_MESH_BYTES)


def _input_file(path: str, what: str, max_size: int = 64 * 1024 * 1024) -> tuple[str, bytes]:
    """A file the command line or the sweep file names (the sweep's are checked inside its
    repository first: sweep.py), read through the gate; CaseError when it cannot be."""
    absolute = os.path.abspath(path)
    try:
        return absolute, read_bytes(absolute, Roots.user_given(), max_size)
    except Refused as exc:
        if exc.reason == "file not found":
            raise CaseError(f"{what} {display_path(path)}: no such file") from None
        raise CaseError(f"{what} {display_path(path)}: {exc.reason}") from None


def _is_robot_file(spec: str) -> bool:
    return bool(spec) and (os.path.isfile(spec) or spec.lower().endswith((".urdf", ".cfx", ".toml")))


@dataclass
class Axes:
    """The values of each axis, after the command line and the sweep file are combined."""

    apps: list[str]  # paths or globs (already resolved against the sweep file)
    arms: list[str]
    scenarios: list[str | None]
    cells: list[str | None]
    overrides: list[Overrides]


def product_cases(axes: Axes, settings, options: RunOptions) -> list[Case]:  # noqa: ANN001
    apps = find_apps(expand(axes.apps), settings)
    sizes = {k: len(v) for k, v in (("applications", apps), ("arms", axes.arms), ("scenarios", axes.scenarios),
                                    ("cells", axes.cells), ("overrides", axes.overrides)) if v}
    if math.prod(sizes.values()) > MAX_CASES:
        raise TooManyCases(f"{case_count(sizes)}, more than the {MAX_CASES:,} a batch runs (docs/batch.md): split it")
    inputs = _Inputs()
    cases = [_case(app, arm, sc, cell, ov, settings, options, inputs)
             for app, arm, sc, cell, ov in itertools.product(apps, axes.arms or [""], axes.scenarios or [None],
                                                             axes.cells or [None], axes.overrides or [Overrides()])]
    return _unique(cases)


def list_cases(sweep: Sweep, defaults: Axes, settings, options: RunOptions) -> list[Case]:  # noqa: ANN001
    """The [[case]] tables of a sweep; what a table leaves out comes from the command line. The
    applications of every table are found (once per entry) and counted before any case is made."""
    found: dict[str, list[_App]] = {}
    count = 0
    for entry in sweep.cases:  # every entry inside the repository before any is expanded
        check_sweep_app(sweep, entry["application"])
    for entry in sweep.cases:
        app_entry: Entry = entry["application"]
        try:
            if app_entry.value not in found:
                found[app_entry.value] = find_apps(sweep_apps(sweep, app_entry), settings)
        except CaseError as exc:
            raise SweepError(sweep.path, app_entry.line, app_entry.col, str(exc)) from None
        count += len(found[app_entry.value])
        if count > MAX_CASES:
            raise SweepError(sweep.path, app_entry.line, app_entry.col, f"{app_entry.value}: the [[case]] tables"
                             f" make more than the {MAX_CASES:,} cases a batch runs (docs/batch.md): split the sweep")

    def path(entry: dict, k: str, default: Any) -> Any:
        if k not in entry:
            return default
        return None if entry[k] is None else sweep.resolve(entry[k])

    cases: list[Case] = []
    inputs = _Inputs()
    for entry in sweep.cases:
        arm = entry["arm"].value if "arm" in entry else (defaults.arms[0] if defaults.arms else "")
        if "arm" in entry and sweep.is_arm_file(entry["arm"]):
            arm = sweep.path_of(entry["arm"])
        scenario = path(entry, "scenario", defaults.scenarios[0] if defaults.scenarios else None)
        cell = path(entry, "cell", defaults.cells[0] if defaults.cells else None)
        if "cell" in entry and entry["cell"] is None:
            cell = "none"
        cases += [_case(app, arm, scenario, cell, entry["overrides"], settings, options, inputs)
                  for app in found[entry["application"].value]]
    return _unique(cases)


def _unique(cases: list[Case]) -> list[Case]:
    seen: dict[tuple, Case] = {}
    for c in cases:
        seen.setdefault(c.key(), c)
    return [seen[k] for k in sorted(seen)]


class _Inputs:
    """The scenario, cell and robot files of the cases, each read once for all the cases."""

    def __init__(self) -> None:
        self.read: dict[tuple[str, str], tuple[str, Bundle]] = {}

    def get(self, what: str, path: str, app_folder: str) -> tuple[str, Bundle]:
        key = (what, path, app_folder if what == "cell" else "")
        if key not in self.read:
            absolute, data = _input_file(path, what)
            bundle = Bundle()
            if what == "cell":  # as its reader opens it, with the meshes it names (relative to its own folder)
                from ..collision.cellfile import MAX_CELL_BYTES

                _add_cell(bundle, os.path.dirname(absolute), os.path.basename(absolute), Roots.user_given(),
                          MAX_CELL_BYTES, app_folder)
            else:
                bundle.files[absolute] = data
                if what == "robot" and absolute.lower().endswith(".toml"):
                    _add_robot_arm(bundle, absolute, data)
            self.read[key] = (absolute, bundle)
        return self.read[key]


def _add_robot_arm(bundle: Bundle, robot_file: str, data: bytes) -> None:
    """The URDF or arm.cfx a robot file names (robot/overrides.py), carried as its reader opens
    it: inside the robot file's repository (a stand-in `.git` marks it in the worker's mirror)."""
    from ..confine import git_top_level, repository_root
    from ..robot.urdf import MAX_URDF_SIZE

    from .. import tomlfile

    try:
        arm = tomlfile.load_bytes(data)[0].get("arm")
    except tomlfile.TomlError:
        return  # the case's run says what is wrong with the robot file
    if not isinstance(arm, str) or not arm.lower().endswith((".urdf", ".xml", ".cfx")) or "\x00" in arm:
        return
    top = git_top_level(os.path.dirname(robot_file))
    if top is not None:
        bundle.stubs[os.path.join(top, ".git")] = 0
    bundle.add(os.path.dirname(robot_file), arm, Roots([repository_root(robot_file)]), MAX_URDF_SIZE)


def _case(app: _App, arm: str, scenario: str | None, cell: str | None, ov: Overrides, settings,  # noqa: ANN001
          options: RunOptions, inputs: _Inputs) -> Case:
    parts = [app.bundle]
    sc_path = cell_path = None
    if scenario:
        sc_path, bundle = inputs.get("scenario", scenario, "")
        parts.append(bundle)
    if cell and cell.strip().lower() != "none":
        folder = os.path.dirname(app.path) if os.path.isfile(app.path) else app.path
        cell_path, bundle = inputs.get("cell", cell, folder)
        parts.append(bundle)
    robot_path = None
    if arm and arm.strip().lower() != "none" and _is_robot_file(arm):
        robot_path, bundle = inputs.get("robot", arm, "")
        parts.append(bundle)
        arm = display_path(robot_path)
    files, links, stubs = Bundle.merged(parts).items()
    shown = {"scenario": display_path(sc_path) if sc_path else "",
             "cell": display_path(cell_path) if cell_path else ("none" if cell else "")}
    return Case(app=display_path(app.path), app_name=app.name, arm=arm, **shown, overrides=ov, app_path=app.path,
                scenario_path=sc_path, cell_path=cell_path, robot_path=robot_path, cwd=os.getcwd(), settings=settings,
                options=options, files=files, links=links, stubs=stubs)
