"""The controller's state of chapter 8 (power, working mode, emergency stop, monitor speed,
profiles, language, date, versions), set by the scenario's `[controller]` table
(docs/scenario.md) and read and changed by the instructions of chapters 4 and 8."""

from __future__ import annotations

import datetime
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
    versions: dict[str, str] = field(default_factory=lambda: {"VAL 3": "s7.11 - val3check simulator"})
