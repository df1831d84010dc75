"""Output formats of `val3check lint` (docs/output-formats.md).

Each format is a small module with `render(result, ...) -> str`, imported only when used so that
the command starts fast.
"""

from __future__ import annotations

from importlib import import_module

TYPE_CHECKING = False  # not typing's: importing typing costs 3 ms at lint's start-up
if TYPE_CHECKING:
    from ..result import LintResult

FORMATS = ("text", "concise", "json", "sarif", "junit", "github")  # `val3check lint --output-format`
SIM_FORMATS = ("text", "json", "html", "junit")  # `val3check sim --report`: sim_text, sim_json, html/from_run, sim_junit

_MODULES = {
    "text": "text",
    "concise": "text",
    "json": "json_format",
    "sarif": "sarif",
    "junit": "junit",
    "github": "github",
}


def render(fmt: str, result: "LintResult", *, color: bool = False, statistics: bool = False, quiet: bool = False,
           exit_code: int | None = None) -> str:
    """Render `result` in format `fmt` (one of FORMATS).

    `color` and `quiet` (findings only, no summary) affect `text` and `concise`; `statistics`
    (counts per rule) `text`, `concise` and `json`; `exit_code` (the run's, for SARIF's
    `invocations`) `sarif`. The returned string ends with a newline unless it is empty.
    """
    try:
        module_name = _MODULES[fmt]
    except KeyError:
        raise ValueError(f"unknown output format {fmt!r} (expected one of {', '.join(FORMATS)})") from None
    module = import_module(f"{__name__}.{module_name}")
    if fmt in ("text", "concise"):
        return module.render(result, color=color, statistics=statistics, quiet=quiet, concise=fmt == "concise")
    if fmt == "json":
        return module.render(result, statistics=statistics)
    if fmt == "sarif":
        return module.render(result, exit_code=exit_code)
    return module.render(result)
