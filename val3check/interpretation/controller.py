"""The controller's state of chapter 8 (power, working mode, emergency stop, monitor speed,
profiles, language, date, versions), set by the scenario's `[controller]` table
(docs/scenario.md) and read and changed by the instructions of chapters 4 and 8."""

from __future__ import annotations

import datetime
import re
from dataclasses import dataclass, field


@dataclass
class Controller:
    working_mode: int = 4  # remote (8.1 workingMode)
    working_state: int = 0
    es_status: int = 0
    powered: bool = True  # the arm is powered at the start, as the operator at the pendant has it (issue 12)
    power_delay_us: int = 500_000  # enablePower(): the power comes on this much later
    calibrated: bool = True
    monitor_speed: float = 100.0
    operator_speed: bool = False
    safety_fault: str = ""
    profile: str = "default"
    profiles: dict[str, str] = field(default_factory=dict)
    language: str = "english"
    languages: tuple[str, ...] = ("francais", "english", "deutsch", "italiano", "espanol")
    date: datetime.datetime = field(default_factory=lambda: datetime.datetime(2000, 1, 1, 0, 0, 0))
    versions: dict[str, str] = field(default_factory=lambda: default_versions(None, None))


# 8.1 getVersion(sComposant): "VAL 3" is the manual's name, "VAL3" and "System" the names public code
# that runs on controllers asks for (the ROS-Industrial driver staubli_val3_driver takes its CS8
# branch when mid(getVersion("System"), 1, 1) == "7", its CS9 branch on "8", and reads the minor
# version from getVersion("VAL3")). A release is written as the manual's example, "s7.0 - Jun 18
# 2010 - 16:01:17": the letter s, the version, then the build.
DEFAULT_RELEASE = "s7.11"
_RELEASE = re.compile(r"\s*(s\d+(?:\.\d+)*)", re.IGNORECASE)


def default_versions(project_version: str | None, arm_name: str | None) -> dict[str, str]:
    """What getVersion answers when the scenario does not say: the release of the controller that
    saved the application (its project file's version: "s8.13.1Cs9_BS2800" -> "s8.13.1"; a CS9
    project saved as s7 runs on an s8 controller), the arm model's name for "ArmType"; any other
    component (serial numbers, licences: "" is a licence not installed, 8.1) is ""."""
    m = _RELEASE.match(project_version or "")
    release = m.group(1).lower() if m else DEFAULT_RELEASE
    if "cs9" in (project_version or "").lower() and not release.startswith("s8"):
        release = "s8"
    versions = {"VAL 3": f"{release} - val3check simulator", "VAL3": f"{release} - val3check simulator",
                "System": release}
    if arm_name:
        versions["ArmType"] = arm_name.lower()
    return versions
