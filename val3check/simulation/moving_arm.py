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
from ..motion.findings import MotionError, Source
from ..motion.mdesc import MDesc
from ..motion.queue import MotionQueue, QueueFull
from ..motion.records import time_leaving
from .model_arm import ModelArm

US = 1_000_000


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
        self.prismatic = tuple(k == "prismatic" for k in (getattr(model, "joint_kinds", None) or ())) \
            if model is not None else ()
        self._readers: list[Callable[[int, bool], None]] = []  # `watch`

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
        return self._queue

    @property
    def queue_in_use(self) -> MotionQueue | None:
        """The motion queue if the run used it (a motion instruction, or the arm's state read),
        else None: what the run's record of the arm is made from (collect.py)."""
        return self._queue

    def sync(self, time_us: int) -> MotionQueue | None:
        """The queue, with the controller's power and monitor speed applied at `time_us`."""
        q = self.queue
        ctl = self.controller
        if q is not None and ctl is not None:
            t = time_us / US
            if bool(ctl.powered) != q.powered:
                q.set_power(bool(ctl.powered), t)
            if float(ctl.monitor_speed) != q.monitor:
                q.set_monitor_speed(float(ctl.monitor_speed), t)
        return q

    # ---- the Arm port ----------------------------------------------------------------------------

    def start_at(self, joints: Sequence[float]) -> None:
        """The scenario's [robot] joints: the arm starts there (the queue is made again at first use)."""
        super().start_at(joints)
        self._queue = None

    def joints_at(self, time_us: int, millimeter_unit: bool = True) -> Joints:
        """herej(): the commanded joints at `time_us`, in the caller's unit."""
        q = self.sync(time_us)
        if q is None:
            return self._initial
        j = q.position(time_us / US)
        return self.joints_out(j, millimeter_unit)

    def motion_done(self, time_us: int) -> bool:
        """The motion queue is empty (9.5.4, 10.6): no command left to execute."""
        q = self.sync(time_us)
        return q is None or q.is_empty(time_us / US)

    def end_motion(self, time_us: int) -> None:
        """What waitEndMove() does before it waits (and open()/close(), 9.5.4): cancel the blend
        of the last command; error 150 when a recorded command cannot be executed."""
        q = self.sync(time_us)
        if q is None:
            return
        try:
            q.wait_end_move(time_us / US)
        except MotionError as exc:
            raise Val3RuntimeError(exc.code, exc.message) from None

    def has_room(self, time_us: int) -> bool:
        """A place in the motion queue (a motion instruction that found it full waits for this)."""
        q = self.sync(time_us)
        if q is None:
            return True
        q.advance(time_us / US)
        return len(q.pending) < q.capacity

    def waiting_reason(self) -> tuple[str, str] | None:
        """Why recorded motion cannot go on, for a task that waits for it: (rule, words naming
        the condition and what changes it), or None when the arm can move."""
        q = self._queue
        if q is None or (not q.pending and q.open is None):
            return None
        if q.monitor <= 0.0 and q.powered and not q.held:
            return "R003", ("the monitor speed is 0 %: the arm holds until setMonitorSpeed() or the scenario "
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
            return "R018", f"the arm is not powered, {how}"
        if q.held:
            return "R003", "stopMove() holds the motion and no task calls restartMove() or resetMotion()"
        return None

    # ---- the Subsystem -----------------------------------------------------------------------------

    def next_time(self, now_us: int) -> int | None:
        """The Subsystem's next change: a command completes, the arm rests or has rested 50 ms, or --cycles ends the run."""
        q = self.sync(now_us)
        if q is None:
            return None
        t = q.next_time(now_us)
        end = self._cycles_end()
        if end is not None:
            e = int(np.ceil(end * US - 1e-6))
            if e > now_us and (t is None or e < t):
                t = e
        return t

    def advance(self, to_us: int) -> None:
        """The Subsystem's advance: the watchers read the program's values, the commands done by `to_us` complete; EndRun when the arm starts the cycle after the last one asked for."""
        q = self.sync(to_us)
        if q is None:
            return
        for reader in self._readers:
            reader(to_us, True)
        q.advance_us(to_us)
        end = self._cycles_end()
        if end is not None and end * US <= to_us + 1e-6:
            self._end_command = None  # once: stop() then runs as after any end of a run
            self.cycles_goal = None
            raise EndRun("cycles")

    def _cycles_end(self) -> float | None:
        """When the arm starts the command that begins cycle N + 1 (--cycles N)."""
        command = self._end_command
        if command is None or command.placement.s_begin is None or command.state == "cancelled":
            return None
        return time_leaving(self._queue.trajectory.profile, command.placement.s_begin)

    # ---- for the chapter 10 handlers -------------------------------------------------------------------

    def record(self, kind: str, target: Target, tool_in_flange, md: dict, via: Target | None, source: Source,
               tool_name: str, millimeter_unit: bool, time_us: int, loops: tuple = ()):
        """movej/movel/movec: the command's identifier, or QueueFull. Poses of `target`/`via`
        and `tool_in_flange` are 4x4 matrices in the caller's length unit; joints too (a
        SCARA's axis 3); `loops`: the loops the instruction runs in (Machine.loop_passes).
        Raises MotionError (mdesc 100-106, 154, 150, 81)."""
        q = self.sync(time_us)
        s = 1.0 if millimeter_unit else INCH_MM
        target = self._target_in_mm(target, s)
        via = None if via is None else self._target_in_mm(via, s)
        tool = None
        if tool_in_flange is not None:
            tool = np.array(tool_in_flange, dtype=float)
            tool[:3, 3] *= s
        move = MoveCommand(kind, target, MDesc.from_fields(md, s), tool=tool, via=via, source=source,
                           tool_name=tool_name)
        r = q.record(move, time_us / US)
        if not isinstance(r, QueueFull):
            task = source.task
            context = self.context(loops)
            self.contexts[q.history[-1].key] = context
            self.counter.note(task, context)
            if self.cycles_goal is not None and self._end_command is None and \
                    self.counter.completed(task) >= self.cycles_goal:
                self._end_command = q.history[-1]
            for reader in self._readers:
                reader(time_us, False)
        return r

    def context(self, loops: tuple) -> Context:
        """The loops of Machine.loop_passes as motion.cycle passes: each loop statement with the
        number of its entry (the n-th pass counter seen for it) and the pass."""
        out = []
        for compiled, site, counter in loops:
            loop = Loop(compiled.path, site.line, site.col, compiled.name, site.kind)
            seen = self._entries.get(id(counter))
            if seen is None or seen[0] is not counter:
                n = self._entry_count[loop] = self._entry_count.get(loop, 0) + 1
                seen = self._entries[id(counter)] = (counter, n)  # kept: its id is not reused
            out.append(Pass(loop, seen[1], int(counter[0])))
        return tuple(out)

    def _target_in_mm(self, tg: Target, s: float) -> Target:
        """`tg` with its lengths (and a SCARA's axis 3) in mm: `s` millimetres per unit."""
        if tg.is_joint:
            return Target.joint(self.joints_in(tg.joints, s == 1.0), tg.name)
        pose = np.array(tg.pose, dtype=float)
        pose[:3, 3] *= s
        return Target(pose=pose, config=tg.config, name=tg.name, frame=tg.frame)

    def joints_in(self, joints: Sequence[float], millimeter_unit: bool) -> tuple[float, ...]:
        """Joint values of the application (a prismatic axis in its length unit) in the model's."""
        if millimeter_unit or not any(self.prismatic):
            return tuple(float(v) for v in joints)
        return tuple(float(v) * INCH_MM if k < len(self.prismatic) and self.prismatic[k] else float(v)
                     for k, v in enumerate(joints))

    def joints_out(self, joints: Sequence[float], millimeter_unit: bool) -> Joints:
        """Joint values of the model in the caller's unit (a prismatic axis in inches for an inch application)."""
        return tuple(self._out(float(v), k, millimeter_unit) + 0.0 for k, v in enumerate(joints))

    def _out(self, v: float, k: int, millimeter_unit: bool) -> float:
        """One joint value (axis k) in the caller's unit."""
        if millimeter_unit or not (k < len(self.prismatic) and self.prismatic[k]):
            return v
        return v / INCH_MM
