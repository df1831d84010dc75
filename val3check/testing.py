"""Write VAL 3 applications as Stäubli's tools save them (s7 layout: `.pjx`, `.pgx`, `.dtx`),
for tests, benchmarks and anyone checking a tool against small applications.

    folder = write_app(tmp, "begin\\n  nCount = nCount + 1\\nend\\n", globals_=["num nCount"])

Declarations are written as in VAL 3 Studio: "num nGrid[3,4]", "string sColl[\\"\\"]" (a
collection), "num& x_n" (a parameter by reference), "point x_p[,]" (an array parameter of 2
dimensions), "private num nHidden".
"""

from __future__ import annotations

import re
from pathlib import Path

PJX_NS = "http://www.staubli.com/robotics/VAL3/Project/3"
PGX_NS = "http://www.staubli.com/robotics/VAL3/Program/2"
DTX_NS = "http://www.staubli.com/robotics/VAL3/Data/2"
PARAM_NS = "http://www.staubli.com/robotics/VAL3/Param/1"
XSI = 'xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"'

PJX = """<?xml version="1.0" encoding="utf-8"?>
<Project xmlns="{ns}">
  <Parameters version="{version}" stackSize="5000" millimeterUnit="true" />
  <Programs>
{programs}
  </Programs>
  <Database>
    <Data file="{name}.dtx" />
  </Database>
  <Libraries />
</Project>
"""

DTX = """<?xml version="1.0" encoding="utf-8"?>
<Database {xsi} xmlns="{ns}">
  <Datas>
{datas}
  </Datas>
</Database>
"""

PGX_HEAD = """<?xml version="1.0" encoding="utf-8"?>
<Programs {xsi} xmlns="{ns}">
  <Program name="{name}" access="{access}">
"""
CODE_OPEN = "    <Code><![CDATA["
PGX_TAIL = """]]></Code>
  </Program>
</Programs>
"""

# Line of the .pgx holding the first code line ("begin") of a program without parameters or
# locals, and the column where the code starts.
CODE_FIRST_LINE = PGX_HEAD.count("\n") + 1
CODE_FIRST_COL = len(CODE_OPEN) + 1

_DECL = re.compile(r"^\s*(?:(public|private)\s+)?(\w+)\s*(&?)\s*(\w+)\s*(\[[^\]]*\])?\s*$")


def parse_declaration(text: str) -> dict:
    """"private num nGrid[3,4]", "string sColl[\\"\\"]", "num& x_n", "num& x_a[]", "point x_p[,]".

    Returns name, type, access, by_reference, container ("element"/"array"/"collection") and
    sizes (array sizes; empty strings for the dimensions of an array parameter).
    """
    m = _DECL.match(text)
    if not m:
        raise ValueError(f"bad declaration {text!r}")
    access, vtype, ref, name, brackets = m.groups()
    container, sizes = "element", []
    if brackets is not None:
        inner = brackets[1:-1].strip()
        if inner.startswith('"'):
            container = "collection"
        else:
            container = "array"
            sizes = [x.strip() for x in inner.split(",")] if inner else [""]
    return {"name": name, "type": vtype, "access": access or "public", "by_reference": bool(ref),
            "container": container, "sizes": sizes}


def data_xml(decl: str) -> str:
    """The `<Data>` element of a global declared as `decl` (no value: the type's defaults)."""
    d = parse_declaration(decl)
    if d["container"] == "collection":
        return f'    <Data name="{d["name"]}" access="{d["access"]}" xsi:type="collection" type="{d["type"]}" />'
    size = " ".join(d["sizes"]) if d["container"] == "array" else "1"
    return f'    <Data name="{d["name"]}" access="{d["access"]}" xsi:type="array" type="{d["type"]}" size="{size}" />'


def _local_xml(decl: str) -> str:
    d = parse_declaration(decl)
    if d["container"] == "collection":
        return f'      <Local name="{d["name"]}" type="{d["type"]}" xsi:type="collection" />'
    size = " ".join(d["sizes"]) if d["container"] == "array" else "1"
    return f'      <Local name="{d["name"]}" type="{d["type"]}" xsi:type="array" size="{size}" />'


