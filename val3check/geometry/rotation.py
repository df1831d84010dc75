"""Rotations in plain `math`: matrices, VAL 3 angles (9.3.2), quaternions, rigid poses.

Conventions
-----------
- A rotation matrix is a row-major 9-tuple ``(r00, r01, r02, r10, ..., r22)``; its columns are
  the axes of the rotated frame expressed in the reference frame.
- VAL 3 angles (9.3.2): ``rx, ry, rz`` in degrees, applied successively about ``x``, then the new
  ``y'``, then the new ``z''`` (intrinsic X-Y'-Z''), so ``R = Rx(rx) * Ry(ry) * Rz(rz)``.
- A quaternion is ``(w, x, y, z)``.
- A pose is ``(R, p, ang)``: rotation matrix, translation 3-tuple, and the VAL 3 angles the
  rotation was built from when they are known exactly (else ``None``). Carrying the angles lets
  products with a pure translation keep the user's angles bit for bit instead of going through
  matrices (``appro(p, {0,0,-100,0,0,0})`` keeps ``p``'s rx, ry, rz exactly).

Canonical form (9.3.2), as `canonical_angles` and `angles_of` produce it
-------------------------------------------------------------------------
- every angle in ``]-180, 180]`` (``-180`` is written ``180``; ``-0`` is written ``0``);
- when ``ry`` is 90 modulo 180 (gimbal lock: ``|cos ry| < GIMBAL_EPS``), ``ry`` is exactly
  ``+90`` or ``-90`` and ``rx`` is ``0``;
- otherwise, of the two angle triples of the rotation, ``(a, b, c)`` with ``|b| < 90`` is kept
  when ``|a| <= 90`` or ``|c| <= 90``; else ``(a -+ 180, +-180 - b, c -+ 180)`` is taken, whose
  ``rx`` and ``rz`` are both within ``]-90, 90[``. So at least two angles lie in ``[-90, 90]``...
- ...except the manual's exception: when ``rx = 180`` and ``ry = 0`` the triple is kept as
  ``(180, 0, rz)`` whatever ``rz`` (a tool pointing down stays ``{.., 180, 0, rz}`` instead of
  becoming ``{.., 0, 180, rz -+ 180}``). ``|ry| <= EXCEPTION_EPS`` and
  ``|rx| >= 180 - EXCEPTION_EPS`` count as that case, and ``rx`` is then written ``180``.
"""

from __future__ import annotations

import math

Mat = tuple[float, float, float, float, float, float, float, float, float]
Vec = tuple[float, float, float]
Quat = tuple[float, float, float, float]
Angles = tuple[float, float, float]
Pose = tuple[Mat, Vec, "Angles | None"]

IDENTITY: Mat = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)
ZERO: Vec = (0.0, 0.0, 0.0)

GIMBAL_EPS = 1e-10  # |cos ry| below this: ry is taken as exactly +-90 and rx as 0
EXCEPTION_EPS = 1e-9  # degrees: tolerance of the "rx = 180 and ry = 0" exception of 9.3.2

_R2D = 180.0 / math.pi
_D2R = math.pi / 180.0
_H2 = math.sqrt(0.5)
_H3 = math.sqrt(3.0) / 2.0
# Exact sine and cosine of the angles that are multiples of 30 or 45 degrees, so that e.g.
# Rx(180) is exactly diag(1, -1, -1) and {0,0,0,180,0,0} * {0,0,0,180,0,0} is exactly the identity.
_EXACT: dict[float, tuple[float, float]] = {
    0.0: (0.0, 1.0),
    30.0: (0.5, _H3),
    45.0: (_H2, _H2),
    60.0: (_H3, 0.5),
    90.0: (1.0, 0.0),
    120.0: (_H3, -0.5),
    135.0: (_H2, -_H2),
    150.0: (0.5, -_H3),
    180.0: (0.0, -1.0),
}
for _k, (_s, _c) in list(_EXACT.items()):
    if _k not in (0.0, 180.0):
        _EXACT[-_k] = (-_s, _c)


