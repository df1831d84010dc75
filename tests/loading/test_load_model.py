"""Model filling from s7/s8 and s6 files."""

from __future__ import annotations

import pytest
from .loadhelp import DTX_NS, PGX_NS, PJX_NS, XSI, dtx, make_app, pgx, pjx, write

from val3check.loading import load
from val3check.loading.model import Container
from val3check.loading.types import (
    BUILTIN_TYPES,
    arm_family,
    base_type,
    defaults,
    field_key,
)

PICK_CODE = """begin
  // pick a part
  l_grid[0, 0] = x_nCount
  if len(x_sColl["a"])>4
    call place(x_pTarget)
  endIf
end"""

S7_PJX = f"""<?xml version="1.0" encoding="utf-8"?>
<Project xmlns="{PJX_NS}">
  <Parameters version="s7.11" stackSize="6000" millimeterUnit="false" />
  <Programs>
    <Program file="pick.pgx" />
    <Program file="start.pgx" />
    <Program file="stop.pgx" />
  </Programs>
  <Database>
    <Data file="Cell.dtx" />
  </Database>
  <Libraries>
    <Library alias="io" path="Disk://io" autoload="true" />
  </Libraries>
</Project>
"""

S7_PICK = f"""<?xml version="1.0" encoding="utf-8"?>
<Programs {XSI} xmlns="{PGX_NS}">
  <Program name="pick" access="public">
    <Description>Pick one part</Description>
    <Parameters xmlns="http://www.staubli.com/robotics/VAL3/Param/1">
      <Parameter name="x_pTarget" type="pointRx" xsi:type="element" />
      <Parameter name="x_nCount" type="num" xsi:type="element" use="reference" />
      <Parameter name="x_nBuf" type="num" xsi:type="array" use="reference" dimensions="2" />
      <Parameter name="x_sColl" type="string" xsi:type="collection" use="reference" />
      <Parameter name="x_bOld" type="bool" />
    </Parameters>
    <Locals>
      <Local name="l_i" type="num" xsi:type="array" size="1" />
      <Local name="l_grid" type="num" xsi:type="array" size="3 4" />
      <Local name="l_old" type="num" size="5" />
      <Local name="l_c" type="string" xsi:type="collection" />
    </Locals>
    <Code><![CDATA[{PICK_CODE}]]></Code>
  </Program>
</Programs>
"""

S7_DTX = f"""<?xml version="1.0" encoding="utf-8"?>
<Database {XSI} xmlns="{DTX_NS}">
  <Datas>
    <Data name="nCount" access="public" xsi:type="array" type="num" size="1">
      <Value key="0" value="3" />
    </Data>
    <Data name="fPallet" access="public" xsi:type="array" type="frame" size="1">
      <Value key="0" x="400" y="-100" z="10" rz="90" fatherId="world[0]" />
    </Data>
    <Data name="pPick" access="public" xsi:type="array" type="pointRx" size="2">
      <Value key="0" x="500" y="-40" z="200" ry="180" rz="55" shoulder="lefty" fatherId="fPallet[0]" />
      <Value key="1" x="520" y="-40" z="200" ry="180" fatherId="fPallet[0]" />
    </Data>
    <Data name="tGrip" access="private" xsi:type="array" type="tool" size="1">
      <Value key="0" z="120.5" ioLink="valve1" otime="0.2" fatherId="flange[0]" />
    </Data>
    <Data name="mFast" access="public" xsi:type="array" type="mdesc" size="1">
      <Value key="0" vel="50" tmax="1000" blend="off" />
    </Data>
    <Data name="jHome" access="public" xsi:type="array" type="jointRx" size="1">
      <Value key="0" j2="-30" j3="120" />
    </Data>
    <Data name="sName" access="private" xsi:type="array" type="string" size="1">
      <Value key="0" value="caf\u00e9" />
    </Data>
    <Data name="bOk" access="private" xsi:type="array" type="bool" size="1">
      <Value key="0" value="true" />
    </Data>
    <Data name="diValve" access="private" xsi:type="array" type="dio" size="1">
      <Value key="0" link="BasicIO-1\\%Q0" />
    </Data>
    <Data name="nCodes" access="private" xsi:type="collection" type="num">
      <Value key="OK" value="0" />
      <Value key="KO" value="-1" />
    </Data>
  </Datas>
</Database>
"""

