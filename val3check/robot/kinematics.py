"""Forward kinematics: VAL 3 poses, the URDF chain, the closed-form OPW arm, pinocchio.

Units inside: millimetres and radians. Transforms are 3x4 row-major tuples `((r00, r01, r02, x),
(r10, r11, r12, y), (r20, r21, r22, z))` in millimetres.

VAL 3 pose convention (manual 9.3.2): a trsf {x, y, z, rx, ry, rz} is the translation (x, y, z)
and the rotation obtained by turning rx about x, then ry about the new y', then rz about the new
z'': R = Rx(rx)·Ry(ry)·Rz(rz). Poses come back in the canonical form of val3check/geometry/
rotation.py (the one convention of val3check): angles in ]-180, 180], rx = 0 and ry = ±90 at the
gimbal lock, at least two angles within [-90, 90] except the manual's "rx = 180, ry = 0" case.

Three forward kinematics of the same arm, checked against each other by the tests:
  * `Chain.fk`: the URDF joints multiplied out in pure Python (any serial arm);
  * `OPW.fk`: the closed form of an ortho-parallel arm with a spherical wrist (Brandstötter,
    Angerer, Hofbaur 2014), about ten times faster; its parameters are read from the URDF's zero
    pose (`extract_opw`) and verified against the chain, never assumed;
  * pinocchio (`models.RobotModel.fk_pinocchio`), from the same URDF file.
"""

from __future__ import annotations

import math
import random

from ..geometry import rotation as _rot
from ..lengths import M_MM
from ..light_dataclass import dataclass
from .errors import RobotError
from .urdf import IDENTITY, Mat, UrdfInfo, axis_angle, inverse, mul, transform

DEG = math.pi / 180.0
RAD = 180.0 / math.pi


# ---- VAL 3 trsf <-> matrix ---------------------------------------------------------------------
# One convention for the whole of val3check: the geometry package's (val3check/geometry/rotation.py,
# manual 9.3.2, with its canonical form and the "rx = 180, ry = 0" exception), so that
# RobotModel.fk() and here()/jointToPoint() agree with compose()/position() bit for bit.


def trsf_matrix(pose) -> Mat:
    """{x, y, z, rx, ry, rz} (mm, deg) -> 3x4 (mm), R = Rx(rx)·Ry(ry)·Rz(rz) (geometry.rotation.matrix,
    exact for multiples of 30 and 45 degrees)."""
    x, y, z, rx, ry, rz = pose
    m = _rot.matrix(float(rx), float(ry), float(rz))
    return (
        (m[0], m[1], m[2], float(x)),
        (m[3], m[4], m[5], float(y)),
        (m[6], m[7], m[8], float(z)),
    )


def matrix_trsf(M) -> tuple[float, float, float, float, float, float]:
    """3x4 (mm) -> {x, y, z, rx, ry, rz} (mm, deg): the canonical VAL 3 angles of
    geometry.rotation.angles_of (module docstring)."""
    rx, ry, rz = _rot.angles_of((M[0][0], M[0][1], M[0][2], M[1][0], M[1][1], M[1][2], M[2][0], M[2][1], M[2][2]))
    return (M[0][3] + 0.0, M[1][3] + 0.0, M[2][3] + 0.0, rx, ry, rz)


def pose_error(A, B) -> tuple[float, float]:
    """(position error in mm, rotation angle between the orientations in rad) of two 3x4."""
    dp = math.sqrt(sum((A[i][3] - B[i][3]) ** 2 for i in range(3)))
    # angle of A^T B: acos((trace - 1) / 2), computed robustly from the skew part too
    tr = sum(A[k][i] * B[k][i] for i in range(3) for k in range(3))
    vx = sum(A[k][1] * B[k][2] - A[k][2] * B[k][1] for k in range(3))
    vy = sum(A[k][2] * B[k][0] - A[k][0] * B[k][2] for k in range(3))
    vz = sum(A[k][0] * B[k][1] - A[k][1] * B[k][0] for k in range(3))
    ang = math.atan2(0.5 * math.sqrt(vx * vx + vy * vy + vz * vz), 0.5 * (tr - 1.0))
    return dp, abs(ang)