def norm180(a: float) -> float:
    """`a` reduced modulo 360 to ``]-180, 180]`` (and -0.0 to 0.0)."""
    if -180.0 < a <= 180.0:
        return a + 0.0
    r = math.fmod(a, 360.0)
    if r > 180.0:
        r -= 360.0
    elif r <= -180.0:
        r += 360.0
    return r + 0.0


def sincos(deg: float) -> tuple[float, float]:
    """(sin, cos) of an angle in degrees, exact for multiples of 30 and 45 degrees."""
    r = norm180(deg)
    e = _EXACT.get(r)
    if e is not None:
        return e
    t = r * _D2R
    return math.sin(t), math.cos(t)


_MATRICES: dict[tuple[float, float, float], Mat] = {}  # `matrix`, by its angles
MATRICES_KEPT = 4096


def matrix(rx: float, ry: float, rz: float) -> Mat:
    """R = Rx(rx) * Ry(ry) * Rz(rz) (9.3.2: about x, then y', then z''). Kept by value: a
    program computes the same few orientations again and again (issue 29); -0.0 and 0.0, the one
    pair of equal keys with other bits, give the same matrix (norm180)."""
    key = (rx, ry, rz)
    m = _MATRICES.get(key)
    if m is None:
        m = _matrix(rx, ry, rz)
        if len(_MATRICES) >= MATRICES_KEPT:
            _MATRICES.clear()
        _MATRICES[key] = m
    return m


def _matrix(rx: float, ry: float, rz: float) -> Mat:
    """`matrix`, computed."""
    sa, ca = sincos(rx)
    sb, cb = sincos(ry)
    sc, cc = sincos(rz)
    return (
        cb * cc, -cb * sc, sb,
        ca * sc + sa * sb * cc, ca * cc - sa * sb * sc, -sa * cb,
        sa * sc - ca * sb * cc, sa * cc + ca * sb * sc, ca * cb,
    )


def angles_of(m: Mat) -> Angles:
    """The canonical VAL 3 angles (module docstring) of a rotation matrix."""
    r00, r01, r02, r10, r11, r12, r20, _r21, r22 = m
    cb = math.hypot(r00, r01)
    if cb < GIMBAL_EPS:
        return 0.0, (90.0 if r02 > 0.0 else -90.0), norm180(math.atan2(r10, r11) * _R2D)
    b = math.atan2(r02, cb) * _R2D
    a = norm180(math.atan2(-r12, r22) * _R2D)
    # rz from what is left once rx and ry are undone (Ry(-ry) Rx(-rx) R = Rz(rz)): exact even
    # close to the gimbal lock, where -r01 and r00 alone are tiny and noisy
    sa, ca = sincos(a)
    c = norm180(math.atan2(ca * r10 + sa * r20, cb * r00 - r02 * (ca * r20 - sa * r10)) * _R2D)
    return _choose(a, b, c)


def _choose(a: float, b: float, c: float) -> Angles:
    """Pick, between (a, b, c) with |b| < 90 and its twin, the canonical triple."""
    if (a > 90.0 or a < -90.0) and (c > 90.0 or c < -90.0):
        if -EXCEPTION_EPS <= b <= EXCEPTION_EPS and (a >= 180.0 - EXCEPTION_EPS or a <= -180.0 + EXCEPTION_EPS):
            return 180.0, b + 0.0, c  # the exception of 9.3.2: rx = 180, ry = 0
        a = a - 180.0 if a > 0.0 else a + 180.0
        c = c - 180.0 if c > 0.0 else c + 180.0
        b = 180.0 - b if b >= 0.0 else -180.0 - b
        return a + 0.0, norm180(b), c + 0.0
    return a, b + 0.0, c