S6_PJX = """<?xml version="1.0" encoding="utf-8" ?>
<project xmlns="ProjectNameSpace" >
  <parameters version="s6.8" stackSize="6000" millimeterUnit="false" />
  <programSection>
    <program file="pick.pgx" />
    <program file="start.pgx" />
    <program file="stop.pgx" />
  </programSection>
  <dataSection>
    <data file="Cell.dtx" />
  </dataSection>
  <aliasSection>
    <alias name="io" interface="io" autoload="true" password="" />
  </aliasSection>
</project>
"""

S6_PICK = f"""<?xml version="1.0" encoding="utf-8" ?>
<programList {XSI} xmlns="ProgramNameSpace" >
  <program name="pick" public="true" >
    <description>Pick one part</description>
    <paramSection>
      <param name="x_pTarget" type="pointRx" xsi:type="element" />
      <param name="x_nCount" type="num" xsi:type="element" use="reference" />
      <param name="x_nBuf" type="num" xsi:type="array" use="reference" dimensions="2" />
      <param name="x_sColl" type="string" xsi:type="collection" use="reference" />
      <param name="x_bOld" type="bool" />
    </paramSection>
    <localSection>
      <local name="l_i" type="num" xsi:type="array" size="1" />
      <local name="l_grid" type="num" size="3 4" />
      <local name="l_old" type="num" size="5" />
      <local name="l_c" type="string" xsi:type="collection" />
    </localSection>
    <source>
      <code>{PICK_CODE.replace("&", "&amp;").replace(">", "&gt;").replace('"', "&quot;")}</code>
    </source>
  </program>
</programList>
"""

S6_SIMPLE = """<?xml version="1.0" encoding="utf-8" ?>
<programList xmlns="ProgramNameSpace" >
  <program name="{name}" public="false" >
    <description />
    <paramSection/>
    <localSection/>
    <source>
      <code>begin
end</code>
    </source>
  </program>
</programList>
"""

S6_DTX = f"""<?xml version="1.0" encoding="utf-8" ?>
<dataList {XSI} xmlns="DataNameSpace" >
  <aioSection />
  <boolSection>
    <bool name="bOk" public="false" privilege="0" >
      <valueBool index="0" value="true" />
    </bool>
  </boolSection>
  <dioSection>
    <dio name="diValve" public="false" >
      <valueDio index="0" >
        <dioLink alias="io" name="BasicIO-1\\%Q0" ioIndex="0" />
      </valueDio>
    </dio>
  </dioSection>
  <frameSection>
    <frame name="fPallet" public="true" privilege="0" >
      <fFather alias="" name="world" fatherIndex="0" />
      <valueFrame index="0" >
        <tfValue x="400" y="-100" z="10" rz="90" />
      </valueFrame>
    </frame>
  </frameSection>
  <jointRxSection>
    <jointRx name="jHome" public="true" >
      <valueJoint index="0" >
        <jValue j2="-30" j3="120" />
      </valueJoint>
    </jointRx>
  </jointRxSection>
  <mdescSection>
    <mdesc name="mFast" public="true" privilege="0" >
      <valueMdesc index="0" >
        <mdescValue vel="50" tmax="1000" blend="off" />
      </valueMdesc>
    </mdesc>
  </mdescSection>
  <numSection>
    <num name="nCount" public="true" >
      <valueNum index="0" value="3" />
    </num>
    <num name="nCodes" public="false" xsi:type="collection" >
      <valueNum key="OK" value="0" />
      <valueNum key="KO" value="-1" />
    </num>
  </numSection>
  <pointRxSection>
    <pointRx name="pPick" public="true" >
      <pFather alias="" name="fPallet" fatherIndex="0" />
      <valuePoint index="0" >
        <tpValue x="500" y="-40" z="200" ry="180" rz="55" />
        <cpValue shoulder="lefty" />
      </valuePoint>
      <valuePoint index="1" >
        <tpValue x="520" y="-40" z="200" ry="180" />
      </valuePoint>
    </pointRx>
  </pointRxSection>
  <stringSection>
    <string name="sName" public="false" >
      <valueString index="0" value="caf\u00e9" />
    </string>
  </stringSection>
  <toolSection>
    <tool name="tGrip" public="false" privilege="0" >
      <tFather alias="" name="flange" fatherIndex="0" />
      <valueTool index="0" >
        <ttValue z="120.5" />
        <io alias="io" name="valve1" ioIndex="0" open="0.2" />
      </valueTool>
    </tool>
  </toolSection>
</dataList>
"""


