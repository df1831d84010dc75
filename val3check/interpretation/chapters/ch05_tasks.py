"""Chapter 5: tasks (5.10): taskCreate, taskCreateSync, taskSuspend, taskResume, taskKill,
taskStatus, help, delay, clock, wait, watch, setMutex.

The scheduler (scheduler.py) owns the tasks; these instructions ask it. `wait`, `watch` and
`setMutex` take a condition or a variable, not values: the compiler writes them itself with the
primitives of waiting.py; taskCreate is a statement of its own (2.2.5).
"""

from __future__ import annotations

import math
from typing import Any

from ...language.runtime_errors import RUNTIME_CODES, Val3RuntimeError
from ..clock import TICK_US
from ..scheduler import SYNC_LINES
from ..values import clip_string
from ..waiting import DELAY, YIELD

E = Val3RuntimeError


def _int(v: float) -> int:
    return int(math.floor(v + 0.5))


def _compiled(task, func):
    """The compiled program behind a program function."""
    c = task.machine.compiled.get(func.__code__.co_filename)
    if c is None:  # pragma: no cover - every program function comes from compile_program
        raise E(61, f"unknown program {func.__name__}")
    return c


def TASKCREATE(task, unit, name: Any, prio: float, func, args: tuple, pname: str) -> None:
    """5.10 taskCreate: priority 1..100 (70 otherwise), name rules (29), unique (31)."""
    p = int(prio + 0.5) if prio >= 0 else -1
    if not 1 <= p <= 100:
        raise E(70, f"priority {prio!r} not in 1..100")
    task.machine.scheduler.create(task, unit, name, _compiled(task, func).func, args, p, 0, pname)


def TASKCREATESYNC(task, unit, name: Any, period: float, overrun, func, args: tuple, pname: str) -> None:
    """5.10 taskCreateSync, nPériode: "La valeur indiquée est arrondie au multiple de 4 ms
    immédiatement inférieur (0.004 seconde). Le système accepte toutes les durées positives, mais
    pas plus de deux durées différentes de tâches synchrones à la fois." A positive period below
    4 ms is accepted: nothing runs more often than the 4 ms cycle, so the task runs once per
    cycle (5.5: "séquencée exactement une fois pour chaque période"). A period that is not
    positive is an invalid parameter (70); a third period is 32."""
    if not period > 0:
        raise E(70, f"period {period!r}: the period of a synchronous task must be positive")
    ticks = max(1, int(period * 1_000_000 + 1e-6) // TICK_US)
    period_us = ticks * TICK_US
    scheduler = task.machine.scheduler
    live = {t.period for t in scheduler.tasks if t.period}
    if period_us not in live and len(live) >= 2:
        raise E(32, "only two different periods of synchronous tasks")
    new = scheduler.create(task, unit, name, _compiled(task, func).func, args, SYNC_LINES, period_us, pname)
    new.overrun = overrun
    new.next_run = (scheduler.clock.time_of(task) // TICK_US + 1) * TICK_US


def I_tasksuspend(task, unit, name: str):
    """5.10 taskSuspend: error 30 when no task of this name is visible (5.3)."""
    scheduler = task.machine.scheduler
    target = scheduler.find(unit, name)
    if target is None:
        raise E(30, f'no task "{name}"')
    scheduler.suspend(target)
    if target is task:
        yield


def I_taskresume(task, unit, name: str, jump: float):
    """5.10 taskResume: restart a STOPPED task `jump` lines from where it stopped."""
    scheduler = task.machine.scheduler
    target = scheduler.find(unit, name)
    if target is None:
        raise E(30, f'no task "{name}"')
    scheduler.resume(target, _int(jump))
    yield from YIELD(task)


def I_taskkill(task, unit, name: str):
    """5.10 taskKill: no effect when no such task is visible."""
    scheduler = task.machine.scheduler
    target = scheduler.find(unit, name)
    if target is None:
        return
    scheduler.kill(target, by=task)
    yield from YIELD(task)


def I_taskstatus(task, unit, name: str) -> float:
    scheduler = task.machine.scheduler
    target = scheduler.find(unit, name)
    if target is None:
        return -1.0
    return float(scheduler.status_code(target))


def help_text(code: float) -> str:
    n = int(code)
    extra = {-1: "no task of this name was created by this library or application",
             0: "the task is suspended without runtime error", 1: "the task is running"}
    return extra.get(n) or RUNTIME_CODES.get(n, "")


def I_help(task, unit, code: float) -> str:
    return clip_string(help_text(code))


def I_delay(task, unit, s: float):
    """5.10 delay: the waiting generator itself (the generated code's `yield from` runs it)."""
    return DELAY(task, s)


def I_clock(task, unit) -> float:
    """5.10 clock: seconds since the controller started, millisecond precision."""
    return round(task.machine.clock.time_of(task) / 1000.0) / 1000.0


def register(registry) -> None:
    registry.inline("taskCreate", "taskCreateSync", "wait", "watch", "setMutex", chapter=__name__)
    registry.helpers(TASKCREATE=TASKCREATE, TASKCREATESYNC=TASKCREATESYNC)
    for name, func in (("taskStatus", I_taskstatus), ("help", I_help), ("clock", I_clock)):
        registry.instruction(name, func)
    for name, func in (("taskSuspend", I_tasksuspend), ("taskResume", I_taskresume), ("taskKill", I_taskkill),
                       ("delay", I_delay)):
        registry.instruction(name, func, blocking=True)
