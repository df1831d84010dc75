"""Compliant moves (11.1) on the simulated arm: the force balance along the move's path decides
whether the arm follows its path, holds, or goes back, through the queue-time warp of
arm_layers.py (the motion queue plans the move as a standard one, blend off).

11.1.3: "Lorsque le paramètre d'effort est positif, tout se passe comme si un effort extérieur
poussait le bras vers la position commandée : le bras se déplace alors tout seul, mais peut être
retenu ou accéléré par une action extérieure"; "nul, le bras est passif, c'est-à-dire qu'il ne se
déplace que sous l'action d'un effort extérieur"; "négatif, tout se passe comme si un effort
extérieur tirait le bras vers sa position initiale : pour déplacer le bras vers la position
commandée, il faut alors fournir un effort extérieur plus fort que l'effort commandé". 11.1.4:
"le bras peut revenir en arrière vers son point de départ, mais il ne peut pas le dépasser : le
bras s'arrête alors brutalement sur le point de départ".

The cell's forces are the scenario's (docs/scenario.md): `[[pushes]]` (a force along the path,
at given times or while a signal has a value) and `[[surfaces]]` (a plane the tool centre point
meets). The net force along the path is the move's nForce plus the pushes (both in % of the
arm's nominal load, positive towards the target):

* net > 0: the arm follows its path with the limits of its mdesc (as a standard move: 11.1.2
  "des limitations de vitesse et d'accélération sont effectuées, comme sur un mouvement
  standard"), until its target, or until its tool centre point meets a surface, where it stops
  and presses on it with the net force;
* net = 0: the arm holds where it is;
* net < 0: the arm goes back along its path, with the same limits, and stops on its start point.

What is a model: the arm's masses are not public, so a force does not give a speed: the arm moves
at its mdesc limits whenever the net force drives it, and stops at once when it no longer does
(and on a surface: a rigid one). The precision of the force "limitée par les frottements
internes" (11.1.4) is not modelled.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from ..diagnostics import Diagnostic
from ..light_dataclass import dataclass, field
from ..motion.motion_records import time_leaving
from ..rules import codes

US = 1_000_000
EPS = 1e-9
# A move that meets a surface ends there (its target is the contact point, contact.py) and holds this
# long before its end: its command never completes while it presses (isEmpty, waitEndMove).
CONTACT_S = 1e-6


@dataclass
class CompliantMove:
    """A compliant command of the queue: its force (% of the nominal load, 11.1.3), its tool (4x4
    mm in the flange, None for the flange), the contact found on its path (path parameter)."""

    command: Any
    force: float
    tool: np.ndarray | None
    contact: tuple[float, str, np.ndarray] | None = None  # (fraction, surface, point) where the tool meets it
    said: bool = False


@dataclass
class Surface:
    """A plane the tool meets (scenario [[surfaces]]): a point, the normal towards the side the
    tool comes from (world frame, mm), its name and scenario line."""

    name: str
    point: np.ndarray
    normal: np.ndarray
    line: int = 0


@dataclass
class Push:
    """A force of the cell along the compliant move's path (% of the nominal load, towards the
    target): during windows of real time [start, end) (end None: for ever)."""

    force: float
    windows: list[list[float | None]] = field(default_factory=list)
    io: Any = None  # a signal it follows, with the value that starts it and the delay
    becomes: Any = True
    after: float = 0.0

    def at(self, t: float) -> float:
        for a, b in self.windows:
            if a <= t + EPS and (b is None or t < b - EPS):
                return self.force
        return 0.0

    def changes_after(self, t: float) -> float | None:
        out = [x for w in self.windows for x in w if x is not None and x > t + EPS]
        return min(out) if out else None

    def signal(self, at: float, value: Any) -> None:
        """The signal it follows changed at `at` (s)."""
        if value == self.becomes:
            self.windows.append([at + self.after, None])
        elif self.windows and self.windows[-1][1] is None:
            self.windows[-1][1] = max(at, self.windows[-1][0])


class Compliance:
    """The compliant moves of one arm and the cell's forces on them (module docstring)."""

    def __init__(self) -> None:
        self.moves: list[CompliantMove] = []
        self.pushes: list[Push] = []
        self.surfaces: list[Surface] = []
        self.report: Callable[[Diagnostic], None] | None = None
        self.t_eval = 0.0
        self._cell_log: Any = None

    # ---- the cell's forces -----------------------------------------------------------------------

    def watch_signals(self, cell: Any) -> None:
        """Follow the signals of the pushes (the cell's log of I/O changes has their exact time)."""
        if self._cell_log is not None:
            return
        self._cell_log = cell.log_io

        def log_io(at: int, io: Any, value: Any, source: str) -> None:
            self._cell_log(at, io, value, source)
            for p in self.pushes:
                if p.io is io:
                    p.signal(at / US, value)

        cell.log_io = log_io

    def push(self, t: float) -> float:
        return sum(p.at(t) for p in self.pushes)

    def _push_change(self, t: float) -> float | None:
        times = [c for c in (p.changes_after(t) for p in self.pushes) if c is not None]
        return min(times) if times else None

    # ---- where the arm is ---------------------------------------------------------------------------

    def window(self, q: Any, move: CompliantMove) -> tuple[float, float | None] | None:
        """(τ start, τ end or None) of a move in queue time, None when not placed on the path."""
        place = move.command.placement
        if move.command.state in ("cancelled", "failed") or place.s_begin is None:
            return None
        prof = q.profile
        ts = time_leaving(prof, place.s_begin)
        if ts is None:
            return None
        te = prof.time_at(place.s_end) if place.s_end is not None else None
        return ts, te

    def current(self, q: Any, tau: float) -> tuple[CompliantMove, float, float | None] | None:
        """The compliant move the arm is on at queue time tau (at its start included)."""
        for move in self.moves:
            w = self.window(q, move)
            if w is None:
                continue
            ts, te = w
            if ts - EPS <= tau and (te is None or tau < te - EPS):
                return move, ts, te
        return None

    def is_compliant(self, q: Any, layers: Any, t: float) -> bool:
        """isCompliant(): the arm is on a compliant move, and no stop holds it (11.1.2: after
        stopMove the robot "ne sera plus compliant jusqu'à l'exécution du restartMove()")."""
        if q is None or q.held or not q.powered or q.monitor <= 0.0:
            return False
        return self.current(q, layers.warp.tau(t)) is not None

    # ---- the force balance over time ------------------------------------------------------------------

    def update(self, q: Any, layers: Any, to: float) -> None:
        """Decide the warp's rate at each change up to real time `to` (s)."""
        if not self.moves:
            self.t_eval = max(self.t_eval, to)
            return
        _ = q.trajectory  # the plan up to date
        warp = layers.warp
        t = min(self.t_eval, to)
        for _ in range(10_000):
            rate, nxt = self._decide(q, warp, t)
            if warp.rate(t) != rate:
                warp.set_rate(t, rate)
            if nxt is None or nxt > to or nxt <= t + 1e-12:
                break
            t = nxt
        self.t_eval = max(self.t_eval, to)

    def next_time(self, q: Any, layers: Any, now: float) -> float | None:
        """The next real time after `now` at which the force balance may change the motion."""
        if not self.moves:
            return None
        self.update(q, layers, now)
        _, nxt = self._decide(q, layers.warp, now)
        return nxt if nxt is not None and nxt > now else None

    def _decide(self, q: Any, warp: Any, t: float) -> tuple[int, float | None]:
        """(the rate from real time t, the next real time to decide again)."""
        tau = warp.tau(t)
        cands = [self._push_change(t)]
        cur = self.current(q, tau)
        if cur is None:
            ahead = [w[0] for w in (self.window(q, m) for m in self.moves) if w is not None and w[0] > tau + EPS]
            if ahead:
                cands.append(t + (min(ahead) - tau))
            return 1, _first(cands)
        move, ts, te = cur
        net = move.force + self.push(t)
        if net > 0:
            if move.contact is None:
                if te is not None:
                    cands.append(t + (te - tau))
                return 1, _first(cands)
            if te is not None and tau >= te - CONTACT_S - EPS:  # on the surface: it presses there
                self._said_contact(move, t, net)
                return 0, _first(cands)
            if te is not None:
                cands.append(t + (te - CONTACT_S - tau))
            return 1, _first(cands)
        if net < 0 and tau > ts + EPS:
            cands.append(t + (tau - ts))
            return -1, _first(cands)
        return 0, _first(cands)

    def _said_contact(self, move: CompliantMove, t: float, net: float) -> None:
        if move.said or self.report is None:
            return
        move.said = True
        src = move.command.request.source
        x, y, z = (float(v) for v in move.contact[2])
        self.report(Diagnostic(
            codes.COMPLIANT_MOVE_ON_SURFACE, f"{move.command.request.kind}f: the tool meets the surface '{move.contact[1]}' at "
            f"({x:.1f}, {y:.1f}, {z:.1f}) mm and presses on it with {net:g} % of the arm's nominal load; the move "
            "stays there, short of its target, until the force changes or resetMotion()", src.path, src.line,
            src.col, time_us=math.ceil(t * US - 1e-6), task=src.task, program=src.program))

    def waiting_reason(self, q: Any, layers: Any, t: float) -> str | None:
        """Why the motion does not go on, when a compliant move holds it."""
        cur = self.current(q, layers.warp.tau(t))
        if cur is None or layers.warp.rate(t) != 0:
            return None
        move = cur[0]
        line = move.command.request.source.line
        if move.contact is not None:
            return (f"the compliant move of line {line} presses on the surface '{move.contact[1]}': it goes on only "
                    "if a force of the cell pulls it back ([[pushes]]) or resetMotion() cancels it")
        return (f"the compliant move of line {line} has a net force of {move.force + self.push(t):g} % towards its "
                "target: the arm holds, and nothing in the scenario pushes it ([[pushes]], docs/scenario.md)")


