"""The path as the time parameterisation sees it: a grid of path positions with the path's
derivatives, the TCP rates and the limits of the command that owns each gridpoint.

    grid, owners = sample_path(path, a, b, kin, limits)    # between global path positions a and b

A `Grid` gives at each gridpoint the joint derivatives q'(s), q''(s), the rates of the tool centre
point |dp/ds| (mm) and |dθ/ds| (deg), and the limits of 10.3.1 of the command the gridpoint
belongs to (`mdesc.Limits`: joint speeds V, accelerations A, decelerations D, tvel, rvel, all
including the monitor speed); `owners` is that command's key at each gridpoint.
"""

from __future__ import annotations

import math

import numpy as np

from ...light_dataclass import dataclass
from .. import trial_memo

ROWS_KEPT = 128  # grids whose rows are kept (`_assemble`)
XMAX = 1e12  # "no bound" on ṡ² (path units are degrees of joint motion: ṡ stays far below 1e6)
MIN_GRID = 9  # gridpoints of the shortest piece of path given to the solver


@dataclass
class Grid:
    """A path sampled for the time parameterisation (N gridpoints). V, A, D: (N, 6) limits;
    tv, rv: (N,) Cartesian limits; pt, rt: (N,) |dp/ds| (mm) and |dθ/ds| (deg)."""

    s: np.ndarray
    q1: np.ndarray
    q2: np.ndarray
    pt: np.ndarray
    rt: np.ndarray
    V: np.ndarray
    A: np.ndarray
    D: np.ndarray
    tv: np.ndarray
    rv: np.ndarray
    rows: tuple | None = None  # the bytes of q1 .. rv (the time parameterisation's key), when kept

    def __len__(self) -> int:
        """The number of gridpoints."""
        return len(self.s)

    def slice(self, i0: int, i1: int | None = None) -> "Grid":
        """The gridpoints i0..i1 (a Python slice) as a Grid."""
        sl = slice(i0, i1)
        return Grid(self.s[sl], self.q1[sl], self.q2[sl], self.pt[sl], self.rt[sl], self.V[sl], self.A[sl],
                    self.D[sl], self.tv[sl], self.rv[sl])

    def xmax(self) -> np.ndarray:
        """The velocity limit curve from the speed limits: joints, TCP, tool rotation (ṡ²)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            aq = np.abs(self.q1)
            joint = np.where(aq > 1e-12, self.V / aq, np.inf).min(axis=1)
            tcp = np.where(self.pt > 1e-12, self.tv / self.pt, np.inf)
            rot = np.where(self.rt > 1e-12, self.rv / self.rt, np.inf)
            sd = np.minimum(np.minimum(joint, tcp), rot)
        return np.minimum(sd * sd, XMAX)

    def accel_bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """(upper, lower) magnitude of q̈ per gridpoint and axis: q̈ ∈ [-lower, upper] (module doc)."""
        pos = self.q1 >= 0.0
        up = np.where(pos, self.A, self.D)
        lo = np.where(pos, self.D, self.A)
        flat = np.abs(self.q1) < 1e-12
        both = np.minimum(self.A, self.D)
        return np.where(flat, both, up), np.where(flat, both, lo)

    def u_range(self, i: int, x: float) -> tuple[float, float]:
        """[u_min, u_max] of the path acceleration at gridpoint i and speed² x (decel and accel
        limits as in the module docstring)."""
        up, lo = self.accel_bounds_at(i)
        q1 = self.q1[i]
        q2 = self.q2[i]
        umin, umax = -math.inf, math.inf
        for k in range(q1.shape[0]):
            a = q1[k]
            c = q2[k] * x
            if abs(a) < 1e-12:
                continue
            hi = (up[k] - c) / a
            low = (-lo[k] - c) / a
            if a < 0:
                hi, low = low, hi
            umax = min(umax, hi)
            umin = max(umin, low)
        return umin, umax

    def accel_bounds_at(self, i: int):
        """`accel_bounds` at gridpoint i."""
        pos = self.q1[i] >= 0.0
        return np.where(pos, self.A[i], self.D[i]), np.where(pos, self.D[i], self.A[i])



def sample_path(path, a: float, b: float, kin, limits) -> tuple[Grid, np.ndarray]:
    """The path (paths.Path) between global positions a and b sampled for the time
    parameterisation, and the key of the command that owns each gridpoint; `limits(key)` gives
    that command's mdesc.Limits. At least MIN_GRID gridpoints (the solver cannot start and stop
    within fewer)."""
    grid, own = _sample_spans(path, a, b, kin, limits)
    if len(grid) >= MIN_GRID:
        return grid, own
    return _sample_spans(path, a, b, kin, limits, np.linspace(a, b, MIN_GRID))


def gridpoint_before(path, s: float, kin) -> float:
    """The last of the path's own gridpoints (those of the span holding s) at or before global
    position s: a time parameterisation from there samples the path exactly as one from further
    back (planner.py re-times from there)."""
    i, sigma = path.locate(s)
    if i < 0:
        return s
    sig = path.spans[i].sample(kin)["sigma"][:-1]
    k = int(np.searchsorted(sig, sigma + 1e-12 * max(1.0, abs(s)), side="right")) - 1
    return path.offsets[i] + float(sig[max(k, 0)])


def _sample_spans(path, a: float, b: float, kin, limits, points: np.ndarray | None = None) -> tuple[Grid, np.ndarray]:
    """The spans' own gridpoints between a and b (both ends and the junctions included), or
    exactly `points` (a short piece of path)."""
    if points is not None:  # exactly these points (a short piece of path)
        parts = []
        for s_ in points:
            i, sig = path.locate(float(s_))
            sp = path.spans[i]
            smp = sp.sample_at(kin, min(max(sig, 0.0), sp.length))
            own = np.array([sp.owner_at(sig)])
            parts.append((np.array([s_]), smp["q1"], smp["q2"], smp["pt"], smp["rt"], own))
        return _assemble(parts, limits)
    i0, _ = path.locate(a)
    parts = []
    seen: list | None = []  # (rows, the owners' limits) of each span: what `_assemble` keeps its grid by
    i = i0
    while i < len(path.spans):
        off = path.offsets[i]
        sp = path.spans[i]
        lo, hi = max(a - off, 0.0), min(b - off, sp.length)
        if hi < lo - 1e-12 or off > b + 1e-12:
            break
        smp = sp.sample(kin)
        first = not parts
        # the span's rows between lo and hi depend on its samples (shared by the same part of the
        # same geometry, paths.Span.sample), lo, hi and its owners only: a repeated motion reuses them
        start = None
        if first:  # from one of the span's own gridpoints, its very row (a re-timing from there, planner.py)
            sig = smp["sigma"][:-1]
            tol = 1e-12 * max(1.0, abs(a))
            k = int(np.searchsorted(sig, lo - tol))
            start = k if k < len(sig) and abs(sig[k] - lo) <= tol else None
        # (a re-timing from a position off the grid, lo, is not kept: it does not come back)
        memo = smp.setdefault("rows", {})
        key = (lo, hi, first, start, tuple(st for _, st in sp.owners))
        hit = memo.get(key)
        if hit is None:
            hit = _span_rows(sp, smp, kin, lo, hi, first, start)
            if not first or start is not None:
                if len(memo) >= 8:
                    memo.pop(next(iter(memo)))
                memo[key] = hit
            else:
                seen = None  # rows made for this grid only: neither is it kept
        pts, q1, q2, pt, rt, which = hit
        own = np.full(len(pts), sp.owners[0][0]) if which is None else np.array([k for k, _ in sp.owners])[which]
        parts.append((pts + off, q1, q2, pt, rt, own))
        if seen is not None:
            seen.append((hit, tuple([limits(k) for k, _ in sp.owners])))
        if off + sp.length >= b - 1e-12:
            break
        i += 1
    return _assemble(parts, limits, seen, kin)


def _span_rows(sp, smp: dict, kin, lo: float, hi: float, first: bool, start: int | None) -> tuple:
    """(σ, q1, q2, pt, rt, owner) of a span's gridpoints between σ = lo and hi (`_sample_spans`);
    `start`: the row of lo in the span's grid (first span), None when lo is not on it; owner: the
    index in `sp.owners` of each gridpoint's owner (None: the only one)."""
    keys = ("sigma", "q1", "q2", "pt", "rt")
    sig = smp["sigma"][:-1]  # the grid (the last row is the junction point)
    if first:
        from_ = lo
    else:  # at the junction the curvature may jump: constrain this span's side too
        start = len(sig)  # the junction row
        from_ = smp["sigma"][-1]
    j0 = int(np.searchsorted(sig, from_ + 1e-9, side="right"))
    j1 = int(np.searchsorted(sig, hi - 1e-9, side="left"))
    end = len(sig) - 1 if abs(hi - sig[-1]) <= 1e-9 else None
    blocks = []
    if start is None:
        blocks.append(sp.sample_at(kin, lo))
    else:
        blocks.append({k: smp[k][start:start + 1] for k in keys})
    if j1 > j0:
        blocks.append({k: smp[k][j0:j1] for k in keys})
    blocks.append({k: smp[k][end:end + 1] for k in keys} if end is not None else sp.sample_at(kin, hi))
    pts = np.concatenate([bl["sigma"] for bl in blocks])
    q1 = np.vstack([bl["q1"] for bl in blocks])
    q2 = np.vstack([bl["q2"] for bl in blocks])
    pt = np.concatenate([bl["pt"] for bl in blocks])
    rt = np.concatenate([bl["rt"] for bl in blocks])
    which = None
    if len(sp.owners) > 1:
        owner_starts = np.array([st for _, st in sp.owners])
        which = np.clip(np.searchsorted(owner_starts, pts + 1e-12, side="right") - 1, 0, None)
    return pts, q1, q2, pt, rt, which


