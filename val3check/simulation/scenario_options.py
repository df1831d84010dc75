"""The scenario's tables for chapter 11 and the cell the options act in (docs/scenario.md):
`[options]` (the runtime licences, 11.3), `[[surfaces]]` and `[[pushes]]` (the cell's forces on
compliant moves, 11.1), `[[alterations]]` (what the cell alters, 11.2), read by `scenario.Applier`
after its own tables.

    apply_options(applier, data)      # applier: scenario.Applier (at(), fail(), signal())
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..excerpt import shown
from .alteration import ScenarioAlteration
from .ch11_continuous import set_continuous
from .ch11_licences import OEM_STATES, OPTIONS, licences_of
from .compliance import Push, Surface
from .scenario_numbers import finite as _finite
from .scenario_numbers import seconds as _seconds

TABLES = ("options", "surfaces", "pushes", "alterations")


def apply_options(ap: Any, data: dict) -> None:
    """Read the chapter 11 tables of the scenario `data` into the run (`ap.machine`)."""
    if "options" in data:
        _options(ap, data["options"])
    for i, table in enumerate(_array(ap, data, "surfaces")):
        _surface(ap, table, ("surfaces", i), i)
    for i, table in enumerate(_array(ap, data, "pushes")):
        _push(ap, table, ("pushes", i))
    for i, table in enumerate(_array(ap, data, "alterations")):
        _alteration(ap, table, ("alterations", i))


def _alteration(ap: Any, table: dict, here: tuple) -> None:
    """[[alterations]]: what the cell alters while alter mode is on (11.2): a conveyor (mm/s) or an
    offset (a trsf, reached over `ramp` s), in the axes of alterBegin's reference."""
    ap._keys(table, {"conveyor", "trsf", "at", "until", "ramp"}, here, "[[alterations]]")
    if ("conveyor" in table) == ("trsf" in table):
        ap.fail(here, "[[alterations]] needs conveyor = [vx, vy, vz] (mm/s) or trsf = [x, y, z, rx, ry, rz]")
    entry = ScenarioAlteration(line=ap.at(here))
    if "conveyor" in table:
        entry.velocity = _vector(ap, table["conveyor"], here + ("conveyor",),
                                 "[[alterations]] conveyor")
    else:
        v = table["trsf"]
        if not isinstance(v, list) or len(v) != 6 or not all(_finite(x) for x in v):
            ap.fail(here + ("trsf",), "[[alterations]] trsf = [x, y, z, rx, ry, rz] (mm, degrees)")
        entry.offset = np.array(v, dtype=float)
    for key in ("at", "until", "ramp"):
        if key in table:
            us = _seconds(table[key])
            if us is None:
                ap.fail(here + (key,), f"[[alterations]] {key} = seconds (a finite number from 0 to 1e7)")
            setattr(entry, key, us / 1e6)
    if entry.until is not None and entry.at is not None and entry.until <= entry.at:
        ap.fail(here + ("until",), "[[alterations]] until must come after at")
    arm = ap.machine.arm
    if getattr(arm, "has_model", False) and getattr(arm, "alteration", None) is not None:
        arm.alteration.scenario.append(entry)


def _array(ap: Any, data: dict, key: str) -> list:
    v = data.get(key, [])
    if not isinstance(v, list) or not all(isinstance(x, dict) for x in v):
        ap.fail((key,), f"{key} must be an array of tables ([[{key}]])")
    return v


def _compliance(ap: Any):
    """The arm's compliance (compliance.py), None without an arm model."""
    arm = ap.machine.arm
    return getattr(arm, "compliance", None) if getattr(arm, "has_model", False) else None


def _vector(ap: Any, v: Any, here: tuple, what: str, nonzero: bool = False) -> np.ndarray:
    if not isinstance(v, list) or len(v) != 3 or not all(_finite(x) for x in v):
        ap.fail(here, f"{what} = [x, y, z]: three finite numbers (mm, world frame)")
    out = np.array(v, dtype=float)
    if nonzero and not np.linalg.norm(out) > 0:
        ap.fail(here, f"{what}: not a direction (all zeros)")
    return out


