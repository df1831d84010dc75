"""What the readers of every file share: the Sink their diagnostics go into and the attributes
every declaration has (name, type, container, access), each problem an F007 at its element."""

from __future__ import annotations

from ..diagnostics import Diagnostic
from ..light_dataclass import dataclass, field
from ..rules import codes
from .attribute_text import parse_bool
from .model import Container, Origin
from .xmlread import Node

_CONTAINERS = {"element": Container.ELEMENT, "array": Container.ARRAY, "collection": Container.COLLECTION}


@dataclass(slots=True)
class Sink:
    """Where the readers put their diagnostics."""

    path: str
    diagnostics: list[Diagnostic] = field(default_factory=list)

    def f007(self, node: Node, message: str) -> None:
        self.diagnostics.append(Diagnostic(codes.INVALID_DECLARATION, message, self.path, node.line, node.col))

    def add(self, code: str, node: Node, message: str) -> None:
        self.diagnostics.append(Diagnostic(code, message, self.path, node.line, node.col))


def origin_of(sink: Sink, node: Node) -> Origin:
    return Origin(sink.path, node.line, node.col)


def container_of(node: Node, sink: Sink, default: Container, what: str) -> Container:
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


def access_of(node: Node, sink: Sink, what: str) -> str:
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


def required(node: Node, sink: Sink, attr: str, what: str) -> str | None:
    v = node.get(attr)
    if v is None or not v.strip():
        sink.f007(node, f"{what} without a {attr} attribute: ignored")
        return None
    return v.strip()
