"""The pre-commit hook works through pre-commit itself, on a temporary repository.

pre-commit installs val3check from this checkout into its own environment (uncommitted changes
included, via `try-repo`), so this needs the package index to be reachable, as in CI.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from val3check.testing import write_app

ROOT = Path(__file__).resolve().parent.parent
_BESIDE = Path(sys.executable).parent / "pre-commit"  # the one installed with the test extra
PRE_COMMIT = str(_BESIDE) if _BESIDE.exists() else (shutil.which("pre-commit") or str(_BESIDE))


def git(repo: Path, *args: str) -> None:
    subprocess.run(["git", *args], cwd=repo, check=True, capture_output=True)


@pytest.fixture(scope="module")
def home(tmp_path_factory):
    # pre-commit's cache (clones and environments) stays inside the test's temporary folder
    return tmp_path_factory.mktemp("pre-commit-home")


def try_repo(repo: Path, home: Path) -> subprocess.CompletedProcess:
    env = dict(os.environ, PRE_COMMIT_HOME=str(home), GIT_CONFIG_NOSYSTEM="1")
    return subprocess.run(
        [PRE_COMMIT, "try-repo", str(ROOT), "val3check", "--all-files", "--verbose"],
        cwd=repo, capture_output=True, text=True, env=env, timeout=900,
    )


@pytest.mark.skipif(not Path(PRE_COMMIT).exists(), reason="pre-commit is not installed (pip install -e '.[test]')")
def test_hook_through_pre_commit(tmp_path, home):
    repo = tmp_path / "cell"
    repo.mkdir()
    git(repo, "init", "-q")
    git(repo, "config", "user.email", "t@example.invalid")
    git(repo, "config", "user.name", "t")
    write_app(repo, "begin\n  nX = 1\nend\n", name="Good", globals_=["num nX"])
    (repo / "notes.txt").write_text("not VAL 3\n")
    git(repo, "add", "-A")
    ok = try_repo(repo, home)
    assert ok.returncode == 0, ok.stdout + ok.stderr
    assert "Passed" in ok.stdout

    write_app(repo, "begin\n  while true\n  endFor\nend\n", name="Bad")
    git(repo, "add", "-A")
    bad = try_repo(repo, home)
    assert bad.returncode == 1, bad.stdout + bad.stderr
    assert "Failed" in bad.stdout
    assert "Bad/start.pgx:6:3: F101" in bad.stdout
