"""11.3 getLicence, and the runtime licences of the options of chapter 11 the other handlers ask.

11.3.2 getLicence(sOemNomLicence, sOemMotDePasse) returns "oemLicenceDisabled" (the VAL 3
runtime licence "oemLicence" is not installed: the OEM licence cannot be tested), "" (the OEM
licence is not enabled: password not defined or invalid), "demo" or "enabled". The options of
chapter 11 need their runtime licence too (12.1, error 250: "Pas de licence d'exécution (runtime)
pour cette instruction"; alterBegin and alter return -2 instead, 11.2.6).

Nothing in a simulation knows the controller's licences: the scenario says them (`[options]`,
docs/scenario.md). Without it every option is taken as licensed and every OEM licence as
enabled, and the run says so once, as an info (R050), at the first instruction that relies on
it; a key the table leaves out is assumed the same way (the OEM licences listed imply the
oemLicence runtime licence).
"""

from __future__ import annotations

from ..language.runtime_errors import Val3RuntimeError
from ..light_dataclass import dataclass, field
from ..rules import codes
from .runtime_notes import note

# The runtime options of chapter 11 (the catalogue's `option` names) and what needs them.
OPTIONS = {
    "compliance": "compliant moves (11.1)",
    "alter": "ALTER, the real-time alteration of a path (11.2)",
    "oemLicence": "the OEM licences (11.3)",
    "absoluteRobot": "the absolute robot (11.4)",
    "continuousAxis": "the continuous axis (11.5)",
}
OEM_STATES = ("enabled", "demo", "")


@dataclass
class Licences:
    """What the scenario's `[options]` says: `options` {name: installed} (absent: assumed
    installed), `oem` {licence: (state, password or None)} or None when the scenario gives none
    (every OEM licence is then "enabled"), `given` whether the scenario had an `[options]` table."""

    options: dict[str, bool] = field(default_factory=dict)
    oem: dict[str, tuple[str, str | None]] | None = None
    given: bool = False

    def installed(self, option: str) -> bool | None:
        """True or False as the scenario says; None when it says nothing (assumed installed)."""
        return self.options.get(option)


def licences_of(machine) -> Licences:
    """The run's licences (the scenario's `[options]`, or the defaults)."""
    lic = machine.__dict__.get("licences")
    if lic is None:
        lic = machine.__dict__["licences"] = Licences()
    return lic


def licensed(task, option: str, what: str) -> bool:
    """Whether the runtime licence of `option` is installed; R050 (once) when it is assumed."""
    lic = licences_of(task.machine)
    said = lic.installed(option)
    if said is None:
        where = "has no [options] table" if not lic.given else f"does not say `{option}` in [options]"
        note(task, codes.OPTION_LICENCE_ASSUMED, f"{what}: the scenario {where}: the {option} option ({OPTIONS[option]}) is taken as "
                           f"licensed (docs/scenario.md, [options])", once=f"option:{option}")
        return True
    return said


def require(task, option: str, what: str) -> None:
    """Error 250 (12.1) when the scenario says the option's runtime licence is not installed."""
    if not licensed(task, option, what):
        raise Val3RuntimeError(250, f"{what}: no runtime licence for the {option} option ({OPTIONS[option]}): the "
                                    "scenario's [options] says it is not installed")


def I_getlicence(task, unit, name: str, password: str) -> str:
    """11.3.2 getLicence(sOemNomLicence, sOemMotDePasse): the state of the OEM licence."""
    lic = licences_of(task.machine)
    if lic.installed("oemLicence") is False:
        return "oemLicenceDisabled"
    if lic.oem is None:
        runtime = "" if lic.installed("oemLicence") else "the oemLicence option is taken as installed and "
        note(task, codes.OPTION_LICENCE_ASSUMED, f"getLicence: the scenario gives no OEM licences ([options] oem): {runtime}every OEM "
                           "licence is taken as \"enabled\" (docs/scenario.md)", once="oem")
        return "enabled"
    state, secret = lic.oem.get(name, ("", None))
    if secret is not None and password != secret:
        return ""
    return state


def register(registry) -> None:
    """11.3."""
    registry.instruction("getLicence", I_getlicence)