def _assemble(parts, limits, seen=None, kin=None) -> tuple[Grid, np.ndarray]:
    """One Grid from the parts (s, q1, q2, pt, rt, owners) of consecutive spans, without
    repeated positions, with each owner's limits. `seen`: each part's rows (the very tuple
    `_sample_spans` keeps) and its owners' limits (mdesc.Limits objects): a grid of the same rows
    and limits, the same positions kept, has the same q1 .. rv, shared (read-only views of their
    bytes, `rows`) from the last one; only s (the path's positions) and the owners are new."""
    s = np.concatenate([p[0] for p in parts])
    own = np.concatenate([p[5] for p in parts])
    keep = np.concatenate([[True], np.diff(s) > 1e-9])
    s, own = s[keep], own[keep]
    store = key = None
    if seen is not None and kin is not None and trial_memo.REUSE:
        store = kin.reuse.get("grid-rows")
        if store is None:
            store = kin.reuse.keep("grid-rows", {})
        key = (tuple([(id(rows), tuple([id(lim) for lim in lims])) for rows, lims in seen]), keep.tobytes())
        hit = store.get(key)
        if hit is not None and all(r is rows and all(x is y for x, y in zip(ls, lims))
                                   for (r, ls), (rows, lims) in zip(hit[0], seen)):
            q1, q2, pt, rt, V, A, D, tv, rv, content = hit[1]
            return Grid(s, q1, q2, pt, rt, V, A, D, tv, rv, content), own
    q1 = np.vstack([p[1] for p in parts])[keep]
    q2 = np.vstack([p[2] for p in parts])[keep]
    pt = np.concatenate([p[3] for p in parts])[keep]
    rt = np.concatenate([p[4] for p in parts])[keep]
    n = len(s)
    V = np.empty((n, q1.shape[1]))
    A = np.empty_like(V)
    D = np.empty_like(V)
    tv = np.empty(n)
    rv = np.empty(n)
    for key_ in sorted(set(own.tolist())):  # np.unique's order, without its cost (a few owners)
        m = own == key_
        lim = limits(int(key_))
        V[m], A[m], D[m], tv[m], rv[m] = lim.V, lim.A, lim.D, lim.tvel, lim.rvel
    if store is None:
        return Grid(s, q1, q2, pt, rt, V, A, D, tv, rv), own
    # kept as their bytes (the key of Timing._topp's cache holds the very same), read through views
    content = tuple(x.tobytes() for x in (q1, q2, pt, rt, V, A, D, tv, rv))
    width = q1.shape[1]
    arrays = tuple(np.frombuffer(c).reshape(n, width) if k in (0, 1, 4, 5, 6) else np.frombuffer(c)
                   for k, c in enumerate(content))
    if len(store) >= ROWS_KEPT:
        store.pop(next(iter(store)))
    store[key] = (tuple(seen), (*arrays, content))
    return Grid(s, *arrays, content), own
