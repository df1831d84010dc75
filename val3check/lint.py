"""The lint pipeline: load files -> parse programs -> (semantic checks) -> filtered findings.

Each phase lives in its own package and only hands data forward; this module wires them and
applies the user's configuration (rule selection, severities, suppressions).
"""

from __future__ import annotations

import gc
import os
import re

from . import __version__, suppression
from .config import Settings
from .diagnostics import Diagnostic, Severity
from .language.target import Target, arm_family, target_for
from .light_dataclass import dataclass
from .loading import LoadOptions, load
from .loading.controller import controller_arm
from .loading.model import Application, Workspace
from .parsing.parser import parse_program
from .result import LintResult
from .rules.catalogue import catalogue
from .semantics import analyse


@dataclass(slots=True)
class LintRun:
    result: LintResult
    workspace: Workspace
    unreadable: bool  # nothing could be read at all: exit code 2
    # every path named is excluded (--force-exclude), or holds only excluded files: exit code 0
    nothing_to_check: bool = False
    # the findings reported, with their paths as on disk (in `result.diagnostics` order): what
    # --update-baseline records and --fix repairs
    findings: list = None  # type: ignore[assignment]


def display_path(path: str) -> str:
    """Relative to the current directory when inside it, POSIX slashes: stable across machines.
    Printable in every format: bytes that are not UTF-8 show as `\\xE9`, control characters as
    `\\x1b` (a file name must not drive the terminal)."""
    if not path:
        return path
    absolute = os.path.abspath(path)
    try:
        rel = os.path.relpath(absolute, os.getcwd())
    except ValueError:  # another drive on Windows
        rel = absolute
    chosen = absolute if rel == ".." or rel.startswith(".." + os.sep) else rel
    return printable_path(chosen.replace(os.sep, "/"))


MAX_MESSAGE = 1000  # characters: a message that quotes a hostile file (a 5000-parameter signature) is cut


def _capped(message: str) -> str:
    if len(message) <= MAX_MESSAGE:
        return message
    return message[:MAX_MESSAGE] + f"… ({len(message)} characters)"


_UNPRINTABLE = r"[\x00-\x1f\x7f\udc80-\udcff]"  # compiled when needed (0.4 ms: the surrogates' range)


def printable_path(text: str) -> str:
    """`text` with undecodable bytes (os.fsdecode's surrogates) and control characters escaped."""
    if text.isprintable():  # none of them is printable: nothing to escape
        return text
    return re.sub(_UNPRINTABLE, lambda m: f"\\x{ord(m.group()) & 0xFF:02x}", text)


def app_target(app: Application, settings: Settings) -> Target:
    """What `app` is checked for: the configured target (else its project file's version) and
    the arm of the controller tree it sits in, if any."""
    found = controller_arm(app.folder, settings.max_file_size) if app.layout != "pgx-only" else None
    arm, cfx = found if found else (None, "")
    return target_for(app.version, settings.target, arm, arm_family(arm) if arm else None, display_path(cfx))


