"""Collisions checked along a simulated run (issue 14 phase 2): `sim` with a cell, against analytic
geometry; the findings R030-R036 at the lines of the motion instructions; the PickPlace cell."""

from __future__ import annotations

import json
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("fcl")

from interpretation.simsupport import code_pos, run_folder, sim  # noqa: E402

from val3check.motion.kin import ArmKin  # noqa: E402
from val3check.robot import load_robot  # noqa: E402
from val3check.simulation.own_clock import own_times  # noqa: E402

ROBOT = load_robot("TX2-60")
KIN = ArmKin(ROBOT)
DT = 0.004
ROOT = Path(__file__).resolve().parents[2]
PICKPLACE = ROOT / "fixtures" / "valid" / "PickPlace"
SCENARIO = ROOT / "fixtures" / "scenarios" / "pickplace.toml"

# A straight line of the tool centre point (tTool, 100 mm out of the flange, pointing down) along y
# at x = 400, z = 100; a ball of radius 10 around the TCP is the tool's only solid.
LINE = """
begin
  tTool.trsf = {0, 0, 100, 0, 0, 0}
  pA.trsf = {400, -200, 100, 0, 180, 0}
  pA.config = {sfree, efree, wfree}
  pB = pA
  pB.trsf.y = 200
  mD.tvel = 200
  movej(pA, tTool, mD)
  movel(pB, tTool, mD)
  waitEndMove()
end
"""
LINE_GLOBALS = ["point pA", "point pB", "tool tTool", "mdesc mD"]
TIP = """
[[tool]]
name = "tip"
tool = "tTool"
shape = "sphere"
radius = 10
"""


def _cell(tmp_path: Path, text: str) -> str:
    p = tmp_path / "cell.toml"
    p.write_text("version = 1\n" + text, encoding="utf-8")
    return str(p)


def _run(tmp_path, code, globals_, cell_text, **kw):
    cell = _cell(tmp_path, cell_text)
    return sim(tmp_path, code, globals_=globals_, robot=ROBOT, collisions=True, cell=cell, **kw)


def _tcp_y(r, t: float) -> float:
    q = r.motion.trajectory.position(t)
    return float(KIN.fk(np.asarray(q)[None])[0][1, 3])


def _crossing(r, rec, y: float) -> float:
    """When the TCP (the flange is 100 mm above it, same y: the tool points down) passes y on the
    movel: bisection on the simulated trajectory."""
    lo, hi = rec.start, rec.end
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if _tcp_y(r, mid) < y:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def test_box_on_the_line_contact_at_its_time_and_line(tmp_path):
    # a box 40 mm wide centred on the line at y = 50: the tip ball (r 10) meets its face y = 30 when
    # the TCP reaches y = 20
    r = _run(tmp_path, LINE, LINE_GLOBALS, TIP + """
[[obstacle]]
name = "block"
shape = "box"
size = [40, 40, 40]
at = { x = 400, y = 50, z = 100 }
""")
    hits = [d for d in r.diagnostics if d.code == "R031"]
    assert len(hits) == 1, r.diagnostics
    d = hits[0]
    assert (d.line, d.col) == code_pos(r, 10, 3) and d.task == "Example~" and d.program == "start"
    assert "tool tTool 'tip' hits obstacle 'block'" in d.message
    rec = r.motion.motions[1]
    assert rec.kind == "movel"
    expected = _crossing(r, rec, 20.0)
    assert abs(d.time_us / 1e6 - expected) <= DT
    c = r.collision.by_motion[1].first_contact
    assert abs(c.time - expected) <= DT and c.kind == "contact"
    assert r.collision.contacts == [(1, c)]
    # the movej before it is clean, and its clearance measured
    assert r.collision.by_motion[0].first_contact is None


