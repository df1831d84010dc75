"""Geometric paths in joint space: the pieces the arm follows, joined into one path.

Every motion becomes joint-space geometry (the time parameterisation works on joints):

* `JointLine` (movej, 10.1.1): the straight line in joint space from start to target.
* `JointSpline` (movel, movec, Cartesian blends): the joint positions solved on a grid of the
  TCP curve (tracking.py) joined by a cubic spline, with the exact end derivatives when given.
* `JointBlend` (blend joint, 10.1.2.3): the superposition of the two neighbouring motions, each
  continued in a straight joint line at its own rate, weighted by a smooth step (zero first and
  second derivatives at the ends): it leaves the first path at its leave point and joins the
  second at its reach point with the same joint velocity, so the velocity is continuous.

A geometry is parameterised by λ ∈ [0, 1] and has a length `ell` in path units (degrees of joint
motion, Euclidean over the six axes); a `Span` is the part λ ∈ [a, b] of one geometry, with
path parameter σ = (λ - a)·ell. `Path` joins spans end to end: global path parameter s.
"""

from __future__ import annotations

import bisect
import math

import numpy as np

from ..light_dataclass import dataclass, field
from . import path_batch, trial_memo
from .curves import bezier, hermite

TIMING_SPLIT = 4  # gridpoints of the timing per interval of a Cartesian path's knots (8 mm: one per 2 mm)
H_FD = 1e-4  # path-units step of the finite differences of the TCP rates
JUNCTION_EPS = 1e-6  # path units: the second gridpoint of a span, on its side of a junction


class JointLine:
    """movej (10.1.1): the straight line in joint space from q0 to q1; λ the fraction of the way."""
    kind = "joint"

    def __init__(self, q0, q1):
        """The line from joints q0 to q1; its length `ell` is the Euclidean joint distance."""
        self.q0 = np.asarray(q0, dtype=float)
        self.q1 = np.asarray(q1, dtype=float)
        self.delta = self.q1 - self.q0
        self.ell = float(np.linalg.norm(self.delta))

    def q(self, lam, order: int = 0) -> np.ndarray:
        """Joint positions (order 0) or derivatives in λ at λ (array)."""
        lam = np.atleast_1d(np.asarray(lam, dtype=float))
        if order == 0:
            return self.q0 + lam[:, None] * self.delta
        if order == 1:
            return np.broadcast_to(self.delta, (len(lam), len(self.delta))).copy()
        return np.zeros((len(lam), len(self.delta)))

    def grid(self, a: float, b: float) -> np.ndarray:
        """Gridpoints of λ in [a, b] for the time parameterisation: one per 8° of joint motion."""
        n = max(8, min(48, math.ceil(self.ell * (b - a) / 8.0)))  # one per 8° of joint motion
        return np.linspace(a, b, n + 1)


