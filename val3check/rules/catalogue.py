"""The rule catalogue: one TOML file per rule code in the top-level `rules/` folder.

A rule file holds the code, name, default severity, manual section, summary, explanation, and
at least one failing (`[[bad]]`) and one passing (`[[good]]`) example; see `rules/README.md`.
The catalogue is data, read at run time, so that `val3check rule CODE`, the SARIF rule
metadata and the example tests all come from the same text.
"""

from __future__ import annotations

import os
from collections.abc import Iterator, Mapping
from functools import cache

from ..diagnostics import Severity
from ..light_dataclass import dataclass, field
from ..resources import resource_path
from . import codes

# Rules outside the default rule set (`opt-in = true` in their file), as ruff keeps some rules out
# of its defaults: they run only when `select` or `extend-select` names their full code. Listed
# here so that deciding needs no rule file read (a test checks it against the files): style rules
# that fire on code the vendor itself writes.
OPT_IN = frozenset({codes.BARE_MULTI_VALUE_ARRAY})

# Code scheme: a family letter, then three digits (rules/README.md).
FAMILIES: dict[str, str] = {
    "F": "syntax and files",
    "N": "names and declarations",
    "T": "types and containers",
    "L": "libraries and user types",
    "S": "suspicious patterns",
    "R": "runtime and simulation",
}


@dataclass(frozen=True, slots=True)
class Example:
    description: str
    code: str | None  # body of start() in a generated application
    files: dict[str, str]  # or: files of an application tree, relative paths -> text
    target: str  # what to lint, relative to the example root
    expect: tuple[str, ...]  # "line:col" (of `code`) or "file:line:col" (of `files`)
    globals: tuple[str, ...] = ()  # declarations for `code` examples: "num nX", "private point pA[3]"
    locals: tuple[str, ...] = ()  # locals of start(): "num l_i", "string l_s[\"\"]"
    programs: dict[str, dict] = field(default_factory=dict)  # other programs: name -> {params, locals, code, access}
    version: str = "s7.11"  # the application's VAL 3 version
    duration: float = 10.0  # runtime (R) examples: simulated seconds
    scenario: str | None = None  # runtime (R) examples: the text of an I/O scenario file
    links: dict[str, str] = field(default_factory=dict)  # runtime (R) examples: dio/aio/sio global -> physical link
    robot: str | None = None
    cell: str | None = None  # runtime (R) examples: the text of a cell file (`--cell`, docs/cell.md)
    config: str | None = None  # a val3check.toml written at the example root and used
    byte_escapes: bool = False  # `\xHH` in `files` stands for the byte HH (for encoding rules)
    severity: str | None = None  # bad examples: the severity every finding of the rule is shown with


@dataclass(frozen=True, slots=True)
class Rule:
    code: str
    name: str
    severity: Severity
    manual: str
    summary: str
    explanation: str
    bad: tuple[Example, ...] = field(default=())
    good: tuple[Example, ...] = field(default=())
    fix: str = ""  # what `val3check lint --fix` does for a finding of this rule ("": no automatic fix)
    opt_in: bool = False  # not in the default rule set: runs only when selected by its full code

    @property
    def family(self) -> str:
        return self.code[0]

    @property
    def family_name(self) -> str:
        return FAMILIES.get(self.family, "")


class CatalogueError(Exception):
    pass


def _example(raw: dict, where: str) -> Example:
    code = raw.get("code")
    files = raw.get("files", {})
    if (code is None) == (not files):
        raise CatalogueError(f"{where}: an example needs exactly one of 'code' or 'files'")
    return Example(
        description=raw.get("description", ""),
        code=code,
        files=dict(files),
        target=raw.get("target", "."),
        expect=tuple(raw.get("expect", ())),
        globals=tuple(raw.get("globals", ())),
        locals=tuple(raw.get("locals", ())),
        programs=dict(raw.get("programs", {})),
        version=raw.get("version", "s7.11"),
        duration=float(raw.get("duration", 10.0)),
        scenario=raw.get("scenario"),
        links=dict(raw.get("links", {})),
        robot=raw.get("robot"),
        cell=raw.get("cell"),
        config=raw.get("config"),
        byte_escapes=bool(raw.get("byte-escapes", False)),
        severity=raw.get("severity"),
    )


def load_rule(path: str | os.PathLike) -> Rule:
    import tomllib

    try:
        with open(path, encoding="utf-8") as fh:
            raw = tomllib.loads(fh.read())
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
        raise CatalogueError(f"{path}: {exc}") from None
    try:
        code = raw["code"]
        if os.path.splitext(os.path.basename(path))[0] != code:
            raise CatalogueError(f"{path}: file name must be the rule code {code!r}")
        return Rule(
            code=code,
            name=raw["name"],
            severity=Severity.parse(raw["severity"]),
            manual=raw.get("manual", ""),
            summary=raw["summary"],
            explanation=raw.get("explanation", "").strip(),
            bad=tuple(_example(e, f"{path} [[bad]]") for e in raw.get("bad", ())),
            good=tuple(_example(e, f"{path} [[good]]") for e in raw.get("good", ())),
            fix=raw.get("fix", "").strip(),
            opt_in=bool(raw.get("opt-in", False)),
        )
    except (KeyError, ValueError) as exc:
        raise CatalogueError(f"{path}: missing or invalid field {exc}") from None


class Catalogue(Mapping):
    """Every rule, by code, in code order: a mapping whose entries are read on first use.

    The codes come from the file names; a rule's file is read when the rule is looked up, so
    that a lint run reads only the rules it reports (reading all of them was a fifth of the
    start-up of `val3check lint`)."""

    def __init__(self, folder: str) -> None:
        self._folder = folder
        names = sorted(n for n in os.listdir(folder) if n.endswith(".toml"))
        self._codes = [n[:-5] for n in names]
        self._known = set(self._codes)
        self._rules: dict[str, Rule] = {}

    def __getitem__(self, code: str) -> Rule:
        rule = self._rules.get(code)
        if rule is None:
            if code not in self._known:
                raise KeyError(code)
            rule = self._rules[code] = load_rule(os.path.join(self._folder, f"{code}.toml"))
        return rule

    def __contains__(self, code: object) -> bool:
        return code in self._known

    def __iter__(self) -> Iterator[str]:
        return iter(self._codes)

    def __len__(self) -> int:
        return len(self._codes)


@cache
def catalogue() -> Catalogue:
    """Every rule, by code, in code order (each read when first looked up)."""
    return Catalogue(resource_path("rules"))
