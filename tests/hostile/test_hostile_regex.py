"""Issue 21 C and D: no regular expression that runs on a file's content takes super-linear time.

Each input below is one the replaced pattern took minutes on (quadratic backtracking, in C code
that `--max-wall` cannot stop): a scenario line of 300 KB (75 s), a fatherId of 150 KB (17 s
per 150 KB), an arm.cfx arm id of 180 KB (97 s), a data file's number of 150 KB, a pyproject.toml
of newlines. The tests assert the outcome on those sizes; the
short inputs check the new code against the pattern it replaced (same answers)."""

from __future__ import annotations

import random
import re

import pytest
from interpretation.simsupport import sim

from val3check.testing import write_app

# ---- C: the scenario's positions --------------------------------------------------------------------

def test_a_300_kb_line_in_a_scenario_is_read_and_errors_keep_their_line(tmp_path):
    scenario = 'description = """\n[a' + " " * 300_000 + 'b\n"""\n[inputs]\nnope = true\n'
    from val3check.simulation.scenario import ScenarioError

    with pytest.raises(ScenarioError) as e:
        sim(tmp_path, "begin\nend\n", scenario=scenario, duration=0.1)
    assert e.value.line == 5 and "unknown signal 'nope'" in e.value.message


def test_scenario_errors_point_at_the_key_at_fault(tmp_path):
    from val3check.simulation.scenario import ScenarioError

    scenario = ('[[events]]\nat = 1\nset = { }\n\n[[events]]\nat = 2\n\n[[events]]\n# at comes later\n'
                'set = {}\nat = -1\n')
    with pytest.raises(ScenarioError) as e:
        sim(tmp_path, "begin\nend\n", scenario=scenario, duration=0.1)
    assert e.value.line == 11 and "[[events]] needs at" in e.value.message
    with pytest.raises(ScenarioError) as e:  # inline tables have positions too
        sim(tmp_path / "b", "begin\nend\n", scenario='events = [{ at = 1 },\n  { at = "x" }]\n', duration=0.1)
    assert e.value.line == 2


# ---- D: VAL 3 data files --------------------------------------------------------------------------

_OLD_FATHER = re.compile(r"^\s*([A-Za-z_]\w*)\s*(?:\[\s*([^\]]*?)\s*\])?\s*$")
_OLD_NUM = re.compile(r"^\s*[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?\s*$")


def test_parse_father_and_parse_num_answer_as_the_patterns_they_replace():
    from val3check.loading.attribute_text import _NUM, parse_father

    rng = random.Random(21)
    alphabet = list("ab_1 [ ]\t\n,é\".-+eE0")
    for _ in range(5_000):
        s = "".join(rng.choice(alphabet) for _ in range(rng.randint(0, 12)))
        m = _OLD_FATHER.match(s)
        assert parse_father(s) == ((m.group(1), m.group(2)) if m else None), s
        assert bool(_NUM.match(s)) == bool(_OLD_NUM.match(s)), s


def test_a_150_kb_fatherid_and_number_are_linted(tmp_path):
    folder = write_app(tmp_path, "begin\nend\n", globals_=["frame fA"])
    dtx = folder / "Example.dtx"
    text = dtx.read_text()
    text = re.sub(r'(<Data name="fA" [^>]*?) />', lambda m: m.group(1) + '><Value key="0" x="' + "1" * 150_000
                  + 'x" fatherId="world[x' + " " * 150_000 + 'y" /></Data>', text)
    dtx.write_text(text)
    from val3check.config import Settings
    from val3check.lint import run

    found = run([str(folder)], Settings()).result.diagnostics
    messages = " ".join(d.message for d in found)
    assert "fatherId 'world[x" in messages and "is not a reference" in messages
    assert "is not a number" in messages
    assert all(len(d.message) < 1000 for d in found)  # the values are quoted short


# ---- D: arm.cfx -------------------------------------------------------------------------------------

def test_arm_ids_are_normalised_as_before_and_in_linear_time():
    from val3check.robot.catalog import normalize_id

    old = re.compile(r"^(.+?)-s\d+[-a-z0-9]*$")

    def before(a):
        n = a.strip().lower().replace("_", "-")
        m = old.match(n)
        return m.group(1) if m else n

    rng = random.Random(3)
    for _ in range(5_000):
        s = "".join(rng.choice("-s1a_S2 .x!") for _ in range(rng.randint(0, 10)))
        assert normalize_id(s) == before(s), s
    assert normalize_id("tx2-60-S1") == "tx2-60" and normalize_id("ts2_60-S1") == "ts2-60"
    assert normalize_id("-s1" * 60_000 + ".") == "-s1" * 60_000 + "."  # 97 s before
    assert normalize_id("-s1" * 60_000) == "-s1"


def test_a_180_kb_arm_id_is_refused_and_quoted_short(tmp_path):
    from val3check.robot import RobotError
    from val3check.robot.identify import from_arm_cfx

    cfx = tmp_path / "arm.cfx"
    cfx.write_text('<?xml version="1.0"?><Configuration><Arm><String name="arm" value="' + "-s1" * 60_000
                   + '." /><String name="lengthAxis3" value="L' + " " * 100_000 + 'x" /></Arm></Configuration>')
    with pytest.raises(RobotError) as e:
        from_arm_cfx(cfx)
    assert "(180001 characters)" in str(e.value) and len(str(e.value)) < 1000


def test_stroke_lengths():
    from val3check.robot.identify import ArmConfig

    for text, mm in [("L200", 200.0), (" l 200.5 mm ", 200.5), ("200mm", 200.0), ("L", None), ("Lmm", None),
                     ("L200x", None), (" " * 200_000 + "x", None), ("L" + " " * 200_000 + "1x", None)]:
        assert ArmConfig("p", "a", None, text).stroke_mm == mm, text


# ---- D: configuration files --------------------------------------------------------------

def test_a_pyproject_of_blank_lines_is_probed_in_linear_time(tmp_path):
    from val3check.config import _TOOL_SECTION, find_config

    assert not _TOOL_SECTION.search(b"\n" * 300_000)  # quadratic before: every line start ran to the end
    assert _TOOL_SECTION.search(b"x = 1\n  [ tool ]  \n") and _TOOL_SECTION.search(b"[tool.val3check]\n")
    (tmp_path / "pyproject.toml").write_text("\n" * 300_000)
    assert find_config(str(tmp_path)) is None
