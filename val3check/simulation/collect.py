"""The record of a run, collected from the machine when it ends: `collect(machine) -> SimResult`
(result.py) with the record of what the arm did and of the scene (`arm_run`, arm_record.py).

This is where the run's objects (the motion queue, the arm model, the program's variables) become
the plain records the reports read: the motion table with each command's tool, limits and
joints, the cycles, the arm's chain and the application's frames once. Nothing else hands the
reports anything of motion/, robot/ or geometry/.
"""

from __future__ import annotations

import math

from pathlib import Path
from typing import Any

from ..diagnostics import Diagnostic
from ..geometry.frames import Frame, root_pose
from ..geometry.rotation import angles_of, matrix
from ..interpretation.machine import Machine
from ..motion.cycle import cycle_stats
from ..motion.mdesc import MDesc
from ..motion.motion_records import busy_time
from ..motion.retime import each_retimed_times
from ..robot.models import ASSUMED_ACCELERATION_RANGE
from ..rules import codes
from .arm_layers import ActualTrajectory
from .arm_record import AccelerationRange, ArmRun, ArmScene, CycleEntry, FramePose, MotionEntry, MotionLimits, ToolUse
from .budget import WALL, RunBudget
from .moving_arm import MovingArm
from .result import END_REASONS, SimResult, TaskSummary


def collect(machine: Machine) -> SimResult:
    """The SimResult of a machine whose run ended: how it ended, the tasks, the diagnostics (the
    arm's findings included), the I/O and user page, and the record of the arm (`arm_run`)."""
    reason = machine.end_reason
    message = END_REASONS.get(reason, reason)
    if reason.startswith("budget:"):
        message = reason[len("budget:"):]
        reason = "budget"
    diags = list(machine.diags)
    if reason == "deadlock" and any(d.code == codes.INPUT_NEVER_DRIVEN for d in diags) and not any(d.code == codes.DEADLOCK for d in diags):
        # no task waits only for variables: the cell, not the program, would go on (R009)
        message = ("every task waits for the cell (inputs, serial or socket peers, keys, the controller's state), "
                   "which nothing in the run plays (a scenario can: docs/scenario.md)")
    if reason == "duration":
        running = [t.name for t in machine.scheduler.history if t.final is not None]
        diags.append(Diagnostic(codes.DURATION_REACHED, f"run stopped at --duration {machine.end_time / 1e6:g} s; tasks still alive: "
                                + (", ".join(running) or "none"), machine.app.path, 0, 0,
                                time_us=machine.end_time, task="", program=""))
    elif reason in ("wall-clock", "steps", "budget"):
        diags.append(Diagnostic(codes.BUDGET_EXCEEDED, f"run cut short: {message}", machine.app.path, 0, 0, time_us=machine.end_time,
                                task="", program=""))
    tasks = []
    for t in machine.scheduler.history:
        final = t.final
        where = (final.where if final is not None else None) or t.errpos
        stopped_on_error = t.state.value == "error" or (final is not None and final.state == "error")
        tasks.append(TaskSummary(
            name=t.name,
            program=t.program,
            library=t.unit.name if t.unit is not machine.main else None,
            priority=t.prio if not t.period else None,
            period=t.period / 1e6 if t.period else None,
            created=t.created,
            ended=t.ended,
            end=t.end_state or "alive",
            state_at_end_of_run=final.state if final is not None else t.end_state or "ended",
            error=t.error if stopped_on_error else None,
            error_text=t.errdetail or None,
            blocked_on=final.blocked_on if final is not None else None,
            position=where,
            lines=t.lines,
        ))
    motion = arm_run(machine, diags)
    diags.sort(key=lambda d: d.time_us if d.time_us is not None else 0)  # stable: by time, then as recorded
    page = machine.user_page.default
    screen = {"title": page.title, "lines": page.text()}
    arm = machine.arm
    robot = {"name": arm.name, "initial_joints": list(arm.initial_joints)} if arm.has_model else None
    return SimResult(machine.app.name, machine.app.path, reason, message, machine.end_time,
                     machine.scheduler.total_lines, tasks, diags, machine.recorder.transcript, machine.recorder.io_log,
                     screen, list(machine.destroyed), {k: sorted(v) for k, v in machine.link_names.items()},
                     robot=robot, globals=dict(machine.main.globals) if machine.main is not None else {},
                     motion=motion, tool_events=list(machine.recorder.tool_events),
                     task_states=list(machine.recorder.finish_task_states()))


