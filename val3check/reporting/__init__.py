"""Output formats of `val3check lint` (docs/output-formats.md).

Each format is a small module with `render(result, ...) -> str`, imported only when used so that
the command starts fast.
"""

from __future__ import annotations

from importlib import import_module
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..result import LintResult

FORMATS = ("text", "json", "sarif", "junit", "github")  # `val3check lint --format`
SIM_FORMATS = ("text", "json")  # `val3check sim --report`: sim_text.py, sim_json.py

_MODULES = {
    "text": "text",
    "json": "json_format",
    "sarif": "sarif",
    "junit": "junit",
    "github": "github",
}


def render(fmt: str, result: "LintResult", *, color: bool = False, statistics: bool = False) -> str:
    """Render `result` in format `fmt` (one of FORMATS).

    `color` and `statistics` only affect the `text` format; the machine-readable formats ignore
    them. The returned string ends with a newline unless it is empty (`github` with no findings).
    """
    try:
        module_name = _MODULES[fmt]
    except KeyError:
        raise ValueError(f"unknown output format {fmt!r} (expected one of {', '.join(FORMATS)})") from None
    module = import_module(f"{__name__}.{module_name}")
    if fmt == "text":
        return module.render(result, color=color, statistics=statistics)
    return module.render(result)
