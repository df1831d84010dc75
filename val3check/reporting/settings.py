"""`val3check lint --show-settings` and `--show-files`: what a run would check, and with what."""

from __future__ import annotations

import json
from typing import Any

from ..lint import Discovery, display_path


def _files(found: Discovery) -> list[str]:
    return sorted({display_path(f) for app in found.targets for f in app.files})


def render_files(found: Discovery) -> str:
    return "".join(f + "\n" for f in _files(found))


def settings_record(settings, found: Discovery, rules) -> dict[str, Any]:  # noqa: ANN001
    enabled = [code for code in rules if settings.enabled(code)]
    return {
        "configuration": display_path(settings.source) if settings.source else None,
        "root": display_path(settings.root) if settings.root else None,
        "settings": {
            "select": list(settings.select),
            "extend-select": list(settings.extend_select),
            "ignore": list(settings.ignore),
            "per-file-ignores": {k: list(v) for k, v in sorted(settings.per_file_ignores.items())},
            "severity": {k: v.label for k, v in sorted(settings.severity.items())},
            "fail-on": settings.fail_on,
            "disk-roots": [display_path(d) for d in settings.disk_roots],
            "exclude": list(settings.exclude),
            "extend-exclude": list(settings.extend_exclude),
            "force-exclude": settings.force_exclude,
            "max-file-size": settings.max_file_size,
            "target": settings.target.label() if settings.target is not None else None,
        },
        "applications": sorted(display_path(app.path) for app in found.targets),
        "skipped": sorted(display_path(p) for p in found.skipped),
        "files": _files(found),
        "rules": enabled,
    }


def render_settings(settings, found: Discovery, rules, json_format: bool = False) -> str:  # noqa: ANN001
    record = settings_record(settings, found, rules)
    if json_format:
        return json.dumps({"version": 1, **record}, indent=2, sort_keys=True, ensure_ascii=True) + "\n"
    out = [f"configuration: {record['configuration'] or 'none (defaults)'}"]
    for key, value in record["settings"].items():
        out.append(f"  {key} = {json.dumps(value, ensure_ascii=False)}")
    out.append(f"applications ({len(record['applications'])}):")
    out += [f"  {a}" for a in record["applications"]]
    if record["skipped"]:
        out.append("paths named but excluded (--force-exclude):")
        out += [f"  {p}" for p in record["skipped"]]
    out.append(f"files: {len(record['files'])} (--show-files lists them)")
    out.append(f"rules enabled ({len(record['rules'])} of {len(rules)}):")
    line = " "
    for code in record["rules"]:
        if len(line) + len(code) + 1 > 80:
            out.append(line)
            line = " "
        line += " " + code
    if line.strip():
        out.append(line)
    return "\n".join(out) + "\n"
