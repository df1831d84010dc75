"""Joint speeds and accelerations the models assume where Stäubli publishes none: one rule per
family (robots/README.md and docs/motion.md, "Accelerations"). Used by generate.py (written into
each URDF with its reason) and by bench/bench_cycle.py (which fits and checks the SCARA rule).

Six-axis arms: no public figure constrains their accelerations (no cycle time is published for
the TX2/TX/RX arms; their data sheets give joint speeds, which the models use). Rule, an
assumption and nothing more: each joint reaches its nominal speed from rest in SIX_AXIS_RAMP_S.
Its range: the reports give every cycle time for accelerations ½ to 2 times these (ramps of 0.5
to 0.125 s; val3check.robot.models.ASSUMED_ACCELERATION_RANGE), and a measured cycle fits them
(val3check robots fit).

SCARA arms: Stäubli publishes the standard cycle of the TS2 range (PUBLISHED_CYCLES). No joint
speed of any Stäubli SCARA is public, so speeds and accelerations are both assumed, by one rule for
every SCARA of reach R (mm), with R0 = SCARA_REACH_REF:

    speed of axis i         SCARA_SPEEDS_REF[i] × R0 / R      (the flange's top speed the same for every size)
    ramp to that speed      SCARA_RAMP_REF_S × √(R / R0)      (acceleration ∝ R^-3/2)

so that a fixed motion (the 300 mm standard cycle) takes longer on a longer arm, as the published
cycles do (they grow as R^0.45 from the TS2-40 to the TS2-100). The exponents are chosen on the
four figures (speed ∝ 1/R and acceleration ∝ R^-3/2 leave a spread of ±4 %; acceleration ∝ R^-2,
±10 %, measured with the reference before its fix; the same limits for every size give the trend
backwards). The cycle fixes only a
combination of speed and acceleration, not each: SCARA_SPEEDS_REF is an assumption (the flange's
top speed 8.7 m/s, axis 1 alone with the arm stretched; the round values 400/600/1000/1500 the
models had before cannot give the TS2-40's figure with any acceleration), and SCARA_RAMP_REF_S is
then fitted so that the optimum of the standard cycle matches the four figures in the
least-squares sense of log(optimum / published): within 3.7 % of each figure, and within 5.0 % for
each arm when fitted on the other three (python bench/bench_cycle.py --fit; refitted to 0.040 s from
0.044 s once tests/motion/reference.py's end-derivative bug was fixed, which had made the first half
of the cycle 8 % short).
"""

from __future__ import annotations

import math

SIX_AXIS_RAMP_S = 0.25

# Stäubli TS2 range, standard cycle (2 kg; up 25 mm, across 300 mm, down 25 mm and back), "up to"
# cycles per minute, as quoted in issue 23 from Stäubli's TS2 range leaflet and product-range
# brochure by public catalogue data; not checked against a Stäubli document here (none was
# reachable: docs/motion.md, "Accelerations").
PUBLISHED_CYCLES = {"TS2-40": 240, "TS2-60": 220, "TS2-80": 200, "TS2-100": 170}
CYCLE_SOURCE = ("Stäubli TS2 range leaflet and product-range brochure (standard cycle 25/300/25 mm and back, "
                "2 kg: up to 240/220/200/170 cycles per minute for the TS2-40/-60/-80/-100), as quoted by public "
                "catalogue data in issue 23; no Stäubli document was reachable to check them")

SCARA_REACH_REF = 620.0  # mm: the TS2-60's reach, where SCARA_SPEEDS_REF apply
SCARA_SPEEDS_REF = (800.0, 1200.0, 2000.0, 3000.0)  # deg/s, deg/s, mm/s, deg/s (assumed)
SCARA_RAMP_REF_S = 0.040  # s, fitted: bench/bench_cycle.py --fit (0.0400)


def six_axis_ramp() -> float:
    return SIX_AXIS_RAMP_S


def scara(reach_mm: float, ramp_ref_s: float = SCARA_RAMP_REF_S) -> tuple[tuple[float, ...], float]:
    """(nominal speeds, ramp time in s) of a SCARA of this reach, by the family's rule; the
    accelerations are speed / ramp. Rounded: speeds to 0.1, the ramp to 0.1 ms."""
    k = SCARA_REACH_REF / reach_mm
    speeds = tuple(round(v * k, 1) for v in SCARA_SPEEDS_REF)
    return speeds, round(ramp_ref_s * math.sqrt(reach_mm / SCARA_REACH_REF), 4)


# ---- what each model says about them (its <assumption> elements) ----------------------------------


def six_axis_text() -> str:
    r = f"{SIX_AXIS_RAMP_S:g}"
    return ("Stäubli publishes no joint accelerations, and no cycle time of a six-axis arm was found to derive them "
            f"from: each joint is assumed to reach its nominal speed from rest in {r} s (acceleration = nominal speed / "
            f"{r} s); decelerations equal. Set ramp_s or accelerations (measured values remove the uncertainty range)")


def scara_accel_text(name: str, reach: float, ramp: float) -> str:
    pub = PUBLISHED_CYCLES.get(name)
    grounded = (f"this arm's own figure, {60 / pub:.3f} s, is one of them" if pub else
                "no cycle is published for this arm: the rule extrapolates the TS2 figures")
    return (f"Stäubli publishes no joint accelerations. SCARA rule (robots/dynamics.py): every axis reaches its nominal "
            f"speed from rest in {SCARA_RAMP_REF_S:g} s × √(reach / {SCARA_REACH_REF:g} mm), {ramp:g} s at this arm's "
            f"{reach:g} mm; the reference ramp is fitted so that the optimum of the TS2 standard cycle matches "
            f"Stäubli's figures for the TS2-40/-60/-80/-100 within 4 % ({grounded}); decelerations equal. Set "
            "ramp_s or accelerations (measured values remove the uncertainty range)")


def scara_speed_text(reach: float) -> str:
    ref = " ".join(f"{v:g}" for v in SCARA_SPEEDS_REF)
    return (f"No public source gives a Stäubli SCARA's joint speeds. SCARA rule (robots/dynamics.py): {ref} (deg/s; "
            f"mm/s for axis 3) at {SCARA_REACH_REF:g} mm of reach, times {SCARA_REACH_REF:g} / {reach:g} for this arm "
            "(the flange's top speed the same for every size); not a Stäubli figure: the published cycles fix only a "
            "combination of speed and acceleration. Set the arm's own")
