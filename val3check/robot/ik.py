"""Closed-form inverse kinematics of an ortho-parallel arm with a spherical wrist (all 8 branches).

After Brandstötter, Angerer, Hofbaur, "An analytical solution of the inverse kinematics problem of
industrial serial manipulators with an ortho-parallel basis and a spherical wrist" (Austrian
Robotics Workshop 2014), written here from the geometry (kinematics.OPW):

  wrist centre  C = P - c4·R·z                    (P, R: the OPW flange pose in the world frame)
  axis 1        with ρ² = Cx² + Cy², u = ±√(ρ² - b²) (the shoulder branches), q1 = atan2(Cy, Cx) -
                atan2(b, u); u is the wrist centre's forward distance from axis 1 in the arm plane
  axes 2, 3     in the arm plane x' = u - a1, z' = Cz - c1, d² = x'² + z'², k = √(c3² + a2²),
                ψ = atan2(a2, c3): cos(q3 + ψ) = (d² - c2² - k²) / (2·c2·k), q3 = ±acos(…) - ψ (the
                elbow branches), q2 = atan2(x', z') - atan2(k·sin(q3+ψ), c2 + k·cos(q3+ψ))
  axes 4, 5, 6  M = (Rz(q1)·Ry(q2+q3))ᵀ·R = Rz(q4)·Ry(q5)·Rz(q6): q5 = ±atan2(√(M02² + M12²), M22)
                (the wrist branches), q4 = atan2(±M12, ±M02), then q6 from Ry(-q5)·Rz(-q4)·M so that
                the orientation is met exactly even near the wrist singularity

Singular positions (wrist centre on axis 1 with b = 0; q5 = 0) leave one angle free: it is taken
from the `hint` (the initial joint position of pointToJoint), so that the arm does not turn for
nothing. Branches that coincide there come back once.
"""

from __future__ import annotations

import math

from .kinematics import OPW
from .urdf import Mat, inverse, mul

_SING = 1e-12


def opw_ik(opw: OPW, T: Mat, hint=None) -> list[tuple[float, float, float, float, float, float]]:
    """All (up to 8) joint solutions, radians, principal values, for the flange pose T (mm).

    Out-of-reach branches are left out; joint limits are not applied here."""
    if opw.G is not None:
        T = mul(T, inverse(opw.G))
    a1, a2, b, c1, c2, c3, c4 = opw.a1, opw.a2, opw.b, opw.c1, opw.c2, opw.c3, opw.c4
    r00, r01, r02, px = T[0]
    r10, r11, r12, py = T[1]
    r20, r21, r22, pz = T[2]
    cx = px - c4 * r02
    cy = py - c4 * r12
    cz = pz - c4 * r22
    rho2 = cx * cx + cy * cy
    disc = rho2 - b * b
    if disc < 0.0:
        if disc < -1e-9 * max(rho2, 1.0):
            return []
        disc = 0.0
    k_sh = math.sqrt(disc)
    h = hint
    if rho2 < _SING and b == 0.0:  # wrist centre on axis 1: q1 is free
        base_angle = opw.signs[0] * h[0] if h is not None else 0.0
    else:
        base_angle = math.atan2(cy, cx)
    kk = math.hypot(c3, a2)
    psi = math.atan2(a2, c3)
    two_c2k = 2.0 * c2 * kk
    zp = cz - c1
    out = []
    on_axis = rho2 < _SING and b == 0.0
    for branch in (0, 1):
        if on_axis:  # u = 0 on both branches; the second one turns the arm round
            u = 0.0
            q1 = base_angle + (math.pi if branch else 0.0)
        else:
            u = -k_sh if branch else k_sh
            q1 = base_angle - math.atan2(b, u)
        xp = u - a1
        d2 = xp * xp + zp * zp
        cphi = (d2 - c2 * c2 - kk * kk) / two_c2k
        if cphi > 1.0 or cphi < -1.0:
            if abs(cphi) > 1.0 + 1e-10:
                continue
            cphi = 1.0 if cphi > 0 else -1.0
        phi = math.acos(cphi)
        s1, co1 = math.sin(q1), math.cos(q1)
        # N = Rz(-q1)·R
        n00 = co1 * r00 + s1 * r10
        n02 = co1 * r02 + s1 * r12
        n10 = -s1 * r00 + co1 * r10
        n12 = -s1 * r02 + co1 * r12
        alpha = math.atan2(xp, zp)
        for ph in ((phi, -phi) if phi != 0.0 else (phi,)):
            q3 = ph - psi
            q2 = alpha - math.atan2(kk * math.sin(ph), c2 + kk * math.cos(ph))
            t = q2 + q3
            ct, st = math.cos(t), math.sin(t)
            # M = Ry(-t)·N
            m00 = ct * n00 - st * r20
            m02 = ct * n02 - st * r22
            m10, m12 = n10, n12
            m20 = st * n00 + ct * r20
            m22 = st * n02 + ct * r22
            s5abs = math.hypot(m02, m12)
            q5p = math.atan2(s5abs, m22)
            for sgn in ((1.0, -1.0) if s5abs > _SING else (1.0,)):
                q5 = sgn * q5p
                if s5abs > _SING:
                    q4 = math.atan2(sgn * m12, sgn * m02)
                else:
                    q4 = opw.signs[3] * h[3] if h is not None else 0.0
                c4_, s4_ = math.cos(q4), math.sin(q4)
                c5_, s5_ = math.cos(q5), math.sin(q5)
                # Rz(q6) = Ry(-q5)·Rz(-q4)·M: first column (cos q6, sin q6, 0)
                p00 = c4_ * m00 + s4_ * m10
                p10 = -s4_ * m00 + c4_ * m10
                q6 = math.atan2(p10, c5_ * p00 - s5_ * m20)
                out.append((q1, q2, q3, q4, q5, q6))
    s = opw.signs
    if s != (1, 1, 1, 1, 1, 1):
        out = [tuple(si * qi for si, qi in zip(s, q)) for q in out]
    return out