def run(paths: list[str], settings: Settings, *, baseline=None, overlay: dict[str, bytes] | None = None,  # noqa: ANN001
        only: str | None = None) -> LintRun:
    """Lint `paths` with `settings`. The cyclic garbage collector is paused meanwhile: the run
    builds hundreds of thousands of small objects that live until the end (trees, symbols), and
    its periodic collections would walk them over and over (a fifth of the run); they are
    collected as usual afterwards."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        return _run(paths, settings, baseline, overlay, only)
    finally:
        if enabled:
            gc.enable()


def _given_and_exclusion(paths: list[str], settings: Settings):  # noqa: ANN202
    """The paths to load and the exclusion that applies below them (val3check.exclusion): with
    force-exclude, the named paths that match are dropped; without, they are checked and the
    patterns that match them do not apply."""
    exclusion = settings.exclusion()
    if not settings.force_exclude:
        return list(paths), [], exclusion.without_patterns_matching(list(paths))
    kept, skipped = [], []
    for p in paths:
        (skipped if os.path.lexists(p) and exclusion.matches(p, os.path.isdir(p)) else kept).append(p)
    return kept, skipped, exclusion


@dataclass(slots=True)
class Discovery:
    """What a run checks, before any program is parsed (`--show-files`, `--show-settings`)."""

    workspace: Workspace
    targets: list[Application]  # the applications checked
    found: list[Diagnostic]  # the loader's findings
    given: list[str]  # the paths named, less those force-excluded
    skipped: list[str]  # the paths named that force-exclude dropped
    skip: object  # skip(path, is_folder) -> bool, or None: the exclusion that applies


def discover(paths: list[str], settings: Settings, overlay: dict[str, bytes] | None = None) -> Discovery:
    given, skipped, exclusion = _given_and_exclusion(paths, settings)
    skip = exclusion.matches if exclusion.patterns else None
    workspace, found = load(given, LoadOptions(disk_roots=list(settings.disk_roots), max_file_size=settings.max_file_size,
                                               skip=skip, overlay=overlay))
    targets = [workspace.apps[key] for key in workspace.targets]
    if skip is not None:
        targets = [app for app in targets if not skip(app.path, app.layout == "pgx-only")]
    return Discovery(workspace, targets, found, given, skipped, skip)


def _run(paths: list[str], settings: Settings, baseline, overlay, only) -> LintRun:  # noqa: ANN001
    """`baseline`: a val3check.baseline.Baseline whose findings are not reported; `overlay`:
    absolute path -> unsaved text (loading.LoadOptions); `only`: report the findings of this
    file alone (absolute path; the rest of its application is read for context)."""
    rules = catalogue()
    found_ = discover(paths, settings, overlay)
    workspace, targets, found, skip = found_.workspace, found_.targets, found_.found, found_.skip

    directives = suppression.Suppressions()
    unparsed: set[str] = set()  # program files with syntax errors: their semantic findings are unknown
    files: set[str] = set()
    for app in targets:
        files.update(app.files)
        suppression.collect(app, directives)
        for program in app.programs.values():
            errors = parse_program(program)
            if errors:
                unparsed.add(program.origin.path)
                found.extend(errors)
        found.extend(analyse(workspace, app, app_target(app, settings)))

    left = [d for d in found if not (skip is not None and skip(d.path, False))]
    left = [d for d in left if not directives.suppresses(d.code, d.path, d.line)]
    left.extend(directives.findings(list(rules), unparsed))
    kept: dict[tuple, tuple[Diagnostic, Diagnostic]] = {}
    for d in left:
        if not settings.enabled(d.code, d.path):
            continue
        if only is not None and os.path.abspath(d.path) != only:
            continue
        rule = rules.get(d.code)
        severity = d.shown_severity(settings.severity.get(d.code) or (rule.severity if rule else Severity.ERROR))
        shown = Diagnostic(
            code=d.code,
            message=_capped(d.message),
            path=display_path(d.path),
            line=d.line,
            col=d.col,
            end_line=d.end_line,
            end_col=d.end_col,
            severity=severity,
        )
        kept.setdefault(shown.sort_key(), (d, shown))  # a library shared by two targets reports once
        files.add(d.path)
    ordered = [kept[k] for k in sorted(kept)]
    known = 0
    if baseline is not None:
        new, known = baseline.split([d for d, _ in ordered], overlay)
        new_ids = {id(d) for d in new}
        ordered = [pair for pair in ordered if id(pair[0]) in new_ids]

    result = LintResult(
        diagnostics=[shown for _, shown in ordered],
        files=sorted({display_path(f) for f in files if f and (only is None or os.path.abspath(f) == only)}),
        applications=sorted(display_path(app.path) for app in targets),
        rules=rules,
        tool_version=__version__,
        quotable={display_path(f): f for f in sorted(workspace.quotable)},
        sources={display_path(p): text for p, text in (overlay or {}).items()},
        fail_on=settings.fail_on,
        root=repository_base(paths, settings),
        baselined=known,
    )
    missing_arg = any(not os.path.exists(p) for p in paths)
    named = {os.path.abspath(p) for p in found_.given}
    # nothing left once the exclusions applied, and nothing wrong with the paths named
    nothing = (not targets and bool(found_.skipped or workspace.excluded)
               and not any(d.path in named for d in found))
    return LintRun(result=result, workspace=workspace, unreadable=missing_arg or (not targets and not nothing),
                   nothing_to_check=nothing and not missing_arg, findings=[d for d, _ in ordered])


def repository_base(paths: list[str], settings: Settings) -> str:
    """What the CI formats make paths relative to: the git top level of the first path named,
    else the configuration's folder, else the current folder."""
    from .confine import git_top_level

    first = os.path.abspath(paths[0] if paths else ".")
    folder = first if os.path.isdir(first) else os.path.dirname(first)
    return git_top_level(folder) or settings.root or os.getcwd()


def exit_code(run_: LintRun, fail_on: str) -> int:
    """0: nothing at or above `fail_on`; 1: findings; 2: input that could not be read at all."""
    if run_.unreadable:
        return 2
    if fail_on == "never":
        return 0
    threshold = Severity.parse(fail_on)
    return 1 if any(d.severity is not None and d.severity >= threshold for d in run_.result.diagnostics) else 0
