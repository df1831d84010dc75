"""Clearances, contacts and nearest points of every pair of shapes a cell allows, against an
independent reference (issue 24): analytic for spheres, dense point samples of the surfaces
otherwise (tests/collision/reference.py), random poses drawn by hypothesis (derandomized, few
examples each).

Every case goes through the whole checker: shape A is a tool solid 200 mm out of the flange of a
TX2-60 holding still, shape B an obstacle placed near it; one sample is checked.
"""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest

from val3check.collision import Cell, CollisionChecker, MeshData, Obstacle, Shape, ToolSolid  # noqa: E402

from . import reference as ref
from .helpers import ARM, ROBOT, MotionSpan

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, Phase, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

S = 0.6  # sampling spacing of the reference (mm)
COVER = ref.cover(S)
TOOL = (0.0, 0.0, 200.0, 0.0, 0.0, 0.0)
Q0 = ROBOT.solve((350.0, 0.0, 100.0, 180.0, 0.0, 0.0), None, None, tool=TOOL)
TCP = np.asarray(ROBOT.fk_matrix(Q0, tool=TOOL), dtype=float)
if TCP.shape == (3, 4):
    TCP = np.vstack([TCP, [0.0, 0.0, 0.0, 1.0]])
# few examples, the same on every run, no shrinking (a failure is reported as found: CI stays fast)
SETTINGS = settings(max_examples=4, derandomize=True, deadline=None, phases=[Phase.explicit, Phase.generate],
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                           HealthCheck.filter_too_much])


def _mesh_data(m, solid: bool = True) -> MeshData:
    return MeshData("test.stl", np.asarray(m.vertices, dtype=float), np.asarray(m.faces, dtype=np.int64), solid)


def _sheet():
    import trimesh

    g = np.linspace(-35.0, 35.0, 4)
    X, Y = np.meshgrid(g, g)
    v = np.c_[X.ravel(), Y.ravel(), np.zeros(16)]
    f = []
    for i in range(3):
        for j in range(3):
            a = i * 4 + j
            f += [[a, a + 1, a + 5], [a, a + 5, a + 4]]
    return trimesh.Trimesh(v, np.array(f), process=False)


@functools.cache
def shapes() -> dict[str, tuple[Shape, np.ndarray, float]]:
    """name -> (shape, dense samples of its surface in its frame, bounding radius)."""
    import trimesh

    ico = ref.convex_meshes()["icosphere"]
    boxmesh = ref.convex_meshes()["boxmesh"]
    chan = ref.channel()
    cage = trimesh.creation.box((60.0, 60.0, 60.0))
    sheet = _sheet()
    out = {
        "sphere": (Shape("sphere", (12.0,)), ref.sample_sphere(12.0, S), 12.0),
        "box": (Shape("box", (30.0, 20.0, 16.0)), ref.sample_box((30.0, 20.0, 16.0), S), 19.7),
        "cylinder": (Shape("cylinder", (8.0, 36.0)), ref.sample_cylinder(8.0, 36.0, S), 19.7),
        "icosphere": (Shape("mesh", (), _mesh_data(ico)), ref.sample_mesh(ico, S), 25.0),
        "boxmesh": (Shape("mesh", (), _mesh_data(boxmesh)), ref.sample_mesh(boxmesh, S), 35.4),
        "channel": (Shape("mesh", (), _mesh_data(chan)), ref.sample_mesh(chan, S), 72.2),
        "sheet": (Shape("mesh", (), _mesh_data(sheet, solid=False)), ref.sample_mesh(sheet, S), 49.5),
        "cage": (Shape("mesh", (), _mesh_data(cage, solid=False)), ref.sample_mesh(cage, S), 52.0),
    }
    return out


@functools.cache
def _tree(name: str):
    from scipy.spatial import cKDTree

    return cKDTree(shapes()[name][1])


def _pose(R: np.ndarray, t) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = t
    return T


def run(a: str | Shape, pose_a: np.ndarray, b: str | Shape, pose_b: np.ndarray, touch: float = 0.05):
    """Shape a (a name of `shapes` or a Shape) as a tool solid at pose_a (world), shape b as an
    obstacle at pose_b (world): the report of the arm holding still there."""
    cell = Cell(path="test", touch_mm=touch)
    cell.obstacles.append(Obstacle("b", shapes()[b][0] if isinstance(b, str) else b, "world", pose_b))
    cell.tools.append(ToolSolid("a", "tTool", shapes()[a][0] if isinstance(a, str) else a,
                                np.linalg.inv(TCP) @ pose_a))
    chk = CollisionChecker(ARM, cell, tools={"tTool": TOOL})
    return chk.check_motion(MotionSpan(1), [0.0], [Q0])


