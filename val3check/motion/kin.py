"""The arm model's kinematics over many joint positions at once (numpy), for paths.

`RobotModel` (val3check/robot) solves one pose at a time in pure Python (~20,000 inverse
solutions per second). A Cartesian path needs hundreds of solutions per command, so this module
evaluates the same closed forms on arrays: forward kinematics, every inverse branch, the
configuration of 9.7.4 and the distances to the three singularities of 10.1.4.3. The tests hold
it equal to the scalar model.

Units: joints in degrees, lengths in millimetres, poses as 4x4 matrices (N, 4, 4).
"""

from __future__ import annotations

import math

import numpy as np

from ..light_dataclass import dataclass
from ..robot.dh import fk_many as dh_fk_many
from ..robot.dh import refine as dh_refine
from ..robot.errors import IKUnsupported
from ..robot.ik import opw_ik

DEG = math.pi / 180.0
RAD = 180.0 / math.pi
# Below this |sin(j5)| the wrist is exactly singular: j4 is then taken from the previous
# position of the path (only j4 + j6 is defined).
WRIST_EXACT = 1e-9
SMALL_N = 12  # below this many positions, forward kinematics loops over the pure-Python closed form


def as4(m) -> np.ndarray:
    """A 3x4 or 4x4 matrix (nested sequences) as a 4x4 array."""
    a = np.asarray(m, dtype=float)
    if a.shape == (4, 4):
        return a.copy()
    out = np.eye(4)
    out[:3, :4] = a[:3, :4]
    return out


def inv4(T: np.ndarray) -> np.ndarray:
    """Inverse of rigid transforms (..., 4, 4)."""
    R = T[..., :3, :3]
    p = T[..., :3, 3]
    out = np.zeros_like(T)
    Rt = np.swapaxes(R, -1, -2)
    out[..., :3, :3] = Rt
    out[..., :3, 3] = -np.einsum("...ij,...j->...i", Rt, p)
    out[..., 3, 3] = 1.0
    return out


@dataclass(frozen=True)
class Singularity:
    """Distances to the singularities of an RX/TX arm (10.1.4.3), per joint position.

    wrist: |j5| in degrees (axes 4 and 6 aligned); elbow: the angle between the arm and the
    forearm away from the stretched arm, in degrees (j3 = 0 on Stäubli arms); shoulder: the
    distance of the wrist centre from axis 1 in mm, less the lateral offset (the wrist centre
    "above axis 1", 10.1.4.2)."""

    wrist: np.ndarray
    elbow: np.ndarray
    shoulder: np.ndarray


class Reuse(dict):
    """Results of pure computations on one arm geometry (joint curves, their samples), keyed by
    everything they depend on: a cyclic program builds the same motions again and again. Bounded:
    the oldest entry goes first."""

    LIMIT = 4096

    def keep(self, key, value):
        """Remember `value` under `key`; returns it."""
        if len(self) >= self.LIMIT:
            self.pop(next(iter(self)))
        self[key] = value
        return value


