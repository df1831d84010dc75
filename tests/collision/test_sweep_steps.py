"""What makes a sweep cheaper (issue 29, ninth round) gives what the code it replaces gave, bit for
bit: the boxes and motion bounds of `bounds.prepare` from one matrix-vector product per solid over
all the poses' rows (`rows_times`), and the per-watch values the sweep decides from, read once for
all watches."""

from __future__ import annotations

import numpy as np
import pytest

from val3check.collision import Cell, Obstacle, Shape, ToolSolid  # noqa: E402
from val3check.collision import sweep as sweep_module  # noqa: E402
from val3check.collision.bounds import rows_times  # noqa: E402
from val3check.collision.cellfile import trsf_matrix  # noqa: E402

from .helpers import ROBOT, TOOL, MotionSpan, checker, joint_motion, line_motion


def _poses(rng, g: int, n: int, kind: int) -> np.ndarray:
    """(g, n, 4, 4) contiguous poses: random rotations and offsets at several scales, or rows
    with zeros, -0.0, integers and huge or tiny values."""
    F = np.zeros((g, n, 4, 4))
    F[..., 3, 3] = 1.0
    if kind == 0:
        q, _ = np.linalg.qr(rng.normal(size=(g * n, 3, 3)))
        F[..., :3, :3] = q.reshape(g, n, 3, 3)
        F[..., :3, 3] = rng.normal(size=(g, n, 3)) * 500.0
    elif kind == 1:
        F[..., :3, :] = np.round(rng.normal(size=(g, n, 3, 4)) * 3.0)  # exact zeros and integers
        F[..., 0, 0] = -0.0
    else:
        F[..., :3, :] = rng.normal(size=(g, n, 3, 4)) * rng.choice([1e-300, 1e-8, 1.0, 1e8, 1e300], size=(g, n, 3, 4))
    return F


def _per_pose(M: np.ndarray, v: np.ndarray) -> np.ndarray:
    """The formulation `rows_times` replaces: one 3x3 product per pose (M (.., N, 3, 3), v (.., 3))."""
    return (M @ v[:, None, :, None])[..., 0]


@pytest.mark.parametrize("kind", [0, 1, 2])
def test_rows_times_gives_the_per_pose_products_bit_for_bit(kind):
    rng = np.random.default_rng(29 + kind)
    for _ in range(40):
        g, n, b = int(rng.integers(1, 9)), int(rng.integers(1, 300)), int(rng.integers(1, 14))
        F = _poses(rng, g, n, kind)
        groups = rng.integers(0, g, size=b)
        vec = rng.normal(size=(b, 3)) * rng.choice([1e-3, 1.0, 50.0, 1e4])
        if kind == 1:
            vec[0] = (0.0, -0.0, 2.0)
        half = np.abs(rng.normal(size=(b, 3))) * 30.0
        rows = F[..., :3]
        R = F[groups][..., :3, :3]
        got = rows_times(rows, vec, groups)[..., :3]
        assert got.tobytes() == _per_pose(R, vec).tobytes()
        got = rows_times(np.abs(rows), half, groups)[..., :3]
        assert got.tobytes() == _per_pose(np.abs(R), half).tobytes()
        spheres = rng.normal(size=(g, 3)) * 100.0
        got = rows_times(rows, spheres, range(g))[..., :3]
        assert got.tobytes() == _per_pose(F[:, :, :3, :3], spheres).tobytes()


def _cell() -> Cell:
    c = Cell(path="test", margin_mm=5.0)
    c.obstacles.append(Obstacle("table", Shape("box", (400.0, 800.0, 40.0)), "world",
                                trsf_matrix((500.0, 0.0, -120.0, 0, 0, 0))))
    c.obstacles.append(Obstacle("ball", Shape("sphere", (20.0,)), "world", trsf_matrix((350.0, 30.0, 140.0, 0, 0, 0))))
    c.tools.append(ToolSolid("tip", "tTool", Shape("sphere", (10.0,)), np.eye(4)))
    return c


