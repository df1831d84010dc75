"""The motion descriptor (10.5) and the limits it gives a motion (10.3).

`MDesc` holds the fields in millimetres (the caller converts an application in inches,
2.1.4.1). `check()` gives the runtime error of 12.1 (100-106) a motion instruction raises on
invalid fields; `Limits` is what the time parameterisation obeys.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

BLENDS = ("off", "joint", "Cartesian")


@dataclass(frozen=True)
class MDesc:
    """10.5.1 mdesc: accel, vel, decel in % of nominal; tvel mm/s; rvel deg/s; blend; leave and
    reach in mm. The defaults are the manual's {100, 100, 100, 9999, 9999, joint, 50, 50}."""

    accel: float = 100.0
    vel: float = 100.0
    decel: float = 100.0
    tvel: float = 9999.0
    rvel: float = 9999.0
    blend: str = "joint"
    leave: float = 50.0
    reach: float = 50.0

    @classmethod
    def from_fields(cls, fields: dict, mm_per_unit: float = 1.0) -> "MDesc":
        """From the interpreter's dict {accel, vel, decel, tvel, rvel, blend, leave, reach};
        tvel, leave and reach in the application's length unit (mm_per_unit converts)."""
        blend = str(fields.get("blend", "joint"))
        low = blend.lower()
        blend = "Cartesian" if low == "cartesian" else low
        return cls(float(fields.get("accel", 100.0)), float(fields.get("vel", 100.0)),
                   float(fields.get("decel", 100.0)), float(fields.get("tvel", 9999.0)) * mm_per_unit,
                   float(fields.get("rvel", 9999.0)), blend, float(fields.get("leave", 50.0)) * mm_per_unit,
                   float(fields.get("reach", 50.0)) * mm_per_unit)

    def check(self) -> tuple[int, str] | None:
        """(code, message) of the first invalid field (12.1: 100-106), or None.

        The manual says "negative or too large" without a figure for "too large": val3check
        rejects negative values, zero speeds and accelerations (the arm could never move) and
        values that are not finite numbers, and sets no upper bound (docs/motion.md)."""
        for code, name, value in ((100, "vel", self.vel), (101, "accel", self.accel), (102, "decel", self.decel),
                                  (103, "tvel", self.tvel), (104, "rvel", self.rvel)):
            if not math.isfinite(value) or value <= 0.0:
                what = "negative" if value < 0 else "zero" if value == 0 else "not a finite number"
                return code, f"mdesc.{name} = {value:g} is invalid ({what})"
        for code, name, value in ((105, "reach", self.reach), (106, "leave", self.leave)):
            if not math.isfinite(value) or value < 0.0:
                what = "negative" if value < 0 else "not a finite number"
                return code, f"mdesc.{name} = {value:g} is invalid ({what})"
        if self.blend not in BLENDS:
            return 154, f"mdesc.blend = {self.blend!r} is not off, joint or Cartesian"
        return None

    @property
    def blended(self) -> bool:
        return self.blend != "off"


@dataclass(frozen=True)
class Limits:
    """What a motion obeys (10.3.1): per axis speed V, acceleration A (path speed increasing)
    and deceleration D (decreasing), deg/s and deg/s²; TCP speed tvel (mm/s) and tool rotation
    speed rvel (deg/s). Every figure already includes the monitor speed."""

    V: np.ndarray
    A: np.ndarray
    D: np.ndarray
    tvel: float
    rvel: float

    @classmethod
    def of(cls, kin, md: MDesc, monitor: float) -> "Limits":
        """Nominal figures of the arm times the mdesc percentages, times the monitor speed
        (0..1): every limit scales with it (docs/motion.md)."""
        m = monitor
        return cls(kin.speeds * (md.vel / 100.0 * m), kin.accels * (md.accel / 100.0 * m),
                   kin.accels * (md.decel / 100.0 * m), md.tvel * m, md.rvel * m)

    @classmethod
    def reduced(cls, kin, monitor: float) -> "Limits":
        """The reduced speed of a connection move (10.1.3): 10 % of the nominal joint speeds and
        accelerations, 250 mm/s at the flange."""
        return cls.of(kin, MDesc(accel=10.0, vel=10.0, decel=10.0, tvel=250.0, rvel=9999.0), monitor)
