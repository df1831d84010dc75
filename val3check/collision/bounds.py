"""What is known of each watch along one motion before and between measurements: the motion
bound (docs/cell.md, "How the check works"), the broad phase's boxes, and the lower bound of the
distance at every sample that the measurements raise.

    layout = scene_layout(world, watches)          # once per scene
    tracks = prepare(path, layout, watches, steps, static, touch)   # once per motion
    track.record(u, d, exact, valid)               # after each measurement
"""

from __future__ import annotations

import math

import numpy as np

from ..light_dataclass import dataclass
from .bodies import Body, aabb_gap
from .groups import Group, Watch
from .path import ArmPath

NEAR_MM = 50.0  # obstacles further than this from a body's box swept over a motion: one bound for all samples


class Track:
    """One watch along the motion being checked; per sample (N,), per step (N-1,):

    path_bound    per sample: the motion bound from the start (mm), along the path (it holds
                  between the samples too)
    sample_bound  per sample: the same from sample to sample (how far points are apart at the
                  samples; sharper, but only at the samples)
    box_gap       per sample: a lower bound of the distance from the bodies' boxes
    lower         per sample: the best lower bound of the distance known so far
    exact         per sample: `lower` is a measured, exact distance
    box_free      per step: the boxes alone keep the groups apart along it
    gap_first, gap_last  box_gap at the first and the last sample (floats)
    first_todo    the first step the boxes alone do not keep apart, or -1 when there is none
    landing       body pairs (id, id) touching at the motion's start or end, or allowed to touch
                  since a grasp or release: left out of the clearance
    in_contact    the last measurement found a contact
    first_contact the first contact of the watch in this motion (records.Contact) or None"""

    __slots__ = ("box_free", "box_gap", "exact", "first_contact", "first_todo", "gap_first", "gap_last", "in_contact",
                 "landing", "lower", "path_bound", "sample_bound", "watch")

    def __init__(self, watch: Watch, path_bound: np.ndarray, sample_bound: np.ndarray, box_gap: np.ndarray,
                 lower: np.ndarray, exact: np.ndarray, box_free: np.ndarray, gap_first: float, gap_last: float,
                 first_todo: int) -> None:
        self.watch = watch
        self.path_bound = path_bound
        self.sample_bound = sample_bound
        self.box_gap = box_gap
        self.lower = lower
        self.exact = exact
        self.box_free = box_free
        self.gap_first, self.gap_last, self.first_todo = gap_first, gap_last, first_todo
        self.landing: set[tuple[int, int]] = set()
        self.in_contact = False
        self.first_contact = None

    def bound_at(self, u: float) -> float:
        """The path bound from the start to position u."""
        C = self.path_bound
        n = len(C) - 1
        k = int(u)
        if k >= n:
            return float(C[n])
        return float(C[k] + (u - k) * (C[k + 1] - C[k]))

    def position_at(self, target: float) -> float:
        """The first position u where the path bound from the start reaches `target`."""
        C = self.path_bound
        n = len(C) - 1
        if target >= C[n]:
            return float(n)
        k = int(np.searchsorted(C, target, side="right")) - 1
        k = max(0, min(k, n - 1))
        span = C[k + 1] - C[k]
        f = 0.0 if span <= 0.0 else (target - C[k]) / span
        return k + min(max(f, 0.0), 1.0)

    def record(self, u: float, d: float, exact: bool, valid: float = math.inf) -> None:
        """A measurement d at position u bounds the distance at every sample (before `valid`): d
        minus the motion since."""
        S, C = self.sample_bound, self.path_bound
        k = int(u)
        if k == u:
            bound = d - np.abs(S - S[k])
        else:  # between samples: the path bound to the samples around it, then from sample to sample
            n = len(S) - 1
            before = d - (self.bound_at(u) - C[k]) - np.abs(S - S[k])
            after = d - (C[min(k + 1, n)] - self.bound_at(u)) - np.abs(S - S[min(k + 1, n)])
            bound = np.maximum(before, after)
        if valid < len(self.lower):
            bound[math.ceil(valid):] = -math.inf
        np.maximum(self.lower, bound, out=self.lower)
        if k == u:
            self.lower[k] = max(self.lower[k], d) if not exact else d
            self.exact[k] = self.exact[k] or exact