def test_the_tracks_values_read_once_are_their_arrays(monkeypatch):
    """gap_first, gap_last and first_todo, read for all watches at once, are each track's box gap
    at its ends and its first step the boxes do not keep apart (-1: none), for motions of one,
    two and many samples, near and far from the cell."""
    seen = []
    prepare = sweep_module.prepare

    def keep(*a, **k):
        tracks = prepare(*a, **k)
        seen.append(tracks)
        return tracks

    monkeypatch.setattr(sweep_module, "prepare", keep)
    chk = checker(_cell())
    q = ROBOT.solve((350.0, -200.0, 100.0, 180.0, 0.0, 0.0), None, None, tool=TOOL)
    chk.check_motion(MotionSpan(1), [0.0], [q])
    chk.check_motion(MotionSpan(2), [0.0, 0.004], [q, q])
    times, Q = line_motion((350.0, -200.0, 100.0), (350.0, 200.0, 100.0), 250.0)
    chk.check_motion(MotionSpan(3), times, Q)
    chk.check_motion(MotionSpan(4), *joint_motion([-25.0, 13.0, 90.0, 154.0, 73.0, -172.0],
                                                   [-25.0, 13.0, 150.0, 154.0, 73.0, -172.0], 0.5))
    assert [len(t[0].box_gap) for t in seen] == [1, 2, len(times), 126]
    firsts = set()
    for tracks in seen:
        for tr in tracks:
            assert tr.gap_first == tr.box_gap[0] and type(tr.gap_first) is float
            assert tr.gap_last == tr.box_gap[-1] and type(tr.gap_last) is float
            todo = np.nonzero(~tr.box_free)[0]
            assert tr.first_todo == (int(todo[0]) if len(todo) else -1) and type(tr.first_todo) is int
            firsts.add(min(tr.first_todo, 1))
    assert firsts == {-1, 0, 1}  # watches kept apart all along, blocked at the start and later


def _two_calls(q_at, times):
    """The formulation `samples_and_mids` replaces: the samples, then the mid-steps."""
    joints = np.asarray(q_at.many(times), dtype=float)
    if len(times) < 2:  # no step (`step_travel` asks for no mid-step)
        return joints, joints[:0]
    return joints, np.asarray(q_at.many(0.5 * (times[:-1] + times[1:])), dtype=float)


def test_samples_and_mids_in_one_evaluation_are_two_evaluations_bit_for_bit():
    """On a long run of joint lines (motions over one and two spans, windows before, after and
    across motions), and on every motion the bundled pick-and-place sweeps in its first 30 s
    (Cartesian lines, joint moves, blends): the joints at the samples and halfway between them
    from one `q_at.many` call are those of two calls."""
    import sys
    import tempfile
    from pathlib import Path as FsPath

    from val3check.collision.path import samples_and_mids
    from val3check.simulation import collision_run
    from val3check.simulation import own_clock as oc

    from .test_reuse_costs import _long_run, _windows

    traj, spans = _long_run()
    owns = list(oc.own_clocks(traj, _windows(spans)))
    for own in owns:
        got, want = samples_and_mids(own.q_at, own.times), _two_calls(own.q_at, own.times)
        assert got[0].tobytes() == want[0].tobytes() and got[1].tobytes() == want[1].tobytes()

    root = FsPath(__file__).resolve().parents[2]
    sys.path.insert(0, str(root / "tests"))
    from interpretation.simsupport import run_folder

    seen = []
    real = collision_run.samples_and_mids

    def kept(q_at, times):
        seen.append((q_at, times, real(q_at, times)))
        return seen[-1][2]

    app = root / "fixtures" / "valid" / "PickPlace"
    scenario = (root / "fixtures" / "scenarios" / "pickplace.toml").read_text(encoding="utf-8")
    mp = pytest.MonkeyPatch()
    mp.setattr(collision_run, "samples_and_mids", kept)
    try:
        run_folder(app, scenario=scenario, duration=30.0, robot=ROBOT, collisions=True,
                   cell=str(app / "val3check-cell.toml"), tmp_path=FsPath(tempfile.mkdtemp()))
    finally:
        mp.undo()
    assert len(seen) > 30
    for q_at, times, (joints, mids) in seen:
        want = _two_calls(q_at, times)
        assert joints.tobytes() == want[0].tobytes() and mids.tobytes() == want[1].tobytes()


