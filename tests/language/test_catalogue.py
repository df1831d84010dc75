"""The instruction catalogue: its schema, and its agreement with the manual's table of contents."""

from __future__ import annotations

from collections import defaultdict

import pytest

from val3check.language.instructions import (
    ANY_TYPE,
    CONTAINERS,
    Overload,
    load_errata,
    load_instructions,
    lookup,
)
from val3check.language.types import data_type_names, load_constants, load_operators, load_types

from .manual_toc import MANUAL, TocSignature, read_toc_sections, read_toc_signatures

# Where the catalogue knowingly departs from the table of contents, because an instruction's own
# section says otherwise. (name, parameter index): what differs.
KNOWN_DIFFERENCES = {
    ("getJointForce", 0): "container",  # signature num& nForce, text: a num array large enough
}


@pytest.fixture(scope="module")
def toc() -> list[TocSignature]:
    if not MANUAL.is_file():
        pytest.skip(f"the VAL 3 manual is not at {MANUAL} (shared/ beside the repository)")
    return read_toc_signatures(MANUAL)


@pytest.fixture(scope="module")
def toc_sections() -> set[str]:
    if not MANUAL.is_file():
        pytest.skip(f"the VAL 3 manual is not at {MANUAL} (shared/ beside the repository)")
    return read_toc_sections(MANUAL)


def _matches(overload: Overload, sig: TocSignature) -> bool:
    return overload.accepts_arity(len(sig.params)) and all(
        p.type == t for p, t in zip(overload.params, sig.types)
    )


# --- the catalogue on its own ----------------------------------------------------------------


def test_catalogue_loads_and_is_cached():
    catalogue = load_instructions()
    assert len(catalogue) >= 150
    assert load_instructions() is catalogue
    assert all(key == instr.name.lower() for key, instr in catalogue.items())


def test_every_entry_and_overload_has_a_section():
    for instr in load_instructions().values():
        assert instr.section, instr.name
        for overload in instr.overloads:
            assert overload.section, instr.name


def test_every_type_is_known():
    data_types = data_type_names()
    for instr in load_instructions().values():
        for overload in instr.overloads:
            assert overload.returns in data_types | {"void"}, (instr.name, overload.returns)
            for param in overload.params:
                assert param.type in data_types | {ANY_TYPE, "program"}, (instr.name, param)
                assert param.container in CONTAINERS
                assert set(param.accepts) <= data_types, (instr.name, param)
                if param.accepts:
                    assert param.type == ANY_TYPE
                if param.type == "program":
                    assert instr.kind == "special"


def test_kind_agrees_with_return_types():
    for instr in load_instructions().values():
        returns = {o.returns for o in instr.overloads}
        if instr.kind == "procedure":
            assert returns == {"void"}, instr.name
        elif instr.kind in ("function", "library"):
            assert returns != {"void"}, instr.name
        else:
            assert instr.kind == "special" and instr.special_form and instr.syntax, instr.name
        assert (instr.kind == "library") == (instr.library_prefix != "none"), instr.name


def test_overloads_of_a_name_are_distinguishable():
    for instr in load_instructions().values():
        seen = set()
        for overload in instr.overloads:
            key = tuple(p.type for p in overload.params)
            assert key not in seen, (instr.name, key)
            seen.add(key)


def test_errata_are_not_instructions_and_point_to_one():
    for spelling, erratum in load_errata().items():
        assert lookup(spelling) is None, spelling
        assert lookup(erratum.canonical) is not None, erratum.canonical


def test_names_do_not_clash_with_constants():
    names = {n.lower() for n in load_instructions()}
    assert not names & {c.lower() for c in load_constants()}


# --- against the manual's table of contents ----------------------------------------------------


def test_the_table_of_contents_was_read(toc):
    # 194 signatures on lines 9-388 of the s7 manual; far fewer means the reader broke
    assert len(toc) >= 190
    assert {s.name for s in toc} >= {"size", "toBinary", "put", "libLoad", "taskCreateSync", "alter", "resetTurn"}


def test_every_toc_name_is_in_the_catalogue_with_its_spelling(toc):
    for sig in toc:
        instr = lookup(sig.name)
        assert instr is not None, f"missing instruction: {sig}"
        assert instr.name == sig.name, f"{sig}: catalogue spells it {instr.name}"


def test_every_toc_signature_is_an_overload(toc):
    for sig in toc:
        instr = lookup(sig.name)
        matching = [o for o in instr.overloads if _matches(o, sig)]
        assert len(matching) == 1, f"{sig}: {len(matching)} matching overloads"
        overload = matching[0]
        assert overload.returns == sig.returns, f"{sig}: returns {overload.returns}"
        for i, (param, toc_param) in enumerate(zip(overload.params, sig.params)):
            assert param.ref == toc_param.ref, f"{sig}: parameter {i} by reference?"
            if param.type != ANY_TYPE and (sig.name, i) not in KNOWN_DIFFERENCES:
                assert param.container == toc_param.container, f"{sig}: parameter {i} container"


def test_every_overload_is_in_the_table_of_contents(toc):
    by_name = defaultdict(list)
    for sig in toc:
        by_name[sig.name].append(sig)
    for instr in load_instructions().values():
        for overload in instr.overloads:
            assert any(_matches(overload, s) for s in by_name[instr.name]), overload.signature(instr.name)


def test_sections_follow_the_table_of_contents(toc):
    for sig in toc:
        (overload,) = [o for o in lookup(sig.name).overloads if _matches(o, sig)]
        assert overload.section == sig.section, f"{sig}: catalogue says {overload.section}, TOC {sig.section}"


def test_library_identifiers_follow_the_table_of_contents(toc):
    forms = defaultdict(set)
    for sig in toc:
        forms[sig.name].add(sig.library)
    for name, seen in forms.items():
        instr = lookup(name)
        expected = {frozenset({True}): "required", frozenset({True, False}): "optional", frozenset({False}): "none"}
        assert instr.library_prefix == expected[frozenset(seen)], name


def test_special_forms_follow_the_table_of_contents(toc):
    special = {s.name for s in toc if s.special}
    assert special == {"taskCreate", "taskCreateSync"}
    assert {i.name for i in load_instructions().values() if i.kind == "special"} == special


def test_every_cited_section_exists(toc_sections):
    cited: list[tuple[str, str]] = []
    for instr in load_instructions().values():
        cited += [(instr.name, s) for s in instr.sections]
    cited += [(t.name, t.section) for t in load_types().values()]
    cited += [(c.name, c.section) for c in load_constants().values()]
    cited += [(f"operator {o.op}", o.section) for o in load_operators()]
    for what, section in cited:
        assert section in toc_sections, (what, section)


def test_an_instruction_is_built_when_first_asked_and_once():
    import subprocess
    import sys

    code = (
        "from val3check.language import instructions as I\n"
        "a = I.lookup('MOVEJ')\n"
        "assert list(I._BUILT) == ['movej'], list(I._BUILT)\n"
        "assert I.lookup('movej') is a and I.load_instructions()['movej'] is a\n"
        "assert len(I._BUILT) == len(I.load_instructions()) == len(I.entries())\n"
        "assert I.lookup('noSuchInstruction') is None\n"
        "assert I.yielding_instructions() == {k for k, i in I.load_instructions().items() if i.yields}\n"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=False)
    assert r.returncode == 0, r.stderr
