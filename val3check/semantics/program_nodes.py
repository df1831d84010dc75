"""One walk of a program's tree, shared by the checks that look at its nodes (issue 29).

`ProgramNodes(body)` walks the tree once (`parsing.ast.nodes`: depth first, source order) and
groups the nodes by kind. A check reads the kinds it subscribes to (`of(A.Name)`) instead of
walking the tree again, as pyflakes' and ruff's checkers dispatch on the kind of node. The nodes
under one node are a slice of that walk (`under(node)`: a loop's).

Readers: `patterns_usage.gather` (names, calls, strings, assignments, loops: the S rules),
`limits` (numeric constants, F017), `patterns_style.check_loops` (the nodes of each loop, S014).
`semantics.analyse` makes one per parsed program and hands it to both families.
"""

from __future__ import annotations

from collections import defaultdict

from ..loading.model import Application
from ..parsing import ast as A


class ProgramNodes:
    """The nodes of one program body, in the order of `parsing.ast.nodes`, and by kind."""

    __slots__ = ("order", "_kinds", "_ids", "_from")

    def __init__(self, body: A.ProgramBody) -> None:
        order = A.nodes(body)
        kinds: defaultdict[type, list] = defaultdict(list)
        for node in order:
            kinds[node.__class__].append(node)
        self.order = order
        self._kinds = kinds
        self._ids: list[int] | None = None  # id() of each node of `order`, made when `under` first needs it
        self._from = 0

    def of(self, kind: type) -> list | tuple:
        """The nodes of class `kind`, in source order (depth first). Shared: read, do not modify."""
        return self._kinds.get(kind, ())

    def under(self, node: object) -> list:
        """`node` and every node under it, in source order: what `parsing.ast.nodes(node)` gives,
        as a slice of the program's walk (a subtree is contiguous in a depth-first order and ends
        with its last child's last child...)."""
        within, ids = self.order, self._ids
        if ids is None:
            ids = self._ids = list(map(id, within))
        try:  # from where the last search started: callers that go in source order make one pass
            start = ids.index(id(node), self._from)
        except ValueError:
            start = ids.index(id(node), 0, self._from)
        self._from = start
        last = node
        child = A.last_child(node)
        while child is not None:
            last = child
            child = A.last_child(child)
        return within[start:ids.index(id(last), start) + 1]


def program_walks(app: Application) -> dict[str, ProgramNodes]:
    """The walk of each program of `app` whose code parsed, by program name."""
    return {name: ProgramNodes(p.body) for name, p in app.programs.items() if p.body is not None}
