"""The `frame` (9.4) and `tool` (9.5) trees.

A `Frame` is a node: its `trsf` is its position in its reference frame `ref` (another `Frame`
node, shared, not copied: re-teaching a frame moves everything linked to it, 9.4.2). The tree is
rooted at `world` (`new_world()`); a `Tool` likewise has a base tool `ref`, rooted at `flange`
(`new_flange()`), plus its `gripper` output and `otime`/`ctime` delays (9.5.1).

Roots. `world` and `flange` are ordinary nodes with ``is_root=True`` and ``ref=None``. The
program may change their coordinates (``world.trsf.x = 1``, ``flange = tTool``...): as the manual
says (9.4.1, 9.5.1), the error comes "during a geometric computation": any computation whose
chain reaches a root whose trsf is not exactly {0,0,0,0,0,0} or which was given a reference
raises 161 (world) or 160 (flange).

Undefined references. A node with ``ref=None`` that is not a root (a local frame, a frame in a
user-type field, before `=`/`link`/`setFrame`) raises 163 (frame) or 164 (tool) as soon as a
computation needs its chain; a chain that loops without reaching a root also counts as
undefined (163/164). A global node (``local=False``) may not get a local node as reference:
`link` and `=` raise 165 (12.1: global variable linked to a local variable).

Equality (9.4.3, 9.5.3): same reference node (identity) and same trsf fields (exact, like trsf
==); tools also compare gripper (identity or ==), otime and ctime. A root is its own reference
for `=` and `==`: ``f = world`` makes `f` a copy of world linked to world, and ``f == world``.
"""

from __future__ import annotations

from typing import Any

from ..language.runtime_errors import Val3RuntimeError

from . import rotation as R
from .trsf import Trsf

MAX_DEPTH = 10000  # a longer chain is a loop


class Frame:
    """A reference frame (9.4): `trsf` in the reference frame `ref` (None: undefined)."""

    __slots__ = ("is_root", "local", "name", "ref", "trsf")
    KIND = "frame"
    ROOT_ERROR = 161  # 12.1: invalid coordinates of the world frame
    UNDEFINED_ERROR = 163  # 12.1: frame without reference frame

    def __init__(self, trsf: Trsf | None = None, ref: Frame | None = None, *, name: str = "",
                 local: bool = False, is_root: bool = False) -> None:
        self.trsf = trsf if trsf is not None else Trsf()
        self.ref = ref
        self.name = name
        self.local = local
        self.is_root = is_root

    def __eq__(self, other: object) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        return reference_of(self) is reference_of(other) and self.trsf == other.trsf  # type: ignore[arg-type]

    def __ne__(self, other: object) -> bool:
        r = self.__eq__(other)
        return r if r is NotImplemented else not r

    __hash__ = object.__hash__  # nodes are identified by identity (dict keys, sets)

    # Field access by name (``f["trsf"]``, ``t["otime"]``) for the interpreter's (container,
    # key) places; the write goes to the node itself.
    def __getitem__(self, name: str):
        return getattr(self, name)

    def __setitem__(self, name: str, value) -> None:
        setattr(self, name, value)

    def __repr__(self) -> str:
        ref = reference_of(self)
        rname = "None" if ref is None else (ref.name or "?")
        return f"{type(self).__name__}({self.name or '?'}, {self.trsf!r}, ref={rname})"


