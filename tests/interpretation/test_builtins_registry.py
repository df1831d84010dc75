"""The registry of pure instructions against the instruction catalogue."""

from __future__ import annotations

import inspect

import pytest

from val3check.interpretation.builtins import OPERATORS, PURE, Builtin, format_num_default, lookup
from val3check.language.runtime_errors import Val3RuntimeError
from val3check.language.instructions import load_instructions

# Chapter 3 sections whose instructions are all pure, plus the pure one of 4.3.
PURE_SECTIONS = {"3.2.3", "3.3.3", "3.4.3"}
ALSO_PURE = {"getDisplayLen"}


def _catalogue_overloads():
    for ins in load_instructions().values():
        for ov in ins.overloads:
            section = ov.section or ins.section
            if section in PURE_SECTIONS or ins.name in ALSO_PURE:
                yield ins.name, ov


def _type(param) -> str:
    return param.type + ("[]" if param.container == "array" else "")


def test_every_pure_instruction_of_chapter_3_is_registered():
    names = {name for name, _ in _catalogue_overloads()}
    assert names == set(PURE)


@pytest.mark.parametrize(("name", "overload"), list(_catalogue_overloads()), ids=lambda x: str(x)[:20])
def test_registry_matches_the_catalogue_signature(name, overload):
    builtin = PURE[name]
    assert builtin.name == name
    assert builtin.params == tuple(_type(p) for p in overload.params)
    assert builtin.returns == overload.returns
    assert builtin.outputs == tuple(i for i, p in enumerate(overload.params) if p.ref)
    assert len(inspect.signature(builtin.func).parameters) == len(overload.params)


def test_lookup_ignores_case():
    assert lookup("TOSTRING") is PURE["toString"]
    assert lookup("roundup") is PURE["roundUp"]
    assert lookup("movej") is None


def test_calling_convention_with_outputs():
    to_num = PURE["toNum"]
    assert to_num.outputs == (1, 2)
    assert to_num.func("10 20", 0.0, False) == ("20", 10.0, True)
    to_binary = PURE["toBinary"]
    value, out = to_binary.func([1.0], 1, "1", [0.0, 0.0])
    assert (value, out) == (1.0, [1.0, 0.0])


def test_functions_without_outputs_return_plain_values():
    assert PURE["sin"].func(30) == 0.5
    assert PURE["sel"].func(True, 1, 2) == 1.0
    assert PURE["len"].func("abc") == 3.0
    assert isinstance(PURE["bNot"].func(0), float)


def test_operators_and_display():
    assert OPERATORS[("+", "string")]("a", "b") == "ab"
    with pytest.raises(Val3RuntimeError) as info:
        OPERATORS[("/", "num")](1, 0)
    assert info.value.code == 10
    assert OPERATORS[("%", "num")](-7, 3) == -1.0
    assert format_num_default(3.14159) == "3.142"


def test_builtin_is_frozen():
    with pytest.raises(AttributeError):
        PURE["sin"].outputs = (0,)  # type: ignore[misc]
    assert isinstance(PURE["sin"], Builtin)