class ArmKin:
    """Vectorised kinematics of one `RobotModel` (ortho-parallel base, spherical wrist)."""

    def __init__(self, model) -> None:
        """The kinematics of `model` (robot.RobotModel): its closed form, joint limits, speeds, accelerations."""
        self.model = model
        self.opw = model.opw
        self.lo = np.array([lo for lo, _ in model.joint_limits], dtype=float)
        self.hi = np.array([hi for _, hi in model.joint_limits], dtype=float)
        # axes whose range covers a full turn: a path unwraps them (9.6.3 "plus d'un tour")
        self.multi_turn = (self.hi - self.lo) >= 360.0 - 1e-9
        self.speeds = np.array(model.nominal_speeds, dtype=float)
        self.accels = np.array(model.accelerations, dtype=float)
        kinds = getattr(model, "joint_kinds", None) or ("revolute",) * len(self.lo)
        self.revolute = np.array([k != "prismatic" for k in kinds])
        self.multi_turn &= self.revolute
        self.scara = getattr(model, "scara", None) is not None
        self.dh = getattr(model, "dh", None)  # a geometry setDH changed (robot/absolute.py, 11.4)
        self.branch_is_config = False
        self._configs: list[tuple[str, ...]] = []  # arms without the OPW form: codes by first use
        self.reuse = Reuse()  # results that depend on this geometry only (issue 29), cleared by setDH
        if self.opw is not None:
            o = self.opw
            self.signs = np.array(o.signs, dtype=float)
            self.G = None if o.G is None else as4(o.G)
            self.Ginv = None if self.G is None else inv4(self.G)
            self.branch_is_config = bool(np.all(self.signs > 0) and o.a2 == 0.0)
            self._deg_signs = DEG * self.signs

    def use_geometry(self, model) -> None:
        """setDH (11.4): the same arm with the geometry of `model` (robot/absolute.py) from now on,
        for everyone holding this object (the queue's collaborators)."""
        self.model = model
        self.dh = getattr(model, "dh", None)
        self.reuse.clear()  # a new geometry: nothing computed with the old one is reused

    # ---- forward kinematics ------------------------------------------------------------------

    def fk(self, Q) -> np.ndarray:
        """Flange in world (N, 4, 4), mm, for joint positions Q (N, 6) in degrees."""
        Q = np.atleast_2d(np.asarray(Q, dtype=float))
        if self.dh is not None:
            return dh_fk_many(self.dh, Q)
        if self.opw is None:  # any URDF chain: one position at a time
            return np.array([as4(self.model.fk_matrix(q)) for q in Q])
        if len(Q) <= SMALL_N:  # numpy's per-call cost outweighs a few closed-form evaluations
            out = np.zeros((len(Q), 4, 4))
            out[:, 3, 3] = 1.0
            fk1 = self.opw.fk
            for i, q in enumerate((Q * DEG).tolist()):
                out[i, :3, :] = fk1(q)
            return out
        o = self.opw
        t = Q * self._deg_signs
        t[:, 2] += t[:, 1]  # t23
        c = np.cos(t)
        sn = np.sin(t)
        c1, c2, c23, c4, c5, c6 = c.T
        s1, s2, s23, s4, s5, s6 = sn.T
        c4c5 = c4 * c5
        s4c5 = s4 * c5
        w00 = c4c5 * c6 - s4 * s6
        w01 = -c4c5 * s6 - s4 * c6
        w02 = c4 * s5
        w10 = s4c5 * c6 + c4 * s6
        w11 = -s4c5 * s6 + c4 * c6
        w12 = s4 * s5
        w20 = -s5 * c6
        w21 = s5 * s6
        m00 = c23 * w00 + s23 * w20
        m01 = c23 * w01 + s23 * w21
        m02 = c23 * w02 + s23 * c5
        m20 = c23 * w20 - s23 * w00
        m21 = c23 * w21 - s23 * w01
        m22 = c23 * c5 - s23 * w02
        u = o.a1 + o.c2 * s2 + o.c3 * s23 + o.a2 * c23 + o.c4 * m02
        v = o.b + o.c4 * w12
        z = o.c1 + o.c2 * c2 + o.c3 * c23 - o.a2 * s23 + o.c4 * m22
        n = len(Q)
        T = np.empty((n, 4, 4))
        T[:, 0, :] = np.stack([c1 * m00 - s1 * w10, c1 * m01 - s1 * w11, c1 * m02 - s1 * w12, c1 * u - s1 * v], axis=1)
        T[:, 1, :] = np.stack([s1 * m00 + c1 * w10, s1 * m01 + c1 * w11, s1 * m02 + c1 * w12, s1 * u + c1 * v], axis=1)
        T[:, 2, :] = np.stack([m20, m21, m22, z], axis=1)
        T[:, 3, :] = (0.0, 0.0, 0.0, 1.0)
        if self.G is not None:
            T = T @ self.G
        return T

    def tcp(self, Q, tool: np.ndarray | None) -> np.ndarray:
        """Tool centre point poses (N, 4, 4): flange * tool."""
        T = self.fk(Q)
        return T if tool is None else T @ tool

    # ---- inverse kinematics ------------------------------------------------------------------

    @property
    def generic(self) -> bool:
        """True for an arm without the six-axis closed form (a SCARA): one pose at a time through
        the model's own inverse kinematics."""
        return self.opw is None

    def need_ik(self) -> None:
        """Raise IKUnsupported when the arm has no inverse kinematics the motion can use."""
        if self.opw is None and not self.scara:
            self.model._need_opw()  # raises IKUnsupported with the model's reason
            raise IKUnsupported(f"{self.model.name}: no closed-form inverse kinematics")

    def turns(self, sols: np.ndarray, q_start: np.ndarray) -> np.ndarray:
        """Each axis of the joint positions `sols` (N, axes) on the turn within its limits nearest
        the start (9.6.3: an axis of more than one turn takes the turn nearest jInitial); when no
        turn fits, the turn least outside them (so that a violation is measured from there)."""
        out = sols.copy()
        shifts = 360.0 * np.arange(-2, 3)
        for r in range(len(out)):
            for k in range(out.shape[1]):
                if not self.revolute[k]:  # a prismatic axis (SCARA axis 3) has no turns
                    continue
                cand = sols[r, k] + shifts
                excess = np.maximum(self.lo[k] - cand, cand - self.hi[k])
                inside = excess <= 1e-7
                if inside.any():
                    c = cand[inside]
                    out[r, k] = c[np.argmin(np.abs(c - q_start[k]))]
                else:
                    out[r, k] = cand[np.argmin(excess)]
        return out

    def config_name(self, code: int) -> tuple[str, ...]:
        """The configuration (VAL 3 names) of a code of `config_codes`."""
        if self.opw is not None:
            return config_name(code)
        return self._configs[code]

    def code_of(self, names) -> int:
        """The configuration code of names such as (righty, epositive, wnegative)."""
        names = tuple(names)
        if self.opw is not None:
            return config_code(names)
        if names not in self._configs:
            self._configs.append(names)
        return self._configs.index(names)

    def solutions(self, T) -> tuple[np.ndarray, np.ndarray]:
        """Every inverse solution of one flange pose: (Q (M, n) degrees, codes (M,)). Six-axis
        arms: every branch, principal values, limits not applied; other arms: the model's solutions
        within the limits."""
        self.need_ik()
        if self.opw is not None:
            sols = self.ik_all(T)[0]
            sols = sols[~np.isnan(sols[:, [0, 1, 2, 4, 5]]).any(axis=1)]
            sols[np.isnan(sols[:, 3]), 3] = 0.0
            return sols, (self.config_codes(sols) if len(sols) else np.zeros(0, dtype=int))
        sols = self.model.ik(np.asarray(T)[:3, :4].tolist())
        Q = np.array(sols, dtype=float).reshape(-1, len(self.lo))
        return Q, np.array([self.code_of(self.model.config_of(q)) for q in Q], dtype=int)

    def solve_config(self, T, code: int) -> np.ndarray:
        """Arms without the OPW form: the solution of configuration `code` at each pose (N, n),
        NaN rows where there is none (within the limits)."""
        names = self._configs[code]
        out = np.full((len(T), len(self.lo)), np.nan)
        for i, M in enumerate(np.asarray(T)):
            sols = self.model.ik(M[:3, :4].tolist(), config=names)
            if sols:
                out[i] = sols[0]
        return out

    def ik_all(self, T, branches=None) -> np.ndarray:
        """Every inverse branch (N, 8, 6), degrees, principal values, NaN where a branch does not
        exist; branch index = 4·shoulder + 2·elbow + wrist (`branches`: compute only these).
        Where the wrist is exactly singular j4 is NaN (the caller takes it from its neighbour).
        On the Stäubli arms (no axis sign change, no forearm offset) the branch index is the
        configuration code of 9.7.4 (`branch_is_config`). A geometry setDH changed: each nominal
        branch refined by Newton's method (robot/dh.py), NaN where it does not converge."""
        out = self._ik_nominal(T, branches)
        if self.dh is None:
            return out
        T = np.asarray(T, dtype=float)
        T = T[None] if T.ndim == 2 else T
        flat = out.reshape(-1, 6)
        have = ~np.isnan(flat[:, [0, 1, 2, 4, 5]]).any(axis=1)
        if np.any(have):
            Q0 = np.where(np.isnan(flat[have]), 0.0, flat[have])
            poses = np.repeat(T, out.shape[1], axis=0)[have]
            flat[have] = dh_refine(self.dh, poses, Q0)
        return flat.reshape(out.shape)

    def _ik_nominal(self, T, branches=None) -> np.ndarray:
        """ik_all of the model's closed form (the standard geometry)."""
        self.need_ik()
        o = self.opw
        T = np.asarray(T, dtype=float)
        if T.ndim == 2:
            T = T[None]
        if len(T) <= 2 and branches is None:  # a pose or two: the pure-Python closed form is faster
            out = np.full((len(T), 8, 6), np.nan)
            for i, M in enumerate(T):
                sols = opw_ik(o, M[:3, :4].tolist())
                if len(sols) != 8:  # singular or partly out of reach: branches are not 1 to 1
                    break
                out[i] = np.array(sols) * RAD
            else:
                return out
        if self.Ginv is not None:
            T = T @ self.Ginv
        a1, a2, b, c1, c2, c3, c4 = o.a1, o.a2, o.b, o.c1, o.c2, o.c3, o.c4
        r = T[:, :3, :3]
        px, py, pz = T[:, 0, 3], T[:, 1, 3], T[:, 2, 3]
        cx = px - c4 * r[:, 0, 2]
        cy = py - c4 * r[:, 1, 2]
        cz = pz - c4 * r[:, 2, 2]
        rho2 = cx * cx + cy * cy
        disc = rho2 - b * b
        disc = np.where((disc < 0) & (disc > -1e-9 * np.maximum(rho2, 1.0)), 0.0, disc)
        ksh = np.sqrt(np.where(disc >= 0, disc, np.nan))
        base = np.arctan2(cy, cx)
        kk = math.hypot(c3, a2)
        psi = math.atan2(a2, c3)
        zp = cz - c1
        n = len(T)
        out = np.full((n, 8, 6), np.nan)
        want = set(range(8)) if branches is None else set(branches)
        for sh in (0, 1):
            if not (want & {4 * sh, 4 * sh + 1, 4 * sh + 2, 4 * sh + 3}):
                continue
            uu = -ksh if sh else ksh
            q1 = base - np.arctan2(b, uu)
            xp = uu - a1
            d2 = xp * xp + zp * zp
            cphi = (d2 - c2 * c2 - kk * kk) / (2.0 * c2 * kk)
            cphi = np.where((np.abs(cphi) > 1.0) & (np.abs(cphi) <= 1.0 + 1e-10), np.sign(cphi), cphi)
            phi = np.arccos(np.where(np.abs(cphi) <= 1.0, cphi, np.nan))
            s1, co1 = np.sin(q1), np.cos(q1)
            n00 = co1 * r[:, 0, 0] + s1 * r[:, 1, 0]
            n02 = co1 * r[:, 0, 2] + s1 * r[:, 1, 2]
            n10 = -s1 * r[:, 0, 0] + co1 * r[:, 1, 0]
            n12 = -s1 * r[:, 0, 2] + co1 * r[:, 1, 2]
            alpha = np.arctan2(xp, zp)
            for el in (0, 1):
                if not (want & {4 * sh + 2 * el, 4 * sh + 2 * el + 1}):
                    continue
                ph = -phi if el else phi
                q3 = ph - psi
                q2 = alpha - np.arctan2(kk * np.sin(ph), c2 + kk * np.cos(ph))
                tt = q2 + q3
                ct, st = np.cos(tt), np.sin(tt)
                m00 = ct * n00 - st * r[:, 2, 0]
                m02 = ct * n02 - st * r[:, 2, 2]
                m10, m12 = n10, n12
                m20 = st * n00 + ct * r[:, 2, 0]
                m22 = st * n02 + ct * r[:, 2, 2]
                s5abs = np.hypot(m02, m12)
                q5p = np.arctan2(s5abs, m22)
                exact = s5abs <= WRIST_EXACT
                for wr in (0, 1):
                    if 4 * sh + 2 * el + wr not in want:
                        continue
                    sg = -1.0 if wr else 1.0
                    q5 = sg * q5p
                    q4 = np.where(exact, np.nan, np.arctan2(sg * m12, sg * m02))
                    q4c = np.where(exact, 0.0, q4)
                    c4_, s4_ = np.cos(q4c), np.sin(q4c)
                    c5_, s5_ = np.cos(q5), np.sin(q5)
                    p00 = c4_ * m00 + s4_ * m10
                    p10 = -s4_ * m00 + c4_ * m10
                    q6 = np.arctan2(p10, c5_ * p00 - s5_ * m20)
                    k = 4 * sh + 2 * el + wr
                    out[:, k, 0] = q1
                    out[:, k, 1] = q2
                    out[:, k, 2] = q3
                    out[:, k, 3] = q4
                    out[:, k, 4] = q5
                    out[:, k, 5] = q6
        out *= RAD * self.signs
        return out

    # ---- configurations and singularities ----------------------------------------------------

    def shoulder_value(self, Q) -> np.ndarray:
        """d1·sin(j2) + d2·sin(j2+j3) + δ (mm, 9.7.4.1): the forward distance of the wrist centre."""
        o = self.opw
        Q = np.atleast_2d(np.asarray(Q, dtype=float))
        t2 = Q[:, 1] * DEG * o.signs[1]
        t23 = t2 + Q[:, 2] * DEG * o.signs[2]
        v = o.c2 * np.sin(t2) + o.c3 * np.sin(t23) + o.a1
        if o.a2:
            v = v + o.a2 * np.cos(t23)
        return v

    def config_codes(self, Q) -> np.ndarray:
        """Configuration of 9.7.4 as a code per position: 4·righty + 2·enegative + wnegative (arms
        without the OPW form: an index of their configurations, `config_name`)."""
        self.need_ik()
        Q = np.atleast_2d(np.asarray(Q, dtype=float))
        if self.opw is None:
            return np.array([self.code_of(self.model.config_of(q)) for q in Q], dtype=int)
        s = self.opw.signs
        righty = self.shoulder_value(Q) < 0
        eneg = s[2] * Q[:, 2] < 0
        wneg = s[4] * Q[:, 4] < 0
        return righty.astype(int) * 4 + eneg.astype(int) * 2 + wneg.astype(int)

    def singularity(self, Q) -> Singularity:
        """Distances to the wrist, elbow and shoulder singularities (see `Singularity`). A SCARA
        (9.7.5): elbow = how far j2 is from 0 or ±180° (arm stretched or folded), shoulder = the
        distance of axis 4 from axis 1 (mm); it has no wrist singularity."""
        self.need_ik()
        o = self.opw
        Q = np.atleast_2d(np.asarray(Q, dtype=float))
        if o is None:
            j2 = np.abs(np.remainder(Q[:, 1] + 90.0, 180.0) - 90.0)
            xy = self.fk(Q)[:, :2, 3] if len(Q) else np.zeros((0, 2))
            return Singularity(np.full(len(Q), np.inf), j2, np.hypot(xy[:, 0], xy[:, 1]))
        wrist = np.abs(Q[:, 4])
        psi = math.degrees(math.atan2(o.a2, o.c3))
        elbow = np.abs(Q[:, 2] * o.signs[2] + psi)
        u = self.shoulder_value(Q)
        return Singularity(wrist, elbow, np.abs(u))


CONFIG_NAMES = (("lefty", "righty"), ("epositive", "enegative"), ("wpositive", "wnegative"))


def config_name(code: int) -> tuple[str, str, str]:
    """("righty", "epositive", "wnegative") of a configuration code."""
    return (CONFIG_NAMES[0][(code >> 2) & 1], CONFIG_NAMES[1][(code >> 1) & 1], CONFIG_NAMES[2][code & 1])


def config_code(names) -> int:
    """Inverse of `config_name`."""
    s, e, w = names
    return 4 * (s == "righty") + 2 * (e == "enegative") + (w == "wnegative")


def wrap_near(values: np.ndarray, reference: np.ndarray) -> np.ndarray:
    """values + k·360 nearest reference (element-wise)."""
    return values + 360.0 * np.round((reference - values) / 360.0)
