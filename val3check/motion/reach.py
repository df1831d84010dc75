"""The static reach check: every point and joint of the data files against the arm, no run.

`val3check reach APP --robot NAME` reads the application's data files (and those of the
libraries it declares), resolves each point through its reference frames (`fatherId`, 9.4) and
each tool through its base tools (9.5), and checks, for every tool the application declares
(the flange when it declares none):

* a point: is there a joint position within the software limits that puts the tool centre
  point there, in the point's configuration (9.7.2; `same` fields are free here: there is no
  start position)? Reported when none (out of reach, outside the joint limits — which axis, by
  how much — or not in the requested configuration), or when every such position is near a
  singularity or within `LIMIT_MARGIN` of a joint limit (with the margins).
* a joint position: within the limits? near a limit or a singularity?

Points and tools that cannot be resolved (no reference, a loop, a reference that names nothing)
are listed as such. The result is a `ReachReport` (val3check/reporting/reach.py renders it).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..geometry import frames as GF
from ..geometry import points as GP
from ..geometry import rotation as R
from ..geometry.frames import Frame, Tool
from ..geometry.points import Point
from ..geometry.trsf import Trsf
from ..lengths import INCH_MM
from ..loading.attribute_text import parse_father
from ..loading.types import arm_family, base_type
from .checks import LIMIT_MARGIN, THRESHOLDS, UNITS, WHAT
from .kin import ArmKin

ORDER = {"family": 0, "unreachable": 1, "limits": 2, "config": 3, "unresolved": 4, "near-singularity": 5,
         "near-limit": 6, "ok": 7}
# A point may be used with only some of the declared tools, or not at all: a static "unreachable"
# is not certain to be a defect, so nothing here is an error (`sim` reports what a run does).
SEVERITY = {"family": "warning", "unreachable": "warning", "limits": "warning", "config": "warning",
            "unresolved": "warning", "near-singularity": "info", "near-limit": "info", "ok": "info"}


@dataclass
class ReachEntry:
    """One point or joint of the data files checked with one tool: its status (ORDER), message and position."""
    name: str  # "pPick[0]", "lib:pHome[0]"
    kind: str  # point | joint
    tool: str  # "tGripper[0]" for points, "" for joints
    status: str  # see ORDER
    message: str
    path: str
    line: int
    col: int
    data: dict = field(default_factory=dict)

    @property
    def severity(self) -> str:
        """The entry's severity (SEVERITY: never an error)."""
        return SEVERITY[self.status]

    def as_dict(self) -> dict:
        """The entry in the JSON report."""
        return {"name": self.name, "kind": self.kind, "tool": self.tool, "status": self.status,
                "severity": self.severity, "message": self.message, "path": self.path, "line": self.line,
                "col": self.col, "data": self.data}


@dataclass
class ReachReport:
    """The static reach check of one application on one arm: every entry, and the counts."""
    app: str
    robot: str
    tools: list[str]
    points: int = 0
    joints: int = 0
    entries: list[ReachEntry] = field(default_factory=list)

    def problems(self) -> list[ReachEntry]:
        """The entries that are not ok."""
        return [e for e in self.entries if e.status != "ok"]

    def as_dict(self) -> dict:
        """The JSON report (`val3check reach --format json`)."""
        return {"version": 1, "app": self.app, "robot": self.robot, "tools": self.tools,
                "checked": {"points": self.points, "joints": self.joints},
                "thresholds": {"singularity": dict(THRESHOLDS), "joint_limit_margin_deg": LIMIT_MARGIN},
                "entries": [e.as_dict() for e in self.problems()]}


def _trsf(fields: dict, scale: float) -> Trsf:
    """A trsf from a data file's fields (lengths scaled to mm)."""
    def f(k):
        """A number field, 0 when absent or not a number."""
        v = fields.get(k, 0.0)
        return float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else 0.0

    return Trsf(f("x") * scale, f("y") * scale, f("z") * scale, f("rx"), f("ry"), f("rz"))


def _label(name: str, key: str, prefix: str) -> str:
    """The name shown for an element: prefix, name and key (lib:pHome[0])."""
    return f"{prefix}{name}[{key}]"


