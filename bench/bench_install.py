"""What `pip install val3check` and each extra weigh: a fresh virtual environment per install
(lint only, `[sim]`, `[lsp]`, `[dask]`), the size of what the install adds to the environment's
site-packages (an empty environment's pip subtracted) and the distributions it brings, largest first.
The figures of README.md ("Installing") come from here. Needs pip's index or its cache.
Run: python bench/bench_install.py [--extras sim,lsp,dask] [--keep DIR]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def _site(venv: Path) -> Path:
    """The site-packages folder of a virtual environment."""
    out = subprocess.run([str(venv / "bin" / "python"), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                         capture_output=True, text=True, check=True)
    return Path(out.stdout.strip())


def _size(folder: Path) -> int:
    """Bytes of the files under `folder` (links not followed)."""
    total = 0
    for dirpath, _, files in os.walk(folder):
        for f in files:
            p = os.path.join(dirpath, f)
            if not os.path.islink(p):
                total += os.path.getsize(p)
    return total


def _distributions(venv: Path, site: Path) -> list[tuple[str, int]]:
    """(name, bytes) of every distribution installed, from its RECORD, largest first."""
    code = ("import importlib.metadata as m, json, os\n"
            "out = []\n"
            "for d in m.distributions():\n"
            "    n = 0\n"
            "    for f in d.files or []:\n"
            "        p = f.locate()\n"
            "        if os.path.isfile(p) and not os.path.islink(p): n += os.path.getsize(p)\n"
            "    out.append((d.metadata['Name'], n))\n"
            "print(json.dumps(out))")
    out = subprocess.run([str(venv / "bin" / "python"), "-I", "-c", code], capture_output=True, text=True, check=True,
                         cwd=str(venv))
    return sorted(dict(json.loads(out.stdout)).items(), key=lambda x: (-x[1], x[0]))


def measure(spec: str, work: Path, label: str) -> tuple[int, int, list[tuple[str, int]], float]:
    """(bytes added to site-packages, to the whole environment, distributions, seconds) of
    `pip install spec` in a fresh venv."""
    venv = work / label
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    site = _site(venv)
    empty, empty_env = _size(site), _size(venv)
    t0 = time.perf_counter()
    subprocess.run([str(venv / "bin" / "pip"), "install", "-q", "--disable-pip-version-check", spec], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    seconds = time.perf_counter() - t0
    dists = [d for d in _distributions(venv, site) if d[0] not in ("pip", "setuptools")]
    return _size(site) - empty, _size(venv) - empty_env, dists, seconds


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--extras", default="sim,lsp,dask", help="the extras to weigh besides the lint-only install")
    ap.add_argument("--keep", metavar="DIR", help="make the environments in DIR and keep them")
    args = ap.parse_args()
    specs = [("lint only", str(ROOT))] + [(f"[{e}]", f"{ROOT}[{e}]") for e in args.extras.split(",") if e]
    with tempfile.TemporaryDirectory(prefix="val3check-install-") as tmp:
        work = Path(args.keep or tmp)
        work.mkdir(parents=True, exist_ok=True)
        for label, spec in specs:
            added, env, dists, seconds = measure(spec, work, label.strip("[]").replace(" ", "-"))
            top = ", ".join(f"{n} {b / 1e6:.0f}" for n, b in dists[:8])
            print(f"{label}: {added / 1e6:.0f} MB in site-packages ({env / 1e6:.0f} MB with the environment's "
                  f"scripts; {env / 2**20:.0f} MiB), {len(dists)} distributions; largest (MB): {top}; "
                  f"installed in {seconds:.0f} s")


if __name__ == "__main__":
    main()
