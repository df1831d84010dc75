"""The motion queue of one arm: chapter 10 as a state machine in simulated time (10.2, 10.6).

A motion instruction records a command and returns its identifier at once (10.2.1); the arm
executes the queue behind the program. Everything here is a pure function of the calls and
their times (seconds), so a fake clock tests it:

    q = MotionQueue(model)                   # the arm at rest, powered, monitor speed 100 %
    i = q.record(MoveCommand(...), now)      # an id (int), or QueueFull(until=...) when full
    q.wait_end_move(now)                     # cancels the last blend; the time the arm gets there
    q.get_move_id(now); q.position(now); q.is_settled(now) ...
    q.next_event(now) / q.advance(now)       # for the scheduler (Subsystem protocol)

The queue keeps the state of 10.2/10.6: the commands recorded and not done (`pending`), every
command of the run (`history`), the last one left blended (`open`), the identifiers, arm power,
stopMove's hold, the monitor speed, and the failure that makes the next instruction raise 150.
Its collaborators do the rest, each with explicit inputs and outputs:

* construction.py  a recorded command's joint-space geometry (10.1), or why it cannot be executed;
* failures.py      the findings of commands the arm cannot execute (R010-R013): 154 or 150;
* planner.py       the path built from the commands, blends (blending.py) and replans;
* timing/          a path plus its limits → a time parameterisation (the one place of 10.3);
* checks.py        the singularity analysis (R014 when a command completes).

Semantics (docs/motion.md gives the choices where the manual is silent):

* The path is built as commands arrive. A blended command (blend joint/Cartesian) ends, for now,
  at its leave point: the arm never passes it before the next command is recorded (10.2.2); when
  it comes, the blend to it is built and the not-yet-executed tail is re-timed from the arm's
  exact state. waitEndMove cancels the last blend: the arm goes on to the target and stops
  (10.1.2.2).
* Errors at the instruction raise `MotionError` before anything is recorded (mdesc 100-106; 154
  for a target outside the software limits, out of reach or only in another configuration, and an
  arc movec cannot define; 81). A command whose path the arm cannot follow (found while the path
  is interpolated: a joint limit, the workspace's edge, a singularity on the way) is accepted, the
  arm stops before it, and the next motion instruction, waitEndMove, open or close raises 150
  (12.1) until resetMotion (failures.py).
* getMoveId: integer part the command being executed, fraction its progress along its own
  part of the path (a blend belongs to the first command up to that command's target, then to
  the next); at rest after command n: n + 1 (10.6 examples).
* The monitor speed (8.1: 0 to 100 %) scales every limit; at 0 the arm holds on its path, as for
  stopMove, until the monitor speed rises again.
"""

from __future__ import annotations

import math

import numpy as np

from ..light_dataclass import dataclass
from . import findings as F
from . import trial_memo
from .checks import slowdown
from .commands import MoveCommand
from .construction import JOINT_EQ, construct
from .failures import deferred, failure_text
from .findings import Finding, MotionError
from .kin import ArmKin
from .mdesc import CommandLimits, Limits, MDesc
from .paths import JointLine
from .planner import Planner
from .queued import Geometry, QueuedCommand, Request
from .trajectory import Trajectory

CAPACITY = 16  # commands recorded and not yet completed (10.2.1: the memory is limited)
SETTLE_S = 0.05  # isSettled: at rest for 50 ms (perfect tracking: the commanded position)
CLASSES = 4096  # command classes kept (`_class_of`); the table is emptied when full


@dataclass
class QueueFull:
    """The queue is full: the motion instruction waits until `until` (None: no place will free
    while the arm cannot move: power off, stopMove or monitor speed 0)."""

    until: float | None


