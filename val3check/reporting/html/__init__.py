"""The HTML report of a simulation run (docs/html-report.md).

    from val3check.reporting.html import render, arm_chain, synthetic_model, check_model

    model = synthetic_model(duration=60.0)       # or a model built from a run
    model["scene"]["arm"] = arm_chain("robots/tx2-60.urdf")
    html = render(model)                         # one self-contained page

`render(model) -> str` checks the model (`check_model`, ModelError with the key at fault) and
returns the page; `arm_chain(urdf, ...)` reads an arm's chain and solids for the 3D view;
`chain_fk(arm, joints)` is the same forward kinematics the page runs; `synthetic_model(...)`
gives a scripted pick-and-place run for tests and the demo
(`python -m val3check.reporting.html --demo -o demo.html`).
"""

from __future__ import annotations

from .arm import arm_chain, chain_fk
from .from_sim import model_from_sim_report
from .model import VERSION, ModelError, check_model
from .page import render
from .synthetic import synthetic_model

__all__ = ["VERSION", "ModelError", "arm_chain", "chain_fk", "check_model", "model_from_sim_report", "render",
           "synthetic_model"]
