"""The type facts have one source, language/types.toml: every declared field of every built-in
structured type, and every alias of a field (the spellings of data files), reads and writes
through `val3check sim`; a new variable gets the defaults the manual states."""

from __future__ import annotations

from pathlib import Path

import pytest

from val3check.language.types import load_types

from .simsupport import build, gv, run_folder, sim

MANUAL = Path(__file__).resolve().parents[3] / "shared" / "manual" / "val3-reference-manual-s7-fr.md"

STRUCTURED = {name: bt for name, bt in load_types().items() if bt.kind == "structured"}
# a value different from the default, for each kind of field
ENUM_VALUE = {"shoulder": "lefty", "elbow": "enegative", "wrist": "wpositive", "blend": "Cartesian"}
STRUCT_VALUE = {"trsf": "{1, 2, 3, 4, 5, 6}", "config": "{lefty, enegative, wpositive}"}


def _spellings():
    for tname, bt in STRUCTURED.items():
        for f in bt.fields:
            for spelling in (f.name, *f.aliases):
                yield pytest.param(tname, f.name, f.type, spelling, id=f"{tname}.{spelling}")


@pytest.mark.parametrize("tname,field,ftype,spelling", list(_spellings()))
def test_every_field_and_alias_reads_and_writes(tmp_path, tname, field, ftype, spelling):
    globals_ = [f"{tname} xVal", "num nRead", "bool bRead", "trsf trRead", "config cRead", "dio dOut"]
    if ftype == "num":
        code = f"  xVal.{spelling} = 7\n  nRead = xVal.{spelling}\n"
        r = sim(tmp_path, f"begin\n{code}end\n", globals_=globals_)
        assert gv(r, "nRead") == 7.0
    elif ftype in ENUM_VALUE:
        value = ENUM_VALUE[ftype]
        code = f"  xVal.{spelling} = {value}\n  bRead = (xVal.{spelling} == {value})\n"
        r = sim(tmp_path, f"begin\n{code}end\n", globals_=globals_)
        assert gv(r, "bRead") is True
    elif ftype in STRUCT_VALUE:
        read = "trRead" if ftype == "trsf" else "cRead"
        code = f"  xVal.{spelling} = {STRUCT_VALUE[ftype]}\n  {read} = xVal.{spelling}\n"
        r = sim(tmp_path, f"begin\n{code}end\n", globals_=globals_)
        got = gv(r, read)
        if ftype == "trsf":
            got = (got.x, got.y, got.z, got.rx, got.ry, got.rz) if not isinstance(got, dict) else tuple(got.values())
            assert got == (1.0, 2.0, 3.0, 4.0, 5.0, 6.0)
        else:
            assert got == {"shoulder": "lefty", "elbow": "enegative", "wrist": "wpositive"}
    else:
        assert ftype == "dio", f"a field type this test does not know: {tname}.{field} {ftype}"
        folder = build(tmp_path, f"begin\n  dioLink(xVal.{spelling}, dOut)\n  xVal.{spelling} = true\n"
                                 f"  bRead = xVal.{spelling}\nend\n", globals_=globals_, links={"dOut": "Cell\\out3"})
        r = run_folder(folder)
        assert gv(r, "bRead") is True and gv(r, "dOut") is True
    assert not r.diagnostics, r.diagnostics


def test_mdesc_tmax_reads_the_translation_speed(tmp_path):
    # A program reading mDesc.tmax (the .dtx spelling of tvel) passes lint: sim reads tvel.
    folder = build(tmp_path, "begin\n  nA = mSlow.tmax\n  nB = mSlow.tvel\n  mSlow.tmax = 250\n  nC = mSlow.rmax\nend\n",
                   globals_=["mdesc mSlow", "num nA", "num nB", "num nC"])
    dtx = folder / "Example.dtx"
    dtx.write_text(dtx.read_text(encoding="utf-8").replace(
        '<Data name="mSlow" access="public" xsi:type="array" type="mdesc" size="1" />',
        '<Data name="mSlow" access="public" xsi:type="array" type="mdesc" size="1">'
        '<Value key="0" tmax="1000" rmax="45" /></Data>'), encoding="utf-8")
    r = run_folder(folder)
    assert not r.diagnostics, r.diagnostics
    assert (gv(r, "nA"), gv(r, "nB"), gv(r, "nC")) == (1000.0, 1000.0, 45.0)
    assert gv(r, "mSlow")["tvel"] == 250.0


# The defaults the manual states, quoted (section, the manual's words, what sim must give).
MANUAL_DEFAULTS = [
    ("9.3.1", "Par défaut, une variable de type **trsf** est initialisée à la valeur **{0,0,0,0,0,0}**.",
     "trsf", {"x": 0.0, "y": 0.0, "z": 0.0, "rx": 0.0, "ry": 0.0, "rz": 0.0}),
    ("9.2.1", "Par défaut, chaque champ d'une variable de type **joint** est initialisé à la valeur **0**.",
     "joint", {f"j{i}": 0.0 for i in range(1, 7)}),
    ("10.5.1", "Par défaut, une variable de type **mdesc** est initialisée avec **{100,100,100,9999,9999,joint,50,50}**.",
     "mdesc", {"accel": 100.0, "vel": 100.0, "decel": 100.0, "tvel": 9999.0, "rvel": 9999.0, "blend": "joint",
               "leave": 50.0, "reach": 50.0}),
    ("9.5.1", "Par défaut, la sortie d'un outil est la sortie **valve1** du système, les temps d'ouverture et de "
              "fermeture sont à **0**, et l'outil de base est **flange**.",
     "tool", {"gripper": "valve1", "otime": 0.0, "ctime": 0.0, "ref": "flange"}),
]


@pytest.mark.parametrize("section,quote,tname,expected", MANUAL_DEFAULTS, ids=[m[2] for m in MANUAL_DEFAULTS])
def test_defaults_are_the_manuals(tmp_path, section, quote, tname, expected):
    if MANUAL.exists():
        assert quote in MANUAL.read_text(encoding="utf-8"), f"{section}: the quote is not in the manual"
    r = sim(tmp_path, "begin\nend\n", globals_=[f"{tname} xVal"])
    value = r.globals["xVal"].data[0]
    if tname == "trsf":
        got = dict(zip(expected, (value.x, value.y, value.z, value.rx, value.ry, value.rz)))
    elif tname == "tool":
        got = {"gripper": value.gripper.link, "otime": value.otime, "ctime": value.ctime,
               "ref": "flange" if value.ref is not None and value.ref.is_root else value.ref}
    else:
        got = dict(value)
    assert got == expected
    # the same facts, as data: types.toml's field defaults
    fields = {f.name: f.default for f in STRUCTURED[tname].fields if f.default is not None}
    for k, v in fields.items():
        assert expected[k] == v, (tname, k)
