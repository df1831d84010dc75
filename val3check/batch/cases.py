"""The cases of a batch: applications × arms × scenarios × cells × overrides, each carrying
its inputs.

A case is self-contained: the bytes of every file its run reads (the application, its
libraries and user types, the controller tree's arm.cfx, the scenario, the cell, a robot file)
travel with it, so that a worker needs no shared disk (docs/batch.md). Applications are found
the way `val3check lint` finds them (folders, controller trees), after globs are expanded."""

from __future__ import annotations

import glob
import hashlib
import itertools
import os
import re
from dataclasses import dataclass, field
from typing import Any

from ..lint import discover, display_path
from .sweep import Entry, Overrides, Sweep, SweepError

_GLOB = re.compile(r"[*?\[]")


class CaseError(Exception):
    """A batch that cannot be made (usage error, exit code 2)."""


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
    """Paths with their globs expanded (`**` included), in order, without repeats; a glob that
    matches nothing is an error (a typo must not make an empty batch that passes)."""
    out: list[str] = []
    for p in patterns:
        found = sorted(glob.glob(p, recursive=True)) if _GLOB.search(p) else [p]
        if not found:
            raise CaseError(f"{display_path(p)}: no file or folder matches this pattern")
        out += [f for f in found if f not in out]
    return out


@dataclass
class _App:
    path: str
    name: str
    files: tuple[tuple[str, bytes], ...]


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
            data = _read(d.path, settings.max_file_size)
            apps.append(_App(d.path, os.path.splitext(os.path.basename(d.path))[0],
                             ((d.path, data),) if data is not None else ()))
    if not apps:
        raise CaseError(f"no application found in {', '.join(display_path(p) for p in paths)}")
    return sorted(apps, key=lambda a: display_path(a.path))


def _bundle(ws, app, max_size: int) -> tuple[tuple[str, bytes], ...]:  # noqa: ANN001
    """The files of `app`, of its libraries and user types (transitively), and the arm.cfx of
    its controller tree: what a worker writes before it loads the application."""
    from ..collision.cellfile import find_cell
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
    found = find_cell(app.folder)  # the cell the single run finds beside the application
    if found is not None:
        paths.add(str(found))
        paths.update(cell_meshes(str(found), app.folder))
    return tuple((p, data) for p in sorted(paths) if (data := _read(p, max_size)) is not None)


def cell_meshes(cell_path: str, app_folder: str) -> list[str]:
    """The mesh files a cell file names (its `file` keys) that the cell reader would open: they
    travel with the case. A file it would refuse stays behind, and the case's run says why."""
    from pathlib import Path

    from .. import tomlfile
    from ..collision.cellfile import MAX_CELL_BYTES
    from ..collision.meshes import MeshProblem, resolve_mesh_path

    try:
        with open(cell_path, "rb") as fh:
            data = tomlfile.load_bytes(fh.read(MAX_CELL_BYTES + 1))[0]
    except (OSError, tomlfile.TomlError):
        return []
    names, todo = [], [data]
    while todo:  # iterative: a hostile file must not exhaust the stack
        v = todo.pop()
        if isinstance(v, dict):
            if isinstance(v.get("file"), str):
                names.append(v["file"])
            todo.extend(v.values())
        elif isinstance(v, list):
            todo.extend(v)
    out = []
    for name in names:
        try:
            out.append(str(resolve_mesh_path(name, Path(cell_path).resolve().parent, [app_folder])))
        except (MeshProblem, OSError, ValueError):
            continue
    return out


def _read(path: str, max_size: int) -> bytes | None:
    try:
        with open(path, "rb") as fh:
            data = fh.read(max_size + 1)
    except OSError:
        return None  # the worker's loader reports the file as the single run would
    return data if len(data) <= max_size else None


def _input_file(path: str, what: str, max_size: int = 64 * 1024 * 1024) -> tuple[str, bytes]:
    absolute = os.path.abspath(path)
    if not os.path.isfile(absolute):
        raise CaseError(f"{what} {display_path(path)}: no such file")
    data = _read(absolute, max_size)
    if data is None:
        raise CaseError(f"{what} {display_path(path)}: cannot read (or larger than {max_size} bytes)")
    return absolute, data


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
    cases = [_case(app, arm, sc, cell, ov, settings, options)
             for app, arm, sc, cell, ov in itertools.product(apps, axes.arms or [""], axes.scenarios or [None],
                                                             axes.cells or [None], axes.overrides or [Overrides()])]
    return _unique(cases)


def list_cases(sweep: Sweep, defaults: Axes, settings, options: RunOptions) -> list[Case]:  # noqa: ANN001
    """The [[case]] tables of a sweep; what a table leaves out comes from the command line."""
    cases = []
    def path(entry: dict, k: str, default: Any) -> Any:
        if k not in entry:
            return default
        return None if entry[k] is None else sweep.resolve(entry[k])

    for entry in sweep.cases:
        app_entry: Entry = entry["application"]
        try:
            paths = expand([sweep.resolve(app_entry)])
            for p in paths:
                sweep.check_inside(app_entry, p)
            apps = find_apps(paths, settings)
        except CaseError as exc:
            raise SweepError(sweep.path, app_entry.line, app_entry.col, str(exc)) from None
        arm = entry["arm"].value if "arm" in entry else (defaults.arms[0] if defaults.arms else "")
        if "arm" in entry and arm.lower().endswith((".urdf", ".cfx", ".toml")):
            arm = sweep.resolve(entry["arm"])
        scenario = path(entry, "scenario", defaults.scenarios[0] if defaults.scenarios else None)
        cell = path(entry, "cell", defaults.cells[0] if defaults.cells else None)
        if "cell" in entry and entry["cell"] is None:
            cell = "none"
        cases += [_case(app, arm, scenario, cell, entry["overrides"], settings, options) for app in apps]
    return _unique(cases)


def _unique(cases: list[Case]) -> list[Case]:
    seen: dict[tuple, Case] = {}
    for c in cases:
        seen.setdefault(c.key(), c)
    return [seen[k] for k in sorted(seen)]


def _case(app: _App, arm: str, scenario: str | None, cell: str | None, ov: Overrides, settings,  # noqa: ANN001
          options: RunOptions) -> Case:
    files = list(app.files)
    sc_path = cell_path = None
    if scenario:
        sc_path, data = _input_file(scenario, "scenario")
        files.append((sc_path, data))
    if cell and cell.strip().lower() != "none":
        cell_path, data = _input_file(cell, "cell")
        files.append((cell_path, data))
        files += [(m, d) for m in cell_meshes(cell_path, os.path.dirname(app.path) if os.path.isfile(app.path)
                                              else app.path) if (d := _read(m, 64 * 1024 * 1024)) is not None]
    robot_path = None
    if arm and arm.strip().lower() != "none" and _is_robot_file(arm):
        robot_path, data = _input_file(arm, "robot")
        files.append((robot_path, data))
        arm = display_path(robot_path)
    shown = {"scenario": display_path(sc_path) if sc_path else "",
             "cell": display_path(cell_path) if cell_path else ("none" if cell else "")}
    return Case(app=display_path(app.path), app_name=app.name, arm=arm, **shown, overrides=ov, app_path=app.path,
                scenario_path=sc_path, cell_path=cell_path, robot_path=robot_path, cwd=os.getcwd(), settings=settings,
                options=options, files=tuple(sorted(dict(files).items())))