class JointSpline:
    """Joint positions Q (N, 6) at λ and their derivatives D = dq/dλ (from tracking, by central
    differences of the inverse solution), joined by cubic Hermite pieces: C1, and as close to the
    exact inverse solution between gridpoints as a cubic spline."""

    kind = "spline"

    def __init__(self, lam: np.ndarray, Q: np.ndarray, D: np.ndarray):
        """The knots λ, joint positions Q and dq/dλ D (knots on top of each other dropped)."""
        lam = np.asarray(lam, dtype=float)
        apart = np.diff(lam) > 1e-12  # no knots on top of each other
        keep = np.concatenate([[True], apart])
        if len(lam) > 2 and not apart[-1]:  # the last two coincide: keep the curve's end
            keep[-2], keep[-1] = False, True
        self.lam = lam[keep]
        self.Q = np.asarray(Q, dtype=float)[keep]
        self.D = np.asarray(D, dtype=float)[keep]
        if len(self.lam) < 2:
            raise ValueError("a spline needs two points")
        self.ell = max(float(np.linalg.norm(np.diff(self.Q, axis=0), axis=1).sum()), 1e-12)

    def q(self, lam, order: int = 0) -> np.ndarray:
        """Joint positions (order 0) or derivatives in λ, on the cubic Hermite pieces."""
        h, u, p0, m0, p1, m1 = self._pieces(lam)
        d = hermite(u, p0, m0, p1, m1, order)
        return d if order == 0 else d / h ** order

    def q01(self, lam) -> tuple[np.ndarray, np.ndarray]:
        """(`q(lam)`, `q(lam, 1)`) from one search of the knots (Path.q01)."""
        h, u, p0, m0, p1, m1 = self._pieces(lam)
        return hermite(u, p0, m0, p1, m1, 0), hermite(u, p0, m0, p1, m1, 1) / h

    def _pieces(self, lam) -> tuple:
        """The Hermite piece of each λ: its width h, the fraction u across it, its ends and tangents."""
        x = np.atleast_1d(np.asarray(lam, dtype=float))
        knots = self.lam
        i = np.clip(np.searchsorted(knots, x, side="right") - 1, 0, len(knots) - 2)
        h = (knots[i + 1] - knots[i])[:, None]
        u = (x - knots[i])[:, None] / h
        return h, u, self.Q[i], self.D[i] * h, self.Q[i + 1], self.D[i + 1] * h

    def grid(self, a: float, b: float) -> np.ndarray:
        """The time parameterisation's gridpoints in [a, b]: the knots inside, a and b, and
        TIMING_SPLIT - 1 more points evenly between each two (the timing's discretisation error
        shrinks with the spacing, docs/motion.md "Timing")."""
        inner = self.lam[(self.lam > a + 1e-12) & (self.lam < b - 1e-12)]
        knots = np.concatenate([[a], inner, [b]])
        f = np.arange(TIMING_SPLIT) / TIMING_SPLIT
        fine = knots[:-1, None] + f[None, :] * np.diff(knots)[:, None]
        return np.append(fine.ravel(), b)


def blend_length(ell_l: float, ell_r: float) -> float:
    """The path length of a blend whose two sides are ell_l (leave point to the via point, on the
    first path) and ell_r (via point to the reach point, on the second), in path units."""
    return 4.0 * ell_l * ell_r / (ell_l + ell_r)


class BlendParam:
    """The blend's curve parameter u ∈ [0, 1] against its path parameter σ ∈ [0, L]: u' = 1/(2ℓl)
    at the leave point and 1/(2ℓr) at the reach point, linear in between (u quadratic in σ), so
    that the Bézier curve below leaves and joins its neighbours with their own velocity."""

    def __init__(self, ell_l: float, ell_r: float):
        """The parameter of a blend whose sides are ell_l and ell_r long."""
        self.ell_l, self.ell_r = float(ell_l), float(ell_r)
        self.L = blend_length(ell_l, ell_r)
        self.c1 = 1.0 / (2.0 * ell_l)
        self.c2 = (1.0 / (2.0 * ell_r) - self.c1) / (2.0 * self.L)

    def u(self, sigma):
        """u at σ (clipped to [0, 1])."""
        return np.clip(self.c1 * sigma + self.c2 * sigma * sigma, 0.0, 1.0)

    def du(self, sigma):
        """du/dσ at σ."""
        return self.c1 + 2.0 * self.c2 * sigma


def blend_controls(pL, vL, pR, vR, ell_l: float, ell_r: float):
    """Control points of the blend from (pL, vL) to (pR, vR): the corner of the two tangents, as a
    cubic (the degree-raised parabola with its control point at the via point when the
    neighbours are straight lines through it)."""
    return pL, pL + (2.0 / 3.0) * ell_l * vL, pR - (2.0 / 3.0) * ell_r * vR, pR


# The shape of blends: a cubic Hermite curve whose end tangents are `scale` × (ℓl + ℓr) long —
# for two straight lines meeting at the via point with leave = reach, the parabola through their
# corner. ("bezier": the Bézier curve through the corner of the two tangents, tighter when leave
# and reach differ a lot; measured slower on random U cycles, bench/bench_motion.py.) When several
# shapes are listed the queue takes the one its estimate says the arm follows fastest.
BLEND_SHAPES = ("bezier",)


