"""The sweep file of `val3check sim --sweep` (docs/batch.md): which applications, arms,
scenarios, cells and overrides make the cases of a batch.

Two shapes: the product of axes (`applications`, `arms`, `scenarios`, `cells`, `[[overrides]]`),
or an explicit list of `[[case]]` tables. Paths are relative to the sweep file's folder.
Every mistake is reported at its line and column (val3check.tomlpos finds them: tomllib keeps
none)."""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field

from .. import tomlfile
from ..tomlpos import positions

SWEEP_VERSION = 1
MAX_SWEEP_SIZE = 512 * 1024  # bytes: a sweep is a page of TOML (10,000 [[case]] tables fit)
MAX_CASES = 10_000  # cases in one batch, counted before any is made (docs/batch.md): split larger sweeps
MAX_DURATION = 1e7  # seconds, as `sim --duration`
AXES = ("applications", "arms", "scenarios", "cells")
OVERRIDE_KEYS = ("monitor_speed", "cycles", "duration")
CASE_KEYS = ("application", "arm", "scenario", "cell") + OVERRIDE_KEYS


def case_count(sizes: dict[str, int]) -> str:
    """`2 applications × 3 arms × 2 overrides make 12 cases`: how a batch's size comes about."""
    total = math.prod(sizes.values())
    return " × ".join(f"{n:,} {k}" for k, n in sizes.items()) + f" make {total:,} case{'s' if total != 1 else ''}"


class SweepError(Exception):
    def __init__(self, path: str, line: int, col: int, message: str) -> None:
        where = f"{path}:{line}:{col}" if line else path
        super().__init__(f"{where}: {message}")
        self.path, self.line, self.col, self.message = path, line, col, message


@dataclass(frozen=True)
class Overrides:
    """What a case changes from the command line's run options; None: not changed."""

    monitor_speed: float | None = None  # percent, 0 < x <= 100 (the controller's monitor speed, 8.x)
    cycles: int | None = None
    duration: float | None = None

    def label(self) -> str:
        """`ms50 c3 d20` (empty when nothing is overridden): part of a case's name."""
        parts = []
        if self.monitor_speed is not None:
            parts.append(f"ms{self.monitor_speed:g}")
        if self.cycles is not None:
            parts.append(f"c{self.cycles}")
        if self.duration is not None:
            parts.append(f"d{self.duration:g}")
        return " ".join(parts)

    def as_dict(self) -> dict:
        return {k: getattr(self, k) for k in OVERRIDE_KEYS if getattr(self, k) is not None}


@dataclass(frozen=True)
class Entry:
    """One value of an axis as the sweep file writes it, with where it is written."""

    value: str
    line: int
    col: int


@dataclass
class Sweep:
    path: str
    mode: str  # "product" or "list"
    applications: list[Entry] = field(default_factory=list)  # paths or globs, resolved against the file's folder
    arms: list[Entry] = field(default_factory=list)
    scenarios: list[Entry | None] = field(default_factory=list)  # None: no scenario
    cells: list[Entry | None] = field(default_factory=list)  # None: no cell
    overrides: list[Overrides] = field(default_factory=list)
    # list mode: one dict per [[case]] (keys of CASE_KEYS; paths as Entry, overrides as Overrides)
    cases: list[dict] = field(default_factory=list)

    def resolve(self, entry: Entry) -> str:
        """A path written in the sweep, relative to the sweep file's folder."""
        return os.path.normpath(os.path.join(os.path.dirname(self.path), os.path.expanduser(entry.value)))

    def roots(self) -> list[str]:
        """Where the sweep's paths may lead (val3check.confine: a file read from a repository must
        not reach outside it): the git repository holding the sweep file; outside any
        repository, the sweep file's folder and the current folder."""
        from ..confine import git_top_level

        folder = os.path.dirname(os.path.abspath(self.path))
        top = git_top_level(folder)
        return [os.path.realpath(r) for r in ([top] if top else [folder, os.getcwd()])]

    def check_inside(self, entry: Entry, path: str) -> None:
        """SweepError at the entry's line when `path` (one it leads to, symbolic links resolved)
        is outside roots(): checked before anything there is opened or listed."""
        from ..confine import Roots

        if not Roots(self.roots()).allows(path):
            where = "the repository" if len(self.roots()) == 1 else "the folder"
            raise SweepError(self.path, entry.line, entry.col,
                             f"{entry.value}: leads outside {where} of the sweep file"
                             " (paths in a sweep stay inside it)")

    def path_of(self, entry: Entry) -> str:
        """The path an entry names, resolved and checked inside roots()."""
        path = self.resolve(entry)
        self.check_inside(entry, path)
        return path

    def is_arm_file(self, entry: Entry) -> bool:
        """An `arms` value that names a file (a URDF, an arm.cfx, a robot file, anything else
        with a folder or an extension, or a file beside the sweep) rather than a catalogue arm:
        it goes through check_inside like every path of the sweep, whatever its extension."""
        v = entry.value.strip()
        if v.lower() == "none":
            return False
        return (os.sep in v or "/" in v or "\\" in v or v.startswith("~") or bool(os.path.splitext(v)[1])
                or os.path.lexists(self.resolve(entry)))


