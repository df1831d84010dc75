"""Configuration: `[tool.val3check]` in pyproject.toml, or a val3check.toml, like ruff's.

The file is found by walking up from the first target (or the current directory). Command-line
options override it. Keys (kebab-case, as ruff):

    select = ["F", "L"]             # codes or prefixes to enable (default: every rule)
    extend-select = ["S101"]        # added to `select`
    ignore = ["S1"]                 # codes or prefixes to disable
    per-file-ignores = { "legacy/**" = ["S"] }   # glob, relative to the config file's folder
    severity = { S101 = "error" }   # change a rule's severity
    fail-on = "error"               # error | warning | info | never
    disk-roots = ["../controller/usr/usrapp"]    # where `Disk://` libraries are also searched
    exclude = ["build/"]            # gitignore patterns of what is skipped (replaces the default,
                                    # ["**/usr/templates/"]); extend-exclude adds to it
    force-exclude = true            # also skip the paths named on the command line that match
    baseline = "val3check-baseline.json"   # findings recorded there are not reported (val3check.baseline)
    max-file-size = 16777216        # bytes; larger files are reported (F002) and skipped
    target = "CS9"                  # controller and/or VAL 3 version: "CS9", "s8.13", "CS8 s7.11"
                                    # (default: each application's project file version)
"""

from __future__ import annotations

import fnmatch
import os
import re

from .diagnostics import Severity
from .excerpt import excerpt
from .exclusion import DEFAULT_EXCLUDE, Exclusion
from .language.target import TargetError, TargetSpec, parse_target
from .light_dataclass import dataclass, field
from .rules.catalogue import OPT_IN

CONFIG_NAMES = ("val3check.toml", "pyproject.toml")
# `[tool.val3check]`, `[tool.val3check.severity]`, `tool.val3check.x = `, or a `[tool]` table
# (which may hold `val3check = {...}`): a pyproject.toml without any of them has no section of ours.
# Linear: blanks before the header are spaces and tabs of its own line (`^\s*` would run over all
# the blank lines below each line start: quadratic on a file of newlines).
_TOOL_SECTION = re.compile(rb"tool\s*\.\s*\"?val3check|^[ \t]*\[[ \t]*tool[ \t]*\]", re.MULTILINE)
FAIL_ON_CHOICES = ("error", "warning", "info", "never")


class ConfigError(Exception):
    """A configuration file or option that cannot be used (exit code 2)."""


@dataclass(slots=True)
class Settings:
    select: list[str] = field(default_factory=lambda: [""])  # "" is the prefix of every code
    extend_select: list[str] = field(default_factory=list)
    ignore: list[str] = field(default_factory=list)
    per_file_ignores: dict[str, list[str]] = field(default_factory=dict)
    severity: dict[str, Severity] = field(default_factory=dict)
    fail_on: str = "error"
    disk_roots: list[str] = field(default_factory=list)
    exclude: list[str] = field(default_factory=lambda: list(DEFAULT_EXCLUDE))  # gitignore patterns
    extend_exclude: list[str] = field(default_factory=list)
    force_exclude: bool = False  # the paths named on the command line are excluded too
    baseline: str = ""  # the baseline file (absolute), "" for none
    max_file_size: int = 16 * 1024 * 1024
    target: TargetSpec | None = None  # None: each application's project file version
    root: str = ""  # folder of the configuration file, "" when none was found
    source: str = ""  # path of the configuration file that was read

    def enabled(self, code: str, path: str | None = None) -> bool:
        """Ruff's rule: the longest matching prefix among select and ignore wins. An opt-in rule
        (rules.catalogue.OPT_IN) runs only when select or extend-select names its full code."""
        if code in OPT_IN and code not in self.select and code not in self.extend_select:
            return False
        best_sel = max((len(p) for p in self.select + self.extend_select if code.startswith(p)), default=-1)
        best_ign = max((len(p) for p in self.ignore if code.startswith(p)), default=-1)
        if best_sel < 0 or best_ign >= best_sel:
            return False
        if path is not None and self.per_file_ignores:
            rel = self._relative(path)
            for pattern, codes in self.per_file_ignores.items():
                if _glob_match(rel, pattern) and any(code.startswith(c) for c in codes):
                    return False
        return True

    def unknown_codes(self, known: list[str]) -> list[str]:
        """Codes or prefixes that match no rule: a typo must not silently select nothing."""
        asked = set(self.select + self.extend_select + self.ignore) | set(self.severity)
        for values in self.per_file_ignores.values():
            asked.update(values)
        return sorted(p for p in asked if p and not any(c.startswith(p) for c in known))

    def exclusion(self) -> Exclusion:
        """`exclude` and `extend-exclude`, relative to the configuration's folder."""
        return Exclusion(self.exclude + self.extend_exclude, self.root or os.getcwd())

    def excluded(self, path: str, is_dir: bool = False) -> bool:
        return self.exclusion().matches(path, is_dir)

    def _relative(self, path: str) -> str:
        base = self.root or os.getcwd()
        rel = os.path.relpath(os.path.abspath(path), base)
        return rel.replace(os.sep, "/")


