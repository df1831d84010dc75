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


@pytest.mark.parametrize("opts", [{}, {"slots": True}, {"frozen": True}, {"frozen": True, "slots": True}])
def test_the_standard_modules_functions_work_on_them(opts):
    """dataclasses.fields, replace, asdict, astuple and is_dataclass give what they give on a
    standard class of the same fields."""
    std, mine = _pair(**opts)
    for cls in (std, mine):
        p = cls(1, 5, [7], "m")
        assert dataclasses.is_dataclass(cls) and dataclasses.is_dataclass(p)
        assert [(f.name, f.type, f.repr, f.compare, f.init) for f in dataclasses.fields(p)] == [
            ("x", "int", True, True, True), ("y", "int", True, True, True), ("tags", "list", True, True, True),
            ("note", "str", True, True, True)]
        q = dataclasses.replace(p, y=9)
        assert (q.x, q.y, q.tags, q.note) == (1, 9, [7], "m") and type(q) is cls
        assert dataclasses.asdict(p) == {"x": 1, "y": 5, "tags": [7], "note": "m"}
        assert dataclasses.astuple(p) == (1, 5, [7], "m")
        assert dataclasses.fields(mine)[2].default_factory is list and dataclasses.fields(mine)[1].default == 2
        assert cls.__dataclass_params__.frozen is bool(opts.get("frozen"))


@pytest.mark.parametrize("opts", [{}, {"slots": True}, {"frozen": True}, {"frozen": True, "slots": True}])
def test_fields_left_out_of_repr_or_comparison_and_post_init(opts):
    made = []
    for deco, fld in ((dataclasses.dataclass, dataclasses.field), (records.dataclass, records.field)):
        @deco(**opts)
        class R:
            """A record."""

            a: int
            hidden: int = fld(default=0, repr=False)
            cache: dict = fld(default_factory=dict, compare=False)

            def __post_init__(self) -> None:
                self.cache["seen"] = self.a  # the dict is mutable even in a frozen record

        made.append(R)
    for R in made:
        assert repr(R(1, 2)).endswith("R(a=1, cache={'seen': 1})")
        assert R(1, 2, {"x": 1}) == R(1, 2) and R(1, 2) != R(1, 3)
        assert R(1).cache == {"seen": 1}
        if opts.get("frozen"):
            assert hash(R(1, 2, {"x": 1})) == hash(R(1, 2))
    std, mine = made
    assert repr(std(4, 5)).split("R(")[1] == repr(mine(4, 5)).split("R(")[1]


@pytest.mark.parametrize("slots", [False, True])
def test_frozen_records_pickle_and_copy(slots):
    import copy
    import pickle

    r = _Frozen[slots](1, [2])
    for back in (pickle.loads(pickle.dumps(r)), copy.copy(r), copy.deepcopy(r)):
        assert back == r and type(back) is type(r) and back.b == [2]
        with pytest.raises(AttributeError):
            back.a = 3


@records.dataclass(frozen=True)
class _FrozenDict:
    """Frozen, with a __dict__."""

    a: int
    b: list


@records.dataclass(frozen=True, slots=True)
class _FrozenSlots:
    """Frozen and slotted: unpickled through __setstate__."""

    a: int
    b: list


_Frozen = {False: _FrozenDict, True: _FrozenSlots}


def test_the_standard_module_is_imported_only_when_asked():
    import subprocess
    import sys

    code = ("import sys\nfrom val3check.light_dataclass import dataclass\n"
            "@dataclass(frozen=True)\nclass A:\n    '''A.'''\n    x: int\n"
            "a = A(1); hash(a); repr(a); a == A(1)\nprint('dataclasses' in sys.modules)\n"
            "import dataclasses\nprint(dataclasses.replace(a, x=2))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["False", "A(x=2)"]
