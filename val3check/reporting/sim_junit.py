"""`val3check sim --report junit`: a run as JUnit XML for the test tabs of CI systems.

One `<testcase>` per application and scenario run (classname = the application's path, name =
"sim APP" and the scenario's file when there is one). It fails when the run raised diagnostics at
or above `--fail-on`: one `<failure>` whose text lists each of them with file, line, column,
simulated time and task (so that the exit code 1 and the failed test say the same). The
diagnostics below `--fail-on` are in its `<system-out>`. `<properties>` carry how the run ended,
the simulated duration and the cycle time. Deterministic: no wall-clock value (`time` is 0).
"""

from __future__ import annotations

import statistics
import xml.etree.ElementTree as ET
from typing import Any

from ..diagnostics import Severity
from ._common import TOOL_NAME
from .junit import document, testcase, xml_text


def _line(d) -> str:
    where = d.path
    if d.line:
        where += f":{d.line}" + (f":{d.col}" if d.col else "")
    when = f" (at {d.time_us / 1e6:.3f} s" + (f", task {d.task}" if d.task else "") + ")" if d.time_us is not None else ""
    return f"{where}: {d.code} [{d.severity.label}] {d.message}{when}"


def _cycle_time(result: Any) -> str | None:
    m = result.motion
    if m is None:
        return None
    from ..simulation.arm_record import main_cycle

    best = main_cycle(m.cycles)
    return None if best is None else f"{statistics.median(best.times):.6f}"


def case(report: Any, fail_on: str, scenario: str | None = None) -> tuple[ET.Element, bool]:
    """The test case of one run (`report`: a SimReport) and whether it failed."""
    r = report.result
    name = f"sim {r.application}" + (f" with {scenario}" if scenario else "")
    el = testcase(report.app_path, name, file=report.app_path)
    props = ET.SubElement(el, "properties")
    values = [("end_reason", r.end_reason), ("simulated_duration_s", f"{r.sim_time_us / 1e6:.6f}"),
              ("robot", (r.robot or {}).get("name", "none")), ("cycle_time_s", _cycle_time(r)),
              ("scenario", scenario)]
    for k, v in values:
        if v is not None:
            ET.SubElement(props, "property", {"name": k, "value": xml_text(str(v))})
    threshold = None if fail_on == "never" else Severity.parse(fail_on)
    failing = [d for d in report.diagnostics if threshold is not None and d.severity >= threshold]
    ids = {id(d) for d in failing}
    lower = [d for d in report.diagnostics if id(d) not in ids]
    if failing:
        f = ET.SubElement(el, "failure", {
            "message": xml_text(f"{len(failing)} runtime diagnostic(s) at or above {fail_on}: "
                            f"{failing[0].code} {failing[0].message}"),
            "type": xml_text(failing[0].code)})
        f.text = xml_text("\n".join(_line(d) for d in failing))
    if lower:
        out = ET.SubElement(el, "system-out")
        out.text = xml_text("\n".join(_line(d) for d in lower))
    return el, bool(failing)


def render_runs(runs: list[tuple[Any, str | None]], fail_on: str = "error") -> str:
    """JUnit XML of several runs: [(SimReport, scenario path or None)]."""
    cases, failures = [], 0
    for report, scenario in runs:
        el, failed = case(report, fail_on, scenario)
        cases.append(el)
        failures += failed
    counts = {"tests": str(len(cases)), "failures": str(failures), "errors": "0", "skipped": "0", "time": "0"}
    return document(f"{TOOL_NAME} sim", cases, counts)


def render(report: Any, *, fail_on: str = "error", scenario: str | None = None) -> str:
    """`val3check sim --report junit`: one run."""
    return render_runs([(report, scenario)], fail_on)
