"""The language server, `val3check server` (docs/editors.md): diagnostics as you type, hover,
go to definition and document symbols for VAL 3 files, over stdio.

`features.py` holds what the server knows (no protocol); `server.py` speaks LSP with pygls,
which the `lsp` extra installs (`pip install 'val3check[lsp]'`).
"""

REQUIREMENTS = ("pygls", "lsprotocol")


def missing_packages() -> list[str]:
    """The server's dependencies that are not installed."""
    from importlib.util import find_spec

    return [name for name in REQUIREMENTS if find_spec(name) is None]