@pytest.mark.parametrize("gap", [4.0, 12.5])
def test_box_beside_the_line_near_miss_with_the_analytic_clearance(tmp_path, gap):
    # a wide plate under the line, its top `gap` below the tip ball
    r = _run(tmp_path, LINE, LINE_GLOBALS, "margin_mm = 15\n" + TIP + f"""
[[obstacle]]
name = "plate"
shape = "box"
size = [100, 200, 20]
at = {{ x = 400, y = 0, z = {100 - 10 - gap - 10} }}
""")
    m = r.collision.by_motion[1].min_clearance
    assert abs(m.mm - gap) <= 0.05 + 0.02 * gap  # docs/cell.md: within 0.05 mm + 2 %
    assert {m.body_a, m.body_b} == {"tool tTool 'tip'", "obstacle 'plate'"}
    near = [d for d in r.diagnostics if d.code == "R033"]
    assert [(d.line, d.col) for d in near] == [code_pos(r, 10, 3)]
    assert f"{m.mm:.1f} mm" in near[0].message and "margin 15 mm" in near[0].message
    assert not [d for d in r.diagnostics if d.code in ("R031", "R032")]
    # the per-sample clearance: a lower bound, the minimum among them
    rep = r.collision.by_motion[1]
    assert rep.clearance.min() == pytest.approx(m.mm, abs=1e-9)
    t, c = r.collision.clearance_trace()
    assert len(t) == len(c) == sum(len(x.times) for x in r.collision.by_motion.values())


def test_without_margin_no_near_miss(tmp_path):
    r = _run(tmp_path, LINE, LINE_GLOBALS, TIP + """
[[obstacle]]
name = "plate"
shape = "box"
size = [100, 200, 20]
at = { x = 400, y = 0, z = 76 }
""")
    assert not [d for d in r.diagnostics if d.code.startswith("R03")]
    assert r.collision.by_motion[1].min_clearance.mm == pytest.approx(4.0, abs=0.2)


PICK = """
begin
  tGrip.trsf = {0, 0, 100, 0, 0, 0}
  pPick.trsf = {400, -200, 40, 0, 180, 0}
  pPick.config = {sfree, efree, wfree}
  pPlace = pPick
  pPlace.trsf.y = 200
  movej(appro(pPick, {0, 0, -100, 0, 0, 0}), tGrip, mD)
  movel(pPick, tGrip, mD)
  close(tGrip)
  movel(appro(pPick, {0, 0, -100, 0, 0, 0}), tGrip, mD)
  movel(appro(pPlace, {0, 0, -100, 0, 0, 0}), tGrip, mD)
  movel(pPlace, tGrip, mD)
  open(tGrip)
  movel(appro(pPlace, {0, 0, -100, 0, 0, 0}), tGrip, mD)
  movel(appro(pPlace, {0, 0, 20, 0, 0, 0}), tGrip, mD)
  waitEndMove()
end
"""
PICK_GLOBALS = ["point pPick", "point pPlace", "tool tGrip", "mdesc mD"]
# a 40 mm cube held with its top at the TCP, on a table whose top is at z = 0; the tool's tip is a
# small ball 5 mm above the TCP (inside the gripper's fingers)
PICK_CELL = """
[[tool]]
name = "finger"
tool = "tGrip"
shape = "sphere"
radius = 4
at = { z = -5 }

[[obstacle]]
name = "table"
shape = "box"
size = [200, 600, 40]
at = { x = 400, z = -20 }

[[part]]
name = "brick"
tool = "tGrip"
grasp = "close"
shape = "box"
size = [40, 40, 40]
at = { z = 20 }
"""


