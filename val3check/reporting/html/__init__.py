"""The HTML report of a simulation run (docs/html-report.md).

    from val3check.reporting.html import render, check_model

    model = model_from_run(report)              # the model of a run (from_run.py)
    html = render(model)                         # one self-contained page

`render(model) -> str` checks the model (`check_model`, ModelError with the key at fault) and
returns the page (a scripted pick-and-place model for the tests is `tests/synthetic_run.py`);
`model_from_sim_report` builds a model from the JSON report of a run and the arm and cell it names, rebuilt
by `simulation.report_scene.ReportScene` (`val3check html --sim-report`). The arm's chain of the 3D view is read by
`val3check.robot.chain.arm_chain` (a run publishes it in its record of the scene). The names are
imported when first used, so that the page of a run (from_run.py) loads nothing else.
"""

from __future__ import annotations

from importlib import import_module
from typing import Any

_EXPORTS = {"VERSION": "model", "ModelError": "model", "check_model": "model", "render": "page",
            "model_from_sim_report": "from_sim"}

__all__ = ["ModelError", "VERSION", "check_model", "model_from_sim_report", "render"]


def __getattr__(name: str) -> Any:
    """The module's names, imported from their module when first used."""
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    return getattr(import_module(f"{__name__}.{module}"), name)
