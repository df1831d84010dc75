"""The scenario's tables for chapter 11 and the cell the options act in (docs/scenario.md):
`[options]` (the runtime licences, 11.3), read by `scenario.Applier` after its own tables.

    apply_options(applier, data)      # applier: scenario.Applier (its lines, fail(), signal())
"""

from __future__ import annotations

from typing import Any

from .ch11_continuous import set_continuous
from .ch11_licences import OEM_STATES, OPTIONS, licences_of

TABLES = ("options",)


def apply_options(ap: Any, data: dict) -> None:
    """Read the chapter 11 tables of the scenario `data` into the run (`ap.machine`)."""
    if "options" in data:
        _options(ap, data["options"])


def _options(ap: Any, table: Any) -> None:
    """[options]: `alter = false`..., `oem = { Name = "enabled" | "demo" | "" | { state, password } }`."""
    line = ap.lines.section("options")
    if not isinstance(table, dict):
        ap.fail(line, "[options] must be a table: alter = true, compliance = false, oem = { MyLicence = \"enabled\" }")
    lic = licences_of(ap.machine)
    lic.given = True
    for key, value in table.items():
        ln = ap.lines.key(key, line) or line
        if key == "oem":
            lic.oem = _oem(ap, value, ln)
        elif key in OPTIONS:
            if not isinstance(value, bool):
                ap.fail(ln, f"[options] {key}: true (installed) or false, not {value!r}")
            lic.options[key] = value
            if key == "continuousAxis" and getattr(ap.machine.arm, "has_model", False):
                set_continuous(ap.machine.arm, value)  # the axis's range with the option, or without (11.5)
        else:
            ap.fail(ln, f"[options]: unknown key {key!r} (allowed: {', '.join(sorted([*OPTIONS, 'oem']))})")


def _oem(ap: Any, table: Any, line: int) -> dict[str, tuple[str, str | None]]:
    """oem = { Name = "enabled" } or { Name = { state = "demo", password = "secret" } }."""
    if not isinstance(table, dict):
        ap.fail(line, "[options] oem = { LicenceName = \"enabled\" | \"demo\" | \"\" }")
    out: dict[str, tuple[str, str | None]] = {}
    states = ", ".join(f'"{s}"' for s in OEM_STATES)
    for name, spec in table.items():
        password = None
        if isinstance(spec, dict):
            unknown = set(spec) - {"state", "password"}
            if unknown:
                ap.fail(line, f"[options] oem {name}: unknown key {sorted(unknown)[0]!r} (allowed: password, state)")
            password = spec.get("password")
            if password is not None and not isinstance(password, str):
                ap.fail(line, f"[options] oem {name}: password = \"text\"")
            spec = spec.get("state", "enabled")
        if spec not in OEM_STATES:
            ap.fail(line, f"[options] oem {name}: {states}, not {spec!r}")
        out[str(name)] = (spec, password)
    return out