def _write_s7(root):
    folder = root / "Cell"
    write(folder / "Cell.pjx", S7_PJX, bom=True, crlf=True)
    write(folder / "pick.pgx", S7_PICK, bom=True, crlf=True)
    write(folder / "start.pgx", pgx("start"), bom=True, crlf=True)
    write(folder / "stop.pgx", pgx("stop"), bom=True, crlf=True)
    write(folder / "Cell.dtx", S7_DTX, bom=True, crlf=True)
    return folder


def _write_s6(root):
    folder = root / "Cell"
    write(folder / "Cell.pjx", S6_PJX, crlf=True)
    write(folder / "pick.pgx", S6_PICK, crlf=True)
    write(folder / "start.pgx", S6_SIMPLE.format(name="start"), crlf=True)
    write(folder / "stop.pgx", S6_SIMPLE.format(name="stop"), crlf=True)
    write(folder / "Cell.dtx", S6_DTX, crlf=True)
    return folder


def _dump(app):
    """The model without positions, paths and layout."""

    def data(d):
        return (
            d.name,
            d.type,
            d.container,
            d.sizes,
            d.access,
            d.father,
            d.link,
            sorted(
                (
                    v.key,
                    tuple(sorted(v.fields.items())),
                    tuple(sorted(v.given)),
                    v.father,
                    tuple((k, data(m)) for k, m in sorted(v.members.items())),
                )
                for v in d.values
            ),
        )

    return {
        "params": (app.stack_size, app.millimeter_unit, app.globals_known),
        "programs": {
            n: (
                p.name,
                p.access,
                p.description,
                p.code,
                [(q.name, q.type, q.container, q.dimensions, q.by_reference) for q in p.parameters],
                [(q.name, q.type, q.container, q.sizes) for q in p.locals],
            )
            for n, p in sorted(app.programs.items())
        },
        "data": {n: data(d) for n, d in sorted(app.data.items())},
        "libraries": {a: (r.alias, r.path, r.autoload) for a, r in app.libraries.items()},
    }


@pytest.fixture
def s7_app(tmp_path):
    folder = _write_s7(tmp_path / "s7")
    ws, diags = load([str(folder)])
    return folder, ws, diags


def test_s7_application(s7_app):
    folder, ws, diags = s7_app
    assert [d.code for d in diags] == ["L003"]  # io: the controller's library, not in the tree
    assert ws.targets == [str(folder / "Cell.pjx")]
    app = ws.apps[ws.targets[0]]
    assert (app.name, app.layout, app.version, app.version_major) == ("Cell", "s7", "s7.11", 7)
    assert (app.stack_size, app.millimeter_unit, app.globals_known) == (6000, False, True)
    assert list(app.programs) == ["pick", "start", "stop"]
    assert app.files == [str(folder / n) for n in ("Cell.pjx", "pick.pgx", "start.pgx", "stop.pgx", "Cell.dtx")]
    pick = app.programs["pick"]
    assert (pick.access, pick.description, pick.code) == ("public", "Pick one part", PICK_CODE)
    assert (pick.origin.path, pick.origin.line, pick.origin.col) == (str(folder / "pick.pgx"), 3, 3)
    assert app.programs["start"].access == "private"
    params = {p.name: p for p in pick.parameters}
    assert [p.name for p in pick.parameters] == ["x_pTarget", "x_nCount", "x_nBuf", "x_sColl", "x_bOld"]
    assert (params["x_pTarget"].container, params["x_pTarget"].by_reference, params["x_pTarget"].dimensions) == (
        Container.ELEMENT,
        False,
        0,
    )
    assert params["x_nCount"].by_reference
    assert (params["x_nBuf"].container, params["x_nBuf"].dimensions) == (Container.ARRAY, 2)
    assert params["x_sColl"].container is Container.COLLECTION
    assert params["x_bOld"].container is Container.ELEMENT  # no xsi:type: element
    assert params["x_pTarget"].origin.line == 6
    locs = {v.name: v for v in pick.locals}
    assert (locs["l_i"].container, locs["l_i"].sizes) == (Container.ELEMENT, (1,))  # size 1: element
    assert (locs["l_grid"].container, locs["l_grid"].sizes) == (Container.ARRAY, (3, 4))
    assert (locs["l_old"].container, locs["l_old"].sizes) == (Container.ARRAY, (5,))  # no xsi:type: array
    assert (locs["l_c"].container, locs["l_c"].sizes) == (Container.COLLECTION, ())
    # code positions survive BOM + CRLF
    assert (pick.code_map.to_file(1, 1).line, pick.code_map.to_file(1, 1).col) == (18, 20)
    assert pick.code_map.to_file(4, 3).line == 21