def to_surface(name: str, pose: np.ndarray, p) -> float:
    """The reference distance from a world point to a shape's surface (sampled)."""
    x = (np.asarray(p, dtype=float) - pose[:3, 3]) @ pose[:3, :3]
    return float(_tree(name).query(x)[0])


def sample_distance(a: str, pose_a: np.ndarray, b: str, pose_b: np.ndarray) -> float:
    """The reference distance between the two surfaces (samples of a against samples of b): a
    coarse look first (one sample in 50) bounds the search of the whole."""
    pa = ref.transform(shapes()[a][1], np.linalg.inv(pose_b) @ pose_a)
    tree = _tree(b)
    upper = float(tree.query(pa[::50])[0].min())
    d, _ = tree.query(pa, distance_upper_bound=upper + 1e-9)
    return float(min(d.min(), upper))


def _clear_of(a: str, b: str, pose_a: np.ndarray, pose_b: np.ndarray) -> bool:
    """Whether the solids are apart for sure: the surfaces' samples further apart than the sampling
    error, and no solid inside the other (one's centre outside the other's bounding sphere)."""
    d = sample_distance(a, pose_a, b, pose_b)
    far = np.linalg.norm(pose_a[:3, 3] - pose_b[:3, 3]) > shapes()[a][2] + shapes()[b][2]
    return d > 3.0 * COVER and (far or _outside(a, pose_a, b, pose_b))


def _outside(a: str, pose_a: np.ndarray, b: str, pose_b: np.ndarray) -> bool:
    """A's sample points and B's are not inside the other: checked with the analytic inside of
    primitives and the convex hulls of convex meshes; the channel and the surfaces only by their
    samples (apart when far enough)."""
    import trimesh

    for x, px, y, py in ((a, pose_a, b, pose_b), (b, pose_b, a, pose_a)):
        p = ref.transform(shapes()[x][1][::50], np.linalg.inv(py) @ px)
        shape = shapes()[y][0]
        if shape.kind == "sphere" and (np.linalg.norm(p, axis=1) < shape.size[0]).any():
            return False
        if shape.kind == "box" and (np.abs(p) < 0.5 * np.asarray(shape.size)).all(axis=1).any():
            return False
        if shape.kind == "cylinder" and ((np.hypot(p[:, 0], p[:, 1]) < shape.size[0])
                                         & (np.abs(p[:, 2]) < 0.5 * shape.size[1])).any():
            return False
        if shape.kind == "mesh" and shape.mesh.solid:
            m = trimesh.Trimesh(shape.mesh.vertices, shape.mesh.faces, process=False)
            if y == "channel":
                if (_in_channel(p)).any():
                    return False
            elif (np.einsum("ij,kj->ik", p, m.face_normals) - (m.face_normals * m.triangles_center).sum(1)
                  < 0.0).all(axis=1).any():
                return False
    return True


def _in_channel(p: np.ndarray) -> np.ndarray:
    x, y, z = p[:, 0], p[:, 1], p[:, 2]
    inz = np.abs(z) < 30.0
    bottom = (np.abs(x) < 50.0) & (y > -40.0) & (y < -20.0)
    walls = (np.abs(x) > 30.0) & (np.abs(x) < 50.0) & (y > -40.0) & (y < 40.0)
    return inz & (bottom | walls)


NAMES = ["sphere", "box", "cylinder", "icosphere", "boxmesh", "channel", "sheet", "cage"]
unit = st.floats(0.0, 0.999)


@pytest.mark.parametrize("a", ["sphere", "box", "cylinder", "icosphere", "channel"])
@pytest.mark.parametrize("b", NAMES)
@SETTINGS
@given(ra=st.tuples(unit, unit, unit), rb=st.tuples(unit, unit, unit), direction=st.tuples(unit, unit),
       gap=st.floats(1.0, 40.0))
