"""Path construction: from what a motion instruction recorded to the command's motion in joint
space (10.1), or the reason the arm cannot execute it.

    built = construct(kin, move, q_start, tool, now)   # -> Construction; raises MotionError

* movej (10.1.1): the straight line in joint space to the target; a point target takes the
  joint position of `pointToJoint` in the point's configuration (9.7.4), each axis on the turn
  nearest the start (9.6.3).
* movel, movec (10.1.4): the TCP curve (cartesian.Line, Arc) solved in the configuration of the
  start (tracking.track), joined into a paths.JointSpline.

Errors of the instruction itself raise `MotionError` at once, before anything is recorded (81: a
joint of the other arm family; 154: a target outside the software limits, out of reach or only in
another configuration than the instruction allows, a movec intermediate point the arc cannot pass,
an arc that three positions do not define; failures.py says why these are known at the
instruction). A command whose path the arm cannot follow comes back with its `failure`: the queue
records it and the next motion instruction raises 150.
"""

from __future__ import annotations

import numpy as np

from ..light_dataclass import dataclass, field
from . import findings as F
from . import trial_memo
from .cartesian import Arc, ArcError, Line
from .failures import limit_finding, named, path_failure, rounded, target_error, unreachable_finding
from .findings import Finding, MotionError
from .paths import JointLine, JointSpline
from .queued import Geometry
from .tracking import track

JOINT_EQ = 1e-6  # degrees: joint positions this close are the same position (9.2.2)


@dataclass
class Construction:
    """The command's geometry; `blend` its blend (off when the arm does not move); `failure` the
    finding of a command the arm cannot execute (None when it can); `notes` findings that do not
    stop it (R016)."""

    geometry: Geometry
    blend: str
    failure: Finding | None = None
    notes: list[Finding] = field(default_factory=list)


def construct(kin, move, q_start: np.ndarray, tool: np.ndarray | None, now: float) -> Construction:
    """The geometry of `move` (commands.MoveCommand) from joints `q_start` with the TCP `tool` in
    the flange (4x4 mm, None: the flange), recorded at `now` (s)."""
    built = Construction(Geometry(q_start, q_start.copy()), move.mdesc.blend)
    if move.kind == "movej":
        q_end = _movej_target(kin, move, q_start, tool, now)
        built.geometry.q_end = q_end
        if np.abs(q_end - q_start).max() <= JOINT_EQ:
            built.notes.append(Finding(
                F.NO_OP, "movej: the target is the position the motion starts from: the arm does not move",
                move.source, now, data={"joints": rounded(q_start)}))
            built.geometry.q_end = q_start.copy()
            built.blend = "off"
        else:
            built.geometry.joint_curve = joint_line(kin, q_start, q_end)
        return built
    _cartesian(kin, built, move, q_start, tool, now)
    return built


def joint_line(kin, q_start: np.ndarray, q_end: np.ndarray) -> JointLine:
    """The JointLine from q_start to q_end, the same object for the same joints (kin.reuse): its
    samples are then computed once."""
    key = ("line", q_start.tobytes(), np.asarray(q_end, float).tobytes())
    hit = kin.reuse.get(key)
    return hit if hit is not None else kin.reuse.keep(key, JointLine(q_start.copy(), np.array(q_end, dtype=float)))


def _movej_target(kin, move, q_start, tool, now) -> np.ndarray:
    """The joint target of a movej; MotionError 154 when the arm cannot go there (10.6: "si
    jPosition se situe en dehors des butées logicielles, si pPosition ne peut pas être atteinte")."""
    target = move.target
    source = move.source
    if target.is_joint:
        j = np.asarray(target.joints, dtype=float)
        if len(j) != len(q_start):
            raise MotionError(81, f"movej: a joint value with {len(j)} axes for the {len(q_start)}-axis arm")
        over = np.maximum(kin.lo - j, j - kin.hi)
        if np.any(over > 1e-7):
            ax = int(np.argmax(over))
            raise target_error(limit_finding(kin, "movej: the joint target", ax, float(over[ax]), j[ax], source, now))
        return j
    # the joints are a function of the pose, the tool, the configuration and the start (kin.reuse)
    key = ("solve", np.asarray(target.pose, float).tobytes(), None if tool is None else np.asarray(tool, float).tobytes(),
           tuple(target.config), q_start.tobytes())
    hit = kin.reuse.get(key) if trial_memo.REUSE else None
    if hit is not None:
        return hit.copy()
    T = target.pose if tool is None else target.pose @ np.linalg.inv(tool)
    from ..robot.errors import Unreachable

    try:
        j = kin.model.solve(T[:3, :4].tolist(), target.config, initial=tuple(q_start))
    except Unreachable as exc:
        raise target_error(unreachable_finding(kin, "movej", target, T, q_start, exc.reason, source, now)) from None
    j = np.asarray(j, dtype=float)
    if trial_memo.REUSE:
        kin.reuse.keep(key, j.copy())
    return j