def test_s7_data(s7_app):
    folder, ws, diags = s7_app
    app = ws.apps[ws.targets[0]]
    d = app.data
    assert list(d) == ["nCount", "fPallet", "pPick", "tGrip", "mFast", "jHome", "sName", "bOk", "diValve", "nCodes"]
    assert (d["nCount"].container, d["nCount"].sizes, d["nCount"].values[0].fields) == (
        Container.ARRAY,
        (1,),
        {"value": 3.0},
    )
    assert d["nCount"].origin.line == 4 and d["nCount"].values[0].origin.line == 5
    p = d["pPick"]
    assert (p.type, p.sizes, p.father, p.access) == ("pointRx", (2,), "fPallet[0]", "public")
    v0, v1 = p.values
    assert v0.fields == {
        "x": 500.0,
        "y": -40.0,
        "z": 200.0,
        "rx": 0.0,
        "ry": 180.0,
        "rz": 55.0,
        "shoulder": "lefty",
        "elbow": "esame",
        "wrist": "wsame",
    }
    assert v0.given == ("x", "y", "z", "ry", "rz", "shoulder")
    assert v1.fields["shoulder"] == "ssame" and v1.father == "fPallet[0]"
    assert d["fPallet"].father == "world[0]"
    t = d["tGrip"]
    assert t.values[0].fields == {
        "x": 0.0,
        "y": 0.0,
        "z": 120.5,
        "rx": 0.0,
        "ry": 0.0,
        "rz": 0.0,
        "gripper": "valve1",
        "otime": 0.2,
        "ctime": 0.0,
    }
    assert (t.father, t.link, t.access) == ("flange[0]", "valve1", "private")
    assert d["mFast"].values[0].fields == {
        "accel": 100.0,
        "vel": 50.0,
        "decel": 100.0,
        "tvel": 1000.0,
        "rvel": 9999.0,
        "blend": "off",
        "leave": 50.0,
        "reach": 50.0,
    }
    assert d["jHome"].values[0].fields == {"j1": 0.0, "j2": -30.0, "j3": 120.0, "j4": 0.0, "j5": 0.0, "j6": 0.0}
    assert d["sName"].values[0].fields == {"value": "caf\u00e9"}
    assert d["bOk"].values[0].fields == {"value": True}
    assert d["diValve"].link == "BasicIO-1\\%Q0"
    c = d["nCodes"]
    assert (c.container, c.sizes, [v.key for v in c.values]) == (Container.COLLECTION, (), ["OK", "KO"])
    assert c.values[1].fields == {"value": -1.0}


def test_s6_layout_gives_the_same_model(tmp_path, s7_app):
    _, ws7, _ = s7_app
    folder = _write_s6(tmp_path / "s6")
    ws6, diags = load([str(folder)])
    assert [d.code for d in diags] == ["L003"], diags
    a6, a7 = ws6.apps[ws6.targets[0]], ws7.apps[ws7.targets[0]]
    assert (a6.layout, a6.version, a6.version_major) == ("s6", "s6.8", 6)
    assert a6.libraries["io"].path == "io"  # s6: the interface names the library
    a6.libraries["io"].path = "Disk://io"
    d6, d7 = _dump(a6), _dump(a7)
    for key in d7:
        assert d6[key] == d7[key], key


