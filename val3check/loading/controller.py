"""The controller tree an application sits in, and the arm it declares.

A controller tree (as SRS exports it or as copied from a controller) holds the applications in
`usr/usrapp/<Application>/` and the arm in `usr/configs/arm.cfx`
(`<String name="arm" value="tx2_60-S1" />`, srs-project-files.md). Only that layout is looked
at: the `usrapp` folder must be an ancestor of the application folder (at most a few levels up),
so nothing outside the controller tree that holds the application is ever read. The file is
read with the loader's safe XML reader (no entities, size limit).
"""

from __future__ import annotations

import os

from ..confine import Roots
from .xmlread import read_xml

_LEVELS = 3  # usr/usrapp/App, usr/usrapp/Group/App, usr/usrapp/Group/Sub/App


def find_arm_cfx(app_folder: str) -> str | None:
    """`usr/configs/arm.cfx` of the controller tree that holds `app_folder`, or None."""
    folder = os.path.abspath(app_folder)
    for _ in range(_LEVELS):
        parent = os.path.dirname(folder)
        if parent == folder:
            return None
        if os.path.basename(parent).lower() == "usrapp":
            usr = os.path.dirname(parent)
            for configs in ("configs", "Configs", "CONFIGS"):
                candidate = os.path.join(usr, configs, "arm.cfx")
                if os.path.isfile(candidate):
                    return candidate
            return None
        folder = parent
    return None


def read_arm_id(cfx_path: str, max_size: int) -> str | None:
    """The arm id an arm.cfx declares; None when it cannot be read or has none."""
    # val3check.confine: the file, links resolved, must lie in the controller tree's usr folder
    usr = os.path.dirname(os.path.dirname(os.path.abspath(cfx_path)))
    res = read_xml(cfx_path, max_size, Roots([usr]))
    if res.root is None:
        return None
    stack = [res.root]
    while stack:
        node = stack.pop()
        if (node.get("name") or "").lower() == "arm":
            value = (node.get("value") or "").strip()
            if value:
                return value
        stack.extend(reversed(node.children))
    return None


def controller_arm(app_folder: str, max_size: int = 16 * 1024 * 1024) -> tuple[str, str] | None:
    """(arm id, arm.cfx path) of the controller tree holding the application, or None."""
    cfx = find_arm_cfx(app_folder)
    if cfx is None:
        return None
    arm = read_arm_id(cfx, max_size)
    return (arm, cfx) if arm else None
