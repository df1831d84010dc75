"""The motion queue of one arm: chapter 10 as a state machine in simulated time.

A motion instruction records a command and returns its identifier at once (10.2.1); the arm
executes the queue behind the program. Everything here is a pure function of the calls and
their times (seconds), so a fake clock tests it:

    q = MotionQueue(model)                   # the arm at rest, powered, monitor speed 100 %
    i = q.record(MoveCommand(...), now)      # an id (int), or QueueFull(until=...) when full
    q.wait_end_move(now)                     # cancels the last blend; the time the arm gets there
    q.get_move_id(now); q.position(now); q.is_settled(now) ...
    q.next_event(now) / q.advance(now)       # for the scheduler (Subsystem protocol)

Semantics (docs/motion.md gives the choices where the manual is silent):

* The path is built as commands arrive. A blended command (blend joint/Cartesian) ends, for now,
  at its leave point: the arm never passes it before the next command is recorded (10.2.2); when
  it comes, the blend to it is built and the not-yet-executed tail is re-timed from the arm's
  exact state (from the start of the final braking, which is the only part the new end changes).
  waitEndMove cancels the last blend: the arm goes on to the target and stops (10.1.2.2).
* A chain of blended commands is timed as one path; the arm stops only where the path does not
  continue with the same velocity (blend off, no next command yet, a cusp).
* Errors at the instruction raise `MotionError` (mdesc 100-106, unreachable target 154...). A
  command whose path cannot be executed (a singularity, a joint limit or the edge of the
  workspace along the way) is accepted, the arm stops before it, and the next motion
  instruction, waitEndMove, open or close raises 150 (12.1) until resetMotion.
* getMoveId: integer part the command being executed, fraction its progress along its own
  part of the path (a blend belongs to the first command up to that command's target, then to
  the next); at rest after command n: n + 1 (10.6 examples).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from . import findings as F
from .cartesian import ArcError, Arc, Blend, Line
from .checks import THRESHOLDS, WHAT, singular_pass
from .commands import MoveCommand
from .findings import Finding, MotionError, Source
from .kin import ArmKin
from .mdesc import Limits, MDesc
from .paths import BLEND_SHAPES, JointBlend, JointLine, JointSpline, Path, Span, tcp_rates
from .timing import Grid, TimedProfile, brake_stop, duration, topp, trapezoid
from .tracking import track
from .trajectory import Profile, Trajectory

CAPACITY = 16  # commands recorded and not yet completed (10.2.1: the memory is limited)
SETTLE_S = 0.05  # isSettled: at rest for 50 ms (perfect tracking: the commanded position)
MIN_BLEND_MM = 0.01  # a leave or reach shorter than this: no blend, the arm stops at the point
CUSP_COS = math.cos(math.radians(170.0))  # a blend that turns back more than this: the arm stops
JOINT_EQ = 1e-6  # degrees: joint positions this close are the same position (9.2.2)
# Commands recorded less than this apart while the arm starts from rest are timed together: in
# that time the arm moves less than a micrometre, the same whichever way it is computed.
MERGE_WINDOW = 0.001
EXACT_REST = False
TOPP_CACHE = 512  # time parameterisations remembered (`_topp`)
MIN_GRID = 9  # gridpoints of the shortest piece of path given to toppra


@dataclass
class QueueFull:
    """The queue is full: the motion instruction waits until `until` (None: no place will free
    while the arm cannot move: power off or stopMove)."""

    until: float | None


@dataclass(eq=False)
class Cmd:
    """A command in the queue (`state`: pending, done, failed, cancelled)."""

    key: int
    id: int | None
    kind: str
    source: Source
    recorded: float
    q_start: np.ndarray
    q_end: np.ndarray
    mdesc: MDesc
    tool: np.ndarray | None = None
    geom: object = None  # JointLine | JointSpline | None (no motion)
    curve: object = None  # the TCP curve of movel/movec
    lam_in: float = 0.0
    lam_leave: float = 1.0
    blend: str = "off"
    S_begin: float | None = None
    S_end: float | None = None
    S_prov: float | None = None
    S_nom: tuple[float, float, float] | None = None  # (s at lam_in, s at the end of its own span, λ there)
    state: str = "pending"
    t_done: float | None = None
    spans: list = field(default_factory=list)  # Span objects it (partly) owns
    reduced: bool = False  # connection move at reduced speed
    tool_name: str = ""
    target_name: str = ""
    frame_name: str = ""  # the reference frame of a point target
    checked: bool = False
    rest_time: float | None = None  # alone, from rest to rest (`_rest_time`)


class MotionQueue:
    def __init__(self, model, joints=None, *, powered: bool = True, monitor: float = 100.0,
                 capacity: int = CAPACITY):
        self.model = model
        self.kin = ArmKin(model)
        q0 = np.zeros(len(model.joint_limits)) if joints is None else np.asarray(joints, dtype=float)
        self.path = Path(q0)
        self.profile = Profile(0.0, 0.0)
        self._trajectory = Trajectory(self.path, self.profile)
        self._pending: tuple[float, float, bool] | None = None  # a replan not done yet (see _replan)
        self.capacity = capacity
        self.powered = powered
        self.held = False  # stopMove
        self.monitor = float(monitor)
        self.next_id = 0
        self.pos_id = 0
        self.pending: list[Cmd] = []
        self.history: list[Cmd] = []
        self.open: Cmd | None = None  # the last command, blended, waiting for the next one
        self.failure: Finding | None = None  # a recorded command that cannot be executed
        self.connect_to: np.ndarray | None = None  # resetMotion(jStart)
        self.auto_connect = False
        self.findings: list[Finding] = []
        self._limits: dict[int, Limits] = {}
        self._keys = 0
        self._by_key: dict[int, Cmd] = {}
        self.fallbacks = 0
        self.stops_chosen = 0  # junctions where stopping at the via point was chosen (`_blend_pays`)
        self._trial = None  # the timing of the last blend trial, reused by the plan that follows
        self._fell = False  # the last time parameterisation fell back to the safe profile
        self._topp_cache: dict = {}  # `_topp`
        self._samples: dict = {}  # samples of spans timed in trials, reused when the span is added

    # ---- recording ---------------------------------------------------------------------------

    def record(self, command: MoveCommand, now: float) -> int | QueueFull:
        """movej/movel/movec (10.6): the command's identifier, or QueueFull."""
        self._advance(now, lenient=True)
        if self.failure is not None:
            raise MotionError(150, self._failure_text())
        src = command.source
        bad = command.mdesc.check()
        if bad is not None:
            code, msg = bad
            f = Finding(F.MDESC, f"{command.kind}: {msg}", src, now, error=code,
                        data={"field": msg.split(" ")[0].replace("mdesc.", ""), "code": code})
            raise MotionError(code, msg, f)
        if len(self.pending) >= self.capacity:
            return QueueFull(self._first_done_time())
        q_s = self._start_joints()
        if self.connect_to is not None:
            target = self.connect_to
            self.connect_to = None
            if np.max(np.abs(target - q_s)) > JOINT_EQ:
                self._add_connection(q_s, target, now, src)
                q_s = target
        cmd = self._build(command, q_s, now)
        cmd.id = self.next_id
        self.next_id += 1
        if cmd.state == "failed":
            self.history.append(cmd)
            if self.open is not None:
                self._close_open()
                self._replan(now, from_final_decel=True)
            return cmd.id
        self._integrate(cmd, now)
        return cmd.id

    def _start_joints(self) -> np.ndarray:
        if self.pending:
            return self.pending[-1].q_end.copy()
        return self.path.q_rest.copy()

    def _new_cmd(self, kind, source, now, q_s, mdesc, tool) -> Cmd:
        self._keys += 1
        c = Cmd(self._keys, None, kind, source, now, q_s, q_s.copy(), mdesc, tool)
        self._by_key[c.key] = c
        return c

    def _add_connection(self, q_s, target, now, src) -> None:
        """resetMotion(jStart): a point-to-point move to jStart at reduced speed first (10.1.3)."""
        c = self._new_cmd("connection", src, now, q_s, MDesc(blend="off"), None)
        c.reduced = True
        c.q_end = np.asarray(target, dtype=float)
        c.geom = JointLine(q_s, c.q_end)
        self._integrate(c, now)

    # ---- geometry of a command ---------------------------------------------------------------

    def _build(self, command: MoveCommand, q_s: np.ndarray, now: float) -> Cmd:
        md = command.mdesc
        tool = None if command.tool is None else np.asarray(command.tool, dtype=float)
        c = self._new_cmd(command.kind, command.source, now, q_s, md, tool)
        c.tool_name = command.tool_name
        c.target_name = command.target.name
        c.frame_name = command.target.frame
        c.blend = md.blend
        if command.kind == "movej":
            q_end = self._movej_target(c, command, q_s, tool, now)
            if q_end is None:
                return c
            c.q_end = q_end
            if np.max(np.abs(c.q_end - q_s)) <= JOINT_EQ:
                self.findings.append(Finding(
                    F.NO_OP, "movej: the target is the position the motion starts from: the arm does not move",
                    command.source, now, data={"joints": _r(q_s)}))
                c.q_end = q_s.copy()
                c.blend = "off"
            else:
                c.geom = JointLine(q_s, c.q_end)
            return c
        self._cartesian(c, command, q_s, tool, now)
        return c

    def _defer(self, c: Cmd, f: Finding) -> None:
        """A command the arm cannot execute (its target out of reach, outside the joint limits,
        in another configuration, or its path): it is recorded and returns its identifier, the
        arm stops before it, and the next motion instruction, waitEndMove, open or close raises
        150 (12.1: "un mouvement demandé précédemment n'a pas pu être terminé (point hors
        d'atteinte, singularité, problème de configuration...)"; waitEndMove, 10.6: "destination
        hors d'atteinte")."""
        if f.error != 150:
            f = Finding(f.code, f.message, f.source, f.time, f.move_id, 150, f.data)
        c.state = "failed"
        self.findings.append(f)
        self.failure = f

    def _movej_target(self, c: Cmd, command: MoveCommand, q_s, tool, now) -> np.ndarray | None:
        """The joint target of a movej; None when the arm cannot go there (`_defer`)."""
        tg = command.target
        src = command.source
        kin = self.kin
        if tg.is_joint:
            j = np.asarray(tg.joints, dtype=float)
            if len(j) != len(q_s):
                raise MotionError(81, f"movej: a joint value with {len(j)} axes for the {len(q_s)}-axis arm")
            over = np.maximum(kin.lo - j, j - kin.hi)
            if np.any(over > 1e-7):
                ax = int(np.argmax(over))
                self._defer(c, self._limit_finding("movej: the joint target", ax, float(over[ax]), j[ax], src, now))
                return None
            return j
        T = tg.pose if tool is None else tg.pose @ np.linalg.inv(tool)
        from ..robot.errors import Unreachable

        try:
            j = self.model.solve(T[:3, :4].tolist(), tg.config, initial=tuple(q_s))
        except Unreachable as exc:
            self._defer(c, self._unreachable_finding("movej", tg, T, q_s, exc.reason, src, now))
            return None
        return np.asarray(j, dtype=float)

    def _cartesian(self, c: Cmd, command: MoveCommand, q_s, tool, now) -> None:
        kin = self.kin
        src = command.source
        kind = command.kind
        T_end = command.target.pose
        T0 = kin.tcp(q_s[None], tool)[0]
        try:  # an arc that three positions do not define is an invalid instruction (154)
            curve = Line(T0, T_end) if kind == "movel" else Arc(T0, command.via.pose, T_end)
        except ArcError as exc:
            f = Finding(F.CIRCLE, str(exc), src, now, error=154, data=dict(exc.data, what=exc.what))
            raise MotionError(154, f.message, f) from None
        code0 = int(kin.config_codes(q_s)[0])
        cfg0 = kin.config_name(code0)
        fields = ("shoulder", "elbow", "wrist")[:len(cfg0)]
        # 10.1.4.2: a line or a circle cannot change configuration
        for field_name, want, have in zip(fields, command.target.config, cfg0):
            w = want.lower()
            if w.endswith("same") or w.endswith("free"):
                continue
            if w != have:
                self._defer(c, Finding(
                    F.CONFIG_CHANGE, f"{kind}: the target imposes {field_name} {w} but the motion starts in {have}: "
                    f"a straight line or a circle cannot change configuration (10.1.4.2); use movej, or "
                    f"{field_name[0]}same/{field_name[0]}free", src, now,
                    data={"field": field_name, "requested": w, "start": have}))
                return
        flange_end = T_end if tool is None else T_end @ np.linalg.inv(tool)
        sols, sol_codes = kin.solutions(flange_end)
        codes = {int(x) for x in sol_codes}
        if code0 not in codes:
            if codes:
                other = kin.config_name(min(codes))
                f = Finding(F.CONFIG_CHANGE,
                            f"{kind}: the target can only be reached in configuration {'/'.join(other)}, not in the "
                            f"start configuration {'/'.join(cfg0)}: a straight line or a circle cannot change "
                            "configuration (10.1.4.2); use movej", src, now,
                            data={"start": list(cfg0), "target": list(other)})
            else:
                f = Finding(F.UNREACHABLE, f"{kind}: the target{_name(command.target)} is out of the arm's reach",
                            src, now, data={"target_mm": _r(T_end[:3, 3])})
            self._defer(c, f)
            return
        # the target in the start configuration: within the joint limits?
        mine = self._turns(sols[sol_codes == code0], q_s)
        over = np.maximum(kin.lo - mine, mine - kin.hi).max(axis=1)
        if np.all(over > 1e-7):
            best = mine[int(np.argmin(over))]
            ex = np.maximum(kin.lo - best, best - kin.hi)
            ax = int(np.argmax(ex))
            self._defer(c, self._limit_finding(f"{kind}: the target{_name(command.target)} in the start configuration "
                                               f"{'/'.join(cfg0)}", ax, float(ex[ax]), float(best[ax]), src, now))
            return
        c.curve = curve
        if curve.length_mm < 1e-6 and curve.angle_deg < 1e-6:
            c.blend = "off"
            return
        tr = track(kin, curve, tool, q_s, code0)
        if tr.failure is not None:
            self._defer(c, self._path_failure(kind, tr.failure, curve, src, now))
            return
        c.geom = JointSpline(tr.lam, tr.Q, tr.D)
        c.geom.sing = tr.sing
        c.geom.curve = curve
        c.q_end = tr.Q[-1].copy()

    # ---- findings ------------------------------------------------------------------------------

    def _limit_finding(self, what, ax, amount, value, src, now, error=150) -> Finding:
        lo, hi = self.model.joint_limits[ax]
        side = "below" if value < lo else "above"
        u = "°" if self.kin.revolute[ax] else " mm"
        return Finding(F.JOINT_LIMIT, f"{what} is outside the software limits: j{ax + 1} = {value:.3f}{u} is "
                       f"{amount:.3f}{u} {side} its limit [{lo:g}, {hi:g}]", src, now, error=error,
                       data={"axis": ax + 1, "value_deg": round(value, 6), "excess_deg": round(amount, 6),
                             "limits_deg": [lo, hi]})

    def _unreachable_finding(self, kind, tg, T, q_s, reason, src, now) -> Finding:
        if reason in ("limits", "config"):
            # the solutions in the requested configuration, ignoring the limits: if there are some,
            # the joint limits are what stops the motion (which axis, by how much)
            sols, codes = self.kin.solutions(T)
            if len(sols):
                sols = self._turns(sols, q_s)
                start = tuple(self.model.config_of(q_s))
                wanted = [s0 if w.endswith("same") else (None if w.endswith("free") else w)
                          for w, s0 in zip((c.lower() for c in tg.config), start)]
                keep = [all(w is None or w == v for w, v in zip(wanted, self.kin.config_name(int(cd)))) for cd in codes]
                sols = sols[np.array(keep, dtype=bool)]
            if len(sols):
                sols[np.isnan(sols[:, 3]), 3] = q_s[3]
                over = np.maximum(self.kin.lo - sols, sols - self.kin.hi)
                worst = over.max(axis=1)
                i = int(np.argmin(worst))
                ax = int(np.argmax(over[i]))
                return self._limit_finding(f"{kind}: every joint position reaching the point{_name(tg)}", ax,
                                           float(over[i, ax]), float(sols[i, ax]), src, now)
        if reason == "config":
            msg = (f"{kind}: the point{_name(tg)} is reachable, but not in the requested configuration "
                   f"{'/'.join(tg.config)} (same fields relative to the start {'/'.join(self.model.config_of(q_s))})")
        else:
            msg = f"{kind}: the point{_name(tg)} is out of the arm's reach"
        return Finding(F.UNREACHABLE, msg, src, now, error=150,
                       data={"target_mm": _r(T[:3, 3]), "reason": reason, "config": list(tg.config)})

    def _turns(self, sols: np.ndarray, q_s: np.ndarray) -> np.ndarray:
        """Each axis on the turn within its limits nearest the start (9.6.3: an axis of more than
        one turn takes the turn nearest jInitial); when no turn fits, the turn least outside them
        (so that a violation is measured from there)."""
        kin = self.kin
        out = sols.copy()
        shifts = 360.0 * np.arange(-2, 3)
        for r in range(len(out)):
            for k in range(out.shape[1]):
                if not kin.revolute[k]:  # a prismatic axis (SCARA axis 3) has no turns
                    continue
                cand = sols[r, k] + shifts
                excess = np.maximum(kin.lo[k] - cand, cand - kin.hi[k])
                inside = excess <= 1e-7
                if inside.any():
                    c = cand[inside]
                    out[r, k] = c[np.argmin(np.abs(c - q_s[k]))]
                else:
                    out[r, k] = cand[np.argmin(excess)]
        return out

    def _path_failure(self, kind, fl, curve, src, now) -> Finding:
        at = fl.lam * curve.length_mm
        where = f"{at:.1f} mm along the path" if curve.length_mm > 1e-6 else f"{fl.lam * 100:.0f} % along the path"
        data = {"along_mm": round(at, 3), "fraction": round(fl.lam, 6)}
        if fl.joints is not None:
            data["joints"] = _r(fl.joints)
        if fl.kind == "limits":
            f = self._limit_finding(f"{kind}: the path ({where})", fl.axis, fl.amount,
                                    fl.joints[fl.axis], src, now, error=150)
            return Finding(f.code, f.message, src, now, error=150, data={**f.data, **data})
        if fl.kind == "singular":
            return Finding(F.SINGULAR_STOP,
                           f"{kind}: the path goes through the {WHAT[fl.which]} {where}: axis {fl.axis + 1} would "
                           f"have to turn {fl.amount:.1f}° at once; the path cannot be followed (10.1.4.3)",
                           src, now, error=150, data={**data, "singularity": fl.which, "axis": fl.axis + 1,
                                                      "jump_deg": round(fl.amount, 3)})
        if fl.kind == "config":
            other = "/".join(self.kin.config_name(fl.other_config))
            return Finding(F.CONFIG_CHANGE,
                           f"{kind}: the path leaves the start configuration {where} (only {other} reaches it): a "
                           "straight line or a circle cannot change configuration (10.1.4.2)", src, now, error=150,
                           data={**data, "other": other})
        return Finding(F.UNREACHABLE, f"{kind}: the path goes out of the arm's reach {where}", src, now, error=150,
                       data=data)

    def _failure_text(self) -> str:
        f = self.failure
        return f"{f.source.label()}: {f.message}; resetMotion() clears the motion queue"

    # ---- building the path -----------------------------------------------------------------------

    def _positions(self, c: Cmd, lam) -> np.ndarray:
        lam = np.atleast_1d(np.asarray(lam, dtype=float))
        if c.curve is not None:
            return c.curve.positions(lam)
        return self.kin.tcp(c.geom.q(lam), c.tool)[:, :3, 3]

    def _distance_lambda(self, c: Cmd, d: float, from_end: bool) -> float | None:
        """λ where the TCP is at distance d from the target (from_end) or from the start, taking
        the last such point before the target (the first after the start); d is clipped to half
        the chord. None when d is too short to blend."""
        if isinstance(c.curve, Line):  # exact on a line
            L = c.curve.length_mm
            d = min(d, L / 2.0)
            if d < MIN_BLEND_MM:
                return None
            return 1.0 - d / L if from_end else d / L
        lam = np.linspace(0.0, 1.0, 33)
        P = self._positions(c, lam)
        ref = P[-1] if from_end else P[0]
        chord = float(np.linalg.norm(P[-1] - P[0]))
        d = min(d, chord / 2.0)
        if d < MIN_BLEND_MM:
            return None
        for _ in range(3):  # refine the bracket 8 times per round (1/16384 of the path)
            dist = np.linalg.norm(P - ref, axis=1)
            far = np.nonzero(dist >= d)[0]
            j = int(far.max()) if from_end else int(far.min())
            j = min(j, len(lam) - 2) if from_end else max(j, 1)
            a, b = (lam[j], lam[j + 1]) if from_end else (lam[j - 1], lam[j])
            lam = np.linspace(a, b, 9)
            P = self._positions(c, lam)
        dist = np.linalg.norm(P - ref, axis=1)
        far = np.nonzero(dist >= d)[0]
        return float(lam[far.max()] if from_end else lam[far.min()])

    def _integrate(self, c: Cmd, now: float) -> None:
        prev = self.open
        self.open = None
        hard = True
        if prev is not None:
            cand = self._blend_candidate(prev, c) if c.geom is not None else None
            if cand is not None and not self._blend_pays(prev, c, cand, now):
                cand = None  # stopping at the via point is faster: the arm does that
            if cand is None:
                self._close(prev)
            else:
                self._commit_blend(prev, c, cand)
                hard = False
        self.pending.append(c)
        self.history.append(c)
        if c.geom is None:
            c.S_begin = c.S_end = self.path.end
        else:
            if c.blend != "off":
                lam_l = self._distance_lambda(c, c.mdesc.leave, from_end=True)
                if lam_l is None or lam_l <= c.lam_in + 1e-9:
                    c.blend = "off"
                else:
                    c.lam_leave = lam_l
            if hard:
                c.S_begin = self.path.end
            b = c.lam_leave if c.blend != "off" else 1.0
            s0 = self.path.end
            if b > c.lam_in + 1e-12:
                sp = self._span(c.geom, c.lam_in, b, [(c.key, 0.0)], smooth=not hard, tool=c.tool)
                self.path.append(sp)
                c.spans.append(sp)
            c.S_nom = (s0, self.path.end, b)
            if c.blend != "off":
                self.open = c
                c.S_prov = self.path.end + (1.0 - c.lam_leave) * c.geom.ell
            else:
                c.S_end = self.path.end
        self._replan(now, from_final_decel=prev is not None)

    def _close(self, c: Cmd) -> None:
        """The command goes to its target and stops there (no blend): the rest of its path."""
        if c.lam_leave < 1.0 - 1e-12:
            sp = self._span(c.geom, c.lam_leave, 1.0, [(c.key, 0.0)], smooth=True, tool=c.tool)
            self.path.append(sp)
            c.spans.append(sp)
            if c.S_nom is not None:
                c.S_nom = (c.S_nom[0], self.path.end, 1.0)
        c.blend = "off"
        c.lam_leave = 1.0
        c.S_end = self.path.end
        c.S_prov = None

    def _close_open(self) -> None:
        if self.open is not None:
            self._close(self.open)
            self.open = None

    def _blend_candidate(self, prev: Cmd, c: Cmd):
        """The blend from prev's leave point to c's reach point (10.1.2): (geometry, λ of the
        reach point on c, the share of the blend that belongs to prev), or None when the two
        cannot be blended. Nothing is changed yet (`_commit_blend`)."""
        lam_r = self._distance_lambda(c, prev.mdesc.reach, from_end=False)
        if lam_r is None or lam_r >= 1.0 - 1e-9:
            return None
        gL, gR = prev.geom, c.geom
        lam_l = prev.lam_leave
        qL = gL.q([lam_l])[0]
        vL = gL.q([lam_l], 1)[0] / gL.ell
        qR = gR.q([lam_r])[0]
        vR = gR.q([lam_r], 1)[0] / gR.ell
        nl, nr = np.linalg.norm(vL), np.linalg.norm(vR)
        if nl < 1e-12 or nr < 1e-12 or float(vL @ vR) / (nl * nr) < CUSP_COS:
            return None
        ell_l = (1.0 - lam_l) * gL.ell
        ell_r = lam_r * gR.ell
        geom = None
        same_tool = (prev.tool is None and c.tool is None) or (
            prev.tool is not None and c.tool is not None and np.allclose(prev.tool, c.tool))
        if prev.blend == "Cartesian" and same_tool:
            geom = self._cartesian_blend(prev, c, qL, vL, qR, vR, ell_l, ell_r)
        if geom is None:
            shapes = [JointBlend(qL, vL, qR, vR, ell_l, ell_r, shape) for shape in BLEND_SHAPES]
            geom = shapes[0] if len(shapes) == 1 else min(shapes, key=lambda g: self._blend_time(g, prev, c))
        # the blend belongs to prev up to the point proportional to the two sides
        return geom, lam_r, geom.ell * ell_l / (ell_l + ell_r)

    def _commit_blend(self, prev: Cmd, c: Cmd, cand) -> Span:
        geom, lam_r, split = cand
        sp = self._span(geom, 0.0, 1.0, [(prev.key, 0.0), (c.key, split)], smooth=True, tool=prev.tool)
        off = self.path.append(sp)
        prev.spans.append(sp)
        c.spans.append(sp)
        prev.S_end = off + split
        prev.S_prov = None
        c.S_begin = off + split
        c.lam_in = lam_r
        return sp

    def _blend_pays(self, prev: Cmd, c: Cmd, cand, now: float) -> bool:
        """Whether the arm gets to c's target through the blend no later than by stopping at
        the via point (prev's target), from the state the re-timing will start from.

        10.1.2.1: blending is there to make the motion faster, and 10.1.2.3 lets the controller
        choose the blend's shape for speed; a blend of an awkward shape (very different leave
        and reach) can be slower than the stop it replaces, and then the arm stops at the via
        point instead. The blend is timed exactly (as the queue will time it, c closed at its
        target), and so is the stop (to the via point, then c alone from rest to rest); the
        blend is kept when it is no slower. By induction over the commands (docs/motion.md), a
        chain recorded ahead of the arm is then never slower than the same commands unblended."""
        geom, lam_r, split = cand
        prof = self.profile
        if self._pending is not None:
            t0 = self._pending[0]
        elif self._can_move():
            t0 = max(now, prof.T[prof.final_decel_start()])
        else:
            t0 = prof.t_end
        s0, v0, _ = prof.state(t0)
        if t0 >= prof.t_end:
            s0, v0 = prof.s_end, 0.0
        blended = [self._span(geom, 0.0, 1.0, [(prev.key, 0.0), (c.key, split)], smooth=True, tool=prev.tool),
                   self._span(c.geom, lam_r, 1.0, [(c.key, 0.0)], smooth=True, tool=c.tool)]
        tail = self._span(prev.geom, prev.lam_leave, 1.0, [(prev.key, 0.0)], smooth=True, tool=prev.tool)
        t_blend, pieces = self._trial_duration(s0, v0, blended)
        t_stop = self._trial_duration(s0, v0, [tail])[0] + self._rest_time(c)
        for sp in blended + [tail]:  # the one chosen is sampled once
            self._remember(sp)
        if t_blend <= t_stop * (1.0 + 1e-9):
            # when c ends there (no blend after it), this timing is the plan that follows
            self._trial = (t0, blended, pieces) if c.blend == "off" else None
            return True
        self.stops_chosen += 1
        self._trial = None
        return False

    def _span(self, geom, a, b, owners, smooth, tool) -> Span:
        """A span, with the samples of an identical one timed in a trial (`_blend_pays`)."""
        sp = Span(geom, a, b, owners, smooth, tool)
        hit = self._samples.get((id(geom), a, b))
        if hit is not None and hit[0] is geom and hit[1] is tool:
            sp._cache = hit[2]
        return sp

    def _remember(self, sp: Span) -> None:
        if sp._cache is not None:
            if len(self._samples) > 64:
                self._samples.clear()
            self._samples[(id(sp.geom), sp.a, sp.b)] = (sp.geom, sp.tool, sp._cache)

    def _rest_time(self, c: Cmd) -> float:
        """The time of command c alone, from rest at its start to rest at its target."""
        if c.rest_time is None:
            sp = self._span(c.geom, 0.0, 1.0, [(c.key, 0.0)], smooth=False, tool=c.tool)
            trial = Path(c.q_start)
            trial.append(sp)
            grid, owners = self._grid(0.0, trial.end, trial)
            c.rest_time = duration(*self._time(grid, owners, 0.0, report=False))
            self._remember(sp)
        return c.rest_time

    def _trial_duration(self, s0: float, v0: float, extra: list):
        """How long the arm takes from path position s0 at speed v0 to the end of the path
        followed by the spans `extra` (not added to the path), timed as `_plan_from` times it,
        and the pieces' profiles (s shifted to the path's positions)."""
        path = self.path
        trial = Path(path.q_rest)
        shift = 0.0
        if path.spans:
            i0, _ = path.locate(s0)
            for sp in path.spans[i0:]:
                trial.append(Span(sp.geom, sp.a, sp.b, sp.owners, sp.smooth, sp.tool, _cache=sp._cache))
            shift = path.offsets[i0]
        a = s0 - shift
        for sp in extra:
            trial.append(sp)
        total = 0.0
        pieces = []
        for b in trial.stops_after(a) + [trial.end]:
            if b - a <= _eps(b):
                a = b
                continue
            grid, owners = self._grid(a, b, trial)
            self._fell = False
            s, sd = self._time(grid, owners, v0, report=False)
            total += duration(s, sd)
            if self._fell:  # not reused: the plan reports it (R019)
                pieces = None
            if pieces is not None:
                pieces.append((s + shift, sd))
            a, v0 = b, 0.0
        return total, pieces

    def _blend_time(self, geom, prev: Cmd, c: Cmd) -> float:
        """An estimate of the time to go through a blend: its length at the speed its curvature
        and the joint speeds allow (the blend shape the arm follows fastest is chosen)."""
        lam = np.linspace(0.0, 1.0, 17)
        q1 = geom.q(lam, 1) / geom.ell
        q2 = geom.q(lam, 2) / geom.ell ** 2
        la, lb = self.limits_of(prev), self.limits_of(c)
        V = np.minimum(la.V, lb.V)
        A = np.minimum(np.minimum(la.A, la.D), np.minimum(lb.A, lb.D))
        with np.errstate(divide="ignore"):
            xv = np.min(np.where(np.abs(q1) > 1e-12, (V / np.abs(q1)) ** 2, np.inf), axis=1)
            xa = np.min(np.where(np.abs(q2) > 1e-12, A / np.abs(q2), np.inf), axis=1)
        sd = np.sqrt(np.minimum(xv, xa))
        return float(np.trapezoid(1.0 / np.maximum(sd, 1e-9), lam * geom.ell))

    def _cartesian_blend(self, prev: Cmd, c: Cmd, qL, vL, qR, vR, ell_l, ell_r):
        """A Cartesian blend tracked in the configuration of the leave point, of the shape the arm
        follows fastest; None when no shape can be followed there (the joint blend is used
        instead, docs/motion.md)."""
        best = None
        for shape in BLEND_SHAPES:
            g = self._cartesian_blend_shape(prev, qL, vL, qR, vR, ell_l, ell_r, shape)
            if g is not None:
                t = self._blend_time(g, prev, c) if len(BLEND_SHAPES) > 1 else 0.0
                if best is None or t < best[0]:
                    best = (t, g)
        return None if best is None else best[1]

    def _cartesian_blend_shape(self, prev: Cmd, qL, vL, qR, vR, ell_l, ell_r, shape):
        kin = self.kin
        h = 1e-4
        T = kin.tcp(np.vstack([qL, qL + h * vL, qL - h * vL, qR, qR + h * vR, qR - h * vR]), prev.tool)
        from .cartesian import rotvec

        def state(i):
            p = T[i, :3, 3]
            v = (T[i + 1, :3, 3] - T[i + 2, :3, 3]) / (2 * h)
            w = rotvec(T[i + 1, :3, :3] @ T[i + 2, :3, :3].T) / (2 * h)
            return p, T[i, :3, :3], v, w

        curve = Blend(state(0), state(3), ell_l, ell_r, shape)
        ell_b = curve.ell
        code = int(kin.config_codes(qL)[0])
        tr = track(kin, curve, prev.tool, qL, code)
        if tr.failure is not None or np.max(np.abs(tr.Q[-1] - qR)) > 1e-5:
            return None
        Q = tr.Q.copy()
        Q[-1] = qR
        D = tr.D.copy()
        D[0], D[-1] = ell_b * vL, ell_b * vR  # exactly the neighbours' velocities: C1 junctions
        g = JointSpline(tr.lam, Q, D)
        g.ell = ell_b
        g.sing = tr.sing
        g.curve = curve
        return g

    # ---- timing ------------------------------------------------------------------------------------

    def _can_move(self) -> bool:
        return self.powered and not self.held

    def _replan(self, now: float, from_final_decel: bool) -> None:
        """Re-time what the path added changes (see the module docstring), from the start of the
        final braking (or the end of the motion ahead), or now when that is past.

        The work is done when something reads the profile (`_flush`), so that a burst of records
        is timed once: a record merges into a pending replan when it comes before that replan's
        start (exactly the same result) or, from rest, within MERGE_WINDOW of the first record."""
        if not self._can_move():
            return
        if self._pending is not None:
            t_r0, t_req0, rest0 = self._pending
            if now <= t_r0 + 1e-12 or (rest0 and now - t_req0 <= MERGE_WINDOW):
                return
            self._flush()
        if from_final_decel:
            k = self.profile.final_decel_start()
            t_r = max(now, self.profile.T[k])
        else:
            t_r = max(now, self.profile.t_end)
        self._pending = (t_r, now, t_r >= self.profile.t_end)

    def _flush(self) -> None:
        """Do the pending replan (before anything reads the profile)."""
        if self._pending is not None:
            t_r = self._pending[0]
            self._pending = None
            self._plan_from(t_r)

    @property
    def trajectory(self) -> Trajectory:
        """The arm's trajectory (path + time parameterisation), up to date."""
        self._flush()
        return self._trajectory

    def _plan_from(self, t_r: float) -> None:
        prof = self.profile
        prof.cut(t_r)
        s_r, sd_r = prof.s_end, prof.SD[-1]
        if self.path.end - s_r <= _eps(s_r):
            if sd_r > 0:  # numerically at the end: stop there
                prof.SD[-1] = 0.0
            return
        trial, self._trial = self._trial, None
        if trial is not None and trial[0] == t_r and len(self.path.spans) >= len(trial[1]) and all(
                _same_span(x, y) for x, y in zip(self.path.spans[-len(trial[1]):], trial[1])) and trial[2] and abs(trial[2][0][0][0] - s_r) <= _eps(s_r) and abs(trial[2][-1][0][-1] - self.path.end) <= 1e-9 * max(
                1.0, self.path.end):
            t_cur = max(t_r, prof.t_end)
            pieces = trial[2]
            for i, (s_, sd_) in enumerate(pieces):  # the blend trial timed exactly this (`_blend_pays`)
                s_ = s_.copy()
                if i == 0:
                    s_[0] = s_r
                if i == len(pieces) - 1:
                    s_[-1] = self.path.end  # exactly where the last command ends
                prof.append(t_cur, s_, sd_)
                t_cur = prof.t_end
            return
        stops = self.path.stops_after(s_r) + [self.path.end]
        a, v0 = s_r, sd_r
        t_cur = max(t_r, prof.t_end)
        for b in stops:
            if b - a <= _eps(b):
                a = b
                continue
            grid, owners = self._grid(a, b)
            s, sd = self._time(grid, owners, v0)
            prof.append(t_cur, s, sd)
            t_cur = prof.t_end
            a, v0 = b, 0.0

    def limits_of(self, c: Cmd) -> Limits:
        lim = self._limits.get(c.key)
        if lim is None:
            m = self.monitor / 100.0
            lim = Limits.reduced(self.kin, m) if c.reduced else Limits.of(self.kin, c.mdesc, m)
            self._limits[c.key] = lim
        return lim

    def _grid(self, a: float, b: float, path: Path | None = None) -> tuple[Grid, np.ndarray]:
        """The path between global a and b sampled for the time parameterisation, and the key of
        the command that owns each gridpoint (at least MIN_GRID gridpoints: toppra cannot start and
        stop within fewer)."""
        grid, own = self._grid_spans(a, b, path=path)
        if len(grid) >= MIN_GRID:
            return grid, own
        return self._grid_spans(a, b, np.linspace(a, b, MIN_GRID), path=path)

    def _grid_spans(self, a: float, b: float, points: np.ndarray | None = None,
                    path: Path | None = None) -> tuple[Grid, np.ndarray]:
        path = self.path if path is None else path
        if points is not None:  # exactly these points (a short piece of path)
            parts = []
            for s_ in points:
                i, sig = path.locate(float(s_))
                sp = path.spans[i]
                smp = sp.sample_at(self.kin, min(max(sig, 0.0), sp.length))
                own = np.array([sp.owner_at(sig)])
                parts.append((np.array([s_]), smp["q1"], smp["q2"], smp["pt"], smp["rt"], own))
            return self._assemble(parts)
        kin = self.kin
        i0, _ = path.locate(a)
        parts = []
        keys = ("sigma", "q1", "q2", "pt", "rt")
        i = i0
        while i < len(path.spans):
            off = path.offsets[i]
            sp = path.spans[i]
            lo, hi = max(a - off, 0.0), min(b - off, sp.length)
            if hi < lo - 1e-12 or off > b + 1e-12:
                break
            smp = sp.sample(kin)
            sig = smp["sigma"][:-1]  # the grid (the last row is the junction point)
            first = not parts
            if first:
                start = 0 if abs(lo - sig[0]) <= 1e-12 else None
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
            if len(sp.owners) == 1:
                own = np.full(len(pts), sp.owners[0][0])
            else:
                owner_starts = np.array([st for _, st in sp.owners])
                owner_keys = np.array([k for k, _ in sp.owners])
                own = owner_keys[np.clip(np.searchsorted(owner_starts, pts + 1e-12, side="right") - 1, 0, None)]
            parts.append((pts + off, q1, q2, pt, rt, own))
            if off + sp.length >= b - 1e-12:
                break
            i += 1
        return self._assemble(parts)

    def _assemble(self, parts) -> tuple[Grid, np.ndarray]:
        s = np.concatenate([p[0] for p in parts])
        q1 = np.vstack([p[1] for p in parts])
        q2 = np.vstack([p[2] for p in parts])
        pt = np.concatenate([p[3] for p in parts])
        rt = np.concatenate([p[4] for p in parts])
        own = np.concatenate([p[5] for p in parts])
        keep = np.concatenate([[True], np.diff(s) > 1e-9])
        s, q1, q2, pt, rt, own = s[keep], q1[keep], q2[keep], pt[keep], rt[keep], own[keep]
        n = len(s)
        V = np.empty((n, q1.shape[1]))
        A = np.empty_like(V)
        D = np.empty_like(V)
        tv = np.empty(n)
        rv = np.empty(n)
        for key in np.unique(own):
            m = own == key
            lim = self.limits_of(self._by_key[int(key)])
            V[m], A[m], D[m], tv[m], rv[m] = lim.V, lim.A, lim.D, lim.tvel, lim.rvel
        return Grid(s, q1, q2, pt, rt, V, A, D, tv, rv), own

    def _time(self, grid: Grid, owners: np.ndarray, v0: float, report: bool = True) -> tuple[np.ndarray, np.ndarray]:
        """The profile of one stop-to-stop piece: exact on a straight joint line with one set of
        limits, toppra otherwise."""
        s = grid.s
        if _straight(grid, owners):
            aq = np.abs(grid.q1[0])
            mv = aq > 1e-12
            V = float(np.min(grid.V[0][mv] / aq[mv]))
            A = float(np.min(grid.A[0][mv] / aq[mv]))
            D = float(np.min(grid.D[0][mv] / aq[mv]))
            if np.max(grid.pt) * V <= grid.tv[0] and np.max(grid.rt) * V <= grid.rv[0]:
                ss, sd = trapezoid(float(s[-1] - s[0]), v0, V, A, D)
                return ss + s[0], sd
        res = self._topp(grid, v0)
        self._fell = res.fallback
        if res.fallback and report:
            self.fallbacks += 1
            key = int(owners[0])
            c = self._by_key.get(key)
            if c is not None and c.id is not None:
                self.findings.append(Finding(
                    F.FALLBACK, "the time-optimal parameterisation of this motion failed: a slower safe profile "
                    "is used (its times are an upper bound)", c.source, c.recorded, move_id=c.id))
        return res.s, res.sd

    def _topp(self, grid: Grid, v0: float):
        """timing.topp, remembered: a cyclic program times the same pieces of path again and
        again (the same points, from rest), and an identical problem has an identical answer."""
        s0 = grid.s[0]
        key = (v0, (grid.s - s0).tobytes(), grid.q1.tobytes(), grid.q2.tobytes(), grid.pt.tobytes(),
               grid.rt.tobytes(), grid.V.tobytes(), grid.A.tobytes(), grid.D.tobytes(), grid.tv.tobytes(),
               grid.rv.tobytes())
        hit = self._topp_cache.get(key)
        if hit is not None:
            s_rel, sd, fallback = hit
            s = s_rel + s0
            if len(s) == len(grid.s):  # toppra's answer is on the grid: exactly its positions
                s = grid.s.copy()
            s[0], s[-1] = grid.s[0], grid.s[-1]  # the ends exactly (a command ends there)
            return TimedProfile(s, sd.copy(), fallback)
        res = topp(grid, v0)
        if len(self._topp_cache) >= TOPP_CACHE:
            self._topp_cache.pop(next(iter(self._topp_cache)))
        self._topp_cache[key] = (res.s - s0, res.sd.copy(), res.fallback)
        return res

    # ---- time passes --------------------------------------------------------------------------------

    def advance(self, now: float) -> None:
        """Complete the commands the arm has finished by `now` (the Subsystem's advance)."""
        self._advance(now)

    def _advance(self, now: float, lenient: bool = False) -> None:
        if self._pending is not None:
            t_r0, t_req0, rest0 = self._pending
            # a record within the merge window: the profile up to now is the current one
            if not (lenient and (now <= t_r0 + 1e-12 or (rest0 and now - t_req0 <= MERGE_WINDOW))):
                self._flush()
        while self.pending:
            c = self.pending[0]
            if c.S_end is None:
                break
            t = self.profile.time_at(c.S_end)
            if t is None or t > now + 1e-12:
                break
            c.state = "done"
            c.t_done = max(t, c.recorded)
            if c.id is not None:
                self.pos_id = c.id + 1
            self.pending.pop(0)
            self._check_singularity(c)

    def _first_done_time(self) -> float | None:
        self._flush()
        if not self.pending:
            return None
        c = self.pending[0]
        if c.S_end is None:
            return None
        return self.profile.time_at(c.S_end)

    def next_event(self, now: float) -> float | None:
        """The earliest time after `now` at which something a task can observe changes: a command completes (a queue place frees, isEmpty, waitEndMove), the arm comes
        to rest, or it has been at rest 50 ms (isSettled). None when nothing will change."""
        self._flush()
        cands = []
        t = self._first_done_time()
        if t is not None and t > now:
            cands.append(t)
        te = self.profile.t_end
        if te > now:
            cands.append(te)
        if te > 0 and te + SETTLE_S > now:
            cands.append(te + SETTLE_S)
        cands = [c for c in cands if c > now + 1e-12]
        return min(cands) if cands else None

    def next_time(self, now_us: int) -> int | None:
        """next_event in integer microseconds (the scheduler's Subsystem protocol)."""
        t = self.next_event(now_us / 1e6)
        return None if t is None else int(math.ceil(t * 1e6 - 1e-6))

    def advance_us(self, to_us: int) -> None:
        self.advance(to_us / 1e6)

    # ---- the instructions of 10.6 ---------------------------------------------------------------------

    def wait_end_move(self, now: float) -> float | None:
        """waitEndMove (10.6): cancel the blend of the last command; the time at which the
        commanded position reaches its target (None: not while power is off or stopMove holds).
        Raises MotionError(150) when a recorded command cannot be executed."""
        self.advance(now)
        if self.failure is not None:
            raise MotionError(150, self._failure_text())
        if self.open is not None:
            self._close_open()
            self._replan(now, from_final_decel=True)
        return self.end_time(now)

    def end_time(self, now: float) -> float | None:
        """When every recorded command is done (now when the queue is empty)."""
        self.advance(now)
        if not self.pending:
            return now
        c = self.pending[-1]
        if c.S_end is None:
            return None
        t = self.profile.time_at(c.S_end)
        return None if t is None else max(t, now)

    def is_empty(self, now: float) -> bool:
        self.advance(now)
        return not self.pending

    def is_settled(self, now: float) -> bool:
        self._flush()
        since = self.profile.rest_since(now)
        return since is not None and now - since >= SETTLE_S - 1e-9

    def stop_move(self, now: float) -> None:
        """stopMove: stop on the path with the current command's deceleration; hold the motion."""
        if self.held:
            return
        self.held = True
        self._brake(now)

    def restart_move(self, now: float) -> None:
        self._flush()
        if not self.held:
            return
        self.held = False
        if self.powered:
            self._plan_from(max(now, self.profile.t_end))

    def set_power(self, on: bool, now: float) -> None:
        """Arm power (enablePower/disablePower, the scenario): without it the arm stops on its
        path and holds; recorded commands wait."""
        if on == self.powered:
            return
        self.powered = on
        if not on:
            self._brake(now)
        elif not self.held:
            self._plan_from(max(now, self.profile.t_end))

    def set_monitor_speed(self, percent: float, now: float) -> None:
        """setMonitorSpeed: every limit scales at once, the motion ahead is re-timed."""
        self._flush()
        if percent == self.monitor:
            return
        self.monitor = float(percent)
        self._limits.clear()
        if self._can_move():
            self._plan_from(now)

    def reset_motion(self, now: float, joints=None) -> None:
        """resetMotion / resetMotion(jStart): stop on the path, cancel every command, ids back
        to 0; with jStart the next command first connects to it (10.1.3). A jStart with another
        number of axes is error 81, one outside the joint limits error 70 (an invalid parameter:
        no connection move could reach it)."""
        if joints is not None:
            j = np.asarray(joints, dtype=float)
            if len(j) != len(self.kin.lo):
                raise MotionError(81, f"resetMotion: a joint value with {len(j)} axes for the {len(self.kin.lo)}-axis arm")
            if not self.model.in_limits(tuple(j)):
                raise MotionError(70, "resetMotion: the start position is outside the software joint limits")
        self._brake(now)
        s_stop = self.profile.s_end
        for c in self.pending:
            c.state = "cancelled"
        self.pending = []
        self.open = None
        self.failure = None
        self.path.cut(s_stop)
        self.held = False
        self.next_id = 0
        self.pos_id = 0
        self.connect_to = None if joints is None else np.asarray(joints, dtype=float)

    def set_move_id(self, value: float) -> None:
        """setMoveId: the identifier of the next motion command (10.6)."""
        self.next_id = value

    def get_move_id(self, now: float) -> float:
        """getMoveId (10.4, 10.6)."""
        self.advance(now)
        if not self.pending:
            return float(self.pos_id)
        c = self.pending[0]
        self._flush()
        s, _, _ = self.profile.state(now)
        end = c.S_end if c.S_end is not None else c.S_prov
        if c.id is None or c.S_begin is None or end is None or s < c.S_begin - 1e-12 or end - c.S_begin <= 0:
            return float(self.pos_id)
        if c.S_nom is not None:
            # on its own part of the path the progress is the command's path parameter (the
            # fraction of the distance for movel); across the blends it goes on linearly
            s0, s1, lam1 = c.S_nom
            frac = float(np.interp(s, [c.S_begin, s0, s1, end], [0.0, c.lam_in, lam1, 1.0]))
        else:
            frac = (s - c.S_begin) / (end - c.S_begin)
        return c.id + min(max(frac, 0.0), 0.999999)

    def _brake(self, now: float) -> None:
        self._flush()
        t_r = now
        prof = self.profile
        prof.cut(t_r)
        sd = prof.SD[-1]
        if sd <= 0.0:
            return
        s_r = prof.s_end
        stops = self.path.stops_after(s_r) + [self.path.end]
        grid, _ = self._grid(s_r, stops[0])
        s, v = brake_stop(grid, sd)
        prof.append(prof.t_end, s, v)

    # ---- the arm's state -------------------------------------------------------------------------------

    def position(self, now: float) -> np.ndarray:
        """herej(): the commanded joint position (degrees)."""
        self._flush()
        return self._trajectory.position(now)

    def velocity(self, now: float) -> np.ndarray:
        self._flush()
        return self._trajectory.velocity(now)

    def acceleration(self, now: float) -> np.ndarray:
        """Joint accelerations of the commanded motion (deg/s²): q'·s̈ + q''·ṡ²."""
        self._flush()
        s, sd, sdd = self.profile.state(now)
        if sd == 0.0 and sdd == 0.0:
            return np.zeros_like(self.path.q_rest)
        return self.path.q([s], 1)[0] * sdd + self.path.q([s], 2)[0] * sd * sd

    def joint_force(self, now: float) -> np.ndarray | None:
        """getJointForce: the inverse dynamics of the commanded motion (N·m), or None when the
        arm model has no inertial data (dynamics.py)."""
        from .dynamics import joint_forces

        return joint_forces(self.model, self.position(now), self.velocity(now), self.acceleration(now))

    def get_speed(self, tool, now: float) -> float:
        """getSpeed(tool): the TCP translation speed from the commanded joint speeds (mm/s)."""
        q = self.position(now)
        qd = self.velocity(now)
        if not np.any(qd):
            return 0.0
        h = 1e-4
        T = self.kin.tcp(np.vstack([q + h * qd, q - h * qd]), None if tool is None else np.asarray(tool, float))
        return float(np.linalg.norm(T[0, :3, 3] - T[1, :3, 3]) / (2 * h))

    def blocked_reason(self) -> str | None:
        """Why recorded commands do not move, if they wait: for a task waiting on them."""
        if not self.pending and self.open is None:
            return None
        if not self.powered:
            return "the arm is not powered"
        if self.held:
            return "stopMove() holds the motion until restartMove() or resetMotion()"
        return None

    # ---- singularities along completed commands -------------------------------------------------------

    def _check_singularity(self, c: Cmd) -> None:
        """R014: a Cartesian command that passed near a singularity and slowed for it."""
        if c.checked or c.geom is None or not isinstance(c.geom, JointSpline) or c.curve is None:
            return
        c.checked = True
        sing = getattr(c.geom, "sing", None)
        if sing is None or (sing.wrist.min(initial=np.inf) >= THRESHOLDS["wrist"]
                            and sing.elbow.min(initial=np.inf) >= THRESHOLDS["elbow"]
                            and sing.shoulder.min(initial=np.inf) >= THRESHOLDS["shoulder"]):
            return
        g = c.geom
        q1 = g.q(g.lam, 1) / g.ell
        pt, _ = tcp_rates(self.kin, g.Q, q1, c.tool)
        lim = self.limits_of(c)
        sp = singular_pass(sing, q1, pt, lim.V, lim.tvel)
        if sp is None or sp.ratio >= 0.5:
            return
        lam = float(g.lam[sp.index])
        at = lam * c.curve.length_mm
        # where the arm passed it, and how fast
        s_glob = None
        for span in c.spans:
            if span.geom is g and span.a - 1e-12 <= lam <= span.b + 1e-12 and span.offset is not None:
                s_glob = span.offset + (lam - span.a) * g.ell
        t_pass = self.profile.time_at(s_glob) if s_glob is not None else None
        unit = "°" if sp.which != "shoulder" else " mm"
        msg = (f"{c.kind} passes near the {WHAT[sp.which]}: {sp.distance:.2f}{unit} at {at:.1f} mm along the path; "
               f"to keep {sp.reference:.0f} mm/s axis {sp.axis + 1} would need {sp.needed:.0f}°/s (limit "
               f"{sp.nominal:.0f}°/s): the TCP slows to {sp.cap:.0f} mm/s ({sp.ratio * 100:.0f} %)")
        self.findings.append(Finding(
            F.SINGULAR_SLOW, msg, c.source, t_pass if t_pass is not None else c.recorded, move_id=c.id,
            data={"singularity": sp.which, "distance": round(sp.distance, 4), "along_mm": round(at, 3),
                  "axis": sp.axis + 1, "needed_deg_s": round(sp.needed, 3), "limit_deg_s": round(sp.nominal, 3),
                  "tcp_cap_mm_s": round(sp.cap, 3), "reference_mm_s": round(sp.reference, 3)}))


def _eps(s: float) -> float:
    """A tolerance on path positions: s grows over a run (and so do its rounding errors)."""
    return 1e-12 * max(1.0, abs(s))


def _same_span(x: Span, y: Span) -> bool:
    return x.geom is y.geom and x.a == y.a and x.b == y.b and x.smooth == y.smooth


def _straight(grid: Grid, owners: np.ndarray) -> bool:
    """A straight joint line with one set of limits (the exact trapezoid applies)."""
    return bool(np.all(np.abs(grid.q2) < 1e-12) and np.all(owners == owners[0])
                and np.allclose(grid.q1, grid.q1[0], atol=1e-12))


def _r(v) -> list[float]:
    return [round(float(x), 6) for x in v]


def _name(tg) -> str:
    return f" {tg.name}" if getattr(tg, "name", "") else ""