def arm_run(machine: Machine, diags: list[Diagnostic]) -> ArmRun | None:
    """The arm's findings as diagnostics (added to `diags`), and the record of what it did: None
    when the run has no moving arm or never used it."""
    arm = machine.arm
    q = arm.queue_in_use if isinstance(arm, MovingArm) else None
    if q is None:
        return None
    end_s = machine.end_time / 1_000_000
    q.advance(arm.queue_time(machine.end_time))
    for f in q.findings:
        src = f.source
        diags.append(Diagnostic(f.code, f.message, src.path, src.line, src.col, time_us=int(round(f.time * 1e6)),
                                task=src.task, program=src.program, error=f.error))
    layers = getattr(arm, "layers", None)
    # the records taken as the run went (live_record.py), and those of the commands left
    queue_records = records = arm.live.records(arm, q, arm.queue_time(machine.end_time))
    trajectory = q.trajectory
    if layers is not None and not layers.trivial:  # chapter 11 moved the arm off the queue's trajectory
        trajectory = ActualTrajectory(trajectory, layers)
        records = [actual_record(rec, arm) for rec in records]
    same: dict = {}  # the limits and tool poses of the run's entries, one object each (a long run repeats them)
    motions = [_entry(rec, asked, layers, same) for rec, asked in zip(records, arm.live.kept)]
    # each task's cycle loop and the first command of each of its passes (by index): the same for the
    # run's records and for the acceleration range's re-timed ones
    passes = task_cycles(machine, [_Indexed(r.id, r.source, i) for i, r in enumerate(records)])
    starts = [r.start for r in records]
    cycles = {task: _moved_entry(st, starts) for task, st in passes.items()}
    if trajectory is q.trajectory:
        busy, idle = busy_time(q.trajectory.profile, end_s)
    else:
        busy = sum(b - a for a, b in trajectory.moving(end_s))
        idle = max(end_s - busy, 0.0)
    scene = arm_scene(arm.model, arm.initial_joints, machine.main.globals if machine.main is not None else {},
                      geometries=getattr(arm, "geometries", ()), base=getattr(arm, "base_model", None))
    poses: dict = {}  # one read-only matrix per distinct tool pose (a cyclic cell repeats a few)
    tools = [ToolUse(*e, tcp_matrix=_shared_matrix(e.tcp_in_flange, poses)) for e in machine.recorder.tool_events]
    spread = None
    if getattr(arm.model, "accelerations_assumed", False):  # issue 23: the range if they are off
        spread = acceleration_range(machine, q, queue_records, diags, passes)
    return ArmRun(scene, motions, cycles, trajectory, tools, busy, idle, end_s, spread)