def test_part_carried_after_close_hits_a_wall_and_is_left_on_open(tmp_path):
    # a wall between pick and place, its top 30 mm under the TCP's travel height (z = 140): the
    # part (40 mm under the TCP) hits it, the finger above the TCP does not
    wall = """
[[obstacle]]
name = "wall"
shape = "box"
size = [100, 20, 100]
at = { x = 400, y = 0, z = 60 }
"""
    r = _run(tmp_path, PICK, PICK_GLOBALS, PICK_CELL + wall)
    hits = [d for d in r.diagnostics if d.code == "R031"]
    carried = [d for d in hits if "part 'brick' hits obstacle 'wall'" in d.message]
    assert [(d.line, d.col) for d in carried] == [code_pos(r, 12, 3)], hits
    # the part is left on the table on open: the last movel brings the finger 20 mm into it
    left = [d for d in hits if "part 'brick'" in d.message and "wall" not in d.message]
    assert [(d.line, d.col) for d in left] == [code_pos(r, 16, 3)], hits
    assert "tool tGrip 'finger'" in left[0].message
    assert not [d for d in r.diagnostics if d.code in ("R032", "R035")]


def test_part_carried_and_set_down_clean(tmp_path):
    # without the wall and without going back down on the part left: no finding; the part touches
    # the table at pick and place only (allowed)
    code = PICK.replace("  movel(appro(pPlace, {0, 0, 20, 0, 0, 0}), tGrip, mD)\n", "")
    r = _run(tmp_path, code, PICK_GLOBALS, PICK_CELL)
    assert not [d for d in r.diagnostics if d.code.startswith("R03")], r.diagnostics
    assert len(r.collision.by_motion) == 6 and not r.collision.contacts and not r.collision.drops


def test_obstacle_follows_the_frame_the_program_moves(tmp_path):
    # the same line twice; between them the program moves fBlock under the line
    code = """
begin
  tTool.trsf = {0, 0, 100, 0, 0, 0}
  pA.trsf = {400, -200, 100, 0, 180, 0}
  pA.config = {sfree, efree, wfree}
  pB = pA
  pB.trsf.y = 200
  movej(pA, tTool, mD)
  movel(pB, tTool, mD)
  waitEndMove()
  fBlock.trsf.x = 400
  movel(pA, tTool, mD)
  waitEndMove()
end
"""
    r = _run(tmp_path, code, LINE_GLOBALS + ["frame fBlock"], TIP + """
[[obstacle]]
name = "block"
shape = "box"
frame = "fBlock"
size = [40, 40, 40]
at = { y = 50, z = 100 }
""")
    hits = [d for d in r.diagnostics if d.code == "R031"]
    assert [(d.line, d.col) for d in hits] == [code_pos(r, 12, 3)], r.diagnostics
    assert not [d for d in r.diagnostics if d.code == "R036"]


def test_frame_without_value_leaves_the_obstacle_out_and_says_where(tmp_path):
    r = _run(tmp_path, LINE, LINE_GLOBALS, TIP + """
[[obstacle]]
name = "block"
shape = "box"
frame = "fNowhere[3]"
size = [40, 40, 40]
at = { x = 400, y = 50, z = 100 }
""")
    found = [d for d in r.diagnostics if d.code.startswith("R03")]
    assert [(d.code, Path(d.path).name, d.line) for d in found] == [("R036", "cell.toml", 9)]
    assert "fNowhere[3]" in found[0].message


def test_start_in_collision_reported_once(tmp_path):
    # the arm stands with its flange in a ball; the movej away starts in collision; the contact is not
    # reported again as a contact of that motion
    code = """
begin
  pA.trsf = {400, 0, 100, 0, 180, 0}
  pA.config = {sfree, efree, wfree}
  movej(pA, flange, mD)
  movej(pA, flange, mD)
  waitEndMove()
end
"""
    r = _run(tmp_path, code, ["point pA", "mdesc mD"], """
[[obstacle]]
name = "ball"
shape = "sphere"
radius = 40
at = { x = 0, y = 20, z = 660 }
""")
    found = [(d.code, d.line) for d in r.diagnostics if d.code.startswith("R03")]
    assert found == [("R032", code_pos(r, 5, 3)[0])]


def test_cell_file_errors_are_diagnostics_and_the_arm_is_still_checked(tmp_path):
    r = _run(tmp_path, LINE, LINE_GLOBALS, """
[[obstacle]]
name = "block"
shape = "cube"
""")
    bad = [d for d in r.diagnostics if d.code == "R030"]
    assert bad and all(Path(d.path).name == "cell.toml" and d.line >= 2 for d in bad)
    assert r.collision is not None and r.collision.cell is None and len(r.collision.by_motion) == 2


