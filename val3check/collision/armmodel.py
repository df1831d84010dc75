"""The arm as collision bodies: its links' solids, the allowed-collision matrix, and how far each
link can be from each joint axis (for the motion bound of docs/cell.md)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..robot.links import ArmLinks, arm_links
from .acm import ACM, arm_acm
from .bodies import Body, make_bodies
from .meshes import MeshProblem, load_mesh


class ArmModel:
    """A `RobotModel` seen by the collision checker.

    links          `ArmLinks` (link tree, FK of every link)
    bodies         {link: [Body]} for the links that have collision solids
    acm            the allowed-collision matrix (`acm.ACM`; `acm.source` "urdf" or "computed")
    flange_link    the link of the VAL 3 flange frame: tools and parts hang on it
    touch_links    the links a tool may touch by default: the first two links with solids found
                   going up from the flange (the flange plate and the wrist it is mounted on)
    weights(link, bodies)   the motion bound's factors (docs/cell.md)
    """

    def __init__(self, robot, acm: ACM | None = None) -> None:
        self.robot = robot
        self.links: ArmLinks = arm_links(robot)
        self.bodies: dict[str, list[Body]] = {}
        for s in self.links.solids:
            label = f"{s.link} ({s.name})"
            if s.kind == "mesh":
                try:
                    mesh = load_mesh(Path(s.mesh), s.mesh, s.size, solid=False)
                except MeshProblem as exc:
                    from ..robot.errors import RobotError

                    raise RobotError(f"{robot.source}: link {s.link!r}: {exc}") from None
                # not known to be closed: a surface; a convex one is measured as its solid hull (an envelope)
                bodies = make_bodies("link", s.link, s.name, label, "mesh", (), s.origin, mesh.vertices, mesh.faces,
                                     solid=False, hull_solid=True)
            else:
                bodies = make_bodies("link", s.link, s.name, label, s.kind, s.size, s.origin)
            self.bodies.setdefault(s.link, []).extend(bodies)
        self.flange_link = robot.flange_frame
        self.touch_links = self._touch_links()
        self.acm = acm or arm_acm(self.links, self.bodies, robot.joint_limits, robot.source)

    @property
    def n_joints(self) -> int:
        return len(self.links.joint_names)

    def _touch_links(self) -> tuple[str, ...]:
        out: list[str] = []
        n = self.flange_link
        while n != self.links.root and len(out) < 2:
            if self.bodies.get(n):
                out.append(n)
            n = self.links.edges[n].parent
        if len(out) < 2 and self.bodies.get(self.links.root):
            out.append(self.links.root)
        return tuple(out)

    def weights(self, link: str, bodies: list[Body]) -> np.ndarray:
        """Per joint value, how far (mm) a point of `bodies` (carried by `link`) may move per unit of
        that joint's travel (radian, or mm for a prismatic axis), whatever the other joints:
          * the joint nearest the link (its axis fixed in the link's frame): the largest distance
            from that axis to a point of the bodies, 0 for a solid of revolution about it;
          * a joint further up: the lengths of the links in between, end to end, plus the largest
            distance from the link's origin to a point of the bodies (the axis can be anywhere
            within that reach after the joints in between have turned);
          * a prismatic joint: 1;  a joint that does not move the link: 0."""
        w = np.zeros(self.n_joints)
        if not bodies:
            return w
        links = self.links
        pris = links.prismatic
        far = max(b.reach() for b in bodies)
        for j, r in links.reach_from_joint(link).items():
            w[j] = 1.0 if pris[j] else r + far
        n, T = link, np.eye(4)
        while n != links.root:
            e = links.edges[n]
            if e.kind != "fixed" and e.index >= 0:
                if not pris[e.index]:
                    inv = np.linalg.inv(T)
                    p0 = inv[:3, 3]
                    d = inv[:3, :3] @ e.axis
                    w[e.index] = max(b.from_line(p0, d / np.linalg.norm(d)) for b in bodies)
                break
            T = e.origin @ T
            n = e.parent
        return w


_MODELS: dict[tuple, ArmModel] = {}


def arm_model(robot) -> ArmModel:
    """The `ArmModel` of a robot, built once per URDF file (and per joint names and limits: the
    allowed-collision matrix samples the limits; a robot file may override them) in a process."""
    p = Path(robot.source)
    try:
        mtime = p.stat().st_mtime_ns
    except OSError:
        mtime = 0
    key = (str(p.resolve()), mtime, tuple(robot.joint_names), tuple(map(tuple, robot.joint_limits)),
           robot.world_frame, robot.flange_frame)
    m = _MODELS.get(key)
    if m is None:
        m = _MODELS[key] = ArmModel(robot)
    return m
