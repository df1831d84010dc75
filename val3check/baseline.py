"""The baseline file: findings a legacy application already had, so that only new ones fail.

    val3check lint --baseline val3check-baseline.json --update-baseline   # record today's findings
    val3check lint --baseline val3check-baseline.json                     # report only new ones

A finding is recorded by its rule code, its file (relative to the baseline file's folder), its
message with line numbers taken out ("first on line 12" -> "first on line #") and a hash of
the text of its line with every blank removed, never by its line number: lines added or
removed above it, or a re-indented line, keep it known (the way ruff's and mypy-baseline's
fingerprints work). Identical findings are counted: a third copy of a finding recorded twice is
new. Editing the flagged line itself makes the finding new, as it should.

The file is JSON, version 1, sorted, one entry per distinct finding:
`{"version": 1, "tool": "val3check", "findings": [{"code", "path", "message", "source", "count"}]}`.
"""

from __future__ import annotations

import hashlib
import json
import os
import re

from .diagnostics import Diagnostic

VERSION = 1
MAX_SIZE = 64 * 1024 * 1024  # bytes
_LINE_NUMBERS = re.compile(r"\b(lines?|line:)\s*\d+(?:\s*(?:,|and|-)\s*\d+)*", re.IGNORECASE)


class BaselineError(Exception):
    """A baseline file that cannot be read or written (exit code 2)."""


def _message(text: str) -> str:
    return _LINE_NUMBERS.sub(lambda m: m.group(1) + " #", text)


class _Lines:
    """Lines of the files findings point at, each read once through val3check.confine."""

    def __init__(self, overlay: dict[str, bytes] | None = None) -> None:
        self._files: dict[str, list[str]] = {}
        self._overlay = overlay or {}

    def line(self, path: str, number: int) -> str:
        if number < 1:
            return ""
        if path not in self._files:
            from .confine import Refused, Roots, read_bytes

            data = self._overlay.get(path)
            if data is None:
                try:
                    data = read_bytes(path, Roots.user_given(), MAX_SIZE)
                except Refused:
                    data = b""
            text = data.decode("utf-8-sig", errors="replace")
            self._files[path] = [x[:-1] if x.endswith("\r") else x for x in text.split("\n")]
        lines = self._files[path]
        return lines[number - 1] if number <= len(lines) else ""


class Baseline:
    def __init__(self, path: str, counts: dict[tuple[str, str, str, str], int] | None = None) -> None:
        self.path = os.path.abspath(path)
        self.folder = os.path.dirname(self.path)
        self.counts = dict(counts or {})

    def key(self, d: Diagnostic, lines: _Lines) -> tuple[str, str, str, str]:
        """(code, path, message, source) of a finding whose `path` is absolute."""
        rel = os.path.relpath(os.path.abspath(d.path), self.folder).replace(os.sep, "/")
        source = "".join(lines.line(d.path, d.line).split())
        digest = hashlib.sha256(source.encode("utf-8", "surrogatepass")).hexdigest()[:16] if source else ""
        return d.code, rel, _message(d.message), digest

    def split(self, findings: list[Diagnostic], overlay: dict[str, bytes] | None = None) -> tuple[list[Diagnostic], int]:
        """(the findings the baseline does not know, how many it knew)."""
        left = dict(self.counts)
        lines = _Lines(overlay)
        new, known = [], 0
        for d in findings:
            k = self.key(d, lines)
            if left.get(k, 0) > 0:
                left[k] -= 1
                known += 1
            else:
                new.append(d)
        return new, known

    @classmethod
    def of(cls, path: str, findings: list[Diagnostic], overlay: dict[str, bytes] | None = None) -> "Baseline":
        base = cls(path)
        lines = _Lines(overlay)
        for d in findings:
            k = base.key(d, lines)
            base.counts[k] = base.counts.get(k, 0) + 1
        return base

    def text(self) -> str:
        entries = [{"code": c, "path": p, "message": m, "source": s, "count": n}
                   for (c, p, m, s), n in sorted(self.counts.items(), key=lambda item: (item[0][1], item[0][0], item[0][2],
                                                                                        item[0][3]))]
        return json.dumps({"version": VERSION, "tool": "val3check", "findings": entries}, indent=2, sort_keys=True,
                          ensure_ascii=True) + "\n"

    def write(self) -> None:
        tmp = self.path + ".tmp"
        try:
            with open(tmp, "w", encoding="utf-8", newline="\n") as fh:
                fh.write(self.text())
            os.replace(tmp, self.path)
        except OSError as exc:
            raise BaselineError(f"{self.path}: cannot write the baseline: {exc.strerror or exc}") from None


def read_baseline(path: str) -> Baseline:
    from .confine import Refused, Roots, read_bytes

    try:
        data = json.loads(read_bytes(path, Roots.user_given(), MAX_SIZE).decode("utf-8"))
    except Refused as exc:
        hint = "; record one with --update-baseline" if exc.reason == "file not found" else ""
        raise BaselineError(f"{path}: cannot read the baseline: {exc.reason}{hint}") from None
    except (UnicodeDecodeError, ValueError, RecursionError) as exc:
        raise BaselineError(f"{path}: not a val3check baseline (invalid JSON: {exc})") from None
    if not isinstance(data, dict) or data.get("version") != VERSION or not isinstance(data.get("findings"), list):
        raise BaselineError(f"{path}: not a val3check baseline of version {VERSION}")
    counts: dict[tuple[str, str, str, str], int] = {}
    for entry in data["findings"]:
        try:
            key = (str(entry["code"]), str(entry["path"]), str(entry["message"]), str(entry.get("source", "")))
            n = int(entry.get("count", 1))
        except (KeyError, TypeError, ValueError):
            raise BaselineError(f"{path}: a baseline entry needs code, path, message and count") from None
        counts[key] = counts.get(key, 0) + max(n, 0)
    return Baseline(path, counts)