def test_user_type_values_nest(tmp_path):
    body = """    <Data name="part" access="public" xsi:type="array" type="Part" size="2">
      <Value key="0">
        <Field name="nId" xsi:type="array" type="num" size="1">
          <Value key="0" value="7" />
        </Field>
        <Field name="header" xsi:type="array" type="Header" size="1">
          <Value key="0">
            <Field name="nData" xsi:type="array" type="num" size="12" />
            <Field name="mSpeed" xsi:type="array" type="mdesc" size="1">
              <Value key="0" leave="0" reach="0" />
            </Field>
          </Value>
        </Field>
      </Value>
    </Data>
"""
    app = make_app(tmp_path / "App", data_body=body)
    ws, diags = load([str(app)])
    assert diags == []
    part = ws.apps[str(app)].data["part"]
    assert part.type == "Part" and part.sizes == (2,)
    v = part.values[0]
    assert v.fields == {} and list(v.members) == ["nId", "header"]
    assert v.members["nId"].values[0].fields == {"value": 7.0}
    assert v.members["nId"].access == "public"
    header = v.members["header"].values[0]
    assert header.members["nData"].sizes == (12,) and header.members["nData"].values == []
    m = header.members["mSpeed"].values[0]
    assert (m.fields["leave"], m.fields["reach"], m.fields["vel"]) == (0.0, 0.0, 100.0)
    assert m.origin.line == 13


def test_mdesc_manual_spellings(tmp_path):
    body = """    <Data name="m" access="public" xsi:type="array" type="mdesc" size="1">
      <Value key="0" tvel="10" rvel="20" blend="Cartesian" />
    </Data>
"""
    app = make_app(tmp_path / "App", data_body=body)
    ws, diags = load([str(app)])
    assert diags == []
    v = ws.apps[str(app)].data["m"].values[0]
    assert (v.fields["tvel"], v.fields["rvel"], v.fields["blend"]) == (10.0, 20.0, "Cartesian")
    assert v.given == ("tvel", "rvel", "blend")


def test_bad_values_are_f007_and_loading_goes_on(tmp_path):
    body = """    <Data name="nBad" access="public" xsi:type="array" type="num" size="abc">
      <Value key="0" value="12x" />
    </Data>
    <Data access="public" xsi:type="array" type="num" size="1" />
    <Data name="bBad" access="public" xsi:type="array" type="bool" size="1">
      <Value key="0" value="yes" />
    </Data>
    <Data name="nOdd" access="public" xsi:type="matrix" type="num" />
    <Data name="pBad" access="secret" xsi:type="array" type="point" size="2">
      <Value key="5" shoulder="upside" />
    </Data>
    <Data name="nGood" access="public" xsi:type="array" type="num" size="1">
      <Value key="0" value="-1.5e2" />
    </Data>
"""
    app = make_app(tmp_path / "App", data_body=body)
    dtx_path = str(tmp_path / "App" / "App.dtx")
    ws, diags = load([str(app)])
    got = [(d.code, d.path, d.line) for d in diags]
    assert got == [
        ("F007", dtx_path, 4),  # size="abc"
        ("F007", dtx_path, 5),  # value="12x"
        ("F007", dtx_path, 7),  # missing name
        ("F007", dtx_path, 9),  # value="yes"
        ("F007", dtx_path, 11),  # xsi:type="matrix"
        ("F007", dtx_path, 12),  # access="secret"
        ("F007", dtx_path, 13),  # key 5 outside size 2
        ("F007", dtx_path, 13),  # shoulder="upside"
    ], diags
    data = ws.apps[str(app)].data
    assert list(data) == ["nBad", "bBad", "nOdd", "pBad", "nGood"]
    assert data["nBad"].sizes == (1,) and data["nBad"].values[0].fields == {"value": 0.0}
    assert data["nBad"].values[0].given == ()
    assert data["nOdd"].container is Container.ELEMENT
    assert data["pBad"].access == "private"
    assert data["nGood"].values[0].fields == {"value": -150.0}


def test_bad_program_declarations(tmp_path):
    extra = """    <Parameters xmlns="http://www.staubli.com/robotics/VAL3/Param/1">
      <Parameter name="x_a" type="num" xsi:type="vector" />
      <Parameter type="num" xsi:type="element" />
      <Parameter name="x_b" type="num" xsi:type="array" dimensions="4" />
      <Parameter name="x_c" type="num" use="byname" />
    </Parameters>
    <Locals>
      <Local name="l_a" type="num" xsi:type="array" size="abc" />
      <Local name="l_b" type="num" xsi:type="array" size="0" />
      <Local name="l_c" xsi:type="array" size="1" />
    </Locals>
"""
    folder = tmp_path / "App"
    make_app(folder)
    write(folder / "start.pgx", pgx("start", extra=extra))
    ws, diags = load([str(folder)])
    start = str(folder / "start.pgx")
    assert [(d.code, d.path, d.line) for d in diags] == [
        ("F007", start, 5),
        ("F007", start, 6),
        ("F007", start, 7),
        ("F007", start, 8),
        ("F007", start, 11),
        ("F007", start, 12),
        ("F007", start, 13),
    ], diags
    prog = ws.apps[str(folder / "App.pjx")].programs["start"]
    assert [p.name for p in prog.parameters] == ["x_a", "x_b", "x_c"]
    assert prog.parameters[0].container is Container.ELEMENT
    assert prog.parameters[1].dimensions == 1
    assert [(v.name, v.sizes) for v in prog.locals] == [("l_a", (1,)), ("l_b", (1,))]