def is_canonical(rx: float, ry: float, rz: float) -> bool:
    """True when (rx, ry, rz) is already the triple `angles_of` would give for its rotation."""
    if not (-180.0 < rx <= 180.0 and -180.0 < ry <= 180.0 and -180.0 < rz <= 180.0):
        return False
    if ry == 90.0 or ry == -90.0:
        return rx == 0.0
    if -90.0 < ry < 90.0:
        if -90.0 <= rx <= 90.0 or -90.0 <= rz <= 90.0:
            return True
        return rx == 180.0 and -EXCEPTION_EPS <= ry <= EXCEPTION_EPS
    # |ry| > 90: the twin of a triple whose rx and rz were both beyond 90 degrees
    if not (-90.0 < rx < 90.0 and -90.0 < rz < 90.0):
        return False
    twin_b = 180.0 - ry if ry > 0.0 else -180.0 - ry
    return not (-EXCEPTION_EPS <= twin_b <= EXCEPTION_EPS and -EXCEPTION_EPS <= rx <= EXCEPTION_EPS)


def canonical_angles(rx: float, ry: float, rz: float) -> Angles:
    """The canonical form of any angle triple: unchanged (bit for bit) when already canonical."""
    rx, ry, rz = float(rx) + 0.0, float(ry) + 0.0, float(rz) + 0.0
    if is_canonical(rx, ry, rz):
        return rx, ry, rz
    return angles_of(matrix(rx, ry, rz))


# --- 3x3 algebra ------------------------------------------------------------------------------


def mat_mul(a: Mat, b: Mat) -> Mat:
    a00, a01, a02, a10, a11, a12, a20, a21, a22 = a
    b00, b01, b02, b10, b11, b12, b20, b21, b22 = b
    return (
        a00 * b00 + a01 * b10 + a02 * b20, a00 * b01 + a01 * b11 + a02 * b21, a00 * b02 + a01 * b12 + a02 * b22,
        a10 * b00 + a11 * b10 + a12 * b20, a10 * b01 + a11 * b11 + a12 * b21, a10 * b02 + a11 * b12 + a12 * b22,
        a20 * b00 + a21 * b10 + a22 * b20, a20 * b01 + a21 * b11 + a22 * b21, a20 * b02 + a21 * b12 + a22 * b22,
    )


def transpose(m: Mat) -> Mat:
    return (m[0], m[3], m[6], m[1], m[4], m[7], m[2], m[5], m[8])


def mat_vec(m: Mat, v: Vec) -> Vec:
    x, y, z = v
    return (m[0] * x + m[1] * y + m[2] * z, m[3] * x + m[4] * y + m[5] * z, m[6] * x + m[7] * y + m[8] * z)


def column(m: Mat, i: int) -> Vec:
    return (m[i], m[3 + i], m[6 + i])


def from_columns(ex: Vec, ey: Vec, ez: Vec) -> Mat:
    return (ex[0], ey[0], ez[0], ex[1], ey[1], ez[1], ex[2], ey[2], ez[2])


# --- vectors ----------------------------------------------------------------------------------


def add(a: Vec, b: Vec) -> Vec:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def sub(a: Vec, b: Vec) -> Vec:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def scale(a: Vec, k: float) -> Vec:
    return (a[0] * k, a[1] * k, a[2] * k)


def dot(a: Vec, b: Vec) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a: Vec, b: Vec) -> Vec:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def length(a: Vec) -> float:
    return math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])


def unit(a: Vec) -> Vec:
    n = length(a)
    return (a[0] / n, a[1] / n, a[2] / n)


# --- quaternions ------------------------------------------------------------------------------


def quat_of(m: Mat) -> Quat:
    """Unit quaternion of a rotation matrix (Shepperd's method), with w >= 0."""
    r00, r01, r02, r10, r11, r12, r20, r21, r22 = m
    tr = r00 + r11 + r22
    if tr > 0.0:
        s = math.sqrt(tr + 1.0) * 2.0
        q = (0.25 * s, (r21 - r12) / s, (r02 - r20) / s, (r10 - r01) / s)
    elif r00 > r11 and r00 > r22:
        s = math.sqrt(1.0 + r00 - r11 - r22) * 2.0
        q = ((r21 - r12) / s, 0.25 * s, (r01 + r10) / s, (r02 + r20) / s)
    elif r11 > r22:
        s = math.sqrt(1.0 + r11 - r00 - r22) * 2.0
        q = ((r02 - r20) / s, (r01 + r10) / s, 0.25 * s, (r12 + r21) / s)
    else:
        s = math.sqrt(1.0 + r22 - r00 - r11) * 2.0
        q = ((r10 - r01) / s, (r02 + r20) / s, (r12 + r21) / s, 0.25 * s)
    n = math.sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3])
    if q[0] < 0.0:
        n = -n
    return (q[0] / n, q[1] / n, q[2] / n, q[3] / n)