# ---- the URDF chain -------------------------------------------------------------------------------


@dataclass(frozen=True)
class ChainJoint:
    name: str
    before: Mat  # fixed transform from the previous joint's moving frame (or the world) to this joint
    axis: tuple[float, float, float]
    lower: float  # rad (revolute) or mm (prismatic)
    upper: float
    velocity: float  # rad/s or mm/s
    effort: float | None
    kind: str = "revolute"  # or "prismatic" (URDF "continuous" is a revolute joint of ±360°)


# The two serial layouts val3check knows: six revolute joints (RX/TX arms) and the four axes of a
# SCARA (RS/TS, manual 9.7.5): two revolute, one prismatic (its value is a length), one revolute.
LAYOUTS = {
    ("revolute",) * 6: "six-axis",
    ("revolute", "revolute", "prismatic", "revolute"): "scara",
}


class Chain:
    """The serial chain world -> flange of a URDF, in millimetres: six revolute joints, or the
    revolute-revolute-prismatic-revolute chain of a SCARA. `world_shift` moves the world frame
    relative to the URDF's world link (a user's assumption, e.g. the height of a SCARA's world)."""

    def __init__(self, info: UrdfInfo, world: str, flange: str, world_shift: Mat | None = None):
        path = info.path
        for what, link in (("world_frame", world), ("flange_frame", flange)):
            if link not in info.links:
                raise RobotError(f"{path}: <val3check {what}=\"{link}\">: the URDF has no link named {link!r}")
        root = info.root_link()
        if not root:
            raise RobotError(f"{path}: the links do not form one tree with a single root")
        to_world = info.chain(root, world)
        to_flange = info.chain(root, flange)
        if to_world is None or to_flange is None:
            raise RobotError(f"{path}: {world!r} and {flange!r} are not both below the root link {root!r}")
        moving = [j for j in to_world if j.kind != "fixed"]
        if moving:
            raise RobotError(f"{path}: the world frame {world!r} must be fixed to the base, but joint {moving[0].name!r} moves it")
        W = IDENTITY
        for j in to_world:
            W = mul(W, transform(_mm(j.xyz), j.rpy))
        if world_shift is not None:
            W = mul(W, world_shift)
        joints: list[ChainJoint] = []
        acc = inverse(W)
        for j in to_flange:
            acc = mul(acc, transform(_mm(j.xyz), j.rpy))
            if j.kind == "fixed":
                continue
            if j.kind not in ("revolute", "continuous", "prismatic"):
                raise RobotError(f"{path}: joint {j.name!r} is {j.kind or 'untyped'}: only revolute and prismatic joints are supported")
            if j.kind != "continuous" and (j.lower is None or j.upper is None):
                raise RobotError(f"{path}: joint {j.name!r} has no <limit lower upper>: the joint limits are needed")
            if not j.velocity or j.velocity <= 0:
                raise RobotError(f"{path}: joint {j.name!r} has no <limit velocity>: the nominal joint speed is needed")
            if j.kind == "prismatic":  # URDF metres -> millimetres
                joints.append(ChainJoint(j.name, acc, j.axis, j.lower * M_MM, j.upper * M_MM, j.velocity * M_MM,
                                         j.effort, "prismatic"))
            else:
                lo, hi = (j.lower, j.upper) if j.kind == "revolute" else (-2 * math.pi, 2 * math.pi)
                joints.append(ChainJoint(j.name, acc, j.axis, lo, hi, j.velocity, j.effort))
            acc = IDENTITY
        kinds = tuple(j.kind for j in joints)
        if kinds not in LAYOUTS:
            if len(joints) == 6 or "prismatic" not in kinds:
                raise RobotError(f"{path}: {len(joints)} moving joints between {world!r} and {flange!r}: a six-axis arm "
                                 "(six revolute joints) or a SCARA (revolute, revolute, prismatic, revolute) is needed")
            raise RobotError(f"{path}: joints {', '.join(kinds)} between {world!r} and {flange!r}: a SCARA is revolute, "
                             "revolute, prismatic, revolute (manual 9.7.5)")
        self.kind = LAYOUTS[kinds]
        self.joints = joints
        self.tip = acc  # last joint frame -> flange
        self.world_in_root = W

    def fk(self, q) -> Mat:
        """Flange in the world frame (mm) for joint values q (rad, or mm for a prismatic joint)."""
        T = IDENTITY
        for j, a in zip(self.joints, q):
            T = mul(T, j.before)
            if j.kind == "prismatic":
                x, y, z = j.axis
                n = math.sqrt(x * x + y * y + z * z)
                T = mul(T, ((1.0, 0.0, 0.0, a * x / n), (0.0, 1.0, 0.0, a * y / n), (0.0, 0.0, 1.0, a * z / n)))
            else:
                T = mul(T, axis_angle(j.axis, a))
        return mul(T, self.tip)

    def zero_frames(self) -> list[tuple[tuple[float, float, float], tuple[float, float, float]]]:
        """(origin, axis direction) of each joint in the world frame at the zero position."""
        out = []
        T = IDENTITY
        for j in self.joints:
            T = mul(T, j.before)
            x, y, z = j.axis
            n = math.sqrt(x * x + y * y + z * z)
            d = tuple((T[i][0] * x + T[i][1] * y + T[i][2] * z) / n for i in range(3))
            out.append(((T[0][3], T[1][3], T[2][3]), d))
        return out

