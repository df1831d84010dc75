"""Old (s6) program files: a by-reference parameter whose container is not written, used by the
program as an array, is bound to the caller's array (2.6.3), not to one element
(interpretation/compiler/legacy.py)."""

from __future__ import annotations

from pathlib import Path

from val3check.config import Settings
from val3check.lint import run
from val3check.simulation import SimOptions, simulate

from .simsupport import errors, out

_PROGRAM = """<?xml version="1.0" encoding="utf-8"?>
<programList xmlns="ProgramNameSpace">
  <program name="{name}" public="false">
    <description />
    <paramSection>{params}</paramSection>
    <localSection>{locals}</localSection>
    <source>
      <code>begin
{code}
end
      </code>
    </source>
  </program>
</programList>
"""


def _s6_app(folder: Path, programs: dict[str, tuple[str, str, str]], data: str) -> Path:
    folder.mkdir(parents=True)
    listed = "".join(f'    <program file="{n}.pgx" />\n' for n in programs)
    (folder / "Paste.pjx").write_text(f"""<?xml version="1.0" encoding="utf-8"?>
<project xmlns="ProjectNameSpace">
  <parameters version="s6.8" stackSize="5000" millimeterUnit="true" />
  <programSection>
{listed}  </programSection>
  <dataSection>
    <data file="Paste.dtx" />
  </dataSection>
  <aliasSection />
</project>
""", encoding="utf-8")
    for name, (params, locals_, code) in programs.items():
        (folder / f"{name}.pgx").write_text(_PROGRAM.format(name=name, params=params, locals=locals_, code=code),
                                            encoding="utf-8")
    (folder / "Paste.dtx").write_text(f"""<?xml version="1.0" encoding="utf-8"?>
<dataList xmlns="DataNameSpace">
{data}
</dataList>
""", encoding="utf-8")
    return folder


def _run(folder: Path):
    lr = run([str(folder)], Settings())
    assert not [d for d in lr.result.diagnostics if d.severity is not None and d.severity.label == "error"]
    ws = lr.workspace
    return simulate(ws, ws.apps[ws.targets[0]], SimOptions(duration=1.0))


LINES = """  <stringSection>
    <string name="sLines" public="false" privilege="0">
      <valueString index="0" value="" />
      <valueString index="1" value="" />
      <valueString index="2" value="" />
    </string>
    <string name="sOne" public="false" privilege="0">
      <valueString index="0" value="" />
    </string>
  </stringSection>"""


def test_s6_reference_parameter_indexed_by_the_program_takes_the_whole_array(tmp_path):
    folder = _s6_app(tmp_path / "Paste", {
        "start": ("", "", '  call fill(sLines)\n  call mark(sOne)\n  putln(sLines[0] + sLines[1] + sLines[2] + sOne)'),
        "stop": ("", "", ""),
        # handed on to a parameter the callee indexes: an array too
        "fill": ('<param name="x_sOut" type="string" byVal="false" />', "", '  call paste(x_sOut, "b")'),
        "paste": (('<param name="x_sPaste" type="string" byVal="false" />'
                   '<param name="x_sWhat" type="string" byVal="true" />'),
                  '<local name="l_i" type="num" size="1" />',
                  '  for l_i = 0 to size(x_sPaste) - 1\n    x_sPaste[l_i] = x_sWhat + toString("", l_i)\n  endFor'),
        # not used as an array: an element reference (2.6.2)
        "mark": ('<param name="x_sMark" type="string" byVal="false" />', "", '  x_sMark = "!"'),
    }, LINES)
    r = _run(folder)
    assert errors(r) == [] and [d.code for d in r.diagnostics if d.code == "R004"] == []
    assert out(r) == ["b0b1b2!"]


def test_s6_array_reference_from_an_index_is_the_part_of_the_array(tmp_path):
    folder = _s6_app(tmp_path / "Paste", {
        "start": ("", "", '  call paste(sLines[1])\n  putln(sLines[0] + "|" + sLines[1] + "|" + sLines[2])'),
        "stop": ("", "", ""),
        "paste": ('<param name="x_sPaste" type="string" byVal="false" />', "",
                  '  x_sPaste[0] = "x"\n  x_sPaste[1] = "y"'),
    }, LINES)
    assert out(_run(folder)) == ["|x|y"]  # 2.6.3: the part of the array from index 1
