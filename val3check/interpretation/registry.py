"""Where an instruction is registered: the table of what the virtual controller can run.

One module per chapter of the manual registers its instructions with an explicit call,
`register(registry)` (interpretation/chapters/, simulation/ch10_motion.py); `val3check.simulation`
makes the calls when it assembles a run. Nothing registers on import.

A registry holds:
- instruction handlers: `I(task, unit, *args)` by lower-case VAL 3 name, called with the
  arguments compiled for the catalogue's parameters (references as (container, key) pairs,
  arrays as `Arr`); `blocking` ones are generators (`yield from`: they may hand over, 5.4);
- the pure built-ins (`builtins/`: math, bit fields, strings);
- the inline forms: instructions the compiler writes itself because their arguments are not
  plain values (`size(x)` of any variable, `wait(cond)` re-evaluated...);
- the helpers the generated code calls by name (`IX`, `WAIT`, `TRSF`...).

A catalogue instruction with none of these stops the task with a "not simulated" diagnostic,
decided in one place, `not_simulated_kind`: R002 when it moves the arm, reads its motion or
needs its hardware, R004 otherwise.
"""

from __future__ import annotations

from typing import Any, Callable

from ..language import lookup
from ..light_dataclass import dataclass  # (frozen record classes made without dataclasses' cost)
from .not_simulated import ARM_LIMIT, OTHER_LIMIT, limit_code

# Options of chapter 11 that drive the arm (compliance, alter, absolute robot, continuous
# axis); the latch of 9.2.3 needs the arm's position capture hardware.
ARM_OPTIONS = frozenset({"compliance", "alter", "absoluteRobot", "continuousAxis"})
ARM_HARDWARE = frozenset({"setlatch", "getlatch"})


@dataclass(frozen=True, slots=True)
class Handler:
    name: str  # lower-case VAL 3 name
    func: Callable[..., Any]
    blocking: bool  # a generator: the generated code calls it with `yield from`
    chapter: str  # the module that registered it
    # `raw`: the instruction's parameters are not public (an s8 instruction known from calls):
    # the handler gets the call's text, `I(task, unit, text, used)`, and its arguments are not
    # evaluated; `used` is the type its value is used as ("" when it is a statement)
    raw: bool = False


@dataclass(frozen=True, slots=True)
class SystemHandler:
    """A `$name()` instruction of the system library (undocumented: not in the manual) that the
    simulator runs. `params` says how each argument is passed: "value", "ref" (a (container,
    key) pair) or "array" (an `Arr`); `returns` the type of its value ("void": none)."""

    name: str  # as written, with its `$`
    func: Callable[..., Any]
    params: tuple[str, ...]
    returns: str
    blocking: bool
    chapter: str


@dataclass(frozen=True, slots=True)
class Status:
    """How the simulator runs a catalogue instruction (for the documentation and the tests)."""

    implemented: bool
    how: str  # "handler", "builtin", "inline", or the rule of the not-simulated diagnostic


class RegistryError(Exception):
    pass