class MotionQueue:
    """See the module docstring. `model`: the arm (robot.RobotModel); `joints`: where it starts."""

    def __init__(self, model, joints=None, *, powered: bool = True, monitor: float = 100.0,
                 capacity: int = CAPACITY):
        """An empty queue, the arm at rest at `joints` (all zeros by default)."""
        self.model = model
        self.kin = ArmKin(model)
        q0 = np.zeros(len(model.joint_limits)) if joints is None else np.asarray(joints, dtype=float)
        self.capacity = capacity
        self.powered = powered
        self.held = False  # stopMove
        self.monitor = float(monitor)
        # the limits scale with the last monitor speed above 0 (at 0 the arm holds)
        self.limits = CommandLimits(self.kin, self.monitor if self.monitor > 0 else 100.0)
        self.planner = Planner(self.kin, q0, self.limits.of, self._fell_back, self.limits.value_keys)
        self.next_id = 0
        self.pos_id = 0
        self.pending: list[QueuedCommand] = []  # recorded and not done, the one executed first
        self.history: list[QueuedCommand] = []  # every command of the run, in recording order
        self.open: QueuedCommand | None = None  # the last command, blended, waiting for the next one
        self.failure: Finding | None = None  # a recorded command that cannot be executed
        self.connect_to: np.ndarray | None = None  # resetMotion(jStart)
        self.auto_connect = False
        self.findings: list[Finding] = []
        self.completed = 0  # commands of the program done (a counter: the progress display asks often)
        self._keys = 0
        self._by_key: dict[int, QueuedCommand] = {}
        self._classes: dict[tuple, tuple] = {}  # `_class_of`
        self._checked: dict[int, tuple] = {}  # id(mdesc) -> (it, MDesc.check's answer)
        self._done: tuple = ()  # (planner.changes, command key, its end, when it gets there): `_done_time`
        self._next: tuple = ()  # (what next_event's answer depends on, the time asked, the answer): `next_event`
        self._told = 0.0  # the latest time the queue was advanced to (`final_before`)
        self.released_done = 0  # commands of the program done and released from `history` (`release`)

    # ---- what the arm does (the planner's) -------------------------------------------------------

    @property
    def path(self):
        """The arm's path over the run (paths.Path)."""
        return self.planner.path

    @property
    def profile(self):
        """The path parameter over simulated time (trajectory.Profile), as planned so far."""
        return self.planner.profile

    @property
    def trajectory(self) -> Trajectory:
        """The arm's trajectory (path + time parameterisation), up to date."""
        self.planner.flush()
        return self.planner.trajectory

    @property
    def fallbacks(self) -> int:
        """Pieces of path timed with the safe profile (R019)."""
        return self.planner.fallbacks

    @property
    def stops_chosen(self) -> int:
        """Via points where stopping was chosen over a slower blend."""
        return self.planner.stops_chosen

    def limits_of(self, command: QueuedCommand) -> Limits:
        """The limits `command` obeys at the current monitor speed."""
        return self.limits.of(command.key)

    # ---- recording ---------------------------------------------------------------------------------

    def record(self, move: MoveCommand, now: float) -> int | QueueFull:
        """movej/movel/movec (10.6): the command's identifier, or QueueFull."""
        self._advance(now, lenient=True)
        if self.failure is not None:
            raise MotionError(150, failure_text(self.failure))
        source = move.source
        md = move.mdesc
        checked = self._checked.get(id(md))  # (a frozen value: checked once per object, kept alive here)
        if checked is None or checked[0] is not md:
            if len(self._checked) >= 64:
                self._checked.clear()
            checked = self._checked[id(md)] = (md, md.check())
        bad = checked[1]
        if bad is not None:
            code, msg = bad
            f = Finding(F.MDESC, f"{move.kind}: {msg}", source, now, error=code,
                        data={"field": msg.split(" ")[0].replace("mdesc.", ""), "code": code})
            raise MotionError(code, msg, f)
        if len(self.pending) >= self.capacity:
            return QueueFull(self._first_done_time())
        q_s = self._start_joints()
        connect = self.connect_to is not None and np.max(np.abs(self.connect_to - q_s)) > JOINT_EQ
        tool = None if move.tool is None else np.asarray(move.tool, dtype=float)
        # raises at the instruction (154, 81: construction.py) before anything is recorded
        built = construct(self.kin, move, self.connect_to if connect else q_s, tool, now)
        if connect:
            self._add_connection(q_s, self.connect_to, now, source)
        self.connect_to = None
        command = self._new_command(Request(move.kind, source, now, move.mdesc, tool, move.tool_name,
                                            move.target.name, move.target.frame), built.geometry)
        command.placement.blend = built.blend
        self.findings.extend(built.notes)
        command.id = self.next_id
        self.next_id += 1
        if built.failure is not None:
            self._defer(command, built.failure)
            self.history.append(command)
            if self.open is not None:
                self._close_open()
                self.planner.replan(now, True, self._can_move())
            return command.id
        self._append(command, now)
        return command.id

    def _start_joints(self) -> np.ndarray:
        """Where the next command starts: the end of the last one, or where the arm rests."""
        if self.pending:
            return self.pending[-1].geometry.q_end.copy()
        return self.path.q_rest.copy()

    def _new_command(self, request: Request, geometry: Geometry) -> QueuedCommand:
        """A command with the next key, its limits known by that key."""
        self._keys += 1
        command = QueuedCommand(self._keys, None, request, geometry)
        self._by_key[command.key] = command
        asked = self.limits.register(command.key, request.mdesc, request.reduced)
        command.cls = self._class_of(request, geometry, asked)
        return command

    def _class_of(self, request: Request, geometry: Geometry, asked: tuple) -> int:
        """The command's class (QueuedCommand.cls): one number per kind, curves (by the objects, kept
        alive by the table so that their ids name them), start, end, tool, and mdesc and reduced speed
        (`asked`: the one tuple CommandLimits keeps for their values, by its id)."""
        tool = request.tool
        values = (request.kind, id(geometry.joint_curve), id(geometry.tcp_curve), geometry.q_start.tobytes(),
                  geometry.q_end.tobytes(), None if tool is None else tool.tobytes(), id(asked))
        hit = self._classes.get(values)
        if hit is None:
            if len(self._classes) >= CLASSES:
                self._classes.clear()
            hit = self._classes[values] = (trial_memo.number(), geometry.joint_curve, geometry.tcp_curve)
        return hit[0]

    def _add_connection(self, q_s, target, now, source) -> None:
        """resetMotion(jStart): a point-to-point move to jStart at reduced speed first (10.1.3)."""
        q_end = np.asarray(target, dtype=float)
        command = self._new_command(Request("connection", source, now, MDesc(blend="off"), None, reduced=True),
                                    Geometry(q_s, q_end, JointLine(q_s, q_end)))
        self._append(command, now)

    def _append(self, command: QueuedCommand, now: float) -> None:
        """Queue a command the arm can execute: joined to the path (and the open command's blend)."""
        previous, self.open = self.open, None
        opened = self.planner.extend(command, previous, now, self._can_move())
        self.pending.append(command)
        self.history.append(command)
        if opened:
            self.open = command

    def _defer(self, command: QueuedCommand, finding: Finding) -> None:
        """A command the arm cannot execute (failures.py): recorded with its identifier, the arm
        stops before it, and the next motion instruction, waitEndMove, open or close raises 150."""
        finding = deferred(finding)
        command.state = "failed"
        self.findings.append(finding)
        self.failure = finding

    def _close_open(self) -> None:
        """The blended last command goes to its target and stops (waitEndMove, 10.1.2.2)."""
        if self.open is not None:
            self.planner.close(self.open)
            self.open = None

    def _fell_back(self, key: int) -> None:
        """R019 for the command `key` when its piece of path got the safe profile."""
        command = self._by_key.get(key)
        if command is not None and command.id is not None:
            self.findings.append(Finding(
                F.FALLBACK, "the time-optimal parameterisation of this motion failed: a slower safe profile "
                "is used (its times are an upper bound)", command.request.source, command.request.recorded,
                move_id=command.id))

    def _can_move(self) -> bool:
        """Power on, no stopMove, a monitor speed above 0."""
        return self.powered and not self.held and self.monitor > 0.0

    # ---- time passes -------------------------------------------------------------------------------

    def advance(self, now: float) -> None:
        """Complete the commands the arm has finished by `now` (the Subsystem's advance)."""
        planner = self.planner
        pending = self.pending
        if planner.due is None and pending:
            # (most calls: no replan due and the first command's kept end time still ahead, as `_advance` reads it)
            done = self._done
            if done and (done[3] is None or done[3] > now + 1e-12) and done[0] == planner.changes and \
                    done[1] == pending[0].key and done[2] == pending[0].placement.s_end and trial_memo.REUSE:
                if now > self._told:
                    self._told = now
                return
        self._advance(now)

    def _advance(self, now: float, lenient: bool = False) -> None:
        """Complete the commands done by `now`; `lenient`: a record within the merge window does
        not force the replan due (the profile up to now is the current one)."""
        if now > self._told:
            self._told = now
        planner = self.planner
        if planner.due is not None and not (lenient and planner.merges(now)):
            planner.flush()
        pending = self.pending
        while pending:
            command = pending[0]
            done = self._done  # (most cycles: the first command's kept end time, still ahead)
            if done and done[1] == command.key and done[0] == planner.changes and \
                    done[2] == command.placement.s_end and trial_memo.REUSE:
                t = done[3]
            else:
                t = self._done_time(command)
            if t is None or t > now + 1e-12:
                break
            command.state = "done"
            command.t_done = max(t, command.request.recorded)
            if command.id is not None:
                self.pos_id = command.id + 1
                self.completed += 1
            pending.pop(0)
            self._check_singularity(command)

    def _check_singularity(self, command: QueuedCommand) -> None:
        """R014 for a completed command that passed near a singularity (checks.slowdown)."""
        g = command.geometry
        if g.joint_curve is None or g.tcp_curve is None:
            return
        found = slowdown(self.kin, command, self.limits.of(command.key), self.profile)
        if found is not None:
            self.findings.append(found)

    def _first_done_time(self) -> float | None:
        """When the command executed first completes (a queue place frees)."""
        self.planner.flush()
        if not self.pending:
            return None
        return self._done_time(self.pending[0])

    def _done_time(self, command: QueuedCommand) -> float | None:
        """When the commanded position reaches `command`'s end (None: not planned yet). Asked every
        scheduler cycle: kept until the profile changes (planner.changes) or the end moves."""
        end = command.placement.s_end
        if end is None:
            return None
        done = self._done
        if done and done[0] == self.planner.changes and done[1] == command.key and done[2] == end \
                and trial_memo.REUSE:
            return done[3]
        t = self.profile.time_at(end)
        self._done = (self.planner.changes, command.key, end, t)
        return t

    def next_event(self, now: float) -> float | None:
        """The earliest time after `now` at which something a task can observe changes: a command
        completes (a queue place frees, isEmpty, waitEndMove), the arm comes to rest, or it has
        been at rest 50 ms (isSettled). None when nothing will change."""
        after = now + 1e-12  # (asked every scheduler cycle: no lists, the flush once)
        planner = self.planner
        if planner.due is None and self._next and trial_memo.REUSE:
            # nothing changed since the last answer (the profile, the first command, its end) and
            # it is still ahead: the same answer (the times it passed over were at or before then)
            state, asked, best = self._next
            first = self.pending[0] if self.pending else None
            if state[0] == planner.changes and state[1] is first and \
                    (first is None or state[2] == first.placement.s_end) and asked <= now and \
                    (best is None or best > after):
                return best
        best = None
        t = self._first_done_time()  # (it does the replan due before anything is read)
        if t is not None and t > after:
            best = t
        te = self.planner.profile.t_end
        if te > after and (best is None or te < best):
            best = te
        if te > 0 and te + SETTLE_S > after and (best is None or te + SETTLE_S < best):
            best = te + SETTLE_S
        first = self.pending[0] if self.pending else None
        self._next = ((planner.changes, first, None if first is None else first.placement.s_end), now, best)
        return best

    def next_time(self, now_us: int) -> int | None:
        """next_event in integer microseconds (the scheduler's Subsystem protocol)."""
        t = self.next_event(now_us / 1e6)
        return None if t is None else int(math.ceil(t * 1e6 - 1e-6))

    def advance_us(self, to_us: int) -> None:
        """advance at a time in integer microseconds (the scheduler's Subsystem protocol)."""
        self.advance(to_us / 1e6)

    # ---- the instructions of 10.6 ----------------------------------------------------------------

    def wait_end_move(self, now: float) -> float | None:
        """waitEndMove (10.6): cancel the blend of the last command; the time at which the
        commanded position reaches its target (None: not while the arm cannot move).
        Raises MotionError(150) when a recorded command cannot be executed."""
        self.advance(now)
        if self.failure is not None:
            raise MotionError(150, failure_text(self.failure))
        if self.open is not None:
            self._close_open()
            self.planner.replan(now, True, self._can_move())
        return self.end_time(now)

    def end_time(self, now: float) -> float | None:
        """When every recorded command is done (now when the queue is empty)."""
        self.advance(now)
        if not self.pending:
            return now
        end = self.pending[-1].placement.s_end
        if end is None:
            return None
        t = self.profile.time_at(end)
        return None if t is None else max(t, now)

    def is_empty(self, now: float) -> bool:
        """isEmpty (10.6): every recorded command is done."""
        self.advance(now)
        return not self.pending

    def is_settled(self, now: float) -> bool:
        """isSettled (10.6): the commanded position has not moved for 50 ms."""
        self.planner.flush()
        since = self.profile.rest_since(now)
        return since is not None and now - since >= SETTLE_S - 1e-9

    def stop_move(self, now: float) -> None:
        """stopMove: stop on the path with the current command's deceleration; hold the motion."""
        if self.held:
            return
        self.held = True
        self.planner.brake(now)

    def restart_move(self, now: float) -> None:
        """restartMove: resume a motion held by stopMove."""
        self.planner.flush()
        if not self.held:
            return
        self.held = False
        if self._can_move():
            self.planner.plan_from(max(now, self.profile.t_end))

    def set_power(self, on: bool, now: float) -> None:
        """Arm power (enablePower/disablePower, the scenario): without it the arm stops on its
        path and holds; recorded commands wait."""
        if on == self.powered:
            return
        self.powered = on
        if not on:
            self.planner.brake(now)
        elif self._can_move():
            self.planner.plan_from(max(now, self.profile.t_end))

    def set_monitor_speed(self, percent: float, now: float) -> None:
        """setMonitorSpeed (8.1: 0 to 100 %): every limit scales at once, the motion ahead is
        re-timed. At 0 the arm stops on its path (with the decelerations it had) and holds until
        the monitor speed rises again."""
        self.planner.flush()
        percent = float(percent)
        if percent == self.monitor:
            return
        if percent <= 0.0:
            if self._can_move():
                self.planner.brake(now)
            self.monitor = 0.0
            return
        was = self.monitor
        self.monitor = percent
        self.limits.set_monitor(percent)
        if self._can_move():
            self.planner.plan_from(now if was > 0.0 else max(now, self.profile.t_end))

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
        self.planner.brake(now)
        s_stop = self.profile.s_end
        for command in self.pending:
            command.state = "cancelled"
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
        command = self.pending[0]
        place = command.placement
        self.planner.flush()
        s, _, _ = self.profile.state(now)
        end = place.s_end if place.s_end is not None else place.s_provisional
        if command.id is None or place.s_begin is None or end is None or s < place.s_begin - 1e-12 \
                or end - place.s_begin <= 0:
            return float(self.pos_id)
        if place.nominal is not None:
            # on its own part of the path the progress is the command's path parameter (the
            # fraction of the distance for movel); across the blends it goes on linearly
            s0, s1, lam1 = place.nominal
            frac = float(np.interp(s, [place.s_begin, s0, s1, end], [0.0, place.lam_in, lam1, 1.0]))
        else:
            frac = (s - place.s_begin) / (end - place.s_begin)
        return command.id + min(max(frac, 0.0), 0.999999)

    def blocked_reason(self) -> str | None:
        """Why recorded commands do not move, if they wait: for a task waiting on them."""
        if not self.pending and self.open is None:
            return None
        if not self.powered:
            return "the arm is not powered"
        if self.held:
            return "stopMove() holds the motion until restartMove() or resetMotion()"
        if self.monitor <= 0.0:
            return "the monitor speed is 0 %: the arm holds until it rises"
        return None

    # ---- the arm's state -----------------------------------------------------------------------------

    def position(self, now: float) -> np.ndarray:
        """herej(): the commanded joint position (degrees)."""
        return self.trajectory.position(now)

    def velocity(self, now: float) -> np.ndarray:
        """The commanded joint velocities (deg/s)."""
        return self.trajectory.velocity(now)

    def acceleration(self, now: float) -> np.ndarray:
        """Joint accelerations of the commanded motion (deg/s²): q'·s̈ + q''·ṡ²."""
        self.planner.flush()
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


    def final_before(self) -> float:
        """The time before which the profile can no longer change (issue 29: the record is taken as
        the run goes, simulation/live_record.py): a replan or a brake cuts it at the time the queue
        is told or later (planner.py), a replan due at its start (a record that merges into it)."""
        due = self.planner.due
        return self._told if due is None else min(self._told, due.t_from)

    def release(self, n: int) -> None:
        """Drop the first n commands of `history`: their record is taken and nothing reads them
        again (simulation/live_record.py)."""
        for command in self.history[:n]:
            self._by_key.pop(command.key, None)
            if command.state == "done" and command.id is not None:
                self.released_done += 1
        del self.history[:n]

    def release_history(self) -> None:
        """The run is over and its record taken (simulation/retention.py): drop the commands kept
        for it (the trajectory stays)."""
        self.history, self.pending, self.open, self._by_key = [], [], None, {}
        self.limits._asked.clear()
        self.limits.value_keys.clear()
