"""What a case writes under --out-dir, rendered where the case ran (the run's objects stay
there; bytes travel back). The one place to add a per-case output: a line per kind."""

from __future__ import annotations

import os
import tempfile

# --case-reports: kind -> file suffix. JSON always (the summary's data); the HTML page and the
# MCAP trace on demand: a 60 s run of the PickPlace cell renders its JSON in 0.08 s, its page in
# 0.17 s (1.4 MB) and its trace in 0.8 s (2.8 MB), more than the simulation itself.
KINDS = {"json": ".json", "html": ".html", "trace": ".mcap"}


def case_outputs(report, kinds: tuple[str, ...] = ("json",), fail_on: str = "error") -> dict[str, bytes]:  # noqa: ANN001
    """File suffix -> bytes of the case's reports (`report`: reporting.sim_report.SimReport),
    each as the single run writes it: `--report json`, `--report html`, `--trace`."""
    out: dict[str, bytes] = {}
    if "json" in kinds:
        from ..reporting.sim_json import render

        out[".json"] = render(report).encode("utf-8")
    if "html" in kinds:
        from ..reporting.html.from_run import render_run

        out[".html"] = render_run(report, fail_on=fail_on).encode("utf-8")
    if "trace" in kinds:
        from ..reporting.mcap_trace import write_trace

        fd, path = tempfile.mkstemp(suffix=".mcap")
        os.close(fd)
        try:
            write_trace(report, path)
            with open(path, "rb") as fh:
                out[".mcap"] = fh.read()
        finally:
            os.unlink(path)
    return out
