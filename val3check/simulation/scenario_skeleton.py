"""`val3check sim --init-scenario FILE`: a scenario skeleton (docs/scenario.md) to edit.

Found from the code, without running it: every input the application reads or waits on (a
dio or aio global it reads and never writes, directly or through the programs it passes it to),
every sio it reads, every key press it waits for (`get`, `getKey`, `isKeyPressed`), and every
part of the controller state of chapters 4 and 8 it reads (`workingMode()`, `isPowered()`...),
each with the place that reads it. Inputs and the controller state are written with their
defaults, so the skeleton as written changes nothing in a run; key presses and serial data have
no default and are written as commented-out entries to fill in (the run with the skeleton is
the run without a scenario; only the I/O log also shows the initial values of the inputs). A global that is both read and
written, or handed to a library, is listed as a comment: the scenario drives inputs only, and
writing a driven input is error 122.
"""

from __future__ import annotations

import datetime
import json
from dataclasses import dataclass, field

from ..interpretation.controller import Controller, default_versions
from ..interpretation.virtual_disk import disk_key
from ..loading.model import Application, Workspace
from ..parsing import ast as A

# which instruction reads (or changes) which key of [controller] (docs/scenario.md)
CONTROLLER_READS = {
    "enablepower": ("working_mode", "es_status", "powered", "power_delay"),
    "disablepower": ("powered",),
    "ispowered": ("powered",),
    "iscalibrated": ("calibrated",),
    "workingmode": ("working_mode", "working_state"),
    "esstatus": ("es_status",),
    "safetyfault": ("safety_fault",),
    "getmonitorspeed": ("monitor_speed",),
    "setmonitorspeed": ("working_mode", "operator_speed", "monitor_speed"),
    "getversion": ("versions",),
    "getprofile": ("profile",),
    "setprofile": ("profile", "profiles"),
    "getlanguage": ("language",),
    "setlanguage": ("language", "languages"),
    "getdate": ("date",),
    # motion needs arm power and follows the monitor speed (docs/motion.md)
    "movej": ("powered", "monitor_speed"),
    "movel": ("powered", "monitor_speed"),
    "movec": ("powered", "monitor_speed"),
}
CONTROLLER_ORDER = ("working_mode", "working_state", "es_status", "powered", "power_delay", "calibrated",
                    "monitor_speed", "operator_speed", "safety_fault", "profile", "profiles", "language",
                    "languages", "date", "versions")
# instructions whose first argument is written, not read (3.5.3, 3.6.2, 3.7.3)
WRITES_FIRST = {"dioset", "aioset", "sioset", "diolink", "aiolink", "siolink"}
KEY_CALLS = {"get", "getkey", "iskeypressed"}


@dataclass
class _Use:
    reads: dict[str, list[str]] = field(default_factory=dict)  # lower name -> where ("start.pgx:12")
    writes: set[str] = field(default_factory=set)
    indices: dict[str, set[int] | None] = field(default_factory=dict)  # constant indices read; None: any
    calls: list[tuple[str, list[str | None], str]] = field(default_factory=list)  # callee, arg names, where
    to_library: dict[str, str] = field(default_factory=dict)  # name -> the library call it is handed to
    keys: list[tuple[str, str, int | None]] = field(default_factory=list)  # instruction, where, key code
    controller: dict[str, list[str]] = field(default_factory=dict)  # key -> where
    versions: list[str] = field(default_factory=list)  # the getVersion() components asked for by name
    files: list[tuple[str, str]] = field(default_factory=list)  # ($fileOpen path, where)
    state_waits: list[tuple[str, str]] = field(default_factory=list)  # ([controller] key, where) of wait()s


def _base(expr) -> tuple[str | None, int | None]:  # noqa: ANN001
    """The variable an expression names (`diX`, `diX[2]`, `diX[i]`) and its constant index."""
    if isinstance(expr, A.Name):
        return expr.name.lower(), None
    if isinstance(expr, A.Index) and isinstance(expr.base, A.Name):
        idx = expr.indices[0] if len(expr.indices) == 1 else None
        return expr.base.name.lower(), int(idx.value) if isinstance(idx, A.Number) else -1
    return None, None


