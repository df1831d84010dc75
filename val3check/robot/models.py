"""RobotModel: one arm (six-axis RX/TX or SCARA RS/TS): limits, speeds, accelerations, kinematics."""

from __future__ import annotations

import functools
import itertools
import math
from dataclasses import replace
from typing import Sequence

from ..lengths import M_MM
from ..light_dataclass import dataclass, field
from . import overrides
from . import scara as _scara
from .configuration import Config, classify, resolve
from .errors import IKUnsupported, RobotError, Unreachable
from .ik import opw_ik
from .kinematics import DEG, RAD, OPW, Chain, matrix_trsf, trsf_matrix
from .provenance import Provenance
from .urdf import IDENTITY, Mat, inverse, mul

# Where accelerations are assumed (no measured values), cycle times are to be given with the range
# they take for accelerations this many times the assumption (issue 23: half and twice).
ASSUMED_ACCELERATION_RANGE = (0.5, 2.0)
LIMIT_TOL_DEG = 1e-7  # a solution this close outside a joint limit is taken as on it (deg, or mm)

FAMILY_TYPES = {"six-axis": "Rx", "scara": "Rs"}  # VAL 3 type family: pointRx/jointRx/configRx, pointRs…

# The world frame turned into the cell (Z up, against gravity) for each mount (robots/README.md,
# "Mounting"). The VAL 3 world is attached to the arm's base; the mount only places it in the cell.
_MOUNT_ROTATION = {
    ("six-axis", "floor"): IDENTITY,
    ("six-axis", "ceiling"): ((1.0, 0.0, 0.0, 0.0), (0.0, -1.0, 0.0, 0.0), (0.0, 0.0, -1.0, 0.0)),  # Rx(180)
    ("six-axis", "wall"): ((0.0, 0.0, 1.0, 0.0), (0.0, 1.0, 0.0, 0.0), (-1.0, 0.0, 0.0, 0.0)),  # Ry(90): axis 1 horizontal
    ("scara", "floor"): IDENTITY,
    ("scara", "wall"): IDENTITY,  # Stäubli's "WA" SCARA: a console on a wall, axes still vertical
    ("scara", "ceiling"): ((1.0, 0.0, 0.0, 0.0), (0.0, -1.0, 0.0, 0.0), (0.0, 0.0, -1.0, 0.0)),
}


def _as_matrix(pose) -> Mat:
    """A VAL 3 trsf {x,y,z,rx,ry,rz} (mm, deg) or a 3x4/4x4 matrix (mm) -> 3x4."""
    if len(pose) == 6 and not hasattr(pose[0], "__len__"):
        return trsf_matrix(pose)
    rows = tuple(tuple(float(v) for v in pose[i][:4]) for i in range(3))
    if any(len(r) != 4 for r in rows):
        raise RobotError("a pose is a trsf (x, y, z, rx, ry, rz) or a 3x4/4x4 matrix")
    return rows  # type: ignore[return-value]