class _Space:
    """The frames, tools, points and joints of one application's data (geometry nodes)."""

    def __init__(self, app, prefix: str, world: Frame, flange: Tool):
        """The data of `app` (a loading.model.Application), names prefixed with `prefix`."""
        self.app = app
        self.prefix = prefix
        scale = 1.0 if getattr(app, "millimeter_unit", True) else INCH_MM
        self.nodes: dict[tuple[str, str], object] = {}
        self.items: list[tuple[str, str, object, object]] = []  # (kind, label, value, origin)
        self.families: dict[str, tuple[str | None, dict]] = {}  # label -> (Rx | Rs | None, config written)
        pending = []
        for name, data in app.data.items():
            b = base_type(data.type)
            if b not in ("frame", "tool", "point", "joint"):
                continue
            for v in data.values:
                label = _label(name, v.key, prefix)
                if b == "frame":
                    node = Frame(_trsf(v.fields, scale), None, name=label)
                elif b == "tool":
                    node = Tool(_trsf(v.fields, scale), None, name=label)
                elif b == "point":
                    cfg = tuple(str(v.fields.get(k, "ssame")) for k in ("shoulder", "elbow", "wrist"))
                    node = Point(_trsf(v.fields, scale), cfg, None, name=label)
                    self.families[label] = (arm_family(data.type), {k: str(v.fields[k]) for k in CONFIG_FIELDS
                                                                    if k in v.fields})
                else:
                    keys = sorted((k for k in v.fields if k[:1] == "j" and k[1:].isdigit()), key=lambda s: int(s[1:]))
                    node = tuple(float(v.fields[k]) for k in keys)
                self.nodes[(name.lower(), v.key)] = node
                if b in ("frame", "tool", "point"):
                    father = v.father or data.father
                    pending.append((node, father, b))
                if b in ("tool", "point", "joint"):
                    self.items.append((b, label, node, v.origin))
        for node, father, b in pending:
            root = flange if b == "tool" else world
            if not father:
                node.ref = root
                continue
            m = parse_father(father)
            if not m:
                continue
            fname, idx = m[0].lower(), (m[1] or "0").strip().strip('"')
            if fname == "world" and b != "tool":
                node.ref = world
            elif fname == "flange" and b == "tool":
                node.ref = flange
            else:
                ref = self.nodes.get((fname, idx))
                want = Tool if b == "tool" else Frame
                node.ref = ref if type(ref) is want else None


def check_reach(ws, app, model) -> ReachReport:
    """The reach check of `app` (and the libraries it declares) with the arm `model`."""
    kin = ArmKin(model)
    kin.need_ik()  # six-axis arms without the closed form: IKUnsupported (a RobotError)
    world, flange = GF.new_world(), GF.new_flange()
    spaces = [_Space(app, "", world, flange)]
    for alias in sorted(app.libraries):
        lib = ws.library(app, alias)
        if lib is not None and lib is not app:
            spaces.append(_Space(lib, f"{alias}:", world, flange))
    tools: list[tuple[str, np.ndarray | None]] = []
    entries: list[ReachEntry] = []
    for sp in spaces:
        for kind, label, node, origin in sp.items:
            if kind != "tool":
                continue
            try:
                tools.append((label, _pose4(GF.root_pose(node))))
            except Exception as exc:  # noqa: BLE001 - any failure of the geometry is the entry's reason
                entries.append(ReachEntry(label, "tool", "", "unresolved", f"tool {label}: {_why(exc)}",
                                          origin.path, origin.line, origin.col))
    if not tools:
        tools = [("flange", None)]
    report = ReachReport(app.name, model.name, [t for t, _ in tools])
    for sp in spaces:
        for kind, label, node, origin in sp.items:
            if kind == "point":
                report.points += 1
                try:
                    target = _pose4(GP.world_pose(node))
                except Exception as exc:  # noqa: BLE001 - any failure of the geometry is the entry's reason
                    entries.append(ReachEntry(label, "point", "", "unresolved", f"point {label}: {_why(exc)}",
                                              origin.path, origin.line, origin.col))
                    continue
                other = _other_family(model, label, *sp.families[label])
                for tname, tool in tools:
                    e = _check_point(kin, label, node.config, target, tname, tool, origin)
                    if other:  # the cause first, then what the check finds with the shoulder alone
                        e = ReachEntry(label, e.kind, e.tool, "family", f"{other}; {e.message}", e.path, e.line,
                                       e.col, {**e.data, "found": e.status})
                    entries.append(e)
            elif kind == "joint":
                report.joints += 1
                entries.append(_check_joint(kin, label, node, origin))
    entries.sort(key=lambda e: (ORDER[e.status], e.path, e.line, e.name, e.tool))
    report.entries = entries
    return report