def test_without_cell_self_collision_only(tmp_path):
    code = """
begin
  movej({-25, 13, 90, 154, 73, -172}, flange, mD)
  movej({-25, 13, 150, 154, 73, -172}, flange, mD)
  waitEndMove()
end
"""
    r = sim(tmp_path, code, globals_=["mdesc mD"], robot=ROBOT, collisions=True)
    found = [d for d in r.diagnostics if d.code.startswith("R03")]
    assert found and {(d.code, d.line) for d in found} == {("R034", code_pos(r, 4, 3)[0])}
    assert "self-collision" in found[0].message
    assert r.collision.cell is None and r.collision.cell_path is None
    assert r.collision.clearance_trace()[0].size == 0


def test_no_collision_checks_unless_asked(tmp_path):
    r = sim(tmp_path, LINE, globals_=LINE_GLOBALS, robot=ROBOT)
    assert r.collision is None


# ---- PickPlace, through the command line ------------------------------------------------------------------


def _cli(args, capsys):
    from val3check.cli import main

    code = main(args)
    out = capsys.readouterr()
    return code, out.out, out.err


def test_pickplace_cell_found_beside_the_application_is_clean(capsys):
    code, out, err = _cli(["sim", str(PICKPLACE), "--robot", "tx2-60", "--scenario", str(SCENARIO),
                           "--report", "json", "--duration", "20"], capsys)
    assert code == 0, err
    rep = json.loads(out)
    c = rep["collision"]
    assert c["cell"]["found"] == "found" and c["cell"]["path"].endswith("PickPlace/val3check-cell.toml")
    assert c["summary"]["contacts"] == 0 and c["summary"]["near_misses"] == 0
    assert c["summary"]["motions"] == sum(1 for m in rep["motion"]["motions"] if m["start"] is not None)
    # the closest approach: a jaw (outer face 32 mm from the cube's centre) beside the cube left in
    # the next slot (70 mm pitch, 20 mm half width): 70 - 20 - 32 = 18 mm
    assert c["summary"]["min_clearance_mm"] == pytest.approx(18.0, abs=0.05)
    assert c["cell"]["parts"] == ["cube"]
    assert not [d for d in rep["diagnostics"] if d["code"].startswith("R03")]


def test_pickplace_text_names_the_cell(capsys):
    code, out, _ = _cli(["sim", str(PICKPLACE), "--robot", "tx2-60", "--scenario", str(SCENARIO),
                         "--duration", "8"], capsys)
    assert code == 0
    assert "collision: cell " in out and "(found beside the application)" in out
    assert "closest approach to the cell per motion instruction:" in out and "no contact over" in out


def test_pickplace_with_a_post_on_the_pallet_reports_the_place_movel(tmp_path, capsys):
    app = tmp_path / "PickPlace"
    shutil.copytree(PICKPLACE, app)
    cell = (app / "val3check-cell.toml").read_text(encoding="utf-8")
    # a post standing in slot 1 of the pallet (fPallet x = 70, y = 0), in the pallet's frame
    (app / "val3check-cell.toml").write_text(cell + """
[[obstacle]]
name = "post"
shape = "cylinder"
radius = 15
length = 200
frame = "fPallet"
at = { x = 70, z = 60 }
""", encoding="utf-8")
    code, out, _ = _cli(["sim", str(app), "--robot", "tx2-60", "--scenario", str(SCENARIO), "--report", "json",
                         "--duration", "12"], capsys)
    assert code == 1
    rep = json.loads(out)
    hits = [d for d in rep["diagnostics"] if d["code"] == "R031"]
    assert hits
    place = (app / "place.pgx").read_text(encoding="utf-8").split("\n")
    line = next(i for i, t in enumerate(place, 1) if "movej(appro(l_pSlot" in t)
    first = hits[0]
    assert first["path"].endswith("place.pgx") and first["task"] == "robot"
    assert first["line"] in (line, line + 1)  # the approach movej or the movel down
    assert "obstacle 'post'" in first["message"]


