"""The pre-commit hook through pre-commit itself, configured as the README says, in fresh
repositories (issue 16 items 2 and 3; issue 28 item 5).

A mirror of this checkout (uncommitted changes included) is made into a git repository with no
tag, as a clone of val3check may be; the README's snippet is used as written with only its
`repo:` pointed at the mirror, then pinned as the README says (`pre-commit autoupdate --freeze`).
pre-commit installs val3check from it into its own environment, so this needs the package index
to be reachable, as in CI. The README's local hook runs the val3check of this environment.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from val3check.testing import write_app

ROOT = Path(__file__).resolve().parent.parent
_BESIDE = Path(sys.executable).parent / "pre-commit"  # the one installed with the test extra
PRE_COMMIT = str(_BESIDE) if _BESIDE.exists() else (shutil.which("pre-commit") or str(_BESIDE))
pytestmark = pytest.mark.skipif(not Path(PRE_COMMIT).exists(),
                                reason="pre-commit is not installed (pip install -e '.[test]')")


def git(repo: Path, *args: str) -> str:
    env = dict(os.environ, GIT_CONFIG_NOSYSTEM="1", GIT_AUTHOR_NAME="t", GIT_AUTHOR_EMAIL="t@example.invalid",
               GIT_COMMITTER_NAME="t", GIT_COMMITTER_EMAIL="t@example.invalid")
    return subprocess.run(["git", *args], cwd=repo, check=True, capture_output=True, text=True, env=env).stdout


def readme_snippets() -> list[str]:
    """The README's pre-commit configurations (the YAML blocks of its pre-commit section)."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    section = text[text.index("### pre-commit"):]
    section = section[:section.index("\n## ")]
    return re.findall(r"```yaml\n(.*?)```", section, re.S)


def readme_snippet() -> str:
    return readme_snippets()[0]


def test_the_readme_names_a_revision_every_clone_has():
    rev = re.search(r"^\s*rev:\s*(\S+)", readme_snippet(), re.M).group(1)
    assert rev == "HEAD"  # not a tag: a clone may have none (issue 28 item 5)


@pytest.fixture(scope="module")
def home(tmp_path_factory):
    # pre-commit's cache (clones and environments) stays inside the test's temporary folder
    return tmp_path_factory.mktemp("pre-commit-home")


@pytest.fixture(scope="module")
def mirror(tmp_path_factory):
    """This checkout as a repository of its own, without any tag."""
    repo = tmp_path_factory.mktemp("mirror")
    files = subprocess.run(["git", "ls-files", "-co", "--exclude-standard"], cwd=ROOT, check=True,
                           capture_output=True, text=True).stdout.split("\n")
    for rel in filter(None, files):
        source = ROOT / rel
        if source.is_file():
            (repo / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source, repo / rel)
    git(repo, "init", "-q")
    git(repo, "add", "-A")
    git(repo, "commit", "-qm", "mirror")
    assert git(repo, "tag") == ""
    return repo


def _cell(tmp_path: Path, mirror: Path, snippet: str | None = None) -> Path:
    repo = tmp_path / "cell"
    repo.mkdir()
    git(repo, "init", "-q")
    config = re.sub(r"(?m)^(\s*- repo:)\s*https?://\S+", rf"\1 {mirror}", snippet or readme_snippet())
    (repo / ".pre-commit-config.yaml").write_text(config)
    return repo


def pre_commit(repo: Path, home: Path, *args: str) -> subprocess.CompletedProcess:
    env = dict(os.environ, PRE_COMMIT_HOME=str(home), GIT_CONFIG_NOSYSTEM="1",
               PATH=str(Path(sys.executable).parent) + os.pathsep + os.environ.get("PATH", ""))
    return subprocess.run([PRE_COMMIT, *args], cwd=repo, capture_output=True, text=True, env=env, timeout=900)


def run(repo: Path, home: Path, *args: str) -> subprocess.CompletedProcess:
    return pre_commit(repo, home, "run", *args, "--verbose")


def test_the_readme_snippet_in_a_fresh_repository(tmp_path, home, mirror):
    repo = _cell(tmp_path, mirror)
    write_app(repo, "begin\n  nX = 1\nend\n", name="Good", globals_=["num nX"])
    (repo / "notes.txt").write_text("not VAL 3\n")
    git(repo, "add", "-A")
    ok = run(repo, home, "--all-files")  # as written: rev HEAD
    assert ok.returncode == 0, ok.stdout + ok.stderr
    assert "Passed" in ok.stdout
    # pinned as the README says: the mirror's commit, by its full SHA
    pinned = pre_commit(repo, home, "autoupdate", "--freeze")
    assert pinned.returncode == 0, pinned.stdout + pinned.stderr
    sha = git(mirror, "rev-parse", "HEAD").strip()
    assert re.search(rf"^\s*rev:\s*{sha}\b", (repo / ".pre-commit-config.yaml").read_text(), re.M)
    git(repo, "add", "-A")
    ok = run(repo, home, "--all-files")
    assert ok.returncode == 0, ok.stdout + ok.stderr

    write_app(repo, "begin\n  while true\n  endFor\nend\n", name="Bad")
    git(repo, "add", "-A")
    bad = run(repo, home, "--all-files")
    assert bad.returncode == 1, bad.stdout + bad.stderr
    assert "Failed" in bad.stdout
    assert "Bad/start.pgx:6:3: F101" in bad.stdout


def test_a_commit_touching_only_excluded_files_passes(tmp_path, home, mirror):
    repo = _cell(tmp_path, mirror)
    write_app(repo, "begin\n  nX = 1\nend\n", name="Good", globals_=["num nX"])
    git(repo, "add", "-A")
    git(repo, "commit", "-qm", "the cell")
    # Stäubli's templates of a controller tree (excluded by default), with an error val3check would report
    write_app(repo / "controller" / "usr" / "templates", "begin\n  if true\nend\n", name="Tpl")
    git(repo, "add", "-A")
    r = run(repo, home)  # the staged files, as `git commit` runs it
    assert r.returncode == 0, r.stdout + r.stderr
    assert "Passed" in r.stdout and "nothing to check" in r.stdout
    # the same files without the exclusion fail
    (repo / "val3check.toml").write_text("exclude = []\n")
    git(repo, "add", "-A")
    r = run(repo, home)
    assert r.returncode == 1 and "Tpl/start.pgx" in r.stdout


def test_the_readme_local_hook(tmp_path, home):
    """The README's hook for the val3check of the environment (`language: system`)."""
    local = readme_snippets()[1]
    assert "repo: local" in local
    repo = _cell(tmp_path, Path("unused"), local)
    write_app(repo, "begin\n  while true\n  endFor\nend\n", name="Bad")
    git(repo, "add", "-A")
    bad = run(repo, home, "--all-files")
    assert bad.returncode == 1, bad.stdout + bad.stderr
    assert "Bad/start.pgx:6:3: F101" in bad.stdout