def _first(times) -> float | None:
    times = [x for x in times if x is not None]
    return min(times) if times else None


# ---- where a compliant move meets a surface (at its record) ----------------------------------------------


def meets_surface(surfaces: list[Surface], kin: Any, kind: str, q_start: np.ndarray, target: Any,
                  tool: np.ndarray | None) -> tuple[float, str, np.ndarray] | None:
    """(fraction of the move, surface, contact point in mm) where the tool centre point of the move
    from q_start (model units) to `target` (mm: a pose for "movel", joints for "movej") first meets a
    surface coming from its side; None when it does not."""
    if not surfaces:
        return None
    if kind == "movel":
        p0 = kin.tcp(q_start[None], tool)[0, :3, 3]
        p1 = np.asarray(target, dtype=float)[:3, 3]

        def points(f):
            return p0 + np.outer(np.atleast_1d(f), p1 - p0)
    else:
        q1 = np.asarray(target, dtype=float)

        def points(f):
            return kin.tcp(q_start + np.outer(np.atleast_1d(f), q1 - q_start), tool)[:, :3, 3]
    best = None
    grid = np.linspace(0.0, 1.0, 257)
    for surf in surfaces:
        d = (points(grid) - surf.point) @ surf.normal
        if d[0] <= 0:
            continue
        below = np.flatnonzero(d <= 0)
        if not len(below):
            continue
        k = below[0]
        if kind == "movel":  # a straight line: the exact crossing
            f = float(d[0] / (d[0] - ((points(1.0)[0] - surf.point) @ surf.normal)))
        else:
            a, b = grid[k - 1], grid[k]
            for _ in range(60):
                m = 0.5 * (a + b)
                if float((points(m)[0] - surf.point) @ surf.normal) > 0:
                    a = m
                else:
                    b = m
            f = b
        if best is None or f < best[0]:
            best = (f, surf.name, points(f)[0])
    return best


def pose_between(start: np.ndarray, end: np.ndarray, f: float) -> np.ndarray:
    """movel's law (10.1.4.1, interpolateL) at fraction f: the position on the line, the orientation
    turned by f of the smallest rotation from start to end (4x4)."""
    from scipy.spatial.transform import Rotation

    out = np.eye(4)
    out[:3, 3] = start[:3, 3] + f * (end[:3, 3] - start[:3, 3])
    rel = Rotation.from_matrix(start[:3, :3].T @ end[:3, :3]).as_rotvec()
    out[:3, :3] = start[:3, :3] @ Rotation.from_rotvec(f * rel).as_matrix()
    return out