def _glob_match(rel: str, pattern: str) -> bool:
    pattern = pattern.rstrip("/")
    if fnmatch.fnmatchcase(rel, pattern):
        return True
    # a folder pattern covers everything below it
    return fnmatch.fnmatchcase(rel, pattern + "/*")


def find_config(start: str, warn=None) -> str | None:  # noqa: ANN001
    """The first val3check.toml, or pyproject.toml with a [tool.val3check] table, at or above
    `start`. A pyproject.toml that cannot be read is skipped, and said so through `warn`."""
    folder = os.path.abspath(start) if start else os.getcwd()
    if not os.path.isdir(folder):
        folder = os.path.dirname(folder)
    while True:
        for name in CONFIG_NAMES:
            candidate = os.path.join(folder, name)
            if os.path.isfile(candidate) and _has_section(candidate, name, warn):
                return candidate
        parent = os.path.dirname(folder)
        if parent == folder:
            return None
        folder = parent


MAX_CONFIG_SIZE = 4 * 1024 * 1024  # bytes: a configuration is a few lines
MAX_FILE_SIZE_LIMIT = 1 << 30  # max-file-size cannot exceed 1 GiB


def _read_toml(path: str) -> dict:
    """The TOML document at `path`, read through val3check.confine (a regular file, its size
    checked before reading) and val3check.tomlfile; ConfigError for anything else."""
    from . import tomlfile
    from .confine import Refused, Roots, read_bytes

    try:
        data = read_bytes(path, Roots.user_given(), MAX_CONFIG_SIZE)
        return tomlfile.load_bytes(data)[0]
    except Refused as exc:
        raise ConfigError(f"{path}: cannot read configuration: {exc.reason}") from None
    except tomlfile.TomlError as exc:
        where = f"{path}:{exc.line}:{exc.col}" if exc.line else path
        raise ConfigError(f"{where}: cannot read configuration: {exc.message}") from None


def _read_bytes_capped(path: str) -> bytes:
    from .confine import Refused, Roots, read_bytes

    try:
        return read_bytes(path, Roots.user_given(), MAX_CONFIG_SIZE)
    except Refused as exc:
        raise ConfigError(f"{path}: cannot read configuration: {exc.reason}") from None


def _tool_table(data: dict, path: str) -> dict | None:
    """`[tool.val3check]`, None when absent; ConfigError when `tool` or it is not a table."""
    tool = data.get("tool")
    if tool is None:
        return None
    if not isinstance(tool, dict):
        raise ConfigError(f"{path}: 'tool' must be a table")
    section = tool.get("val3check")
    if section is not None and not isinstance(section, dict):
        raise ConfigError(f"{path}: [tool.val3check] must be a table")
    return section


def _has_section(path: str, name: str, warn=None) -> bool:  # noqa: ANN001
    if name != "pyproject.toml":
        return True
    try:
        data = _read_bytes_capped(path)
    except ConfigError as exc:
        if warn is not None:
            warn(f"{exc}; this pyproject.toml is ignored")
        return False
    if not _TOOL_SECTION.search(data):
        return False  # most pyproject.toml files are not ours: no need to parse them
    try:
        tool = _read_toml(path).get("tool")
    except ConfigError as exc:
        if warn is not None:
            warn(f"{exc}; this pyproject.toml is ignored")
        return False
    if tool is not None and not isinstance(tool, dict):
        if warn is not None:
            warn(f"{path}: 'tool' is not a table; this pyproject.toml is ignored")
        return False
    return tool is not None and "val3check" in tool  # a [tool.val3check] of the wrong type: load_settings says so


def _str_list(value, key: str, path: str) -> list[str]:
    if isinstance(value, str):
        value = [value]
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        raise ConfigError(f"{path}: '{key}' must be a list of strings")
    return [v.strip().upper() if key in ("select", "extend-select", "ignore") else v for v in value]