def load_sweep(path: str) -> Sweep:
    from ..confine import Refused, Roots, read_bytes

    try:
        raw = read_bytes(path, Roots.user_given(), MAX_SWEEP_SIZE)
    except Refused as exc:
        raise SweepError(path, 0, 0, f"cannot read: {exc.reason}") from None
    try:
        data, text = tomlfile.load_bytes(raw)
    except tomlfile.TomlError as exc:
        raise SweepError(path, exc.line, exc.col, exc.message) from None
    return _Reader(path, text).sweep(data)


class _Reader:
    def __init__(self, path: str, text: str) -> None:
        self.path = path
        self.pos = positions(text)

    def fail(self, where: tuple, message: str, key: bool = False) -> None:
        line, col = self.pos.at(where, key=key)
        raise SweepError(self.path, line, col, message)

    def sweep(self, data: dict) -> Sweep:
        known = {"version", "description", "mode", "case", "overrides", *AXES}
        for k in data:
            if k not in known:
                self.fail((k,), f"unknown key {k!r} (allowed: {', '.join(sorted(known))})", key=True)
        version = data.get("version", SWEEP_VERSION)
        if version != SWEEP_VERSION or isinstance(version, bool):
            self.fail(("version",), f"unsupported sweep version {version!r} (expected {SWEEP_VERSION})")
        if "description" in data and not isinstance(data["description"], str):
            self.fail(("description",), "description: expected a string")
        if "case" in data:
            mode = "list"
            extra = [k for k in ("overrides", *AXES) if k in data]
            if extra:
                self.fail((extra[0],), f"{extra[0]!r} and [[case]] do not mix: a sweep is either the product of its"
                          " axes or a list of [[case]] tables", key=True)
        else:
            mode = "product"
        declared = data.get("mode", mode)
        if declared not in ("product", "list"):
            self.fail(("mode",), f'mode: "product" or "list", not {declared!r}')
        if declared != mode:
            self.fail(("mode",), 'mode = "list" needs [[case]] tables' if declared == "list"
                      else 'mode = "product" does not go with [[case]] tables (a list)')
        sweep = Sweep(self.path, mode)
        if mode == "list":
            cases = data["case"]
            if not isinstance(cases, list) or not cases or not all(isinstance(c, dict) for c in cases):
                self.fail(("case",), "[[case]]: expected one or more tables")
            if len(cases) > MAX_CASES:
                self.fail(("case", MAX_CASES), f"{len(cases):,} [[case]] tables, more than the {MAX_CASES:,} cases a batch"
                          " runs (docs/batch.md): split the sweep", key=True)
            sweep.cases = [self.case(i, c) for i, c in enumerate(cases)]
            return sweep
        sweep.applications = self.strings("applications", data)
        sweep.arms = self.strings("arms", data)
        sweep.scenarios = self.strings("scenarios", data, allow_none=True)
        sweep.cells = self.strings("cells", data, allow_none=True)
        if "overrides" in data:
            table = data["overrides"]
            if not isinstance(table, list) or not table or not all(isinstance(t, dict) for t in table):
                self.fail(("overrides",), "[[overrides]]: expected one or more tables")
            if len(table) > MAX_CASES:
                self.fail(("overrides", MAX_CASES), f"{len(table):,} [[overrides]] tables, more than the {MAX_CASES:,}"
                          " cases a batch runs (docs/batch.md): split the sweep", key=True)
            sweep.overrides = [self.overrides(("overrides", i), t, OVERRIDE_KEYS) for i, t in enumerate(table)]
        sizes = {k: len(v) for k in ("arms", "scenarios", "cells", "overrides") if (v := getattr(sweep, k))}
        if math.prod(sizes.values()) > MAX_CASES:
            biggest = max(sizes, key=lambda k: sizes[k])
            self.fail((biggest,), f"{case_count(sizes)} for each application, more than the {MAX_CASES:,} cases a"
                      " batch runs (docs/batch.md): split the sweep", key=True)
        return sweep

    def strings(self, key: str, data: dict, allow_none: bool = False) -> list:
        if key not in data:
            return []
        values = data[key]
        if not isinstance(values, list) or not values:
            self.fail((key,), f"{key}: expected a non-empty array of strings")
        if len(values) > MAX_CASES:
            self.fail((key,), f"{key}: {len(values):,} values, more than the {MAX_CASES:,} cases a batch runs"
                      " (docs/batch.md): split the sweep", key=True)
        out: list = []
        for i, v in enumerate(values):
            if not isinstance(v, str) or not v.strip():
                self.fail((key, i), f"{key}[{i}]: expected a non-empty string"
                          + (' ("none" for none)' if allow_none else ""))
            line, col = self.pos.at((key, i))
            if "\x00" in v:
                self.fail((key, i), f"{key}[{i}]: a path cannot hold a NUL character")
            out.append(None if allow_none and v.strip().lower() == "none" else Entry(v, line, col))
        return out

    def case(self, index: int, table: dict) -> dict:
        where = ("case", index)
        for k in table:
            if k not in CASE_KEYS:
                self.fail(where + (k,), f"[[case]] {index + 1}: unknown key {k!r} (allowed: {', '.join(CASE_KEYS)})",
                          key=True)
        if "application" not in table:
            self.fail(where, f"[[case]] {index + 1}: no application")
        out: dict = {}
        for k in ("application", "arm", "scenario", "cell"):
            if k in table:
                v = table[k]
                if not isinstance(v, str) or not v.strip():
                    self.fail(where + (k,), f"[[case]] {index + 1}: {k}: expected a non-empty string")
                if "\x00" in v:
                    self.fail(where + (k,), f"[[case]] {index + 1}: {k}: a path cannot hold a NUL character")
                line, col = self.pos.at(where + (k,))
                out[k] = None if k in ("scenario", "cell") and v.strip().lower() == "none" else Entry(v, line, col)
        out["overrides"] = self.overrides(where, table, OVERRIDE_KEYS, only=OVERRIDE_KEYS)
        return out

    def overrides(self, where: tuple, table: dict, allowed: tuple, only: tuple | None = None) -> Overrides:
        values: dict = {}
        for k, v in table.items():
            if only is not None and k not in only:
                continue
            at = where + (k,)
            if k not in allowed:
                self.fail(at, f"[[overrides]]: unknown key {k!r} (allowed: {', '.join(allowed)})", key=True)
            number = isinstance(v, (int, float)) and not isinstance(v, bool)
            if k == "monitor_speed" and not (number and math.isfinite(v) and 0 < v <= 100):
                self.fail(at, f"monitor_speed: a percentage above 0 and at most 100, not {v!r}")
            if k == "cycles" and not (isinstance(v, int) and not isinstance(v, bool) and v >= 1):
                self.fail(at, f"cycles: a positive whole number of cycles, not {v!r}")
            if k == "duration" and not (number and math.isfinite(v) and 0 < v <= MAX_DURATION):
                self.fail(at, f"duration: a positive number of seconds (at most {MAX_DURATION:g}), not {v!r}")
            values[k] = float(v) if k != "cycles" else v
        return Overrides(**values)
