"""Turn parsed project, program and data files (s7/s8 and s6 layouts) into the model.

Both layouts are read by the same functions: element names are compared case-insensitively
and each s6 spelling (`programSection`, `paramSection`, `aliasSection`...) is accepted next to
its s7 one. Every problem with one declaration is an F007 at that element; the rest of the
file is still read.
"""

from __future__ import annotations

import math
import re
from typing import Any

from ..diagnostics import Diagnostic
from ..light_dataclass import dataclass, field
from ..positions import SourceMap
from ..rules import codes
from . import types as t
from .model import Container, Data, Local, Origin, Parameter, Program, Value
from .xmlread import Node

# ---------------------------------------------------------------------------------------------
# Which document is this?

_S7_NS = re.compile(r"^https?://www\.staubli\.com/robotics/val3/(project|program|data)/\d+(\.\d+)*/?$", re.I)
_S6_NS = {"projectnamespace": "project", "programnamespace": "programs", "datanamespace": "data"}
# root element (lower case) -> (kind, layout)
_ROOTS = {
    "project": ("project", None),
    "programs": ("programs", "s7"),
    "programlist": ("programs", "s6"),
    "database": ("data", "s7"),
    "datalist": ("data", "s6"),
}
_S7_NAMES = {
    "project": "<Project> in namespace http://www.staubli.com/robotics/VAL3/Project/3",
    "programs": "<Programs> in namespace http://www.staubli.com/robotics/VAL3/Program/2",
    "data": "<Database> in namespace http://www.staubli.com/robotics/VAL3/Data/2",
}
_WHAT = {
    "project": "a VAL 3 project file (.pjx)",
    "programs": "a VAL 3 program file (.pgx)",
    "data": "a VAL 3 data file (.dtx)",
}


def classify(root: Node) -> tuple[str, str] | None:
    """(kind, layout) of a document: kind in project/programs/data, layout s7 or s6."""
    low = root.tag.lower()
    entry = _ROOTS.get(low)
    if entry is None:
        return None
    kind, layout = entry
    ns = root.ns
    if ns:
        m = _S7_NS.match(ns)
        if m:
            ns_kind = {"project": "project", "program": "programs", "data": "data"}[m.group(1).lower()]
            if ns_kind != kind:
                return None
            return kind, "s7"
        s6 = _S6_NS.get(ns.lower())
        if s6 is None or s6 != kind:
            return None
        return kind, "s6"
    # No namespace: be liberal, decide the layout from the spelling of the root element.
    if layout is None:
        layout = "s6" if root.tag == "project" else "s7"
    return kind, layout


def check_root(root: Node, expected: str, path: str) -> tuple[str | None, list[Diagnostic]]:
    """The layout of a document of the expected kind, or None with F006."""
    got = classify(root)
    if got is not None and got[0] == expected:
        return got[1], []
    found = f"<{root.tag}>" + (f" in namespace {root.ns}" if root.ns else " without namespace")
    if got is not None:
        msg = f"expected {_WHAT[expected]} but this is {_WHAT[got[0]]} (root {found})"
    else:
        msg = f"expected {_WHAT[expected]} (root {_S7_NAMES[expected]}, or its s6 form) but the root element is {found}"
    return None, [Diagnostic(codes.UNEXPECTED_DOCUMENT, f"unexpected document: {msg}", path, root.line, root.col)]


# ---------------------------------------------------------------------------------------------
# Small value parsers.

# Unambiguous (`\d+(?:\.\d*)?`, not `\d+\.?\d*`, which can split a run of digits in two in
# n ways and takes quadratic time on "111...1x"): linear on any text.
_NUM = re.compile(r"^\s*[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?\s*$")
_CONTAINERS = {"element": Container.ELEMENT, "array": Container.ARRAY, "collection": Container.COLLECTION}


def parse_num(text: str) -> float | None:
    if _NUM.match(text):
        return float(text)
    return None


