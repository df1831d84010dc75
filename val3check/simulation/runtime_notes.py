"""Findings a handler of the arm's instructions adds at the line running (chapters 9 and 11):
info and warning diagnostics with the simulated time and the task, said once per key when asked.

    note(task, "R050", "message", once="licences")   # a Diagnostic at the task's running line
"""

from __future__ import annotations

from ..diagnostics import Diagnostic


def where(task) -> tuple[str, int, int, str]:
    """(path, line, col, program) of the line the task is executing (the application when unknown)."""
    w = task.machine.line_running()
    if w is None:
        return task.machine.app.path, 0, 0, task.program
    return w


def note(task, code: str, message: str, *, once: str | None = None) -> None:
    """Add a runtime finding `code` at the task's running line; with `once`, only the first time
    the run says something under that key."""
    machine = task.machine
    if once is not None:
        said = machine.__dict__.setdefault("_said_once", set())
        if once in said:
            return
        said.add(once)
    path, line, col, program = where(task)
    machine.diags.append(Diagnostic(code, message, path, line, col, time_us=machine.clock.time_of(task),
                                    task=task.name, program=program))
