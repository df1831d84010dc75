"""Find the data folders (`grammars/`, `rules/`) in a source checkout or an installed wheel."""

from __future__ import annotations

from pathlib import Path

_PACKAGE = Path(__file__).resolve().parent


def resource_dir(name: str) -> Path:
    installed = _PACKAGE / "_data" / name  # the wheel copies the folders here (pyproject.toml)
    if installed.is_dir():
        return installed
    return _PACKAGE.parent / name  # source checkout / editable install
