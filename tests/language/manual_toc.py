"""Read the instruction signatures of the VAL 3 s7 manual's table of contents (for the tests)."""

from __future__ import annotations

import html
import re
from dataclasses import dataclass
from pathlib import Path

# The repository is /work/main, the manual /work/shared/manual (shared/ sits beside the clone).
MANUAL = Path(__file__).resolve().parents[2].parent / "shared" / "manual" / "val3-reference-manual-s7-fr.md"
TOC_LINES = (9, 388)  # 1-based, inclusive

# Slips of this edition's table of contents (OCR), mapped to the instruction's real spelling.
TOC_SPELLING = {"getMoveld": "getMoveId", "setMoveld": "setMoveId", "In": "ln"}

_SIGNATURE = re.compile(r"(?P<returns>\w+)\s+(?P<library>@)?(?P<name>[A-Za-z]\w*)\s*\((?P<params>[^()]*)\)")
_LIBRARY = re.compile(r"identifi(?:ant|er)\s*:\s*")
_HEADING = re.compile(r"^\s*(?:<b>)?\s*(?P<number>\d+(?:\.\d+)+)\s")
_TASK = re.compile(r"void\s+(?P<name>taskCreate\w*)\s+(?P<params>.*?),\s*programme\(")
_LEADER = re.compile(r"\.{4,}.*$")


@dataclass(frozen=True)
class TocParam:
    text: str
    type: str
    ref: bool
    container: str


@dataclass(frozen=True)
class TocSignature:
    line: int
    section: str
    returns: str
    name: str
    params: tuple[TocParam, ...]
    library: bool = False
    special: bool = False

    @property
    def types(self) -> tuple[str, ...]:
        return tuple(p.type for p in self.params)

    def __str__(self) -> str:
        prefix = "identifiant:" if self.library else ""
        return f"line {self.line}: {self.returns} {prefix}{self.name}({', '.join(p.text for p in self.params)})"


def _param(text: str) -> TocParam:
    text = text.strip()
    m = re.match(r"(?P<type>\*|[A-Za-z]+)\s*(?P<ref>&)?", text)
    assert m, f"unreadable parameter {text!r}"
    container = "collection" if text.endswith('[""]') else "array" if text.endswith("[]") else "element"
    return TocParam(text, m["type"], bool(m["ref"]), container)


def _clean(raw: str) -> str:
    text = re.sub(r"\s*<sup>(.*?)</sup>", r"\1", raw)  # "trs <sup>f</sup>" is trsf
    text = html.unescape(re.sub(r"<[^>]+>", "", text))
    text = _LEADER.sub("", text)
    return text.replace("(CS8C only)", "")


def read_toc_sections(path: Path = MANUAL) -> set[str]:
    """Every numbered section of the table of contents ("2.5.4", "10.1.2.1"...)."""
    lines = path.read_text(encoding="utf-8").splitlines()[TOC_LINES[0] - 1 : TOC_LINES[1]]
    return {m["number"] for line in lines if (m := _HEADING.match(line))}


def read_toc_signatures(path: Path = MANUAL) -> list[TocSignature]:
    lines = path.read_text(encoding="utf-8").splitlines()
    found: list[TocSignature] = []
    section = ""
    for number in range(TOC_LINES[0], TOC_LINES[1] + 1):
        raw = lines[number - 1]
        heading = _HEADING.match(raw)
        if heading:
            section = heading["number"]
        if "<b>" not in raw or "(" not in raw:
            continue
        text = _clean(raw)
        task = _TASK.search(text)
        if task:
            params = [_param(p) for p in task["params"].split(",")]
            params.append(TocParam("programme(..)", "program", False, "element"))
            found.append(TocSignature(number, section, "void", task["name"], tuple(params), special=True))
            continue
        text = _LIBRARY.sub("@", text)  # "identifiant: libLoad" is called as alias:libLoad
        for m in _SIGNATURE.finditer(text):
            params = tuple(_param(p) for p in m["params"].split(",") if p.strip())
            name = TOC_SPELLING.get(m["name"], m["name"])
            found.append(TocSignature(number, section, m["returns"], name, params, library=bool(m["library"])))
    return found