class BlendShape:
    """A blend curve from (pL, vL) to (pR, vR) (positions and velocities per path unit σ), in
    joint or Cartesian space: `point(σ, order)` with σ ∈ [0, ell]; velocity continuous at both
    ends whatever the shape."""

    def __init__(self, pL, vL, pR, vR, ell_l: float, ell_r: float, shape="bezier"):
        """The shape from (pL, vL) to (pR, vR); `shape`: bezier, or a tangent scale (BLEND_SHAPES)."""
        pL, vL, pR, vR = (np.asarray(x, dtype=float) for x in (pL, vL, pR, vR))
        self.shape = shape
        if shape == "bezier":
            self.param = BlendParam(ell_l, ell_r)
            self.ell = self.param.L
            self.P = blend_controls(pL, vL, pR, vR, ell_l, ell_r)
        else:
            self.ell = float(shape) * (ell_l + ell_r)
            self.P = (pL, self.ell * vL, pR, self.ell * vR)

    def point(self, sigma, order: int = 0) -> np.ndarray:
        """Position (or d/dσ, d²/dσ²) at σ (array)."""
        sig = np.atleast_1d(np.asarray(sigma, dtype=float))
        if self.shape != "bezier":
            u = (sig / self.ell)[:, None]
            d = hermite(u, *self.P, order=order)
            return d if order == 0 else d / self.ell ** order
        pr = self.param
        u = pr.u(sig)[:, None]
        if order == 0:
            return bezier(u, *self.P)
        du = pr.du(sig)[:, None]
        d1 = bezier(u, *self.P, order=1)
        if order == 1:
            return d1 * du
        return bezier(u, *self.P, order=2) * du * du + d1 * (2.0 * pr.c2)

    def point01(self, sigma) -> tuple[np.ndarray, np.ndarray]:
        """(`point(σ)`, `point(σ, 1)`) from one evaluation of the parameter (Path.q01)."""
        sig = np.atleast_1d(np.asarray(sigma, dtype=float))
        if self.shape != "bezier":
            u = (sig / self.ell)[:, None]
            return hermite(u, *self.P, order=0), hermite(u, *self.P, order=1) / self.ell
        pr = self.param
        u = pr.u(sig)[:, None]
        return bezier(u, *self.P), bezier(u, *self.P, order=1) * pr.du(sig)[:, None]


class JointBlend:
    """A joint blend (10.1.2.3): from the leave point (qL, velocity vL = dq/dσ of the first path)
    to the reach point (qR, vR of the second) along a `BlendShape` in joint space (the queue picks
    the shape the arm can follow fastest). ℓl, ℓr: the path lengths from the leave point to the
    via point and from there to the reach point."""

    kind = "joint-blend"

    def __init__(self, qL, vL, qR, vR, ell_l: float, ell_r: float, shape="bezier"):
        """The blend from (qL, vL) to (qR, vR) along the shape `shape`."""
        self.curve = None
        self.shape = BlendShape(qL, vL, qR, vR, ell_l, ell_r, shape)
        self.ell = self.shape.ell

    def q(self, lam, order: int = 0) -> np.ndarray:
        """Joint positions (order 0) or derivatives in λ."""
        sig = np.atleast_1d(np.asarray(lam, dtype=float)) * self.ell
        d = self.shape.point(sig, order)
        return d if order == 0 else d * self.ell ** order

    def q01(self, lam) -> tuple[np.ndarray, np.ndarray]:
        """(`q(lam)`, `q(lam, 1)`) from one evaluation of the shape (Path.q01)."""
        sig = np.atleast_1d(np.asarray(lam, dtype=float)) * self.ell
        d0, d1 = self.shape.point01(sig)
        return d0, d1 * self.ell  # (x ** 1 is x)

    def grid(self, a: float, b: float) -> np.ndarray:
        """Gridpoints of λ in [a, b]: one per degree of joint motion (at least 24, at most 240)."""
        n = max(24, min(240, math.ceil(self.ell * (b - a))))
        return np.linspace(a, b, n + 1)


