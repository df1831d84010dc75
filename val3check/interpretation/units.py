"""A loaded application: the started one or a library (chapter 6), with its globals (from its
data file, or a libSave snapshot) and its compiled programs."""

from __future__ import annotations

from typing import Any

from ..loading.model import Application, Container
from ..parsing.parser import parse_program
from ..semantics.checker import expression_types
from .compiler import Compiled, compile_program
from .memory import resolve_fathers
from .system_io import is_system_io
from .values import Arr, Screen, copy_globals


class Unit:
    _count = 0

    def __init__(self, machine, model: Application, disk_path: str) -> None:
        Unit._count += 1
        self.uid = Unit._count
        self.machine = machine
        self.model = model
        self.disk_path = disk_path
        self.space = machine.space_for(model)
        self.aliases: dict[str, Any] = {a: None for a in model.libraries}
        for a in model.libraries:  # the controller's own I/O library is always there (io:...)
            if is_system_io(model, a, machine.ws):
                self.aliases[a] = machine.system_io_for(model, a)
        self.globals: dict[str, Any] = {}
        self.programs: dict[str, Compiled] = {}
        self.ns: dict[str, Any] = {}
        self.compile_errors: list = []
        self.expression_types: dict = {}
        self.parse_findings: list = []  # syntax errors of its programs (F101...)
        self.load_failures: dict[str, str] = {}  # alias -> why its library could not be loaded

    @property
    def name(self) -> str:
        return self.model.name

    def init_globals(self, saved: dict[str, Any] | None = None) -> None:
        restored = copy_globals({n: saved[n] for n in self.model.data if n in saved}) if saved is not None else {}
        self.space.reserve_globals(d for n, d in self.model.data.items() if n not in restored)
        cell = self.machine.cell
        cell.pending = []
        for name, d in self.model.data.items():
            if name in restored:
                self.globals[name] = restored[name]
            else:
                self.globals[name] = self.space.container(d)
        # frames, tools and points of the data file: linked to their fatherId (9.4.1)
        resolve_fathers(cell, self.globals)
        for name in self.model.data:
            c = self.globals[name]
            if type(c) is Arr and c.t == "screen":  # the transcript names a screen by its variable
                for i, scr in enumerate(c.data):
                    if type(scr) is Screen and not scr.name:
                        scr.name = name if len(c.data) == 1 else f"{name}[{i}]"

    def build(self) -> None:
        """Compile every program into the unit's namespace (the machine's base namespace plus
        the unit's globals: `g_name` its container, `d_name` the values of an array)."""
        machine = self.machine
        ns = dict(machine.base_namespace)
        ns["A"] = self
        space = self.space
        cell = machine.cell
        # the compiled code's defaults are those of locals (no reference frame/tool, 9.4.1)
        ns["DEFAULT"] = lambda t, name="": space.default(t, True, name)
        ns["LOCAL"] = self._local
        ns["IODEF"] = lambda link: cell.io("dio", link)
        for name, c in self.globals.items():
            ns[f"g_{name}"] = c
            if type(c) is Arr:
                ns[f"d_{name}"] = c.data
        self.ns = ns
        for prog in self.model.programs.values():
            machine.check_load_budgets()
            if prog.body is None and prog.code is not None:
                self.parse_findings.extend(parse_program(prog))
        # the compiler reads the types semantic analysis computes (lint's checks)
        self.expression_types = expression_types(machine.ws, self.model)
        for prog in self.model.programs.values():
            compiled = compile_program(self, prog, ns)
            self.programs[prog.name] = compiled
            machine.compiled[compiled.filename] = compiled
            if compiled.error is not None:
                self.compile_errors.append(compiled)

    def _local(self, t: str, cont: str, sizes: tuple, name: str = "") -> Any:
        return self.space.local_container(t, Container.COLLECTION if cont == "COLLECTION" else Container.ARRAY, sizes,
                                          name)

    def program(self, name: str) -> Compiled | None:
        p = self.programs.get(name)
        if p is None:
            low = name.lower()
            p = next((c for n, c in self.programs.items() if n.lower() == low), None)
        return p

    def public_program(self, name: str) -> Compiled | None:
        p = self.program(name)
        if p is None:
            return None
        model = self.model.programs.get(p.name)
        return p if model is not None and model.access != "private" else None

    def public_global(self, name: str) -> Any:
        d = self.model.data.get(name)
        if d is None or d.access == "private":
            return None
        return self.globals.get(name)
