"""The speed and acceleration rules of the catalogue models (robots/dynamics.py, issue 23): one
rule per family, recomputed here from its statement; every model says that its accelerations are
assumed, and measured values (a robot file, a URDF that gives them) remove that."""

from __future__ import annotations

import math

import pytest

from val3check.robot import catalog, load_robot
from val3check.robot.models import ASSUMED_ACCELERATION_RANGE

# robots/dynamics.py, as documented in docs/motion.md ("Accelerations")
SIX_AXIS_RAMP = 0.25
SCARA_REACH_REF, SCARA_SPEEDS_REF, SCARA_RAMP_REF = 620.0, (800.0, 1200.0, 2000.0, 3000.0), 0.040
PUBLISHED = {"TS2-40": 240, "TS2-60": 220, "TS2-80": 200, "TS2-100": 170}


@pytest.mark.parametrize("name", catalog.names())
def test_every_model_follows_its_family_rule(name):
    robot = load_robot(name)
    assert robot.accelerations_assumed
    if robot.family == "six-axis":
        assert robot.accelerations == pytest.approx([v / SIX_AXIS_RAMP for v in robot.nominal_speeds], rel=1e-12)
        return
    R = robot.reach_mm
    speeds = [round(v * SCARA_REACH_REF / R, 1) for v in SCARA_SPEEDS_REF]
    ramp = round(SCARA_RAMP_REF * math.sqrt(R / SCARA_REACH_REF), 4)
    assert robot.nominal_speeds == pytest.approx(speeds)
    assert robot.accelerations == pytest.approx([v / ramp for v in speeds], abs=0.05)
    assert {"ramp_s", "nominal_speeds"} <= robot.assumed


def test_a_longer_scara_is_slower_as_the_published_cycles_are():
    arms = [load_robot(n) for n in PUBLISHED]
    assert [a.reach_mm for a in arms] == sorted(a.reach_mm for a in arms)
    for short, long in zip(arms, arms[1:]):
        assert all(x > y for x, y in zip(short.nominal_speeds, long.nominal_speeds))
        assert all(x > y for x, y in zip(short.accelerations, long.accelerations))
    # the flange's top speed (axis 1 alone, arm stretched) is the same for every size
    tops = {round(math.radians(a.nominal_speeds[0]) * a.reach_mm, -1) for a in arms}
    assert len(tops) == 1


@pytest.mark.parametrize("name,cpm", sorted(PUBLISHED.items()))
def test_the_published_cycle_is_recorded_with_its_source(name, cpm):
    facts = {f.key: f.text for f in load_robot(name).provenance.facts}
    assert facts["standard_cycle"].startswith(f"{cpm} cycles per minute ({60 / cpm:.3f} s)")
    assert "TS2 range leaflet" in facts["standard_cycle"]


def test_measured_accelerations_remove_the_assumption(tmp_path):
    robot = load_robot("TX2-60")
    assert robot.describe()["accelerations_assumed"] is True
    given = robot.with_assumptions({"accelerations": [1000, 1000, 1000, 2000, 2000, 3000]})
    assert not given.accelerations_assumed and given.describe()["accelerations_assumed"] is False
    assert not robot.with_assumptions({"ramp_s": 0.3}).accelerations_assumed
    assert robot.with_assumptions({"nominal_speeds": {"j1": 400}}).accelerations_assumed  # same ramp, still assumed
    f = tmp_path / "cell.toml"
    f.write_text('arm = "TS2-60"\n[assume]\naccelerations = [9000, 9000, 20000, 30000]\n', encoding="utf-8")
    assert not load_robot(str(f)).accelerations_assumed


def test_a_urdf_is_assumed_unless_it_gives_its_accelerations(tmp_path):
    src = load_robot("TX2-60").source
    text = open(src, encoding="utf-8").read()
    plain = tmp_path / "plain.urdf"  # no per-joint accelerations: the default ramp, an assumption
    plain.write_text("\n".join(line for line in text.splitlines() if "<joint name=\"joint_" not in line
                               or "type=" in line), encoding="utf-8")
    assert load_robot(str(plain)).accelerations_assumed
    measured = tmp_path / "measured.urdf"  # the accelerations given, no <assumption> about them
    measured.write_text("\n".join(line for line in text.splitlines() if 'key="ramp_s"' not in line), encoding="utf-8")
    assert not load_robot(str(measured)).accelerations_assumed


def test_the_range_scales_every_acceleration():
    robot = load_robot("TS2-80")
    lo, hi = ASSUMED_ACCELERATION_RANGE
    assert (lo, hi) == (0.5, 2.0)
    slow, fast = robot.with_acceleration_scale(lo), robot.with_acceleration_scale(hi)
    assert slow.accelerations == pytest.approx([a / 2 for a in robot.accelerations])
    assert fast.accelerations == pytest.approx([a * 2 for a in robot.accelerations])
    assert slow.nominal_speeds == robot.nominal_speeds and slow.accelerations_assumed
    with pytest.raises(Exception):
        robot.with_acceleration_scale(0)
