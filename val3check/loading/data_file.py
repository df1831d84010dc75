"""A data file (.dtx) as the model's global data, in the s7 layout (<Database><Data>) and the s6
one (<dataList><numSection>...): containers, keys, values and their fields, with defaults filled in."""

from __future__ import annotations

import math
import re

from ..rules import codes
from . import types as t
from .attribute_text import parse_bool, parse_num, parse_sizes, parse_uint
from .declaration import Sink, access_of, container_of, origin_of, required
from .model import Container, Data, Value
from .xmlread import Node

TYPE_CHECKING = False  # not typing's: importing typing costs 3 ms at lint's start-up
if TYPE_CHECKING:
    from typing import Any


def short(text: str, limit: int = 60) -> str:
    """A value as quoted in a message: long ones cut (a hostile file may hold megabytes)."""
    return text if len(text) <= limit else text[:limit] + f"... ({len(text)} characters)"


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
    name = required(node, sink, "name", f"{owner}{'<' + node.tag + '>'}")
    if name is None:
        return None
    what = f"{kind} {owner}{name}"
    typ = required(node, sink, "type", what)
    if typ is None:
        return None
    if access is None:
        access = access_of(node, sink, what)
    raw_size = node.get("size")
    default = Container.ARRAY if raw_size is not None else Container.ELEMENT
    container = container_of(node, sink, default, what)
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
    return _make_data(name, typ, container, sizes, access, values, origin_of(sink, node))


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
    return Value(key, fields, given, origin_of(sink, node), members, father)


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
                sink.f007(node, f'{what}: {attr}="{short(raw)}" is not a number; the default is used')
                continue
            if not math.isfinite(v):
                # 3.2.1: a num is a double (about 14 significant digits): 1e400 is none
                sink.f007(
                    node,
                    f'{what}: {attr}="{short(raw)}" is beyond the range of a num (about ±1.8e308,'
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
    name = required(node, sink, "name", f"<{node.tag}>")
    if name is None:
        return None
    what = f"global {name}"
    access = access_of(node, sink, what)
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
    container = container_of(node, sink, Container.ARRAY, what)
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
        values.append(Value(key, fields, given, origin_of(sink, vn), {}, father))
    return _make_data(name, typ, container, sizes, access, values, origin_of(sink, node))