class Registry:
    def __init__(self) -> None:
        self._handlers: dict[str, Handler] = {}
        self._builtins: dict[str, Any] = {}
        self._inline: dict[str, str] = {}
        self._helpers: dict[str, Any] = {}
        self._system: dict[str, SystemHandler] = {}

    # ---- registration (chapter modules) ---------------------------------------------------------

    def instruction(self, name: str, func: Callable[..., Any], *, blocking: bool = False, chapter: str = "",
                    raw: bool = False) -> None:
        low = name.lower()
        self._claim(low, name)
        self._handlers[low] = Handler(low, func, blocking, chapter or func.__module__, raw)

    def system(self, name: str, func: Callable[..., Any], params: tuple[str, ...] = (), returns: str = "void", *,
               blocking: bool = False, chapter: str = "") -> None:
        """A `$name()` system instruction the simulator runs (SystemHandler). A `$` call nothing
        registers goes on with an info (R041), not_simulated.SYSTEM."""
        if not name.startswith("$") or name.lower() in self._system:
            raise RegistryError(f"system instruction {name} is registered twice or has no $")
        self._system[name.lower()] = SystemHandler(name, func, tuple(params), returns, blocking,
                                                   chapter or func.__module__)

    def builtin(self, entry: Any) -> None:
        """A pure built-in (`builtins.Builtin`). The catalogue may give the same name to an
        inline form of another shape (insert, delete: 2.5.4 and 3.4.3); the compiler chooses."""
        low = entry.name.lower()
        if low in self._builtins or low in self._handlers:
            raise RegistryError(f"{entry.name} is registered twice")
        self._builtins[low] = entry

    def inline(self, *names: str, chapter: str = "") -> None:
        """Instructions the compiler writes itself (compiler/calls.py INLINE_FORMS)."""
        for name in names:
            low = name.lower()
            if low in self._handlers or low in self._inline:
                raise RegistryError(f"{name} is registered twice")
            self._inline[low] = chapter

    def helpers(self, **named: Any) -> None:
        """Names the generated code calls (compiler/)."""
        for name, obj in named.items():
            if name in self._helpers and self._helpers[name] is not obj:
                raise RegistryError(f"helper {name} is registered twice")
            self._helpers[name] = obj

    def _claim(self, low: str, name: str) -> None:
        if low in self._handlers or low in self._inline:
            raise RegistryError(f"instruction {name} is registered twice")

    # ---- lookups (compiler) ---------------------------------------------------------------------

    def handler(self, name: str) -> Handler | None:
        return self._handlers.get(name.lower())

    def system_handler(self, name: str) -> SystemHandler | None:
        return self._system.get(name.lower())

    def system_names(self) -> list[str]:
        """The `$` instructions the simulator runs, as written (docs, tests)."""
        return sorted((h.name for h in self._system.values()), key=str.lower)

    def builtin_of(self, name: str) -> Any | None:
        return self._builtins.get(name.lower())

    def is_inline(self, name: str) -> bool:
        return name.lower() in self._inline

    def inline_names(self) -> frozenset[str]:
        return frozenset(self._inline)

    @staticmethod
    def not_simulated_kind(name: str) -> str:
        """The diagnostic of a catalogue instruction nothing simulates: ARM_LIMIT (R002) for what
        moves the arm, reads its motion or needs its hardware (chapter 10, the arm options of
        chapter 11, the latch), OTHER_LIMIT (R004) for the rest (getLicence...)."""
        ins = lookup(name)
        if ins is None:
            return OTHER_LIMIT
        chapter = ins.section.split(".")[0]
        if chapter == "10" or ins.option in ARM_OPTIONS or ins.name.lower() in ARM_HARDWARE:
            return ARM_LIMIT
        return OTHER_LIMIT

    def status(self, name: str) -> Status:
        low = name.lower()
        if low in self._handlers:
            return Status(True, "handler")
        if low in self._inline:
            return Status(True, "inline")
        if low in self._builtins:
            return Status(True, "builtin")
        return Status(False, limit_code(self.not_simulated_kind(low)))

    def namespace(self) -> dict[str, Any]:
        """The names the generated code finds: helpers, `I_<name>` handlers, `B_<name>` built-ins."""
        ns: dict[str, Any] = dict(self._helpers)
        for low, h in self._handlers.items():
            ns[f"I_{low}"] = h.func
        for h in sorted(self._system):
            ns[system_symbol(h)] = self._system[h].func
        for low, b in self._builtins.items():
            plain = not b.outputs and not any(p.endswith("[]") for p in b.params)
            ns[f"B_{low}"] = b.func if plain else b
        return ns


def system_symbol(name: str) -> str:
    """The name of a `$name()` handler in the generated code."""
    return "S_" + "".join(c if c.isalnum() else "_" for c in name.lower().lstrip("$"))