def test_no_cell_and_no_option_says_so(tmp_path, capsys):
    app = tmp_path / "PickPlace"
    shutil.copytree(PICKPLACE, app)
    (app / "val3check-cell.toml").unlink()
    code, out, _ = _cli(["sim", str(app), "--robot", "tx2-60", "--scenario", str(SCENARIO), "--duration", "6"],
                        capsys)
    assert code == 0
    assert "collision: no cell file" in out and "against itself only" in out


def test_cell_option_with_errors_points_at_the_cell_file(tmp_path, capsys):
    cell = tmp_path / "bad.toml"
    cell.write_text('version = 1\n[[obstacle]]\nname = "t"\nshape = "box"\nsize = [1, 2]\n', encoding="utf-8")
    code, out, _ = _cli(["sim", str(PICKPLACE), "--robot", "tx2-60", "--scenario", str(SCENARIO), "--duration", "4",
                         "--cell", str(cell)], capsys)
    assert code == 1
    assert "bad.toml:5:8: R030 error: cell file: " in out
    assert "cannot be used (R030)" in out


def test_json_collision_section_is_deterministic(capsys):
    args = ["sim", str(PICKPLACE), "--robot", "tx2-60", "--scenario", str(SCENARIO), "--report", "json",
            "--duration", "6"]
    _, a, _ = _cli(args, capsys)
    _, b, _ = _cli(args, capsys)
    assert a == b
    m = json.loads(a)["collision"]["motions"][1]
    assert len(m["clearance"]["times"]) == len(m["clearance"]["mm"]) > 10
    assert math.isclose(m["clearance"]["times"][0], m["start"])


def test_pickplace_parts_stay_on_the_pallet_until_it_is_cleared(tmp_path, capsys):
    # without `cleared_by` the cubes of the first pallet stay: the first cube of the second pallet is
    # set down on the one in slot 0
    app = tmp_path / "PickPlace"
    shutil.copytree(PICKPLACE, app)
    cell = (app / "val3check-cell.toml").read_text(encoding="utf-8")
    assert 'cleared_by = "doPalletFull"' in cell
    (app / "val3check-cell.toml").write_text(cell.replace('cleared_by = "doPalletFull"', ""), encoding="utf-8")
    code, out, _ = _cli(["sim", str(app), "--robot", "tx2-60", "--scenario", str(SCENARIO), "--report", "json",
                         "--duration", "35"], capsys)
    rep = json.loads(out)
    hits = [d for d in rep["diagnostics"] if d["code"] == "R031"]
    assert code == 1 and hits
    pallet_change = next(e["time"] for e in rep["io_log"] if e["link"].endswith("%Q1") and e["value"] is True)
    place = (app / "place.pgx").read_text(encoding="utf-8").split("\n")
    down = next(i for i, t in enumerate(place, 1) if "movel(l_pSlot, tGripper, mApproach)" in t)
    first = hits[0]
    assert first["time"] > pallet_change and first["line"] == down
    assert "part 'cube' hits part 'cube'" in first["message"]


def test_cleared_by_is_checked_where_it_is_written(tmp_path):
    from val3check.collision import CellError, read_cell

    p = tmp_path / "cell.toml"
    p.write_text('version = 1\n[[part]]\nname = "c"\ntool = "tG"\nshape = "sphere"\nradius = 5\ncleared_by = 3\n',
                 encoding="utf-8")
    with pytest.raises(CellError) as exc:
        read_cell(p)
    assert [(line, col) for _, line, col, _ in exc.value.problems] == [(7, 14)]
    assert "cleared_by must be the name or the link of a digital input or output" in str(exc.value)