def acceleration_range(machine: Machine, q, queue_records, diags: list[Diagnostic],
                       passes: dict | None = None) -> AccelerationRange:
    """The cycles of the run re-timed with the accelerations × each factor of the assumed range
    (issue 23), within the run's wall-clock budget (budget.py): when it is spent the re-timing stops
    there, the range covers the run up to that time (`AccelerationRange.partial`) and an R006 says so.
    `passes`: `task_cycles` of the records as `_Indexed` (found here when not given)."""
    out_of_time = RunBudget.of(machine).out_of_time
    # each task's cycle loop, and the command that starts each of its passes, are the same for every
    # factor (the same commands recorded in the same loops; only their times move): found once, by
    # index, and each factor times only those commands' starts (not every record's start and end)
    if passes is None:
        passes = task_cycles(machine, [_Indexed(r.id, r.source, i) for i, r in enumerate(queue_records)])
    firsts = sorted({i for st in passes.values() for i in st.starts})
    cycles, cut = [], None
    for at, rt in each_retimed_times(q, [queue_records[i].start for i in firsts], ASSUMED_ACCELERATION_RANGE,
                                     out_of_time):  # one factor at a time
        start = dict(zip(firsts, at))  # (by index, as the records are)
        cycles.append({task: _moved_entry(st, start) for task, st in passes.items()})
        if rt.cut is not None:
            cut = rt.cut if cut is None else min(cut, rt.cut)
    partial = None
    if cut is not None:
        partial = (f"the cycle time's range if the assumed accelerations are off covers the run up to {cut:.3f} s "
                   f"only: {WALL} (--max-wall {machine.budgets.wall_s:g} s) was spent while re-timing it")
        diags.append(Diagnostic(codes.BUDGET_EXCEEDED, partial, machine.app.path, 0, 0, time_us=machine.end_time, task="",
                                program=""))
    return AccelerationRange(ASSUMED_ACCELERATION_RANGE, tuple(cycles), partial)


def actual_record(rec, arm):
    """A motion record (queue times) in real time: when the arm got there (arm_layers.Warp)."""
    from dataclasses import replace

    layers = arm.layers
    start = rec.start if rec.start is None else layers.warp.leaving_time(rec.start)
    end = arm.real_time(rec.end)
    return replace(rec, start=start, end=end if end is not None or rec.end is None else None)


class _Indexed:
    """What cycle_stats reads of a motion record, its start being its index: each task's cycle loop
    and the first command of its passes found once, for the run's records and for every factor of
    the acceleration range (`arm_run`)."""

    __slots__ = ("id", "source", "start")

    def __init__(self, id_: Any, source: Any, index: int) -> None:
        self.id, self.source, self.start = id_, source, index


def _moved_entry(st, start) -> CycleEntry:
    """The cycle of a task as the reports give it, the CycleEntry of cycle_stats on records (the
    run's, or re-timed), from the CycleStats of the same records as `_Indexed` (the indices of each
    pass's first command) and those commands' starts by index (`start[i]`: a list or a dict),
    None: never started, and neither is any pass after it."""
    starts = []
    for i in st.starts:
        t = start[i]
        if t is None:
            break
        starts.append(t)
    return CycleEntry(st.task, st.marker, tuple(starts), st.loop and st.loop.program, st.loop and st.loop.kind, st.why,
                      st.passes)


def task_cycles(machine: Machine, records) -> dict:
    """Each task's cycle (motion/cycle.py) from the run's motion records (or the same re-timed):
    the loops each command was recorded in and the loops each task was in when the run ended."""
    arm = machine.arm
    contexts = arm.live.contexts  # (complete once the run's records are made: `arm_run`)
    inside = {t.name: arm.context(t.final.loops) for t in machine.scheduler.history
              if t.final is not None and t.final.loops}
    return cycle_stats(records, contexts, inside)


def _entry(rec, asked: tuple, layers=None, same: dict | None = None) -> MotionEntry:
    """A row of the motion table: the motion record (motion/motion_records.py) and what its command
    (motion/queued.py) asked (`asked`: its request, start and end joints, state: live_record.py);
    its joints with the turns resetTurn took off (`layers`). `same`: the limits and tool poses
    already made, reused when equal."""
    req, q_start, q_end, state = asked
    connection = req.kind == "connection"
    limits = None if connection else _limits(req.mdesc, same)
    trsf = None
    if not connection and req.tool is not None:
        import numpy as np

        key = ("trsf", np.asarray(req.tool, dtype=float).tobytes())  # (by the bytes: -0.0 is not 0.0 in a report)
        trsf = same.get(key) if same is not None else None
        if trsf is None:
            trsf = _trsf(req.tool)
            if same is not None:
                same[key] = trsf
    return MotionEntry(
        rec.id, rec.kind, rec.source, rec.state, rec.recorded, rec.start, rec.end, rec.length_mm, rec.peak_tcp_mm_s,
        rec.dominant, rec.limit_share, rec.target, req.frame_name, rec.tool,
        tool_in_flange=None if connection else req.tool,
        tool_trsf=trsf,
        joints_start=_turned(q_start, rec.start, layers),
        joints_end=_turned(q_end, rec.end, layers) if state != "failed" else None,
        limits=limits)


