"""ALTER (11.2): the real-time alteration of an alterable path, on the 4 ms setpoints, as a layer
over the queue's timed nominal trajectory (arm_layers.py): whatever times the nominal path, the
alteration is an offset applied sample by sample on top of it.

11.2.1: "L'altération cartésienne d'une trajectoire permet d'appliquer à la trajectoire une
transformation géométrique (translation, rotation, rotation au centre outil) qui est
immédiatement effective". 11.2.6 alterBegin: "La trajectoire pivote autour du centre du repère ou
de l'outil en utilisant la partie de rotation de la trsf. La trajectoire est ensuite soumise à une
translation par la partie de translation de la trsf. Les coordonnées trsf de la commande alter
sont définies dans le repère alterReference"; a frame "est fixe dans l'espace (World)", a tool "est
fixe par rapport au centre outil". alter: "L'altération est appliquée par le système toutes les
4 ms : Lorsque plusieurs instructions alter sont exécutées en moins de 4 ms, c'est la dernière qui
s'applique".

So at each 4 ms setpoint t_k the flange of the nominal trajectory F becomes R·A·R⁻¹·F (a frame R
in world) or F·T·A·T⁻¹ (a tool T in the flange), A the alteration in force (the last alter()
before t_k, composed with the scenario's), and the joints are those of that pose in the nominal
position's configuration (11.2.5: "le système utilise, en effet, toujours la même configuration"),
nearest it. Between setpoints the offset is linear (the amplifiers interpolate).

Safety (11.2.4, alterBegin's mdesc): the altered path's joint speeds (vel), its tool centre point's
speed (tvel) and rotation speed (rvel) are checked from setpoint to setpoint; beyond them, or out
of reach, "le bras est arrêté brusquement sur la dernière position valide et le mode alter est
verrouillé en position d'erreur. Un resetMotion est requis" (R055; the next motion instruction:
error 150). A stop condition (stopMove, the arm power, an emergency stop, the monitor speed at 0)
leaves the alteration alterStopTime() to stop, then locks it until the condition is gone.
"""

from __future__ import annotations

import bisect
import math
from collections.abc import Callable
from typing import Any

import numpy as np

from ..diagnostics import Diagnostic
from ..light_dataclass import dataclass, field
from ..motion.findings import NO_OP, UNREACHABLE, Finding, MotionError, Source
from ..motion.kin import wrap_near
from ..motion.motion_records import time_leaving
from ..robot.kinematics import trsf_matrix
from ..rules import codes

US = 1_000_000
TICK = 0.004
TICK_US = 4000
SYSTEM_STOP_S = 0.5  # alterStopTime: "le temps imposé par le système (généralement 0.5s lorsqu'un eStop survient)"


def trsf4(values, mm_per_unit: float = 1.0) -> np.ndarray:
    """A VAL 3 trsf (x, y, z in the unit, rx, ry, rz degrees) as a 4x4 in mm."""
    m = np.eye(4)
    m[:3, :4] = np.array(trsf_matrix(tuple(values)), dtype=float)
    m[:3, 3] *= mm_per_unit
    return m


@dataclass
class ScenarioAlteration:
    """The scenario's [[alterations]]: a conveyor (mm/s along the reference's axes, from `at` or
    the start of alter mode, until `until`) or an offset (a trsf reached over `ramp` s from `at`)."""

    velocity: np.ndarray | None = None
    offset: np.ndarray | None = None  # (x, y, z, rx, ry, rz)
    at: float | None = None
    until: float | None = None
    ramp: float = 0.0
    line: int = 0

    def at_time(self, t: float, mode_start: float) -> np.ndarray:
        """The 4x4 this entry contributes at real time t."""
        if self.velocity is not None:
            t0 = mode_start if self.at is None else max(self.at, mode_start)
            t1 = t if self.until is None else min(t, self.until)
            m = np.eye(4)
            m[:3, 3] = self.velocity * max(t1 - t0, 0.0)
            return m
        t0 = self.at or 0.0
        if t < t0:
            return np.eye(4)
        f = 1.0 if self.ramp <= 0 else min((t - t0) / self.ramp, 1.0)
        return trsf4(tuple(v * f for v in self.offset))


