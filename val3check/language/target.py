"""What an application is checked for: the controller, the VAL 3 version and the arm.

The configuration key `target` names the controller and/or the VAL 3 version the applications
run on (`target = "CS9"`, `"s8.13"`, `"CS8 s7.11"`); without it each application is checked
for the version its project file writes (`<Parameters version="s7.11">`). The arm comes from the
controller tree (`usr/configs/arm.cfx`) when the application sits in one.

Why it matters: s8 (CS9 controllers) adds instructions, forms of s7 instructions and the `?`
print statement (language/s8.toml). Real CS9 code is often saved with an s7 version in its
project file, so an s8 form there is "s8 only" (T030, a warning) unless the configuration says
the target is an s7 controller (then T031, an error) or an s8 one (then it is fine).
"""

from __future__ import annotations

import re

from ..light_dataclass import dataclass

# Controllers and the VAL 3 majors they run: CS8/CS8C controllers run s5 to s7, CS9 ones s8
# (the s8 reference manual is written for CS9; s7 is the last version for CS8C).
CONTROLLERS: dict[str, tuple[int, ...]] = {"CS8": (5, 6, 7), "CS8C": (5, 6, 7), "CS9": (8,)}
_VERSION = re.compile(r"s([5-8])(?:\.\d+)*\Z", re.IGNORECASE)
# A project file's version: "s7.11", "s8.20.2Cs9_BS4270" (SRS writes the build after the number).
_PROJECT_VERSION = re.compile(r"\s*s(\d+)((?:\.\d+)*)", re.IGNORECASE)

EXAMPLES = '"CS9", "s8.13", "CS8 s7.11"'


# The type family of an arm, from the arm id arm.cfx writes (`<String name="arm" value="tx2_60-S1"/>`).
# Six-axis TX, TX2 and RX arms use the Rx types (pointRx, jointRx, configRx), SCARA TS, TS2 and
# RS arms the Rs types (9.7.2, srs-project-files.md "Arm-specific type names"). Ids seen in real
# controller trees (shared/robots/staubli-arms-more.toml, S6): "ts2_60-S1", "ts60-S1", "tx200-S3";
# staubli-arms.toml: "tx2-60", "tx60l", "rx160". Other ids (TP80 picker...) are not classified.
ARM_FAMILIES: tuple[tuple[str, str], ...] = (("tx", "Rx"), ("rx", "Rx"), ("ts", "Rs"), ("rs", "Rs"))


def arm_family(arm_id: str) -> str | None:
    """ "Rx" or "Rs" for an arm id ("tx2_60-S1" -> "Rx", "ts60-S1" -> "Rs"); None when unknown."""
    m = re.match(r"([a-z]+)\d", (arm_id or "").strip().lower())
    if m is None:
        return None
    return dict(ARM_FAMILIES).get(m.group(1)[:2]) if len(m.group(1)) == 2 else None


class TargetError(ValueError):
    """A `target` the configuration cannot use."""


@dataclass(frozen=True, slots=True)
class TargetSpec:
    """The configuration's `target`: what every application is checked for."""

    controller: str | None = None  # "CS8", "CS8C", "CS9"
    version: str | None = None  # "s8.13", "s7"

    @property
    def major(self) -> int | None:
        if self.version is not None:
            return int(self.version[1])
        if self.controller is not None:
            majors = CONTROLLERS[self.controller]
            return majors[-1] if len(majors) == 1 else None
        return None

    def label(self) -> str:
        return " ".join(p for p in (self.controller, self.version) if p)


def parse_target(text: str) -> TargetSpec:
    """`"CS9"`, `"s8.13"`, `"CS8 s7.11"` (case-insensitive, any order, spaces or a comma)."""
    if not isinstance(text, str) or not text.strip():
        raise TargetError(f"'target' must be a controller and/or a VAL 3 version, e.g. {EXAMPLES}")
    controller = version = None
    for word in re.split(r"[\s,]+", text.strip()):
        up = word.upper()
        if up in CONTROLLERS:
            if controller is not None:
                raise TargetError(f"'target' names two controllers ({controller}, {up}): give one")
            controller = up
        elif _VERSION.match(word):
            if version is not None:
                raise TargetError(f"'target' names two VAL 3 versions ({version}, {word}): give one")
            version = "s" + word[1:]
        else:
            raise TargetError(f"'target': unknown word {word!r}: expected a controller ({', '.join(CONTROLLERS)}) "
                              f"and/or a VAL 3 version (s5 to s8, e.g. s8.13); examples: {EXAMPLES}")
    if controller is not None and version is not None:
        major = int(version[1])
        if major not in CONTROLLERS[controller]:
            runs = "s8" if controller == "CS9" else "s5 to s7"
            raise TargetError(f"'target': {controller} controllers run VAL 3 {runs}, not {version}")
    return TargetSpec(controller, version)


def project_major(version: str) -> int | None:
    """6, 7 or 8 from a project file's version ("s7.11", "s8.20.2Cs9_BS4270"); None if unknown."""
    m = _PROJECT_VERSION.match(version or "")
    return int(m.group(1)) if m else None


@dataclass(frozen=True, slots=True)
class Target:
    """What one application is checked for.

    `major`: the VAL 3 major version (None: unknown); `explicit`: it comes from the
    configuration, not from the project file; `arm`/`family`: the arm of the controller tree
    ("tx2_60-S1", "Rx"), None when the application is not in a controller tree (or the arm is not
    one of the known families).
    """

    major: int | None
    label: str  # for messages: "s7.11 (project file)", "CS9 (configuration)"
    explicit: bool = False
    arm: str | None = None
    family: str | None = None
    arm_source: str = ""  # the arm.cfx the arm was read from

    @property
    def s8(self) -> bool:
        return self.major is not None and self.major >= 8

    @property
    def cs9(self) -> bool:
        """The application is written for a CS9 controller: the configuration says so, or its
        project file's version does (SRS writes "s7.0.1Cs9", "s8.3Cs9_BS845" for CS9 code: Stäubli's
        own CS9 templates saved as s7.0.1Cs9 call CS9 instructions such as userPageAlert)."""
        return "cs9" in self.label.lower()


def target_for(project_version: str, spec: TargetSpec | None, arm: str | None = None, family: str | None = None,
               arm_source: str = "") -> Target:
    """The target of an application whose project file writes `project_version`."""
    own = project_major(project_version)
    if spec is None or (spec.controller is None and spec.version is None):
        label = f"{project_version} (project file)" if project_version else "version unknown (no project file version)"
        return Target(own, label, False, arm, family, arm_source)
    major = spec.major
    if major is None and spec.controller is not None:
        majors = CONTROLLERS[spec.controller]
        major = own if own in majors else majors[-1]
    return Target(major, f"{spec.label()} (configuration)", True, arm, family, arm_source)
