"""The HTML report without a browser: the report model, the arm chain, the synthetic run, the page's
bytes (self-contained, escaped, deterministic, small). The page in Chromium: test_html_browser.py."""

from __future__ import annotations

import base64
import copy
import hashlib
import json
import math
import random
import re
import struct
from pathlib import Path

import jsonschema
import pytest

from synthetic_run import CART_ACCEL, MDESC, _trapezoid, synthetic_model
from val3check.reporting.html import ModelError, check_model, render
from val3check.robot.chain import arm_chain, chain_fk
from val3check.reporting.html.pack import FULL_RATE_MAX, PLOT_BUCKETS, page_data
from val3check.robot import RobotError, load_robot, names
from val3check.robot.urdf import mul

ROOT = Path(__file__).resolve().parents[2]
SCHEMA = json.loads((ROOT / "docs" / "html-report.schema.json").read_text(encoding="utf-8"))


@pytest.fixture(scope="module")
def model() -> dict:
    return synthetic_model(duration=20.0)


@pytest.fixture(scope="module")
def page(model) -> str:
    return render(model)


def _data(page: str) -> dict:
    m = re.search(r'<script type="application/json" id="v3-data">(.*?)</script>', page, re.S)
    return json.loads(m.group(1))


# ---- the arm chain ---------------------------------------------------------------------------


@pytest.mark.parametrize("name", names())
def test_chain_fk_is_the_arm_models_forward_kinematics(name):
    robot = load_robot(name)
    arm = arm_chain(robot.source)
    assert arm["joint_names"] == list(robot.joint_names)
    rng = random.Random(7)
    for _ in range(20):
        q = [rng.uniform(lo, hi) for lo, hi in robot.joint_limits]
        P = chain_fk(arm, q)[arm["flange_frame"]]
        F = robot.fk_matrix(q)
        assert max(abs(P[i][k] - F[i][k]) for i in range(3) for k in range(4)) < 1e-6
        # the world frame link is the identity in the world frame
        W = chain_fk(arm, q)[arm["world_frame"]]
        assert max(abs(W[i][k] - (1.0 if i == k else 0.0)) for i in range(3) for k in range(4)) < 1e-9


def test_chain_lists_every_joint_parents_first_and_the_cylinders_in_mm():
    arm = arm_chain(ROOT / "robots" / "tx2-60.urdf")
    seen = {arm["root"]}
    for j in arm["joints"]:
        assert j["parent"] in seen
        seen.add(j["child"])
    assert {j["name"] for j in arm["joints"]} >= {"joint_1", "joint_6", "base_link-world", "link_6-flange"}
    assert [j["index"] for j in arm["joints"] if j["type"] == "revolute"] == [0, 1, 2, 3, 4, 5]
    base = next(link for link in arm["links"] if link["name"] == "base_link")["solids"][0]
    assert base["shape"] == "cylinder" and base["radius"] == 110.0 and base["length"] == 265.0
    assert base["pose"][2][3] == 132.5
    assert arm["root_in_world"][2][3] == -375.0  # world is 375 mm above the mounting plane
    assert arm["notes"] == []


URDF_PRISMATIC = """<?xml version="1.0"?>
<robot name="gantry">
  <link name="base"><collision><geometry><box size="0.1 0.2 0.3"/></geometry></collision></link>
  <link name="carriage">
    <collision name="c"><origin xyz="0 0 0.05"/><geometry><sphere radius="0.02"/></geometry></collision>
    <visual><geometry><mesh filename="package://x/carriage.stl"/></geometry></visual>
    <collision name="m"><geometry><mesh filename="package://x/carriage.stl" scale="1 1 1"/></geometry></collision>
  </link>
  <link name="head"/>
  <joint name="slide" type="prismatic">
    <parent link="base"/><child link="carriage"/><origin xyz="0 0 1" rpy="0 0 0"/><axis xyz="0 2 0"/>
    <limit lower="-1" upper="1" velocity="1"/>
  </joint>
  <joint name="turn" type="continuous">
    <parent link="carriage"/><child link="head"/><origin xyz="0.5 0 0"/><axis xyz="0 0 1"/>
  </joint>
</robot>
"""