CONFIG_FIELDS = ("shoulder", "elbow", "wrist")
SIX_AXIS_ONLY = {"elbow", "wrist"}  # a SCARA's configuration is its shoulder (9.7.2)


def _other_family(model, label: str, family: str | None, written: dict) -> str:
    """Why the point `label` is of the other arm family than `model`'s (9.7.2: RX/TX points have a
    shoulder, an elbow and a wrist; RS/TS points a shoulder only), or "" when it is not: a
    `pointRx` on a SCARA or a `pointRs` on a six-axis arm (the controller stops with error 81 when
    an instruction uses it), or a `point` whose data imposes an elbow or a wrist on a SCARA."""
    scara = tuple(getattr(model, "config_fields", CONFIG_FIELDS)) == ("shoulder",)
    if scara and family == "Rx":
        return (f"point {label} is a pointRx, of a six-axis arm (shoulder, elbow, wrist), not of the {model.name}, a "
                "SCARA whose points have a shoulder only (9.7.2): a motion instruction that uses it stops with "
                "error 81")
    if not scara and family == "Rs":
        return (f"point {label} is a pointRs, of a SCARA (shoulder only), not of the {model.name}, a six-axis arm "
                "(9.7.2): a motion instruction that uses it stops with error 81")
    imposed = {k: v for k, v in written.items() if k in SIX_AXIS_ONLY and not v.lower().endswith(("same", "free"))}
    if scara and family is None and imposed:
        said = ", ".join(f"{k} {v}" for k, v in imposed.items())
        return (f"point {label} has the configuration of a six-axis arm ({said}), not of the {model.name}, a SCARA "
                "whose points have a shoulder only (9.7.2): written for another arm family?")
    return ""


def _why(exc: Exception) -> str:
    """The message of an error of the geometry."""
    return getattr(exc, "detail", "") or str(exc)


def _pose4(p: R.Pose) -> np.ndarray:
    """A geometry pose (rotation, translation) as a 4x4 matrix."""
    m, t, _ = p
    T = np.eye(4)
    T[:3, :3] = np.array(m).reshape(3, 3)
    T[:3, 3] = t
    return T


def _margins(kin: ArmKin, Q: np.ndarray):
    """Per solution: (smallest margin to a joint limit in degrees and its axis, the singularity
    nearest relative to its threshold: name, distance, relative)."""
    lim = np.minimum(Q - kin.lo, kin.hi - Q)
    sing = kin.singularity(Q)
    rel = np.stack([sing.wrist / THRESHOLDS["wrist"], sing.elbow / THRESHOLDS["elbow"],
                    sing.shoulder / THRESHOLDS["shoulder"]], axis=1)
    names = ("wrist", "elbow", "shoulder")
    dist = np.stack([sing.wrist, sing.elbow, sing.shoulder], axis=1)
    return lim, rel, names, dist


def _check_point(kin, label, config, T, tname, tool, origin) -> ReachEntry:
    """The entry of one point (its TCP pose T in world) with one tool."""
    flange_T = T if tool is None else T @ np.linalg.inv(tool)
    sols, codes = kin.solutions(flange_T)
    base = {"kind": "point", "tool": tname, "path": origin.path, "line": origin.line, "col": origin.col}
    where = f"point {label} with tool {tname}"
    if not len(sols):
        return ReachEntry(label, status="unreachable", message=f"{where} is out of the arm's reach"
                          + ("" if not kin.generic else " (or outside the joint limits)"),
                          data={"target_mm": _r(T[:3, 3])}, **base)
    want = [c.lower() for c in config]
    keep = np.array([all(w.endswith(("same", "free")) or w == v
                         for w, v in zip(want, kin.config_name(int(cd)))) for cd in codes])
    if not keep.any():
        return ReachEntry(label, status="config", message=f"{where} is reachable, but not in configuration "
                          f"{'/'.join(config)}", data={"config": list(config)}, **base)
    sols = _in_range_turns(kin, sols[keep])
    excess = np.maximum(kin.lo - sols, sols - kin.hi)
    inside = (excess <= 1e-7).all(axis=1)
    if not inside.any():
        worst = excess.max(axis=1)
        i = int(np.argmin(worst))
        ax = int(np.argmax(excess[i]))
        return ReachEntry(label, status="limits",
                          message=f"{where}: every joint position reaching it is outside the joint limits (at best j{ax + 1} "
                                  f"= {sols[i, ax]:.2f}°, {excess[i, ax]:.2f}° beyond [{kin.lo[ax]:g}, {kin.hi[ax]:g}])",
                          data={"axis": ax + 1, "excess_deg": round(float(excess[i, ax]), 4)}, **base)
    return _near(kin, sols[inside], where, label, base)


