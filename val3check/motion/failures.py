"""The findings of a motion command the arm cannot execute (R010-R013), and their runtime errors.

10.6 names two moments. What is known when the instruction records its command stops the task at
that instruction (`target_error`, 154 of 12.1, "instruction de mouvement invalide"): `movej`
"génère une erreur d'exécution ... si jPosition se situe en dehors des butées logicielles, si
pPosition ne peut pas être atteinte", `movel` also "si un mouvement en ligne droite vers pPosition
n'est pas possible" (a configuration change, 10.1.4.2), `movec` "si point pIntermédiaire (ou point
pCible) ne peut pas être atteint". What the trajectory generator only finds while it interpolates
the path (10.1.4.3: "une erreur est générée lors du mouvement du robot"): a line or a circle
through a joint limit, the edge of the workspace, a singularity or a configuration change. That
command is recorded and returns its identifier, the arm stops before it, and the next motion
instruction, waitEndMove, open or close raises 150 (12.1: "un mouvement demandé précédemment n'a
pas pu être terminé (point hors d'atteinte, singularité, problème de configuration...)").

Every function builds a `findings.Finding` from explicit inputs (the arm's kinematics, the
numbers of the failure, the instruction's source and time); nothing here keeps state.
"""

from __future__ import annotations

import numpy as np

from . import findings as F
from .checks import WHAT
from .findings import Finding, MotionError, Source

INVALID_MOTION = 154  # 12.1: "instruction de mouvement invalide": a target the command cannot reach
LATER = 150  # 12.1: "un mouvement demandé précédemment n'a pas pu être terminé"


def target_error(finding: Finding) -> MotionError:
    """The error at the instruction for a target it cannot reach (module docstring): 154, with
    the finding (R010-R012) behind it."""
    f = Finding(finding.code, finding.message, finding.source, finding.time, finding.move_id, INVALID_MOTION,
                finding.data)
    return MotionError(INVALID_MOTION, f.message, f)


def deferred(finding: Finding) -> Finding:
    """The finding of a command that cannot be executed, with the error that follows it (150)."""
    if finding.error == 150:
        return finding
    return Finding(finding.code, finding.message, finding.source, finding.time, finding.move_id, 150, finding.data)


def failure_text(finding: Finding) -> str:
    """The message of the error 150 a later instruction raises for `finding`."""
    return f"{finding.source.label()}: {finding.message}; resetMotion() clears the motion queue"


def limit_finding(kin, what: str, axis: int, amount: float, value: float, source: Source, now: float,
                  error: int = 150) -> Finding:
    """R011: `what` puts axis `axis` (0-based) at `value`, `amount` outside its software limits."""
    lo, hi = kin.model.joint_limits[axis]
    side = "below" if value < lo else "above"
    u = "°" if kin.revolute[axis] else " mm"
    return Finding(F.JOINT_LIMIT, f"{what} is outside the software limits: j{axis + 1} = {value:.3f}{u} is "
                   f"{amount:.3f}{u} {side} its limit [{lo:g}, {hi:g}]", source, now, error=error,
                   data={"axis": axis + 1, "value_deg": round(value, 6), "excess_deg": round(amount, 6),
                         "limits_deg": [lo, hi]})


def unreachable_finding(kin, kind: str, target, flange: np.ndarray, q_start: np.ndarray, reason: str,
                        source: Source, now: float) -> Finding:
    """R010 (or R011 when the joint limits are what stops it): no joint position reaches the point
    `target` (the flange pose `flange`) in its configuration; `reason` as robot.errors.Unreachable
    gives it ("reach", "limits", "config")."""
    model = kin.model
    if reason in ("limits", "config"):
        # the solutions in the requested configuration, ignoring the limits: if there are some,
        # the joint limits are what stops the motion (which axis, by how much)
        sols, codes = kin.solutions(flange)
        if len(sols):
            sols = kin.turns(sols, q_start)
            start = tuple(model.config_of(q_start))
            wanted = [s0 if w.endswith("same") else (None if w.endswith("free") else w)
                      for w, s0 in zip((c.lower() for c in target.config), start)]
            keep = [all(w is None or w == v for w, v in zip(wanted, kin.config_name(int(cd)))) for cd in codes]
            sols = sols[np.array(keep, dtype=bool)]
        if len(sols):
            sols[np.isnan(sols[:, 3]), 3] = q_start[3]
            over = np.maximum(kin.lo - sols, sols - kin.hi)
            worst = over.max(axis=1)
            i = int(np.argmin(worst))
            ax = int(np.argmax(over[i]))
            return limit_finding(kin, f"{kind}: every joint position reaching the point{named(target)}", ax,
                                 float(over[i, ax]), float(sols[i, ax]), source, now)
    if reason == "config":
        msg = (f"{kind}: the point{named(target)} is reachable, but not in the requested configuration "
               f"{'/'.join(target.config)} (same fields relative to the start {'/'.join(model.config_of(q_start))})")
    else:
        msg = f"{kind}: the point{named(target)} is out of the arm's reach"
    if getattr(target, "note", ""):
        msg += f"; {target.note}"
    return Finding(F.UNREACHABLE, msg, source, now, error=150,
                   data={"target_mm": rounded(flange[:3, 3]), "reason": reason, "config": list(target.config)})


def path_failure(kin, kind: str, failure, curve, source: Source, now: float) -> Finding:
    """R010-R013 for a Cartesian path that cannot be followed (`failure`: tracking.Failure on
    `curve`): where along the path, and why."""
    at = failure.lam * curve.length_mm
    where = f"{at:.1f} mm along the path" if curve.length_mm > 1e-6 else f"{failure.lam * 100:.0f} % along the path"
    data = {"along_mm": round(at, 3), "fraction": round(failure.lam, 6)}
    if failure.joints is not None:
        data["joints"] = rounded(failure.joints)
    if failure.kind == "limits":
        f = limit_finding(kin, f"{kind}: the path ({where})", failure.axis, failure.amount,
                          failure.joints[failure.axis], source, now, error=150)
        return Finding(f.code, f.message, source, now, error=150, data={**f.data, **data})
    if failure.kind == "singular":
        return Finding(F.SINGULAR_STOP,
                       f"{kind}: the path goes through the {WHAT[failure.which]} {where}: axis {failure.axis + 1} "
                       f"would have to turn {failure.amount:.1f}° at once; the path cannot be followed (10.1.4.3)",
                       source, now, error=150, data={**data, "singularity": failure.which, "axis": failure.axis + 1,
                                                     "jump_deg": round(failure.amount, 3)})
    if failure.kind == "config":
        other = "/".join(kin.config_name(failure.other_config))
        return Finding(F.CONFIG_CHANGE,
                       f"{kind}: the path leaves the start configuration {where} (only {other} reaches it): a "
                       "straight line or a circle cannot change configuration (10.1.4.2)", source, now, error=150,
                       data={**data, "other": other})
    return Finding(F.UNREACHABLE, f"{kind}: the path goes out of the arm's reach {where}", source, now, error=150,
                   data=data)


def rounded(values) -> list[float]:
    """Numbers of a finding's data, to the micrometre or micro-degree."""
    return [round(float(x), 6) for x in values]


def named(target) -> str:
    """" pA" for a target named pA, "" for an unnamed one (in messages)."""
    return f" {target.name}" if getattr(target, "name", "") else ""
