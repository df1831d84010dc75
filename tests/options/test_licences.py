"""11.3 getLicence and the runtime licences of chapter 11's options: from the scenario's
[options] (docs/scenario.md); without it everything is licensed, said once (R050)."""

from __future__ import annotations

import pytest
from interpretation.simsupport import codes, gv, sim

PROGRAM = """begin
  sA = getLicence("CellA", "pwA")
  sB = getLicence("CellB", "wrong")
  sC = getLicence("CellC", "any")
  sD = getLicence("Unknown", "x")
end
"""
GLOBALS = ["string sA", "string sB", "string sC", "string sD"]


def test_without_a_scenario_every_oem_licence_is_enabled_said_once(tmp_path):
    r = sim(tmp_path, PROGRAM, globals_=GLOBALS)
    assert codes(r) == ["R050"]
    assert [gv(r, n) for n in ("sA", "sB", "sC", "sD")] == ["enabled"] * 4


def test_the_scenario_gives_the_states_and_checks_the_passwords(tmp_path):
    r = sim(tmp_path, PROGRAM, globals_=GLOBALS, scenario="""version = 1
[options]
oemLicence = true
oem = { CellA = { state = "enabled", password = "pwA" }, CellB = { state = "demo", password = "pwB" }, CellC = "demo" }
""")
    assert codes(r) == []
    assert [gv(r, n) for n in ("sA", "sB", "sC", "sD")] == ["enabled", "", "demo", ""]


def test_without_the_oem_runtime_licence(tmp_path):
    r = sim(tmp_path, PROGRAM, globals_=GLOBALS, scenario="version = 1\n[options]\noemLicence = false\n")
    assert codes(r) == []
    assert [gv(r, n) for n in ("sA", "sB", "sC", "sD")] == ["oemLicenceDisabled"] * 4


@pytest.mark.parametrize("text,line", [
    ("[options]\nalter = 1\n", 3),
    ("[options]\nturbo = true\n", 3),
    ("[options]\noem = { A = \"maybe\" }\n", 3),
    ("[options]\noem = { A = { state = \"demo\", pin = 3 } }\n", 3),
])
def test_a_bad_options_table_is_a_scenario_error_with_its_line(tmp_path, text, line):
    from val3check.simulation.scenario import ScenarioError

    with pytest.raises(ScenarioError) as exc:
        sim(tmp_path, PROGRAM, globals_=GLOBALS, scenario="version = 1\n" + text)
    assert exc.value.line == line
