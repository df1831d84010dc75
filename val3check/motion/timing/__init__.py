"""Time parameterisation: a path plus its limits → how fast the arm goes along it (10.3).

The one interface the rest of motion/ uses (planner.py), in the spirit of toppra's path /
constraint / algorithm (written here: its grid set the ramps, issue 23):

    timing = Timing(kin)
    piece = timing.time(path, a, b, v0, limits)   # TimedPiece: ṡ along [a, b] from speed v0 to rest
    s, sd = timing.brake(path, a, b, sd0, limits) # stop on the path as soon as the limits allow

`path` is a paths.Path (global path parameter s, in degrees of joint motion), [a, b] a piece of
it between two stops, `limits(key)` the mdesc.Limits of the command whose key owns a stretch of
it. The answer is a profile of breakpoints (s, ṡ) with a constant path acceleration between
them (trajectory.Profile appends it). Inside:

* `grid.py`      the path sampled with the limits at each gridpoint (`Grid`);
* `analytic.py`  the exact profile of a straight joint line under one set of limits (trapezoid);
* `optimal.py`   the time-optimal profile of everything else at the gridpoints (reachability);
* `refine.py`    the bang-bang inside each grid interval (ramps not set by the grid);
* `safe.py`      braking, and the safe profile when no optimal one is found (R019).

Every limit of 10.3.1 is obeyed: joint speeds, accelerations and decelerations, tvel, rvel, all
times the monitor speed (docs/motion.md, "Timing").
"""

from __future__ import annotations

import numpy as np

from ...light_dataclass import dataclass
from .analytic import duration, trapezoid
from .grid import Grid, gridpoint_before, sample_path
from .optimal import TimedProfile, topp
from .safe import brake_stop

MATCH = 1e-9  # relative ṡ² within which a re-timing from further back passes where the arm is
TOPP_CACHE = 512  # time parameterisations remembered (`Timing._topp`)


@dataclass
class TimedPiece:
    """The path speed ṡ at path positions s (constant path acceleration in between), from the
    piece's start speed to rest. `fallback`: no optimal profile was found and the safe, slower one was used
    (R019); `owner`: the key of the command that owns the start of the piece."""

    s: np.ndarray
    sd: np.ndarray
    fallback: bool
    owner: int

    @property
    def duration(self) -> float:
        """The piece's time (s)."""
        return duration(self.s, self.sd)

    def after(self, a: float, v0: float) -> TimedPiece | None:
        """The piece from position a on, when it passes there at speed v0 (ṡ² linear in s between
        breakpoints); None when it does not."""
        s, sd = self.s, self.sd
        i = int(np.clip(np.searchsorted(s, a, side="right") - 1, 0, len(s) - 2))
        ds = s[i + 1] - s[i]
        x = sd[i] ** 2 + (sd[i + 1] ** 2 - sd[i] ** 2) * (a - s[i]) / ds if ds > 0 else sd[i] ** 2
        if abs(x - v0 * v0) > MATCH * max(x, v0 * v0):
            return None
        keep = s > a + 1e-12 * max(1.0, abs(a))
        return TimedPiece(np.concatenate([[a], s[keep]]), np.concatenate([[v0], sd[keep]]), self.fallback, self.owner)