_IDENTIFIER = re.compile(r"[A-Za-z_]\w*")


def parse_father(text: str) -> tuple[str, str | None] | None:
    """A fatherId as (name, index): "fPallet[2]" -> ("fPallet", "2"), "world" -> ("world", None),
    " a [ 1 2 ] " -> ("a", "1 2"); None when it is not `name` or `name[index]`. Written without
    a backtracking regular expression: the lazy index pattern with blanks on both sides that it
    replaces took quadratic time on "world[x" followed by thousands of spaces (17 s for 150 KB)."""
    t = text.strip()
    m = _IDENTIFIER.match(t)
    if m is None:
        return None
    rest = t[m.end():].lstrip()
    if not rest:
        return m.group(), None
    if rest[0] != "[" or rest[-1] != "]" or "]" in rest[1:-1]:
        return None
    return m.group(), rest[1:-1].strip()


def _short(text: str, limit: int = 60) -> str:
    """A value as quoted in a message: long ones cut (a hostile file may hold megabytes)."""
    return text if len(text) <= limit else text[:limit] + f"... ({len(text)} characters)"


def parse_bool(text: str) -> bool | None:
    low = text.strip().lower()
    if low == "true":
        return True
    if low == "false":
        return False
    return None


_DIGITS = re.compile(r"[0-9]+")
HUGE = 10**12  # what a longer run of digits counts as: beyond every limit, and no 4,300-digit int()


def parse_uint(text: str) -> int | None:
    """A non-negative integer written in ASCII digits ("²" and other Unicode digits are not),
    None otherwise; more than 12 digits count as HUGE (Python refuses to convert 4,300)."""
    text = text.strip()
    if not _DIGITS.fullmatch(text):
        return None
    digits = text.lstrip("0") or "0"
    return int(digits) if len(digits) <= 12 else HUGE


def parse_sizes(text: str) -> tuple[int, ...] | None:
    """ "3 4" -> (3, 4); None when not 1 to 3 positive integers."""
    parts = text.replace(",", " ").split()
    if not 1 <= len(parts) <= 3:
        return None
    out = []
    for p in parts:
        n = parse_uint(p)
        if n is None or n < 1:
            return None
        out.append(n)
    return tuple(out)


@dataclass(slots=True)
class Sink:
    """Where the readers put their diagnostics."""

    path: str
    diagnostics: list[Diagnostic] = field(default_factory=list)

    def f007(self, node: Node, message: str) -> None:
        self.diagnostics.append(Diagnostic(codes.INVALID_DECLARATION, message, self.path, node.line, node.col))

    def add(self, code: str, node: Node, message: str) -> None:
        self.diagnostics.append(Diagnostic(code, message, self.path, node.line, node.col))


def _origin(sink: Sink, node: Node) -> Origin:
    return Origin(sink.path, node.line, node.col)


def _container(node: Node, sink: Sink, default: Container, what: str) -> Container:
    raw = node.attrs.get("xsi:type")
    if raw is None:
        return default
    c = _CONTAINERS.get(raw.strip().lower())
    if c is None:
        sink.f007(
            node, f'{what}: unknown xsi:type "{raw}" (expected element, array or collection); read as {default.value}'
        )
        return default
    return c


def _access(node: Node, sink: Sink, what: str) -> str:
    """access="public|private" (s7) or public="true|false" (s6); default private."""
    raw = node.get("access")
    if raw is not None:
        low = raw.strip().lower()
        if low in ("public", "private"):
            return low
        sink.f007(node, f'{what}: invalid access "{raw}" (expected public or private); read as private')
        return "private"
    raw = node.get("public")
    if raw is not None:
        b = parse_bool(raw)
        if b is None:
            sink.f007(node, f'{what}: invalid public="{raw}" (expected true or false); read as private')
            return "private"
        return "public" if b else "private"
    return "private"


