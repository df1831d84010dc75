"""Which VAL 3 document an XML root is (project, program or data file) and in which layout (s7 or s6).

Element names are compared case-insensitively; a document of another kind than the one listed
(or a file named on the command line that is no VAL 3 document) is an F006, here.
"""

from __future__ import annotations

import re

from ..diagnostics import Diagnostic
from ..rules import codes
from .xmlread import Node

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


def not_val3(path: str, root: Node | None) -> Diagnostic:
    """F006 for a file named on the command line that is no VAL 3 document: not XML (`root` None),
    or XML of another kind."""
    if root is None:
        return Diagnostic(codes.UNEXPECTED_DOCUMENT, "not a VAL 3 file (it is not XML); expected a .pjx project, a .pgx "
                          "program file, a .dtx data file or an application folder", path)
    return Diagnostic(codes.UNEXPECTED_DOCUMENT, f"unexpected document: not a VAL 3 file (root <{root.tag}>); expected "
                      "a .pjx project, a .pgx program file or an application folder", path, root.line, root.col)