def _box_gaps_before(lay, nw, lo, hi, static_lo, static_hi):
    """The formulation `box_gaps` replaces: on the boxes laid out sample by sample (N, B, 3)."""
    from val3check.collision.bodies import aabb_gap
    from val3check.collision.bounds import NEAR_MM

    n = len(lo)
    A = np.full((nw, n), np.inf)
    if len(static_lo) and lay.static_watches:
        far = aabb_gap(lo.min(axis=0)[:, None], hi.max(axis=0)[:, None], static_lo[None], static_hi[None])
        near = far < NEAR_MM
        to_static = np.broadcast_to(np.where(near, np.inf, far).min(axis=1), (n, len(far))).copy()
        bi, si = np.nonzero(near)
        if len(bi):
            g = aabb_gap(lo[:, bi], hi[:, bi], static_lo[si][None], static_hi[si][None])
            for j in range(len(bi)):
                np.minimum(to_static[:, bi[j]], g[:, j], out=to_static[:, bi[j]])
        for wi, cols in zip(lay.static_watches, lay.static_columns):
            A[wi] = to_static[:, cols].min(axis=1)
    if len(lay.pair_a):
        ia, ib = lay.pair_a, lay.pair_b
        pair = aabb_gap(lo[:, ia], hi[:, ia], lo[:, ib], hi[:, ib])
        A[lay.self_watches] = np.minimum.reduceat(pair, lay.pair_starts, axis=1).T
    return A


def test_box_gaps_on_boxes_laid_out_body_by_body_are_the_gaps_sample_by_sample():
    """Random boxes near and far from a static set (touching, overlapping, apart, infinite), with
    self watches of several pairs: every gap the same bits as on the layout it replaces."""
    from val3check.collision.bounds import Layout, box_gaps

    rng = np.random.default_rng(35)
    for trial in range(60):
        b, n, s = int(rng.integers(1, 14)), int(rng.integers(1, 200)), int(rng.integers(0, 12))
        c = rng.normal(size=(b, n, 3)) * rng.choice([10.0, 100.0, 1000.0])
        h = np.abs(rng.normal(size=(b, n, 3))) * 30.0
        if trial % 4 == 0:
            c = np.round(c / 10.0) * 10.0  # boxes that touch exactly
            h = np.round(h / 5.0) * 5.0
        if trial % 9 == 0:
            c[0, 0, 0] = np.inf
        lo, hi = c - h, c + h
        sc = rng.normal(size=(s, 3)) * 300.0
        sh = np.abs(rng.normal(size=(s, 3))) * 50.0
        static_lo, static_hi = sc - sh, sc + sh
        nstatic = int(rng.integers(0, 5))
        columns = [np.sort(rng.choice(b, size=int(rng.integers(1, b + 1)), replace=False)) for _ in range(nstatic)]
        pa, pb, starts, selfw = [], [], [], []
        for wi in range(nstatic, nstatic + int(rng.integers(0, 4))):
            starts.append(len(pa))
            selfw.append(wi)
            for _ in range(int(rng.integers(1, 6))):
                pa.append(int(rng.integers(0, b)))
                pb.append(int(rng.integers(0, b)))
        nw = nstatic + len(selfw) + 1  # and a watch with no pairs
        lay = Layout(groups=[], bodies=[], body_group=np.zeros(b, dtype=int), center_local=np.zeros((b, 3)),
                     half_local=np.zeros((b, 3)), sphere_center=np.zeros((0, 3)), sphere_radius=np.zeros(0),
                     group_a=np.zeros(nw, dtype=int), group_b=np.zeros(nw, dtype=int), weights=np.zeros((6, nw)),
                     pair_a=np.array(pa, dtype=int), pair_b=np.array(pb, dtype=int),
                     pair_starts=np.array(starts, dtype=int), self_watches=np.array(selfw, dtype=int),
                     static_watches=list(range(nstatic)), static_columns=columns)
        with np.errstate(invalid="ignore"):  # inf - inf: a NaN gap, the same either way
            got = box_gaps(lay, nw, lo, hi, static_lo, static_hi)
            want = _box_gaps_before(lay, nw, lo.transpose(1, 0, 2), hi.transpose(1, 0, 2), static_lo, static_hi)
        assert got.tobytes() == want.tobytes()
