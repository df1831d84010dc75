"""What the fuzz suite generates for sweep files and the batch (issue 21), and what it checks:
shared by test_hostile_fuzz_batch.py (bounded, in CI) and bench/fuzz.py (the long run).

Every input is a sweep file in a fresh repository that also holds a symbolic-link loop, a link
leading out and, beside the repository, files holding a secret. The promise: the sweep makes
its cases or is refused with a message naming the sweep file (and its line, for what is written
in it); the `val3check sim --sweep` command ends with exit code 0, 1 or 2 without a traceback;
no byte of the secret is carried by a case, printed or written; nothing outside the repository
is listed.
"""

from __future__ import annotations

import json
import os
import shutil
import tempfile
from pathlib import Path

from hypothesis import strategies as st

from .fuzzing import SCALARS, VALUES, toml_text

SECRET = "TOPSECRET-sweep-fuzz"
_START = "begin\n  putln(\"hello\")\nend\n"

PATHS = ["apps/A", "apps/B", "apps/*", "apps/**/*.pjx", "apps/**", "loop/**/*.pjx", "link-out/*", "link-out",
         "../outside/secret.toml", "../outside", "/etc/passwd", "/proc/self/environ", "/**/*.pjx", "/proc/*", "~/.bashrc",
         "apps/A\x00x", "apps/[", "*", "**", ".", "..", "../../..", "x" * 300, "apps/A/../../..", "sc.toml",
         "cell.toml", "none", "NONE", "", " ", "\\\\server\\share", "apps/?", "apps/.hidden", "C:\\x"]
ARMS = ["tx2-60", "TX2_90", "none", "nosuch-arm", "robot.toml", "evil.toml", "/etc/passwd", "/etc/shadow",
        "../outside/secret.urdf", "link-out/secret.urdf", "x.urdf", "a.cfx", "passwd", "~/x.urdf", "tx2-60\x00"]
_GOOD = {"monitor_speed": st.sampled_from([50, 100, 12.5]), "cycles": st.integers(1, 3), "duration": st.just(0.2)}
OVERRIDES = st.one_of(
    st.fixed_dictionaries({}, optional=_GOOD), st.fixed_dictionaries({}, optional=_GOOD),
    st.dictionaries(st.sampled_from(["monitor_speed", "cycles", "duration", "bogus"]),
                    st.one_of(st.integers(-5, 10**6), st.floats(allow_nan=True, allow_infinity=True), SCALARS),
                    max_size=3))
_PATH = st.one_of(st.sampled_from(PATHS), st.sampled_from(PATHS).map(lambda p: p + "/x.pjx"))
_ARM = st.one_of(st.sampled_from(ARMS), _PATH)
_CASE = st.one_of(
    st.fixed_dictionaries({"application": _PATH}, optional={"arm": _ARM, "scenario": _PATH, "cell": _PATH, **_GOOD}),
    st.fixed_dictionaries({"application": _PATH}, optional={"arm": _ARM, "scenario": _PATH, "cell": _PATH, **_GOOD}),
    st.fixed_dictionaries({}, optional={
        "application": st.one_of(_PATH, SCALARS), "arm": st.one_of(_ARM, SCALARS), "scenario": st.one_of(_PATH, SCALARS),
        "cell": st.one_of(_PATH, SCALARS), "monitor_speed": SCALARS, "cycles": SCALARS, "bogus": VALUES}))
PRODUCT = st.fixed_dictionaries({}, optional={
    "version": st.one_of(st.just(1), st.just(1), st.just(1), SCALARS), "description": st.text(max_size=20),
    "mode": st.sampled_from(["product", "product", "list"]),
    "applications": st.one_of(st.lists(_PATH, min_size=1, max_size=3), st.lists(_PATH, min_size=1, max_size=3), VALUES),
    "arms": st.one_of(st.lists(_ARM, min_size=1, max_size=3), st.lists(_ARM, min_size=1, max_size=3), VALUES),
    "scenarios": st.lists(_PATH, min_size=1, max_size=2),
    "cells": st.lists(_PATH, min_size=1, max_size=2),
    "overrides": st.lists(OVERRIDES, min_size=1, max_size=3),
})
LIST = st.fixed_dictionaries({"case": st.lists(_CASE, min_size=1, max_size=3)},
                             optional={"version": st.just(1), "mode": st.sampled_from(["list", "list", "product"])})


def render(doc: dict) -> str:
    """A TOML document whose strings are escaped as TOML basic strings (a NUL written as \\u0000
    reaches the reader as a NUL in a path, not as a TOML syntax error)."""
    def value(v) -> str:  # noqa: ANN001
        if isinstance(v, str):
            return json.dumps(v, ensure_ascii=False)
        if isinstance(v, list):
            return "[" + ", ".join(value(x) for x in v) + "]"
        if isinstance(v, dict):
            return "{" + ", ".join(f"{json.dumps(k, ensure_ascii=False)} = {value(x)}" for k, x in v.items()) + "}"
        return toml_text({"x": v})[4:].strip()

    lines, tables = [], []
    for k, v in doc.items():
        if isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            for x in v:
                tables.append(f"[[{k}]]\n" + "".join(f"{json.dumps(a, ensure_ascii=False)} = {value(b)}\n"
                                                     for a, b in x.items()))
        else:
            lines.append(f"{k} = {value(v)}\n")
    return "".join(lines) + "\n".join(tables)


