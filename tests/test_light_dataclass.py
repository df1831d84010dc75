"""light_dataclass.dataclass: the subset of dataclasses the lint path uses behaves as dataclasses does."""

from __future__ import annotations

import dataclasses

import pytest

from val3check import light_dataclass as records


def _pair(**opts):
    def make(deco, fld):
        @deco(**opts)
        class P:
            """A point."""

            x: int
            y: int = 2
            tags: list = fld(default_factory=list)
            note: str = fld(default="n")

            def norm(self) -> int:
                return self.x + self.y

        return P

    return make(dataclasses.dataclass, dataclasses.field), make(records.dataclass, records.field)


@pytest.mark.parametrize("opts", [{}, {"slots": True}, {"frozen": True}, {"frozen": True, "slots": True},
                                  {"slots": True, "eq": False}])
def test_same_behaviour_as_dataclasses(opts):
    std, mine = _pair(**opts)
    for cls in (std, mine):
        a, b = cls(1), cls(1, 2, [], "n")
        assert (a.x, a.y, a.tags, a.note, a.norm()) == (1, 2, [], "n", 3)
        assert (b.x, b.y, b.tags, b.note) == (a.x, a.y, a.tags, a.note)
        assert cls(1).tags is not cls(1).tags  # a new list each time
        assert cls.__match_args__ == ("x", "y", "tags", "note")
        assert hasattr(cls(1), "__dict__") != bool(opts.get("slots"))
        assert cls.__doc__ == "A point."
    assert repr(mine(1)).endswith("P(x=1, y=2, tags=[], note='n')") and repr(std(1)) == repr(mine(1))
    eq = opts.get("eq", True)
    assert (mine(1) == mine(1)) is eq and (mine(1) == mine(2)) is False
    assert (mine(1) == std(1)) is False  # another class
    frozen = opts.get("frozen", False)
    if frozen:
        assert hash(mine(1, 2, (), "n")) == hash(mine(1, 2, (), "n"))
        with pytest.raises(AttributeError):
            mine(1).x = 3
    elif eq:
        with pytest.raises(TypeError):
            hash(mine(1))  # mutable and compared by value: unhashable, as with dataclasses
    else:
        p = mine(1)
        assert hash(p) == hash(p) and p != mine(1)  # identity
    with pytest.raises(TypeError):
        mine()  # x is required


def test_lint_does_not_import_dataclasses():
    import subprocess
    import sys

    code = ("import sys, val3check.lint, val3check.semantics.checker, val3check.semantics.patterns; "
            "print('dataclasses' in sys.modules, 'inspect' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["False", "False"], "a module of the lint path imports dataclasses"


@pytest.mark.parametrize("frozen", [False, True])
def test_classes_of_one_shape_share_code_not_names(frozen):
    """Records whose fields have the same kinds share one compiled `__init__` (renamed): each
    keeps its own field names, keywords, defaults and factories."""

    @records.dataclass(frozen=frozen, slots=True)
    class A:
        a: int
        b: int = 5
        c: list = records.field(default_factory=list)

    @records.dataclass(frozen=frozen, slots=True)
    class B:
        u: str
        v: str = "v"
        w: dict = records.field(default_factory=dict)

    a, b = A(1), B(u="x", w={1: 2})
    assert (a.a, a.b, a.c) == (1, 5, []) and (b.u, b.v, b.w) == ("x", "v", {1: 2})
    assert A(1, c=[3]).c == [3] and A(1).c is not A(1).c
    assert A.__init__.__code__.co_varnames[:4] == ("self", "a", "b", "c")
    assert A.__init__.__code__.co_code == B.__init__.__code__.co_code
    with pytest.raises(TypeError, match="'a'"):
        A()
    with pytest.raises(TypeError, match="'z'"):
        B("x", z=1)
