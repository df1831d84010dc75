"""The application model every later phase reads: one shape for s6, s7 and s8 files.

Positions (`path`, `line`, `col`) are those of the XML element that declares the thing, so
that a diagnostic about a declaration points at the line the user would edit.
"""

from __future__ import annotations

from enum import Enum

from ..light_dataclass import dataclass, field
from ..positions import SourceMap

TYPE_CHECKING = False  # not typing's: importing typing costs 3 ms at lint's start-up
if TYPE_CHECKING:
    from typing import Any


class Container(str, Enum):
    """Manual 2.3.4."""

    ELEMENT = "element"
    ARRAY = "array"
    COLLECTION = "collection"


@dataclass(slots=True)
class Origin:
    """Where a declaration is written."""

    path: str
    line: int = 0
    col: int = 0


@dataclass(slots=True)
class Parameter:
    """A program parameter (manual 2.6)."""

    name: str
    type: str  # as written in the file: "num", "pointRx", a user type name...
    container: Container
    dimensions: int  # 1, 2 or 3 for arrays; 0 for element/collection
    by_reference: bool
    origin: Origin


@dataclass(slots=True)
class Local:
    """A local variable of a program (manual 2.5.2)."""

    name: str
    type: str
    container: Container
    sizes: tuple[int, ...]  # () for a collection; (1,) for an element
    origin: Origin


@dataclass(slots=True)
class Program:
    name: str
    access: str  # "public" | "private"
    parameters: list[Parameter]
    locals: list[Local]
    code: str | None  # the text of <Code>/<code>, None when the element is missing
    code_map: SourceMap  # maps positions in `code` to positions in `origin.path`
    origin: Origin
    description: str = ""
    body: Any = None  # the parsed AST (val3check.parsing.ast.ProgramBody), set by the parser


@dataclass(slots=True)
class Value:
    """One value of a global: `key` is the index ("0", "1 2" for 2-D) or the collection key.

    `fields` holds every field of the type with defaults filled in (manual 2.4 and the type's
    chapter), converted: num -> float, bool -> bool, others -> str. `given` lists the field
    names that the file actually wrote. User-type values keep their fields in `members`.
    Field keys are those of `loading.types.DEFAULTS`: the manual's field names (mdesc `tvel`,
    tool `gripper`), whatever spelling the file used (`tmax`, `ioLink`: `loading.types.field_key`).
    """

    key: str
    fields: dict[str, Any]
    given: tuple[str, ...]
    origin: Origin
    members: dict[str, "Data"] = field(default_factory=dict)
    father: str | None = None  # this value's frame/tool parent ("fPallet[0]"), from fatherId


@dataclass(slots=True)
class Data:
    """A global variable (manual 2.5), or a field of a user-type value.

    `values` lists the values the file writes, in file order; indices or keys it does not
    write take the type's defaults (or, for user types, the type application's defaults).
    """

    name: str
    type: str
    container: Container
    sizes: tuple[int, ...]  # array sizes; () for element and collection
    access: str  # "public" | "private"
    values: list[Value]
    origin: Origin
    father: str | None = None  # frame/tool/point parent, e.g. "world[0]", "fPallet[0]" (from fatherId)
    link: str | None = None  # dio/aio/sio/screen physical link, tool gripper link


@dataclass(slots=True)
class LibraryRef:
    """A library declared in the project file (manual chapter 6)."""

    alias: str
    path: str  # as written, e.g. "Disk://lib/lib.pjx"
    autoload: bool
    origin: Origin
    resolved: str | None = None  # absolute path of the library's .pjx once found
    # where the library was found by name when its path led nowhere (F016, shown as reports
    # show paths): a guess; "" when found at its place
    guessed: str = ""


@dataclass(slots=True)
class TypeRef:
    """A user type declared in the project file (manual chapter 7)."""

    name: str
    path: str
    origin: Origin
    resolved: str | None = None
    guessed: str = ""  # as LibraryRef.guessed


@dataclass(slots=True)
class Application:
    name: str
    path: str  # the .pjx file, or the folder for a .pgx-only application
    layout: str  # "s7" (also s8 files), "s6", or "pgx-only"
    version: str = ""  # e.g. "s7.11", "s8.3"; "" when unknown
    stack_size: int = 5000  # bytes, manual 2.1.4.2
    millimeter_unit: bool = True  # manual 2.1.4.1
    programs: dict[str, Program] = field(default_factory=dict)
    data: dict[str, Data] = field(default_factory=dict)
    libraries: dict[str, LibraryRef] = field(default_factory=dict)
    types: dict[str, TypeRef] = field(default_factory=dict)
    files: list[str] = field(default_factory=list)  # every file read for this application
    globals_known: bool = True  # False for .pgx files without a .pjx/.dtx
    # "data" / "program" when a file of that kind listed by the project could not be read:
    # the application's globals (or programs) are then only partly known.
    unread: set[str] = field(default_factory=set)
    # Lower-case names of the listed program files that could not be read ("pick" for
    # pick.pgx): the programs they would define may exist; every other name is really undefined.
    unread_programs: set[str] = field(default_factory=set)
    # Lower-case names the s8 web user pages bind to (`*.bindings.json`, loading/bindings.py):
    # programs and globals used by the pages.
    ui_names: set[str] = field(default_factory=set)

    @property
    def folder(self) -> str:
        import os

        return self.path if self.layout == "pgx-only" else os.path.dirname(self.path)

    @property
    def version_major(self) -> int | None:
        """6, 7 or 8 from "s7.11"; None when unknown."""
        v = self.version.strip().lower()
        if len(v) >= 2 and v[0] == "s" and v[1] in "0123456789":
            return int(v[1])
        return None


@dataclass(slots=True)
class Workspace:
    """Everything one run loaded: the target applications and the libraries/types they use.

    `apps` maps an application's absolute path (its .pjx, or folder for pgx-only) to the
    application, so that a library used by several targets is loaded once.
    """

    targets: list[str] = field(default_factory=list)  # keys into `apps`, in discovery order
    apps: dict[str, Application] = field(default_factory=dict)
    # where paths written in files may lead (val3check.confine.Roots), set by the loader; the
    # simulator's libLoad resolves paths within the same roots
    roots: Any = None
    # the repositories of the targets and their index of applications by name (resolve.py): the
    # simulator's libLoad resolves a path as the loader does, the guess by name included
    repos: list[str] = field(default_factory=list)
    repository_index: Any = None
    # files read as VAL 3 (absolute paths): the only files a report may quote
    quotable: set[str] = field(default_factory=set)
    excluded: int = 0  # folders and files skipped because the configuration excludes them

    def library(self, app: Application, alias: str) -> Application | None:
        ref = app.libraries.get(alias)
        return self.apps.get(ref.resolved) if ref and ref.resolved else None

    def user_type(self, app: Application, name: str) -> Application | None:
        ref = app.types.get(name)
        return self.apps.get(ref.resolved) if ref and ref.resolved else None