# mostly well-formed sweeps (what the reader's checks and the paths see), some random text
SWEEP = st.one_of(PRODUCT.map(render), PRODUCT.map(render), PRODUCT.map(render), LIST.map(render),
                  LIST.map(render), st.text(max_size=300), PRODUCT.map(toml_text))


def make_repository() -> Path:
    """tmp/repo (a git repository: two small applications, a scenario, a cell, robot files, a
    link loop, a link leading out), tmp/outside (the secrets). Returns tmp."""
    from val3check.testing import write_app

    tmp = Path(tempfile.mkdtemp(prefix="val3fuzz-sweep"))
    out = tmp / "outside"
    out.mkdir()
    (out / "secret.toml").write_text(f'unit = "{SECRET}"\n[controller]\nmonitor_speed = "{SECRET}"\n')
    (out / "secret.urdf").write_text(f"<robot name='{SECRET}'><link name='{SECRET}'/></robot>\n")
    (out / "Out").mkdir()
    repo = tmp / "repo"
    (repo / ".git").mkdir(parents=True)
    for name in ("A", "B"):
        write_app(repo / "apps", _START, name=name)
    (repo / "sc.toml").write_text("version = 1\n")
    (repo / "cell.toml").write_text('[[obstacle]]\nname = "t"\nshape = "box"\nsize = [1, 1, 1]\n'
                                    'at = [5000, 0, 0, 0, 0, 0]\n')
    (repo / "robot.toml").write_text('arm = "tx2-60"\nname = "Mine"\n')
    (repo / "evil.toml").write_text(f'arm = "{out / "secret.urdf"}"\n')
    (repo / "loop").mkdir()
    for link in ("l1", "l2", "l3"):
        os.symlink(".", repo / "loop" / link)
    os.symlink(out, repo / "link-out")
    os.symlink(out / "secret.toml", repo / "apps" / "A" / "val3check-cell.toml")  # a cell leading out
    return tmp


def make_cases(text: str, tmp: Path):
    """The cases of the sweep `text` (not run), or the SweepError/CaseError refusing it."""
    from val3check.batch.cases import CaseError, RunOptions, list_cases, product_cases
    from val3check.batch.command import _axes
    from val3check.batch.sweep import SweepError
    from val3check.config import Settings

    class Args:
        app, robot, scenario, cell, sweep = [], None, None, None, "sweep.toml"

    (tmp / "repo" / "sweep.toml").write_text(text, encoding="utf-8", errors="surrogateescape")
    old = os.getcwd()
    os.chdir(tmp / "repo")
    try:
        axes, sweep = _axes(Args)
        if sweep.mode == "list":
            return list_cases(sweep, axes, Settings(), RunOptions())
        return product_cases(axes, Settings(), RunOptions())
    except (SweepError, CaseError) as exc:
        return exc
    finally:
        os.chdir(old)


def check_cases(got, tmp: Path) -> str:
    """The promise on what `make_cases` gave; returns a label for hypothesis's statistics."""
    from val3check.batch.sweep import SweepError

    repo = os.path.realpath(tmp / "repo")
    if isinstance(got, Exception):
        message = str(got)
        assert SECRET not in message, message
        if isinstance(got, SweepError):
            assert message.startswith("sweep.toml"), message
        return f"refused: {type(got).__name__}"
    for case in got:
        for path, data in case.files:
            assert SECRET.encode() not in data, path
            assert os.path.realpath(path).startswith(repo + os.sep), path  # only the repository's files travel
        for path, size in case.stubs:
            assert size == 0 or os.path.realpath(path).startswith(repo + os.sep), path
    return f"{len(got)} cases"


def run_sweep(text: str, tmp: Path) -> tuple[int, str, str]:
    """`val3check sim --sweep` on `text` in the repository, small budgets: (exit code, out, err)."""
    import contextlib
    import io

    from val3check.cli import main

    (tmp / "repo" / "sweep.toml").write_text(text, encoding="utf-8", errors="surrogateescape")
    out, err = io.StringIO(), io.StringIO()
    old = os.getcwd()
    os.chdir(tmp / "repo")
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = main(["sim", "--sweep", "sweep.toml", "--duration", "0.2", "--max-wall", "5", "-j", "1",
                         "--out-dir", "results", "--format", "json"])
    finally:
        os.chdir(old)
    written = "".join(p.read_text(errors="replace") for p in (tmp / "repo" / "results").rglob("*") if p.is_file()) \
        if (tmp / "repo" / "results").is_dir() else ""
    assert code in (0, 1, 2), code
    assert "Traceback" not in err.getvalue(), err.getvalue()
    assert SECRET not in out.getvalue() + err.getvalue() + written
    if code == 2:
        assert err.getvalue().startswith("val3check sim: error: "), err.getvalue()
    return code, out.getvalue(), err.getvalue()


def cleanup(tmp: Path) -> None:
    shutil.rmtree(tmp, ignore_errors=True)