def test_frame_changed_while_the_motion_before_runs_is_seen_by_the_next_one(tmp_path):
    # line 11 is queued behind line 10; the program moves fBlock under the line while line 10 runs:
    # line 10 started with the old value (clean), line 11 starts with the new one (contact)
    code = """
begin
  tTool.trsf = {0, 0, 100, 0, 0, 0}
  pA.trsf = {400, -200, 100, 0, 180, 0}
  pA.config = {sfree, efree, wfree}
  pB = pA
  pB.trsf.y = 200
  fBlock.trsf.x = -2000
  movej(pA, tTool, mD)
  waitEndMove()
  movel(pB, tTool, mD)
  movel(pA, tTool, mD)
  fBlock.trsf.x = 400
  waitEndMove()
end
"""
    r = _run(tmp_path, code, LINE_GLOBALS + ["frame fBlock"], TIP + """
[[obstacle]]
name = "block"
shape = "box"
frame = "fBlock"
size = [40, 40, 40]
at = { y = 50, z = 100 }
""")
    hits = [d for d in r.diagnostics if d.code == "R031"]
    assert [(d.line, d.col) for d in hits] == [code_pos(r, 12, 3)], r.diagnostics
    assert r.collision.by_motion[1].first_contact is None
    assert not [d for d in r.diagnostics if d.code in ("R032", "R036")]


def test_an_obstacle_beside_the_base_is_no_near_miss_of_every_motion(tmp_path):
    # a cabinet 5 mm from the arm's base (a cylinder of radius 111 mm up to z = -110), margin 10:
    # the base never moves, so the motions' clearances are those of what they move
    r = _run(tmp_path, LINE, LINE_GLOBALS, "margin_mm = 10\n" + TIP + """
[[obstacle]]
name = "cabinet"
shape = "box"
size = [100, 100, 100]
at = { x = -166, z = -300 }
""")
    assert not [d for d in r.diagnostics if d.code.startswith("R03")], r.diagnostics
    assert all(rep.min_clearance is None or "base_link" not in rep.min_clearance.body_a
               for rep in r.collision.by_motion.values())
    # moved into the base: the first motion starts in collision
    (tmp_path / "in").mkdir()
    r = _run(tmp_path / "in", LINE, LINE_GLOBALS, TIP + """
[[obstacle]]
name = "cabinet"
shape = "box"
size = [100, 100, 100]
at = { x = -150, z = -300 }
""")
    found = [(d.code, d.message) for d in r.diagnostics if d.code.startswith("R03")]
    assert len(found) == 1 and found[0][0] == "R032" and "base_link (base) hits obstacle 'cabinet'" in found[0][1]


def test_a_cell_without_an_arm_model_is_said_not_checked(tmp_path):
    r = sim(tmp_path, LINE.replace("movej(pA, tTool, mD)\n  movel(pB, tTool, mD)\n  waitEndMove()\n", ""),
            globals_=LINE_GLOBALS, cell=_cell(tmp_path, TIP))
    found = [d for d in r.diagnostics if d.code.startswith("R03")]
    assert [d.code for d in found] == ["R037"] and "no arm model" in found[0].message
    assert r.collision is None


