"""What the arm did in a run, as the run publishes it: the one record the reports read
(docs/sim-report.md, "For developers"). Built once at the end of the run (collect.py).

    m = result.motion                  # ArmRun | None (no arm model, or the arm never used)
    m.scene                            # ArmScene: the arm and the application's frames, once
    m.motions[i]                       # MotionEntry: one per command recorded, in recording order
    m.cycles[task]                     # CycleEntry: the cycle of a task that moves the arm (its loop)
    main_cycle(m.cycles)               # the one the verdict quotes (most complete cycles)
    m.trajectory                       # JointTrajectory: the joints at any simulated time
    m.tcp_speed(times, joints, speeds) # the TCP's speed at samples of the trajectory
    m.cell_timeline                    # CellTimeline | None: the cell as the collision checks placed it

Times are simulated seconds, joints degrees (a SCARA's axis 3 millimetres), lengths
millimetres, poses 4x4 matrices in millimetres. Everything is plain data but the two ports,
`JointTrajectory` and `ArmKinematics` (the arm's forward kinematics and its URDF, read once when
first asked): a report reads this record and imports nothing of robot/, geometry/ or motion/.
"""

from __future__ import annotations

import statistics
from typing import Any, Protocol

import numpy as np

from ..light_dataclass import dataclass, field

TCP_STEP_S = 1e-4  # the TCP speed: the TCP moved along the joint velocity over this step
BLOCK = 4096  # samples whose link poses are computed at once (memory bounded on long runs)


class JointTrajectory(Protocol):
    """The arm's commanded joint trajectory (motion/trajectory.py implements it)."""

    def position(self, t: float) -> np.ndarray: ...  # joints at time t
    def velocity(self, t: float) -> np.ndarray: ...  # joint speeds at time t
    def positions(self, times) -> np.ndarray: ...  # joints at many times (N, axes)
    def sample(self, t0: float, t1: float, dt: float = 0.004): ...  # (times, joints, speeds) every dt
    def segments(self, t_end: float, dt: float = 0.004): ...  # [(first tick, joints, speeds)] where it moves
    def moving(self, t_end: float) -> list[tuple[float, float]]: ...  # the intervals of motion


class ArmKinematics(Protocol):
    """The arm's links and their forward kinematics (collect.ModelKinematics implements it)."""

    def chain(self) -> dict: ...  # the kinematic chain as plain data (robot/chain.py): the 3D view's
    def urdf(self) -> tuple[str, str]: ...  # (file name, text) of the arm's URDF
    def link_edges(self) -> list[tuple[str, str, bool]]: ...  # (parent, child, moves) below the root
    # {link: 4x4 in world} at one position (reached at `t`: the geometry then, setDH 11.4)
    def link_poses(self, joints, t: float | None = None) -> dict[str, np.ndarray]: ...
    # {link: (N, 4, 4)} at N positions (reached at `times`)
    def link_poses_many(self, joints, links=None, times=None) -> dict[str, np.ndarray]: ...
    def geometry_at(self, t: float) -> int: ...  # the number of the geometry in force at `t` (setDH)


@dataclass(frozen=True)
class FramePose:
    """A frame or tool variable of the application at the end of the run: `kind` "frame" (its pose
    in world) or "tool" (its TCP in the flange), the number of elements of its array, the pose."""

    kind: str
    array_size: int
    matrix: np.ndarray


@dataclass(frozen=True)
class ArmScene:
    """The arm of the run and the application's frames, once (what does not change over the run).
    `frames`: by name, and `name[i]` for each element of an array (the first also by name)."""

    name: str
    axes: int
    joint_names: tuple[str, ...]
    joint_units: tuple[str, ...]
    joint_limits: tuple
    nominal_speeds: tuple
    accelerations: tuple
    initial_joints: tuple[float, ...]
    world_frame: str
    flange_frame: str
    frames: dict[str, FramePose]
    kinematics: ArmKinematics


@dataclass(frozen=True)
class MotionLimits:
    """What a motion instruction's mdesc asked (10.5.1): vel, accel, decel in %, tvel (mm/s) and
    rvel (deg/s) or None at their default (no Cartesian limit)."""

    vel: float
    accel: float
    decel: float
    tvel: float | None
    rvel: float | None


