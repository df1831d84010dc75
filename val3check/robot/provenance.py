"""Where each value of an arm model comes from: public facts, assumptions, disagreements, gaps.

A generated model (robots/generate.py) writes them in its URDF's <val3check> element:

    <fact key="geometry" text="S1 Staubli_TX2_40.py (RoboDK library)"/>
    <assumption key="nominal_speeds" value="555 475 585 1035 1135 1575" text="not published: the TX40's"/>
    <alternative key="limits.j3" chosen="-152.5..152.5" other="-142.5..142.5" text="why this one"/>
    <missing key="max_torques" text="no public source"/>
    <reference id="S1" text="RoboDK robot library as copied into …"/>

`val3check robots NAME` prints them; assumptions can be overridden (overrides.py) and then say so.
"""

from __future__ import annotations

from ..light_dataclass import dataclass


@dataclass(frozen=True)
class Fact:
    key: str
    text: str  # where it comes from


@dataclass(frozen=True)
class Assumption:
    key: str  # the override key (overrides.KEYS) when there is one
    value: str  # the value used, as text
    text: str  # why, and what it rests on
    by: str = "model"  # "model" (the URDF says so), "controller" (arm.cfx), "user" (an override)


@dataclass(frozen=True)
class Alternative:
    key: str
    chosen: str
    other: str
    text: str  # which sources, and why the chosen value


@dataclass(frozen=True)
class Missing:
    key: str
    text: str


@dataclass(frozen=True)
class Provenance:
    facts: tuple[Fact, ...] = ()
    assumptions: tuple[Assumption, ...] = ()
    alternatives: tuple[Alternative, ...] = ()
    missing: tuple[Missing, ...] = ()
    references: tuple[Fact, ...] = ()  # (source id such as "S1", what it is)

    @classmethod
    def from_meta(cls, items: list[tuple[str, dict[str, str]]]) -> "Provenance":
        facts, assumptions, alternatives, missing, refs = [], [], [], [], []
        for tag, a in items:
            if tag == "fact":
                facts.append(Fact(a.get("key", ""), a.get("text", "")))
            elif tag == "assumption":
                assumptions.append(Assumption(a.get("key", ""), a.get("value", ""), a.get("text", "")))
            elif tag == "alternative":
                alternatives.append(Alternative(a.get("key", ""), a.get("chosen", ""), a.get("other", ""), a.get("text", "")))
            elif tag == "missing":
                missing.append(Missing(a.get("key", ""), a.get("text", "")))
            elif tag == "reference":
                refs.append(Fact(a.get("id", ""), a.get("text", "")))
        return cls(tuple(facts), tuple(assumptions), tuple(alternatives), tuple(missing), tuple(refs))

    def assumed(self) -> frozenset[str]:
        return frozenset(a.key for a in self.assumptions)

    def replace_assumption(self, new: Assumption) -> "Provenance":
        """The same with `new` in place of the assumption of the same key (or added)."""
        kept = tuple(a for a in self.assumptions if a.key != new.key)
        return Provenance(self.facts, kept + (new,), self.alternatives, self.missing, self.references)
