"""Loading: find VAL 3 applications on disk and read them into the model (`model.py`).

    ws, diagnostics = load(["path/to/App", "other/App2/App2.pjx"], LoadOptions(disk_roots=[...]))

`load` never raises for bad input: unreadable or malformed files, missing listed files,
libraries that cannot be found... all become Diagnostics (codes F001-F016, L001-L005, see
`rules/`) and loading goes on with the next file. Every file is read through
`val3check.confine`: a path written in a file never leads outside the run's roots (the paths
given, their repository, the disk roots, each target's Disk:// folder and controller tree). Every path in the result is absolute and
normalised (os.path.abspath). Output is deterministic (sorted listings, file order).

What `paths` may name:

- a `.pjx` project file, or an application folder (`<folder>.pjx`, or its only `.pjx`);
- a folder holding applications at any depth, such as a repository or a controller tree
  (`<ctrl>/usr/usrapp/<App>/`); hidden folders (`.git`...), `node_modules` and virtual
  environments are skipped, and symbolic links that lead back to a folder already searched
  are not followed again;
- a `.pgx` file: when a `.pjx` in its folder lists it, the whole application is loaded and
  becomes the target (its globals, libraries and types are needed to check the file);
  otherwise it is loaded alone as a "pgx-only" application, like a folder of `.pgx` files
  without project (`layout == "pgx-only"`, `globals_known == False`, one F009 info).

Libraries and user types declared by each loaded project are resolved (see `resolve.py`)
and loaded too, recursively, once per file, into `Workspace.apps`; `Workspace.targets` lists
only what the user named.
"""

from __future__ import annotations

from ..diagnostics import Diagnostic
from .loader import LoadOptions, load_paths
from .model import Workspace
from .types import base_type

__all__ = ["LoadOptions", "load", "base_type"]


def load(paths: list[str], options: LoadOptions | None = None) -> tuple[Workspace, list[Diagnostic]]:
    ws, diags, _ = load_paths(list(paths), options or LoadOptions())
    return ws, diags
