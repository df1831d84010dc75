"""The run's wall-clock and memory budgets after the simulation: they cover every phase of a run
(docs/performance.md, "Long runs").

The simulation ends at RUN_SHARE of --max-wall (Budgets.run_share); the rest is kept for what
follows it: the collision checks stop when the whole budget is spent (R037), and the report
writers then leave out what grows with the run (the trajectory, the trace's arm messages) and say
so. What is left to do then is bounded by design (reporting/thinning.py, simulation/folding.py),
so the command overshoots --max-wall by at most that: writing tables of bounded size.

    budget = RunBudget.of(machine)
    why = budget.spent()        # None, or what was spent ("the wall-clock budget (--max-wall 60 s)")
"""

from __future__ import annotations

from collections.abc import Callable
from copy import copy
from dataclasses import dataclass
from typing import Any

RUN_SHARE = 0.75  # of --max-wall for the simulation; the checks and reports have the rest
WALL = "the wall-clock budget"


@dataclass
class RunBudget:
    wall_clock: Callable[[], float]
    deadline: float  # on wall_clock: the end of --max-wall, counted from the start of the run
    max_wall: float
    memory: Any = None  # interpretation.memory_budget.MemoryBudget: --max-memory

    @classmethod
    def of(cls, machine: Any) -> RunBudget:
        """The budgets of the run of `machine` (interpretation.machine.Machine)."""
        b = machine.budgets
        memory = machine.cell.budget
        if memory is not None:  # without its clock, a method of the machine: the reports must not
            memory = copy(memory)  # keep the finished run's machine (its queue, every command) alive
            memory.clock = None
        return cls(b.wall_clock, machine.wall_start + b.wall_s, b.wall_s, memory)

    def out_of_time(self) -> bool:
        """--max-wall is spent."""
        return self.wall_clock() > self.deadline

    def spent(self) -> str | None:
        """What is spent, as a clause ("the wall-clock budget (--max-wall 60 s) is spent"), None
        while both budgets hold."""
        if self.out_of_time():
            return f"{WALL} (--max-wall {self.max_wall:g} s) is spent"
        over = self.memory.over() if self.memory is not None else None
        return over