def _paths(value, key: str, path: str) -> list[str]:
    """`_str_list` of paths: a NUL character (no file name holds one) is reported at its line."""
    values = _str_list(value, key, path)
    if any("\x00" in v for v in values):
        raise ConfigError(f"{path}:{_line_of(path, key)}: '{key}': a path cannot hold a NUL character")
    return values


def _line_of(path: str, key: str) -> int:
    """The line where `key` is set in the file at `path` (tomllib keeps no positions); 0 when not found."""
    import re

    pattern = re.compile(r"""^[ \t]*["']?""" + re.escape(key) + r"""["']?[ \t]*=""")
    try:
        lines = _read_bytes_capped(path).decode("utf-8", "replace").splitlines()
    except ConfigError:
        return 0
    return next((i for i, line in enumerate(lines, 1) if pattern.match(line)), 0)


KNOWN_KEYS = {
    "select", "extend-select", "ignore", "per-file-ignores", "severity", "fail-on", "disk-roots", "exclude", "max-file-size",
    "target", "extend-exclude", "force-exclude", "baseline",
}


def load_settings(path: str) -> Settings:
    data = _read_toml(path)
    if os.path.basename(path) == "pyproject.toml":
        data = _tool_table(data, path) or {}
    elif "tool" in data:
        section = _tool_table(data, path)
        if section is not None:
            data = section
    unknown = sorted(set(data) - KNOWN_KEYS)
    if unknown:
        shown = ", ".join(excerpt(k) for k in unknown[:10]) + (f" and {len(unknown) - 10} more" if len(unknown) > 10 else "")
        raise ConfigError(f"{path}: unknown option(s): {shown} (known: {', '.join(sorted(KNOWN_KEYS))})")
    root = os.path.dirname(os.path.abspath(path))
    s = Settings(root=root, source=path)
    if "select" in data:
        s.select = _str_list(data["select"], "select", path)
    s.extend_select = _str_list(data.get("extend-select", []), "extend-select", path)
    s.ignore = _str_list(data.get("ignore", []), "ignore", path)
    pfi = data.get("per-file-ignores", {})
    if not isinstance(pfi, dict):
        raise ConfigError(f"{path}: 'per-file-ignores' must be a table of glob = [codes]")
    s.per_file_ignores = {k: [c.upper() for c in _str_list(v, "per-file-ignores", path)] for k, v in pfi.items()}
    sev = data.get("severity", {})
    if not isinstance(sev, dict):
        raise ConfigError(f"{path}: 'severity' must be a table of CODE = \"error|warning|info\"")
    try:
        s.severity = {k.upper(): Severity.parse(str(v)) for k, v in sev.items()}
    except ValueError as exc:
        raise ConfigError(f"{path}: severity: {excerpt(str(exc), 200)}") from None
    fail_on = data.get("fail-on", "error")
    fail_on = fail_on.lower() if isinstance(fail_on, str) else ""
    if fail_on not in FAIL_ON_CHOICES:
        raise ConfigError(f"{path}: 'fail-on' must be one of {', '.join(FAIL_ON_CHOICES)}")
    s.fail_on = fail_on
    s.disk_roots = [os.path.normpath(os.path.join(root, d)) for d in _paths(data.get("disk-roots", []), "disk-roots", path)]
    if "exclude" in data:
        s.exclude = _str_list(data["exclude"], "exclude", path)
    s.extend_exclude = _str_list(data.get("extend-exclude", []), "extend-exclude", path)
    force = data.get("force-exclude", False)
    if not isinstance(force, bool):
        raise ConfigError(f"{path}: 'force-exclude' must be true or false")
    s.force_exclude = force
    baseline = data.get("baseline", "")
    if not isinstance(baseline, str):
        raise ConfigError(f"{path}: 'baseline' must be the path of a file")
    _paths(baseline, "baseline", path)
    s.baseline = os.path.normpath(os.path.join(root, baseline)) if baseline else ""
    size = data.get("max-file-size", s.max_file_size)
    if not isinstance(size, int) or isinstance(size, bool) or not 0 < size <= MAX_FILE_SIZE_LIMIT:
        raise ConfigError(f"{path}: 'max-file-size' must be a number of bytes from 1 to {MAX_FILE_SIZE_LIMIT}")
    s.max_file_size = size
    if "target" in data:
        try:
            s.target = parse_target(data["target"])
        except TargetError as exc:
            raise ConfigError(f"{path}: {excerpt(str(exc), 300)}") from None
    return s