def _limits(md, same: dict | None) -> MotionLimits:
    """The MotionLimits of the mdesc `md` (motion/mdesc.MDesc, frozen); `same`: one object per
    distinct value (by its repr: -0.0 is not 0.0), kept by the mdesc object too (a cyclic program
    passes the same few again and again; held with it, so that its id is not another's)."""
    kept = same is not None and md.__class__ is MDesc  # (frozen: its limits never change)
    held = same.get(("mdesc", id(md))) if kept else None
    if held is not None and held[0] is md:
        return held[1]
    limits = MotionLimits(md.vel, md.accel, md.decel, md.tvel_limit, md.rvel_limit)
    if same is not None:
        limits = same.setdefault(("limits", repr(limits)), limits)
        if kept:
            same[("mdesc", id(md))] = (md, limits)
    return limits


def _turned(joints, t, layers):
    """Joints of the queue as the arm had them at t (the turns of resetTurn, 11.5)."""
    if layers is None or not layers.turns.times or t is None:
        return joints
    return joints + layers.turns.at(t)


def _trsf(m) -> tuple[float, ...]:
    """A 4x4 matrix (mm) as a VAL 3 trsf: x, y, z (mm), rx, ry, rz (degrees, 9.3.2)."""
    r = tuple(float(m[i][j]) for i in range(3) for j in range(3))
    rx, ry, rz = angles_of(r)
    return (float(m[0][3]), float(m[1][3]), float(m[2][3]), rx, ry, rz)


def _shared_matrix(trsf, poses: dict) -> Any:
    """`_matrix(trsf)`, read-only, made once per pose in `poses` (keyed by its bits: -0.0 is not 0.0)."""
    import numpy as np

    key = np.asarray(trsf, dtype=float).tobytes()
    m = poses.get(key)
    if m is None:
        m = poses[key] = _matrix(trsf)
        m.flags.writeable = False
    return m


def _matrix(trsf) -> Any:
    """A VAL 3 trsf (x, y, z mm, rx, ry, rz degrees, 9.3.2) as a 4x4 matrix (mm)."""
    import numpy as np

    x, y, z, rx, ry, rz = (float(v) for v in trsf)
    T = np.eye(4)
    T[:3, :3] = np.reshape(matrix(rx, ry, rz), (3, 3))
    T[:3, 3] = (x, y, z)
    return T


def arm_scene(model: Any, initial_joints, globals_: dict, geometries=(), base: Any = None) -> ArmScene:
    """The scene of a run on `model` (robot.RobotModel): the arm, and the frame and tool variables
    of the application (`globals_`: name -> Arr of run-time values) as the run left them.
    `geometries`: (from time s, model) of each setDH of the run (11.4), `base` the geometry before."""
    axes = len(model.joint_limits)
    return ArmScene(model.name, axes, tuple(model.joint_names),
                    tuple(getattr(model, "joint_units", None) or ["deg"] * axes), tuple(model.joint_limits),
                    tuple(model.nominal_speeds), tuple(model.accelerations), tuple(initial_joints),
                    model.world_frame, model.flange_frame, app_frames(globals_),
                    ModelKinematics(model, [(-math.inf, base or model), *geometries] if geometries else ()))


def app_frames(globals_: dict) -> dict[str, FramePose]:
    """The application's frame and tool variables, by name (and `name[i]` for each element):
    their pose in the world frame (frames) or the flange (tools), 4x4 mm. A frame whose pose is
    undefined (error 163...) is left out."""
    import numpy as np

    out: dict[str, FramePose] = {}
    for name, arr in sorted(globals_.items()):
        kind = getattr(arr, "t", None)
        if kind not in ("frame", "tool"):
            continue
        data = getattr(arr, "data", [])
        for i, node in enumerate(data):
            if not isinstance(node, Frame):
                continue
            try:
                R, v, _ = root_pose(node)
            except Exception:  # noqa: BLE001 - an undefined frame (error 163) is simply not drawn
                continue
            M = np.eye(4)
            M[:3, :3] = np.reshape(R, (3, 3))  # row-major (geometry/rotation.py)
            M[:3, 3] = v
            pose = FramePose(kind, len(data), M)
            out[f"{name}[{i}]"] = pose
            if i == 0:
                out[name] = pose
    return out