def _mm(xyz) -> tuple[float, float, float]:
    return (xyz[0] * M_MM, xyz[1] * M_MM, xyz[2] * M_MM)


# ---- ortho-parallel arm with a spherical wrist ---------------------------------------------------


@dataclass(frozen=True)
class OPW:
    """Brandstötter et al. parameters (mm), axis sign corrections, and the flange offset G.

    In the world frame, at the zero position: axis 1 is the world Z axis, axis 2 the line
    (x = a1, z = c1) along Y, the elbow is c2 above axis 2, the wrist centre is (a1 + a2, b,
    c1 + c2 + c3) and the flange point c4 above it on axis 6. Joint angle q_i turns the arm by
    sign_i·q_i about the positive axis. flange = T_opw(q)·G.
    """

    a1: float
    a2: float
    b: float
    c1: float
    c2: float
    c3: float
    c4: float
    signs: tuple[int, int, int, int, int, int] = (1, 1, 1, 1, 1, 1)
    G: Mat | None = None  # None: the flange frame is the OPW tool frame itself

    def fk(self, q) -> Mat:
        """Flange in the world frame (mm) for joint angles q (rad)."""
        s = self.signs
        t1, t2, t3, t4, t5, t6 = (s[0] * q[0], s[1] * q[1], s[2] * q[2], s[3] * q[3], s[4] * q[4], s[5] * q[5])
        c1, s1 = math.cos(t1), math.sin(t1)
        c2, s2 = math.cos(t2), math.sin(t2)
        t23 = t2 + t3
        c23, s23 = math.cos(t23), math.sin(t23)
        c4, s4 = math.cos(t4), math.sin(t4)
        c5, s5 = math.cos(t5), math.sin(t5)
        c6, s6 = math.cos(t6), math.sin(t6)
        # W = Rz(t4)·Ry(t5)·Rz(t6)
        w00 = c4 * c5 * c6 - s4 * s6
        w01 = -c4 * c5 * s6 - s4 * c6
        w02 = c4 * s5
        w10 = s4 * c5 * c6 + c4 * s6
        w11 = -s4 * c5 * s6 + c4 * c6
        w12 = s4 * s5
        w20 = -s5 * c6
        w21 = s5 * s6
        w22 = c5
        # M = Ry(t23)·W
        m00 = c23 * w00 + s23 * w20
        m01 = c23 * w01 + s23 * w21
        m02 = c23 * w02 + s23 * w22
        m20 = -s23 * w00 + c23 * w20
        m21 = -s23 * w01 + c23 * w21
        m22 = -s23 * w02 + c23 * w22
        # wrist centre in the joint-1 frame, then the flange point c4 along axis 6
        u = self.a1 + self.c2 * s2 + self.c3 * s23 + self.a2 * c23 + self.c4 * m02
        v = self.b + self.c4 * w12
        z = self.c1 + self.c2 * c2 + self.c3 * c23 - self.a2 * s23 + self.c4 * m22
        T = (
            (c1 * m00 - s1 * w10, c1 * m01 - s1 * w11, c1 * m02 - s1 * w12, c1 * u - s1 * v),
            (s1 * m00 + c1 * w10, s1 * m01 + c1 * w11, s1 * m02 + c1 * w12, s1 * u + c1 * v),
            (m20, m21, m22, z),
        )
        return T if self.G is None else mul(T, self.G)


