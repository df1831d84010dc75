"""A command in the motion queue (10.2.1): what the instruction asked, its joint-space geometry,
where it lies on the arm's path, and how far the arm has gone with it.

Everywhere in motion/ a `QueuedCommand` is called `command` (the one before it `previous`), and
the `commands.MoveCommand` a motion instruction hands to the queue is called `move`.

    command.request     what the instruction asked (kind, source, mdesc, tool...), never changed
    command.geometry    its joint-space curve from q_start to q_end and its TCP curve (construction.py)
    command.placement   where it lies on the arm's path: its blend, leave and reach points, path
                        positions (planner.py builds it)
    command.state       pending, done, failed (the arm cannot execute it), cancelled (resetMotion)

Path positions are the global path parameter s of `paths.Path` (degrees of joint motion).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..light_dataclass import dataclass, field
from .findings import Source
from .mdesc import MDesc


@dataclass(frozen=True, slots=True)  # (kept for every command of the run: no __dict__ each)
class Request:
    """What a motion instruction recorded (10.2.1): its kind (movej, movel, movec, or
    "connection" for the move to resetMotion's jStart, 10.1.3), where it is written, when it was
    recorded (s), its mdesc (mm), the tool's TCP in the flange (4x4 mm, None: the flange) and the
    names the reports show. `reduced`: the connection move's reduced speed."""

    kind: str
    source: Source
    recorded: float
    mdesc: MDesc
    tool: np.ndarray | None = None
    tool_name: str = ""
    target_name: str = ""
    frame_name: str = ""  # the reference frame of a point target
    reduced: bool = False


@dataclass(slots=True)
class Geometry:
    """The command's motion in joint space: from `q_start` to `q_end` (degrees; a SCARA's axis 3
    in mm) along `joint_curve` (paths.JointLine for movej, paths.JointSpline for movel and movec;
    None when the arm does not move), and the TCP curve of movel/movec (cartesian.Line, Arc)."""

    q_start: np.ndarray
    q_end: np.ndarray
    joint_curve: object = None
    tcp_curve: object = None


class Nominal(NamedTuple):
    """The command's own part of the path, for getMoveId's progress: path position where that part
    starts, where it ends (its leave point or target), and the command's λ there."""

    s_start: float
    s_end: float
    lam_end: float


@dataclass(slots=True)
class Placement:
    """Where the command lies on the arm's path. `blend`: off, joint or Cartesian (off once the
    command is closed: it goes to its target and stops); `lam_in`: λ of its reach point (where the
    blend from the previous command joins it), `lam_leave`: λ of its leave point. `s_begin`,
    `s_end`: path positions where it begins and ends (`s_end` None while it waits, blended, for
    the next command; `s_provisional` is then where its target is); `spans`: the paths.Span it
    (partly) owns."""

    blend: str = "off"
    lam_in: float = 0.0
    lam_leave: float = 1.0
    s_begin: float | None = None
    s_end: float | None = None
    s_provisional: float | None = None
    nominal: Nominal | None = None
    spans: list = field(default_factory=list)


@dataclass(eq=False, slots=True)
class QueuedCommand:
    """A command in the queue (see the module docstring). `key` is unique over the run (the
    identifier `id` is the program's, 10.6: it repeats after resetMotion, None for a connection
    move). `t_done`: when the commanded position reached its end. `checked`: its pass near a
    singularity was looked at (R014, once); `rest_time`: its time alone from rest to rest (the
    blend decision, planner.py), once computed.

    `cls` (issue 29, a hook for the record and the collision checks): a number equal for two
    commands of one process only when their kind, joint and TCP curves (the same objects, so the
    same start, end and path: construction.py reuses them), tool values, mdesc values and reduced
    speed are equal: the same command from the same start. It says nothing of its neighbours'
    blends or of when the arm runs it (MotionQueue assigns it; numbers are never given twice)."""

    key: int
    id: int | None
    request: Request
    geometry: Geometry
    placement: Placement = field(default_factory=Placement)
    state: str = "pending"
    t_done: float | None = None
    checked: bool = False
    rest_time: float | None = None
    cls: int | None = None

    @property
    def kind(self) -> str:
        """movej, movel, movec or connection."""
        return self.request.kind

    @property
    def tool(self) -> np.ndarray | None:
        """The TCP in the flange (4x4 mm), None for the flange."""
        return self.request.tool