def _param_xml(decl: str) -> str:
    d = parse_declaration(decl)
    use = ' use="reference"' if d["by_reference"] else ""
    dims = f' dimensions="{len(d["sizes"])}"' if d["container"] == "array" else ""
    return f'      <Parameter name="{d["name"]}" type="{d["type"]}" xsi:type="{d["container"]}"{use}{dims} />'


def project_xml(name: str, programs: list[str], version: str = "s7.11") -> str:
    """A `.pjx` listing `programs` (names) and the data file `<name>.dtx`."""
    entries = "\n".join(f'    <Program file="{p}.pgx" />' for p in programs)
    return PJX.format(ns=PJX_NS, name=name, programs=entries, version=version)


def database_xml(body: str) -> str:
    """A `.dtx` holding `body` (`<Data>` elements, one per line, indented by 4)."""
    return DTX.format(xsi=XSI, ns=DTX_NS, datas=body)


def program_file(name: str, code: str, params=(), locals_=(), access: str = "public") -> str:
    """A `.pgx` of one program (its code: from `begin` to `end`)."""
    head = PGX_HEAD.format(xsi=XSI, ns=PGX_NS, name=name, access=access)
    if params:
        head += f'    <Parameters xmlns="{PARAM_NS}">\n'
        head += "\n".join(_param_xml(p) for p in params) + "\n    </Parameters>\n"
    if locals_:
        head += "    <Locals>\n" + "\n".join(_local_xml(x) for x in locals_) + "\n    </Locals>\n"
    return head + CODE_OPEN + code.rstrip("\n") + PGX_TAIL


def write_app(root: Path, code: str, name: str = "Example", *, globals_=(), locals_=(), programs=None,
              version: str = "s7.11") -> Path:
    """An application whose start() holds `code` (its locals: `locals_`); returns its folder.

    `globals_` are declarations for the .dtx; `programs` maps other program names to
    {"params": [...], "locals": [...], "code": "...", "access": "public"}.
    """
    folder = root / name
    folder.mkdir(parents=True, exist_ok=True)
    others = dict(programs or {})
    names = ["start", "stop"] + [p for p in others if p not in ("start", "stop")]
    (folder / f"{name}.pjx").write_text(project_xml(name, names, version), encoding="utf-8")
    (folder / f"{name}.dtx").write_text(database_xml("\n".join(data_xml(g) for g in globals_)), encoding="utf-8")
    (folder / "start.pgx").write_text(program_file("start", code, locals_=locals_), encoding="utf-8")
    if "stop" not in others:
        (folder / "stop.pgx").write_text(program_file("stop", "begin\nend\n"), encoding="utf-8")
    for prog, spec in others.items():
        text = program_file(prog, spec.get("code", "begin\nend\n"), spec.get("params", ()), spec.get("locals", ()),
                            spec.get("access", "public"))
        (folder / f"{prog}.pgx").write_text(text, encoding="utf-8")
    return folder


def write_files(root: Path, files: dict[str, str | bytes]) -> None:
    """Files at relative paths under `root` (text written as UTF-8)."""
    for rel, content in files.items():
        target = root / rel
        target.parent.mkdir(parents=True, exist_ok=True)
        if isinstance(content, bytes):
            target.write_bytes(content)
        else:
            target.write_bytes(content.encode("utf-8"))


def code_position(line: int, col: int, pgx_text: str | None = None) -> tuple[int, int]:
    """Where line/col of a `write_app` snippet land in the .pgx file (`pgx_text`: its content,
    when the program has parameters or locals)."""
    first = CODE_FIRST_LINE
    if pgx_text is not None:  # parameters and locals come before the code
        first = next(k for k, text in enumerate(pgx_text.split("\n"), start=1) if CODE_OPEN in text)
    return first + line - 1, (CODE_FIRST_COL + col - 1) if line == 1 else col
