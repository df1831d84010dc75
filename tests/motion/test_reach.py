"""`val3check reach`: the static reach check of the data files."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

from val3check.cli import main
from val3check.loading import load
from val3check.motion.reach import check_reach
from val3check.robot import load_robot

ROOT = Path(__file__).resolve().parents[2]
CELL = ROOT / "fixtures" / "valid" / "Cell"


def report_of(path, robot="TX2-60"):
    ws, _ = load([str(path)])
    app = ws.apps[ws.targets[0]]
    return check_reach(ws, app, load_robot(robot))


def test_cell_points_resolved_through_their_frames():
    r = report_of(CELL)
    assert r.tools == ["tGripper[0]", "tSuction[0]"] and r.points == 7 and r.joints == 1
    by = {(e.name, e.tool): e for e in r.entries}
    # pPlace[2] is in fPallet[1] (rz 180) in fCell: world (750, -500, 60), 900 mm away
    e = by[("pPlace[2]", "tGripper[0]")]
    assert e.status == "unreachable" and e.severity == "warning" and e.line == 27
    assert e.data["target_mm"] == [750.0, -500.0, 60.0]
    e = by[("pPick[1]", "tSuction[0]")]
    assert e.status == "limits" and e.data["axis"] == 5
    assert by[("pPick[0]", "tGripper[0]")].status == "ok"
    assert by[("jHome[0]", "")].status == "ok"
    # a bigger arm reaches the pallets
    r90 = report_of(CELL, "TX2-90XL")
    assert {e.status for e in r90.entries if e.name.startswith("pPlace") and e.tool == "tGripper[0]"} <= {
        "ok", "near-singularity", "near-limit"}


def test_joints_outside_or_near_the_limits_and_points_near_a_singularity(tmp_path):
    app = tmp_path / "Cell"
    shutil.copytree(CELL, app)
    dtx = app / "Cell.dtx"
    text = dtx.read_text(encoding="utf-8-sig")
    text = text.replace('<Value key="0" j1="0" j2="-20" j3="110" j4="0" j5="80" j6="0" />',
                        '<Value key="0" j1="0" j2="-20" j3="110" j4="0" j5="80" j6="0" />\n'
                        '      <Value key="1" j1="0" j2="130" j3="0" j4="0" j5="0" j6="0" />\n'
                        '      <Value key="2" j1="179" j2="0" j3="90" j4="0" j5="45" j6="0" />')
    text = text.replace('type="jointRx" size="1">', 'type="jointRx" size="3">', 1)
    # the gripper horizontal in front of the forearm, in the configuration where the wrist is
    # straight (j5 = 0): flange at (380, 20, 290) pointing along X, the TCP 145.5 mm further
    text = text.replace('<Data name="jHome"',
                        '<Data name="pStraight" access="private" xsi:type="array" type="pointRx" size="1">\n'
                        '      <Value key="0" x="525.5" y="20" z="290" ry="90" shoulder="lefty" elbow="epositive" '
                        'wrist="wpositive" fatherId="world[0]" />\n'
                        '    </Data>\n    <Data name="jHome"')
    dtx.write_text(text, encoding="utf-8")
    r = report_of(app)
    by = {(e.name, e.tool): e for e in r.entries}
    e = by[("jHome[1]", "")]
    assert e.status == "limits" and e.data == {"axis": 2, "excess_deg": 2.5}
    e = by[("jHome[2]", "")]
    assert e.status == "near-limit" and e.data["limit_axis"] == 1 and e.data["limit_margin_deg"] == 1.0
    e = by[("pStraight[0]", "tGripper[0]")]
    assert e.status == "near-singularity" and e.data["singularity"] == "wrist"
    assert e.data["singularity_distance"] < 1e-6


def test_cli(tmp_path, capsys):
    out = tmp_path / "reach.json"
    # a point may be used with only some of the tools, or not at all: warnings, exit 0 by
    # default, 1 with --fail-on warning (as lint)
    assert main(["reach", str(CELL), "--robot", "tx2-60", "--format", "json", "-o", str(out)]) == 0
    assert main(["reach", str(CELL), "--robot", "tx2-60", "--fail-on", "warning"]) == 1
    assert main(["reach", str(CELL), "--robot", "tx2-60", "--fail-on", "never"]) == 0
    body = json.loads(out.read_text())
    assert body["version"] == 1 and body["robot"] == "TX2-60"
    assert {e["status"] for e in body["entries"]} == {"unreachable", "limits"}
    assert main(["reach", str(CELL), "--robot", "tx2-90xl"]) in (0, 1)
    text = capsys.readouterr().out
    assert "val3check reach: Cell with TX2-90XL" in text
    assert main(["reach", str(CELL), "--robot", "nosuch"]) == 2


PICKPLACE = ROOT / "fixtures" / "valid" / "PickPlace"


def test_a_point_or_joint_of_the_other_arm_family_says_so(tmp_path):
    """Issue 28 item 13: a six-axis configuration (elbow, wrist) on a SCARA is not just "out of
    reach": the entry says the point belongs to another arm family (9.7.2), then what the check
    finds with the shoulder alone."""
    r = report_of(PICKPLACE, "TS2-60")
    by = {e.name: e for e in r.entries}
    assert by["pPick[0]"].status == "family" and by["pPick[0]"].severity == "warning"
    assert "is a pointRx, of a six-axis arm" in by["pPick[0]"].message and "error 81" in by["pPick[0]"].message
    assert by["jHome[0]"].status == "family" and "6 axes, a six-axis arm's" in by["jHome[0]"].message
    # a generic `point` whose data imposes an elbow and a wrist, far away: the family first, then the reach
    app = tmp_path / "PickPlace"
    shutil.copytree(PICKPLACE, app)
    dtx = app / "PickPlace.dtx"
    text = dtx.read_text(encoding="utf-8").replace('type="pointRx"', 'type="point"')
    dtx.write_text(text.replace('x="0" y="0" z="0" ry="180" shoulder="lefty"', 'x="2000" y="0" z="0" ry="180" '
                                                                              'shoulder="lefty"'), encoding="utf-8")
    by = {e.name: e for e in report_of(app, "TS2-60").entries}
    e = by["pPick[0]"]
    assert e.status == "family" and e.data["found"] == "unreachable"
    assert e.message.startswith("point pPick[0] has the configuration of a six-axis arm (elbow epositive, wrist "
                                "wpositive), not of the TS2-60, a SCARA")
    assert "; point pPick[0] with tool tGripper[0] is out of the arm's reach" in e.message
    assert by["pSlot0[0]"].status != "family"  # esame, wsame impose nothing
    # on the six-axis arm it was written for, no family entry
    assert "family" not in {e.status for e in report_of(PICKPLACE, "TX2-60").entries}
