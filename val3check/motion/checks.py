"""Thresholds of the motion diagnostics and the analysis of a path near a singularity.

10.1.4.3: near a singularity two axes line up and a small motion of the tool needs large joint
motions; on a straight line or a circle the joint speed limits then force the tool to slow down,
and through the singularity the path cannot be followed at all (10.3.4: the arm would stop on a
following error). The manual gives no figures; val3check uses these (docs/motion.md):
"""

from __future__ import annotations

import numpy as np

from ..light_dataclass import dataclass
from . import findings as F
from .findings import Finding
from .paths import JointSpline, tcp_rates

# A position is "near" a singularity below these distances (kin.Singularity).
THRESHOLDS = {"wrist": 5.0, "elbow": 5.0, "shoulder": 30.0}  # degrees, degrees, mm
UNITS = {"wrist": "°", "elbow": "°", "shoulder": " mm"}
WHAT = {
    "wrist": "wrist singularity (axes 4 and 6 aligned, j5 = 0)",
    "elbow": "elbow singularity (arm stretched)",
    "shoulder": "shoulder singularity (wrist centre on axis 1)",
}
# A Cartesian path near a singularity is reported (warning) when the joint speed limits cut the
# TCP speed there below this fraction of the speed the path allows elsewhere (or of tvel).
SLOWDOWN_WARN = 0.5
# The static reach check: a joint within this margin of a software limit is "near" it (degrees).
LIMIT_MARGIN = 2.0


@dataclass
class SingularPass:
    """How a Cartesian path passes a singularity (the closest gridpoint)."""

    which: str  # "wrist" | "elbow" | "shoulder"
    distance: float  # degrees or mm (see THRESHOLDS)
    index: int  # gridpoint of the closest approach
    axis: int  # the axis whose speed limit binds there (0-based)
    cap: float  # TCP speed the joint speed limits allow there (mm/s)
    reference: float  # TCP speed the path allows elsewhere, at most tvel (mm/s)
    needed: float  # speed the axis would need to keep `reference` (deg/s)
    nominal: float  # that axis's speed limit (deg/s)

    @property
    def ratio(self) -> float:
        """The TCP speed there over the speed elsewhere (1 when nothing is allowed elsewhere)."""
        return self.cap / self.reference if self.reference > 0 else 1.0


def nearest(sing) -> tuple[str, float, int]:
    """(which, distance, gridpoint) of the closest approach to a singularity, relative to the
    thresholds."""
    best = ("wrist", np.inf, 0, np.inf)
    for which in ("wrist", "elbow", "shoulder"):
        d = getattr(sing, which)
        if len(d) == 0:
            continue
        i = int(np.argmin(d))
        rel = float(d[i]) / THRESHOLDS[which]
        if rel < best[3]:
            best = (which, float(d[i]), i, rel)
    return best[0], best[1], best[2]


def singular_pass(sing, q1: np.ndarray, pt: np.ndarray, V: np.ndarray, tvel: float) -> SingularPass | None:
    """The closest approach of a path to a singularity when it is within the thresholds, with
    what it costs: the TCP speed cap from the joint speed limits there versus the cap elsewhere
    (at most tvel). q1: dq/dσ (N, 6); pt: |dp/dσ| (N,); V: joint speed limits (6,)."""
    which, dist, i = nearest(sing)
    if not np.isfinite(dist) or dist >= THRESHOLDS[which]:
        return None
    aq = np.abs(q1)
    with np.errstate(divide="ignore", invalid="ignore"):
        per_axis = np.where(aq > 1e-12, V / aq, np.inf) * pt[:, None]  # mm/s allowed by each axis
    cap = per_axis.min(axis=1)
    finite = cap[np.isfinite(cap)]
    ref_path = float(np.percentile(finite, 90)) if len(finite) else np.inf
    reference = min(tvel, ref_path)
    axis = int(np.argmin(per_axis[i])) if np.isfinite(cap[i]) else 0
    needed = float(aq[i, axis] / pt[i] * reference) if pt[i] > 1e-12 else float("inf")
    return SingularPass(which, dist, i, axis, float(cap[i]), float(reference), needed, float(V[axis]))


def slowdown(kin, command, limits, profile) -> Finding | None:
    """R014: a Cartesian command (a queued.QueuedCommand) that passed near a singularity and slowed
    there below SLOWDOWN_WARN of its speed elsewhere; `limits`: its mdesc.Limits, `profile` the
    arm's trajectory.Profile (when it passed there). None when it did not."""
    g = command.geometry.joint_curve
    curve = command.geometry.tcp_curve
    if g is None or not isinstance(g, JointSpline) or curve is None:
        return None
    sing = getattr(g, "sing", None)
    if sing is None:
        return None
    far = g.__dict__.get("far_from_singularities")  # (asked per command: the spline's own answer, kept)
    if far is None or far[0] is not sing:
        far = g.far_from_singularities = (sing, bool(
            sing.wrist.min(initial=np.inf) >= THRESHOLDS["wrist"] and sing.elbow.min(initial=np.inf) >= THRESHOLDS["elbow"]
            and sing.shoulder.min(initial=np.inf) >= THRESHOLDS["shoulder"]))
    if far[1]:
        return None
    q1 = g.q(g.lam, 1) / g.ell
    pt, _ = tcp_rates(kin, g.Q, q1, command.tool)
    sp = singular_pass(sing, q1, pt, limits.V, limits.tvel)
    if sp is None or sp.ratio >= SLOWDOWN_WARN:
        return None
    lam = float(g.lam[sp.index])
    at = lam * curve.length_mm
    # where the arm passed it, and how fast
    s_glob = None
    for span in command.placement.spans:
        if span.geom is g and span.a - 1e-12 <= lam <= span.b + 1e-12 and span.offset is not None:
            s_glob = span.offset + (lam - span.a) * g.ell
    t_pass = profile.time_at(s_glob) if s_glob is not None else None
    unit = "°" if sp.which != "shoulder" else " mm"
    msg = (f"{command.kind} passes near the {WHAT[sp.which]}: {sp.distance:.2f}{unit} at {at:.1f} mm along the path; "
           f"to keep {sp.reference:.0f} mm/s axis {sp.axis + 1} would need {sp.needed:.0f}°/s (limit "
           f"{sp.nominal:.0f}°/s): the TCP slows to {sp.cap:.0f} mm/s ({sp.ratio * 100:.0f} %)")
    return Finding(F.SINGULAR_SLOW, msg, command.request.source,
                   t_pass if t_pass is not None else command.request.recorded, move_id=command.id,
                   data={"singularity": sp.which, "distance": round(sp.distance, 4), "along_mm": round(at, 3),
                         "axis": sp.axis + 1, "needed_deg_s": round(sp.needed, 3), "limit_deg_s": round(sp.nominal, 3),
                         "tcp_cap_mm_s": round(sp.cap, 3), "reference_mm_s": round(sp.reference, 3)})