def _required(node: Node, sink: Sink, attr: str, what: str) -> str | None:
    v = node.get(attr)
    if v is None or not v.strip():
        sink.f007(node, f"{what} without a {attr} attribute: ignored")
        return None
    return v.strip()


# ---------------------------------------------------------------------------------------------
# Programs (.pgx).


def read_programs(root: Node, sink: Sink) -> list[Program]:
    out = []
    for node in root.children:
        if node.ltag != "program":
            continue
        p = read_program(node, sink)
        if p is not None:
            out.append(p)
    return out


def read_program(node: Node, sink: Sink) -> Program | None:
    name = _required(node, sink, "name", f"<{node.tag}>")
    if name is None:
        return None
    what = f"program {name}"
    access = _access(node, sink, what)
    desc = node.find("description")
    params: list[Parameter] = []
    section = node.find("parameters", "paramsection")
    if section is not None:
        for pn in section.children:
            if pn.ltag in ("parameter", "param"):
                prm = _read_parameter(pn, sink, what)
                if prm is not None:
                    params.append(prm)
    locals_: list[Local] = []
    section = node.find("locals", "localsection")
    if section is not None:
        for ln in section.children:
            if ln.ltag == "local":
                loc = _read_local(ln, sink, what)
                if loc is not None:
                    locals_.append(loc)
    code_nodes = node.findall("code")
    code_node = code_nodes[0] if code_nodes else None
    if code_node is None:
        src = node.find("source")
        if src is not None:
            code_nodes = src.findall("code")
            code_node = code_nodes[0] if code_nodes else None
    for extra in code_nodes[1:]:
        sink.add(
            codes.CODE_ELEMENT_IGNORED,
            extra,
            f"program {name} has a second <{extra.tag}> element (the first is on line"
            f" {code_node.line}): it is not read",
        )
    for child in code_node.children if code_node is not None else ():
        sink.add(
            codes.CODE_ELEMENT_IGNORED,
            child,
            f"program {name}: the element <{child.tag}> inside <{code_node.tag}> is not VAL 3"
            " code (a '<' that should be written &lt;, or code outside its CDATA section?): its content is"
            " not read",
        )
    if code_node is None:
        sink.add(
            codes.PROGRAM_WITHOUT_CODE,
            node,
            f"program {name} has no <Code> element (s6: <source><code>): its instructions are unknown",
        )
        code, smap = None, SourceMap()
    else:
        code, smap = code_node.text, code_node.smap or SourceMap.identity("", code_node.line, code_node.col)
    return Program(
        name=name,
        access=access,
        parameters=params,
        locals=locals_,
        code=code,
        code_map=smap,
        origin=_origin(sink, node),
        description=desc.text.strip() if desc is not None else "",
    )


def _read_parameter(node: Node, sink: Sink, prog: str) -> Parameter | None:
    name = _required(node, sink, "name", f"{prog}: parameter")
    if name is None:
        return None
    typ = _required(node, sink, "type", f"{prog}: parameter {name}")
    if typ is None:
        return None
    what = f"{prog}: parameter {name}"
    container = _container(node, sink, Container.ELEMENT, what)
    dims = 0
    raw = node.get("dimensions")
    if container is Container.ARRAY:
        dims = 1
        if raw is not None:
            if raw.strip() in ("1", "2", "3"):
                dims = int(raw)
            else:
                sink.f007(node, f'{what}: invalid dimensions "{raw}" (expected 1, 2 or 3); read as 1')
    elif raw is not None and not raw.strip().isdigit():
        sink.f007(node, f'{what}: invalid dimensions "{raw}" (expected a number)')
    use = node.get("use")
    by_ref = False
    by_val = node.get("byVal")  # s6 files: byVal="false" means by reference
    if use is None and by_val is not None:
        by_ref = by_val.strip().lower() == "false"
    elif use is not None:
        low = use.strip().lower()
        if low == "reference":
            by_ref = True
        elif low != "value":
            sink.f007(node, f'{what}: invalid use "{use}" (expected value or reference); read as value')
    return Parameter(name, typ, container, dims, by_ref, _origin(sink, node))


