"""A motion command as a motion instruction records it (10.2.1): kind, targets, tool, mdesc.

The caller (the chapter-10 instruction handlers) resolves the VAL 3 values before recording:
a point becomes the pose of its tool centre point in world (4x4, mm) with its requested
configuration; a tool becomes its pose in the flange (4x4, mm); an mdesc becomes an `MDesc` in
mm. Frames and tools are read when the instruction executes, as on the controller.
"""

from __future__ import annotations

import numpy as np

from ..light_dataclass import dataclass
from .findings import Source
from .mdesc import MDesc

KINDS = ("movej", "movel", "movec")


@dataclass(frozen=True)
class Target:
    """A joint position (degrees) or a TCP pose in world (4x4, mm) with the point's requested
    configuration (VAL 3 names: "righty", "ssame", "efree"...; 9.7.2)."""

    joints: tuple[float, ...] | None = None
    pose: np.ndarray | None = None
    config: tuple[str, ...] = ("ssame", "esame", "wsame")
    name: str = ""
    frame: str = ""  # the name of the point's reference frame (reports)
    note: str = ""  # what a failure to reach it adds (a configuration of the other arm family)

    @classmethod
    def joint(cls, joints, name: str = "") -> Target:
        """A joint target (degrees; a SCARA's axis 3 in mm)."""
        return cls(joints=tuple(float(v) for v in joints), name=name)

    @classmethod
    def point(cls, pose, config=("ssame", "esame", "wsame"), name: str = "", frame: str = "",
              note: str = "") -> Target:
        """A point target: the TCP pose in world (4x4 or 3x4, mm), its configuration, names and a
        note for the reports."""
        p = np.asarray(pose, dtype=float)
        if p.shape == (3, 4):
            p = np.vstack([p, [0.0, 0.0, 0.0, 1.0]])
        return cls(pose=p, config=tuple(config), name=name, frame=frame, note=note)

    @property
    def is_joint(self) -> bool:
        """A joint target (else a point)."""
        return self.joints is not None


@dataclass(frozen=True)
class MoveCommand:
    """What movej/movel/movec record: `via` is movec's intermediate point; `tool` the TCP in
    the flange (4x4, mm, None for the flange itself)."""

    kind: str
    target: Target
    mdesc: MDesc
    tool: np.ndarray | None = None
    via: Target | None = None
    source: Source = Source()  # noqa: RUF009 - frozen: one shared empty position is safe
    tool_name: str = ""

    def __post_init__(self) -> None:
        """ValueError for a kind or targets the instruction cannot have."""
        if self.kind not in KINDS:
            raise ValueError(f"unknown motion kind {self.kind!r}")
        if self.kind == "movec" and (self.via is None or self.via.is_joint or self.target.is_joint):
            raise ValueError("movec needs an intermediate point and a target point")
        if self.kind == "movel" and self.target.is_joint:
            raise ValueError("movel needs a point")
