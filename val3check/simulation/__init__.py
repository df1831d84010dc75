"""`val3check sim`: assemble a run of the virtual controller (interpretation/, motion/),
run it, and hand its `SimResult` to the reports (reporting/).

- `run`           `simulate()`, `SimOptions`: the registry of instructions, the arm, the
                  machine and its subsystems, the scenario;
- `result`        `SimResult`, `TaskSummary`: what a run hands to the reports;
- `scenario`      the cell around the application (docs/scenario.md): read the file, then set
                  the cell's timeline, reactions, keys, controller and arm before the run;
- `robot_choice`  the arm model of the run (--robot, arm.cfx);
- `requirements`  the packages of the `sim` extra, checked before a run.
"""

from .result import SimResult, TaskSummary
from .robot_choice import choose_sim_robot
from .run import SimOptions, simulate

__all__ = ["SimOptions", "SimResult", "TaskSummary", "choose_sim_robot", "simulate"]
