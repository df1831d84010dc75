"""RobotModel: one six-axis arm (limits, speeds, accelerations, kinematics) and load_robot()."""

from __future__ import annotations

import functools
import math
import os
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Sequence

from . import catalog as _catalog
from .configuration import Config, classify, resolve
from .errors import IKUnsupported, RobotError, Unreachable
from .ik import opw_ik
from .kinematics import DEG, RAD, OPW, Chain, extract_opw, matrix_trsf, trsf_matrix
from .urdf import Mat, inverse, mul, read_urdf

# Acceleration assumed when a URDF gives none (robots/README.md): nominal speed reached in this time.
DEFAULT_RAMP_S = 0.25
LIMIT_TOL_DEG = 1e-7  # a solution this close outside a joint limit is taken as on it


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
    """A six-axis arm. Joint values are VAL 3's: degrees; lengths in millimetres.

    Attributes: name, source (URDF path), srs_arm_id, joint_names, joint_limits ((min, max) deg per
    axis), nominal_speeds (deg/s), accelerations (deg/s², see acceleration_note), max_torques (N·m
    or None), reach_mm, opw (closed-form parameters, None when the arm has none: then ik() raises
    IKUnsupported, with the reason in opw_reason)."""

    name: str
    source: str
    srs_arm_id: str
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

    # ---- limits ---------------------------------------------------------------------------------

    def in_limits(self, joints: Sequence[float]) -> bool:
        """True when every axis is within its software limits (isInRange, 9.2.3)."""
        return all(lo - LIMIT_TOL_DEG <= j <= hi + LIMIT_TOL_DEG for j, (lo, hi) in zip(joints, self.joint_limits))

    def with_accelerations(self, accelerations: Sequence[float], note: str = "given by the user") -> "RobotModel":
        """A copy with other nominal accelerations (deg/s², one per axis)."""
        acc = tuple(float(a) for a in accelerations)
        if len(acc) != 6 or any(not a > 0 for a in acc):
            raise RobotError("accelerations: six positive values in deg/s² are needed")
        return replace(self, accelerations=acc, acceleration_note=note)

    # ---- forward kinematics ---------------------------------------------------------------------

    def fk_matrix(self, joints: Sequence[float], tool=None) -> Mat:
        """The flange (or tool) in the world frame as a 3x4 matrix in mm, joints in degrees."""
        q = [j * DEG for j in joints]
        T = self.opw.fk(q) if self.opw is not None else self.chain.fk(q)
        return T if tool is None else mul(T, _as_matrix(tool))

    def fk(self, joints: Sequence[float], tool=None) -> tuple[float, float, float, float, float, float]:
        """here(flange, world) at these joints: (x, y, z, rx, ry, rz) in mm and degrees (9.3.2)."""
        return matrix_trsf(self.fk_matrix(joints, tool))

    def fk_chain(self, joints: Sequence[float]) -> Mat:
        """The URDF chain multiplied out in pure Python (reference for the closed form)."""
        return self.chain.fk([j * DEG for j in joints])

    def pinocchio(self):
        """(pinocchio.Model, pinocchio.Data) of the URDF (imports pinocchio on first use)."""
        return _pinocchio_model(self.source)

    def collision_model(self):
        """pinocchio.GeometryModel of the collision solids of the URDF."""
        import pinocchio as pin

        model, _ = self.pinocchio()
        return pin.buildGeomFromUrdf(model, self.source, pin.GeometryType.COLLISION)

    def fk_pinocchio(self, joints: Sequence[float]) -> Mat:
        """The flange in the world frame computed by pinocchio (3x4, mm)."""
        import pinocchio as pin

        model, data = self.pinocchio()
        ids = _pin_ids(self.source, self.joint_names, self.world_frame, self.flange_frame)
        q = pin.neutral(model)
        for (idx, nq), j in zip(ids[0], joints):
            a = j * DEG
            if nq == 1:
                q[idx] = a
            else:  # continuous joint: (cos, sin)
                q[idx], q[idx + 1] = math.cos(a), math.sin(a)
        pin.forwardKinematics(model, data, q)
        pin.updateFramePlacement(model, data, ids[2])
        M = ids[3].actInv(data.oMf[ids[2]])  # world^-1 · flange
        R, p = M.rotation, M.translation * 1000.0
        return tuple((float(R[i, 0]), float(R[i, 1]), float(R[i, 2]), float(p[i])) for i in range(3))  # type: ignore[return-value]

    # ---- configurations -------------------------------------------------------------------------

    def config_of(self, joints: Sequence[float]) -> tuple[str, str, str]:
        """(shoulder, elbow, wrist) of a joint position by the formulas of 9.7.4: righty/lefty,
        epositive/enegative, wpositive/wnegative."""
        o = self._need_opw()
        s = o.signs
        return classify(s[1] * joints[1], s[2] * joints[2], s[4] * joints[4], o.c2, o.c3, o.a1, o.a2)

    # ---- inverse kinematics ---------------------------------------------------------------------

    def ik(self, pose, config=None, near: Sequence[float] | None = None, same_from: Sequence[float] | None = None,
           tool=None, all_turns: bool = False) -> list[tuple[float, ...]]:
        """Joint positions (degrees) that put the flange (or `tool`) at `pose` in the world frame.

        pose: a trsf (x, y, z, rx, ry, rz) in mm/deg or a 3x4/4x4 matrix in mm. config: None (all
        free), a Config, or three names ("righty", "esame", "wfree"...). Every branch (up to 8)
        within the joint limits and the configuration comes back. Axes that can turn more than once
        (±270° on j4 and j6) take, per branch, the value nearest `near` (9.6.3), or the one nearest
        0 without `near`; all_turns=True lists every such value instead. `same` fields take the
        configuration of `same_from` (default: `near`). With `near`, the nearest solution comes
        first. An empty list when nothing reaches the pose; `solve()` says why."""
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

    def _need_opw(self) -> OPW:
        if self.opw is None:
            raise IKUnsupported(
                f"{self.name}: no closed-form inverse kinematics: {self.opw_reason}. Only arms with an "
                "ortho-parallel base and a spherical wrist (Stäubli RX/TX/TX2) are supported"
            )
        return self.opw

    def _ik(self, pose, config, near, same_from, tool, all_turns):
        opw = self._need_opw()
        req = Config.parse(config)
        T = _as_matrix(pose)
        if tool is not None:
            T = mul(T, inverse(_as_matrix(tool)))
        ref = same_from if same_from is not None else near
        wanted = resolve(req, self.config_of(ref) if ref is not None else None)
        hint = [v * DEG for v in near] if near is not None else None
        raw = opw_ik(opw, T, hint)
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
                if (abs(q[0] - o[0]) < 1e-9 and abs(q[1] - o[1]) < 1e-9 and abs(q[2] - o[2]) < 1e-9
                        and abs(q[3] - o[3]) < 1e-9 and abs(q[4] - o[4]) < 1e-9 and abs(q[5] - o[5]) < 1e-9):
                    break
            else:
                out.append(q)
        if not out:
            wanted_txt = "/".join(w for w in wanted if w is not None)
            return [], ("config", f"{self.name}: the pose is reachable within the joint limits, but not in configuration {wanted_txt}")
        if near is not None:
            out.sort(key=lambda q: sum((a - b) ** 2 for a, b in zip(q, near)))
        return out, ("", "")

    def _turns(self, raw, near, all_turns) -> list[tuple[float, ...]]:
        """Degrees within the joint limits: per axis, the value (mod 360) nearest near (or 0), or
        every value with all_turns. Solutions with an axis that fits nowhere are dropped."""
        limits = self.joint_limits
        out: list[tuple[float, ...]] = []
        tol = LIMIT_TOL_DEG
        for q in raw:
            vals: list[float] = []
            multi: list[list[float]] | None = None
            for i in range(6):
                lo, hi = limits[i]
                v = math.remainder(q[i] * RAD, 360.0)
                if hi - lo < 360.0 - 2 * tol:  # at most one value fits
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
                cands = [min(max(v + 360.0 * k, lo), hi) for k in range(kmin, kmax + 1)]
                if all_turns and len(cands) > 1:
                    if multi is None:
                        multi = [[x] for x in vals]
                    multi.append(cands)
                    vals.append(cands[0])
                    continue
                target = near[i] if near is not None else 0.0
                best = cands[0]
                for c in cands[1:]:
                    if abs(c - target) < abs(best - target):
                        best = c
                vals.append(best)
                if multi is not None:
                    multi.append([best])
            else:
                if multi is None:
                    out.append(tuple(vals))
                else:
                    import itertools

                    out.extend(itertools.product(*multi))
        return out

    # ---- description ----------------------------------------------------------------------------

    def describe(self) -> dict:
        o = self.opw
        return {
            "name": self.name,
            "srs_arm_id": self.srs_arm_id,
            "source": self.source,
            "reach_mm": round(self.reach_mm, 6),
            "joints": [
                {
                    "name": n,
                    "min_deg": lo,
                    "max_deg": hi,
                    "nominal_speed_deg_s": v,
                    "acceleration_deg_s2": a,
                    "max_torque_nm": t,
                }
                for n, (lo, hi), v, a, t in zip(self.joint_names, self.joint_limits, self.nominal_speeds, self.accelerations, self.max_torques)
            ],
            "acceleration_note": self.acceleration_note,
            "closed_form_ik": o is not None,
            "opw_mm": None if o is None else {k: round(getattr(o, k), 9) for k in ("a1", "a2", "b", "c1", "c2", "c3", "c4")},
        }