def extract_opw(chain: Chain, tol_mm: float = 1e-6) -> tuple[OPW | None, str]:
    """The OPW parameters of a chain read from its zero position, verified on random positions.

    Returns (OPW, "") or (None, why the arm is not ortho-parallel with a spherical wrist)."""
    if chain.kind != "six-axis":
        return None, "not a six-axis arm"
    frames = chain.zero_frames()
    expected = ("z", "y", "y", "z", "y", "z")
    unit = {"y": (0.0, 1.0, 0.0), "z": (0.0, 0.0, 1.0)}
    signs = []
    for i, ((_, d), e) in enumerate(zip(frames, expected)):
        u = unit[e]
        dot = d[0] * u[0] + d[1] * u[1] + d[2] * u[2]
        if abs(abs(dot) - 1.0) > 1e-9:
            return None, f"axis {i + 1} is not along world {e.upper()} at the zero position"
        signs.append(1 if dot > 0 else -1)
    (p1, _), (p2, _), (p3, _), (p4, _), (p5, _), (p6, _) = frames
    if math.hypot(p1[0], p1[1]) > tol_mm:
        return None, "axis 1 does not pass through the world origin"
    a1, c1 = p2[0], p2[2]
    if abs(p3[0] - p2[0]) > tol_mm:
        return None, "axis 3 is not straight above axis 2 at the zero position"
    c2 = p3[2] - p2[2]
    if math.hypot(p4[0] - p6[0], p4[1] - p6[1]) > tol_mm or abs(p5[0] - p4[0]) > tol_mm:
        return None, "axes 4, 5 and 6 do not meet in one point (no spherical wrist)"
    cx, cy, cz = p4[0], p4[1], p5[2]
    a2, b, c3 = cx - a1, cy, cz - c1 - c2
    F = chain.fk((0.0,) * 6)
    c4 = F[2][3] - cz
    base = OPW(a1, a2, b, c1, c2, c3, c4, tuple(signs))  # type: ignore[arg-type]
    T0 = base.fk((0.0,) * 6)
    G = mul(inverse(T0), F)
    if max(abs(G[i][k] - IDENTITY[i][k]) for i in range(3) for k in range(4)) < 1e-12:
        opw = base
    else:
        opw = OPW(a1, a2, b, c1, c2, c3, c4, tuple(signs), G)  # type: ignore[arg-type]
    rng = random.Random(12345)
    for _ in range(32):
        q = [rng.uniform(-math.pi, math.pi) for _ in range(6)]
        dp, da = pose_error(opw.fk(q), chain.fk(q))
        if dp > 1e-7 or da > 1e-10:
            return None, f"the closed-form model does not reproduce the URDF chain ({dp:.3g} mm off)"
    return opw, ""