def test_clearance_and_nearest_points_of_every_pair(a, b, ra, rb, direction, gap):
    """Apart: the clearance is the distance, the nearest points are on their solids (world), as far
    apart as the clearance."""
    # b at a random direction from a, in the lower half (away from the arm), their bounding
    # spheres `gap` apart; or, when a fits, a inside the cage (a surface) or between the
    # channel's walls, up to `gap` mm from the middle
    R_a, R_b = ref.random_rotation(ra), ref.random_rotation(rb)
    pose_a = _pose(R_a, TCP[:3, 3])
    theta, phi = 2 * math.pi * direction[0], math.acos(-direction[1])
    u = np.array([math.cos(theta) * math.sin(phi), math.sin(theta) * math.sin(phi), math.cos(phi)])
    r_a = shapes()[a][2]
    if b == "cage" and r_a < 28.0:
        middle, room = np.zeros(3), 29.0 - r_a
    elif b == "channel" and r_a < 28.0:
        middle, room = np.array([0.0, 10.0, 0.0]), 29.0 - r_a
    else:
        middle, room = None, 0.0
    if middle is None:
        pose_b = _pose(R_b, TCP[:3, 3] + (r_a + shapes()[b][2] + gap) * u)
    else:  # b's `middle` (its frame) near the tool
        pose_b = _pose(R_b, TCP[:3, 3] - R_b @ middle + min(gap, room) * u)
    hypothesis.assume(_clear_of(a, b, pose_a, pose_b))
    rep = run(a, pose_a, b, pose_b)
    assert rep.starts_in_collision is None
    m = rep.min_clearance
    assert m is not None and (m.body_a, m.body_b) == ("tool tTool 'a'", "obstacle 'b'")
    d_ref = sample_distance(a, pose_a, b, pose_b)
    assert m.mm <= d_ref + 1e-6 and m.mm >= d_ref - 2.0 * COVER - 1e-3, (m.mm, d_ref)
    assert to_surface(a, pose_a, m.point_a) <= COVER + 1e-3
    assert to_surface(b, pose_b, m.point_b) <= COVER + 1e-3
    assert math.dist(m.point_a, m.point_b) == pytest.approx(m.mm, abs=1e-3)


# ---- spheres: analytic ----------------------------------------------------------------------------------------


def _sphere_to(b: str, pose_b: np.ndarray, c: np.ndarray) -> float:
    """Signed distance from a point to the solid of a primitive (negative inside): analytic."""
    shape = shapes()[b][0]
    x = np.linalg.inv(pose_b)[:3, :3] @ c + np.linalg.inv(pose_b)[:3, 3]
    if shape.kind == "sphere":
        return float(np.linalg.norm(x) - shape.size[0])
    if shape.kind == "box":
        h = 0.5 * np.asarray(shape.size)
        out = ref.point_to_box(x, shape.size)
        return out if out > 0.0 else -float((h - np.abs(x)).min())
    r, length = shape.size
    out = ref.point_to_cylinder(x, r, length)
    return out if out > 0.0 else -min(r - math.hypot(x[0], x[1]), length / 2 - abs(x[2]))


@pytest.mark.parametrize("b", ["sphere", "box", "cylinder"])
@SETTINGS
@given(rb=st.tuples(unit, unit, unit), offset=st.tuples(st.floats(-40, 40), st.floats(-40, 40), st.floats(-40, 40)))
def test_a_ball_against_a_primitive_is_exact(b, rb, offset):
    """A ball: the clearance is the distance of its centre to the solid minus its radius, apart or
    overlapping (then minus the penetration depth), to 1e-6 mm; a contact exactly when the
    overlap is deeper than the touch tolerance."""
    pose_a = _pose(np.eye(3), TCP[:3, 3])
    pose_b = _pose(ref.random_rotation(rb), TCP[:3, 3] + np.asarray(offset))
    expected = _sphere_to(b, pose_b, pose_a[:3, 3]) - 12.0
    hypothesis.assume(abs(expected + 0.05) > 1e-3)  # not at the touch tolerance itself
    rep = run("sphere", pose_a, b, pose_b)
    if expected > 0.0:
        assert rep.starts_in_collision is None
        assert rep.min_clearance.mm == pytest.approx(expected, abs=1e-5)
    else:
        c = rep.starts_in_collision
        assert (c is not None) == (expected < -0.05)
        assert rep.min_clearance.mm == pytest.approx(expected, abs=1e-5)
        if c is not None:
            assert c.depth_mm == pytest.approx(-expected, abs=1e-5)
    pa, pb = np.asarray(rep.min_clearance.point_a), np.asarray(rep.min_clearance.point_b)
    assert np.linalg.norm(pa - pose_a[:3, 3]) <= 12.0 + 1e-6  # a point of the ball
    assert abs(_sphere_to(b, pose_b, pb)) <= 1e-5  # on b's surface
    assert np.linalg.norm(pa - pb) == pytest.approx(abs(expected), abs=1e-5)


