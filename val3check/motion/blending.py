"""Blending (10.1.2): the leave and reach points of a blended command and the curve between them.

    lam = distance_lambda(kin, command, leave_mm, from_end=True)   # λ of the leave point
    cand = candidate(kin, previous, command, limits_of)            # Candidate, or None

A blended command ends, for now, at its leave point, `leave` mm (TCP distance) before its
target; when the next command comes, the blend goes from there to the next command's reach
point, `reach` mm after the target (both from the mdesc of the command whose target is blended,
10.1.2.1). A joint blend is a paths.JointBlend; a Cartesian blend (blend Cartesian, the same
tool on both sides) is the TCP curve cartesian.Blend solved in the configuration of the leave
point, and falls back to the joint blend where it cannot be followed (docs/motion.md). Whether
the arm then takes the blend or stops at the via point is the planner's choice (planner.py,
`blend_pays`): this module only builds the candidate.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from . import trial_memo
from .cartesian import Blend, Line, rotvec
from .paths import BLEND_SHAPES, JointBlend, JointSpline
from .tracking import track

MIN_BLEND_MM = 0.01  # a leave or reach shorter than this: no blend, the arm stops at the point
CUSP_COS = math.cos(math.radians(170.0))  # a blend that turns back more than this: the arm stops


class Candidate(NamedTuple):
    """A blend not yet committed: its joint-space curve, the λ of the reach point on the next
    command, and the path length of the blend that belongs to the previous command (up to the
    point proportional to the two sides, docs/motion.md)."""

    curve: object
    lam_reach: float
    split: float


def tcp_positions(kin, command, lam) -> np.ndarray:
    """TCP positions (N, 3) of `command` at its λ values: on its TCP curve, or through the
    forward kinematics of its joint curve."""
    lam = np.atleast_1d(np.asarray(lam, dtype=float))
    g = command.geometry
    if g.tcp_curve is not None:
        return g.tcp_curve.positions(lam)
    return kin.tcp(g.joint_curve.q(lam), command.tool)[:, :3, 3]


def distance_lambda(kin, command, d: float, from_end: bool) -> float | None:
    """λ where the TCP is at distance d from the target (from_end) or from the start, taking
    the last such point before the target (the first after the start); d is clipped to half
    the chord. None when d is too short to blend."""
    curve = command.geometry.tcp_curve
    if isinstance(curve, Line):  # exact on a line
        L = curve.length_mm
        d = min(d, L / 2.0)
        if d < MIN_BLEND_MM:
            return None
        return 1.0 - d / L if from_end else d / L
    # a function of the command's curves (the same objects for a repeated motion), its tool, d
    # and the end it is measured from, on this geometry (kin.reuse)
    g = command.geometry
    if command.cls is not None:  # its class (queued.QueuedCommand.cls) holds its curves and tool
        key = ("distance", command.cls, d, from_end)
    else:
        key = ("distance", id(g.joint_curve), id(curve), _value(command.tool), d, from_end)
    hit = kin.reuse.get(key) if trial_memo.REUSE else None
    if hit is not None and hit[0] is g.joint_curve and hit[1] is curve:
        return hit[2]
    lam = _distance_lambda(kin, command, d, from_end)
    kin.reuse.keep(key, (g.joint_curve, curve, lam))
    return lam


def _distance_lambda(kin, command, d: float, from_end: bool) -> float | None:
    """`distance_lambda` on a curve other than a line, computed."""
    lam = np.linspace(0.0, 1.0, 33)
    P = tcp_positions(kin, command, lam)
    ref = P[-1] if from_end else P[0]
    chord = float(np.linalg.norm(P[-1] - P[0]))
    d = min(d, chord / 2.0)
    if d < MIN_BLEND_MM:
        return None
    for _ in range(3):  # refine the bracket 8 times per round (1/16384 of the path)
        dist = np.linalg.norm(P - ref, axis=1)
        far = np.nonzero(dist >= d)[0]
        j = int(far.max()) if from_end else int(far.min())
        j = min(j, len(lam) - 2) if from_end else max(j, 1)
        a, b = (lam[j], lam[j + 1]) if from_end else (lam[j - 1], lam[j])
        lam = np.linspace(a, b, 9)
        P = tcp_positions(kin, command, lam)
    dist = np.linalg.norm(P - ref, axis=1)
    far = np.nonzero(dist >= d)[0]
    return float(lam[far.max()] if from_end else lam[far.min()])


def candidate(kin, previous, command, limits_of) -> Candidate | None:
    """The blend from `previous`'s leave point to `command`'s reach point (10.1.2), or None when
    the two cannot be blended (the reach point too close, a cusp). `limits_of(command)`: the
    limits (mdesc.Limits) the shape estimate uses. Nothing is changed.

    Reused (kin.reuse) when everything it depends on is the same: both commands' curves (the same
    objects: construction.py reuses them), the leave point, the reach distance, the blend kind,
    both tools and both commands' limits (mdesc and monitor speed)."""
    pg, cg = previous.geometry, command.geometry
    curves = (pg.joint_curve, pg.tcp_curve, cg.joint_curve, cg.tcp_curve)
    # the limits choose between shapes only when there are several (`blend_time`)
    limits = (_limits_key(limits_of(previous)), _limits_key(limits_of(command))) if len(BLEND_SHAPES) > 1 else ()
    if previous.cls is not None and command.cls is not None:
        # the commands' classes (queued.QueuedCommand.cls) hold their curves, reach and tools
        key = ("blend", previous.cls, command.cls, previous.placement.lam_leave, previous.placement.blend, limits)
        hit = kin.reuse.get(key)
        return hit[0] if hit is not None else kin.reuse.keep(key, (_candidate(kin, previous, command, limits_of),))[0]
    key = ("blend", *map(id, curves), previous.placement.lam_leave, previous.request.mdesc.reach,
           previous.placement.blend, _value(previous.tool), _value(command.tool), limits)
    hit = kin.reuse.get(key)
    if hit is not None and all(a is b for a, b in zip(hit[0], curves)):
        return hit[1]
    return kin.reuse.keep(key, (curves, _candidate(kin, previous, command, limits_of)))[1]


