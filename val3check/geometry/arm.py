"""Instructions of chapter 9 that need the arm model: here, herej, jointToPoint, pointToJoint,
config(joint). The arm model is any object with the `Kinematics` protocol (val3check/robot/).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Protocol, runtime_checkable

from . import config_values as C
from . import rotation as R
from .frames import Frame, Tool, root_pose
from .jointops import herej  # noqa: F401  (re-exported: 9.2.3 herej)
from .points import Point, world_pose
from .trsf import Trsf

Pose6 = tuple[float, float, float, float, float, float]


@runtime_checkable
class Kinematics(Protocol):
    """What the geometry needs from an arm model. Lengths in the application's length unit
    (the arm model converts if the application is in inches), angles in degrees.

    - ``fk(joints) -> (x, y, z, rx, ry, rz)``: pose of the flange in world (VAL 3 angles,
      9.3.2; any equivalent triple is accepted).
    - ``ik(pose, config, near) -> list of joint sequences``: the joint positions that put the
      flange at `pose` (a 6-tuple as fk returns). `config` is the point's config with its
      `same` fields already replaced by those of `near` (only concrete or `free` values);
      `near` is jInitial: for axes of more than one turn, return the solution(s) nearest to
      it. Solutions outside the software limits should not be returned (or the model provides
      `in_range`). Returning solutions of other configurations is allowed: they are filtered.
    - ``config_of(joints) -> tuple of str``: the concrete configuration, e.g.
      ("lefty", "epositive", "wpositive") (RS/TS arms: ("righty",)), 9.7.4/9.7.5.
    - optional ``in_range(joints) -> bool`` (or ``in_limits``): software joint limits (used by
      pointToJoint to drop solutions out of the limits).
    """

    def fk(self, joints: Sequence[float]) -> Sequence[float]: ...

    def ik(self, pose: Pose6, config: Sequence[str], near: Sequence[float]) -> list[Sequence[float]]: ...

    def config_of(self, joints: Sequence[float]) -> Sequence[str]: ...


def config_of(kin: Kinematics, joints: Sequence[float]) -> C.Config:
    """9.7.6 config(joint): the configuration of the arm at `joints`."""
    return tuple(kin.config_of(joints))


def flange_pose(kin: Kinematics, joints: Sequence[float]) -> R.Pose:
    """Pose of the flange in world at `joints` (from fk)."""
    x, y, z, rx, ry, rz = kin.fk(joints)
    return R.pose(float(x), float(y), float(z), float(rx), float(ry), float(rz))


def joint_to_point(kin: Kinematics, tool: Tool, reference: Frame, joints: Sequence[float]) -> Point:
    """9.6.3 jointToPoint(tTool, fReference, jPosition): the position of the tool centre point
    of `tool` in `reference` when the arm is at `joints`; reference frame `reference`, config
    that of `joints`. Errors 160/164 (tool), 161/163 (frame)."""
    tcp = R.pose_mul(flange_pose(kin, joints), root_pose(tool))
    local = R.pose_mul(R.pose_inv(root_pose(reference)), tcp)
    return Point(Trsf.from_pose(local), config_of(kin, joints), reference)


def here(kin: Kinematics, current: Sequence[float], tool: Tool, reference: Frame) -> Point:
    """9.6.3 here(tTool, fReference): jointToPoint at the current commanded joint position."""
    return joint_to_point(kin, tool, reference, current)


def point_to_joint(kin: Kinematics, tool: Tool, initial: Sequence[float], point: Point
                   ) -> tuple[bool, tuple[float, ...] | None]:
    """9.6.3 pointToJoint(tTool, jInitial, pPosition, jResult) -> (found, joints).

    The flange target is world(point) * !flange(tool). `same` config fields take jInitial's
    configuration, `free` fields accept any; among the solutions of the model that satisfy the
    config (and `in_range` when the model has it), the nearest to jInitial (sum of squared
    differences) is taken. (False, None) when there is none: the caller leaves jResult
    unchanged. 162 when the point has no reference frame."""
    target = R.pose_mul(world_pose(point), R.pose_inv(root_pose(tool)))
    pose6 = Trsf.from_pose(target).as_tuple()
    init = tuple(float(v) for v in initial)
    init_cfg = config_of(kin, init)
    wanted = C.resolve(point.config, init_cfg)
    in_range = getattr(kin, "in_range", None) or getattr(kin, "in_limits", None)
    best: tuple[float, ...] | None = None
    best_d = float("inf")
    for sol in kin.ik(pose6, wanted, init):
        j = tuple(float(v) for v in sol)
        if len(j) != len(init):
            continue
        if not C.matches(wanted, config_of(kin, j)):
            continue
        if in_range is not None and not in_range(j):
            continue
        d = sum((a - b) ** 2 for a, b in zip(j, init))
        if d < best_d:
            best, best_d = j, d
    return (best is not None), best
