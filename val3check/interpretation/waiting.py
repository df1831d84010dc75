"""How a task waits or hands over (5.4, 5.10): the blocking primitives of every chapter.

They are generators used with `yield from` by the generated code and by blocking
instructions. A task that waits for a condition (`wait`, `watch`, a key, data on a sio, the end
of motion) does not poll it: the scheduler evaluates `task.cond` itself once per cycle and
resumes the task only when it is true (or at a watch's timeout), and the clock jumps to the
next time anything can change (a subsystem's next event, a delay's end). `task.waiting_for`
says in a few words what the task waits for: the deadlock report (R003) and the report's task
list show it.
"""

from __future__ import annotations

from .scheduler import TaskState

_YIELD = TaskState.YIELD
_DELAY = TaskState.DELAY
_WAIT = TaskState.WAIT


def YIELD(task):
    """Hand over to the next task (5.4)."""
    task.state = _YIELD
    yield


def DELAY(task, s: float, what: str = "delay"):
    """5.10 delay: the task waits `s` seconds; 0 or less hands over to the next task."""
    if not s > 0:
        task.state = _YIELD
        yield
        return
    task.wake = task.clock.wake_time(task, s)
    task.state = _DELAY
    task.waiting_for = what
    yield
    task.wake = None
    task.waiting_for = ""


def WAIT(task, fn, tdep: bool, what: str = "wait", hint: str = "", reads: frozenset = frozenset()):
    """5.10 wait: the condition is evaluated again at each turn; no hand-over when it is
    already true. While it waits, the scheduler evaluates `task.cond` itself and resumes the
    task only when it is true (with True), or with None when it raised (evaluated again here,
    so that the error stops the task at its line). `tdep`: the condition changes with time
    alone (clock()), so the clock steps cycle by cycle instead of jumping. For the deadlock
    report (deadlock.py): `hint` says which part of the cell would make the condition true and
    the scenario entry that plays it (a wait only the cell can end); `reads` are the globals the
    condition reads (`alias:name` for a library's)."""
    if fn():
        return
    if hint:
        fn.hint = hint
    if reads:
        fn.reads = reads
    task.tdep = tdep
    task.wake = None
    task.cond = fn
    task.waiting_for = what
    while True:
        task.state = _WAIT
        ok = yield
        if ok or fn():
            break
    task.cond = None
    task.tdep = False
    task.waiting_for = ""


def WATCH(task, fn, s: float, tdep: bool, what: str = "watch"):
    """5.10 watch: wait for the condition at most `s` seconds; true if it became true."""
    if fn():
        return True
    machine = task.machine
    task.tdep = tdep
    task.wake = machine.clock.wake_time(task, s) if s > 0 else machine.clock.now
    task.cond = fn
    task.waiting_for = what
    result = False
    while True:
        task.state = _WAIT
        ok = yield
        if ok or fn():
            result = True
            break
        if machine.clock.now >= task.wake:
            break
    task.cond = None
    task.wake = None
    task.tdep = False
    task.waiting_for = ""
    return result


def SETMUTEX(task, pair, name: str = ""):
    """5.10 setMutex: wait until the bool is false, then set it true (`name`: the global)."""
    c, k = pair
    if c[k]:
        yield from WAIT(task, lambda: not c[k], False, "setMutex", reads=frozenset((name,)) if name else frozenset())
    c[k] = True


def register(registry) -> None:
    registry.helpers(YIELD=YIELD, DELAY=DELAY, WAIT=WAIT, WATCH=WATCH, SETMUTEX=SETMUTEX)
