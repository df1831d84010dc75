"""Groups of bodies that move together, and the pairs of groups that must not touch (watches).

A group is carried by one arm link (its solids, the tool on the flange, each carried part on
the flange) or is the static set (obstacles, parts left in the cell: `b` None in a watch). A
watch is a moving group against the static set, or two arm groups the allowed-collision matrix
does not exempt (and the tool and parts against the links they are not mounted on).
"""

from __future__ import annotations

import numpy as np

from .armmodel import ArmModel
from .bodies import Body


class Group:
    """Bodies that move together: `link` is the arm link whose pose carries them (None: static).

    kind: "link", "tool" or "part"; weights: per joint, mm of motion per unit of |Δq| (per
    radian, or per mm: `ArmModel.weights`); movers: the joints that move the link; placed: the
    motion position the bodies were last placed at (-1: not placed by the sweep)."""

    __slots__ = ("bodies", "kind", "link", "movers", "name", "placed", "weights")

    def __init__(self, name: str, kind: str, link: str | None, bodies: list[Body], weights: np.ndarray,
                 movers: frozenset[int]) -> None:
        self.name = name
        self.kind = kind
        self.link = link
        self.bodies = bodies
        self.weights = weights
        self.movers = movers
        self.placed = -1.0


class Watch:
    """A pair of groups that must not touch: `a` moves, `b` is another arm group or None (the
    static set). weights: the motion bound's factors of a relative to b; skip: body pairs (id, id)
    never measured (a tool solid against a link it is mounted on)."""

    __slots__ = ("a", "b", "skip", "weights")

    def __init__(self, a: Group, b: Group | None, weights: np.ndarray, skip: set[tuple[int, int]]) -> None:
        self.a = a
        self.b = b
        self.weights = weights
        self.skip = skip

    @property
    def is_self(self) -> bool:
        """Two parts of the arm (its links, tool and parts), not the arm against the cell."""
        return self.b is not None


def link_group(arm: ArmModel, link: str, bodies: list[Body], name: str | None = None, kind: str = "link") -> Group:
    """The group of `bodies` carried by `link` (the flange link for the tool and the parts)."""
    return Group(link if name is None else name, kind, link, bodies, arm.weights(link, bodies),
                 frozenset(arm.links.movers(link)))


def make_watches(arm: ArmModel, link_groups: dict[str, Group], flange_side: list[Group],
                 tool_touch: dict[int, tuple[str, ...]]) -> list[Watch]:
    """Every watch of a scene: each moving group (links, then `flange_side`: the tool and the
    carried parts) against the static set; link pairs the allowed-collision matrix does not
    exempt; the flange side against every link, less the body pairs mounted together
    (`tool_touch`: per tool body id, the links it may touch; other bodies: the arm's default)."""
    moving: list[Group] = [*link_groups.values(), *flange_side]
    out = [Watch(g, None, g.weights, set()) for g in moving]
    links = sorted(link_groups)
    for i, a in enumerate(links):
        for b in links[i + 1:]:
            if not arm.acm.allowed(a, b):
                ga, gb = link_groups[a], link_groups[b]
                out.append(Watch(ga, gb, relative_weights(ga, gb), set()))
    for g in flange_side:
        for link in links:
            lg = link_groups[link]
            skip = set()
            for b in g.bodies:
                if link in tool_touch.get(id(b), arm.touch_links):
                    skip.update((id(b), id(x)) for x in lg.bodies)
            if len(skip) == len(g.bodies) * len(lg.bodies):
                continue
            out.append(Watch(g, lg, relative_weights(g, lg), skip))
    return out


def relative_weights(a: Group, b: Group) -> np.ndarray:
    """Bound weights of the motion of a relative to b: joints that move both move them together."""
    w = np.zeros_like(a.weights)
    for j in a.movers - b.movers:
        w[j] += a.weights[j]
    for j in b.movers - a.movers:
        w[j] += b.weights[j]
    return w