@dataclass
class RobotModel:
    """An arm. Joint values are VAL 3's: degrees, and millimetres for the prismatic axis 3 of a
    SCARA; lengths in millimetres.

    Attributes: name, source (URDF path), srs_arm_id, family ("six-axis" | "scara"),
    joint_names, joint_kinds ("revolute" | "prismatic" per axis), joint_limits ((min, max) per
    axis), nominal_speeds (deg/s or mm/s), accelerations (deg/s² or mm/s², see
    acceleration_note), accelerations_assumed (True unless measured values were given: the
    reports then state the range for ASSUMED_ACCELERATION_RANGE), max_torques (N·m or None),
    reach_mm, provenance (facts, assumptions, alternatives, missing values), mount, notes (how
    the model was chosen). Closed forms: opw
    (six-axis) or scara; without one, ik() raises IKUnsupported with the reason in opw_reason."""

    name: str
    source: str
    srs_arm_id: str  # as arm.cfx writes it (seen in a real controller tree), or "" (see srs_arm_id_hint)
    joint_names: tuple[str, ...]
    joint_limits: tuple[tuple[float, float], ...]
    nominal_speeds: tuple[float, ...]
    accelerations: tuple[float, ...]
    acceleration_note: str
    max_torques: tuple[float | None, ...]
    reach_mm: float
    chain: Chain = field(repr=False)
    opw: OPW | None = field(repr=False)
    opw_reason: str = ""
    world_frame: str = "world"
    flange_frame: str = "flange"
    family: str = "six-axis"
    joint_kinds: tuple[str, ...] = ()
    scara: _scara.Scara | None = field(default=None, repr=False)
    stroke_mm: float | None = None  # SCARA: nominal stroke of axis 3
    series: str = ""  # TX2, TX, RX, TS2, TS, TP… (catalogue models)
    provenance: Provenance = field(default_factory=Provenance, repr=False)
    mount: str = "floor"
    native_mount: str = "floor"  # the mount the kinematic description is written for (TP80: ceiling)
    notes: tuple[str, ...] = ()
    srs_arm_id_hint: str = ""  # an id inferred (not seen in a real arm.cfx), matched all the same
    # internal value = sign × VAL 3 value, per axis (an override of an axis direction)
    joint_signs: tuple[int, ...] = ()
    world_shift: Mat | None = field(default=None, repr=False)  # world moved from the URDF's world link
    # no measured accelerations: an assumption (a family rule, or the default ramp), robots/README.md
    accelerations_assumed: bool = True

    def __post_init__(self) -> None:
        if not self.joint_kinds:
            self.joint_kinds = tuple(j.kind for j in self.chain.joints)
        if not self.joint_signs:
            self.joint_signs = (1,) * len(self.joint_kinds)

    # ---- identity ---------------------------------------------------------------------------------

    @property
    def type_family(self) -> str:
        """The VAL 3 type family of the arm: "Rx" (pointRx, jointRx, configRx) or "Rs" (SCARA)."""
        return FAMILY_TYPES[self.family]

    @property
    def axes(self) -> int:
        return len(self.joint_limits)

    @property
    def joint_units(self) -> tuple[str, ...]:
        """"deg" or "mm" per axis (a prismatic axis is a length: the application's length unit)."""
        return tuple("mm" if k == "prismatic" else "deg" for k in self.joint_kinds)

    @property
    def config_fields(self) -> tuple[str, ...]:
        """The fields of this arm's config (9.7.2): shoulder, elbow, wrist; shoulder only for RS/TS."""
        return ("shoulder",) if self.family == "scara" else ("shoulder", "elbow", "wrist")

    @property
    def world_in_cell(self) -> Mat:
        """The VAL 3 world frame in a cell frame whose Z points up (against gravity), for the mount
        (a rotation; robots/README.md "Mounting")."""
        if self.mount == self.native_mount:
            return IDENTITY
        R = _MOUNT_ROTATION[(self.family, self.mount)]
        N = _MOUNT_ROTATION[(self.family, self.native_mount)]
        return mul(R, inverse(N))

    @property
    def assumed(self) -> frozenset[str]:
        """Keys of the values that are assumptions rather than public facts (provenance)."""
        return self.provenance.assumed()

    # ---- limits ---------------------------------------------------------------------------------

    def in_limits(self, joints: Sequence[float]) -> bool:
        """True when every axis is within its software limits (isInRange, 9.2.3)."""
        return all(lo - LIMIT_TOL_DEG <= j <= hi + LIMIT_TOL_DEG for j, (lo, hi) in zip(joints, self.joint_limits))

    def with_accelerations(self, accelerations: Sequence[float], note: str = "given by the user",
                           assumed: bool = False) -> "RobotModel":
        """A copy with other nominal accelerations (deg/s² or mm/s², one per axis): given values
        (measured: no uncertainty range) unless `assumed`."""
        acc = tuple(float(a) for a in accelerations)
        if len(acc) != self.axes or any(not a > 0 for a in acc):
            raise RobotError(f"accelerations: {self.axes} positive values (deg/s², mm/s² for a prismatic axis) are needed")
        return replace(self, accelerations=acc, acceleration_note=note, accelerations_assumed=assumed)

    def with_acceleration_scale(self, factor: float) -> "RobotModel":
        """A copy with every acceleration (and deceleration) times `factor`, the rest unchanged:
        re-timing the same paths with ASSUMED_ACCELERATION_RANGE gives a cycle time's range."""
        if not factor > 0:
            raise RobotError("an acceleration scale must be positive")
        return replace(self, accelerations=tuple(a * factor for a in self.accelerations),
                       acceleration_note=f"{self.acceleration_note} (× {factor:g})")

    def with_assumptions(self, values: dict) -> "RobotModel":
        """A copy with the user's values in place of assumptions (overrides.KEYS: nominal_speeds,
        accelerations, ramp_s, limits, max_torques, mount, world_z_mm, axis3_sign, axis4_sign)."""
        return overrides.apply(self, values, by="user")

    # ---- joint values <-> the kinematics' internal values ------------------------------------------

    def _internal(self, joints: Sequence[float]) -> list[float]:
        """VAL 3 joint values -> radians (mm for a prismatic axis), axis signs applied."""
        return [s * (j if k == "prismatic" else j * DEG) for j, k, s in zip(joints, self.joint_kinds, self.joint_signs)]

    # ---- forward kinematics ---------------------------------------------------------------------

    def fk_matrix(self, joints: Sequence[float], tool=None) -> Mat:
        """The flange (or tool) in the world frame as a 3x4 matrix in mm; joints in degrees (mm for
        a SCARA's axis 3)."""
        q = self._internal(joints)
        if self.opw is not None:
            T = self.opw.fk(q)
        elif self.scara is not None:
            T = self.scara.fk(q)
        else:
            T = self.chain.fk(q)
        return T if tool is None else mul(T, _as_matrix(tool))

    def fk(self, joints: Sequence[float], tool=None) -> tuple[float, float, float, float, float, float]:
        """here(flange, world) at these joints: (x, y, z, rx, ry, rz) in mm and degrees (9.3.2)."""
        return matrix_trsf(self.fk_matrix(joints, tool))

    def fk_chain(self, joints: Sequence[float]) -> Mat:
        """The URDF chain multiplied out in pure Python (reference for the closed form)."""
        return self.chain.fk(self._internal(joints))

    def pinocchio(self):
        """(pinocchio.Model, pinocchio.Data) of the URDF (imports pinocchio on first use)."""
        return pinocchio_model(self.source)

    def collision_model(self):
        """pinocchio.GeometryModel of the collision solids of the URDF."""
        import pinocchio as pin

        model, _ = self.pinocchio()
        return pin.buildGeomFromUrdf(model, self.source, pin.GeometryType.COLLISION)

    def fk_pinocchio(self, joints: Sequence[float]) -> Mat:
        """The flange in the world frame computed by pinocchio (3x4, mm)."""
        import pinocchio as pin

        model, data = self.pinocchio()
        ids = pinocchio_ids(self.source, self.joint_names, self.world_frame, self.flange_frame)
        q = pin.neutral(model)
        for (idx, nq), v, kind in zip(ids[0], self._internal(joints), self.joint_kinds):
            if kind == "prismatic":
                q[idx] = v / M_MM  # pinocchio works in metres
            elif nq == 1:
                q[idx] = v
            else:  # continuous joint: (cos, sin)
                q[idx], q[idx + 1] = math.cos(v), math.sin(v)
        pin.forwardKinematics(model, data, q)
        pin.updateFramePlacement(model, data, ids[2])
        M = ids[3].actInv(data.oMf[ids[2]])  # world^-1 · flange
        R, p = M.rotation, M.translation * M_MM
        T = tuple((float(R[i, 0]), float(R[i, 1]), float(R[i, 2]), float(p[i])) for i in range(3))
        return T if self.world_shift is None else mul(inverse(self.world_shift), T)  # type: ignore[return-value,arg-type]

    # ---- configurations -------------------------------------------------------------------------

    def config_of(self, joints: Sequence[float]) -> tuple[str, ...]:
        """The configuration of a joint position: (shoulder, elbow, wrist) by the formulas of 9.7.4
        for a six-axis arm (righty/lefty, epositive/enegative, wpositive/wnegative); (shoulder,)
        for a SCARA, righty when sin(j2) > 0 (9.7.5)."""
        if self.family == "scara":
            self._need_closed_form()
            return (_scara.classify(joints[1]),)
        o = self._need_closed_form()
        s = o.signs
        g = self.joint_signs
        return classify(s[1] * g[1] * joints[1], s[2] * g[2] * joints[2], s[4] * g[4] * joints[4], o.c2, o.c3, o.a1, o.a2)

    def singularities(self, joints: Sequence[float], tol_deg: float = 1e-3, tol_mm: float = 1e-3) -> tuple[str, ...]:
        """The singular positions `joints` is at (within the tolerances): "wrist" (j5 = 0),
        "elbow" (six-axis: arm stretched or folded; SCARA: arm stretched or folded, sin(j2) = 0),
        "shoulder" (the wrist centre, or a SCARA's axis 4, on axis 1)."""
        out = []
        q = self._internal(joints)
        if self.family == "scara":
            sc = self._need_closed_form()
            beta = sc.elbow_angle(q[1])
            if abs(math.sin(beta)) < math.sin(tol_deg * DEG):
                out.append("elbow")
            u, v = q[0] * sc.signs[0] + sc.alpha1, q[0] * sc.signs[0] + beta + sc.alpha1
            if math.hypot(sc.l1 * math.cos(u) + sc.l2 * math.cos(v), sc.l1 * math.sin(u) + sc.l2 * math.sin(v)) < tol_mm:
                out.append("shoulder")
            return tuple(out)
        o = self._need_closed_form()
        s = o.signs
        t2, t3, t5 = s[1] * q[1], s[2] * q[2], s[4] * q[4]
        psi = math.atan2(o.a2, o.c3)
        if abs(math.sin(t3 + psi)) < math.sin(tol_deg * DEG):
            out.append("elbow")
        if abs(math.sin(t5)) < math.sin(tol_deg * DEG):
            out.append("wrist")
        # the wrist centre's forward distance from axis 1 in the arm's plane (9.7.4.1): 0 where the
        # two shoulder branches meet (on axis 1 when b = 0)
        fwd = o.a1 + o.c2 * math.sin(t2) + o.c3 * math.sin(t2 + t3) + o.a2 * math.cos(t2 + t3)
        if abs(fwd) < tol_mm:
            out.append("shoulder")
        return tuple(out)

    # ---- inverse kinematics ---------------------------------------------------------------------

    def ik(self, pose, config=None, near: Sequence[float] | None = None, same_from: Sequence[float] | None = None,
           tool=None, all_turns: bool = False) -> list[tuple[float, ...]]:
        """Joint positions that put the flange (or `tool`) at `pose` in the world frame.

        pose: a trsf (x, y, z, rx, ry, rz) in mm/deg or a 3x4/4x4 matrix in mm. config: None (all
        free), a Config, or names ("righty", "esame", "wfree"...; a SCARA: ("righty",) or three
        fields whose elbow and wrist are same/free). Every branch (up to 8; 2 for a SCARA) within
        the joint limits and the configuration comes back. Axes that can turn more than once (±270°
        on j4 and j6, ±500° on a SCARA's j4) take, per branch, the value nearest `near` (9.6.3), or
        the one nearest 0 without `near`; all_turns=True lists every such value instead. `same`
        fields take the configuration of `same_from` (default: `near`). With `near`, the nearest
        solution comes first. An empty list when nothing reaches the pose; `solve()` says why."""
        sols, _ = self._ik(pose, config, near, same_from, tool, all_turns)
        return sols

    def point_to_joint(self, pose, config=None, initial: Sequence[float] | None = None, tool=None):
        """pointToJoint (9.6.3): the solution nearest `initial` in the requested configuration
        (`same` relative to `initial`), or None when there is none."""
        sols, _ = self._ik(pose, config, initial, initial, tool, False)
        return sols[0] if sols else None

    def solve(self, pose, config=None, initial: Sequence[float] | None = None, tool=None) -> tuple[float, ...]:
        """Like point_to_joint, but raises Unreachable (reason "reach", "limits" or "config") —
        what movej needs to report an error rather than a nearby wrong answer."""
        sols, why = self._ik(pose, config, initial, initial, tool, False)
        if not sols:
            raise Unreachable(why[1], why[0])
        return sols[0]

    def _need_closed_form(self):
        if self.opw is not None:
            return self.opw
        if self.scara is not None:
            return self.scara
        if self.family == "scara":
            raise IKUnsupported(f"{self.name}: no closed-form inverse kinematics: {self.opw_reason}. A SCARA needs its "
                                "four axes vertical, axis 3 prismatic")
        raise IKUnsupported(
            f"{self.name}: no closed-form inverse kinematics: {self.opw_reason}. Only arms with an "
            "ortho-parallel base and a spherical wrist (Stäubli RX/TX/TX2) are supported"
        )

    def _ik(self, pose, config, near, same_from, tool, all_turns):
        solver = self._need_closed_form()
        scara = self.family == "scara"
        req = Config.parse(config, scara=scara)
        T = _as_matrix(pose)
        if tool is not None:
            T = mul(T, inverse(_as_matrix(tool)))
        ref = same_from if same_from is not None else near
        ref_cfg = self.config_of(ref) if ref is not None else None
        wanted = resolve(req, ref_cfg)
        hint = self._internal(near) if near is not None else None
        if scara:
            raw, why = _scara.scara_ik(solver, T, hint)
            if why == "orientation":
                return [], ("reach", f"{self.name}: a SCARA only turns its flange about the vertical: the target's Z "
                                     "axis is tilted from the flange's")
        else:
            raw = self._branches(solver, T, hint)
        if not raw:
            return [], ("reach", f"{self.name}: the pose is out of the arm's reach")
        in_limits = self._turns(raw, near, all_turns)
        if not in_limits:
            return [], ("limits", f"{self.name}: the pose is within reach but outside the joint limits")
        out: list[tuple[float, ...]] = []
        for q in in_limits:
            if wanted != (None, None, None):
                c = self.config_of(q)
                if any(w is not None and w != v for w, v in zip(wanted, c)):
                    continue
            for o in out:  # two branches that meet at a singular position come back once
                for a, b in zip(q, o):
                    if abs(a - b) >= 1e-9:
                        break
                else:
                    break
            else:
                out.append(q)
        if not out:
            wanted_txt = "/".join(w for w in wanted if w is not None)
            return [], ("config", f"{self.name}: the pose is reachable within the joint limits, but not in configuration {wanted_txt}")
        if near is not None:
            out.sort(key=lambda q: sum((a - b) ** 2 for a, b in zip(q, near)))
        return out, ("", "")

    def _branches(self, solver, T, hint) -> list:
        """Every inverse branch of the six-axis closed form (radians; absolute.py refines them)."""
        return opw_ik(solver, T, hint)

    def _turns(self, raw, near, all_turns) -> list[tuple[float, ...]]:
        """VAL 3 values within the joint limits: per revolute axis, the value (mod 360) nearest
        near (or 0), or every value with all_turns. Solutions with an axis that fits nowhere are
        dropped."""
        out: list[tuple[float, ...]] = []
        tol = LIMIT_TOL_DEG
        axes = self._axes_spec()
        for q in raw:
            vals: list[float] = []
            multi: list[list[float]] | None = None
            for i, (prismatic, sign, lo, hi, single) in enumerate(axes):
                if prismatic:
                    v = sign * q[i]
                    if v < lo - tol or v > hi + tol:
                        break
                    v = lo if v < lo else hi if v > hi else v
                    vals.append(v)
                    if multi is not None:
                        multi.append([v])
                    continue
                v = math.remainder((q[i] if sign == 1 else -q[i]) * RAD, 360.0)
                if single:  # at most one value fits
                    if v < lo - tol:
                        v += 360.0
                    elif v > hi + tol:
                        v -= 360.0
                    if v < lo - tol or v > hi + tol:
                        break
                    v = lo if v < lo else hi if v > hi else v
                    vals.append(v)
                    if multi is not None:
                        multi.append([v])
                    continue
                kmin = math.ceil((lo - tol - v) / 360.0)
                kmax = math.floor((hi + tol - v) / 360.0)
                if kmin > kmax:
                    break
                if all_turns and kmax > kmin:
                    cands = [min(max(v + 360.0 * k, lo), hi) for k in range(kmin, kmax + 1)]
                    if multi is None:
                        multi = [[x] for x in vals]
                    multi.append(cands)
                    vals.append(cands[0])
                    continue
                # the turn nearest the target (ties: the lower one)
                target = near[i] if near is not None else 0.0
                k = math.ceil((target - v) / 360.0 - 0.5)
                k = kmin if k < kmin else kmax if k > kmax else k
                best = v + 360.0 * k
                best = lo if best < lo else hi if best > hi else best
                vals.append(best)
                if multi is not None:
                    multi.append([best])
            else:
                if multi is None:
                    out.append(tuple(vals))
                else:
                    out.extend(itertools.product(*multi))
        return out

    def _axes_spec(self) -> tuple:
        """Per axis: (prismatic, sign, min, max, at most one turn fits), for _turns."""
        key = (self.joint_limits, self.joint_kinds, self.joint_signs)
        cached = self.__dict__.get("_spec")
        if cached is None or cached[0] != key:
            spec = tuple((k == "prismatic", s, lo, hi, hi - lo < 360.0 - 2 * LIMIT_TOL_DEG)
                         for (lo, hi), k, s in zip(self.joint_limits, self.joint_kinds, self.joint_signs))
            cached = self.__dict__["_spec"] = (key, spec)
        return cached[1]

    # ---- description ----------------------------------------------------------------------------

    def describe(self) -> dict:
        o, sc, pv = self.opw, self.scara, self.provenance
        return {
            "name": self.name,
            "family": self.family,
            "type_family": self.type_family,
            "series": self.series,
            "srs_arm_id": self.srs_arm_id or None,
            "srs_arm_id_hint": self.srs_arm_id_hint or None,
            "source": self.source,
            "reach_mm": round(self.reach_mm, 6),
            "stroke_mm": self.stroke_mm,
            "mount": self.mount,
            "joints": [
                {
                    "name": n,
                    "kind": k,
                    "unit": u,
                    "min_deg" if u == "deg" else "min_mm": lo,
                    "max_deg" if u == "deg" else "max_mm": hi,
                    "nominal_speed_deg_s" if u == "deg" else "nominal_speed_mm_s": v,
                    "acceleration_deg_s2" if u == "deg" else "acceleration_mm_s2": a,
                    "max_torque_nm" if u == "deg" else "max_force_n": t,
                }
                for n, k, u, (lo, hi), v, a, t in zip(self.joint_names, self.joint_kinds, self.joint_units, self.joint_limits,
                                                      self.nominal_speeds, self.accelerations, self.max_torques)
            ],
            "acceleration_note": self.acceleration_note,
            "accelerations_assumed": self.accelerations_assumed,
            "closed_form_ik": o is not None or sc is not None,
            "opw_mm": None if o is None else {k: round(getattr(o, k), 9) for k in ("a1", "a2", "b", "c1", "c2", "c3", "c4")},
            "scara_mm": None if sc is None else {"l1": round(sc.l1, 9), "l2": round(sc.l2, 9), "z0": round(sc.z0, 9),
                                                 "axis_signs": list(sc.signs)},
            "facts": [{"key": f.key, "source": f.text} for f in pv.facts],
            "assumptions": [{"key": a.key, "value": a.value, "why": a.text, "by": a.by} for a in pv.assumptions],
            "alternatives": [{"key": a.key, "chosen": a.chosen, "other": a.other, "why": a.text} for a in pv.alternatives],
            "missing": [{"key": m.key, "why": m.text} for m in pv.missing],
            "notes": list(self.notes),
        }


# ---- pinocchio, loaded lazily -------------------------------------------------------------------


@functools.lru_cache(maxsize=None)
def pinocchio_model(path: str):
    import pinocchio as pin

    model = pin.buildModelFromUrdf(path)
    return model, model.createData()


@functools.lru_cache(maxsize=None)
def pinocchio_ids(path: str, joint_names: tuple[str, ...], world: str, flange: str):
    model, data = pinocchio_model(path)
    import pinocchio as pin

    qidx = []
    for n in joint_names:
        jid = model.getJointId(n)
        qidx.append((model.joints[jid].idx_q, model.joints[jid].nq))
    wid, fid = model.getFrameId(world), model.getFrameId(flange)
    pin.framesForwardKinematics(model, data, pin.neutral(model))
    world_placement = data.oMf[wid].copy()  # fixed to the base: any q gives it
    return qidx, wid, fid, world_placement