def _surface(ap: Any, table: dict, here: tuple, index: int) -> None:
    """[[surfaces]]: a plane the tool centre point of a compliant move meets (11.1)."""
    ap._keys(table, {"name", "point", "normal"}, here, "[[surfaces]]")
    name = table.get("name", f"surface {index + 1}")
    if not isinstance(name, str):
        ap.fail(here + ("name",), "[[surfaces]] name = \"text\"")
    for key in ("point", "normal"):
        if key not in table:
            ap.fail(here, f"[[surfaces]] needs {key} = [x, y, z]")
    point = _vector(ap, table["point"], here + ("point",), "[[surfaces]] point")
    normal = _vector(ap, table["normal"], here + ("normal",), "[[surfaces]] normal", True)
    comp = _compliance(ap)
    if comp is not None:
        comp.surfaces.append(Surface(name, point, normal / np.linalg.norm(normal), ap.at(here)))


def _push(ap: Any, table: dict, here: tuple) -> None:
    """[[pushes]]: a force of the cell along a compliant move's path, at times or with a signal."""
    ap._keys(table, {"force", "at", "until", "when", "becomes", "after"}, here, "[[pushes]]")
    force = table.get("force")
    if not _finite(force):
        ap.fail(here + ("force",), "[[pushes]] needs force = % of the arm's nominal load (a number)")
    push = Push(float(force))
    if "when" in table:
        if "at" in table or "until" in table:
            ap.fail(here, "[[pushes]]: either at/until (times) or when (a signal), not both")
        name = table["when"]
        if not isinstance(name, str):
            ap.fail(here + ("when",), "[[pushes]] when = \"signal\"")
        io = ap.signal(name, here + ("when",))
        push.io = io
        push.becomes = ap.value(io, table.get("becomes", True), here + ("becomes",), name)
        after = _seconds(table.get("after", 0))
        if after is None:
            ap.fail(here + ("after",), "[[pushes]] after = seconds (a finite number from 0 to 1e7)")
        push.after = after / 1e6
        if io.value == push.becomes:
            push.windows.append([push.after, None])
    else:
        at = _seconds(table.get("at", 0))
        until = _seconds(table["until"]) if "until" in table else None
        if at is None or ("until" in table and (until is None or until <= at)):
            ap.fail(here + ("until" if at is not None and "until" in table else "at",), "[[pushes]] at = seconds, until = later seconds (finite numbers from 0 to 1e7)")
        push.windows.append([at / 1e6, None if until is None else until / 1e6])
    comp = _compliance(ap)
    if comp is not None:
        comp.pushes.append(push)
        if push.io is not None:
            comp.watch_signals(ap.machine.cell_subsystem)


def _options(ap: Any, table: Any) -> None:
    """[options]: `alter = false`..., `oem = { Name = "enabled" | "demo" | "" | { state, password } }`."""
    here = ("options",)
    if not isinstance(table, dict):
        ap.fail(here, "[options] must be a table: alter = true, compliance = false, oem = { MyLicence = \"enabled\" }")
    lic = licences_of(ap.machine)
    lic.given = True
    for key, value in table.items():
        ln = here + (key,)
        if key == "oem":
            lic.oem = _oem(ap, value, ln)
        elif key in OPTIONS:
            if not isinstance(value, bool):
                ap.fail(ln, f"[options] {key}: true (installed) or false, not {shown(value)}")
            lic.options[key] = value
            if key == "continuousAxis" and getattr(ap.machine.arm, "has_model", False):
                set_continuous(ap.machine.arm, value)  # the axis's range with the option, or without (11.5)
        else:
            ap.fail(ln, f"[options]: unknown key {shown(key)} (allowed: {', '.join(sorted([*OPTIONS, 'oem']))})")


def _oem(ap: Any, table: Any, here: tuple) -> dict[str, tuple[str, str | None]]:
    """oem = { Name = "enabled" } or { Name = { state = "demo", password = "secret" } }."""
    if not isinstance(table, dict):
        ap.fail(here, "[options] oem = { LicenceName = \"enabled\" | \"demo\" | \"\" }")
    out: dict[str, tuple[str, str | None]] = {}
    states = ", ".join(f'"{s}"' for s in OEM_STATES)
    for name, spec in table.items():
        password = None
        if isinstance(spec, dict):
            unknown = set(spec) - {"state", "password"}
            if unknown:
                ap.fail(here + (name,), f"[options] oem {shown(name)}: unknown key {shown(min(unknown))} (allowed: password, state)")
            password = spec.get("password")
            if password is not None and not isinstance(password, str):
                ap.fail(here + (name,), f"[options] oem {shown(name)}: password = \"text\"")
            spec = spec.get("state", "enabled")
        if spec not in OEM_STATES:
            ap.fail(here + (name,), f"[options] oem {shown(name)}: {states}, not {shown(spec)}")
        out[str(name)] = (spec, password)
    return out
