"""Issue 21 L: every number of a cell file lies in a documented sane range (docs/cell.md,
"Limits"), checked after the unit: a 1e100 mm box around the arm said "nothing of the cell in
reach" (exit 0), an inch value that overflows to infinity was accepted. Each is refused at its
line and column (R030 in a run); at the limit, the checks still work."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("fcl")

from val3check.collision import CellError, CollisionChecker, MotionSpan, arm_model, read_cell  # noqa: E402
from val3check.robot import load_robot  # noqa: E402


def _problems(tmp_path, text: str) -> list[tuple[int, int, str]]:
    (tmp_path / "cell.toml").write_text(text, encoding="utf-8")
    with pytest.raises(CellError) as e:
        read_cell(tmp_path / "cell.toml")
    return [(p[1], p[2], p[3]) for p in e.value.problems]


BOX = '[[obstacle]]\nname = "cage"\nshape = "box"\n'


@pytest.mark.parametrize("text,line,col,message", [
    (BOX + "size = [1e100, 1, 1]\n", 4, 9, "obstacle 'cage': size must be from 0.001 to 1,000,000 mm (1 km), not 1e+100 mm"),
    (BOX + "size = [1e40, 1, 1]\n", 4, 9, "not 1e+40 mm"),
    (BOX + "size = [1, 1, 1e-9]\n", 4, 15, "size must be from 0.001 to 1,000,000 mm (1 km), not 1e-09 mm"),
    ('unit = "inch"\n' + BOX + "size = [1, 1e308, 1]\n", 5, 12,
     "size must be from 0.001 to 1,000,000 mm (1 km), not 1e+308 inches (inf mm)"),
    ('unit = "inch"\n' + BOX + "size = [1, 1, 1]\nat = { x = 40000 }\n", 6, 12,
     "at.x must be from -1,000,000 to 1,000,000 mm (1 km), not 40000 inches (1.016e+06 mm)"),
    (BOX + "size = [1, 1, 1]\nat = [0, 0, -2e6, 0, 0, 0]\n", 5, 13, "at must be from -1,000,000 to 1,000,000 mm"),
    (BOX + "size = [1, 1, 1]\nat = { rz = 1e300 }\n", 5, 13, "at.rz must be from -36,000 to 36,000 degrees, not 1e+300"),
    ('[[obstacle]]\nshape = "sphere"\nradius = 9223372036854775807\n', 3, 10, "radius must be from 0.001"),
    ('[[tool]]\nshape = "cylinder"\nradius = 10\nlength = 2e6\n', 4, 10, "length must be from 0.001"),
    ("margin_mm = 1e300\n", 1, 13, "margin_mm must be from 0 to 10,000 mm, not 1e+300"),
    ("touch_mm = 20000\n", 1, 12, "touch_mm must be from 0 to 10,000 mm"),
    ('[[obstacle]]\nshape = "mesh"\nfile = "m.stl"\nscale = 1e-9\n', 4, 9, "scale must be from 1e-06 to 1e+06"),
    ('[[obstacle]]\nshape = "mesh"\nfile = "m.stl"\nscale = [1, -1e7, 1]\n', 4, 9, "scale must be from 1e-06 to 1e+06"),
    ('[[obstacle]]\nname = "' + "n" * 300 + '"\nshape = "sphere"\nradius = 1\n', 2, 8,
     "name must be printable text of at most 200 characters"),
    ('[[obstacle]]\nname = "a\\u001bb"\nshape = "sphere"\nradius = 1\n', 2, 8, "not 'a\\x1bb' (control characters)"),
])
def test_numbers_out_of_range_are_refused_where_written(tmp_path, text, line, col, message):
    (tmp_path / "m.stl").write_bytes(b"")
    found = _problems(tmp_path, text)
    assert any(p[:2] == (line, col) and message in p[2] for p in found), found


def test_the_limits_themselves_are_accepted(tmp_path):
    (tmp_path / "cell.toml").write_text(
        'margin_mm = 10000\ntouch_mm = 0\n' + BOX + "size = [1e6, 0.001, 1e6]\nat = [-1e6, 1e6, 0, 36000, -36000, 0]\n")
    cell = read_cell(tmp_path / "cell.toml")
    assert cell.obstacles[0].shape.size == (1e6, 0.001, 1e6)


def test_a_kilometre_box_around_the_arm_is_a_collision(tmp_path):
    # the largest box allowed, centred on the arm: the arm starts inside it (R032 in a run), where
    # a 1e100 mm box was "nothing in reach"
    (tmp_path / "cell.toml").write_text(BOX + "size = [1e6, 1e6, 1e6]\n")
    robot = load_robot("TX2-60")
    checker = CollisionChecker(arm_model(robot), read_cell(tmp_path / "cell.toml"))
    times = np.array([0.0, 0.004])
    joints = np.zeros((2, 6))
    report = checker.check_motion(MotionSpan(1, None, "movej"), times, joints)
    assert report.starts_in_collision
