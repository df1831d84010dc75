"""The language's TOML files (instructions.toml, types.toml, s8.toml), read fast.

Reading them with tomllib took a fifth of the start-up of `val3check lint`. Their content is
also shipped as Python data in `_compiled.py` (regenerate with
`python -m val3check.language.compiled` after editing a TOML file; a test fails while it is out
of date). `load_toml(name)` returns that data when the file's SHA-256 matches the one recorded,
else it reads the TOML file itself (while it is being edited): the TOML files stay the source.
"""

from __future__ import annotations

import os
import sys

from ..resources import sha256_hex

FOLDER = os.path.dirname(os.path.abspath(__file__))
NAMES = ("instructions.toml", "types.toml", "s8.toml")
OUT = os.path.join(FOLDER, "_compiled.py")


def _read(name: str) -> bytes:
    with open(os.path.join(FOLDER, name), "rb") as fh:
        return fh.read()


def load_toml(name: str) -> dict:
    """The parsed content of the language file `name` (one of NAMES)."""
    raw = _read(name)
    try:
        from . import _compiled

        if _compiled.SHA256.get(name) == sha256_hex(raw):
            return _compiled.DATA[name]
    except ImportError:
        pass
    import tomllib

    return tomllib.loads(raw.decode("utf-8"))


def render() -> str:
    import pprint  # imports dataclasses: only when regenerating
    import tomllib

    sha, data = {}, {}
    for name in NAMES:
        raw = _read(name)
        sha[name] = sha256_hex(raw)
        data[name] = tomllib.loads(raw.decode("utf-8"))
    return (
        '"""The language TOML files as Python data. GENERATED: do not edit; run\n'
        '`python -m val3check.language.compiled` after changing a TOML file."""\n'
        "# fmt: off\n"
        f"SHA256 = {pprint.pformat(sha, width=120)}\n"
        f"DATA = {pprint.pformat(data, width=120, compact=True, sort_dicts=False)}\n"
    )


def is_current() -> bool:
    try:
        from . import _compiled
    except ImportError:
        return False
    return all(_compiled.SHA256.get(n) == sha256_hex(_read(n)) for n in NAMES)


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if "--check" in argv:
        ok = is_current()
        print("up to date" if ok else "out of date: run python -m val3check.language.compiled")
        return 0 if ok else 1
    with open(OUT, "w", encoding="utf-8") as fh:
        fh.write(render())
    print(f"wrote {OUT}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