@dataclass(slots=True)  # one per command of the run
class MotionEntry:
    """One command recorded (connection moves included). `id`: the identifier the instruction
    returned (10.6; None for a connection move); `source`: where the instruction is written (path,
    line, col, program, task); `state`: done, failed, cancelled, pending; `recorded`, `start`,
    `end` (None when it never ran); `length_mm`, `peak_tcp_mm_s` of the TCP over its part of the
    path; `dominant_limit` and `limit_seconds` (the seconds under each limit); the names of its
    target, the target's frame and its tool; `tool_in_flange` (4x4 mm, None for the flange and
    connection moves) and the same as a VAL 3 trsf `tool_trsf` (x, y, z mm, rx, ry, rz degrees,
    9.3.2); the joints it goes from and to (`joints_end` None when it failed); `limits`
    (None for a connection move, at reduced speed, 10.1.3); `clearance`: the collision checks'
    report of this motion (a collision.results.MotionReport), None when they did not check it."""

    id: int | float | None
    kind: str
    source: Any
    state: str
    recorded: float
    start: float | None
    end: float | None
    length_mm: float
    peak_tcp_mm_s: float
    dominant_limit: str
    limit_seconds: dict
    target: str
    frame: str
    tool: str
    tool_in_flange: np.ndarray | None
    tool_trsf: tuple[float, ...] | None
    joints_start: np.ndarray
    joints_end: np.ndarray | None
    limits: MotionLimits | None
    clearance: Any = None

    @property
    def duration(self) -> float | None:
        """end - start, None when it never ran."""
        return None if self.start is None or self.end is None else self.end - self.start


@dataclass(frozen=True)
class ToolUse:
    """An open() or close() of a tool (9.5.4; interpretation.recorder.ToolEvent): when, the task,
    "open" or "close", the tool's name, its gripper's link, its centre point in the flange as a
    VAL 3 trsf (x, y, z mm, rx, ry, rz degrees) and as a 4x4 matrix (mm), and the instruction's
    (path, line, col, program)."""

    time_us: int
    task: str
    action: str
    tool: str
    gripper: str
    tcp_in_flange: tuple
    position: tuple
    tcp_matrix: np.ndarray


@dataclass(frozen=True)
class PoseChange:
    """A frame or tool variable the cell file names took a new value at `time` (s): its pose, 4x4
    mm (a frame in world, a tool in the flange), or None while the program has none."""

    time: float
    matrix: np.ndarray | None


@dataclass(frozen=True)
class PartSpan:
    """A part of the cell file (docs/cell.md) over [start, end) (end None: to the end of the run):
    `carried` on the flange from its tool's grasp instruction, or left in the cell until taken
    again or away (`cleared_by`). `pose` (4x4 mm): the part's frame, its tool's frame when it was
    taken (its solids are at their `at` in it), in the flange while carried, else in world."""

    name: str
    tool: str
    carried: bool
    start: float
    end: float | None
    pose: np.ndarray


@dataclass(frozen=True)
class CellTimeline:
    """The cell as the collision checks placed it over the run, as changes (a long run grows it by
    what changes, not by its length): `frames` {name as the cell writes it, spaces left out:
    (PoseChange, ...)} of the frames obstacles hang on, `tools` the same for the tool variables
    tool solids hang on, each value from the time the checks read it (a motion's start, an
    open()/close(); the first one holds from the start of the run); `parts` (PartSpan, ...) by
    start."""

    frames: dict[str, tuple[PoseChange, ...]]
    tools: dict[str, tuple[PoseChange, ...]]
    parts: tuple[PartSpan, ...]


@dataclass(frozen=True)
class CycleEntry:
    """The cycle of a task that records motions (docs/motion.md, "Cycle time"): the loop that
    moves the arm once per part. `marker` (path, line, col), `program` and `kind` (while, do,
    for) of that loop statement, all None without a cycle; `why` it is the cycle (or why there is
    none); `passes` of it that recorded motions; `starts`: when the arm started each pass (its
    first command)."""

    task: str
    marker: tuple[str, int, int] | None
    starts: tuple[float, ...] = ()
    program: str | None = None
    kind: str | None = None
    why: str = ""
    passes: int = 0

    @property
    def times(self) -> list[float]:
        """The cycle times: between successive starts."""
        return [b - a for a, b in zip(self.starts, self.starts[1:])]

    @property
    def count(self) -> int:
        """Complete cycles."""
        return max(len(self.starts) - 1, 0)


@dataclass(frozen=True)
class AccelerationRange:
    """The cycles of the run re-timed with every acceleration and deceleration times each factor
    (docs/motion.md, "Accelerations"): given when the model's accelerations are assumed, so that
    the reports state the cycle time with the range it takes if they are off (issue 23)."""

    factors: tuple[float, ...]  # robot.models.ASSUMED_ACCELERATION_RANGE: (0.5, 2.0)
    cycles: tuple[dict[str, CycleEntry], ...]  # per factor, the re-timed run's cycles by task
    partial: str | None = None  # why the re-timing stopped before the end of the run (its budget)

    @property
    def off_by(self) -> float:
        """How far the accelerations are taken to be off (2 for ½ and 2)."""
        return max(max(self.factors), 1.0 / min(self.factors))

    def cycle_time(self, task: str) -> tuple[float, float] | None:
        """(lowest, highest) median cycle time of `task` over the factors; None when a re-timed
        run has no complete cycle of it."""
        medians = []
        for by_task in self.cycles:
            st = by_task.get(task)
            if st is None or not st.times:
                return None
            medians.append(statistics.median(st.times))
        return min(medians), max(medians)