class _Reader:
    """One program's reads and writes of names, calls, key presses and controller reads."""

    def __init__(self, file: str) -> None:
        self.file = file
        self.use = _Use()

    def where(self, node) -> str:  # noqa: ANN001
        return f"{self.file}:{node.line}"

    def read(self, name: str, index: int | None, node) -> None:  # noqa: ANN001
        self.use.reads.setdefault(name, []).append(self.where(node))
        if index is None or index < 0:
            self.use.indices[name] = None
        elif self.use.indices.get(name, set()) is not None:
            self.use.indices.setdefault(name, set()).add(index)

    def expr(self, e) -> None:  # noqa: ANN001, C901
        if e is None:
            return
        if isinstance(e, A.Name):
            self.read(e.name.lower(), None, e)
        elif isinstance(e, A.Index):
            name, index = _base(e)
            if name is not None:
                self.read(name, index, e)
            else:
                self.expr(e.base)
            for i in e.indices:
                self.expr(i)
        elif isinstance(e, A.Field):
            self.expr(e.base)
        elif isinstance(e, A.CallExpr):
            self.call(e.func, e.args, e)
        elif isinstance(e, A.Unary):
            self.expr(e.operand)
        elif isinstance(e, A.Binary):
            self.expr(e.left)
            self.expr(e.right)
        elif isinstance(e, A.Struct):
            for f in e.fields:
                self.expr(f)
        elif isinstance(e, A.AssignExpr):
            self.write(e.target)
            self.expr(e.value)

    def write(self, target) -> None:  # noqa: ANN001
        name, _ = _base(target)
        if name is not None:
            self.use.writes.add(name)
            if isinstance(target, A.Index):
                for i in target.indices:
                    self.expr(i)
        elif isinstance(target, A.Field):
            self.write(target.base)

    def call(self, func, args, node) -> None:  # noqa: ANN001
        if isinstance(func, A.LibraryName):
            for a in args:
                name, _ = _base(a)
                if name is not None:
                    self.use.to_library.setdefault(name, f"{func.alias}:{func.name}()")
                self.expr(a)
            return
        if not isinstance(func, A.Name):
            if (isinstance(func, A.SystemName) and func.name.lower() == "$fileopen" and args
                    and isinstance(args[0], A.String) and not (len(args) > 1 and isinstance(args[1], A.String)
                                                               and args[1].value.strip().lower() in ("w", "a"))):
                # a file of the controller's disk it reads ("w" and "a" create theirs)
                self.use.files.append((args[0].value, self.where(node)))
            for a in args:
                self.expr(a)
            return
        low = func.name.lower()
        if low in KEY_CALLS:
            code = None
            if low == "iskeypressed" and args and isinstance(args[-1], A.Number):
                code = int(args[-1].value)
            kind = "text" if low == "get" and args and not isinstance(args[-1], A.Number) else low
            self.use.keys.append((kind, self.where(node), code))
        for key in CONTROLLER_READS.get(low, ()):
            self.use.controller.setdefault(key, []).append(self.where(node))
        if low == "getversion" and args and isinstance(args[0], A.String) and args[0].value not in self.use.versions:
            self.use.versions.append(args[0].value)
        if low in ("wait", "watch") and args:  # a wait only the controller's state can end (R009)
            for n in A.walk(args[0]):
                if isinstance(n, A.CallExpr) and isinstance(n.func, A.Name):
                    for key in CONTROLLER_READS.get(n.func.name.lower(), ())[:1]:
                        self.use.state_waits.append((key, self.where(node)))
        for k, a in enumerate(args):
            if k == 0 and low in WRITES_FIRST:
                self.write(a)
            else:
                self.expr(a)

    def statements(self, body) -> None:  # noqa: ANN001, C901
        for s in body or ():
            if isinstance(s, A.Assign):
                self.write(s.target)
                self.expr(s.value)
            elif isinstance(s, A.ExprStatement):
                self.expr(s.call)
            elif isinstance(s, (A.Call, A.TaskCreate, A.TaskCreateSync)):
                for attr in ("task", "priority", "period", "overrun"):
                    self.expr(getattr(s, attr, None))
                if isinstance(s.target, A.LibraryName):
                    self.call(s.target, s.args, s)
                    continue
                self.use.calls.append((s.target.name.lower(), [_base(a)[0] for a in s.args], self.where(s)))
                for a in s.args:
                    name, _ = _base(a)
                    if name is None:
                        self.expr(a)
            elif isinstance(s, A.Print):
                for v in s.values:
                    self.expr(v)
            elif isinstance(s, A.If):
                for b in s.branches:
                    self.expr(b.cond)
                    self.statements(b.body)
                self.statements(s.orelse)
            elif isinstance(s, (A.While, A.DoUntil)):
                self.expr(s.cond)
                self.statements(s.body)
            elif isinstance(s, A.For):
                self.write(s.counter)
                for e in (s.start, s.stop, s.step):
                    self.expr(e)
                self.statements(s.body)
            elif isinstance(s, A.Switch):
                self.expr(s.subject)
                for case in s.cases:
                    for v in case.values:
                        self.expr(v)
                    self.statements(case.body)
                if s.default is not None:
                    self.statements(s.default.body)


