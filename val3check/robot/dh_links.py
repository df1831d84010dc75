"""The links of an arm whose geometry setDH changed (11.4): each link moves with the joint that
carries it, in the DH geometry in force.

A link carried by joint k is fixed in joint k's frame; with the nominal parameters that frame is
Z_k(q) (dh.frames_many, after the joint's rotation) and the link's pose P(q) (links.ArmLinks, the
URDF); with the new parameters the frame is Z'_k(q), so the link is at Z'_k(q)·Z_k(q)⁻¹·P(q).
Links on the base (no joint) do not move; the flange link and the links below it follow the
flange of the new parameters (its last factors, d[6]). The motion bound of the collision checks
(`reach_from_joint`) grows by what the new parameters can add to a distance.
"""

from __future__ import annotations

import math

import numpy as np

from . import dh as _dh


class DHLinks:
    """`links.ArmLinks` of `model` (an AbsoluteRobot) in its DH geometry; everything but the poses
    and the reach bound is the nominal links' (the tree, the solids, the joints)."""

    def __init__(self, base, model) -> None:
        self.base = base
        self.dh = model.dh
        self.nominal = model.dh_nominal
        dl = sum(abs(x - y) for n in ("d", "a", "b") for x, y in zip(self.dh.values(n), self.nominal.values(n)))
        da = sum(abs(math.remainder(x - y, 360.0)) for n in ("theta", "alpha", "beta")
                 for x, y in zip(self.dh.values(n), self.nominal.values(n)))
        self.extra_reach = dl + math.radians(da) * (model.reach_mm + dl)
        # the flange link and the links below it follow the flange (the last factors of 11.4.1)
        self.on_flange = set()
        for link in base.links:
            n = link
            while n != base.root and n != model.flange_frame:
                n = base.edges[n].parent
            if n == model.flange_frame:
                self.on_flange.add(link)

    def __getattr__(self, name):
        return getattr(self.base, name)

    def _corrections(self, Q) -> np.ndarray:
        """(N, 7, 4, 4): Z'_k(q)·Z_k(q)⁻¹ for each joint k, then the same for the flange."""
        Q = np.atleast_2d(np.asarray(Q, dtype=float))
        new, new_flange = _dh.frames_many(self.dh, Q)
        old, old_flange = _dh.frames_many(self.nominal, Q)
        out = np.empty((len(Q), 7, 4, 4))
        for k in range(6):
            rn = _dh._rz_many(Q[:, k] + self.dh.theta[k])
            ro = _dh._rz_many(Q[:, k] + self.nominal.theta[k])
            out[:, k] = (new[:, k] @ rn) @ np.linalg.inv(old[:, k] @ ro)
        out[:, 6] = new_flange @ np.linalg.inv(old_flange)
        return out

    def _slot(self, link: str) -> int | None:
        """Which correction moves `link`: its joint's, the flange's, or none (the base)."""
        if link in self.on_flange:
            return 6
        movers = self.base.movers(link)
        return movers[-1] if movers else None

    def poses(self, q) -> dict[str, np.ndarray]:
        """{link: 4x4 pose in world (mm)} at one joint position."""
        P = self.base.poses(q)
        C = self._corrections([q])[0]
        for link in self.base.links:
            k = self._slot(link)
            if k is not None:
                P[link] = C[k] @ P[link]
        return P

    def poses_many(self, Q, links=None) -> dict[str, np.ndarray]:
        """{link: (N, 4, 4)} at N joint positions (`links`: as ArmLinks.poses_many)."""
        P = self.base.poses_many(Q, links)
        C = self._corrections(Q)
        out = {}
        for link, T in P.items():
            k = self._slot(link)
            out[link] = T if k is None else C[:, k] @ T
        return out

    def reach_from_joint(self, link: str) -> dict[int, float]:
        """The nominal bound plus what the new parameters can add to a distance."""
        return {k: r + self.extra_reach for k, r in self.base.reach_from_joint(link).items()}