def test_an_application_in_inches_with_its_cell_in_inches(tmp_path):
    # the frame test in inches: program, frame values and cell (unit: the application's) in inches
    from interpretation.simsupport import build

    def i(mm: float) -> str:
        return repr(mm / 25.4)

    code = f"""
begin
  tTool.trsf = {{0, 0, {i(100)}, 0, 0, 0}}
  pA.trsf = {{{i(400)}, {i(-200)}, {i(100)}, 0, 180, 0}}
  pA.config = {{sfree, efree, wfree}}
  pB = pA
  pB.trsf.y = {i(200)}
  fBlock.trsf.x = {i(-2000)}
  movej(pA, tTool, mD)
  movel(pB, tTool, mD)
  waitEndMove()
  fBlock.trsf.x = {i(400)}
  movel(pA, tTool, mD)
  waitEndMove()
end
"""
    folder = build(tmp_path, code, globals_=LINE_GLOBALS + ["frame fBlock"])
    pjx = folder / "Example.pjx"
    pjx.write_text(pjx.read_text(encoding="utf-8").replace('millimeterUnit="true"', 'millimeterUnit="false"'),
                   encoding="utf-8")
    cell = _cell(tmp_path, f"""
[[tool]]
name = "tip"
tool = "tTool"
shape = "sphere"
radius = {i(10)}

[[obstacle]]
name = "block"
shape = "box"
frame = "fBlock"
size = [{i(40)}, {i(40)}, {i(40)}]
at = {{ y = {i(50)}, z = {i(100)} }}
""")
    r = run_folder(folder, robot=ROBOT, collisions=True, cell=cell)
    hits = [d for d in r.diagnostics if d.code == "R031"]
    assert [(d.line, d.col) for d in hits] == [code_pos(r, 13, 3)], r.diagnostics
    c = r.collision.by_motion[2].first_contact
    # the tip (10 mm) meets the block's face (y = 30 mm) when the TCP, coming back, is at y = 80 mm
    assert abs(c.time - _crossing_back(r, r.motion.motions[2], 80.0)) <= DT
    assert r.collision.by_motion[1].min_clearance.mm > 500


def _crossing_back(r, rec, y: float) -> float:
    lo, hi = rec.start, rec.end
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if _tcp_y(r, mid) > y:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def test_cell_none_skips_the_cell_found_beside_the_application(capsys):
    code, out, _ = _cli(["sim", str(PICKPLACE), "--robot", "tx2-60", "--scenario", str(SCENARIO), "--duration", "4",
                         "--cell", "none"], capsys)
    assert code == 0
    assert "collision: no cell (--cell none): the arm is checked against itself only" in out
    assert "closest approach" not in out


def test_a_cell_file_found_beside_the_application_may_not_link_out_of_it(tmp_path, capsys):
    app = tmp_path / "repo" / "PickPlace"
    shutil.copytree(PICKPLACE, app)
    secret = tmp_path / "secret.toml"
    secret.write_text('version = 1\ndescription = "outside"\n', encoding="utf-8")
    (app / "val3check-cell.toml").unlink()
    (app / "val3check-cell.toml").symlink_to(secret)
    code, out, _ = _cli(["sim", str(app), "--robot", "tx2-60", "--scenario", str(SCENARIO), "--duration", "4"], capsys)
    assert code == 1
    assert "R030 error: cell file: cannot read the cell file: outside the application" in out
    # named on the command line, the same file is read
    code, out, _ = _cli(["sim", str(app), "--robot", "tx2-60", "--scenario", str(SCENARIO), "--duration", "4",
                         "--cell", str(secret)], capsys)
    assert code == 0 and "R030" not in out


def test_collision_checks_keep_to_the_wall_clock_budget(tmp_path):
    from val3check.simulation.collision_run import ValueWatch, check_run

    r = _run(tmp_path, LINE, LINE_GLOBALS, TIP)
    run, diags = check_run(r.motion, None, ValueWatch(None), ROBOT, max_wall=-1.0, app_path=r.app_path)
    assert not run.by_motion
    assert [d.code for d in diags] == ["R037"] and "0 of 2 motions checked" in diags[0].message