def _program_uses(app: Application) -> dict[str, tuple[_Use, list[str], set[str]]]:
    """program (lower) -> (its uses, its parameter names, its local names), all lower case."""
    import os

    out = {}
    for name, program in app.programs.items():
        reader = _Reader(os.path.basename(program.origin.path))
        if program.body is not None:
            reader.statements(program.body.statements)
        out[name.lower()] = (reader.use, [p.name.lower() for p in program.parameters],
                             {x.name.lower() for x in program.locals})
    return out


def _globals_used(app: Application) -> tuple[dict[str, list[str]], set[str], dict[str, str], dict[str, set[int] | None]]:
    """(global -> where it is read, globals written, global -> library it is handed to,
    global -> constant indices read) over every program, through parameters (a dio/aio/sio
    parameter, by value or by reference, is a link to the same input/output: 3.5.1)."""
    uses = _program_uses(app)
    # parameter effects: (program, param index) -> reads where / written
    param_reads: dict[tuple[str, int], list[str]] = {}
    param_writes: set[tuple[str, int]] = set()
    changed = True
    while changed:
        changed = False
        for prog, (use, params, _locals) in uses.items():
            for k, p in enumerate(params):
                reads = list(use.reads.get(p, []))
                writes = p in use.writes
                for callee, args, _where in use.calls:
                    if callee not in uses:
                        continue
                    for j, a in enumerate(args):
                        if a == p:
                            reads += param_reads.get((callee, j), [])
                            writes = writes or (callee, j) in param_writes
                if reads and param_reads.get((prog, k)) != reads:
                    param_reads[(prog, k)] = reads
                    changed = True
                if writes and (prog, k) not in param_writes:
                    param_writes.add((prog, k))
                    changed = True
    reads: dict[str, list[str]] = {}
    writes: set[str] = set()
    library: dict[str, str] = {}
    indices: dict[str, set[int] | None] = {}
    for prog, (use, params, local_names) in uses.items():
        own = set(params) | local_names

        def visible(name: str) -> bool:
            return name not in own  # noqa: B023

        for name, where in use.reads.items():
            if visible(name):
                reads.setdefault(name, []).extend(where)
                got = use.indices.get(name)
                if name in indices and indices[name] is None or got is None:
                    indices[name] = None
                else:
                    indices.setdefault(name, set()).update(got)
        writes |= {n for n in use.writes if visible(n)}
        library.update({n: lib for n, lib in use.to_library.items() if visible(n)})
        for callee, args, where in use.calls:
            for j, a in enumerate(args):
                if a is None or not visible(a):
                    continue
                if callee not in uses:
                    continue
                if (callee, j) in param_reads:
                    reads.setdefault(a, []).append(where)
                    indices[a] = None
                if (callee, j) in param_writes:
                    writes.add(a)
    return reads, writes, library, indices


def _toml(value) -> str:  # noqa: ANN001
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, datetime.datetime):
        return value.isoformat()
    if isinstance(value, (int, float)):
        return repr(float(value)) if isinstance(value, float) and not value.is_integer() else f"{value:g}"
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{json.dumps(str(k), ensure_ascii=False)} = {_toml(v)}" for k, v in value.items()) + " }"
    raise TypeError(value)


def _places(where: list[str], limit: int = 3) -> str:
    unique = list(dict.fromkeys(where))
    return ", ".join(unique[:limit]) + (f" and {len(unique) - limit} more" if len(unique) > limit else "")


def _signals(app: Application, name: str, indices: set[int] | None) -> tuple[list[tuple[str, str]], list[str]]:
    """(scenario name, link) of the elements of global `name` that may be driven, and the
    elements left out because the data file links them to nothing."""
    data = app.data[name]
    links = {v.key: (v.fields.get("link") or "") for v in data.values}
    size = 1
    for s in data.sizes or (1,):
        size *= s
    wanted = sorted(indices) if indices is not None else range(min(size, 64))
    ok, unlinked = [], []
    for i in wanted:
        if not 0 <= i < size:
            continue
        label = name if size == 1 else f"{name}[{i}]"
        link = links.get(str(i), "")
        (ok if link else unlinked).append((label, link) if link else label)
    return ok, unlinked


