"""A project file (.pjx) as what it declares: version, stack size, unit, and the program, data,
library and type files it lists (read by the loader afterwards)."""

from __future__ import annotations

from ..light_dataclass import dataclass, field
from .attribute_text import parse_bool, parse_uint
from .declaration import Sink, required
from .xmlread import Node


@dataclass(slots=True)
class ProjectFile:
    """What a project file declares, before the listed files are read."""

    version: str = ""
    stack_size: int = 5000
    millimeter_unit: bool = True
    programs: list[tuple[str, Node]] = field(default_factory=list)  # (file as written, element)
    data: list[tuple[str, Node]] = field(default_factory=list)
    libraries: list[tuple[str, str, bool, Node]] = field(default_factory=list)  # alias, path, autoload
    types: list[tuple[str, str, Node]] = field(default_factory=list)  # name, path


def read_project(root: Node, sink: Sink) -> ProjectFile:
    pf = ProjectFile()
    params = root.find("parameters")
    if params is not None:
        pf.version = (params.get("version") or "").strip()
        raw = params.get("stackSize")
        if raw is not None:
            if parse_uint(raw) is not None:
                pf.stack_size = parse_uint(raw)
            else:
                sink.f007(
                    params, f'invalid stackSize "{raw}" (expected a number of bytes); read as 5000 (manual 2.1.4.2)'
                )
        raw = params.get("millimeterUnit")
        if raw is not None:
            b = parse_bool(raw)
            if b is None:
                sink.f007(params, f'invalid millimeterUnit "{raw}" (expected true or false); read as true')
            else:
                pf.millimeter_unit = b
    for section in root.findall("programs", "programsection"):
        for n in section.findall("program"):
            f = required(n, sink, "file", "<Program> entry")
            if f is not None:
                pf.programs.append((f, n))
    for section in root.findall("database", "datasection"):
        for n in section.findall("data"):
            f = required(n, sink, "file", "<Data> entry")
            if f is not None:
                pf.data.append((f, n))
    for section in root.findall("libraries", "aliassection"):
        for n in section.findall("library", "alias"):
            alias = n.get("alias") if n.ltag == "library" else n.get("name")
            alias = (alias or "").strip()
            if not alias:
                sink.f007(
                    n, f"<{n.tag}> entry without an {'alias' if n.ltag == 'library' else 'name'} attribute: ignored"
                )
                continue
            path = (n.get("path") or "").strip()
            if not path and n.ltag == "alias":
                path = (n.get("interface") or "").strip()  # s6: the interface names the library
            if not path:
                sink.f007(n, f"library {alias} has no path: ignored")
                continue
            # A missing attribute loads the library: projects that do not want one loaded at
            # start write autoload="false" (observed on controllers; the manual is silent).
            auto = parse_bool(n.get("autoload") or "true")
            if auto is None:
                sink.f007(n, f'library {alias}: invalid autoload "{n.get("autoload")}" (expected true or false)')
                auto = False
            pf.libraries.append((alias, path, auto, n))
    for section in root.findall("types", "typesection"):
        for n in section.findall("type"):
            name = required(n, sink, "name", "<Type> entry")
            if name is None:
                continue
            path = (n.get("path") or "").strip()
            if not path:
                sink.f007(n, f"user type {name} has no path: ignored")
                continue
            pf.types.append((name, path, n))
    return pf