def mat_of_quat(q: Quat) -> Mat:
    w, x, y, z = q
    return (
        1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - w * z), 2.0 * (x * z + w * y),
        2.0 * (x * y + w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - w * x),
        2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y),
    )


def rotation_between(m1: Mat, m2: Mat) -> tuple[float, Vec]:
    """The smallest rotation taking orientation m1 to m2, in m1's axes: (angle in degrees in
    [0, 180], unit axis). At exactly 180 degrees both senses are equally short; the axis then
    is the one the arithmetic gives (deterministic, but arbitrary). Axis (0, 0, 1) for angle 0."""
    w, x, y, z = quat_of(mat_mul(transpose(m1), m2))  # w >= 0: the shorter way round
    s = math.sqrt(x * x + y * y + z * z)
    if s == 0.0:
        return 0.0, (0.0, 0.0, 1.0)
    return 2.0 * math.atan2(s, w) * _R2D, (x / s, y / s, z / s)


def axis_angle(axis: Vec, deg: float) -> Mat:
    """Rotation of `deg` degrees about the unit vector `axis` (Rodrigues)."""
    s, c = sincos(deg)
    x, y, z = axis
    t = 1.0 - c
    return (
        c + x * x * t, x * y * t - z * s, x * z * t + y * s,
        y * x * t + z * s, c + y * y * t, y * z * t - x * s,
        z * x * t - y * s, z * y * t + x * s, c + z * z * t,
    )


def slerp(m1: Mat, m2: Mat, s: float) -> Mat:
    """Orientation at fraction `s` of the smallest rotation from m1 to m2 (any real s)."""
    angle, axis = rotation_between(m1, m2)
    if angle == 0.0:
        return m1
    return mat_mul(m1, axis_angle(axis, angle * s))


# --- poses (R, p, exact angles or None) -------------------------------------------------------


def pose(x: float, y: float, z: float, rx: float, ry: float, rz: float) -> Pose:
    if rx == 0.0 and ry == 0.0 and rz == 0.0:
        return IDENTITY, (x, y, z), (0.0, 0.0, 0.0)
    return matrix(rx, ry, rz), (x, y, z), (rx, ry, rz)


IDENTITY_POSE: Pose = (IDENTITY, ZERO, (0.0, 0.0, 0.0))


def pose_mul(a: Pose, b: Pose) -> Pose:
    """a * b: b expressed in a's frame, then a's frame in its reference."""
    ra, pa, anga = a
    rb, pb, angb = b
    if rb is IDENTITY or rb == IDENTITY:
        r, ang = ra, anga
    elif ra is IDENTITY or ra == IDENTITY:
        r, ang = rb, angb
    else:
        r, ang = mat_mul(ra, rb), None
    if pb == ZERO:
        p = pa
    else:
        q = mat_vec(ra, pb)
        p = (pa[0] + q[0], pa[1] + q[1], pa[2] + q[2])
    return r, p, ang


def pose_inv(a: Pose) -> Pose:
    r, p, ang = a
    if r is IDENTITY or r == IDENTITY:
        return IDENTITY, (-p[0] + 0.0, -p[1] + 0.0, -p[2] + 0.0), (0.0, 0.0, 0.0)
    rt = transpose(r)
    q = mat_vec(rt, p)
    return rt, (-q[0] + 0.0, -q[1] + 0.0, -q[2] + 0.0), None


def pose_angles(a: Pose) -> Angles:
    """Canonical angles of a pose's rotation (exact when its angles are known)."""
    r, _p, ang = a
    if ang is not None:
        return canonical_angles(*ang)
    return angles_of(r)
