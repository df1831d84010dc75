"""The cell around the program: the I/O scenario file (TOML, docs/scenario.md).

A scenario gives initial input values, inputs that change at given times, reactions of the
cell to outputs, key presses on the pendant, bytes sent by serial/socket peers, and the
controller state of chapter 8. Signals are named by a global dio/aio/sio variable of the
application (`diPart`, `diCode[2]`) or by their physical link (`"BasicIO-1\\%I2"`). An unknown
signal, key or a value of the wrong type is an error that names the line.
"""

from __future__ import annotations

import datetime
from typing import Any

from ..excerpt import excerpt, shown
from ..interpretation.events import ControllerChange, InputsChange, KeyPress, SerialData
from ..interpretation.io_cell import Reaction, SerialReply
from ..interpretation.user_page import Key
from ..interpretation.values import Arr, FaultyIOPoint, IOPoint
from ..interpretation.virtual_disk import disk_key
from ..light_dataclass import dataclass, field
from .scenario_numbers import MAX_SECONDS
from .scenario_numbers import finite as _finite
from .scenario_numbers import seconds as _seconds
from .scenario_options import TABLES as OPTION_TABLES
from .scenario_options import apply_options

SCENARIO_VERSION = 1
LIMIT_TOL = 1e-7  # a joint this close outside its limit is on it (robot.models.LIMIT_TOL_DEG)


class ScenarioError(Exception):
    def __init__(self, path: str, line: int, message: str) -> None:
        super().__init__(f"{path}:{line}: {message}" if line else f"{path}: {message}")
        self.path, self.line, self.message = path, line, message


@dataclass
class Scenario:
    path: str
    text: str
    data: dict = field(default_factory=dict)


MAX_SCENARIO_SIZE = 8 * 1024 * 1024  # bytes: a scenario is a few pages of TOML
MAX_NESTING = 32  # tables and arrays inside each other: the format needs 3


def load_scenario(path: str) -> Scenario:
    """Read a scenario file: a regular file (not a FIFO or a device: val3check.confine), at most
    MAX_SCENARIO_SIZE bytes, UTF-8 TOML nested at most MAX_NESTING deep (val3check.tomlfile)."""
    from .. import tomlfile
    from ..confine import Refused, Roots, read_bytes

    try:
        raw = read_bytes(path, Roots.user_given(), MAX_SCENARIO_SIZE)
    except Refused as exc:
        raise ScenarioError(path, 0, f"cannot read: {exc.reason}") from None
    try:
        data, text = tomlfile.load_bytes(raw, max_depth=MAX_NESTING)
    except tomlfile.TomlError as exc:
        raise ScenarioError(path, exc.line, exc.message) from None
    return Scenario(path, text, data)


RANGE_KEYS = frozenset({"min", "max", "nominal"})


def time_range(v: Any) -> tuple[float, float, float] | None:
    """A time or delay of the scenario as (nominal, min, max) seconds: a number (its own min and
    max), or a range `{ min = 0.1, max = 0.4 }` that `sim --explore` draws in (docs/explore.md),
    whose nominal, the value a plain run uses, is its middle unless `nominal` is given. None when
    it is neither (a bad key, min > max, a nominal outside, a value out of [0, MAX_SECONDS])."""
    if isinstance(v, dict):
        if set(v) - RANGE_KEYS or not {"min", "max"} <= set(v):
            return None
        lo, hi = v["min"], v["max"]
        mid = v.get("nominal", (lo + hi) / 2 if _finite(lo) and _finite(hi) else None)
        if any(_seconds(x) is None for x in (lo, hi, mid)) or not lo <= mid <= hi:
            return None
        return float(mid), float(lo), float(hi)
    return (float(v),) * 3 if _seconds(v) is not None else None


def _time(v: Any) -> int | None:
    """Microseconds of a time that may be a range (its nominal); None when it is not one."""
    r = time_range(v)
    return None if r is None else _seconds(r[0])


EXPLORE_KEYS = {"jitter", "max_cycle_time"}