# ---- overlaps of convex solids: the penetration depth -----------------------------------------------------------


@pytest.mark.parametrize("a", ["box", "cylinder", "icosphere", "boxmesh"])
@pytest.mark.parametrize("b", ["box", "cylinder", "icosphere", "boxmesh"])
@SETTINGS
@given(ra=st.tuples(unit, unit, unit), rb=st.tuples(unit, unit, unit),
       offset=st.tuples(st.floats(-30, 30), st.floats(-30, 30), st.floats(-30, 30)))
def test_overlapping_convex_solids_give_the_penetration_depth(a, b, ra, rb, offset):
    """Convex solids (primitives, convex meshes) overlapping: a contact when the penetration depth
    (the shortest separating translation, by brute force over directions) exceeds the touch
    tolerance, and the clearance is minus that depth."""
    pose_a = _pose(ref.random_rotation(ra), TCP[:3, 3])
    pose_b = _pose(ref.random_rotation(rb), TCP[:3, 3] + np.asarray(offset))
    pa = ref.transform(shapes()[a][1], pose_a)
    pb = ref.transform(shapes()[b][1], pose_b)
    depth = ref.penetration_depth(pa, pb)
    err = 2.0 * COVER  # the reference's own error (samples of curved surfaces)
    hypothesis.assume(depth > 0.05 + err)
    rep = run(a, pose_a, b, pose_b)
    c = rep.starts_in_collision
    assert c is not None and c.kind in ("contact", "inside")
    assert c.depth_mm == pytest.approx(depth, abs=err + 0.02)
    assert rep.min_clearance.mm == pytest.approx(-c.depth_mm, abs=1e-9)


# ---- meshes that are not convex, and surfaces ---------------------------------------------------------------------


def _support(name: str, R: np.ndarray, n: np.ndarray) -> float:
    """max over the shape's points x (rotated by R, centred at 0) of n·x: analytic for primitives,
    over the vertices for a mesh."""
    shape = shapes()[name][0]
    m = R.T @ n
    if shape.kind == "sphere":
        return shape.size[0]
    if shape.kind == "box":
        return float(np.abs(m) @ (0.5 * np.asarray(shape.size)))
    if shape.kind == "cylinder":
        return float(shape.size[0] * math.hypot(m[0], m[1]) + 0.5 * shape.size[1] * abs(m[2]))
    return float((shape.mesh.vertices @ m).max())


# faces of the channel (in its frame) a solid can poke into: a point on it, its outward normal,
# how far from that point the face is flat and free on each side
CHANNEL_FACES = {
    "outer bottom": ((0.0, -40.0, 0.0), (0.0, -1.0, 0.0)),
    "outer side": ((50.0, 0.0, 0.0), (1.0, 0.0, 0.0)),
    "inner bottom": ((0.0, -20.0, 0.0), (0.0, 1.0, 0.0)),
}


@pytest.mark.parametrize("a", ["sphere", "box", "cylinder", "icosphere"])
@pytest.mark.parametrize("face", sorted(CHANNEL_FACES))
@SETTINGS
@given(ra=st.tuples(unit, unit, unit), rb=st.tuples(unit, unit, unit), depth=st.floats(0.2, 8.0),
       along=st.floats(-4.0, 4.0))
def test_a_solid_poking_into_a_non_convex_mesh(a, face, ra, rb, depth, along):
    """A solid pushed `depth` mm into a flat face of the U channel (non-convex): a contact, the
    penetration depth is `depth` (the deepest of its points: exact for a ball, a box and a mesh;
    within the rim's sampling for a cylinder), the witnesses are a point of the solid and a point
    of the channel's surface, `depth` apart."""
    R_a, R_b = ref.random_rotation(ra), ref.random_rotation(rb)
    if a != "sphere" and face == "inner bottom":
        R_a = R_b  # between the channel's walls (60 mm apart), only upright solids fit
    p, n = (np.asarray(v, dtype=float) for v in CHANNEL_FACES[face])
    # the solid's centre, in the channel's frame: its deepest point `depth` inside the face
    t = np.array([0.0, 0.0, along])
    if face == "outer side":
        t = np.array([0.0, along, 0.0])
    centre = p + t + n * (_support(a, R_b.T @ R_a, -n) - depth)
    pose_b = _pose(R_b, TCP[:3, 3] - R_b @ centre)  # the solid at the TCP
    pose_a = _pose(R_a, TCP[:3, 3])
    rep = run(a, pose_a, "channel", pose_b)
    c = rep.starts_in_collision
    bound = 8.0 * (1.0 - math.cos(math.pi / 64)) + 1e-6 if a == "cylinder" else 1e-6
    assert c is not None and c.kind == "contact"
    assert depth - bound <= c.depth_mm <= depth + 1e-6
    m = rep.min_clearance
    assert m.mm == pytest.approx(-c.depth_mm, abs=1e-9)
    assert to_surface("channel", pose_b, m.point_b) <= COVER + 1e-3
    assert math.dist(m.point_a, m.point_b) == pytest.approx(c.depth_mm, abs=1e-6)