def test_a_fast_movej_touching_a_thin_plate_only_between_two_samples(tmp_path):
    # the stretched arm turns on axis 1 (a tool ball of radius 2, 100 mm out of the flange): a plate
    # 4 mm thick across the ball's path, where it is halfway between two 4 ms samples
    code = """
begin
  tTool.trsf = {0, 0, 100, 0, 0, 0}
  movej({-40, 90, 0, 0, 0, 0}, tTool, mD)
  movej({40, 90, 0, 0, 0, 0}, tTool, mD)
  waitEndMove()
end
"""
    (tmp_path / "a").mkdir()
    ball = TIP.replace("radius = 10", "radius = 2")
    free = _run(tmp_path / "a", code, ["tool tTool", "mdesc mD"], ball)
    rec = free.motion.motions[1]
    times = rec.start + own_times(rec.end - rec.start)  # the checks' samples: every 4 ms from the motion's start
    Q = free.motion.trajectory.positions(times)
    speeds = np.abs(np.diff(Q[:, 0]))
    k = int(np.argmax(speeds))  # the fastest step
    mid = free.motion.trajectory.position(0.5 * (times[k] + times[k + 1]))
    T = ROBOT.fk_matrix(list(mid), tool=(0, 0, 100, 0, 0, 0))
    x, y, z = (float(T[i][3]) for i in range(3))
    step_mm = math.radians(speeds[k]) * math.hypot(x, y)
    assert step_mm > 12.0  # the ball moves more than the plate's thickness + its diameter per sample
    rz = math.degrees(math.atan2(y, x))
    (tmp_path / "b").mkdir()
    r = _run(tmp_path / "b", code, ["tool tTool", "mdesc mD"], ball + f"""
[[obstacle]]
name = "plate"
shape = "box"
size = [30, 4, 20]
at = {{ x = {x!r}, y = {y!r}, z = {z!r}, rz = {rz!r} }}
""")
    hits = [d for d in r.diagnostics if d.code == "R031"]
    assert [(d.line, d.col) for d in hits] == [code_pos(r, 5, 3)], r.diagnostics
    rep = r.collision.by_motion[1]
    c = rep.first_contact
    assert "obstacle 'plate'" in (c.body_a, c.body_b)
    # the samples around it are clear; the contact is between them
    i = int(np.searchsorted(rep.times, times[k] - 1e-9))
    assert rep.times[i] == pytest.approx(times[k]) and rep.clearance[i] > 0 and rep.clearance[i + 1] > 0
    assert times[k] < c.time < times[k + 1]


@pytest.mark.parametrize("element,hit", [("fBlocks[2]", True), ("fBlocks[1]", False)])
def test_an_obstacle_in_an_element_of_a_frame_array(tmp_path, element, hit):
    code = LINE.replace("  movej(pA, tTool, mD)", "  fBlocks[2].trsf.x = 400\n  fBlocks[1].trsf.x = -2000\n"
                        "  fBlocks[0].trsf.x = -2000\n  movej(pA, tTool, mD)")
    r = _run(tmp_path, code, LINE_GLOBALS + ["frame fBlocks[3]"], TIP + f"""
[[obstacle]]
name = "block"
shape = "box"
frame = "{element}"
size = [40, 40, 40]
at = {{ y = 50, z = 100 }}
""")
    assert bool([d for d in r.diagnostics if d.code == "R031"]) is hit, r.diagnostics
    assert not [d for d in r.diagnostics if d.code in ("R032", "R036")]


def test_an_obstacle_in_a_frame_of_a_library(tmp_path):
    from interpretation.simsupport import add_libraries, build, make_library

    make_library(tmp_path, "LibF", globals_=["frame fBase"])
    code = LINE.replace("  movej(pA, tTool, mD)", "  lf:fBase.trsf.x = 400\n  movej(pA, tTool, mD)")
    app = build(tmp_path, code, globals_=LINE_GLOBALS, name="App")
    add_libraries(app, {"lf": "Disk://LibF/LibF.pjx"}, name="App", autoload="true")
    cell = _cell(tmp_path, TIP + """
[[obstacle]]
name = "block"
shape = "box"
frame = "lf:fBase"
size = [40, 40, 40]
at = { y = 50, z = 100 }
""")
    r = run_folder(app, robot=ROBOT, collisions=True, cell=cell)
    hits = [d for d in r.diagnostics if d.code == "R031"]
    assert len(hits) == 1 and "obstacle 'block'" in hits[0].message, r.diagnostics
    assert not [d for d in r.diagnostics if d.code in ("R032", "R036")]
