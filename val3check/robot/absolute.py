"""An arm whose geometry setDH changed (11.4, "robot absolu"): the same model, with the forward
kinematics of its DH parameters (dh.py) and an inverse that refines the nominal closed form's
branches by Newton's method on them.

    m2 = with_dh(model, dh)        # an AbsoluteRobot; with_dh(m2, nominal) gives one too
    m2.fk_matrix(joints); m2.ik(pose, config, near); m2.dh; m2.dh_nominal

Everything else is the model's: limits, speeds, and the configuration of a joint position, by the
formulas of 9.7.4 (11.4.3: "La notion de configuration du bras (type de configuration) ne peut
plus être rigoureuse").
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from . import dh as _dh
from .models import RobotModel
from .urdf import mul

DEG = math.pi / 180.0


@dataclass
class AbsoluteRobot(RobotModel):
    """See the module docstring: `dh` the geometry in force, `dh_nominal` the model's standard one."""

    dh: _dh.DH | None = None
    dh_nominal: _dh.DH | None = None

    def fk_matrix(self, joints, tool=None):
        """The flange (or tool) in world (3x4, mm) by the DH product of 11.4.1."""
        F = _dh.fk(self.dh, [float(v) for v in joints])
        T = tuple(tuple(float(v) for v in F[i]) for i in range(3))
        if tool is None:
            return T
        from .models import _as_matrix

        return mul(T, _as_matrix(tool))

    def _branches(self, solver, T, hint) -> list:
        """The nominal branches, each refined for the DH geometry; a branch that does not converge
        (near a singular position or a joint limit, 11.4.3) is left out."""
        raw = super()._branches(solver, T, hint)
        if not raw:
            return raw
        signs = np.array(self.joint_signs, dtype=float)
        Q0 = np.array(raw, dtype=float) / DEG * signs
        M = np.eye(4)
        M[:3, :4] = np.array(T, dtype=float)
        Q = _dh.refine(self.dh, np.repeat(M[None], len(Q0), axis=0), Q0)
        return [tuple(float(v) for v in q * DEG * signs) for q in Q if np.all(np.isfinite(q))]


def with_dh(model: RobotModel, dh: _dh.DH) -> AbsoluteRobot:
    """`model` with the geometry `dh` (its nominal parameters kept in `dh_nominal`)."""
    nominal = getattr(model, "dh_nominal", None) or _dh.nominal_dh(model)
    fields = {f: getattr(model, f) for f in model.__dataclass_fields__ if f not in ("dh", "dh_nominal")}
    if isinstance(model, AbsoluteRobot):
        return replace(model, dh=dh)
    out = AbsoluteRobot(**fields, dh=dh, dh_nominal=nominal)
    out.__dict__.pop("_spec", None)
    return out