@dataclass(frozen=True)
class Layout:
    """What `prepare` needs that depends only on the scene (computed once per scene).

    groups, bodies     the arm-side groups and their bodies, in box-column order
    body_group         (B,) the group of each body
    center_local, half_local  (B, 3) each body's box centre and half sizes in its group's frame
    sphere_center, sphere_radius  (G, 3), (G,) a sphere around each group, in its frame
    group_a, group_b   (W,) each watch's groups (-1: the static set)
    weights            (J, W) each watch's bound weights
    pair_a, pair_b     body columns of the pairs of the self watches, one run per watch
    pair_starts        where each self watch's run starts; self_watches: their indexes
    static_watches     indexes of the watches against the static set; static_columns: their
                       bodies' columns"""

    groups: list[Group]
    bodies: list[Body]
    body_group: np.ndarray
    center_local: np.ndarray
    half_local: np.ndarray
    sphere_center: np.ndarray
    sphere_radius: np.ndarray
    group_a: np.ndarray
    group_b: np.ndarray
    weights: np.ndarray
    pair_a: np.ndarray
    pair_b: np.ndarray
    pair_starts: np.ndarray
    self_watches: np.ndarray
    static_watches: list[int]
    static_columns: list[np.ndarray]


def scene_layout(groups: list[Group], watches: list[Watch]) -> Layout:
    """The layout of the arm-side `groups` and the `watches` of a scene."""
    bodies = [b for g in groups for b in g.bodies]
    index = {id(b): i for i, b in enumerate(bodies)}
    spheres = []
    for g in groups:
        pts = np.concatenate([b.points @ b.local[:3, :3].T + b.local[:3, 3] for b in g.bodies])
        rad = max(b.radius for b in g.bodies)
        c = 0.5 * (pts.min(axis=0) + pts.max(axis=0))
        spheres.append((c, float(np.sqrt(((pts - c) ** 2).sum(axis=1)).max()) + rad))
    gindex = {id(g): i for i, g in enumerate(groups)}
    ia, ib, starts, self_w = [], [], [], []
    static_w, static_cols = [], []
    for wi, w in enumerate(watches):
        if w.b is None:
            static_w.append(wi)
            static_cols.append(np.array([index[id(b)] for b in w.a.bodies], dtype=int))
            continue
        first = len(ia)
        for ba in w.a.bodies:
            for bb in w.b.bodies:
                if (id(ba), id(bb)) not in w.skip:
                    ia.append(index[id(ba)])
                    ib.append(index[id(bb)])
        if len(ia) > first:
            starts.append(first)
            self_w.append(wi)
    return Layout(
        groups=groups,
        bodies=bodies,
        body_group=np.array([gindex[id(g)] for g in groups for _ in g.bodies], dtype=int),
        center_local=np.array([b.local[:3, :3] @ b.center + b.local[:3, 3] for b in bodies]),
        half_local=np.array([np.abs(b.local[:3, :3]) @ b.half for b in bodies]),
        sphere_center=np.array([c for c, _ in spheres]).reshape(-1, 3),
        sphere_radius=np.array([r for _, r in spheres]),
        group_a=np.array([gindex[id(w.a)] for w in watches], dtype=int),
        group_b=np.array([gindex[id(w.b)] if w.b is not None else -1 for w in watches], dtype=int),
        weights=np.array([w.weights for w in watches]).T,
        pair_a=np.array(ia, dtype=int),
        pair_b=np.array(ib, dtype=int),
        pair_starts=np.array(starts, dtype=int),
        self_watches=np.array(self_w, dtype=int),
        static_watches=static_w,
        static_columns=static_cols,
    )