@pytest.mark.parametrize("a", ["sphere", "box", "cylinder"])
@SETTINGS
@given(rb=st.tuples(unit, unit, unit), x=st.floats(-15.0, 15.0), y=st.floats(-33.0, -27.0), z=st.floats(-15.0, 15.0))
def test_a_solid_wholly_inside_a_non_convex_closed_mesh(a, rb, x, y, z):
    """A small solid inside the bottom bar of the channel (20 mm thick), touching no triangle: a
    contact of kind "inside", the clearance minus its depth (a ball: its radius plus how deep its
    centre is); the same channel as a surface holds nothing: no contact, the clearance is the
    distance to its triangles."""
    small = {"sphere": Shape("sphere", (4.0,)), "box": Shape("box", (6.0, 5.0, 4.0)),
             "cylinder": Shape("cylinder", (2.5, 6.0))}[a]
    R_b = ref.random_rotation(rb)
    centre = np.array([x, y, z])
    pose_b = _pose(R_b, TCP[:3, 3] - R_b @ centre)
    cell = Cell(path="test")
    cell.obstacles.append(Obstacle("b", shapes()["channel"][0], "world", pose_b))
    cell.tools.append(ToolSolid("a", "tTool", small, np.eye(4)))
    rep = CollisionChecker(ARM, cell, tools={"tTool": TOOL}).check_motion(MotionSpan(1), [0.0], [Q0])
    c = rep.starts_in_collision
    assert c is not None and c.kind == "inside" and c.body_a == "tool tTool 'a'"
    h = min(y + 40.0, -20.0 - y, 30.0 - abs(z))  # the centre's depth in the bar
    if a == "sphere":
        assert c.depth_mm == pytest.approx(4.0 + h, abs=1e-6)
    else:
        assert h <= c.depth_mm <= h + 6.0
    assert rep.min_clearance.mm == pytest.approx(-c.depth_mm, abs=1e-9)
    # as a surface
    surface = Shape("mesh", (), MeshData("c.stl", small_mesh_vertices(), small_mesh_faces(), solid=False))
    cell.obstacles[0] = Obstacle("b", surface, "world", pose_b)
    rep = CollisionChecker(ARM, cell, tools={"tTool": TOOL}).check_motion(MotionSpan(1), [0.0], [Q0])
    assert rep.starts_in_collision is None and rep.min_clearance.mm > 0.0


def small_mesh_vertices():
    return np.asarray(ref.channel().vertices, dtype=float)


def small_mesh_faces():
    return np.asarray(ref.channel().faces, dtype=np.int64)


@pytest.mark.parametrize("a", ["sphere", "box", "cylinder"])
@SETTINGS
@given(ra=st.tuples(unit, unit, unit), h=st.floats(-6.0, 6.0), x=st.floats(-10, 10), y=st.floats(-10, 10))
def test_a_solid_crossing_a_surface(a, ra, h, x, y):
    """A solid whose centre is h mm from a flat surface (solid = false) crossing it: a contact
    when it reaches through by more than the touch tolerance (a ball: depth r - |h|, exact; other
    solids: at least what fcl finds per triangle)."""
    R_a = ref.random_rotation(ra) if a != "sphere" else np.eye(3)
    pose_a = _pose(R_a, TCP[:3, 3])
    pose_b = _pose(np.eye(3), TCP[:3, 3] + np.array([x, y, -h]))
    reach_down = _support(a, R_a, np.array([0.0, 0.0, -1.0]))
    reach_up = _support(a, R_a, np.array([0.0, 0.0, 1.0]))
    through = min(reach_down - h, reach_up + h)  # how far the solid reaches past the sheet on its thinner side
    hypothesis.assume(abs(through - 0.05) > 0.02)
    rep = run(a, pose_a, "sheet", pose_b)
    c = rep.starts_in_collision
    if through < 0.05:
        assert c is None
        return
    assert c is not None and c.kind == "contact"
    if a == "sphere":
        assert c.depth_mm == pytest.approx(12.0 - abs(h), abs=1e-6)
    else:
        assert 0.05 < c.depth_mm <= through + 1e-6