def skeleton(workspace: Workspace, app: Application, app_label: str) -> str:
    """The text of a scenario skeleton for `app` (its programs parsed)."""
    reads, writes, library, indices = _globals_used(app)
    globals_ = {n.lower(): n for n in app.data}
    uses = _program_uses(app)
    out = [
        f"# Scenario skeleton for {app_label}, written by `val3check sim --init-scenario`",
        "# (docs/scenario.md). What the application reads or waits on, found in its code, with the",
        "# defaults: as written the run is the same as without a scenario. Edit the values, add [[events]] and",
        "# [[reactions]], and uncomment the key presses and serial data the run needs.",
        "version = 1",
        f"description = {_toml('scenario of ' + app.name)}",
        "",
        "[inputs]                           # values at time 0",
    ]
    comments: list[str] = []
    serial: list[str] = []
    for low in sorted(reads, key=lambda n: globals_.get(n, n)):
        name = globals_.get(low)
        if name is None:
            continue
        data = app.data[name]
        kind = data.type.lower()
        if kind not in ("dio", "aio", "sio"):
            continue
        where = _places(reads[low])
        if kind == "sio":
            serial.append(f"{name} (read at {where})")
            continue
        default = "false" if kind == "dio" else "0"
        ok, unlinked = _signals(app, name, indices.get(low))
        why = ("written by the program too" if low in writes else
               f"handed to {library[low]}, which may write it" if low in library else None)
        for label, link in ok:
            line = f"{_toml(label) if '[' in label else label} = {default}"
            note = f"# {kind} {link}, read at {where}"
            if why:
                comments.append(f"# {line}   {note}; not an input: {why}")
            else:
                out.append(f"{line:<34} {note}")
        for label in unlinked:
            comments.append(f"# {label}: read at {where}, but linked to no input in the data file (error 123 when used)")
    if comments:
        out.append("")
        out += comments
    out += ["", "# [[events]]                       # inputs that change at given times",
            "# at = 1.0", "# set = { diSignal = true }", ""]
    keys = [(k, w, c) for use, _p, _l in uses.values() for (k, w, c) in use.keys]
    for kind, where, code in sorted(keys, key=lambda k: (k[1].rsplit(":", 1)[0], int(k[1].rsplit(":", 1)[1]))):
        out.append(f"# [[keys]]                         # {where}: "
                   + {"text": "get() of a text or a number", "get": "get() of a key",
                      "getkey": "getKey()", "iskeypressed": "isKeyPressed()"}[kind])
        out.append("# at = 1.0")
        if kind == "text":
            out.append('# text = ""                       # what the operator types, then Return (270)')
        else:
            out.append(f"# key = {code if code is not None else 271}")
        out.append("")
    opened: dict[str, tuple[str, list[str]]] = {}  # one entry per file of the disk, however it is spelt
    for use, _p, _l in uses.values():
        for path, where in use.files:
            key = disk_key(path)
            if key is not None:
                opened.setdefault(key, (path, []))[1].append(where)
    for key in sorted(opened):
        path, where = opened[key]
        note = f"{', '.join(where)}: $fileOpen of the controller's disk (docs/sim.md)"
        out += [f"# [[files]]                        # {note}", f"# path = {_toml(path)}", '# text = ""', ""]
    for what in serial:
        out += [f"# [[serial]]                       # {what}", f"# sio = {_toml(what.split(' ')[0])}",
                "# at = 1.0", '# send = ""', ""]
    reads_ctl: dict[str, list[str]] = {}
    asked: list[str] = []
    waits: list[tuple[str, str]] = []
    for use, _p, _l in uses.values():
        for k, where in use.controller.items():
            reads_ctl.setdefault(k, []).extend(where)
        asked += [v for v in use.versions if v not in asked]
        waits += use.state_waits
    if reads_ctl:
        defaults = Controller()
        known = default_versions(app.version, None)
        values = {
            "working_mode": defaults.working_mode, "working_state": defaults.working_state,
            "es_status": defaults.es_status, "powered": defaults.powered,
            "power_delay": defaults.power_delay_us / 1_000_000, "calibrated": defaults.calibrated,
            "monitor_speed": defaults.monitor_speed, "operator_speed": defaults.operator_speed,
            "safety_fault": defaults.safety_fault, "profile": defaults.profile, "profiles": defaults.profiles,
            "language": defaults.language, "languages": list(defaults.languages), "date": defaults.date,
            # the components the application asks for by name, as getVersion answers them (8.1)
            "versions": {v: known.get(v, "") for v in asked} if asked else known,
        }
        out.append("[controller]                       # chapter 8 state the application reads (defaults)")
        for key in CONTROLLER_ORDER:
            if key in reads_ctl:
                out.append(f"{key + ' = ' + _toml(values[key]):<34} # {_places(reads_ctl[key])}")
        for key, where in sorted(set(waits), key=lambda kw: (kw[1].rsplit(":", 1)[0], int(kw[1].rsplit(":", 1)[1]))):
            out.append(f"# changes = [ {{ at = 1.0, {key} = {_toml(values[key])} }} ]   # {where}: a wait() only a "
                       f"change of {key} ends")
        out.append("")
    return "\n".join(out).rstrip("\n") + "\n"