@dataclass
class AlterMode:
    """What alterBegin set: the reference (4x4 mm: a frame in world, or a tool in the flange),
    the limits of its mdesc, where it was called."""

    tool: bool
    ref: np.ndarray
    vel: float
    tvel: float
    rvel: float
    decel: float
    source: Source
    start: float | None = None  # when alter mode began (the arm started the alterable move)
    keys: set = field(default_factory=set)  # the commands of its alterable trajectory


class Alteration:
    """The ALTER state of one arm (module docstring). `state`: "off", "pending" (alterBegin waits
    for the alterable move), "active", "ending" (after alterEnd: the alteration frozen until the
    end of the alterable trajectory), "error"."""

    def __init__(self, arm: Any) -> None:
        self.arm = arm
        self.alterable: set[int] = set()  # keys of the alterable commands
        self.next_alterable = False  # the command being recorded is alterable (alterMovej/l/c)
        self.done_keys: set[int] = set()  # commands of alterable trajectories already altered
        self.state = "off"
        self.mode: AlterMode | None = None
        self.program: list[tuple[float, np.ndarray, Source]] = []  # alter() calls: (time, A, where)
        self.program_times: list[float] = []
        self.scenario: list[ScenarioAlteration] = []
        self.ticks: list[int] = []  # sample k at k·4 ms
        self.deltas: list[np.ndarray] = []  # joint offsets at those samples
        self.actual: list[np.ndarray] = []  # joints at those samples
        self.spans: list[int] = []  # index in ticks of each session's first setpoint
        self._cache: tuple = (None, None, None)  # _arrays()
        self.carrier_said = False  # check_carrier
        self.frozen: np.ndarray | None = None  # alterEnd: the alteration kept to the trajectory's end
        self.stop_since: float | None = None  # a stop condition, since when
        self.lock_at: float | None = None
        self.locked: np.ndarray | None = None
        self.deferred: list[tuple[Any, int, Any]] = []  # (move, id, loops) waiting for alterEnd (11.2.3)
        self.deferred_alterable: set[int] = set()  # identifiers of alterable moves among them
        self.close_after_flush = False
        self.report: Callable[[Diagnostic], None] | None = None
        self.begin_time = 0.0
        self.sessions: list[tuple[float, float | None]] = []  # [start, end) of each alteration (from its
        # end on, what is left of the offset is the layers' residual)

    # ---- the layers' interface (arm_layers.Layers.altered) --------------------------------------------------

    def _span_list(self):
        """Each session's setpoints: (first index, end index in ticks, end time or inf)."""
        ends = self.spans[1:] + [len(self.ticks)]
        for n, (i0, i1) in enumerate(zip(self.spans, ends)):
            if i1 > i0:
                end = self.sessions[n][1]
                yield i0, i1, math.inf if end is None else end

    def offset_many(self, times) -> np.ndarray:
        """The joint offsets at real times: linear between the setpoints of a session, nothing
        before its first setpoint or from its end on."""
        times = np.asarray(times, dtype=float)
        out = np.zeros((len(times), self.arm.axes))
        for i0, i1, end in self._span_list():
            k, D = self._arrays(i0, i1)
            sel = (times >= k[0]) & (times < end - 1e-12)
            if sel.any():
                if sel.sum() == 1:  # one time (the arm's position now): the two setpoints around it
                    (i,) = np.nonzero(sel)[0]
                    j = min(max(int(np.searchsorted(k, times[i], side="right")) - 1, 0), len(k) - 1)
                    if j + 1 < len(k):
                        f = (times[i] - k[j]) / (k[j + 1] - k[j])
                        out[i] = D[j] + f * (D[j + 1] - D[j])
                    else:
                        out[i] = D[j]
                    continue
                for j in range(out.shape[1]):
                    out[sel, j] = np.interp(times[sel], k, D[:, j])
        return out

    def _arrays(self, i0: int, i1: int) -> tuple[np.ndarray, np.ndarray]:
        """The setpoint times and joint offsets of ticks[i0:i1], as arrays (kept until more come)."""
        key = (i0, i1)
        if self._cache[0] != key:
            self._cache = (key, np.asarray(self.ticks[i0:i1]) * TICK, np.asarray(self.deltas[i0:i1]))
        return self._cache[1], self._cache[2]

    def rate(self, t: float) -> np.ndarray:
        for i0, i1, end in self._span_list():
            k, _ = self._arrays(i0, i1)
            i = int(np.searchsorted(k, t, side="right")) - 1
            if 0 <= i < i1 - i0 - 1 and t < end:
                a = i0 + i
                return (self.deltas[a + 1] - self.deltas[a]) / (TICK * (self.ticks[a + 1] - self.ticks[a]))
        return np.zeros(self.arm.axes)

    def _sampled(self) -> bool:
        """The current session has setpoints."""
        return bool(self.spans) and len(self.ticks) > self.spans[-1]

    def moving(self) -> list[tuple[float, float]]:
        return [(a, b if b is not None else math.inf) for a, b in self.sessions]

    # ---- the alteration at a setpoint ----------------------------------------------------------------

    def value(self, t: float) -> np.ndarray:
        """The alteration in force at setpoint time t (4x4 mm, in the reference)."""
        if self.frozen is not None:
            return self.frozen
        if self.locked is not None:
            return self.locked
        A = np.eye(4)
        for entry in self.scenario:
            A = A @ entry.at_time(t, self.mode.start)
        n = bisect.bisect_left(self.program_times, t - 1e-9)  # the calls before the setpoint
        return A @ self.program[n - 1][1] if n else A

    def altered_flange(self, F: np.ndarray, A: np.ndarray) -> np.ndarray:
        """The flange of the nominal trajectory under the alteration (module docstring)."""
        R = self.mode.ref
        if self.mode.tool:
            return F @ R @ A @ np.linalg.inv(R)
        return R @ A @ np.linalg.inv(R) @ F

    # ---- the program's instructions ---------------------------------------------------------------------

    def begin(self, mode: AlterMode, q: Any, now: float) -> int:
        """alterBegin: 1 started, 0 waits for the alterable move, -1 already started, -3 in error."""
        if self.state == "error":
            return -3
        if self.state in ("active", "pending", "ending"):
            return -1
        self.mode = mode
        self.state = "pending"
        self.program = []
        self.program_times = []
        self.begin_time = now
        self._activate(q, now)
        return 1 if self.state == "active" else 0

    def alter(self, A: np.ndarray, now: float, source: Source) -> int:
        """alter(trsf): 1, 0 (locked by a stop condition), -1 (not started or over), -3 (error)."""
        if self.state == "error":
            return -3
        if self.state != "active":
            return -1
        if self.lock_at is not None and now >= self.lock_at - 1e-9:
            return 0
        self.program.append((now, A, source))
        self.program_times.append(now)
        return 1

    def end(self, q: Any, now: float, queue_now: float) -> int:
        """alterEnd: 1, -1 (not started), -3 (error). The alteration in force stays to the end of
        the alterable trajectory; the moves waiting for alterEnd are recorded (at queue time
        `queue_now`)."""
        if self.state == "error":
            return -3
        if self.state != "active":
            return -1
        self.frozen = self.value(self._next_tick(now))
        self.state = "ending"
        self.flush(q, queue_now)
        return 1

    def stop_time(self, now: float) -> float:
        """alterStopTime: 0 when alter mode is not active, -1 without a stop condition, else the
        time left before the alteration is locked (0 once it is)."""
        if self.state not in ("active", "ending"):
            return 0.0
        if self.stop_since is None:
            return -1.0
        return max(self.lock_at - now, 0.0)

    # ---- non-alterable moves after an alterable trajectory (11.2.3) --------------------------------------------

    def defers(self, q: Any, alterable: bool) -> bool:
        """Whether a move recorded now waits for alterEnd: a move after the alterable trajectory of
        a pending or active alter mode that is not alterable, and everything after it."""
        if self.deferred:
            return True
        if alterable or self.state not in ("pending", "active") or not q.history:
            return False
        return q.history[-1].key in self.alterable

    def flush(self, q: Any, now: float) -> None:
        """Record the moves that waited for alterEnd, with the identifiers they returned."""
        waiting, self.deferred = self.deferred, []
        keep = q.next_id
        for move, ident, context in waiting:
            q.set_move_id(ident)
            n = len(q.findings)
            try:
                q.record(move, now)
            except MotionError as exc:  # computed only now (11.2.3): the motion is in error, as a move
                # the arm cannot execute (the next motion instruction: 150 until resetMotion)
                f = exc.finding or Finding(UNREACHABLE, f"{move.kind}: {exc.message}", move.source, now, error=exc.code)
                q.findings.append(f)
                q.failure = f
                break
            if ident in self.deferred_alterable:
                self.alterable.add(q.history[-1].key)
            self.arm.recorded(q.history[-1], context)
            self.check_carrier(q, q.history[-1], q.findings[n:])
        self.deferred_alterable = set()
        if waiting:
            q.set_move_id(max(keep, q.next_id))
            if self.close_after_flush:
                q.wait_end_move(now)
        self.close_after_flush = False

    def check_carrier(self, q: Any, command: Any, notes: list) -> None:
        """A null move (R016 among its `notes`) recorded where the offset the alteration leaves
        would decrease along it (docs/motion.md, "ALTER"): on the controller it is computed from the
        altered position and moves the arm; here the offset would vanish at once. Said (R052),
        not hidden: the positions after it keep the offset."""
        if self.report is None or self.carrier_said or not any(f.code == NO_OP for f in notes):
            return
        index = len(q.history) - 1
        if self.state == "ending" and self._sampled():
            delta = self.deltas[-1]
        else:
            items = self.arm.layers.residuals.items
            if not items or items[-1][2] != index:
                return
            delta = items[-1][1]
        if float(np.max(np.abs(delta))) <= 1e-6:
            return
        src = command.request.source
        self.carrier_said = True
        self.report(Diagnostic(
            codes.OPTION_EFFECT_NOT_SIMULATED, f"{command.kind}: its target is the nominal end of the alterable trajectory, where the arm is not: on "
            f"the controller it is computed from the altered position (11.2.3) and moves the arm back by the alteration "
            f"(up to {float(np.max(np.abs(delta))):.3g}° or mm on an axis); the simulation plans the nominal path, which "
            "does not move here: the offset vanishes in one step, a jump the controller does not make (said once)", src.path, src.line, src.col,
            time_us=round(command.request.recorded * US), task=src.task, program=src.program))

    # ---- time passes ---------------------------------------------------------------------------------------

    def needs_ticks(self, q: Any, now: float) -> bool:
        """Whether the scheduler must stop at the next 4 ms setpoint: the alteration or the nominal
        path changes there (not while both stand still: a task waiting then is a deadlock)."""
        if self.state in ("active", "ending"):
            return not self._idle(q, now)
        return self.state == "pending" and self._first_alterable(q) is not None

    def _idle(self, q: Any, t: float) -> bool:
        """From setpoint time t on nothing moves the arm unless a task or the cell acts: the nominal
        at rest, the scenario's alterations constant, no alter() waiting for its setpoint, no lock
        coming."""
        if not self._sampled() or self.ticks[-1] * TICK < t - TICK - 1e-9:
            return False
        if self.program and self.program[-1][0] >= self.ticks[-1] * TICK - 1e-9:
            return False
        if self.stop_since is not None and self.locked is None:
            return False
        tau = self.arm.layers.warp.tau(t)
        if q.profile.t_end > tau + 1e-9 and self.arm.layers.warp.rate(t) != 0:
            return False
        for entry in self.scenario:
            if entry.velocity is not None and (entry.until is None or entry.until > t) and self.locked is None:
                return False
            if entry.offset is not None and (entry.at or 0.0) + entry.ramp > t - 1e-9 and self.locked is None:
                return False
        return True

    def advance(self, q: Any, to: float) -> None:
        """Compute the setpoints up to real time `to` (s); where nothing moves, one setpoint stands
        for the ticks skipped (the offset is constant there)."""
        k_to = math.floor(to / TICK + 1e-9)
        if self.state == "pending":
            self._activate(q, to)
        while self.state in ("active", "ending"):
            k = self.ticks[-1] + 1 if self._sampled() else math.ceil(self.mode.start / TICK - 1e-9)
            if k > k_to:
                break
            if k < k_to and self.state == "active" and self._idle(q, k * TICK):
                k = k_to
            self._sample(q, k)

    def _next_tick(self, t: float) -> float:
        return (math.floor(t / TICK + 1e-9) + 1) * TICK

    def _first_alterable(self, q: Any):
        """The first alterable command not altered yet, not failed or cancelled, and not null."""
        for command in q.history:
            if command.key in self.alterable and command.key not in self.done_keys \
                    and command.state not in ("failed", "cancelled") and command.placement.s_begin is not None:
                place = command.placement
                end = place.s_end if place.s_end is not None else place.s_provisional
                if end is not None and end - place.s_begin > 1e-12:  # 11.2.5: null moves do not count
                    return command
        return None

    def _activate(self, q: Any, t: float) -> None:
        """Alter mode begins when the arm starts the alterable move."""
        first = self._first_alterable(q)
        if first is None:
            return
        _ = q.trajectory  # the plan up to date
        ts = time_leaving(q.profile, first.placement.s_begin)
        layers = self.arm.layers
        tau = layers.warp.tau(t)
        if ts is None or tau < ts - 1e-9:
            return
        start = layers.warp.real_time(ts)
        start = t if start is None else min(max(start, self.begin_time), t)
        self.mode.start = start
        self.mode.keys = set(self._run_keys(q, first))
        self.state = "active"
        self.frozen = None
        self.sessions.append((start, None))
        self.spans.append(len(self.ticks))

    def _run_keys(self, q: Any, first: Any) -> list[int]:
        """The alterable trajectory from `first`: the alterable commands up to the next one that is not."""
        keys, on = [], False
        for command in q.history:
            if command is first:
                on = True
            if on:
                if command.key not in self.alterable:
                    break
                keys.append(command.key)
        return keys

    def _trajectory_end(self, q: Any) -> float | None:
        """Queue time at which the arm reaches the end of the alterable trajectory (None: not yet planned)."""
        self.mode.keys |= set(self._run_keys(q, next(c for c in q.history if c.key in self.mode.keys)))
        last = [c for c in q.history if c.key in self.mode.keys][-1]
        if last.placement.s_end is None:
            return None
        return q.profile.time_at(last.placement.s_end)

    def _sample(self, q: Any, k: int) -> None:
        """The setpoint k·4 ms: the altered joints, the safety checks, the stop conditions."""
        arm = self.arm
        layers = arm.layers
        t = k * TICK
        tau = layers.warp.tau(t)
        ending = False
        if self.state == "ending":
            end = self._trajectory_end(q)
            ending = end is not None and tau >= end - 1e-9
        self._stop_condition(q, t)
        kin = q.kin
        qn = q.trajectory.position(tau)
        F = kin.fk(qn[None])[0]
        A = self.value(t)
        target = self.altered_flange(F, A)
        near = self.actual[-1] if self._sampled() else qn
        qa = solve_near(kin, target, qn, near)
        why = None if qa is not None else "the altered position is out of reach (or outside the joint limits) in the " \
                                           "arm's configuration"
        if why is None:
            if self._sampled() and self.ticks[-1] == k - 1:
                before = self.actual[-1]
            else:  # after setpoints skipped (the offset constant), or the first of the session (nominal)
                before = q.trajectory.position(layers.warp.tau(t - TICK)) + (self.deltas[-1] if self._sampled() else 0.0)
            why = self._too_fast(q, kin, before, qa)
        if why is not None:
            self._fail(q, k, why)
            return
        self.ticks.append(k)
        self.actual.append(qa)
        self.deltas.append(qa - qn)
        if ending:
            self._let_go(q, t)

    def _too_fast(self, q: Any, kin: Any, q0: np.ndarray, q1: np.ndarray) -> str | None:
        """Why the step between two setpoints is beyond alterBegin's mdesc (vel, tvel, rvel), or None."""
        mode = self.mode
        speeds = np.abs(q1 - q0) / TICK
        allowed = kin.speeds * mode.vel / 100.0
        over = speeds > allowed * (1 + 1e-9) + 1e-9
        if np.any(over):
            j = int(np.argmax(speeds / allowed))
            return (f"j{j + 1} would turn at {speeds[j]:.1f}°/s, beyond the alterBegin mdesc's vel {mode.vel:g} % "
                    f"({allowed[j]:.1f}°/s)")
        tool = q.pending[0].request.tool if q.pending else None
        T = kin.tcp(np.vstack([q0, q1]), tool)
        v = float(np.linalg.norm(T[1, :3, 3] - T[0, :3, 3])) / TICK
        if v > mode.tvel * (1 + 1e-9) + 1e-9:
            return f"the tool centre point would move at {v:.1f} mm/s, beyond the alterBegin mdesc's tvel {mode.tvel:g} mm/s"
        rel = T[0, :3, :3].T @ T[1, :3, :3]
        w = math.degrees(math.acos(max(-1.0, min(1.0, (np.trace(rel) - 1) / 2)))) / TICK
        if w > mode.rvel * (1 + 1e-9) + 1e-9:
            return f"the tool would turn at {w:.1f}°/s, beyond the alterBegin mdesc's rvel {mode.rvel:g}°/s"
        return None

    def _fail(self, q: Any, k: int, why: str) -> None:
        """11.2.4: the arm stops at once on the last valid position; alter mode locked in error."""
        layers = self.arm.layers
        t_last = self.ticks[-1] * TICK if self._sampled() else k * TICK
        layers.warp.set_rate(t_last, 0)
        self.state = "error"
        src = self.program[-1][2] if self.program else self.mode.source
        message = f"alter: {why} at {k * TICK:.3f} s: the arm stops at once on its last valid position, alter mode is " \
                  "in error until resetMotion() (11.2.4)"
        q.failure = Finding(codes.ALTERATION_INVALID, message, src, k * TICK, error=150)
        if self.report is not None:
            self.report(Diagnostic(codes.ALTERATION_INVALID, message, src.path, src.line, src.col, time_us=k * TICK_US, task=src.task,
                                   program=src.program))

    def _stop_condition(self, q: Any, t: float) -> None:
        """Stopped motion (stopMove, power, emergency stop, monitor speed 0): alterStopTime() to stop
        the alteration, then it is locked until the condition is gone (11.2.4)."""
        ctl = self.arm.controller
        estop = ctl is not None and getattr(ctl, "es_status", 0) != 0
        cond = q.held or not q.powered or q.monitor <= 0.0 or estop
        if not cond:
            self.stop_since = self.lock_at = None
            self.locked = None
            return
        if self.stop_since is None:
            self.stop_since = t
            T = self._stop_duration(q)
            if not q.powered or estop:
                T = min(T, SYSTEM_STOP_S)
            self.lock_at = t + T
        if t >= self.lock_at - 1e-9 and self.locked is None:
            self.locked = self.value(t)

    def _stop_duration(self, q: Any) -> float:
        """The time to stop the alteration's joint speeds with alterBegin's deceleration."""
        if len(self.ticks) - self.spans[-1] < 2:
            return 0.0
        speed = np.abs(self.deltas[-1] - self.deltas[-2]) / (TICK * (self.ticks[-1] - self.ticks[-2]))
        decel = q.kin.accels * self.mode.decel / 100.0
        return float(np.max(speed / decel))

    def _let_go(self, q: Any, t: float) -> None:
        """The end of the alterable trajectory after alterEnd: what is left of the offset decays
        along the next move (the layers' residual)."""
        layers = self.arm.layers
        delta = self.deltas[-1] if self._sampled() else np.zeros(self.arm.axes)
        last = max(i for i, c in enumerate(q.history) if c.key in self.mode.keys)
        layers.residuals.add(t, delta, last + 1)
        self._close(t)

    def _close(self, t: float) -> None:
        self.done_keys |= self.mode.keys
        self.state = "off"
        self.frozen = self.locked = None
        self.stop_since = self.lock_at = None
        if self.sessions and self.sessions[-1][1] is None:
            self.sessions[-1] = (self.sessions[-1][0], t)

    def after_reset(self, t: float) -> None:
        """resetMotion ends alter mode (11.2.6) and clears an error; moves waiting are cancelled."""
        self.deferred = []
        self.deferred_alterable = set()
        self.close_after_flush = False
        if self.state == "off":
            return
        if self.state != "pending":
            self._close(t)
        self.state = "off"


def solve_near(kin: Any, T: np.ndarray, q_config: np.ndarray, near: np.ndarray) -> np.ndarray | None:
    """The joints (model units) reaching the flange pose T in the configuration of q_config, nearest
    `near`, within the joint limits; None when there is none."""
    if kin.opw is None:
        model = kin.model
        sols = model.ik(T[:3, :4].tolist(), config=model.config_of(tuple(q_config)), near=tuple(near))
        return np.array(sols[0], dtype=float) if sols else None
    branches = kin.ik_all(T[None])[0]
    code = int(kin.config_codes(q_config[None])[0])
    best = None
    for sol in branches:
        if np.isnan(sol[[0, 1, 2, 4, 5]]).any():
            continue
        sol = sol.copy()
        if np.isnan(sol[3]):
            sol[3] = near[3]
        sol[kin.revolute] = wrap_near(sol[kin.revolute], near[kin.revolute])
        if int(kin.config_codes(sol[None])[0]) != code:
            continue
        if np.any(sol < kin.lo - 1e-7) or np.any(sol > kin.hi + 1e-7):
            continue
        d = float(np.sum((sol - near) ** 2))
        if best is None or d < best[0]:
            best = (d, sol)
    return None if best is None else best[1]
