"""The times of a scenario that `sim --explore` moves (docs/explore.md), and the scenario text
of a variant.

A timing is a time or delay written in the scenario file: `[[events]] at`, `[[reactions]] after`,
`[[keys]] at`, `[[serial]] at` and `after`, `[controller] changes` `at`. Each has its nominal
value (what a plain `sim` uses) and the range it may take: `{ min = ..., max = ... }` written in
place of the number, else the number ± the jitter (never below 0). A key left out (a reaction
without `after`) is not moved: write it (`after = 0`) to have it moved.

A variant is the same text with the numbers (and ranges) of its timings replaced, so that its
comments and layout stay the user's and a diff against the nominal shows only the times."""

from __future__ import annotations

import re
from dataclasses import dataclass

from ...simulation.scenario import time_range

RESOLUTION = 0.001  # s: values are drawn and shrunk in milliseconds (the scheduler's cycle is 4 ms)
_TABLES = (("events", ("at",)), ("reactions", ("after",)), ("keys", ("at",)), ("serial", ("at", "after")))


@dataclass(frozen=True)
class Timing:
    path: tuple  # the key in the parsed scenario: ("reactions", 1, "after")
    label: str  # for people: "[[reactions]] #2 after"
    line: int
    nominal: float
    lo: float
    hi: float
    when: str = ""  # reactions: the signal whose change starts the delay; serial: the text answered
    becomes: object = True  # reactions: the value of `when` that starts it

    @property
    def absolute(self) -> bool:
        """A time from the start of the run (not a delay after something)."""
        return self.path[-1] == "at"

    def clamp(self, value: float) -> float:
        return round(min(self.hi, max(self.lo, value)), 6)

    def shown(self, value: float) -> str:
        d = value - self.nominal
        return f"{self.label} (line {self.line}): {fmt(self.nominal)} -> {fmt(value)} s ({d:+.3f} s)"


def fmt(value: float) -> str:
    """A TOML float, shortest first: 0.25, 1.0, 0.304."""
    text = f"{value:.6f}".rstrip("0")
    return text + "0" if text.endswith(".") else text


def timings(data: dict, text: str, jitter: float) -> list[Timing]:
    """Every timing of the parsed scenario `data` (its text for the lines), in file order."""
    from ...tomlpos import positions

    pos = positions(text)
    found = []
    for table, keys in _TABLES:
        entries = data.get(table, [])
        for i, entry in enumerate(entries if isinstance(entries, list) else []):
            for key in keys:
                if isinstance(entry, dict) and key in entry:
                    extra = {}
                    if table == "reactions":
                        extra = {"when": str(entry.get("when", "")), "becomes": entry.get("becomes", True)}
                    found.append(_timing((table, i, key), f"[[{table}]] #{i + 1} {key}", entry[key], pos, jitter,
                                         **extra))
    changes = data.get("controller", {}).get("changes", []) if isinstance(data.get("controller"), dict) else []
    for i, ch in enumerate(changes if isinstance(changes, list) else []):
        if isinstance(ch, dict) and "at" in ch:
            found.append(_timing(("controller", "changes", i, "at"), f"[controller] changes #{i + 1} at", ch["at"],
                                 pos, jitter))
    # a value the positions reader did not follow (it stops on what it does not know) cannot be
    # rewritten: it stays nominal
    return [t for t in found if t is not None and t.path in pos.values]


def _timing(path: tuple, label: str, value: object, pos, jitter: float, **extra) -> Timing | None:
    r = time_range(value)
    if r is None:  # the scenario's reader reports it
        return None
    nominal, lo, hi = r
    if not isinstance(value, dict):
        lo, hi = max(0.0, nominal - jitter), nominal + jitter
    return Timing(path, label, pos.at(path)[0], nominal, round(lo, 6), round(hi, 6), **extra)


def variant_text(text: str, ts: list[Timing], values: tuple[float, ...]) -> str:
    """The scenario text with each timing's value written in place of its number or range."""
    from ...tomlpos import positions

    pos = positions(text)
    starts = [0] + [m.end() for m in re.finditer(r"\n", text)]
    edits = []
    for t, v in zip(ts, values, strict=True):
        line, col = pos.values.get(t.path, (0, 0))
        if not line:
            raise ValueError(f"{t.label}: its value was not found in the text")
        start = starts[line - 1] + col - 1
        edits.append((start, _value_end(text, start), fmt(v)))
    out = []
    last = 0
    for start, end, new in sorted(edits):
        out += [text[last:start], new]
        last = end
    return "".join(out + [text[last:]])


_NUMBER = re.compile(r"[-+0-9_.eEinfa]+")


def _value_end(text: str, start: int) -> int:
    """Where the number or inline table (a range: numbers only) that starts at `start` ends."""
    if text.startswith("{", start):
        return text.index("}", start) + 1
    m = _NUMBER.match(text, start)
    if m is None:
        raise ValueError(f"no number at offset {start}")
    return m.end()
