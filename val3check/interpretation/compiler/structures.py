"""The small records the compiler passes around, and what a compiled program is."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, NamedTuple

from ..memory import TypeSpace

GEOMETRY_TYPES = frozenset({"trsf", "frame", "tool", "point", "joint"})
# the value sets of config and mdesc fields (types.toml "enum" types)
ENUM_VALUES_TYPES = frozenset({"shoulder", "elbow", "wrist", "blend"})

UNKNOWN = "?"  # a type the compiler cannot know (a library loaded with another interface...)


class CompileError(Exception):
    """The program uses something the simulator cannot run (reported as R004 at run time)."""

    def __init__(self, message: str, line: int, col: int) -> None:
        super().__init__(message)
        self.line, self.col = line, col


class Code(NamedTuple):
    """Python code of an expression and its VAL 3 type."""

    text: str
    t: str


class Place(NamedTuple):
    """An assignable place: `container[key]`, or the Python local `key` when `container` is
    None; `space` resolves the names of user types."""

    container: str | None
    key: str
    t: str
    space: TypeSpace


class TypedCode(NamedTuple):
    """An rvalue's code, type, and the TypeSpace that resolves its type's name."""

    text: str
    t: str
    space: TypeSpace


class ContainerRef(NamedTuple):
    """The container object (`Arr`/`Coll`) of an array or collection variable or field."""

    code: str
    t: str
    cont: str  # "array" | "collection"
    ndim: int
    space: TypeSpace


class FieldInfo(NamedTuple):
    t: str
    cont: str  # "element" | "array" | "collection"
    space: TypeSpace
    ndim: int
    name: str  # the canonical name (a file alias, mDesc.tmax, names the field tvel)


class VariableArg(NamedTuple):
    """A variable given to an instruction on any variable (size, insert...): its container
    code, the index tuple's code (or 'None'), and its container kind."""

    container: str
    index: str
    cont: str


@dataclass
class VarInfo:
    name: str
    t: str  # base type ("num", "point"...) or a user type name
    cont: str  # "element" | "array" | "collection"
    ndim: int = 1
    store: str = "py"  # py | box | ref | obj | g | lib
    slot: int = 0  # index in L for "box"
    alias: str = ""  # for "lib"
    space: TypeSpace | None = None  # where the type's name is resolved


class LoopSite(NamedTuple):
    """A loop statement of a program (while, do, for: 2.2.5) in the generated code: where it is
    written, the Python lines it spans, and the local `var`, a one-element list counting the
    passes of the current entry (a new list each time the loop is entered). What a motion
    instruction reads to know which pass of which loops records it (machine.loop_passes)."""

    kind: str  # "while" | "do" | "for"
    line: int
    col: int
    py_first: int
    py_last: int
    var: str


@dataclass
class Compiled:
    """One program, ready to run."""

    name: str
    func: Any  # generator function (T, *args)
    params: list  # model Parameters
    pos: dict[int, tuple[int, int]]  # python line -> (file line, col)
    path: str
    filename: str
    frame_bytes: int
    source: str = ""
    error: CompileError | None = None
    # python line -> (sequence, index, length) of the VAL 3 instruction (taskResume jumps)
    bpos: dict = field(default_factory=dict)
    loops: list[LoopSite] = field(default_factory=list)  # in the order they are written
    _loops_at: dict = field(default_factory=dict, repr=False, compare=False)
    _lines: dict = field(default_factory=dict, repr=False, compare=False)
    _at: dict = field(default_factory=dict, repr=False, compare=False)

    def line_of(self, frame) -> int:
        """The Python line a frame of this program is at. `f_lineno` scans the code's line table
        from its start (tens of microseconds at the end of a long program, asked at each motion
        command): the lines of the program's own code are kept by instruction offset, which
        determines the line (a lambda of the program has other code: asked each time)."""
        func = self.func
        if func is None or frame.f_code is not func.__code__:
            return frame.f_lineno
        at = frame.f_lasti
        line = self._lines.get(at)
        if line is None:
            line = self._lines[at] = frame.f_lineno
        return line

    def at(self, frame) -> tuple[tuple[str, int, int, str] | None, tuple[LoopSite, ...]]:
        """What a frame of this program is at: the file position of its line (path, line,
        column, program; None for a Python line without one) and the loops that line is in.
        Kept by instruction offset for the program's own code, like `line_of` (each motion
        command and tool action asks, from `Machine.line_running` and `loop_passes`)."""
        func = self.func
        if func is None or frame.f_code is not func.__code__:
            return self._at_line(frame.f_lineno)
        at = frame.f_lasti
        found = self._at.get(at)
        if found is None:
            found = self._at[at] = self._at_line(self.line_of(frame))
        return found

    def _at_line(self, py_line: int) -> tuple[tuple[str, int, int, str] | None, tuple[LoopSite, ...]]:
        lc = self.pos.get(py_line)
        return (None if lc is None else (self.path, lc[0], lc[1], self.name)), self.loops_at(py_line)

    def loops_at(self, py_line: int) -> tuple[LoopSite, ...]:
        """The loops whose Python lines hold `py_line`, outermost first (memoised: a motion
        instruction asks at each command it records)."""
        sites = self._loops_at.get(py_line)
        if sites is None:
            sites = self._loops_at[py_line] = tuple(s for s in self.loops if s.py_first <= py_line <= s.py_last)
        return sites
