"""`val3check rules` and `val3check rule CODE|--all`: the catalogue as text or JSON (version 1)."""

from __future__ import annotations

import json
from typing import Any

from ..rules.catalogue import FAMILIES, Example, Rule

VERSION = 1


def _example(ex: Example) -> dict[str, Any]:
    out: dict[str, Any] = {"description": ex.description}
    if ex.code is not None:
        out["code"] = ex.code
    else:
        out["files"] = dict(sorted(ex.files.items()))
        out["target"] = ex.target
    return out


def rule_record(rule: Rule) -> dict[str, Any]:
    """Everything the catalogue says about one rule."""
    return {
        "code": rule.code,
        "name": rule.name,
        "family": rule.family_name,
        "severity": rule.severity.label,
        "manual": rule.manual or None,
        "summary": rule.summary,
        "explanation": rule.explanation,
        "fix": rule.fix or None,
        "opt_in": rule.opt_in,
        "examples": {"bad": [_example(e) for e in rule.bad], "good": [_example(e) for e in rule.good]},
    }


def listing_json(rules) -> str:  # noqa: ANN001
    items = [{"code": r.code, "name": r.name, "family": r.family_name, "severity": r.severity.label, "manual": r.manual,
              "summary": r.summary, "fixable": bool(r.fix), "opt_in": r.opt_in} for r in rules.values()]
    return json.dumps({"rules": items, "version": VERSION}, indent=2, sort_keys=True, ensure_ascii=False) + "\n"


def listing_text(rules) -> str:  # noqa: ANN001
    out = []
    for letter, family in FAMILIES.items():
        members = [r for r in rules.values() if r.family == letter]
        if not members:
            continue
        out.append(f"{letter}  {family}")
        for r in members:
            manual = f"  (manual {r.manual})" if r.manual else ""
            fix = (" [fix]" if r.fix else "") + (" [opt-in]" if r.opt_in else "")
            out.append(f"  {r.code}  {r.severity.label:<7}  {r.name}{fix}: {r.summary}{manual}")
    return "\n".join(out) + "\n"


def explain_json(rules: list[Rule], single: bool) -> str:
    body: Any = rule_record(rules[0]) if single else [rule_record(r) for r in rules]
    return json.dumps(body, indent=2, sort_keys=True, ensure_ascii=False) + "\n"


def explain_text(rule: Rule) -> str:
    out = [f"{rule.code} {rule.name}", "", f"Family: {rule.family_name}", f"Default severity: {rule.severity.label}"]
    if rule.manual:
        out.append(f"Manual: section {rule.manual} (VAL 3 s7 reference manual)")
    if rule.opt_in:
        out.append(f"Opt-in: not in the default rule set; select it by its code (extend-select = [\"{rule.code}\"])")
    out += ["", rule.summary, ""]
    if rule.explanation:
        out += [rule.explanation, ""]
    if rule.fix:
        out += [f"Fix (val3check lint --fix): {rule.fix}", ""]
    for title, examples in (("Fails", rule.bad), ("Passes", rule.good)):
        for ex in examples:
            out.append(f"{title}: {ex.description}" if ex.description else f"{title}:")
            body = ex.code if ex.code is not None else "\n".join(f"--- {name}\n{text}" for name, text in sorted(ex.files.items()))
            out += ["    " + line for line in body.rstrip("\n").split("\n")]
            out.append("")
    return "\n".join(out).rstrip("\n") + "\n"
