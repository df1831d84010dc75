"""Which paths a run skips: `exclude` / `extend-exclude` patterns with gitignore semantics.

Patterns are those of a `.gitignore` file (the `pathspec` library): `templates` matches a file
or folder of that name at any depth, `archive/` only a folder, `/build` only at the top,
`legacy/**/*.pgx`, `!keep.pgx`. They are relative to the folder of the configuration file
(the current folder without one). A folder that matches is not searched at all.

As in ruff, a path named on the command line is checked even when it matches (the patterns
that match it do not apply below it either); `--force-exclude` applies them to named paths too,
which is what a pre-commit hook wants: a commit that touches only excluded files has nothing to
check.

The default, `**/usr/templates/`, skips the templates of a controller tree (Stäubli's own
application templates, not the user's code). It is checked without importing pathspec (a fifth
of lint's start-up time); any other pattern list goes through pathspec.
"""

from __future__ import annotations

import os

DEFAULT_EXCLUDE = ("**/usr/templates/",)


def _relative(path: str, base: str) -> str:
    """`path` relative to `base` with `/` separators; outside `base`, the absolute path without
    its leading `/` (anchored patterns cannot match it, unanchored ones still do)."""
    absolute = os.path.abspath(path)
    rel = os.path.relpath(absolute, base) if base else absolute
    if rel == ".." or rel.startswith(".." + os.sep) or os.path.isabs(rel):
        rel = os.path.splitdrive(absolute)[1].lstrip("/\\")
    rel = rel.replace(os.sep, "/")
    return "" if rel == "." else rel


def _default_match(rel: str, is_dir: bool) -> bool:
    """`**/usr/templates/`: a folder `templates` inside a folder `usr`, or anything below it."""
    parts = rel.split("/")
    last = len(parts) if is_dir else len(parts) - 1  # a file named templates is not the folder
    return any(parts[i] == "usr" and parts[i + 1] == "templates" for i in range(last - 1))


class Exclusion:
    """The exclude patterns of a run, relative to `base` (an absolute folder)."""

    def __init__(self, patterns, base: str) -> None:  # noqa: ANN001
        self.patterns = [p for p in patterns if p.strip() and not p.lstrip().startswith("#")]
        self.base = base
        self._spec = None

    def _matcher(self):  # noqa: ANN202
        if self._spec is None:
            import pathspec  # only for patterns other than the default (start-up time)

            self._spec = pathspec.GitIgnoreSpec.from_lines(self.patterns)
        return self._spec

    def matches(self, path: str, is_dir: bool = False) -> bool:
        """`path` (a file, or a folder when `is_dir`) is excluded."""
        if not self.patterns:
            return False
        rel = _relative(path, self.base)
        if not rel:
            return False
        if tuple(self.patterns) == DEFAULT_EXCLUDE:
            return _default_match(rel, is_dir)
        return self._matcher().match_file(rel + "/" if is_dir else rel)

    def without_patterns_matching(self, paths: list[str]) -> "Exclusion":
        """The patterns that exclude none of `paths` (paths named on the command line are
        checked, and what is below them too, unless another pattern excludes it)."""
        kept = []
        for pattern in self.patterns:
            one = Exclusion([pattern], self.base)
            if pattern.lstrip().startswith("!") or not any(
                one.matches(p, os.path.isdir(p)) for p in paths if os.path.lexists(p)
            ):
                kept.append(pattern)
        if kept == self.patterns:
            return self
        return Exclusion(kept, self.base)