def test_chain_of_a_prismatic_and_continuous_urdf(tmp_path):
    path = tmp_path / "gantry.urdf"
    path.write_text(URDF_PRISMATIC, encoding="utf-8")
    arm = arm_chain(path)
    assert arm["joint_names"] == ["slide", "turn"] and arm["flange_frame"] == "head"
    slide = next(j for j in arm["joints"] if j["name"] == "slide")
    assert slide["type"] == "prismatic" and slide["axis"] == [0.0, 1.0, 0.0]  # normalised
    P = chain_fk(arm, [250.0, 90.0])
    assert P["carriage"][1][3] == pytest.approx(250.0) and P["carriage"][2][3] == pytest.approx(1000.0)
    head = P["head"]
    assert (head[0][3], head[1][3]) == (pytest.approx(500.0), pytest.approx(250.0))
    assert head[0][0] == pytest.approx(0.0, abs=1e-12) and head[1][0] == pytest.approx(1.0)  # turned 90 degrees
    solids = {link["name"]: link["solids"] for link in arm["links"]}
    assert solids["base"][0]["size"] == [100.0, 200.0, 300.0]
    assert [s["name"] for s in solids["carriage"]] == ["c"]
    assert arm["notes"] == ["mesh solids not shown: carriage/m"]


def test_chain_refuses_entities_and_names_missing_links(tmp_path):
    evil = tmp_path / "evil.urdf"
    evil.write_text('<?xml version="1.0"?>\n<!DOCTYPE robot [<!ENTITY x "y">]>\n<robot name="&x;"><link name="a"/></robot>\n')
    with pytest.raises(RobotError, match="entities"):
        arm_chain(evil)
    with pytest.raises(RobotError, match="no such file"):
        arm_chain(tmp_path / "missing.urdf")
    with pytest.raises(RobotError, match="'nowhere' is not a link"):
        arm_chain(ROOT / "robots" / "tx2-60.urdf", flange_frame="nowhere")


# ---- the synthetic run: figures computed, not invented --------------------------------------


def test_synthetic_motions_follow_the_trapezoid_formulas(model):
    robot = load_robot("tx2-60")
    for m in model["motions"]:
        if m["end"] >= model["verdict"]["simulated_duration"]:
            continue  # cut by the end of the run
        if m["kind"] == "movel":
            length = {"pick": 95.0, "place": 90.0, "app_pick": 95.0, "app_place": 90.0}[m["target"]]
            v = m["tvel"]
            if length >= v * v / CART_ACCEL:  # D/v + v/a (accel = decel)
                assert m["duration"] == pytest.approx(length / v + v / CART_ACCEL, abs=1e-6)
                assert m["dominant_limit"] == "tvel"
            else:  # 2·sqrt(D/a)
                assert m["duration"] == pytest.approx(2 * math.sqrt(length / CART_ACCEL), abs=1e-6)
                assert m["dominant_limit"] == "acceleration"
        else:
            # the slowest axis alone sets the time of a synchronised movej
            k = m["start"]
            i0 = round(k / 0.004)
            i1 = round(m["end"] / 0.004)
            pos = model["trajectory"]["positions"]
            times = [max(_trapezoid(abs(pos[j][min(i1 + 1, len(pos[j]) - 1)] - pos[j][max(i0 - 1, 0)]),
                                    robot.nominal_speeds[j] * MDESC["mFast"]["vel"] / 100, robot.accelerations[j])[0]
                         for j in range(6))]
            assert m["duration"] == pytest.approx(max(times), abs=0.01)


def test_synthetic_tcp_speed_reaches_tvel_in_a_long_enough_movel(model):
    tr = model["trajectory"]
    m = next(m for m in model["motions"] if m["kind"] == "movel" and m["dominant_limit"] == "tvel")
    inside = [s for t, s in zip(tr["times"], tr["tcp_speed"]) if m["start"] + 0.2 < t < m["end"] - 0.2]
    assert inside and all(abs(s - m["tvel"]) < 0.01 * m["tvel"] for s in inside)


def test_synthetic_model_is_valid_deterministic_and_fails_on_request(model):
    check_model(model)
    jsonschema.Draft202012Validator.check_schema(SCHEMA)
    jsonschema.Draft202012Validator(SCHEMA).validate(model)
    assert json.dumps(synthetic_model(duration=20.0)) == json.dumps(model)
    assert model["verdict"]["passed"] and model["verdict"]["counts"] == {"error": 0, "warning": 1, "info": 1}
    failing = synthetic_model(duration=30.0, failing=True)
    jsonschema.Draft202012Validator(SCHEMA).validate(failing)
    assert not failing["verdict"]["passed"] and failing["verdict"]["counts"]["error"] == 1
    robot = next(t for t in failing["tasks"] if t["name"] == "robot")
    assert robot["segments"][-1]["state"] == "stopped" and robot["segments"][-1]["end"] == 30.0


# ---- check_model: a clear message with the key at fault --------------------------------------