@dataclass(slots=True)  # about 1.7 spans per motion held for the whole run: no __dict__ each
class Span:
    """The part λ ∈ [a, b] of a geometry. `owners`: (command key, σ from which it owns the span)
    — a blend belongs to the first command up to its nominal target, then to the next.
    `smooth`: joined to the previous span with continuous velocity (else the arm stops between
    them). `tool`: the TCP (4x4) whose speed the limits tvel/rvel concern."""

    geom: object
    a: float
    b: float
    owners: list = field(default_factory=list)
    smooth: bool = False
    tool: np.ndarray | None = None
    offset: float | None = None  # global s of its start, once in a Path
    _cache: dict | None = field(default=None, repr=False)
    # its part of a trial memo key (trial_memo.TrialMemo.key): made once (a span never changes)
    kpart: int | None = field(default=None, repr=False, compare=False)

    @property
    def ell(self) -> float:
        """The length of the whole geometry, in path units."""
        return self.geom.ell

    @property
    def length(self) -> float:
        """The span's own length, in path units."""
        return (self.b - self.a) * self.geom.ell

    def lam(self, sigma) -> np.ndarray:
        """The geometry's λ at the span's σ."""
        return self.a + np.asarray(sigma, dtype=float) / self.geom.ell

    def q(self, sigma, order: int = 0) -> np.ndarray:
        """Joint positions (order 0) or derivatives in σ."""
        d = self.geom.q(self.lam(sigma), order)
        return d if order == 0 else d / self.geom.ell ** order

    def end(self) -> np.ndarray:
        """Joint positions at the span's end (read-only): `q([length])[0]`, a function of the
        geometry, a and b only, so kept on the geometry (a repeated motion's spans share it)."""
        memo = self.geom.__dict__.setdefault("_ends", {})
        key = (self.a, self.b)
        hit = memo.get(key) if trial_memo.REUSE else None
        if hit is None:
            hit = self.q([self.length])[0]
            hit.flags.writeable = False
            if len(memo) >= 16:
                memo.pop(next(iter(memo)))
            memo[key] = hit
        return hit

    def owner_at(self, sigma: float):
        """The key of the command that owns the span at σ."""
        key = self.owners[0][0]
        for k, start in self.owners:
            if sigma >= start - 1e-12:
                key = k
        return key

    def sample(self, kin) -> dict:
        """Gridpoints (σ, both ends included) and what the time parameterisation needs there,
        cached: q1 = dq/dσ, q2 = d²q/dσ², pt = |dp/dσ| (mm), rt = |dθ/dσ| (deg) of the TCP; the
        last row is the point JUNCTION_EPS after the start, where the span's own curvature
        applies (the time parameterisation constrains both sides of a junction)."""
        if self._cache is None:
            # the same part of the same geometry with the same tool on the same arm geometry has the
            # same samples (construction.py reuses the geometries of motions that repeat)
            memo = self.geom.__dict__.setdefault("_samples", {})
            key = (self.a, self.b, None if self.tool is None else np.asarray(self.tool, float).tobytes(), id(kin))
            model = getattr(kin, "model", None)
            hit = memo.get(key)
            if hit is not None and hit[0] is model:
                self._cache = hit[1]
                return self._cache
            self._cache = self._sample(kin)
            if len(memo) > 64:
                memo.clear()
            memo[key] = (model, self._cache)
        return self._cache

    def _sample(self, kin) -> dict:
        """`sample`, computed."""
        lam = self.geom.grid(self.a, self.b)
        eps = min(JUNCTION_EPS, 0.5 * self.length) / self.geom.ell
        lam = np.append(lam, self.a + eps)
        sig = (lam - self.a) * self.geom.ell
        q1 = self.geom.q(lam, 1) / self.geom.ell
        q2 = self.geom.q(lam, 2) / self.geom.ell ** 2
        pt, rt = self._rates(kin, lam, q1)
        return {"sigma": sig, "q1": q1, "q2": q2, "pt": pt, "rt": rt}

    def sample_at(self, kin, sigma: float) -> dict:
        """The same at one σ."""
        lam = self.lam(np.array([sigma]))
        q1 = self.q([sigma], 1)
        pt, rt = self._rates(kin, lam, q1)
        return {"sigma": np.array([sigma]), "q1": q1, "q2": self.q([sigma], 2), "pt": pt, "rt": rt}

    def _rates(self, kin, lam, q1):
        """TCP rates per path unit: from the Cartesian curve when the geometry follows one (exact),
        else from the forward kinematics."""
        curve = getattr(self.geom, "curve", None)
        if curve is not None:
            p, r = curve.rates(lam)
            return p / self.geom.ell, r / self.geom.ell
        return tcp_rates(kin, self.geom.q(lam, 0), q1, self.tool)


def batch_kind(geom) -> str | None:
    """The kind (path_batch.py) whose geometries Path.q evaluates together, None for one evaluated
    alone (another class, or a blend whose shape is not the Bézier one)."""
    cls = geom.__class__
    if cls is JointSpline:
        return path_batch.SPLINE
    if cls is JointLine:
        return path_batch.LINE
    if cls is JointBlend and geom.shape.__class__ is BlendShape and geom.shape.shape == "bezier":
        return path_batch.BLEND
    return None