def _read_local(node: Node, sink: Sink, prog: str) -> Local | None:
    name = _required(node, sink, "name", f"{prog}: local")
    if name is None:
        return None
    typ = _required(node, sink, "type", f"{prog}: local {name}")
    if typ is None:
        return None
    what = f"{prog}: local {name}"
    # srs-project-files.md: "Local may lack xsi:type (then: array)".
    container = _container(node, sink, Container.ARRAY, what)
    if container is Container.COLLECTION:
        sizes: tuple[int, ...] = ()
    else:
        sizes = (1,)
        raw = node.get("size")
        if raw is not None:
            parsed = parse_sizes(raw)
            if parsed is None:
                sink.f007(
                    node, f'{what}: invalid size "{raw}" (expected 1 to 3 positive integers such as "3 4"); read as 1'
                )
            else:
                sizes = parsed
        if container is Container.ELEMENT:
            sizes = (1,)
        elif sizes == (1,):
            # Manual 2.3.4: "Un conteneur tableau à une dimension avec une seule valeur (index 0)
            # est considéré comme un conteneur élément."
            container = Container.ELEMENT
    return Local(name, typ, container, sizes, _origin(sink, node))


# ---------------------------------------------------------------------------------------------
# Data (.dtx), s7 layout.


def read_data_s7(root: Node, sink: Sink) -> list[Data]:
    out = []
    holders = [root] + root.findall("datas")
    for holder in holders:
        for node in holder.children:
            if node.ltag == "data":
                d = read_data_node(node, sink, None)
                if d is not None:
                    out.append(d)
    return out


MAX_FIELD_DEPTH = 16  # user-type values inside user-type values: real types nest 2 or 3 deep


def read_data_node(node: Node, sink: Sink, access: str | None, owner: str = "", depth: int = 0) -> Data | None:
    """A <Data> (global) or a <Field> of a user-type value (access given: "public")."""
    kind = "field" if access is not None else "global"
    name = _required(node, sink, "name", f"{owner}{'<' + node.tag + '>'}")
    if name is None:
        return None
    what = f"{kind} {owner}{name}"
    typ = _required(node, sink, "type", what)
    if typ is None:
        return None
    if access is None:
        access = _access(node, sink, what)
    raw_size = node.get("size")
    default = Container.ARRAY if raw_size is not None else Container.ELEMENT
    container = _container(node, sink, default, what)
    sizes: tuple[int, ...] = ()
    if container is Container.ARRAY:
        sizes = (1,)
        if raw_size is not None:
            parsed = parse_sizes(raw_size)
            if parsed is None:
                sink.f007(
                    node,
                    f'{what}: invalid size "{raw_size}" (expected 1 to 3 positive integers such as "3 4"); read as 1',
                )
            else:
                sizes = parsed
    values = []
    for vn in node.children:
        if vn.ltag == "value":
            values.append(read_value(vn, sink, typ, container, sizes, f"{owner}{name}", depth))
    return _make_data(name, typ, container, sizes, access, values, _origin(sink, node))


def _make_data(name, typ, container, sizes, access, values, origin) -> Data:  # noqa: ANN001
    father = next((v.father for v in values if v.father), None)
    link = None
    if values:
        f = values[0].fields
        link = f.get("link") or f.get("gripper") or None
    return Data(name, typ, container, sizes, access, values, origin, father=father, link=link)