@pytest.mark.parametrize("edit, message", [
    (lambda m: m.update(version=2), "version: version 1 is expected"),
    (lambda m: m["trajectory"]["positions"][2].pop(), r"trajectory.positions\[2\]: \d+ values"),
    (lambda m: m["trajectory"]["times"].__setitem__(5, -1.0), r"trajectory.times\[5\]: times must not decrease"),
    (lambda m: m["tasks"][0]["segments"][0].update(state="sleeping"), r"tasks\[0\].segments\[0\].state: one of running"),
    (lambda m: m["diagnostics"][0].update(severity="fatal"), r"diagnostics\[0\].severity"),
    (lambda m: m["scene"]["obstacles"][0].update(pose=[[1, 0, 0]]), r"scene.obstacles\[0\].pose: a 3x4 matrix"),
    (lambda m: m["scene"]["obstacles"][4]["triangles"].append([0, 1, 99]), r"scene.obstacles\[4\].triangles\[8\]"),
    (lambda m: m["scene"]["arm"]["joints"].reverse(), r"scene.arm.joints\[0\]: parent link"),
    (lambda m: m["scene"]["obstacles"][0].update(track="fNone"), r"scene.obstacles\[0\].track: 'fNone' is not in"),
    (lambda m: m["scene"].update(tracks={"f": {"times": [0, 1], "poses": [None]}}),
     r"scene.tracks\['f'\]: one pose \(or null\) per time"),
    (lambda m: m["scene"].update(tracks={"f": {"times": [1, 0], "poses": [None, None]}}),
     r"scene.tracks\['f'\].times\[1\]: times must not decrease"),
    (lambda m: m["scene"].update(parts=[{"name": "p", "solids": [], "spans": [
        {"start": 2, "end": 1, "carried": True, "pose": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]}]}]),
     r"scene.parts\[0\].spans\[0\]: end is before start"),
    (lambda m: m["verdict"].update(simulated_duration=float("nan")), "verdict.simulated_duration: a finite number"),
    # the long rows are checked at once (issue 29), the message still names the value at fault
    (lambda m: m["trajectory"]["positions"][1].__setitem__(7, True), r"trajectory.positions\[1\]\[7\]: a finite"),
    (lambda m: m["trajectory"]["velocities"][0].__setitem__(3, float("nan")), r"trajectory.velocities\[0\]\[3\]: a fin"),
    (lambda m: m["trajectory"]["positions"][2].__setitem__(1, 10 ** 400), r"trajectory.positions\[2\]\[1\]: a finite"),
    (lambda m: m["trajectory"].update(tcp_speed=[1.0] * (len(m["trajectory"]["times"]) - 1) + ["x"]),
     r"trajectory.tcp_speed\[\d+\]: a finite number is expected, not 'x'"),
    (lambda m: m.pop("verdict"), "key 'verdict' is missing"),
])
def test_check_model_names_the_key(model, edit, message):
    bad = copy.deepcopy(model)
    edit(bad)
    with pytest.raises(ModelError, match=message):
        render(bad)


# ---- the page's bytes -------------------------------------------------------------------------


def test_page_is_self_contained(page):
    # nothing that a browser would fetch: no src/href other than fragments and the empty data: icon
    refs = re.findall(r"""\b(?:src|href|action|poster|srcset)\s*=\s*["']([^"']*)""", page)
    assert refs and all(r.startswith("#") or r == "data:," for r in refs), refs
    assert not re.search(r"url\(\s*['\"]?(?!#)", page)
    assert "@import" not in page and "<link rel=\"stylesheet\"" not in page
    scripts = re.findall(r"<script(?: [^>]*)?>", page)
    assert scripts == ['<script type="application/json" id="v3-data">', "<script>"]  # one copy of the code
    # the policy allows exactly the inline script and style sheet, and nothing to connect to
    csp = re.search(r'http-equiv="Content-Security-Policy" content="([^"]+)"', page).group(1)
    script = re.search(r"<script>(.*)</script>", page, re.S).group(1)
    style = re.search(r"<style>(.*?)</style>", page, re.S).group(1)

    def sha(text):
        return "sha256-" + base64.b64encode(hashlib.sha256(text.encode()).digest()).decode()

    assert f"script-src '{sha(script)}'" in csp and f"style-src '{sha(style)}'" in csp
    assert csp.startswith("default-src 'none';") and "connect-src" not in csp
    assert ' style="' not in page  # inline style attributes would be refused by the policy


def test_page_is_deterministic_and_small():
    a = render(synthetic_model(duration=60.0))
    b = render(synthetic_model(duration=60.0))
    assert a == b
    size = len(a.encode("utf-8"))
    assert size < 2_500_000, size  # the goal is 5 MB for one minute at 4 ms; it is about 1.4 MB


def test_page_escapes_every_text_from_the_run(model):
    m = copy.deepcopy(model)
    evil = "</script><script>alert(1)</script><!-- & <img src=x onerror=alert(2)>"
    m["diagnostics"][0]["message"] = evil
    m["diagnostics"][0]["excerpt"]["lines"][0] = evil
    m["transcript"][0]["text"] = evil
    m["io"][0]["link"] = evil
    m["title"] = evil
    html = render(m)
    assert "<script>alert(1)" not in html
    assert "<img src=x" not in html
    assert html.count("<script") == 2 and html.count("</script>") == 2
    data = re.search(r'id="v3-data">(.*?)</script>', html, re.S).group(1)
    assert "<" not in data and json.loads(data)["diags"][0]["message"] == evil