class Tool(Frame):
    """A tool (9.5): `trsf` in the base tool `ref`, the `gripper` dio, `otime`, `ctime` (s).

    `gripper` is whatever the interpreter uses for a dio link (default None: the interpreter
    puts the system output valve1 there for globals, 9.5.1)."""

    __slots__ = ("ctime", "gripper", "otime")
    KIND = "tool"
    ROOT_ERROR = 160  # 12.1: invalid coordinates of the flange tool
    UNDEFINED_ERROR = 164  # 12.1: tool without reference tool

    def __init__(self, trsf: Trsf | None = None, ref: Tool | None = None, *, gripper: Any = None,
                 otime: float = 0.0, ctime: float = 0.0, name: str = "", local: bool = False,
                 is_root: bool = False) -> None:
        super().__init__(trsf, ref, name=name, local=local, is_root=is_root)
        self.gripper = gripper
        self.otime = float(otime)
        self.ctime = float(ctime)

    def __eq__(self, other: object) -> bool:
        if type(other) is not Tool:
            return NotImplemented
        return (reference_of(self) is reference_of(other) and self.trsf == other.trsf
                and (self.gripper is other.gripper or self.gripper == other.gripper)
                and self.otime == other.otime and self.ctime == other.ctime)

    __hash__ = object.__hash__


def new_world() -> Frame:
    """The root frame `world` (9.4.1). One per application."""
    return Frame(Trsf(), None, name="world", is_root=True)


def new_flange(gripper: Any = None) -> Tool:
    """The root tool `flange` (9.5.1). One per application."""
    return Tool(Trsf(), None, gripper=gripper, name="flange", is_root=True)


def reference_of(node: Frame) -> Frame | None:
    """The reference of a node as `=` and `==` see it: a root is its own reference."""
    return node if node.is_root else node.ref


def _label(node: Frame) -> str:
    return f"{node.KIND} {node.name}" if node.name else f"a {node.KIND}"


def _check_root(node: Frame) -> None:
    t = node.trsf
    if node.ref is not None or not (t.x == 0.0 and t.y == 0.0 and t.z == 0.0 and t.rx == 0.0 and t.ry == 0.0
                                    and t.rz == 0.0):
        raise Val3RuntimeError(node.ROOT_ERROR, f"the coordinates of {node.name or node.KIND} were modified")


def root_pose(node: Frame) -> R.Pose:
    """Pose of `node` in its tree's root (world for frames, flange for tools), with the
    errors 160/161 (modified root) and 163/164 (no reference, or a loop)."""
    if node.is_root:
        _check_root(node)
        return R.IDENTITY_POSE
    chain = []
    n: Frame | None = node
    while n is not None and not n.is_root:
        chain.append(n)
        if len(chain) > MAX_DEPTH:
            raise Val3RuntimeError(node.UNDEFINED_ERROR, f"the references of {_label(node)} form a loop")
        n = n.ref
    if n is None:
        bad = chain[-1]
        raise Val3RuntimeError(node.UNDEFINED_ERROR, f"{_label(bad)} has no reference {node.KIND}")
    _check_root(n)
    t = chain[-1].trsf
    p = t.pose()
    for m in reversed(chain[:-1]):
        p = R.pose_mul(p, m.trsf.pose())
    return p


def held_chain(node: Any) -> tuple | None:
    """What `root_pose(node)` reads, held: per node up to its root, (the node, its reference,
    root flag, trsf, and the trsf's six floats), for `same_chain`; None when there is no walk.
    Floats are immutable: the very same objects again are the same values, bit for bit."""
    out = []
    n = node
    try:
        while n is not None and len(out) <= MAX_DEPTH + 1:
            t = n.trsf
            out.append((n, n.ref, n.is_root, t, (t.x, t.y, t.z, t.rx, t.ry, t.rz)))
            if n.is_root:
                break
            n = n.ref
    except AttributeError:
        return None
    return tuple(out) or None


def same_chain(n: Any, held: tuple) -> bool:
    """Whether `n` and the nodes it links to are the very objects `held_chain` held: then
    `root_pose(n)` gives the same pose (and raises the same errors). (Each attribute compared
    in the bytecode: cheaper than a C call per node here.)"""
    try:
        for node, ref, root, t, (x, y, z, rx, ry, rz) in held:
            if n is not node or n.ref is not ref or n.is_root is not root:
                return False
            t2 = n.trsf
            if (t2 is not t or t2.x is not x or t2.y is not y or t2.z is not z or t2.rx is not rx or t2.ry is not ry
                    or t2.rz is not rz):
                return False
            n = ref
    except AttributeError:
        return False
    return True


