"""Find the data folders (`grammars/`, `rules/`, `robots/`) in a source checkout or an installed wheel."""

from __future__ import annotations

import os

TYPE_CHECKING = False  # not typing's: importing typing costs 3 ms at lint's start-up
if TYPE_CHECKING:
    from pathlib import Path

_PACKAGE = os.path.dirname(os.path.abspath(__file__))


def resource_path(name: str) -> str:
    """The folder `name` as a string (no pathlib: `val3check lint` imports little, to start fast)."""
    installed = os.path.join(_PACKAGE, "_data", name)  # the wheel copies the folders here (pyproject.toml)
    if os.path.isdir(installed):
        return installed
    return os.path.join(os.path.dirname(_PACKAGE), name)  # source checkout / editable install


def resource_dir(name: str) -> "Path":
    from pathlib import Path

    return Path(resource_path(name)).resolve()


def sha256_hex(data: bytes) -> str:
    """SHA-256 of `data`, to tell whether a shipped table matches its source file. CPython's own
    `_sha256` module (3.11; `_sha2` from 3.12) loads in a tenth of a millisecond, `hashlib`
    loads OpenSSL (2 ms of the start-up)."""
    try:
        from _sha256 import sha256  # type: ignore[import-not-found]
    except ImportError:
        try:
            from _sha2 import sha256  # type: ignore[import-not-found,no-redef]
        except ImportError:
            from hashlib import sha256  # type: ignore[no-redef]
    return sha256(data).hexdigest()