# ---- loading --------------------------------------------------------------------------------------


def _clean(x: float) -> float:
    r = round(x, 9)
    return r if abs(r - x) < 1e-9 else x


def from_urdf(path: str | os.PathLike, world_frame: str | None = None, flange_frame: str | None = None,
              name: str | None = None) -> RobotModel:
    """A RobotModel from a URDF. The URDF must say which links are the VAL 3 world and flange frames
    (<val3check world_frame=".." flange_frame=".."/>), unless world_frame/flange_frame are given."""
    info = read_urdf(path)
    meta = info.meta or {}
    world = world_frame or meta.get("world_frame")
    flange = flange_frame or meta.get("flange_frame")
    missing = [a for a, v in (("world_frame", world), ("flange_frame", flange)) if not v]
    if missing:
        if info.meta is None:
            raise RobotError(
                f"{info.path}: no <val3check> element: a URDF must name the links that are the VAL 3 world "
                'and flange frames, e.g. <val3check arm="MyArm" world_frame="base" flange_frame="tool0"/> '
                "inside <robot> (robots/README.md)"
            )
        raise RobotError(f"{info.path}: <val3check> lacks {' and '.join(missing)} (the links of the VAL 3 world and flange frames)")
    chain = Chain(info, world, flange)
    joints = chain.joints
    speeds = tuple(_clean(j.velocity * RAD) for j in joints)
    accs, notes = [], set()
    for j, v in zip(joints, speeds):
        given = info.meta_joints.get(j.name, {}).get("acceleration_deg_s2")
        if given is not None:
            try:
                a = float(given)
            except ValueError:
                raise RobotError(f"{info.path}: joint {j.name!r}: acceleration_deg_s2={given!r} is not a number") from None
            if not a > 0:
                raise RobotError(f"{info.path}: joint {j.name!r}: acceleration_deg_s2 must be positive")
            accs.append(a)
        else:
            accs.append(v / DEFAULT_RAMP_S)
            notes.add("default")
    rule = meta.get("acceleration_rule", "")
    if notes:
        note = f"assumed (not in the URDF): nominal speed reached in {DEFAULT_RAMP_S:g} s from rest"
    else:
        note = f"from the URDF: {rule}" if rule else "from the URDF"
    opw, why = extract_opw(chain)
    if opw is not None:
        reach = opw.a1 + opw.c2 + math.hypot(opw.c3, opw.a2) + opw.c4
    else:  # upper bound: the lengths of the links after axis 1, end to end
        reach = sum(math.sqrt(sum(j.before[i][3] ** 2 for i in range(3))) for j in joints[1:])
        reach += math.sqrt(sum(chain.tip[i][3] ** 2 for i in range(3)))
    return RobotModel(
        name=name or meta.get("arm") or info.robot_name or Path(info.path).stem,
        source=info.path,
        srs_arm_id=meta.get("srs_arm_id", ""),
        joint_names=tuple(j.name for j in joints),
        joint_limits=tuple((_clean(j.lower * RAD), _clean(j.upper * RAD)) for j in joints),
        nominal_speeds=speeds,
        accelerations=tuple(accs),
        acceleration_note=note,
        max_torques=tuple(j.effort for j in joints),
        reach_mm=reach,
        chain=chain,
        opw=opw,
        opw_reason=why,
        world_frame=world,
        flange_frame=flange,
    )


