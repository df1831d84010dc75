"""The numbers a scenario may hold (docs/scenario.md): finite values and times in seconds, shared
by the scenario's reader (scenario.py) and its chapter 11 tables (scenario_options.py)."""

from __future__ import annotations

import math
from typing import Any

MAX_SECONDS = 1e7  # a time, duration or delay (about 115 days): more is a mistake


def finite(v: Any) -> bool:
    """A TOML number val3check can compute with: not a bool, not nan or inf."""
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and abs(v) <= 1e300


def seconds(v: Any) -> int | None:
    """Microseconds from a number of seconds in [0, MAX_SECONDS]; None for anything else
    (nan, inf, negative, not a number)."""
    if not finite(v) or not 0 <= v <= MAX_SECONDS:
        return None
    return round(v * 1_000_000)