def _check_key(node: Node, sink: Sink, key: str, container: Container, sizes: tuple[int, ...], what: str) -> None:
    if container is Container.COLLECTION:
        if key == "":
            sink.f007(node, f"{what}: a collection key cannot be empty (manual 2.3.4)")
        return
    parts = key.replace(",", " ").split()  # SRS writes "1 2"; some tools write "1,2"
    if not parts or not all(parse_uint(p) is not None for p in parts):
        sink.f007(node, f'{what}: invalid key "{key}" (expected an index such as "0" or "1 2")')
        return
    dims = sizes or (1,)
    if len(parts) != len(dims):
        sink.f007(node, f'{what}: key "{key}" has {len(parts)} indices but the array has {len(dims)} dimensions')
        return
    for p, n in zip(parts, dims, strict=True):
        if parse_uint(p) >= n:
            sink.f007(node, f'{what}: index "{key}" is outside the array (size "{" ".join(map(str, dims))}")')
            return


_SKIP_ATTRS = frozenset({"key", "index", "fatherid", "xsi:type", "name"})


def read_value(
    node: Node, sink: Sink, typ: str, container: Container, sizes: tuple[int, ...], owner: str, depth: int = 0
) -> Value:
    key = node.get("key")
    if key is None:
        key = node.get("index", "0") or "0"
    what = f"{owner}[{key}]"
    _check_key(node, sink, key, container, sizes, what)
    if container is not Container.COLLECTION:
        key = " ".join(key.replace(",", " ").split())
    father = node.get("fatherId")
    if father is not None:
        father = father.strip() or None
    attrs = {k: v for k, v in node.attrs.items() if k.lower() not in _SKIP_ATTRS}
    fields, given = convert_fields(node, sink, typ, attrs, what)
    members: dict[str, Data] = {}
    if t.is_user_type(typ):
        fields_ = [fn for fn in node.children if fn.ltag == "field"]
        if fields_ and depth >= MAX_FIELD_DEPTH:
            sink.f007(fields_[0], f"{what}: user-type values nested more than {MAX_FIELD_DEPTH} deep: not read")
            fields_ = []
        for fn in fields_:
            d = read_data_node(fn, sink, "public", f"{owner}[{key}].", depth + 1)
            if d is not None:
                if d.name in members:
                    sink.add(
                        codes.DUPLICATE_FILE_DECLARATION,
                        fn,
                        f"{what}: field {d.name} is written twice; the first one is kept",
                    )
                else:
                    members[d.name] = d
    return Value(key, fields, given, _origin(sink, node), members, father)


def convert_fields(
    node: Node, sink: Sink, typ: str, attrs: dict[str, str], what: str
) -> tuple[dict[str, Any], tuple[str, ...]]:
    """Fields of a built-in type with defaults filled in; the names the file gave."""
    if t.is_user_type(typ):
        return {}, ()
    fields = t.defaults(typ)
    base = t.base_type(typ)
    given: list[str] = []
    lower_keys = {k.lower(): k for k in fields}
    for attr, raw in attrs.items():
        k = t.field_key(typ, attr)
        k = lower_keys.get(k.lower(), k)
        if k not in fields and not (base == "joint" and re.fullmatch(r"j[1-9][0-9]?", k)):
            continue  # unknown attribute: ignored (be liberal)
        kind = t.field_kind(typ, k)
        if kind == "num":
            v = parse_num(raw)
            if v is None:
                sink.f007(node, f'{what}: {attr}="{_short(raw)}" is not a number; the default is used')
                continue
            if not math.isfinite(v):
                # 3.2.1: a num is a double (about 14 significant digits): 1e400 is none
                sink.f007(
                    node,
                    f'{what}: {attr}="{_short(raw)}" is beyond the range of a num (about ±1.8e308,'
                    " manual 3.2.1); the default is used",
                )
                continue
            fields[k] = v
        elif kind == "bool":
            b = parse_bool(raw)
            if b is None:
                sink.f007(node, f'{what}: {attr}="{raw}" is not true or false; the default is used')
                continue
            fields[k] = b
        else:
            allowed = t.CONFIG_VALUES.get(k) if base in ("point", "config") else None
            if base == "mdesc" and k == "blend":
                allowed = t.BLEND_VALUES
            if allowed is not None and raw.strip().lower() not in allowed:
                sink.f007(node, f'{what}: {attr}="{raw}" is not one of {", ".join(allowed)}; the default is used')
                continue
            fields[k] = raw
        if k not in given:
            given.append(k)
    return fields, tuple(given)