@functools.lru_cache(maxsize=None)
def _catalog_model(name: str) -> RobotModel:
    return from_urdf(_catalog.catalog()[name]["path"])


def load_robot(spec: str | os.PathLike | None, app_path: str | os.PathLike | None = None) -> RobotModel:
    """A robot by catalogue name (case-insensitive: 'tx2-60', 'TX2_60'), by URDF path, by arm.cfx
    path, or — spec None — from the usr/configs/arm.cfx of the controller tree holding app_path."""
    if spec is None or str(spec) == "":
        if app_path is None:
            raise RobotError("no robot named and no application to find a controller tree (arm.cfx) from")
        cfx = _catalog.find_arm_cfx(app_path)
        if cfx is None:
            raise RobotError(
                f"no usr/configs/arm.cfx above {app_path}: name the arm with --robot "
                f"(one of {', '.join(_catalog.names())}, or a URDF)"
            )
        return _catalog_model(_catalog.find_srs(_catalog.read_arm_cfx(cfx)))
    text = os.fspath(spec)
    low = text.lower()
    if low.endswith(".cfx"):
        return _catalog_model(_catalog.find_srs(_catalog.read_arm_cfx(text)))
    if low.endswith((".urdf", ".xml")) or os.path.sep in text or os.path.isfile(text):
        if not os.path.isfile(text):
            raise RobotError(f"{text}: no such URDF file")
        return from_urdf(text)
    return _catalog_model(_catalog.find(text))


# ---- pinocchio, loaded lazily -------------------------------------------------------------------


@functools.lru_cache(maxsize=None)
def _pinocchio_model(path: str):
    import pinocchio as pin

    model = pin.buildModelFromUrdf(path)
    return model, model.createData()


@functools.lru_cache(maxsize=None)
def _pin_ids(path: str, joint_names: tuple[str, ...], world: str, flange: str):
    model, data = _pinocchio_model(path)
    import pinocchio as pin

    qidx = []
    for n in joint_names:
        jid = model.getJointId(n)
        qidx.append((model.joints[jid].idx_q, model.joints[jid].nq))
    wid, fid = model.getFrameId(world), model.getFrameId(flange)
    pin.framesForwardKinematics(model, data, pin.neutral(model))
    world_placement = data.oMf[wid].copy()  # fixed to the base: any q gives it
    return qidx, wid, fid, world_placement