def kept(table: dict, node: Any, compute: Any) -> Any:
    """`compute(node)` for a value `root_pose(node)` determines, kept in `table` (id(node) ->
    (`held_chain`, the value)) and given again while `same_chain` holds. What raises is not kept."""
    hit = table.get(id(node))
    if hit is not None and same_chain(node, hit[0]):
        return hit[1]
    value = compute(node)
    held = held_chain(node)
    if held is not None:
        if len(table) >= 64:
            table.clear()
        table[id(node)] = (held, value)
    return value


def pose_values(node: Frame) -> tuple[float, float, float, float, float, float]:
    """The coordinates of `node` in its root (x, y, z, rx, ry, rz; canonical angles)."""
    return Trsf.from_pose(root_pose(node)).as_tuple()


def check_defined(node: Frame) -> None:
    """Raise what a geometric computation with `node` would raise (160/161/163/164)."""
    root_pose(node)


def position(node: Frame, reference: Frame) -> Trsf:
    """9.4.4 position(frame, frame) / 9.5.4 position(tool, tool): coordinates of `node` in
    `reference` (both in the same tree). Angles in canonical form."""
    if type(node) is not type(reference):
        raise TypeError("position(): a frame in a frame, or a tool in a tool")
    a = root_pose(node)
    b = root_pose(reference)
    return Trsf.from_pose(R.pose_mul(R.pose_inv(b), a))


def check_link(node: Any, ref: Frame | None) -> None:
    """165: a global variable may not be linked to a local one (12.1)."""
    if ref is not None and ref.local and not getattr(node, "local", False) and ref is not node:
        raise Val3RuntimeError(165, f"{_label(node) if isinstance(node, Frame) else 'a global'} would be "
                               f"linked to the local {_label(ref)}")


def link(node: Frame, reference: Frame) -> None:
    """9.4.4 link(frame, frame) / 9.5.4 link(tool, tool): `reference` becomes the reference of
    `node`; the position of `node` in its reference (its trsf) is unchanged. Linking a root
    makes it "modified" (160/161 at the next computation)."""
    if type(node) is not type(reference):
        raise TypeError("link(): a frame to a frame, or a tool to a tool")
    check_link(node, reference)
    node.ref = reference


def assign(dst: Frame, src: Frame) -> None:
    """`=` (9.4.3, 9.5.3): copy the position and the reference of `src` into the node `dst`
    (the node keeps its identity: what is linked to `dst` follows). Tools also copy gripper,
    otime, ctime. Assigning to a root makes it modified unless `src` is that same root."""
    if type(dst) is not type(src):
        raise TypeError("=: a frame to a frame, or a tool to a tool")
    ref = reference_of(src)
    check_link(dst, ref)
    if dst is src:
        return
    dst.trsf = src.trsf.copy()
    dst.ref = None if (dst.is_root and ref is dst) else ref
    if isinstance(dst, Tool):
        dst.gripper = src.gripper  # type: ignore[attr-defined]
        dst.otime = src.otime  # type: ignore[attr-defined]
        dst.ctime = src.ctime  # type: ignore[attr-defined]


def copy_node(src: Frame, *, local: bool | None = None, name: str = "") -> Frame:
    """A new node equal to `src` (same reference), e.g. for a by-value parameter."""
    loc = src.local if local is None else local
    if isinstance(src, Tool):
        n: Frame = Tool(src.trsf.copy(), None, gripper=src.gripper, otime=src.otime, ctime=src.ctime,
                        name=name, local=loc)
    else:
        n = Frame(src.trsf.copy(), None, name=name, local=loc)
    ref = reference_of(src)
    check_link(n, ref)
    n.ref = ref
    return n