class Applier:
    """Applies a scenario to a machine; every mistake is a ScenarioError at the line of the key
    at fault (val3check.tomlpos: where each key of the text is written)."""

    def __init__(self, machine, scenario: Scenario) -> None:
        from ..tomlpos import positions

        self.machine = machine
        self.sc = scenario
        self.pos = positions(scenario.text)
        self.signals = self._signals()

    def at(self, path: tuple) -> int:
        """The line of the key `path` (("events", 2, "at")), else of its closest known parent."""
        return self.pos.at(path, key=True)[0]

    def fail(self, where: int | tuple, message: str) -> None:
        raise ScenarioError(self.sc.path, where if isinstance(where, int) else self.at(where), message)

    def _signals(self) -> dict[str, IOPoint]:
        out: dict[str, IOPoint] = {}
        main = self.machine.main
        for name, c in main.globals.items():
            if type(c) is Arr and c.t in ("dio", "aio", "sio"):
                for i, io in enumerate(c.data):
                    if isinstance(io, IOPoint):
                        if i == 0:
                            out[name] = io
                        out[f"{name}[{i}]"] = io
        for (kind, link), io in self.machine.cell.points.items():
            out.setdefault(link, io)
        return out

    def signal(self, name: str, where: tuple, kinds=("dio", "aio")) -> IOPoint:
        io = self.signals.get(name)
        if io is None:
            self.fail(where, f"unknown signal {shown(name)} (a global dio/aio/sio of the application, or a link of its data)")
        if not io.link:
            self.fail(where, f"signal {shown(name)} is not linked to an input/output (its link is empty in the data file)")
        if io.kind not in kinds:
            self.fail(where, f"signal {shown(name)} is a {io.kind}, expected {' or '.join(kinds)}")
        return io

    def value(self, io: IOPoint, v: Any, where: tuple, name: str) -> Any:
        if io.kind == "dio":
            if not isinstance(v, bool):
                self.fail(where, f"{excerpt(name)}: a dio takes true or false, not {shown(v)}")
            return v
        if not _finite(v):
            self.fail(where, f"{excerpt(name)}: an aio takes a number (finite), not {shown(v)}")
        return float(v)

    def settings(self, table: Any, where: tuple, what: str) -> list[tuple[IOPoint, Any]]:
        if not isinstance(table, dict):
            self.fail(where, f"{what}: expected a table of signal = value")
        out = []
        for name, v in table.items():
            io = self.signal(name, where + (name,))
            out.append((io, self.value(io, v, where + (name,), name)))
            io.driven = True  # driven by the scenario: an input (writing it is error 122)
        return out

    def apply(self) -> None:
        d = self.sc.data
        self.machine.cell_subsystem.scenario_path = self.sc.path
        known = {"version", "description", "inputs", "events", "reactions", "keys", "serial", "controller", "io", "robot",
                 "files", *OPTION_TABLES, "explore"}
        for k in d:
            if k not in known:
                self.fail((k,), f"unknown table or key {shown(k)}")
        version = d.get("version", SCENARIO_VERSION)
        if version != SCENARIO_VERSION:
            self.fail(("version",), f"unsupported scenario version {shown(version)} (expected 1)")
        machine = self.machine
        cell = machine.cell_subsystem
        if "inputs" in d:
            for io, v in self.settings(d["inputs"], ("inputs",), "[inputs]"):
                io.value = v
                machine.log_io(0, io, v, "scenario")
        for i, ev in enumerate(_list(d, "events", self)):
            here = ("events", i)
            self._keys(ev, {"at", "set"}, here, "[[events]]")
            at = _time(ev.get("at"))
            if at is None:
                self.fail(here + ("at",), "[[events]] needs at = seconds (a finite number from 0 to 1e7)")
            cell.schedule(at, InputsChange(tuple(self.settings(ev.get("set", {}), here + ("set",), "[[events]] set"))))
        for i, r in enumerate(_list(d, "reactions", self)):
            here = ("reactions", i)
            self._keys(r, {"when", "becomes", "after", "set"}, here, "[[reactions]]")
            name = r.get("when")
            if not isinstance(name, str):
                self.fail(here, "[[reactions]] needs when = \"output\"")
            io = self.signal(name, here + ("when",))
            becomes = self.value(io, r.get("becomes", True), here + ("becomes",), name)
            after = _time(r.get("after", 0))
            if after is None:
                self.fail(here + ("after",), "after = seconds (a finite number from 0 to 1e7)")
            cell.reactions.append(Reaction(io, becomes, after,
                                           tuple(self.settings(r.get("set", {}), here + ("set",), "[[reactions]] set")),
                                           self.at(here)))
        keys = []
        for i, k in enumerate(_list(d, "keys", self)):
            here = ("keys", i)
            self._keys(k, {"at", "key", "text", "hold"}, here, "[[keys]]")
            at = _time(k.get("at", 0))
            if at is None:
                self.fail(here + ("at",), "[[keys]] at = seconds (a finite number from 0 to 1e7)")
            code = k.get("key", 270 if "text" in k else None)
            if isinstance(code, bool) or not isinstance(code, int) or not -1 < code < 1000:
                self.fail(here + ("key",), "[[keys]] key = a key code (4.3), e.g. 270 for Return")
            text = k.get("text")
            if text is not None and not isinstance(text, str):
                self.fail(here + ("text",), "[[keys]] text = \"what the operator types\"")
            hold = _seconds(k.get("hold", 0.2))
            if hold is None:
                self.fail(here + ("hold",), "[[keys]] hold = seconds")
            keys.append(Key(at, code, text, hold))
            cell.schedule(at, KeyPress())
        machine.user_page.set_keys(keys)
        for i, s in enumerate(_list(d, "serial", self)):
            here = ("serial", i)
            self._keys(s, {"sio", "at", "send", "bytes", "when_sent", "after"}, here, "[[serial]]")
            name = s.get("sio")
            if not isinstance(name, str):
                self.fail(here, "[[serial]] needs sio = \"siVariable\"")
            io = self.signal(name, here + ("sio",), kinds=("sio",))
            data = self._bytes(s, here, io)
            if "when_sent" in s:
                pat = s["when_sent"]
                if not isinstance(pat, str) or not pat:
                    self.fail(here + ("when_sent",), "when_sent = \"text the program sends\"")
                after = _time(s.get("after", 0))
                if after is None:
                    self.fail(here + ("after",), "after = seconds")
                cell.serial_replies.append(SerialReply(io, pat.encode("utf-8"), after, data))
            else:
                at = _time(s.get("at", 0))
                if at is None:
                    self.fail(here + ("at",), "[[serial]] at = seconds (a finite number from 0 to 1e7)")
                cell.schedule(at, SerialData(io, data))
        for i, f in enumerate(_list(d, "files", self)):
            self._file(f, ("files", i))
        if "controller" in d:
            self._controller(d["controller"])
        if "io" in d:
            self._io(d["io"])
        if "robot" in d:
            self._robot(d["robot"])
        apply_options(self, d)  # chapter 11: scenario_options.py
        if "explore" in d:
            self._explore(d["explore"])

    def _explore(self, table: Any) -> None:
        """[explore]: what `sim --explore` varies and bounds (docs/explore.md); a plain run
        checks it and does nothing else with it."""
        if not isinstance(table, dict):
            self.fail(("explore",), "[explore] must be a table: jitter = seconds, max_cycle_time = seconds")
        self._keys(table, EXPLORE_KEYS, ("explore",), "[explore]")
        for k, v in table.items():
            if _seconds(v) is None:
                self.fail(("explore", k), f"[explore] {k} = seconds (a finite number from 0 to {MAX_SECONDS:g})")

    def _robot(self, table: Any) -> None:
        """[robot] joints = [j1, ..., j6]: the arm's joint position at the start (degrees, a
        SCARA's joint 3 in millimetres), the one herej() and here() return; each within the arm's
        joint limits. Without an arm model (--robot) it has no effect."""
        here = ("robot",)
        if not isinstance(table, dict):
            self.fail(here, "[robot] must be a table: joints = [j1, j2, j3, j4, j5, j6]")
        self._keys(table, {"joints"}, here, "[robot]")
        if "joints" not in table:
            return
        here = here + ("joints",)
        j = table["joints"]
        if not isinstance(j, list) or not j or not all(_finite(v) for v in j):
            self.fail(here, "[robot] joints = [finite numbers], one per axis, in degrees")
        arm = self.machine.arm
        if not arm.has_model:
            return
        if len(j) != arm.axes:
            self.fail(here, f"[robot] joints: {len(j)} values for the {arm.axes}-axis arm {arm.name}")
        kinds = getattr(getattr(arm, "model", None), "joint_kinds", ()) or ()
        for n, (v, (lo, hi)) in enumerate(zip(j, arm.joint_limits)):
            if not lo - LIMIT_TOL <= v <= hi + LIMIT_TOL:
                unit = "mm" if n < len(kinds) and kinds[n] == "prismatic" else "degrees"
                self.fail(here, f"[robot] joints: joint {n + 1} = {shown(v)} is outside the limits of the arm "
                                f"{arm.name}: [{lo:g}, {hi:g}] {unit}")
        arm.start_at(j)

    def _io(self, table: Any) -> None:
        """[io]: the state of inputs/outputs as ioStatus() reports it (3.5.3), their description,
        and integer analog outputs (3.6.2)."""
        if not isinstance(table, dict):
            self.fail(("io",), "[io] must be a table of signal = { status = ..., description = \"...\", integer = ... }")
        for name, spec in table.items():
            here = ("io", name)
            io = self.signal(name, here, kinds=("dio", "aio", "sio"))
            label = excerpt(name)
            if not isinstance(spec, dict):
                self.fail(here, f"[io] {label}: expected {{ status = 0, description = \"...\" }}")
            self._keys(spec, {"status", "description", "integer"}, here, f"[io] {label}")
            status = spec.get("status", 0)
            if isinstance(status, bool) or status not in (0, 1, 2, -2, -3):
                self.fail(here + ("status",), f"[io] {label}: status is 0 (works), 1 (locked), 2 (simulated), "
                          f"-2 (not installed) or -3 (device in error), not {shown(status)}")
            desc = spec.get("description", "")
            if not isinstance(desc, str):
                self.fail(here + ("description",), f"[io] {label}: description = \"text\"")
            integer = spec.get("integer", False)
            if not isinstance(integer, bool) or integer and io.kind != "aio":
                self.fail(here + ("integer",), f"[io] {label}: integer = true|false, for an aio only")
            io.status = status
            io.description = desc
            io.integer = integer
            if status < 0:
                io.__class__ = FaultyIOPoint

    def _bytes(self, s: dict, here: tuple, io: IOPoint) -> bytes:
        if "send" in s:
            if not isinstance(s["send"], str):
                self.fail(here + ("send",), "send = \"text\" (sent with the end-of-string character)")
            return s["send"].encode("utf-8") + bytes([io.eos])
        if "bytes" in s:
            b = s["bytes"]
            if not isinstance(b, list) or not all(isinstance(x, int) and not isinstance(x, bool) and 0 <= x <= 255 for x in b):
                self.fail(here + ("bytes",), "bytes = [numbers from 0 to 255]")
            return bytes(b)
        self.fail(here, "[[serial]] needs send = \"text\" or bytes = [...]")
        return b""

    def _file(self, f: Any, here: tuple) -> None:
        """[[files]]: a file of the controller's disk for the system library's $file... instructions
        (interpretation/virtual_disk.py); never the user's disk."""
        self._keys(f, {"path", "text", "bytes"}, here, "[[files]]")
        path = f.get("path")
        if not isinstance(path, str) or disk_key(path) is None:
            self.fail(here + ("path",), '[[files]] needs path = "Disk://folder/name.txt"')
        if ("text" in f) == ("bytes" in f):
            self.fail(here, '[[files]] needs text = "..." or bytes = [...]')
        if "text" in f:
            if not isinstance(f["text"], str):
                self.fail(here + ("text",), '[[files]] text = "the content"')
            data = f["text"].encode("utf-8")
        else:
            b = f["bytes"]
            if not isinstance(b, list) or not all(isinstance(x, int) and not isinstance(x, bool) and 0 <= x <= 255 for x in b):
                self.fail(here + ("bytes",), "bytes = [numbers from 0 to 255]")
            data = bytes(b)
        if not self.machine.files.put(path, data):
            self.fail(here, "[[files]]: the controller's disk is full")

    def _keys(self, table: Any, allowed: set[str], here: tuple, what: str) -> None:
        if not isinstance(table, dict):
            self.fail(here, f"{what}: expected a table")
        for k in table:
            if k not in allowed:
                self.fail(here + (k,), f"{what}: unknown key {shown(k)} (allowed: {', '.join(sorted(allowed))})")

    def _controller(self, c: Any) -> None:
        if not isinstance(c, dict):
            self.fail(("controller",), "[controller] must be a table")
        ctl = self.machine.controller
        spec = {
            "working_mode": (int, range(0, 5)), "working_state": (int, range(0, 7)), "es_status": (int, range(0, 3)),
            "powered": (bool, None), "power_delay": ((int, float), None), "calibrated": (bool, None),
            "monitor_speed": ((int, float), None), "operator_speed": (bool, None), "safety_fault": (str, None),
            "profile": (str, None), "profiles": (dict, None), "language": (str, None), "languages": (list, None),
            "date": ((str, datetime.datetime, datetime.date), None), "versions": (dict, None), "changes": (list, None),
        }
        for k, v in c.items():
            here = ("controller", k)
            if k not in spec:
                self.fail(here, f"[controller]: unknown key {shown(k)}")
            types, rng = spec[k]
            if isinstance(v, bool) and types is not bool or isinstance(v, float) and not _finite(v):
                self.fail(here, f"[controller] {k}: bad value {shown(v)}")
            if not isinstance(v, types) or (rng is not None and v not in rng):
                self.fail(here, f"[controller] {k}: bad value {shown(v)}")
            if k == "power_delay":
                if _seconds(v) is None:
                    self.fail(here, f"[controller] power_delay: seconds from 0 to {MAX_SECONDS:g}")
                ctl.power_delay_us = int(round(v * 1_000_000))
            elif k == "monitor_speed":
                if not 0 <= v <= 100:
                    self.fail(here, "[controller] monitor_speed: 0 to 100")
                ctl.monitor_speed = float(v)
            elif k == "date":
                try:
                    ctl.date = v if isinstance(v, datetime.datetime) else (
                        datetime.datetime(v.year, v.month, v.day) if isinstance(v, datetime.date)
                        else datetime.datetime.fromisoformat(v))
                    ctl.date = ctl.date.replace(tzinfo=None)
                except ValueError:
                    self.fail(here, f"[controller] date: not an ISO date {shown(v)}")
            elif k == "profiles":
                if not all(isinstance(x, str) for x in v.values()):
                    self.fail(here, "[controller] profiles = { login = \"password\" }")
                ctl.profiles = dict(v)
            elif k == "languages":
                ctl.languages = tuple(str(x) for x in v)
            elif k == "versions":
                ctl.versions.update({str(a): str(b) for a, b in v.items()})
            elif k == "changes":
                self._changes(v, here, spec)
            else:
                setattr(ctl, k, v)

    def _changes(self, changes: list, here: tuple, spec: dict) -> None:
        for i, ch in enumerate(changes):
            if not isinstance(ch, dict) or _time(ch.get("at")) is None:
                self.fail(here + (i,), "[controller] changes = [{ at = seconds, working_mode = 3, ... }]")
            payload = {}
            for ck, cv in ch.items():
                if ck == "at":
                    continue
                if ck not in ("working_mode", "working_state", "es_status", "powered", "monitor_speed",
                              "safety_fault", "calibrated"):
                    self.fail(here + (i, ck), f"[controller] changes: cannot change {shown(ck)}")
                ctypes, crng = spec[ck]
                if (isinstance(cv, bool) and ctypes is not bool or not isinstance(cv, ctypes)
                        or crng is not None and cv not in crng
                        or ck == "monitor_speed" and not (_finite(cv) and 0 <= cv <= 100)):
                    self.fail(here + (i, ck), f"[controller] changes: {ck}: bad value {shown(cv)}")
                payload[ck] = cv
            self.machine.cell_subsystem.schedule(_time(ch["at"]), ControllerChange(tuple(payload.items())))


def _list(d: dict, key: str, ap: Applier) -> list:
    v = d.get(key, [])
    if not isinstance(v, list):
        ap.fail((key,), f"{key} must be an array of tables ([[{key}]])")
    return v


def apply_scenario(machine, scenario: Scenario) -> None:
    Applier(machine, scenario).apply()