def _cartesian(kin, built: Construction, move, q_start, tool, now) -> None:
    """movel, movec: the TCP curve solved in the start configuration (10.1.4.2). A target (or a
    movec intermediate point) the curve cannot end at (or pass) raises 154 at the instruction; a
    curve the arm cannot follow is `built.failure` (150 later).

    The checks and the joint curve are a function of the kind, the start joints, the tool, the
    target's (and intermediate point's) pose and requested configuration, on this geometry
    (kin.reuse): a motion that repeats exactly reuses them (the same objects). Only motions
    that pass the checks are kept; a raise is found again every time."""
    kind = move.kind
    via = move.via.pose if kind == "movec" else None
    key = ("track", kind, q_start.tobytes(), None if tool is None else np.asarray(tool, float).tobytes(),
           np.asarray(move.target.pose, float).tobytes(), None if via is None else np.asarray(via, float).tobytes(),
           tuple(move.target.config))
    hit = kin.reuse.get(key) if trial_memo.REUSE else None
    if hit is None:
        hit = _checked_track(kin, move, q_start, tool, now)
        if trial_memo.REUSE:
            kin.reuse.keep(key, hit)
    curve, tr, spline = hit
    built.geometry.tcp_curve = curve
    if tr is None:  # the TCP does not move
        built.blend = "off"
        return
    if tr.failure is not None:
        built.failure = path_failure(kin, kind, tr.failure, curve, move.source, now)
        return
    built.geometry.joint_curve = spline
    built.geometry.q_end = tr.Q[-1].copy()


def _checked_track(kin, move, q_start, tool, now) -> tuple:
    """`_cartesian` computed: (TCP curve, tracking.track's answer or None when the TCP does not
    move, the JointSpline or None when the arm cannot follow the curve); raises MotionError."""
    source = move.source
    kind = move.kind
    T_end = move.target.pose
    T0 = kin.tcp(q_start[None], tool)[0]
    try:  # an arc that three positions do not define is an invalid instruction (154)
        curve = Line(T0, T_end) if kind == "movel" else Arc(T0, move.via.pose, T_end)
    except ArcError as exc:
        f = Finding(F.CIRCLE, str(exc), source, now, error=154, data=dict(exc.data, what=exc.what))
        raise MotionError(154, f.message, f) from None
    code0 = int(kin.config_codes(q_start)[0])
    cfg0 = kin.config_name(code0)
    fields = ("shoulder", "elbow", "wrist")[:len(cfg0)]
    # 10.1.4.2: a line or a circle cannot change configuration
    for field_name, want, have in zip(fields, move.target.config, cfg0):
        w = want.lower()
        if w.endswith("same") or w.endswith("free"):
            continue
        if w != have:
            raise target_error(Finding(
                F.CONFIG_CHANGE, f"{kind}: the target imposes {field_name} {w} but the motion starts in {have}: "
                f"a straight line or a circle cannot change configuration (10.1.4.2); use movej, or "
                f"{field_name[0]}same/{field_name[0]}free", source, now,
                data={"field": field_name, "requested": w, "start": have}))
    if kind == "movec":  # 10.6: "si point pIntermédiaire ... ne peut pas être atteint" (its configuration is not used)
        _in_start_configuration(kin, move.via, "the intermediate point", tool, q_start, code0, kind, source, now)
    _in_start_configuration(kin, move.target, "the target", tool, q_start, code0, kind, source, now)
    if curve.length_mm < 1e-6 and curve.angle_deg < 1e-6:
        return curve, None, None
    tr = track(kin, curve, tool, q_start, code0)
    spline = None
    if tr.failure is None:
        spline = JointSpline(tr.lam, tr.Q, tr.D)
        spline.sing = tr.sing
        spline.curve = curve
    return curve, tr, spline


def _in_start_configuration(kin, target, what: str, tool, q_start, code0: int, kind: str, source, now) -> None:
    """MotionError 154 unless a joint position within the software limits, in the configuration
    of the start (code `code0`), puts the TCP at `target`: a line or a circle cannot end at (or
    pass) it otherwise (10.1.4.2)."""
    cfg0 = kin.config_name(code0)
    T = target.pose
    flange = T if tool is None else T @ np.linalg.inv(tool)
    sols, sol_codes = kin.solutions(flange)
    codes = {int(x) for x in sol_codes}
    if code0 not in codes:
        if codes:
            other = kin.config_name(min(codes))
            raise target_error(Finding(
                F.CONFIG_CHANGE, f"{kind}: {what}{named(target)} can only be reached in configuration "
                f"{'/'.join(other)}, not in the start configuration {'/'.join(cfg0)}: a straight line or a circle "
                "cannot change configuration (10.1.4.2); use movej", source, now,
                data={"start": list(cfg0), "target": list(other)}))
        raise target_error(Finding(F.UNREACHABLE, f"{kind}: {what}{named(target)} is out of the arm's reach", source,
                                   now, data={"target_mm": rounded(T[:3, 3])}))
    mine = kin.turns(sols[sol_codes == code0], q_start)
    over = np.maximum(kin.lo - mine, mine - kin.hi).max(axis=1)
    if np.all(over > 1e-7):
        best = mine[int(np.argmin(over))]
        ex = np.maximum(kin.lo - best, best - kin.hi)
        ax = int(np.argmax(ex))
        raise target_error(limit_finding(kin, f"{kind}: {what}{named(target)} in the start configuration "
                                         f"{'/'.join(cfg0)}", ax, float(ex[ax]), float(best[ax]), source, now))
