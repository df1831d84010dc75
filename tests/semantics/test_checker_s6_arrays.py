"""s6 globals: their data files write no size and no container. Indices are still checked (an
s6 global is indexed by numbers), but a bare name is never reported as a missing index."""

from __future__ import annotations

from .checkhelp import collect, write_files

PJX = """<?xml version="1.0" encoding="utf-8"?>
<project xmlns="ProjectNameSpace">
  <parameters version="s6.8" stackSize="5000" millimeterUnit="true" />
  <programSection><program file="start.pgx" /><program file="stop.pgx" /><program file="show.pgx" /></programSection>
  <dataSection><data file="Old.dtx" /></dataSection>
</project>
"""

DTX = """<?xml version="1.0" encoding="utf-8"?>
<dataList xmlns="DataNameSpace">
  <numSection>
    <num name="nVals" public="false"><valueNum index="0" value="1" /><valueNum index="1" value="2" /></num>
    <num name="nLast" public="false"><valueNum index="2" value="7" /></num>
    <num name="nOne" public="false"><valueNum index="0" value="0" /></num>
  </numSection>
  <stringSection>
    <string name="sNames" public="false"><valueString index="0" value="a" /><valueString index="1" value="b" /></string>
  </stringSection>
</dataList>
"""

STOP = """<?xml version="1.0" encoding="utf-8"?>
<programList xmlns="ProgramNameSpace">
  <program name="stop" public="false"><paramSection /><localSection /><source><code>begin
end</code></source></program>
</programList>
"""

SHOW = """<?xml version="1.0" encoding="utf-8"?>
<programList xmlns="ProgramNameSpace">
  <program name="show" public="false">
    <paramSection><param name="x_nVals" type="num" dimensions="1" byVal="false" /><param name="x_n" type="num" /></paramSection>
    <localSection />
    <source><code>begin
  x_n = x_nVals["k"] + x_n["k"]
end</code></source></program>
</programList>
"""


def _start(code: str) -> str:
    return f"""<?xml version="1.0" encoding="utf-8"?>
<programList xmlns="ProgramNameSpace">
  <program name="start" public="false"><paramSection /><localSection />
    <source><code>{code}</code></source></program>
</programList>
"""


def _lint(tmp_path, code: str) -> list:
    """(code, line, col) of the N/T/L findings, all in start.pgx."""
    write_files(tmp_path, {"Old/Old.pjx": PJX, "Old/Old.dtx": DTX, "Old/stop.pgx": STOP, "Old/show.pgx": SHOW,
                           "Old/start.pgx": _start(code)})
    found = collect(tmp_path / "Old", with_path=True)
    assert all(name == "start.pgx" for _, name, _, _ in found), found
    return [(c, line, col) for c, _, line, col in found]


def test_a_bare_global_written_with_several_values_is_not_reported(tmp_path):
    # Real s6 applications pass multi-value mdesc/point arrays bare to movej/movel: s6 files
    # write no size and no container, so whether a bare name means its first value is unknown.
    code = """begin
  nOne = nVals + 1
  nOne = nLast
  sNames = "c"
  get(nVals)
  if nVals == 1
  endIf
end"""
    assert _lint(tmp_path, code) == []


def test_a_global_written_with_one_value_and_whole_variables_are_fine(tmp_path):
    code = """begin
  nOne = nOne + nVals[1] + size(nVals) + nLast[2]
  get(nOne)
  call show(nVals, nOne)
  call show(nVals[1], nVals[0])
  sNames[1] = "c"
end"""
    assert _lint(tmp_path, code) == []


def test_an_s6_global_is_indexed_by_numbers(tmp_path):
    # the parameters of show() may be arrays or not (s6 files do not say): their indices are
    # not checked (show.pgx has no finding)
    code = """begin
  nOne = nVals["a"]
  sNames[nOne] = sNames[true]
end"""
    assert _lint(tmp_path, code) == [("T010", 5, 16), ("T010", 6, 25)]
