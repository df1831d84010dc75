"""What controllers answer (8.1 getVersion, 3.7.3 sioCtrl): the names and values public code that
runs on controllers expects, overridable in the scenario."""

from __future__ import annotations

import re

import pytest

from val3check.interpretation.controller import default_versions

from .simsupport import build, gv, run_folder, sim

# The check public code does to choose between its CS8 and its CS9 code (written here, after the
# ROS-Industrial driver's start(): mid(getVersion("System"), 1, 1) is the major version).
BRANCH = """begin
  if mid(getVersion("System"), 1, 1) == "7"
    sBranch = "CS8"
  elseIf mid(getVersion("System"), 1, 1) == "8"
    sBranch = "CS9"
  endIf
  sMajor = mid(getVersion("VAL3"), 1, 1)
  toNum(sMajor, nMajor, bOk)
  sManual = getVersion("VAL 3")
  sLicence = getVersion("compliance")
end
"""
GLOBALS = ["string sBranch", "string sMajor", "num nMajor", "bool bOk", "string sManual", "string sLicence"]


def _with_version(folder, version):
    pjx = next(folder.glob("*.pjx"))
    text = pjx.read_text(encoding="utf-8")
    pjx.write_text(re.sub(r'<Parameters version="[^"]*"', f'<Parameters version="{version}"', text), encoding="utf-8")


@pytest.mark.parametrize("version,branch,major", [("s7.11", "CS8", 7), ("s8.13.1Cs9_BS2800", "CS9", 8),
                                                  ("s7.0.1Cs9", "CS9", 8)])
def test_public_code_takes_the_branch_of_the_controller_that_saved_it(tmp_path, version, branch, major):
    folder = build(tmp_path, BRANCH, globals_=GLOBALS)
    _with_version(folder, version)
    r = run_folder(folder)
    assert gv(r, "sBranch") == branch and gv(r, "nMajor") == major and gv(r, "bOk") is True
    assert gv(r, "sManual").startswith(f"s{major}")  # 8.1: "s7.0 - Jun 18 2010 - 16:01:17"
    assert gv(r, "sLicence") == ""  # 8.1: "" for a licence not installed


def test_the_scenario_overrides_what_getversion_answers(tmp_path):
    r = sim(tmp_path, BRANCH, globals_=GLOBALS,
            scenario='[controller]\nversions = { System = "s8.20.5", compliance = "enabled" }\n')
    assert gv(r, "sBranch") == "CS9" and gv(r, "sLicence") == "enabled"


def test_arm_type_is_the_arm_model():
    assert default_versions("s7.11", "TX2-60")["ArmType"] == "tx2-60"
    assert "ArmType" not in default_versions("s7.11", None)
    assert default_versions(None, None)["System"] == "s7.11"


@pytest.mark.parametrize("value,code", [("-1", 0), ("0", 0), ("2.5", 0)])
def test_sioctrl_timeout_minus_one_is_no_limit(tmp_path, value, code):
    """3.7.3 "timeout": 0 is no limit; -1 is what the pendant's socket configuration and public
    drivers write for no limit: accepted (0), and sioGet waits for data without a time limit."""
    r = sim(tmp_path, f"""begin
  nR = sioCtrl(siSock, "timeout", {value})
  nGot = sioGet(siSock, nBuf)
end
""", globals_=["sio siSock", "num nR", "num nGot", "num nBuf"], links={"siSock": "Socket\\Motion"},
            scenario='[[serial]]\nsio = "siSock"\nat = 4.0\nbytes = [9]\n', duration=6)
    assert gv(r, "nR") == code
    limited = value == "2.5"
    assert gv(r, "nGot") == (-1 if limited else 1)  # 2.5 s: the timeout comes before the data


def test_sioctrl_port_out_of_range_is_not_supported(tmp_path):
    r = sim(tmp_path, 'begin\n  nR = sioCtrl(siSock, "port", 70000)\n  nS = sioCtrl(siSock, "port", 11000)\nend',
            globals_=["sio siSock", "num nR", "num nS"], links={"siSock": "Socket\\Motion"})
    assert gv(r, "nR") == -3 and gv(r, "nS") == 0