def test_a_ball_inside_a_surface_box_is_clear_and_measured_to_the_faces():
    """A closed mesh read as a surface (solid = false) has no inside: a ball in the middle of a
    60 mm cage is 30 - 12 = 18 mm clear of it."""
    pose = _pose(np.eye(3), TCP[:3, 3])
    rep = run("sphere", pose, "cage", pose)
    assert rep.starts_in_collision is None
    assert rep.min_clearance.mm == pytest.approx(18.0, abs=1e-6)
    assert abs(abs(np.asarray(rep.min_clearance.point_b) - TCP[:3, 3]).max() - 30.0) < 1e-6


# ---- the cases of issue 24 -----------------------------------------------------------------------------------------


@pytest.mark.parametrize("into", [5.0, 15.0])
@pytest.mark.parametrize("wall", ["box", "convex mesh", "channel"])
def test_a_ball_going_into_a_wall_is_a_contact_whatever_the_wall(into, wall):
    """Issue 24: a ball 5 mm, then 15 mm into a mesh wall was "no contact"; as a box, R031. Now the
    same contact and depth for a box, a mesh of the same box and a non-convex mesh."""
    import trimesh

    if wall == "box":
        shape = Shape("box", (20.0, 200.0, 60.0))
    elif wall == "convex mesh":
        shape = Shape("mesh", (), _mesh_data(trimesh.creation.box((20.0, 200.0, 60.0))))
    else:
        shape = shapes()["channel"][0]
    if wall == "channel":  # the channel's outer side x = 50, its material towards -x
        face_x = TCP[0, 3] - 12.0 + into
        centre = face_x - 50.0
    else:  # the wall from x = face_x to face_x + 20
        face_x = TCP[0, 3] + 12.0 - into
        centre = face_x + 10.0
    pose_b = _pose(np.eye(3), [centre, TCP[1, 3], TCP[2, 3]])
    rep = run("sphere", _pose(np.eye(3), TCP[:3, 3]), shape, pose_b)
    c = rep.starts_in_collision
    assert c is not None and c.kind == "contact" and c.depth_mm == pytest.approx(into, abs=1e-6)
    assert rep.min_clearance.mm == pytest.approx(-into, abs=1e-6)


def test_nearest_points_of_a_ball_beside_a_non_convex_channel_are_in_world():
    """Issue 24: a ball passing 15 mm from a channel gave its local coordinates, swapped. The ball
    (r 12) 15 mm off the channel's outer side x = 50: the ball's nearest point is 15 mm from the
    face, the channel's on it, both in world."""
    pose_b = _pose(np.eye(3), TCP[:3, 3] - np.array([50.0 + 15.0 + 12.0, 0.0, 0.0]))
    rep = run("sphere", _pose(np.eye(3), TCP[:3, 3]), "channel", pose_b)
    m = rep.min_clearance
    assert m.mm == pytest.approx(15.0, abs=1e-6)
    np.testing.assert_allclose(m.point_a, TCP[:3, 3] - [12.0, 0.0, 0.0], atol=1e-6)
    np.testing.assert_allclose(m.point_b, TCP[:3, 3] - [27.0, 0.0, 0.0], atol=1e-6)


def test_a_rod_into_a_box_or_its_mesh_gives_the_same_negative_clearance():
    """Issue 24: a 15 mm overlap of a rod with a box was -15.0, with a mesh of the same box -42.97."""
    import trimesh

    out = []
    R = np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]])  # the rod's axis along world x
    for shape in (Shape("box", (40.0, 200.0, 60.0)),
                  Shape("mesh", (), _mesh_data(trimesh.creation.box((40.0, 200.0, 60.0))))):
        axis = R[:, 2]
        pose_a = _pose(R, TCP[:3, 3])
        # the rod's end (18 mm from its centre along its axis) 15 mm into the box's face
        tip = TCP[:3, 3] + 18.0 * axis
        pose_b = _pose(np.eye(3), tip + axis * (20.0 - 15.0))
        rep = run("cylinder", pose_a, shape, pose_b)
        out.append(rep.min_clearance.mm)
        assert rep.starts_in_collision is not None
    assert out[0] == pytest.approx(-15.0, abs=1e-6) and out[1] == pytest.approx(-15.0, abs=1e-6)