def prepare(path: ArmPath, lay: Layout, watches: list[Watch], steps: np.ndarray, static_lo: np.ndarray,
            static_hi: np.ndarray, touch: float) -> list[Track]:
    """The tracks of the watches along the motion, and the boxes of the arm-side bodies at every
    sample (`path.set_boxes`). Per watch and sample: the path bound from the start; the sample
    bound (per step the smaller of the path bound's step and how far the two groups' points move
    in world between the two samples); the boxes' gap (the broad phase; against the static set's
    boxes `static_lo`, `static_hi`); lower = the boxes' gap, not exact; and per step whether the
    boxes alone keep the watch apart along it. `steps`: `ArmPath.step_travel`."""
    n = len(path.times)
    nw = len(watches)
    F = np.stack([path.poses[g.link] for g in lay.groups])  # (G, N, 4, 4)
    rows = F[..., :3]  # (G, N, 4, 3): the rotation's rows (and a row of zeros) of every pose
    if n > 1:
        dC = steps @ lay.weights  # (N-1, watches)
        # how far each group's points move from a sample to the next: |ΔT·c| + ρ·2·sin(θ/2)
        R = F[:, :, :3, :3]
        p = rows_times(rows, lay.sphere_center, range(len(F)))[..., :3] + F[:, :, :3, 3]
        move = np.sqrt(((p[:, 1:] - p[:, :-1]) ** 2).sum(axis=2))
        cos = 0.5 * ((R[:, 1:] * R[:, :-1]).sum(axis=(2, 3)) - 1.0)
        moves = move + lay.sphere_radius[:, None] * np.sqrt(np.maximum(2.0 - 2.0 * np.clip(cos, -1.0, 1.0), 0.0))
        moves = np.vstack([moves, np.zeros((1, n - 1))])  # row -1: the static set does not move
        dS = (moves[lay.group_a] + moves[lay.group_b]).T
        dS = np.minimum(dS, dC)
        Cm = np.vstack([np.zeros(nw), np.cumsum(dC, axis=0)]).T
        Sm = np.vstack([np.zeros(nw), np.cumsum(dS, axis=0)]).T
    else:
        dC = np.zeros((0, nw))
        Cm = Sm = np.zeros((nw, 1))
    # each body's box: its centre carried by its group's frame; its half sizes through |R|
    # (|R_group·R_local| <= |R_group|·|R_local|: exact for solids square to their link)
    c = rows_times(rows, lay.center_local, lay.body_group)[..., :3] + F[lay.body_group, :, :3, 3]
    h = rows_times(np.abs(rows), lay.half_local, lay.body_group)[..., :3]
    lo, hi = c - h, c + h  # (B, N, 3)
    path.set_boxes(lo.transpose(1, 0, 2), hi.transpose(1, 0, 2), {id(b): i for i, b in enumerate(lay.bodies)})
    A = box_gaps(lay, nw, lo, hi, static_lo, static_hi)
    free = (A[:, :-1] + A[:, 1:] - dC.T) > 2.0 * touch
    L = A.copy()
    E = np.zeros((nw, n), dtype=bool)
    # per watch, read as Python values once: the sweep decides from them which watches to look at
    blocked = ~free
    first = np.where(blocked.any(axis=1), blocked.argmax(axis=1), -1) if n > 1 else np.full(nw, -1)
    return [Track(w, *arrays, g0, g1, k) for w, arrays, g0, g1, k in zip(
        watches, zip(Cm, Sm, A, L, E, free), A[:, 0].tolist(), A[:, -1].tolist(), first.tolist())]


def box_gaps(lay: Layout, nw: int, lo: np.ndarray, hi: np.ndarray, static_lo: np.ndarray,
             static_hi: np.ndarray) -> np.ndarray:
    """(W, N): per watch and sample, the gap between the boxes of its two sides (the arm-side boxes
    lo, hi (B, N, 3), a body's samples contiguous; the static set's (S, 3)). Gaps are minima of
    `aabb_gap`s (exact, and never -0.0), so their order and layout do not change a bit."""
    n = lo.shape[1]
    A = np.full((nw, n), np.inf)
    if len(static_lo) and lay.static_watches:
        # boxes swept over the whole motion first: a far obstacle bounds every sample alike
        far = aabb_gap(lo.min(axis=1)[:, None], hi.max(axis=1)[:, None], static_lo[None], static_hi[None])  # (B, S)
        near = far < NEAR_MM
        to_static = np.repeat(np.where(near, np.inf, far).min(axis=1)[:, None], n, axis=1)  # (B, N)
        bi, si = np.nonzero(near)
        if len(bi):
            g = aabb_gap(lo[bi], hi[bi], static_lo[si][:, None], static_hi[si][:, None])  # (pairs, N)
            for j, b in enumerate(bi.tolist()):
                np.minimum(to_static[b], g[j], out=to_static[b])
        for wi, cols in zip(lay.static_watches, lay.static_columns):
            A[wi] = to_static[cols].min(axis=0)
    if len(lay.pair_a):
        ia, ib = lay.pair_a, lay.pair_b
        pair = aabb_gap(lo[ia], hi[ia], lo[ib], hi[ib])  # (pairs, N)
        A[lay.self_watches] = np.minimum.reduceat(pair, lay.pair_starts, axis=0)
    return A


def rows_times(rows: np.ndarray, vectors: np.ndarray, groups) -> np.ndarray:
    """(len(vectors), N, 4): rows[g] @ vectors[i] for each vector i and its group g = groups[i],
    rows (G, N, 4, 3) a view of contiguous poses. One matrix-vector product per vector over the
    rows of all N poses, not one per pose: the same values (a row's product does not depend on the
    rows around it; tests/collision/test_sweep_steps.py checks the bits), without a BLAS call per
    pose."""
    out = np.empty((len(vectors), rows.shape[1], 4))
    for i, g in enumerate(groups):
        np.matmul(rows[g].reshape(-1, 3), vectors[i], out=out[i].reshape(-1))
    return out