class Timing:
    """Time parameterisations of the paths of one arm (`kin`: kin.ArmKin), with a cache: a cyclic
    program times the same pieces of path again and again."""

    def __init__(self, kin) -> None:
        """Nothing timed yet."""
        self.kin = kin
        self._cache: dict = {}
        # what a caller that keeps results built on these answers records (`recording`)
        self.misses = 0  # topp computed, not remembered: a first answer differs in its last bits
        self.used: list | None = None  # (key, entry) of the remembered answers read

    def holds(self, used: list) -> bool:
        """Whether every remembered answer in `used` (recorded while `used` was `self.used`) is
        still the one remembered: a result built on them is then what a new computation gives."""
        cache = self._cache
        return all(cache.get(k) is e for k, e in used)

    def time(self, path, a: float, b: float, v0: float, limits) -> TimedPiece:
        """The profile of the piece [a, b] of `path` (no stop inside) from path speed v0 to rest:
        exact on a straight joint line with one set of limits, optimal.topp otherwise."""
        grid, owners = sample_path(path, a, b, self.kin, limits)
        s = grid.s
        if _straight(grid, owners):
            aq = np.abs(grid.q1[0])
            mv = aq > 1e-12
            V = float(np.min(grid.V[0][mv] / aq[mv]))
            A = float(np.min(grid.A[0][mv] / aq[mv]))
            D = float(np.min(grid.D[0][mv] / aq[mv]))
            if np.max(grid.pt) * V <= grid.tv[0] and np.max(grid.rt) * V <= grid.rv[0]:
                ss, sd = trapezoid(float(s[-1] - s[0]), v0, V, A, D)
                return TimedPiece(ss + s[0], sd, False, int(owners[0]))
        res = self._topp(grid, v0)
        return TimedPiece(res.s, res.sd, res.fallback, int(owners[0]))

    def time_from(self, path, a: float, b: float, v0: float, limits, speed_at) -> TimedPiece:
        """`time` from position a at speed v0, the same whenever the re-timing happens: timed from
        the path's last gridpoint before a, g, at the speed `speed_at(g, a)` the arm had there on
        its way to a (None: it stood still in between), and taken from a on when the arm is where that
        profile passes (it was not braking yet). A re-timing from a itself would put a gridpoint
        at a, and the discretisation would differ by a few parts in 10⁴ with the moment of the
        re-timing (docs/motion.md, "When the program is ahead of the arm")."""
        if v0 > 0.0:
            g = gridpoint_before(path, a, self.kin)
            v_g = speed_at(g, a) if g < a - 1e-12 * max(1.0, abs(a)) else None
            if v_g is not None:
                cut = self.time(path, g, b, v_g, limits).after(a, v0)
                if cut is not None:
                    return cut
        return self.time(path, a, b, v0, limits)

    def brake(self, path, a: float, b: float, sd0: float, limits) -> tuple[np.ndarray, np.ndarray]:
        """Stop on `path` from position a at speed sd0 as soon as the decelerations allow (at the
        latest at b, the next stop): (s, ṡ) breakpoints ending at rest."""
        grid, _ = sample_path(path, a, b, self.kin, limits)
        return brake_stop(grid, sd0)

    def _topp(self, grid: Grid, v0: float) -> TimedProfile:
        """optimal.topp, remembered: an identical problem has an identical answer. Solved on the
        grid relative to its start (s - s0) and shifted back, so that a remembered answer is the
        computed one to the bit wherever the piece lies on the path."""
        s0 = grid.s[0]
        s_rel = grid.s - s0
        rows = grid.rows
        if rows is None:
            rows = (grid.q1.tobytes(), grid.q2.tobytes(), grid.pt.tobytes(), grid.rt.tobytes(), grid.V.tobytes(),
                    grid.A.tobytes(), grid.D.tobytes(), grid.tv.tobytes(), grid.rv.tobytes())
        key = (v0, s_rel.tobytes(), *rows)
        hit = self._cache.get(key)
        if hit is not None:
            if self.used is not None:
                self.used.append((key, hit))
        else:
            res = topp(Grid(s_rel, grid.q1, grid.q2, grid.pt, grid.rt, grid.V, grid.A, grid.D, grid.tv, grid.rv), v0)
            self.misses += 1
            if len(self._cache) >= TOPP_CACHE:
                self._cache.pop(next(iter(self._cache)))
            hit = self._cache[key] = (res.s, res.sd.copy(), res.fallback)
        s_rel, sd, fallback = hit
        s = s_rel + s0
        s[0], s[-1] = grid.s[0], grid.s[-1]  # the ends exactly (a command ends there)
        return TimedProfile(s, sd.copy(), fallback)


def _straight(grid: Grid, owners: np.ndarray) -> bool:
    """A straight joint line with one set of limits (the exact trapezoid applies)."""
    return bool(np.all(np.abs(grid.q2) < 1e-12) and np.all(owners == owners[0])
                and np.allclose(grid.q1, grid.q1[0], atol=1e-12))