def _in_range_turns(kin, sols):
    """Each axis of the solutions on a turn within its limits, when one is."""
    out = sols.copy()
    for r in range(len(out)):
        for k in range(out.shape[1]):
            if not kin.revolute[k]:
                continue
            for shift in (0.0, 360.0, -360.0):
                v = sols[r, k] + shift
                if kin.lo[k] - 1e-7 <= v <= kin.hi[k] + 1e-7:
                    out[r, k] = v
                    break
    return out


def _near(kin, Q, where, label, base) -> ReachEntry:
    """The entry of a position reachable within the limits: near a singularity or a limit, or ok."""
    lim, rel, names, dist = _margins(kin, Q)
    score = np.minimum(lim.min(axis=1) / LIMIT_MARGIN, rel.min(axis=1))
    i = int(np.argmax(score))  # the most comfortable solution
    lmin = float(lim[i].min())
    ax = int(np.argmin(lim[i]))
    j = int(np.argmin(rel[i]))
    data = {"joints": _r(Q[i]), "limit_margin_deg": round(lmin, 4), "limit_axis": ax + 1,
            "singularity": names[j], "singularity_distance": round(float(dist[i, j]), 4)}
    if rel[i, j] < 1.0:
        return ReachEntry(label, status="near-singularity",
                          message=f"{where} is reached only near the {WHAT[names[j]]}: "
                                  f"{dist[i, j]:.2f}{UNITS[names[j]]} (threshold {THRESHOLDS[names[j]]:g}{UNITS[names[j]]})",
                          data=data, **base)
    if lmin < LIMIT_MARGIN:
        return ReachEntry(label, status="near-limit",
                          message=f"{where} is reached only {lmin:.2f}° from the limit of j{ax + 1}",
                          data=data, **base)
    return ReachEntry(label, status="ok", message=f"{where} is reachable", data=data, **base)


def _check_joint(kin, label, j, origin) -> ReachEntry:
    """The entry of one joint value."""
    base = {"kind": "joint", "tool": "", "path": origin.path, "line": origin.line, "col": origin.col}
    Q = np.asarray(j, dtype=float)
    if len(Q) != len(kin.lo):
        if {len(Q), len(kin.lo)} == {4, 6}:  # jointRx on a SCARA, jointRs on a six-axis arm (9.2.1)
            other = "a six-axis arm's" if len(Q) == 6 else "a SCARA's"
            return ReachEntry(label, status="family", message=f"joint {label} has {len(Q)} axes, {other} (9.2.1): "
                              f"not of this {len(kin.lo)}-axis arm (a motion instruction that uses it stops with "
                              "error 81)", **base)
        return ReachEntry(label, status="unresolved", message=f"joint {label} has {len(Q)} axes for a "
                          f"{len(kin.lo)}-axis arm", **base)
    excess = np.maximum(kin.lo - Q, Q - kin.hi)
    if np.any(excess > 1e-7):
        ax = int(np.argmax(excess))
        u = "°" if kin.revolute[ax] else " mm"
        return ReachEntry(label, status="limits", message=f"joint {label}: j{ax + 1} = {Q[ax]:g}{u} is "
                          f"{excess[ax]:.2f}{u} beyond its limits [{kin.lo[ax]:g}, {kin.hi[ax]:g}]",
                          data={"axis": ax + 1, "excess_deg": round(float(excess[ax]), 4)}, **base)
    return _near(kin, Q[None], f"joint {label}", label, base)


def _r(v) -> list[float]:
    """Numbers of the report's data, to 1e-4."""
    return [round(float(x), 4) for x in v]
