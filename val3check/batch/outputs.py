"""What a case writes under --out-dir, rendered where the case ran (the run's objects stay
there; bytes travel back). The one place to add a per-case output: a line per format."""

from __future__ import annotations


def case_outputs(report) -> dict[str, bytes]:  # noqa: ANN001 - reporting.sim_report.SimReport
    """File suffix -> bytes of the case's reports. Today the JSON run report
    (docs/sim-report.md); the HTML report and the MCAP trace go here when `sim` has them."""
    from ..reporting.sim_json import render

    return {".json": render(report).encode("utf-8")}
