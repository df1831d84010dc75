"""The motion descriptor (10.5) and the limits it gives a motion (10.3).

`MDesc` holds the fields in millimetres (the caller converts an application in inches,
2.1.4.1). `check()` gives the runtime error of 12.1 (100-106) a motion instruction raises on
invalid fields; `Limits` is what the time parameterisation obeys.
"""

from __future__ import annotations

import math

import numpy as np

from ..language.types import load_types
from ..light_dataclass import dataclass

BLENDS = ("off", "joint", "Cartesian")
# The fields' defaults: language/types.toml, the one source of the type facts (10.5.1: the
# manual's {100, 100, 100, 9999, 9999, joint, 50, 50}).
DEFAULTS = {f.name: f.default for f in load_types()["mdesc"].fields}


@dataclass(frozen=True)
class MDesc:
    """10.5.1 mdesc: accel, vel, decel in % of nominal; tvel mm/s; rvel deg/s; blend; leave and
    reach in mm; each field's default from language/types.toml (DEFAULTS)."""

    accel: float = float(DEFAULTS["accel"])
    vel: float = float(DEFAULTS["vel"])
    decel: float = float(DEFAULTS["decel"])
    tvel: float = float(DEFAULTS["tvel"])
    rvel: float = float(DEFAULTS["rvel"])
    blend: str = str(DEFAULTS["blend"])
    leave: float = float(DEFAULTS["leave"])
    reach: float = float(DEFAULTS["reach"])

    @classmethod
    def from_fields(cls, fields: dict, mm_per_unit: float = 1.0) -> "MDesc":
        """From the interpreter's dict {accel, vel, decel, tvel, rvel, blend, leave, reach};
        tvel, leave and reach in the application's length unit (mm_per_unit converts)."""
        d = DEFAULTS
        blend = str(fields.get("blend", d["blend"]))
        low = blend.lower()
        blend = "Cartesian" if low == "cartesian" else low
        return cls(float(fields.get("accel", d["accel"])), float(fields.get("vel", d["vel"])),
                   float(fields.get("decel", d["decel"])), float(fields.get("tvel", d["tvel"])) * mm_per_unit,
                   float(fields.get("rvel", d["rvel"])), blend, float(fields.get("leave", d["leave"])) * mm_per_unit,
                   float(fields.get("reach", d["reach"])) * mm_per_unit)

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
        """The command blends into the next one (blend joint or Cartesian)."""
        return self.blend != "off"

    @property
    def tvel_limit(self) -> float | None:
        """tvel (mm/s), or None at or above its default: no limit on the TCP's speed (10.5.1)."""
        return self.tvel if self.tvel < float(DEFAULTS["tvel"]) else None

    @property
    def rvel_limit(self) -> float | None:
        """rvel (deg/s), or None at or above its default: no limit on the tool's rotation speed."""
        return self.rvel if self.rvel < float(DEFAULTS["rvel"]) else None


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
        return cls.of(kin, MDesc(accel=10.0, vel=10.0, decel=10.0, tvel=250.0), monitor)


class CommandLimits:
    """The limits of every command of a motion queue at the monitor speed (docs/motion.md: every
    limit scales with it), by command key, computed once per monitor speed."""

    def __init__(self, kin, monitor: float) -> None:
        """`kin`: the arm's kin.ArmKin (nominal speeds and accelerations); `monitor` in %."""
        self.kin = kin
        self.monitor = float(monitor)
        self._asked: dict[int, tuple[MDesc, bool]] = {}
        # by what was asked, not by command: a long run asks the same few mdescs again and again
        self._same: dict[tuple[MDesc, bool], tuple[MDesc, bool]] = {}
        self._limits: dict[int, Limits] = {}  # by id of the tuple `_same` keeps (never dropped)
        self._objects: dict[tuple[int, bool], tuple] = {}  # (id(mdesc), reduced) -> (mdesc, kept tuple)
        # trial_memo.TrialMemo's values of a command's limits, by command key: valid while `of(key)`
        # gives the same Limits (cleared with `_limits`; a cache: dropping it only costs a recompute)
        self.value_keys: dict[int, tuple] = {}

    def register(self, key: int, mdesc: MDesc, reduced: bool) -> tuple:
        """A command's mdesc (`reduced`: a connection move, 10.1.3); returns the one (mdesc, reduced)
        tuple kept for these values (never dropped: its id names them, queue.MotionQueue._class_of)."""
        # by the object first (hashing an MDesc is a Python call): a run shares its few mdescs
        by = self._objects.get((id(mdesc), reduced))
        if by is not None and by[0] is mdesc:
            asked = by[1]
        else:
            asked = (mdesc, reduced)
            asked = self._same.setdefault(asked, asked)
            if len(self._objects) >= 64:
                self._objects.clear()
            self._objects[(id(mdesc), reduced)] = (mdesc, asked)  # (holds mdesc: its id stays its own)
        self._asked[key] = asked
        self.value_keys.pop(key, None)
        return asked

    def of(self, key: int) -> Limits:
        """The limits of the command `key` at the current monitor speed."""
        asked = self._asked[key]
        # by the id of the one tuple `_same` keeps for these values (hashing an MDesc costs more)
        lim = self._limits.get(id(asked))
        if lim is None:
            mdesc, reduced = asked
            m = self.monitor / 100.0
            lim = Limits.reduced(self.kin, m) if reduced else Limits.of(self.kin, mdesc, m)
            self._limits[id(asked)] = lim
        return lim

    def set_monitor(self, monitor: float) -> None:
        """Another monitor speed (above 0, in %): every limit scales with it."""
        self.monitor = float(monitor)
        self._limits.clear()
        self.value_keys.clear()