# ---------------------------------------------------------------------------------------------
# Data (.dtx), s6 layout: <dataList><numSection><num name= public=><valueNum index= .../>...


def read_data_s6(root: Node, sink: Sink) -> list[Data]:
    out = []
    for section in root.children:
        if not section.ltag.endswith("section"):
            continue
        for node in section.children:
            d = _read_data_s6(node, sink)
            if d is not None:
                out.append(d)
    return out


def _read_data_s6(node: Node, sink: Sink) -> Data | None:
    typ = node.tag
    name = _required(node, sink, "name", f"<{node.tag}>")
    if name is None:
        return None
    what = f"global {name}"
    access = _access(node, sink, what)
    father = None
    value_nodes = []
    for c in node.children:
        low = c.ltag
        if low.endswith("father"):
            fname = (c.get("name") or "").strip()
            if fname:
                father = f"{fname}[{(c.get('fatherIndex') or '0').strip()}]"
        elif low.startswith("value"):
            value_nodes.append(c)
    container = _container(node, sink, Container.ARRAY, what)
    sizes: tuple[int, ...] = ()
    if container is Container.ARRAY:
        raw = node.get("size")
        parsed = parse_sizes(raw) if raw is not None else None
        if raw is not None and parsed is None:
            sink.f007(node, f'{what}: invalid size "{raw}" (expected 1 to 3 positive integers)')
        if parsed is None:
            n = 0
            for vn in value_nodes:
                idx = (vn.get("index") or vn.get("key") or "0").strip()
                if parse_uint(idx) is not None:
                    n = max(n, parse_uint(idx) + 1)
            parsed = (max(n, 1),)
        sizes = parsed
    values = []
    for vn in value_nodes:
        key = (vn.get("key") or vn.get("index") or "0").strip()
        vwhat = f"{name}[{key}]"
        _check_key(vn, sink, key, container, sizes, vwhat)
        attrs = {k: v for k, v in vn.attrs.items() if k.lower() not in _SKIP_ATTRS}
        for sub in vn.children:
            sattrs = sub.attrs
            if "name" in sattrs and not any(k in sattrs for k in ("x", "value")):
                # a link: tool gripper <io alias= name= ioIndex= open= close=>, dio/aio/sio links
                link = sattrs["name"].strip()
                idx = (sattrs.get("ioIndex") or "0").strip()
                if link and idx not in ("", "0"):
                    link = f"{link}[{idx}]"
                attrs["ioLink" if t.base_type(typ) == "tool" else "link"] = link
                if "open" in sattrs:
                    attrs["otime"] = sattrs["open"]
                if "close" in sattrs:
                    attrs["ctime"] = sattrs["close"]
            else:
                attrs.update(sattrs)
        fields, given = convert_fields(vn, sink, typ, attrs, vwhat)
        values.append(Value(key, fields, given, _origin(sink, vn), {}, father))
    return _make_data(name, typ, container, sizes, access, values, _origin(sink, node))


# ---------------------------------------------------------------------------------------------
# Project (.pjx).


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
            f = _required(n, sink, "file", "<Program> entry")
            if f is not None:
                pf.programs.append((f, n))
    for section in root.findall("database", "datasection"):
        for n in section.findall("data"):
            f = _required(n, sink, "file", "<Data> entry")
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
            name = _required(n, sink, "name", "<Type> entry")
            if name is None:
                continue
            path = (n.get("path") or "").strip()
            if not path:
                sink.f007(n, f"user type {name} has no path: ignored")
                continue
            pf.types.append((name, path, n))
    return pf
