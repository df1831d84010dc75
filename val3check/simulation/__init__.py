"""`val3check sim`: assemble a run of the virtual controller (interpretation/, motion/),
run it, and hand its `SimResult` to the reports (reporting/).

- `case`          one case of `val3check sim` (lint, refuse, arm, scenario, cell, run): what
                  the command and a batch's worker both call;
- `run`           `simulate()`, `SimOptions`: the registry of instructions, the arm, the
                  machine and its subsystems, the scenario;
- `scenario`      the cell around the application (docs/scenario.md): read the file, then set
                  the cell's timeline, reactions, keys, controller and arm before the run;
- `moving_arm`    the arm of a run: the Arm port and a Subsystem over motion/'s queue;
                  `model_arm`: what every arm knows from its model, units, the arm that does
                  not move; `ch10_motion`: the instructions of chapter 10;
- `result`        `SimResult`, `TaskSummary`: what a run hands to the reports; `arm_record`:
                  the record of what the arm did and of the scene (the reports read only
                  these); `collect`: builds them from the machine when the run ends;
- `collision_run` the collision checks of a run, with the program's frames and tools;
- `robot_choice`  the arm model of the run (--robot, arm.cfx);
- `requirements`  the packages of the `sim` extra, checked before a run (importing it loads
                  nothing else: the names below are imported when first used).
"""

from __future__ import annotations

from importlib import import_module
from typing import Any

_EXPORTS = {"SimOptions": "run", "simulate": "run", "SimResult": "result", "TaskSummary": "result",
            "choose_sim_robot": "robot_choice"}

__all__ = sorted(_EXPORTS)


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    return getattr(import_module(f"{__name__}.{module}"), name)