def main_cycle(cycles: dict[str, CycleEntry]) -> CycleEntry | None:
    """The cycle a run's verdict quotes: the task's with the most complete cycles (ties: the first
    task by name); None when no task completed one."""
    best = None
    for task in sorted(cycles):
        entry = cycles[task]
        if entry.count and (best is None or entry.count > best.count):
            best = entry
    return best


@dataclass
class ArmRun:
    """What the arm did in a run (see the module docstring): `busy_s`, `idle_s` its moving and
    standing time, `end_s` the end of the run; `tool_events` every open()/close() (ToolUse);
    `acceleration_range` the cycles if the assumed accelerations are off (None when they were
    measured: a robot file's values); `cell_timeline` the cell as the collision checks placed it
    (None: not checked)."""

    scene: ArmScene
    motions: list[MotionEntry]
    cycles: dict[str, CycleEntry]
    trajectory: JointTrajectory
    tool_events: list[ToolUse] = field(default_factory=list)
    busy_s: float = 0.0
    idle_s: float = 0.0
    end_s: float = 0.0
    acceleration_range: AccelerationRange | None = None
    cell_timeline: CellTimeline | None = None

    def sample(self, t0: float = 0.0, t1: float | None = None, dt: float = 0.004):
        """(times (N,), joint positions (N, axes), joint velocities (N, axes)) every `dt` s."""
        return self.trajectory.sample(t0, self.end_s if t1 is None else t1, dt)

    def tcp_speed(self, times, positions, velocities) -> np.ndarray:
        """The TCP's Cartesian speed (mm/s) at samples of the trajectory (times (N,), joints and
        joint velocities (N, axes)), for the tool of the motion under way (`tcp_speed` below)."""
        uses = [(motion.start, motion.tool_in_flange) for motion in self.motions
                if motion.start is not None and motion.kind != "connection"]
        return tcp_speed(self.scene.kinematics, self.scene.flange_frame, uses, times, positions, velocities)


def tcp_speed(kinematics: ArmKinematics, flange: str, tool_uses, times, positions, velocities) -> np.ndarray:
    """The TCP's Cartesian speed (mm/s) at samples of a trajectory (times (N,), joints and joint
    velocities (N, axes)), for the tool of the motion under way: `tool_uses` (start, tool in the
    flange 4x4 or None) of each motion in order of start, connection moves aside; before any, the
    first motion's tool. The TCP moved along the joint velocity over a small step (no spike when
    the tool changes)."""
    h = TCP_STEP_S
    positions, velocities = np.asarray(positions, dtype=float), np.asarray(velocities, dtype=float)
    ahead = positions + h * velocities
    starts = [t for t, _ in tool_uses]
    tools = [tool for _, tool in tool_uses]
    # each motion's tool as the number of its value: a run of motions with one tool, one product
    numbers: dict = {}
    same = np.array([numbers.setdefault(None if t is None else np.asarray(t, dtype=float).tobytes(), k)
                     for k, t in enumerate(tools)], dtype=int)
    times = np.asarray(times, dtype=float)
    idx = np.maximum(np.searchsorted(np.asarray(starts, dtype=float), times, side="right") - 1, 0) if starts \
        else np.zeros(len(times), int)
    out = np.zeros(len(times))
    # a sample at rest has the same pose twice (speed 0, as the product would give): the moving
    # ones only, a block at a time, the flange alone, both poses in one evaluation
    moving = np.flatnonzero(~np.all(ahead == positions, axis=1)) if len(times) else np.zeros(0, int)
    for b in range(0, len(moving), BLOCK):
        rows = moving[b:b + BLOCK]
        P = kinematics.link_poses_many(np.concatenate([positions[rows], ahead[rows]]), (flange,),
                                       times=np.concatenate([times[rows], times[rows]]))[flange]
        P0, P1 = P[:len(rows)], P[len(rows):]
        # each run of samples under one tool: one product
        at = same[idx[rows]] if len(same) else idx[rows]
        cuts = np.flatnonzero(np.diff(at)) + 1
        for lo, hi in zip([0, *cuts.tolist()], [*cuts.tolist(), len(rows)]):
            tool = tools[int(at[lo])] if tools else None
            p = np.array([0.0, 0.0, 0.0, 1.0]) if tool is None else np.asarray(tool, dtype=float)[:, 3]
            out[rows[lo:hi]] = np.linalg.norm((P1[lo:hi] @ p - P0[lo:hi] @ p)[:, :3], axis=1) / h
    return out
