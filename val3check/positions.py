"""Source positions: map text extracted from an XML file back to the file itself.

Diagnostics must point at the line and column a user sees in the `.pgx` file, not in the
extracted `<Code>` block. A `SourceMap` converts (line, column) of the extracted text, both
1-based, into (line, column) of the file. Columns count Unicode code points.
"""

from __future__ import annotations

from .light_dataclass import dataclass, field


@dataclass(frozen=True, slots=True)
class Position:
    line: int  # 1-based; 0 means "the whole file"
    col: int  # 1-based code point column; 0 means "the whole line"


_LINE_STARTS: list[Position] = [Position(0, 1)]  # Position(k, 1) at index k, shared
_LINE_STARTS_MAX = 100_000  # lines kept; later ones are made anew


def line_starts(first: int, stop: int) -> list[Position]:
    """[Position(k, 1) for k in range(first, stop)]: the starts of lines copied verbatim.
    Positions are immutable, so the objects of lines seen before are reused (every code block
    of an application starts its lines at the same few hundred line numbers)."""
    have = len(_LINE_STARTS)
    if stop > have and have <= _LINE_STARTS_MAX:
        _LINE_STARTS.extend([Position(k, 1) for k in range(have, min(stop, _LINE_STARTS_MAX + 1))])
    out = _LINE_STARTS[first:stop]
    if len(out) < stop - first:
        out.extend([Position(k, 1) for k in range(max(first, len(_LINE_STARTS)), stop)])
    return out


@dataclass(slots=True)
class SourceMap:
    """Where each line of an extracted text starts in its file.

    `line_starts[k]` is the file position of the first character of text line k+1.
    `col_maps[k]`, when present, lists the file column of every character of that text line
    (needed when the XML text contained entities such as `&gt;` that shrink on extraction).
    """

    line_starts: list[Position] = field(default_factory=list)
    col_maps: dict[int, list[int]] = field(default_factory=dict)

    @classmethod
    def identity(cls, text: str, first_line: int = 1, first_col: int = 1) -> "SourceMap":
        """Text copied verbatim from the file (CDATA), starting at (first_line, first_col)."""
        n_lines = text.count("\n") + 1
        starts = [Position(first_line, first_col)]
        starts.extend(Position(first_line + k, 1) for k in range(1, n_lines))
        return cls(starts)

    def to_file(self, line: int, col: int) -> Position:
        if not self.line_starts:
            return Position(line, col)
        k = min(max(line, 1), len(self.line_starts)) - 1
        start = self.line_starts[k]
        cols = self.col_maps.get(k)
        if cols is not None:
            if 1 <= col <= len(cols):
                return Position(start.line, cols[col - 1])
            if cols:  # past the end of the line: keep counting from the last character
                return Position(start.line, cols[-1] + col - len(cols))
        return Position(start.line, start.col + col - 1)