def test_page_without_motion_says_so():
    m = synthetic_model(duration=3.0)
    m.update(trajectory=None, motions=[], cycles=[], io=[], transcript=[], arm_timeline=[], tasks=[], diagnostics=[])
    m["scene"] = None
    html = render(m)
    for text in ("No runtime diagnostic.", "No motion in this run.", "No joint trajectory", "No TCP speed",
                 "No task timeline in this report.", "No input or output changed.", "Nothing was written", "No 3D scene"):
        assert text in html
    assert _data(html)["traj"] is None


# ---- packing: full rate up to two minutes, then min/max buckets that keep the peaks ------------


def test_pack_keeps_full_rate_then_buckets_without_losing_peaks(model):
    data = page_data(model)
    assert not data["traj"]["decimated"] and data["traj"]["anim"] is None
    n = len(model["trajectory"]["times"])
    assert len(base64.b64decode(data["traj"]["joints"][0]["pos"]["v"])) == 4 * n

    long = copy.deepcopy(model)
    n = FULL_RATE_MAX * 2 + 7
    tr = long["trajectory"]
    tr["times"] = [k * 0.004 for k in range(n)]
    tr["positions"] = [[math.sin(k / 500 + j) for k in range(n)] for j in range(6)]
    tr["velocities"] = [[0.0] * n for _ in range(6)]
    tr["velocities"][3][12345] = 987.5  # one sample: a peak must survive
    tr["tcp_speed"] = [1.0] * n
    data = page_data(long)["traj"]
    assert data["decimated"] and data["bucket"] == math.ceil(n / PLOT_BUCKETS)
    hi = struct.unpack(f"<{len(base64.b64decode(data['joints'][3]['vel']['hi'])) // 4}f",
                       base64.b64decode(data["joints"][3]["vel"]["hi"]))
    assert len(hi) <= PLOT_BUCKETS and max(hi) == 987.5
    assert len(base64.b64decode(data["anim"]["t"])) == 8 * len(hi)


def test_demo_command_writes_a_page_and_refuses_a_bad_model(tmp_path, capsys):
    from val3check.cli import main as cli_main

    out = tmp_path / "demo.html"
    (tmp_path / "model.json").write_text(json.dumps(synthetic_model(duration=5.0)))
    assert cli_main(["html", str(tmp_path / "model.json"), "-o", str(out), "--model-out", str(tmp_path / "m.json")]) == 0
    assert out.read_text(encoding="utf-8").startswith("<!DOCTYPE html>")
    assert cli_main(["html", str(tmp_path / "m.json"), "-o", str(tmp_path / "again.html")]) == 0
    assert (tmp_path / "again.html").read_bytes() == out.read_bytes()
    (tmp_path / "bad.json").write_text('{"version": 1}')
    assert cli_main(["html", str(tmp_path / "bad.json"), "-o", str(tmp_path / "x.html")]) == 2
    assert "key 'application' is missing" in capsys.readouterr().err
    assert not (tmp_path / "x.html").exists()


def test_pose_helpers_agree(model):
    # the tool's TCP composed on the flange is what the synthetic run measured as TCP speed
    arm, tool = model["scene"]["arm"], model["scene"]["tool"]
    q = [model["trajectory"]["positions"][j][400] for j in range(6)]
    T = mul(chain_fk(arm, q)["flange"], tuple(tuple(r) for r in tool["tcp"]))
    F = load_robot("tx2-60").fk_matrix(q, (0, 0, 120, 0, 0, 0))
    assert max(abs(T[i][3] - F[i][3]) for i in range(3)) < 1e-6


def test_the_verdict_names_the_cycle_s_task_once(model):
    # the basis of a run's cycle names its task ("... of task robot (the while loop ...)"): the
    # verdict adds "(task robot)" only when it does not; the range follows the cycle time
    m = copy.deepcopy(model)
    m["verdict"]["cycle_time"] = {"seconds": 2.757, "task": "robot", "range": [2.564, 3.107], "off_by": 2,
                                  "basis": "median of 3 complete cycles of task robot (the while loop at line 9)"}
    html = render(m)
    assert "of task robot (the while loop at line 9)</span>" in html and "(task robot)" not in html
    assert "2.757 s</b> (2.564–3.107 s if the assumed accelerations are off by 2×)" in html
    m["verdict"]["cycle_time"]["basis"] = "mean of 3 complete iterations of the loop at line 9"
    assert "line 9 (task robot)</span>" in render(m)
