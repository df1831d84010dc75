"""The body pairs allowed to touch since a grasp or a release (`world.World.allowed`), stamped."""

from __future__ import annotations

import itertools

_STAMPS = itertools.count()


class Allowed(dict):
    """The pairs allowed to touch, with a stamp that changes at every change (never given twice):
    `World.key` makes their names again only then."""

    __slots__ = ("stamp",)

    def __init__(self, *args) -> None:
        super().__init__(*args)
        self.stamp = next(_STAMPS)

    def _changed(method):  # noqa: N805  (wraps dict's own mutators)
        def changed(self, *args, **kwargs):
            self.stamp = next(_STAMPS)
            return method(self, *args, **kwargs)
        return changed

    __setitem__ = _changed(dict.__setitem__)
    __delitem__ = _changed(dict.__delitem__)
    __ior__ = _changed(dict.__ior__)
    clear = _changed(dict.clear)
    pop = _changed(dict.pop)
    popitem = _changed(dict.popitem)
    setdefault = _changed(dict.setdefault)
    update = _changed(dict.update)
    del _changed
