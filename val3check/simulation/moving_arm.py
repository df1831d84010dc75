"""The arm of a run: the `Arm` port (interpretation/arm_port.py) and a `Subsystem` of the
scheduler (interpretation/subsystem.py) over the motion queue of chapter 10 (motion/queue.py):
where the interpreter meets motion.

    arm = MovingArm(model, cycles=None)     # model: val3check.robot.RobotModel, or None
    build_machine(..., arm=arm)             # run.py; arm.bind(machine.controller)
    arm.watch(reader)                       # reader(time_us, cycle): after each record, each cycle

What the interpreter reads (herej, here, open/close, the chapter 10 handlers of ch10_motion.py)
is the commanded position of the queue at the simulated time asked; the scheduler asks
`next_time` (the next moment a command completes, the arm comes to rest or has been at rest
50 ms: nothing is polled every 4 ms) and calls `advance` at the start of each cycle.

The controller's arm power and monitor speed (chapter 8, `interpretation/controller.py`, set by
the scenario, enablePower/disablePower and setMonitorSpeed) are followed at each cycle and at
each motion instruction: the queue holds the motion while the power is off and re-times it
when the monitor speed changes (docs/motion.md).

Units are converted here and nowhere else (2.1.4.1): poses, tvel, leave and reach in the
application's length unit, and the prismatic axis of a SCARA (joint 3) in it too; the queue
works in millimetres and degrees, seconds.

`watch(reader)` registers a reader of the program's values (collision_run.ValueWatch reads the
frames and tools of the cell): called (time_us, cycle=False) after each motion instruction
records a command, and (time_us, cycle=True) at the start of each scheduler cycle that advances
the arm (a command ends, the next starts).

Without an arm model (`model` None) the arm is idle: what acts on an idle arm works
(`isEmpty()`, `resetMotion()`, `autoConnectMove()`, `waitEndMove()`...), motion commands stop
the task with R002 saying how to name the arm (ch10_motion.py).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from ..interpretation.arm_port import Joints
from ..interpretation.scheduler import EndRun
from ..language.runtime_errors import Val3RuntimeError
from ..lengths import INCH_MM
from ..motion.commands import MoveCommand, Target
from ..motion.cycle import Context, CycleCounter, Loop, Pass
from ..motion.failures import failure_text
from ..motion.findings import MDESC, Finding, MotionError, Source
from ..motion.mdesc import MDesc
from ..motion.motion_records import time_leaving
from ..motion.queue import MotionQueue, QueueFull
from ..rules import codes
from .alteration import Alteration
from .arm_layers import Layers, QueueView
from .compliance import Compliance
from .live_record import LiveRecord
from .retention import Shared
from .model_arm import ModelArm

US = 1_000_000
TICK_US = 4000  # the controller's setpoints (ALTER's samples, 11.2.3)


class MovingArm(ModelArm):
    """See the module docstring."""

    def __init__(self, model: Any = None, *, cycles: int | None = None) -> None:
        """The arm of `model` (None: an idle arm); `cycles`: --cycles N."""
        super().__init__(model)
        self._queue: MotionQueue | None = None
        self.controller: Any = None
        self.auto_connect = False  # autoConnectMove (kept; the connection move is always automatic)
        self.counter = CycleCounter()
        self.cycles_goal = cycles  # --cycles N: the run ends when the arm starts cycle N + 1
        self._end_command = None  # that command, once recorded
        self.contexts: dict[int, Context] = {}  # command key -> the loops it was recorded in
        self._entries: dict[int, tuple[Any, int]] = {}  # id(pass counter) -> (it, entry number)
        self._entry_count: dict[Loop, int] = {}
        self._loops: dict[int, tuple[Any, Any, Loop]] = {}  # id(loop site) -> (it, its program, its Loop)
        self.prismatic = tuple(k == "prismatic" for k in (getattr(model, "joint_kinds", None) or ())) \
            if model is not None else ()
        self._readers: list[Callable[[int, bool], None]] = []  # `watch`
        self.base_model = model  # the standard geometry (setDH, 11.4, changes `model`)
        # what chapter 11 adds on top of the queue's trajectory (arm_layers.py)
        self.layers = Layers(len(model.joint_limits)) if model is not None else None
        self.compliance = Compliance()  # compliant moves and the cell's forces on them (11.1)
        self.alteration = Alteration(self)  # ALTER (11.2)
        if self.layers is not None:
            self.layers.hooks.append(_Hook(self))
        self.geometries: list[tuple[float, Any]] = []  # (from time s, model) after each setDH
        self.shared = Shared()  # what every command keeps, one object per value (retention.py)
        self.live = LiveRecord()  # the run's records taken as commands become final (issue 29)
        self._mdescs: dict[tuple, MDesc] = {}  # `_mdesc`
        # chapter 10's tools and points as the queue takes them, kept per value (ch10_motion: _tool, _point)
        self.tools: dict[int, tuple] = {}
        self.targets: dict[tuple, tuple] = {}
        self._last_context: tuple | None = None  # `context`: the last loops, their passes and context
        self._tool_in_mm: tuple | None = None  # `record`: (the last read-only tool given, s, its shared array)

    def bind(self, controller: Any) -> None:
        """The controller whose power and monitor speed the arm follows (chapter 8)."""
        self.controller = controller

    def watch(self, reader: Callable[[int, bool], None]) -> None:
        """Call `reader(time_us, cycle)` after each command recorded (cycle False) and at the start
        of each scheduler cycle that advances the arm (cycle True): see the module docstring."""
        self._readers.append(reader)

    # ---- the queue -----------------------------------------------------------------------------

    @property
    def queue(self) -> MotionQueue | None:
        """The motion queue (None without an arm model), created at the first use with the
        controller's power and monitor speed of that moment."""
        if self._queue is None and self.model is not None:
            ctl = self.controller
            self._queue = MotionQueue(self.model, np.array(self._initial, dtype=float),
                                      powered=True if ctl is None else bool(ctl.powered),
                                      monitor=100.0 if ctl is None else float(ctl.monitor_speed))
            self.layers.queue = self._queue
        return self._queue

    @property
    def queue_in_use(self) -> MotionQueue | None:
        """The motion queue if the run used it (a motion instruction, or the arm's state read),
        else None: what the run's record of the arm is made from (collect.py)."""
        return self._queue

    def sync(self, time_us: int) -> MotionQueue | None:
        """The queue, with the controller's power and monitor speed applied at `time_us`, as the
        chapter 10 handlers use it: told the queue time of the real times they give when a layer
        of chapter 11 holds the arm (arm_layers.QueueView)."""
        q = self._sync(time_us)
        if q is None or self.layers.trivial:
            return q
        return QueueView(q, self.layers)  # type: ignore[return-value]

    def queue_time(self, time_us: int) -> float:
        """The queue time (s) of real time `time_us` (arm_layers.Warp)."""
        t = time_us / US
        layers = self.layers
        if layers is None:
            return t
        w = layers.warp  # (Warp.queue_time's identity, asked several times a cycle, without its two calls)
        if len(w.T) == 1 and w.R[0] == 1 and w.TAU[0] == 0.0 and w.max_tau[0] <= t:
            return t
        return w.queue_time(t)

    def real_time(self, tau: float | None) -> float | None:
        """The first real time (s) the arm reaches queue time `tau`."""
        if tau is None or self.layers is None or self.layers.warp.identity:
            return tau
        return self.layers.warp.real_time(tau)

    def _sync(self, time_us: int) -> MotionQueue | None:
        """The queue itself, with the controller's power and monitor speed applied at `time_us`."""
        q = self._queue
        if q is None:
            q = self.queue
        ctl = self.controller
        # (asked several times a cycle, mostly unchanged: equal as they are, they are equal converted)
        if q is not None and ctl is not None and (ctl.powered != q.powered or ctl.monitor_speed != q.monitor):
            powered, monitor = bool(ctl.powered), float(ctl.monitor_speed)
            if powered != q.powered or monitor != q.monitor:
                t = self.queue_time(time_us)
                if powered != q.powered:
                    q.set_power(powered, t)
                if monitor != q.monitor:
                    q.set_monitor_speed(monitor, t)
        return q

    def set_geometry(self, model: Any, t: float) -> None:
        """setDH (11.4): the arm's kinematics are those of `model` from `t` on (the motion queue is
        empty: setDH waits for it)."""
        self.model = model
        self._kin = {}
        q = self._queue
        if q is not None:
            self.live.settle(self, q, self.queue_time(round(t * US)))  # the records so far: the old geometry
            q.model = model
            q.kin.use_geometry(model)
        self.geometries.append((t, model))

    # ---- the Arm port ----------------------------------------------------------------------------

    def start_at(self, joints: Sequence[float]) -> None:
        """The scenario's [robot] joints: the arm starts there (the queue is made again at first use)."""
        super().start_at(joints)
        self._queue = None

    def joints_at(self, time_us: int, millimeter_unit: bool = True) -> Joints:
        """herej(): the commanded joints at `time_us`, in the caller's unit."""
        q = self._sync(time_us)
        if q is None:
            return self._initial
        j = self.layers.actual(q.trajectory, time_us / US)
        return self.joints_out(j, millimeter_unit)

    def actual_position(self, t: float) -> np.ndarray:
        """The arm's commanded joints at `t` seconds (model units), what it does: the latch (9.2.3)
        reads it; no power or monitor speed is applied (`sync`), so a past time can be read."""
        q = self.queue
        if q is None:
            return np.array(self._initial, dtype=float) + self.layers.turns.at(t)
        return self.layers.actual(q.trajectory, t)

    def motion_done(self, time_us: int) -> bool:
        """The motion queue is empty (9.5.4, 10.6): no command left to execute (a move waiting for
        alterEnd is one, 11.2.3)."""
        q = self._sync(time_us)
        return q is None or q.is_empty(self.queue_time(time_us)) and not self.alteration.deferred

    def end_motion(self, time_us: int) -> None:
        """What waitEndMove() does before it waits (and open()/close(), 9.5.4): cancel the blend
        of the last command; error 150 when a recorded command cannot be executed."""
        q = self._sync(time_us)
        if q is None:
            return
        if self.alteration.deferred:  # the blend of the last move, when alterEnd records it
            if q.failure is not None:
                raise Val3RuntimeError(150, failure_text(q.failure))
            self.alteration.close_after_flush = True
            return
        try:
            q.wait_end_move(self.queue_time(time_us))
        except MotionError as exc:
            raise Val3RuntimeError(exc.code, exc.message) from None

    def has_room(self, time_us: int) -> bool:
        """A place in the motion queue (a motion instruction that found it full waits for this)."""
        q = self._sync(time_us)
        if q is None:
            return True
        q.advance(self.queue_time(time_us))
        return len(q.pending) + len(self.alteration.deferred) < q.capacity

    def waiting_reason(self) -> tuple[str, str] | None:
        """Why recorded motion cannot go on, for a task that waits for it: (rule, words naming
        the condition and what changes it), or None when the arm can move."""
        q = self._queue
        if q is not None and self.alteration.deferred:
            move = self.alteration.deferred[0][0]
            return codes.DEADLOCK, (f"the {move.kind} of line {move.source.line}, after an alterable trajectory, waits for "
                            "alterEnd() (11.2.3: it can be computed only after alterEnd), and no task calls it")
        if q is None or (not q.pending and q.open is None):
            return None
        if self.alteration.state == "error":
            return codes.DEADLOCK, (f"the arm stopped on an invalid alteration ({q.failure.source.label()}, R055): the motion "
                            "goes on only after resetMotion() (11.2.4)")
        held = self.compliance.waiting_reason(q, self.layers, self.compliance.t_eval)
        if held is not None:
            return codes.DEADLOCK, held
        if q.monitor <= 0.0 and q.powered and not q.held:
            return codes.DEADLOCK, ("the monitor speed is 0 %: the arm holds until setMonitorSpeed() or the scenario "
                            "([controller] changes = [{ at = ..., monitor_speed = ... }]) raises it")
        if not q.powered:
            ctl = self.controller
            if ctl is not None and (ctl.working_mode != 4 or ctl.es_status != 0):
                how = ("and enablePower() cannot power it outside remote mode or under an emergency stop: "
                       "set [controller] working_mode = 4 and es_status = 0, or powered = true, in the scenario")
            else:
                how = ("nothing powers it: the program can call enablePower() (remote mode), or the scenario "
                       "can start it powered ([controller] powered = true, the default) or power it later "
                       "([controller] changes = [{ at = ..., powered = true }])")
            return codes.MOTION_WITHOUT_POWER, f"the arm is not powered, {how}"
        if q.held:
            return codes.DEADLOCK, "stopMove() holds the motion and no task calls restartMove() or resetMotion()"
        return None

    # ---- the Subsystem -----------------------------------------------------------------------------

    def next_time(self, now_us: int) -> int | None:
        """The Subsystem's next change: a command completes, the arm rests or has rested 50 ms, or --cycles ends the run."""
        q = self._sync(now_us)
        if q is None:
            return None
        t = self._next_queue_event(q, now_us)
        # (what is off is not asked: no compliant move, no alter mode, no --cycles command: each cycle)
        tc = self.compliance.next_time(q, self.layers, now_us / US) if self.compliance.moves else None
        if tc is not None:
            e = max(int(np.ceil(tc * US - 1e-6)), now_us + 1)
            t = e if t is None else min(t, e)
        if self.alteration.state != "off" and self.alteration.needs_ticks(q, now_us / US):  # ALTER's 4 ms setpoints
            e = (now_us // TICK_US + 1) * TICK_US
            t = e if t is None else min(t, e)
        end = None if self._end_command is None else self._cycles_end()
        if end is not None:
            e = int(np.ceil(end * US - 1e-6))
            if e > now_us and (t is None or e < t):
                t = e
        return t

    def advance(self, to_us: int) -> None:
        """The Subsystem's advance: the watchers read the program's values, the commands done by `to_us` complete; EndRun when the arm starts the cycle after the last one asked for."""
        q = self._sync(to_us)
        if q is None:
            return
        for reader in self._readers:
            reader(to_us, True)
        self.compliance.update(q, self.layers, to_us / US)
        if self.alteration.state != "off":  # (off: its advance computes nothing)
            self.alteration.advance(q, to_us / US)
        q.advance(self.queue_time(to_us))
        self.live.take(self, q)
        end = None if self._end_command is None else self._cycles_end()
        if end is not None and end * US <= to_us + 1e-6:
            self._end_command = None  # once: stop() then runs as after any end of a run
            self.cycles_goal = None
            raise EndRun("cycles")

    def _cycles_end(self) -> float | None:
        """When the arm starts the command that begins cycle N + 1 (--cycles N)."""
        command = self._end_command
        if command is None or command.placement.s_begin is None or command.state == "cancelled":
            return None
        return self.real_time(time_leaving(self._queue.trajectory.profile, command.placement.s_begin))

    def _next_queue_event(self, q: MotionQueue, now_us: int) -> int | None:
        """The queue's next event (next_time) in real time: when the arm reaches it."""
        if self.layers.warp.identity:
            return q.next_time(now_us)
        tau = q.next_event(self.queue_time(now_us))
        t = self.real_time(tau)
        if t is None:
            return None
        e = int(np.ceil(t * US - 1e-6))
        return e if e > now_us else now_us + 1

    # ---- for the chapter 10 handlers -------------------------------------------------------------------

    def record(self, kind: str, target: Target, tool_in_flange, md: dict, via: Target | None, source: Source,
               tool_name: str, millimeter_unit: bool, time_us: int, loops: tuple = ()):
        """movej/movel/movec: the command's identifier, or QueueFull. Poses of `target`/`via`
        and `tool_in_flange` are 4x4 matrices in the caller's length unit; joints too (a
        SCARA's axis 3); `loops`: the loops the instruction runs in (Machine.loop_passes).
        Raises MotionError (mdesc 100-106, 154, 150, 81)."""
        q = self._sync(time_us)
        s = 1.0 if millimeter_unit else INCH_MM
        target = self._target_in_mm(target, s)
        via = None if via is None else self._target_in_mm(via, s)
        tool = None if tool_in_flange is None else self._tool_mm(tool_in_flange, s)
        move = MoveCommand(kind, target, self._mdesc(md, s), tool=tool, via=via,
                           source=self.shared.source(source), tool_name=tool_name)
        self.layers.before(time_us / US)
        context = self.context(loops)
        alterable, self.alteration.next_alterable = self.alteration.next_alterable, False
        if self.alteration.defers(q, alterable):
            # 11.2.3: after the alterable trajectory, waits for alterEnd (recorded then, by recorded())
            return self._defer(q, move, alterable, context, time_us)
        n = len(q.findings)
        r = q.record(move, self.queue_time(time_us))
        if not isinstance(r, QueueFull):
            if alterable:
                self.alteration.alterable.add(q.history[-1].key)
            else:
                self.alteration.check_carrier(q, q.history[-1], q.findings[n:])
            self.counter.note(source.task, context)
            self.recorded(q.history[-1], context)
            for reader in self._readers:
                reader(time_us, False)
        return r

    def _tool_mm(self, tool_in_flange: Any, s: float) -> np.ndarray:
        """The shared read-only TCP in the flange in mm (retention.Shared.tool) of `tool_in_flange`
        (`s` mm per unit). The last answer again for the same read-only matrix and `s`
        (ch10_motion._tool gives the same object while the tool is unchanged)."""
        last = self._tool_in_mm
        if last is not None and last[0] is tool_in_flange and last[1] == s:
            return last[2]
        made = np.array(tool_in_flange, dtype=float)
        if s != 1.0:
            made[:3, 3] *= s
        tool = self.shared.tool(made)
        # kept when it cannot change in place and the table already held its value (it stays there)
        fixed = type(tool_in_flange) is np.ndarray and not tool_in_flange.flags.writeable
        self._tool_in_mm = (tool_in_flange, s, tool) if fixed and tool is not made else None
        return tool

    def _mdesc(self, md: dict, s: float) -> MDesc:
        """The shared MDesc of the program's mdesc value `md` (`s` mm per unit), kept by the
        value's fields: a program records the same few mdescs again and again. Not kept when a
        field is zero (0.0 and -0.0 are equal keys with other values) or not hashable."""
        try:
            key = (tuple(md.items()), s)
            hit = self._mdescs.get(key)
        except TypeError:
            return self.shared.mdesc(MDesc.from_fields(md, s))
        if hit is None:
            hit = self.shared.mdesc(MDesc.from_fields(md, s))
            if 0.0 not in md.values():
                if len(self._mdescs) >= 64:
                    self._mdescs.clear()
                self._mdescs[key] = hit
        return hit

    def recorded(self, command: Any, context: Context) -> None:
        """A command entered the queue: its loops, and whether it completes the cycles asked for."""
        self.contexts[command.key] = context
        task = command.request.source.task
        if self.cycles_goal is not None and self._end_command is None and \
                self.counter.completed(task) >= self.cycles_goal:
            self._end_command = command

    def _defer(self, q: MotionQueue, move: MoveCommand, alterable: bool, context: Context,
               time_us: int) -> int | QueueFull:
        """A move recorded after an alterable trajectory while alter mode is on: its identifier now,
        recorded in the queue by alterEnd (11.2.3). What the queue checks at recording first (150, the
        mdesc); a full queue counts the waiting moves."""
        if q.failure is not None:
            raise MotionError(150, failure_text(q.failure))
        bad = move.mdesc.check()
        if bad is not None:
            code, msg = bad
            f = Finding(MDESC, f"{move.kind}: {msg}", move.source, self.queue_time(time_us), error=code,
                        data={"field": msg.split(" ")[0].replace("mdesc.", ""), "code": code})
            raise MotionError(code, msg, f)
        if len(q.pending) + len(self.alteration.deferred) >= q.capacity:
            return QueueFull(None)  # a place frees when alterEnd records them and the arm goes on
        ident = q.next_id
        q.set_move_id(ident + 1)
        self.alteration.deferred.append((move, ident, context))
        if alterable:
            self.alteration.deferred_alterable.add(ident)
        self.counter.note(move.source.task, context)
        for reader in self._readers:
            reader(time_us, False)
        return ident

    def context(self, loops: tuple) -> Context:
        """The loops of Machine.loop_passes as motion.cycle passes: each loop statement with the
        number of its entry (the n-th pass counter seen for it) and the pass."""
        last = self._last_context  # (the loops, their passes, the context): the commands of a pass share it
        if last is not None and len(loops) == len(last[0]):
            for (c, site, counter), (c0, site0, counter0), n in zip(loops, last[0], last[1]):
                if c is not c0 or site is not site0 or counter is not counter0 or int(counter[0]) != n:
                    break
            else:
                return last[2]
        out = []
        for compiled, site, counter in loops:
            known = self._loops.get(id(site))
            if known is None or known[0] is not site or known[1] is not compiled:
                known = self._loops[id(site)] = (site, compiled, Loop(compiled.path, site.line, site.col, compiled.name,
                                                                      site.kind))  # (kept: its id is not reused)
            loop = known[2]
            seen = self._entries.get(id(counter))
            if seen is None or seen[0] is not counter:
                n = self._entry_count[loop] = self._entry_count.get(loop, 0) + 1
                seen = self._entries[id(counter)] = (counter, n)  # kept: its id is not reused
            out.append(Pass(loop, seen[1], int(counter[0])))
        context = self.shared.context(tuple(out))
        self._last_context = (loops, tuple(p.iteration for p in out), context)
        return context

    def _target_in_mm(self, tg: Target, s: float) -> Target:
        """`tg` with its lengths (and a SCARA's axis 3) in mm: `s` millimetres per unit."""
        if tg.is_joint:
            return Target.joint(self.joints_in(tg.joints, s == 1.0), tg.name)
        if s == 1.0:  # already in mm (x * 1.0 is x): the handlers make each target's pose afresh (ch10_motion._point)
            return tg
        pose = np.array(tg.pose, dtype=float)
        pose[:3, 3] *= s
        return Target(pose=pose, config=tg.config, name=tg.name, frame=tg.frame, note=tg.note)

    def joints_in(self, joints: Sequence[float], millimeter_unit: bool) -> tuple[float, ...]:
        """Joint values of the application (a prismatic axis in its length unit) as the motion
        queue's: the model's units, less the turns resetTurn took off the continuous axis (11.5)."""
        if millimeter_unit or not any(self.prismatic):
            out = tuple(float(v) for v in joints)
        else:
            out = tuple(float(v) * INCH_MM if k < len(self.prismatic) and self.prismatic[k] else float(v)
                        for k, v in enumerate(joints))
        if self.layers is None or not self.layers.turns.times:
            return out
        return tuple(float(v) for v in np.asarray(out) - self.layers.turns.latest[:len(out)])

    def joints_out(self, joints: Sequence[float], millimeter_unit: bool) -> Joints:
        """Joint values of the model in the caller's unit (a prismatic axis in inches for an inch application)."""
        return tuple(self._out(float(v), k, millimeter_unit) + 0.0 for k, v in enumerate(joints))

    def _out(self, v: float, k: int, millimeter_unit: bool) -> float:
        """One joint value (axis k) in the caller's unit."""
        if millimeter_unit or not (k < len(self.prismatic) and self.prismatic[k]):
            return v
        return v / INCH_MM


class _Hook:
    """The arm's own layer hooks (arm_layers.Layers.hooks): the compliance brought up to date
    before the program acts on the queue."""

    def __init__(self, arm: MovingArm) -> None:
        self.arm = arm

    def before(self, t: float) -> None:
        q = self.arm.queue_in_use
        if q is not None:
            self.arm.compliance.update(q, self.arm.layers, t)
            if self.arm.alteration.state != "off":  # (off: its advance computes nothing)
                self.arm.alteration.advance(q, t)

    def after_reset(self, t: float) -> None:
        self.arm.alteration.after_reset(t)