def _evaluate(geom, lam: np.ndarray, orders: tuple):
    """`geom.q(lam, order)` for each order of `orders`; orders 0 and 1 from one evaluation of both
    (`q01`) for the classes that have it (not a subclass: it may have its own `q`)."""
    if orders == (0, 1) and (geom.__class__ is JointSpline or geom.__class__ is JointBlend):
        return geom.q01(lam)
    return [geom.q(lam, order) for order in orders]


def tcp_rates(kin, q: np.ndarray, q1: np.ndarray, tool) -> tuple[np.ndarray, np.ndarray]:
    """|dp/dσ| (mm) and |dθ/dσ| (deg) of the TCP for joint derivatives q1, by central
    differences of the forward kinematics along q1."""
    h = H_FD
    n = len(q)
    T = kin.tcp(np.vstack([q + h * q1, q - h * q1]), tool)
    Tp, Tm = T[:n], T[n:]
    pt = np.linalg.norm(Tp[:, :3, 3] - Tm[:, :3, 3], axis=1) / (2 * h)
    Rrel = np.swapaxes(Tm[:, :3, :3], 1, 2) @ Tp[:, :3, :3]
    c = np.clip((np.trace(Rrel, axis1=1, axis2=2) - 1.0) / 2.0, -1.0, 1.0)
    rt = np.degrees(np.arccos(c)) / (2 * h)
    return pt, rt


