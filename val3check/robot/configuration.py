"""Arm configurations of Stäubli RX/TX arms (manual 9.7.4) and the requested-configuration filter.

  shoulder  righty  when d1·sin(j2) + d2·sin(j2+j3) + δ < 0, lefty when it is >= 0, where d1 is
                    the arm length (c2, axis 2 to axis 3), d2 the forearm length (c3, axis 3 to
                    the wrist centre) and δ the distance between axis 1 and axis 2 along x (a1).
  elbow     epositive when j3 >= 0, enegative when j3 < 0
  wrist     wpositive when j5 >= 0, wnegative when j5 < 0

The shoulder quantity is the forward distance of the wrist centre from axis 1 in the arm's plane;
the two shoulder branches of the inverse kinematics are exactly its two signs. For an arm with a
forearm offset (a2 ≠ 0, none of Stäubli's), the same distance adds a2·cos(j2+j3).

A requested configuration (the `config` field of a VAL 3 point) holds, per field, a value, `same`
(ssame/esame/wsame: the configuration of the initial position) or `free` (sfree/efree/wfree: any).

RS/TS (SCARA) arms, 9.7.2 and 9.7.5: the config has the shoulder field only, righty when
sin(j2) > 0, lefty when sin(j2) <= 0 (scara.classify). `Config.parse(spec, scara=True)` takes
("righty",) or "lefty"; three fields are accepted only when elbow and wrist are `same` or `free`
(what an interpreter that always builds three fields gives), never with a value such as
epositive: an RS/TS arm has no elbow or wrist configuration.
"""

from __future__ import annotations

import math

from ..geometry.config_values import CONCRETE
from ..light_dataclass import dataclass
from .errors import RobotError

DEG = math.pi / 180.0

SHOULDER = CONCRETE["shoulder"]  # ("righty", "lefty")
ELBOW = CONCRETE["elbow"]  # ("epositive", "enegative")
WRIST = CONCRETE["wrist"]  # ("wpositive", "wnegative")
_FIELDS = (("shoulder", "s", SHOULDER), ("elbow", "e", ELBOW), ("wrist", "w", WRIST))


@dataclass(frozen=True)
class Config:
    """A requested configuration: each field a value, "same" or "free" (VAL 3 names also accepted)."""

    shoulder: str = "free"
    elbow: str = "free"
    wrist: str = "free"

    @classmethod
    def parse(cls, spec, scara: bool = False) -> "Config":
        if spec is None:
            return FREE
        if isinstance(spec, Config):
            if scara and (spec.elbow not in ("same", "free") or spec.wrist not in ("same", "free")):
                raise RobotError(_NO_ELBOW_WRIST.format(f"{spec.elbow}, {spec.wrist}"))
            return cls(spec.shoulder) if scara else spec
        if isinstance(spec, str):
            spec = spec.replace(",", " ").split()
        spec = tuple(spec)
        if scara:
            if len(spec) == 1:
                return cls.parse((spec[0], "efree", "wfree"))
            if len(spec) == 3:
                rest = [str(v).strip().lower() for v in spec[1:]]
                if any(v not in ("esame", "efree", "wsame", "wfree", "same", "free") for v in rest):
                    raise RobotError(_NO_ELBOW_WRIST.format(", ".join(str(v) for v in spec[1:])))
                return cls.parse((spec[0], "efree", "wfree"))
            raise RobotError(f"an RS/TS (SCARA) configuration has one field (shoulder), not {len(spec)}: {spec!r}")
        if len(spec) != 3:
            raise RobotError(f"a configuration has three fields (shoulder, elbow, wrist), not {len(spec)}: {spec!r}")
        vals = []
        for value, (fname, prefix, allowed) in zip(spec, _FIELDS):
            v = str(value).strip().lower()
            if v in (prefix + "same", "same"):
                v = "same"
            elif v in (prefix + "free", "free"):
                v = "free"
            elif v not in allowed:
                raise RobotError(
                    f"bad {fname} configuration {value!r}: one of {', '.join(allowed)}, {prefix}same, {prefix}free"
                )
            vals.append(v)
        return cls(*vals)

    def val3(self) -> tuple[str, str, str]:
        """The VAL 3 constant names (ssame, efree, ...)."""
        return tuple(
            (prefix + v) if v in ("same", "free") else v for v, (_, prefix, _) in zip((self.shoulder, self.elbow, self.wrist), _FIELDS)
        )  # type: ignore[return-value]


FREE = Config()
_NO_ELBOW_WRIST = ("an RS/TS (SCARA) arm has no elbow or wrist configuration (manual 9.7.2: its config is the "
                   "shoulder field only), but the configuration asks for {}")


def shoulder_value(j2_deg: float, j3_deg: float, d1: float, d2: float, delta: float, a2: float = 0.0) -> float:
    """d1·sin(j2) + d2·sin(j2+j3) + δ (+ a2·cos(j2+j3)), in millimetres (9.7.4.1)."""
    t2 = j2_deg * DEG
    t23 = (j2_deg + j3_deg) * DEG
    v = d1 * math.sin(t2) + d2 * math.sin(t23) + delta
    if a2:
        v += a2 * math.cos(t23)
    return v


def classify(j2_deg: float, j3_deg: float, j5_deg: float, d1: float, d2: float, delta: float, a2: float = 0.0):
    """(shoulder, elbow, wrist) of a joint position, by the formulas of 9.7.4."""
    shoulder = "righty" if shoulder_value(j2_deg, j3_deg, d1, d2, delta, a2) < 0 else "lefty"
    elbow = "epositive" if j3_deg >= 0 else "enegative"
    wrist = "wpositive" if j5_deg >= 0 else "wnegative"
    return shoulder, elbow, wrist


def resolve(requested: Config, same_from_config: tuple[str, str, str] | None) -> tuple[str | None, str | None, str | None]:
    """Per field: the required value, or None when free. `same` takes the initial configuration."""
    out = []
    for i, v in enumerate((requested.shoulder, requested.elbow, requested.wrist)):
        if v == "free":
            out.append(None)
        elif v == "same":
            if same_from_config is None:
                raise RobotError("a 'same' configuration needs the initial joint position (same_from or near)")
            out.append(same_from_config[i])
        else:
            out.append(v)
    return tuple(out)  # type: ignore[return-value]
