"""The packages of the `sim` extra (pyproject.toml): `val3check sim` checks them before it runs,
so that a light install (`pip install val3check`, enough for `lint`) says which extra to add
instead of failing in the middle of a run."""

from __future__ import annotations

from importlib.util import find_spec

# module imported -> distribution to install (pyproject.toml [project.optional-dependencies] sim)
SIM_MODULES = {"numpy": "numpy", "pinocchio": "pin", "fcl": "python-fcl", "trimesh": "trimesh",
               "scipy": "scipy", "mcap": "mcap"}
EXTRA = "sim"


def missing_sim_packages() -> list[str]:
    """The distributions of the sim extra whose module cannot be imported."""
    return [dist for module, dist in SIM_MODULES.items() if find_spec(module) is None]


def install_hint(missing: list[str], command: str = "sim") -> str:
    return (f"val3check {command} needs the robotics stack of the `{EXTRA}` extra, which is not installed "
            f"(missing: {', '.join(missing)}): pip install 'val3check[{EXTRA}]'")