def _value(a) -> bytes | None:
    return None if a is None else np.asarray(a, dtype=float).tobytes()


def _limits_key(lim) -> tuple:
    return (_value(lim.V), _value(lim.A), _value(lim.D), float(lim.tvel), float(lim.rvel))


def _candidate(kin, previous, command, limits_of) -> Candidate | None:
    """`candidate`, computed."""
    lam_r = distance_lambda(kin, command, previous.request.mdesc.reach, from_end=False)
    if lam_r is None or lam_r >= 1.0 - 1e-9:
        return None
    gL, gR = previous.geometry.joint_curve, command.geometry.joint_curve
    lam_l = previous.placement.lam_leave
    qL = gL.q([lam_l])[0]
    vL = gL.q([lam_l], 1)[0] / gL.ell
    qR = gR.q([lam_r])[0]
    vR = gR.q([lam_r], 1)[0] / gR.ell
    nl, nr = np.linalg.norm(vL), np.linalg.norm(vR)
    if nl < 1e-12 or nr < 1e-12 or float(vL @ vR) / (nl * nr) < CUSP_COS:
        return None
    ell_l = (1.0 - lam_l) * gL.ell
    ell_r = lam_r * gR.ell
    curve = None
    same_tool = (previous.tool is None and command.tool is None) or (
        previous.tool is not None and command.tool is not None and np.allclose(previous.tool, command.tool))
    if previous.placement.blend == "Cartesian" and same_tool:
        curve = _cartesian_blend(kin, previous, command, qL, vL, qR, vR, ell_l, ell_r, limits_of)
    if curve is None:
        shapes = [JointBlend(qL, vL, qR, vR, ell_l, ell_r, shape) for shape in BLEND_SHAPES]
        curve = shapes[0] if len(shapes) == 1 else min(
            shapes, key=lambda g: blend_time(g, limits_of(previous), limits_of(command)))
    # the blend belongs to the previous command up to the point proportional to the two sides
    return Candidate(curve, lam_r, curve.ell * ell_l / (ell_l + ell_r))


def blend_time(curve, limits_a, limits_b) -> float:
    """An estimate of the time to go through a blend `curve` under the limits of the two
    commands: its length at the speed its curvature and the joint speeds allow (the shape the
    arm follows fastest is chosen)."""
    lam = np.linspace(0.0, 1.0, 17)
    q1 = curve.q(lam, 1) / curve.ell
    q2 = curve.q(lam, 2) / curve.ell ** 2
    V = np.minimum(limits_a.V, limits_b.V)
    A = np.minimum(np.minimum(limits_a.A, limits_a.D), np.minimum(limits_b.A, limits_b.D))
    with np.errstate(divide="ignore"):
        xv = np.min(np.where(np.abs(q1) > 1e-12, (V / np.abs(q1)) ** 2, np.inf), axis=1)
        xa = np.min(np.where(np.abs(q2) > 1e-12, A / np.abs(q2), np.inf), axis=1)
    sd = np.sqrt(np.minimum(xv, xa))
    return float(np.trapezoid(1.0 / np.maximum(sd, 1e-9), lam * curve.ell))


def _cartesian_blend(kin, previous, command, qL, vL, qR, vR, ell_l, ell_r, limits_of):
    """A Cartesian blend tracked in the configuration of the leave point, of the shape the arm
    follows fastest; None when no shape can be followed there (the joint blend is used instead,
    docs/motion.md)."""
    best = None
    for shape in BLEND_SHAPES:
        g = _cartesian_blend_shape(kin, previous.tool, qL, vL, qR, vR, ell_l, ell_r, shape)
        if g is not None:
            t = blend_time(g, limits_of(previous), limits_of(command)) if len(BLEND_SHAPES) > 1 else 0.0
            if best is None or t < best[0]:
                best = (t, g)
    return None if best is None else best[1]


def _cartesian_blend_shape(kin, tool, qL, vL, qR, vR, ell_l, ell_r, shape):
    """The Cartesian blend of one shape from joints qL (velocity vL) to qR (vR), as a
    JointSpline; None when it cannot be followed in the leave point's configuration."""
    h = 1e-4
    T = kin.tcp(np.vstack([qL, qL + h * vL, qL - h * vL, qR, qR + h * vR, qR - h * vR]), tool)

    def state(i):
        """TCP position, rotation, velocity and angular velocity at row i of T (central differences)."""
        p = T[i, :3, 3]
        v = (T[i + 1, :3, 3] - T[i + 2, :3, 3]) / (2 * h)
        w = rotvec(T[i + 1, :3, :3] @ T[i + 2, :3, :3].T) / (2 * h)
        return p, T[i, :3, :3], v, w

    curve = Blend(state(0), state(3), ell_l, ell_r, shape)
    ell_b = curve.ell
    code = int(kin.config_codes(qL)[0])
    tr = track(kin, curve, tool, qL, code)
    if tr.failure is not None or np.max(np.abs(tr.Q[-1] - qR)) > 1e-5:
        return None
    Q = tr.Q.copy()
    Q[-1] = qR
    D = tr.D.copy()
    D[0], D[-1] = ell_b * vL, ell_b * vR  # exactly the neighbours' velocities: C1 junctions
    g = JointSpline(tr.lam, Q, D)
    g.ell = ell_b
    g.sing = tr.sing
    g.curve = curve
    return g