class Path:
    """Spans joined end to end; s is the global path parameter (never reset: the arm's whole
    run is one path)."""

    def __init__(self, q_start):
        """An empty path: the arm at rest at q_start."""
        self.spans: list[Span] = []
        self.offsets: list[float] = []
        self.end = 0.0
        self._rest = np.asarray(q_start, dtype=float)  # where the path ends (or starts, empty)
        self._rest_of: Span | None = None  # the last span, its end not evaluated yet (`q_rest`)

    @property
    def q_rest(self) -> np.ndarray:
        """Where the path ends (where it starts while empty): evaluated when asked, a trial path
        (planner.py) appends many spans and never asks."""
        sp = self._rest_of
        if sp is not None:
            self._rest = sp.end()
            self._rest_of = None
        return self._rest

    @q_rest.setter
    def q_rest(self, q) -> None:
        self._rest = q
        self._rest_of = None

    def append(self, span: Span) -> float:
        """Add a span at the end; returns its global offset."""
        off = self.end
        span.offset = off
        self.spans.append(span)
        self.offsets.append(off)
        self.end = off + span.length
        self._rest_of = span
        return off

    def cut(self, s: float) -> None:
        """Drop everything after s (the arm stopped there and its commands were cancelled)."""
        i = self.locate(s)[0] if self.spans else -1
        if i < 0:
            return
        off = self.offsets[i]
        sp = self.spans[i]
        sigma = s - off
        q = sp.q([sigma])[0]
        del self.spans[i + 1:]
        del self.offsets[i + 1:]
        if sigma <= 1e-12:
            del self.spans[i:]
            del self.offsets[i:]
        else:
            self.spans[i] = Span(sp.geom, sp.a, sp.a + sigma / sp.geom.ell, sp.owners, sp.smooth, sp.tool, off)
        self.end = s
        self.q_rest = q

    def locate(self, s: float) -> tuple[int, float]:
        """(span index, σ) of global s (the last span for s at or past the end)."""
        if not self.spans:
            return -1, 0.0
        i = bisect.bisect_right(self.offsets, s) - 1
        i = min(max(i, 0), len(self.spans) - 1)
        return i, s - self.offsets[i]

    def q(self, s, order: int = 0) -> np.ndarray:
        """Joint positions (or derivatives) at global s values (array)."""
        return self._at(s, (order,))[0]

    def q01(self, s) -> tuple[np.ndarray, np.ndarray]:
        """(`q(s)`, `q(s, 1)`) from one search of the spans and one evaluation per geometry: the
        same bits as the two calls (a page samples both at every tick)."""
        return self._at(s, (0, 1))

    def _at(self, s, orders: tuple) -> tuple:
        """`q(s, order)` for each order of `orders`."""
        s = np.atleast_1d(np.asarray(s, dtype=float))
        if not self.spans:
            return tuple(np.tile(self.q_rest if order == 0 else np.zeros_like(self.q_rest), (len(s), 1))
                         for order in orders)
        # only the spans between the smallest and the largest s (the path holds the whole run)
        last = len(self.spans) - 1
        i0 = min(max(bisect.bisect_right(self.offsets, float(s.min())) - 1, 0), last)
        i1 = min(max(bisect.bisect_right(self.offsets, float(s.max())) - 1, 0), last)
        outs = tuple(np.empty((len(s), len(self.q_rest))) for _ in orders)
        if i0 == i1:
            sp = self.spans[i0]
            geom = sp.geom
            lam = sp.a + np.clip(s - self.offsets[i0], 0.0, sp.length) / geom.ell  # (Span.q)
            for out, order, d in zip(outs, orders, _evaluate(geom, lam, orders)):
                out[:] = d if order == 0 else d / geom.ell ** order
            return outs
        offs = np.asarray(self.offsets[i0:i1 + 1])
        idx = np.clip(np.searchsorted(offs, s, side="right") - 1, 0, i1 - i0)
        # one evaluation per geometry touched (a cyclic run's spans share a few), each row's λ
        # found for all rows at once: the same element-wise arithmetic as Span.q span by span, so
        # the same bits
        spans = self.spans[i0:i1 + 1]
        group: dict[int, int] = {}
        n = len(spans)
        label, a, b, ell = np.empty(n, dtype=np.intp), np.empty(n), np.empty(n), np.empty(n)
        geoms = []
        for k, sp in enumerate(spans):
            geom = sp.geom
            g = group.get(id(geom))
            if g is None:
                g = group[id(geom)] = len(geoms)
                geoms.append(geom)
            label[k], a[k], b[k], ell[k] = g, sp.a, sp.b, geom.ell
        row_a, row_ell = a[idx], ell[idx]
        sigma = np.clip(s - offs[idx], 0.0, (b[idx] - row_a) * row_ell)  # (Span.length)
        lam = row_a + sigma / row_ell
        row_label = label[idx]
        order_ = np.argsort(row_label, kind="stable")
        bounds = [0, *(np.flatnonzero(np.diff(row_label[order_])) + 1).tolist(), len(s)]
        together: dict = {}  # the geometries of a kind evaluated together (path_batch.py), with their rows
        for lo, hi in zip(bounds[:-1], bounds[1:]):
            rows = order_[lo:hi]
            geom = geoms[int(row_label[rows[0]])]
            cls = batch_kind(geom)
            if cls is not None:
                held = together.setdefault(cls, ([], []))
                held[0].append(geom)
                held[1].append(rows)
                continue
            for out, order, d in zip(outs, orders, _evaluate(geom, lam[rows], orders)):
                out[rows] = d if order == 0 else d / geom.ell ** order
        for cls, (same, rows_of) in together.items():
            rows = np.concatenate(rows_of)
            g_of = np.repeat(np.arange(len(same)), [len(r) for r in rows_of])
            for out, order, d in zip(outs, orders, path_batch.evaluate(cls, same, rows_of, lam, orders)):
                # (as above: each geometry's ell ** order, a Python power)
                out[rows] = d if order == 0 else d / np.array([g.ell ** order for g in same])[g_of][:, None]
        return outs

    def q_end(self, s, order: int = 0) -> np.ndarray:
        """`q` at positions s that end a motion: where a span starts at s, on the span ending there
        (the motion's own end, not the start of the next one, whose rate in s is another)."""
        s = np.atleast_1d(np.asarray(s, dtype=float))
        out = self.q(s, order)
        for k, x in enumerate(s.tolist()):
            i = bisect.bisect_left(self.offsets, x) - 1  # the span with offset < x
            if 0 <= i < len(self.spans) - 1 and self.offsets[i + 1] == x:
                out[k] = self.spans[i].q(np.array([self.spans[i].length]), order)[0]
        return out

    def stops_after(self, s: float) -> list[float]:
        """Global s of every junction after s where the arm must stop (not smooth)."""
        i = max(bisect.bisect_right(self.offsets, s) - 1, 0)
        return [self.offsets[k] for k in range(i, len(self.spans))
                if not self.spans[k].smooth and self.offsets[k] > s + 1e-12 * max(1.0, abs(s))]
