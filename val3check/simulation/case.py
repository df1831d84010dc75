"""One case of `val3check sim`: an application with its settings, arm, scenario, cell and options
in, an outcome out (issue 22). `val3check sim` (cli.py) and a batch's worker (batch/worker.py)
both run their case here, so that a case of a batch is the single run, step by step:

    outcome = run_case(CaseSpec("apps/PickPlace", settings, robot="tx2-60", scenario="nominal.toml"))

the application is linted in-process and picked among the applications found; an application
with lint errors or without start() is refused; then the arm (`--robot`), the scenario (and a
batch's monitor speed), the cell (`--cell`, or the file beside the application), the run. The
callers word the refusals for their readers and build the report (reporting/ sits above this
layer): the outcome says which step refused the case and with what.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable
from typing import Any

from ..diagnostics import Severity
from ..light_dataclass import dataclass, field
from .robot_choice import choose_sim_robot

Say = Callable[[str], None]  # a note for the user (the single run prints it on standard error)


@dataclass
class CaseSpec:
    app: str  # the application as given: its .pjx or folder
    settings: Any  # config.Settings, the command line's options applied
    robot: str | None = None  # --robot: a name, URDF, arm.cfx, robot file or "none"; None: the tree's arm.cfx
    scenario: str | None = None  # the scenario file, as messages show it
    cell: str | None = None  # --cell: a file or "none"; None: val3check-cell.toml beside the application
    monitor_speed: float | None = None  # a batch's override, as the scenario's [controller] monitor_speed
    duration: float = 60.0
    cycles: int | None = None
    max_wall: float = 60.0
    max_lines: int = 50_000_000
    max_memory_mb: float = 512.0
    progress: Callable[[], Any] | None = None  # makes the progress display (None off a terminal), closed at the end
    exact: bool = False  # `app` is the exact path of one application found (a batch's case)
    step: Say | None = None  # told each step as it starts ("lint", "run"): a batch's watchdog times them


# Why a case is not run: the step that refused it.
UNREADABLE, SEVERAL, LINT_ERRORS, NO_START, ROBOT, SCENARIO = (
    "unreadable", "several", "lint-errors", "no-start", "robot", "scenario")


@dataclass
class CaseOutcome:
    refused: str | None  # None: the case ran; else one of the steps above
    message: str = ""  # why it was refused, for the user
    lint: Any = None  # lint.LintRun
    app: Any = None  # loading.model.Application
    errors: list = field(default_factory=list)  # the lint errors that keep it from running
    model: Any = None  # the arm model run (robot.RobotModel) or None
    result: Any = None  # SimResult when it ran


def lint_case(spec: CaseSpec, say: Say | None = None) -> CaseOutcome:
    """The first steps: lint, pick the application, refuse it with errors. `refused` is None when
    the application may run (`--init-scenario` stops here)."""
    from ..lint import run

    if spec.step is not None:
        spec.step("lint")
    outcome = run([spec.app], spec.settings)
    apps = [outcome.workspace.apps[k] for k in outcome.workspace.targets]
    if spec.exact:
        apps = [a for a in apps if os.path.normcase(a.path) == os.path.normcase(spec.app)]
    if outcome.unreadable or not apps:
        return CaseOutcome(UNREADABLE, lint=outcome, errors=_errors(outcome))
    if len(apps) != 1:
        app, message = _app_of_folder(spec.app, apps)
        if app is None:
            return CaseOutcome(SEVERAL, message, lint=outcome)
        if say is not None:
            say(message)
        apps = [app]
    errors = _errors(outcome)
    if errors:
        return CaseOutcome(LINT_ERRORS, lint=outcome, app=apps[0], errors=errors)
    return CaseOutcome(None, lint=outcome, app=apps[0])


def run_case(spec: CaseSpec, say: Say | None = None) -> CaseOutcome:
    """Every step; the outcome holds the run's SimResult, or the step that refused the case."""
    from ..robot import RobotError
    from .collision_run import choose_cell
    from .run import SimOptions, simulate
    from .scenario import Scenario, ScenarioError, load_scenario

    started = time.monotonic()  # --max-wall covers the lint, the arm and the cell too
    case = lint_case(spec, say)
    if case.refused is not None:
        return case
    app = case.app
    if not any(n.lower() == "start" for n in app.programs):
        return _refused(case, NO_START, f"{app.name} has no start() program (2.1.2)")
    if spec.step is not None:
        spec.step("run")
    try:
        robot, note = choose_sim_robot(spec.robot, app.path)
    except RobotError as exc:
        return _refused(case, ROBOT, str(exc))
    case.model = robot
    if note and say is not None:
        say(note)
    try:
        scenario = load_scenario(spec.scenario) if spec.scenario else None
        if spec.monitor_speed is not None:
            scenario = scenario or Scenario("", "", {})
            scenario.data = {**scenario.data, "controller": {**scenario.data.get("controller", {}),
                                                             "monitor_speed": spec.monitor_speed}}
        cell, cell_found = choose_cell(spec.cell, app.path)
        progress = spec.progress() if spec.progress is not None else None
        options = SimOptions(duration=spec.duration, max_wall=spec.max_wall, max_lines=spec.max_lines,
                             max_memory_mb=spec.max_memory_mb, disk_roots=list(spec.settings.disk_roots),
                             robot=robot, cycles=spec.cycles, progress=progress, collisions=True, cell=cell,
                             cell_found=cell_found, started=started, reports_in_budget=True)
        try:
            case.result = simulate(case.lint.workspace, app, options, scenario)
        finally:
            if progress is not None:
                progress.close()
    except ScenarioError as exc:
        return _refused(case, SCENARIO, str(exc))
    return case


def _refused(case: CaseOutcome, step: str, message: str) -> CaseOutcome:
    case.refused, case.message = step, message
    return case


def _errors(outcome) -> list:  # noqa: ANN001 - lint.LintRun
    return [d for d in outcome.result.diagnostics if d.severity is not None and d.severity >= Severity.ERROR]


def _app_of_folder(folder: str, apps: list) -> tuple[Any, str]:
    """`sim DIR` where DIR holds its own .pjx and its libraries in sub-folders: the application of
    DIR itself (`DIR/DIR.pjx`, or the only .pjx in DIR), as a controller's usr/usrapp/DIR would be
    loaded, with a note; else (None, why)."""
    from ..lint import printable_path
    from ..loading.resolve import project_in_folder

    main = project_in_folder(folder) if os.path.isdir(folder) else None
    chosen = [a for a in apps if main is not None and os.path.normcase(a.path) == os.path.normcase(main)]
    shown = printable_path(folder)
    if not chosen:
        names = ", ".join(printable_path(os.path.relpath(a.path)) for a in apps[:8]) + (", ..." if len(apps) > 8 else "")
        return None, (f"{shown} holds {len(apps)} applications ({names}); name one of them, or run them all as a"
                      f" batch: val3check sim {shown} -j {os.cpu_count() or 1} (docs/batch.md)")
    return chosen[0], (f"{shown} holds {len(apps)} applications; running"
                       f" {printable_path(os.path.relpath(chosen[0].path))}, the one named after the folder")