def test_program_without_code_and_without_name(tmp_path):
    folder = tmp_path / "App"
    make_app(folder)
    text = f"""<?xml version="1.0" encoding="utf-8"?>
<Programs {XSI} xmlns="{PGX_NS}">
  <Program name="start" access="public">
    <Description>no code</Description>
  </Program>
  <Program access="public">
    <Code>begin
end</Code>
  </Program>
</Programs>
"""
    write(folder / "start.pgx", text)
    ws, diags = load([str(folder)])
    start = str(folder / "start.pgx")
    assert [(d.code, d.path, d.line, d.col) for d in diags] == [("F010", start, 3, 3), ("F007", start, 6, 3)]
    prog = ws.apps[str(folder / "App.pjx")].programs["start"]
    assert prog.code is None and prog.code_map.line_starts == []


def test_duplicates_are_f011(tmp_path):
    folder = tmp_path / "App"
    make_app(folder, programs=("start", "stop", "start2"))
    write(folder / "start2.pgx", pgx("start"))
    body = """    <Data name="n" access="public" xsi:type="array" type="num" size="1" />
    <Data name="n" access="public" xsi:type="array" type="bool" size="1" />
"""
    write(folder / "App.dtx", dtx(body))
    write(
        folder / "App.pjx",
        pjx(["start.pgx", "stop.pgx", "start2.pgx", "stop.pgx"], ["App.dtx"], [("lib", "./x"), ("lib", "./y")]),
    )
    ws, diags = load([str(folder)])
    got = [(d.code, d.path.rsplit("/", 1)[1], d.line) for d in diags if d.code == "F011"]
    # in reading order: the program (start2.pgx), the listing (pjx line 8: stop.pgx twice),
    # the global, the library alias
    assert got == [("F011", "start2.pgx", 3), ("F011", "App.pjx", 8), ("F011", "App.dtx", 5), ("F011", "App.pjx", 15)]
    app = ws.apps[str(folder / "App.pjx")]
    assert app.data["n"].type == "num"
    assert app.programs["start"].origin.path == str(folder / "start.pgx")


def test_project_parameters_defaults_and_errors(tmp_path):
    folder = tmp_path / "App"
    make_app(folder, params='stackSize="lots" millimeterUnit="maybe"')
    ws, diags = load([str(folder)])
    assert [(d.code, d.line) for d in diags] == [("F007", 3), ("F007", 3)]
    app = ws.apps[str(folder / "App.pjx")]
    assert (app.version, app.version_major, app.stack_size, app.millimeter_unit) == ("", None, 5000, True)


def test_types_helpers():
    assert base_type("pointRx") == "point" and base_type("pointRs") == "point"
    assert base_type("jointRx") == "joint" and base_type("jointRs") == "joint"
    assert base_type("configRx") == "config" and base_type("configRs") == "config"
    assert base_type("num") == "num" and base_type("Part") == "Part"
    assert arm_family("pointRs") == "Rs" and arm_family("jointRx") == "Rx" and arm_family("num") is None
    assert set(BUILTIN_TYPES) >= {
        "num",
        "bool",
        "string",
        "trsf",
        "frame",
        "tool",
        "point",
        "joint",
        "config",
        "mdesc",
        "dio",
        "aio",
        "sio",
        "screen",
    }
    # manual 10.5.1 defaults
    assert list(defaults("mdesc").values()) == [100.0, 100.0, 100.0, 9999.0, 9999.0, "joint", 50.0, 50.0]
    # the manual's names are the keys; the files' spellings are aliases
    assert field_key("mdesc", "tmax") == "tvel" and field_key("mdesc", "rmax") == "rvel"
    assert field_key("mdesc", "tvel") == "tvel" and field_key("tool", "ioLink") == "gripper"
    assert defaults("Part") == {}