class ModelKinematics:
    """The arm's links and their forward kinematics over a robot.RobotModel (the ArmKinematics port
    of arm_record.py): its URDF is read once, when first asked."""

    def __init__(self, model: Any, epochs=()) -> None:
        """Nothing is read yet. `epochs`: [(from time s, model)] when setDH (11.4) changed the
        geometry during the run, the first from -inf (the poses at a time are those of the geometry
        in force then; `model`, the last, is what the chain and the URDF describe)."""
        self.model = model
        self._links: Any = None
        self._epochs = [(t, ModelKinematics(m)) for t, m in epochs]

    def _arm_links(self):
        """robot.links.ArmLinks of the model, read once."""
        if self._links is None:
            from ..robot.links import arm_links

            self._links = arm_links(self.model)
        return self._links

    def chain(self) -> dict:
        """The kinematic chain and solids of the 3D view (robot.chain.arm_chain), with the URDF named
        as the repository holds it (`robots/tx2-60.urdf`) or by its file name."""
        from ..robot.chain import arm_chain

        m = self.model
        return arm_chain(m.source, world_frame=m.world_frame, flange_frame=m.flange_frame, joint_names=m.joint_names,
                         name=m.name, source=f"robots/{Path(m.source).name}" if "/robots/" in m.source
                         else Path(m.source).name)

    def urdf(self) -> tuple[str, str]:
        """(file name, text) of the arm's URDF."""
        return Path(self.model.source).name, Path(self.model.source).read_text(encoding="utf-8")

    def link_edges(self) -> list[tuple[str, str, bool]]:
        """(parent, child, the joint between them moves) for every link below the root, parents
        first."""
        links = self._arm_links()
        return [(links.edges[c].parent, c, links.edges[c].kind != "fixed" and links.edges[c].index >= 0)
                for c in links.links[1:]]

    def link_poses(self, joints, t: float | None = None) -> dict:
        """{link: 4x4 pose in world (mm)} at one joint position (reached at time `t`)."""
        if self._epochs and t is not None:
            return self._at([t])[0][1].link_poses(joints)
        return self._arm_links().poses(joints)

    def link_poses_many(self, joints, links=None, times=None) -> dict:
        """{link: (N, 4, 4) poses in world (mm)} at N joint positions (`links`: only those), reached
        at `times` (N,)."""
        if not self._epochs or times is None:
            return self._arm_links().poses_many(joints, links)
        import numpy as np

        joints = np.asarray(joints, dtype=float)
        out: dict = {}
        for rows, kin in self._at(times):
            got = kin.link_poses_many(joints[rows], links)
            for name, M in got.items():
                out.setdefault(name, np.empty((len(joints), 4, 4)))[rows] = M
        return out

    def geometry_at(self, t: float) -> int:
        """The number of the geometry in force at `t` (0 before any setDH)."""
        return int(self._numbers([t])[0]) if self._epochs else 0

    def _numbers(self, times):
        """The number of the geometry in force at each of `times` (a setDH at t: from t on)."""
        import numpy as np

        starts = np.array([t for t, _ in self._epochs[1:]])
        return np.searchsorted(starts - 1e-9, np.asarray(times, dtype=float), side="right")

    def _at(self, times) -> list:
        """[(rows, the ModelKinematics in force)] of the samples at `times` (the first geometry
        alone when every sample is in it)."""
        import numpy as np

        k = self._numbers(times)
        return [(np.flatnonzero(k == j), self._epochs[j][1]) for j in np.unique(k).tolist()]
