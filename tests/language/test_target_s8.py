"""The target an application is checked for, and the s8 catalogue (language/target.py, s8.toml)."""

from __future__ import annotations

import pytest

from val3check.language import s8
from val3check.language.instructions import lookup
from val3check.language.target import arm_family, parse_target, project_major, target_for
from val3check.language.types import load_types


@pytest.mark.parametrize("arm,family", [
    ("tx2-60-S1", "Rx"), ("tx2_60-S1", "Rx"), ("tx200-S3", "Rx"), ("TX90L", "Rx"), ("rx160", "Rx"),
    ("ts2_60-S1", "Rs"), ("ts60-S1", "Rs"), ("rs80", "Rs"), ("tp80", None), ("", None), ("arm", None),
])
def test_arm_family_from_the_arm_id(arm, family):
    assert arm_family(arm) == family


def test_project_versions_as_tools_write_them():
    assert project_major("s7.11") == 7
    assert project_major("s8.20.2Cs9_BS4270") == 8  # SRS appends the build
    assert project_major("") is None and project_major("7.11") is None


def test_target_of_an_application():
    own = target_for("s7.11", None)
    assert own.major == 7 and not own.explicit and not own.s8
    assert target_for("s7.11", parse_target("CS9")).s8
    assert target_for("s8.13", parse_target("CS8")).major == 7  # a CS8 runs s7 at most
    assert target_for("s6.8", parse_target("CS8")).major == 6
    cs8 = target_for("s8.13", parse_target("CS8 s7.11"))
    assert cs8.major == 7 and cs8.explicit and "CS8 s7.11" in cs8.label
    assert target_for("", None).major is None


def test_every_s8_entry_is_sourced_and_well_typed():
    cat = s8.load_s8()
    types = set(load_types()) | {"*"}
    for name, forms in cat.forms.items():
        s7 = lookup(name)
        assert s7 is not None, f"{name}: a form of an instruction s7 does not have"
        for f in forms:
            assert f.since.startswith("s8") and f.source
            assert all(p.type in types for p in f.overload.params), name
            sig = [(p.type, p.container) for p in f.overload.params]
            assert all(sig != [(p.type, p.container) for p in o.params] for o in s7.overloads), \
                f"{name}: this form is already s7"
    for name, ins in cat.instructions.items():
        assert lookup(name) is None, f"{name} is an s7 instruction"
        assert ins.since.startswith("s8") and ins.source
    assert cat.statements["print"].syntax == "? expr"
    # the $file... system instructions exist on s7 controllers (CS8 add-on): not s8-only
    assert not any(n.startswith("$") for n in cat.instructions)


def test_compiled_language_data_is_current():
    # val3check/language/_compiled.py ships the TOML files as Python data (start-up time)
    from val3check.language import compiled

    assert compiled.is_current(), "run python -m val3check.language.compiled"
    import tomllib

    for name in compiled.NAMES:
        with open(f"{compiled.FOLDER}/{name}", "rb") as fh:
            assert compiled.load_toml(name) == tomllib.load(fh)
