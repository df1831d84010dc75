"""A program file (.pgx, s7 and s6 layouts) as the model's programs: parameters, locals, code."""

from __future__ import annotations

from ..positions import SourceMap
from ..rules import codes
from .attribute_text import parse_sizes
from .declaration import Sink, access_of, container_of, origin_of, required
from .model import Container, Local, Parameter, Program
from .xmlread import Node


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
    name = required(node, sink, "name", f"<{node.tag}>")
    if name is None:
        return None
    what = f"program {name}"
    access = access_of(node, sink, what)
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
        origin=origin_of(sink, node),
        description=desc.text.strip() if desc is not None else "",
    )


def _read_parameter(node: Node, sink: Sink, prog: str) -> Parameter | None:
    name = required(node, sink, "name", f"{prog}: parameter")
    if name is None:
        return None
    typ = required(node, sink, "type", f"{prog}: parameter {name}")
    if typ is None:
        return None
    what = f"{prog}: parameter {name}"
    container = container_of(node, sink, Container.ELEMENT, what)
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
    return Parameter(name, typ, container, dims, by_ref, origin_of(sink, node))


def _read_local(node: Node, sink: Sink, prog: str) -> Local | None:
    name = required(node, sink, "name", f"{prog}: local")
    if name is None:
        return None
    typ = required(node, sink, "type", f"{prog}: local {name}")
    if typ is None:
        return None
    what = f"{prog}: local {name}"
    # srs-project-files.md: "Local may lack xsi:type (then: array)".
    container = container_of(node, sink, Container.ARRAY, what)
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
    return Local(name, typ, container, sizes, origin_of(sink, node))
