"""Issue 9 item 1: no path written in a file makes val3check read, or print, a file outside the
application and its configured roots (val3check/confine.py, rule F014)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from loading.loadhelp import make_app, pgx, pjx, write

from val3check.confine import Refused, Roots, check, read_bytes, repository_root
from val3check.loading import LoadOptions, load
from val3check.loading.resolve import resolve_library

ROOT = Path(__file__).resolve().parent.parent.parent
SECRET = "TOPSECRET-do-not-print"


def val3check(*args, cwd):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    return subprocess.run([sys.executable, "-m", "val3check", *map(str, args)], capture_output=True, text=True,
                          cwd=cwd, env=env, timeout=120)


def _secret_tree(tmp_path: Path) -> Path:
    """tmp/outside/ holds secrets in every shape a loader might accept; tmp/repo is a git
    repository holding the application."""
    out = tmp_path / "outside"
    write(out / "secret.txt", f"{SECRET}\n")
    write(out / "Secret" / "Secret.pjx", f"<{SECRET}>\n")  # a broken project: F004 would quote it
    write(out / "Good" / "Good.pjx", pjx(programs=("start.pgx",)).replace("<Programs>", f"<!-- {SECRET} -->\n  <Programs>"))
    write(out / "Good" / "start.pgx", pgx("start", f"begin\n  // {SECRET}\n  x = \nend"))
    (tmp_path / "repo" / ".git").mkdir(parents=True)
    return out


HOSTILE_PATHS = [
    "Disk://../../outside/secret.txt",
    "Disk://../../outside/Secret",
    "Disk://../../outside/Good/Good.pjx",
    "../../outside/Secret/Secret.pjx",
    "{out}/Secret/Secret.pjx",
    "{out}/secret.txt",
    "Disk://../../../../../../../../../../etc/passwd",
    "/etc/passwd",
    "/proc/self/environ",
    "Disk:\\\\..\\..\\outside\\Secret",
    "USB0://../../outside/Good",
]


@pytest.mark.parametrize("path", HOSTILE_PATHS)
@pytest.mark.parametrize("kind", ["library", "type"])
def test_library_and_type_paths_are_confined(tmp_path, path, kind):
    out = _secret_tree(tmp_path)
    path = path.format(out=out)
    app = make_app(tmp_path / "repo" / "App", **({"libraries": [("x", path)]} if kind == "library" else
                                                 {"types": [("T", path)]}))
    ws, diags = load([str(app.parent)])
    got = [(d.code, d.path, d.line) for d in diags]
    assert got == [("F014", str(app), 11 if kind == "library" else 13)], got
    assert path in diags[0].message  # the path as written, never the content
    assert all(not f.startswith(str(out)) for a in ws.apps.values() for f in a.files)
    assert not any(SECRET in d.message for d in diags)


def test_symbolic_link_to_a_library_outside_is_refused(tmp_path):
    out = _secret_tree(tmp_path)
    app = make_app(tmp_path / "repo" / "App", libraries=[("x", "Disk://Good")])
    os.symlink(out / "Good", tmp_path / "repo" / "Good")  # the library folder is a link that leads out
    ws, diags = load([str(app.parent)])
    assert [(d.code, d.line) for d in diags if d.path == str(app)] == [("F014", 11)]
    assert all(str(out) not in f for a in ws.apps.values() for f in a.files)


def test_disk_root_resolution_stays_inside_the_disk_root(tmp_path):
    out = _secret_tree(tmp_path)
    disk = tmp_path / "repo" / "disk"
    make_app(disk / "Lib")
    app = make_app(tmp_path / "repo" / "App", libraries=[("lib", "Disk://Lib"), ("x", "Disk://../../outside/Good")])
    ws, diags = load([str(app)], LoadOptions(disk_roots=[str(disk)]))
    assert [d.code for d in diags] == ["F014"]
    assert ws.apps[str(app)].libraries["lib"].resolved == str(disk / "Lib" / "Lib.pjx")
    assert all(str(out) not in f for a in ws.apps.values() for f in a.files)


def test_the_repository_bounds_the_search_upwards(tmp_path):
    # Disk://Up/Up.pjx exists two folders above the repository: not searched (no .git: the lint
    # root is the repository)
    make_app(tmp_path / "Up")
    app = make_app(tmp_path / "a" / "b" / "App", libraries=[("up", "Disk://Up/Up.pjx")])
    ws, diags = load([str(app)])
    assert [d.code for d in diags] == ["L001"]
    assert repository_root(str(app)) == str(app.parent)


def test_a_folder_walk_does_not_follow_links_out(tmp_path):
    out = _secret_tree(tmp_path)
    repo = tmp_path / "repo"
    make_app(repo / "App")
    os.symlink(out, repo / "elsewhere")
    os.symlink(out / "secret.txt", repo / "App" / "notes.pgx")
    ws, diags = load([str(repo)])
    found = sorted((d.code, os.path.basename(d.path)) for d in diags)
    assert ("F014", "elsewhere") in found
    assert all(str(out) not in f for a in ws.apps.values() for f in a.files)


def test_special_and_non_regular_files(tmp_path):
    repo = tmp_path / "repo"
    app = make_app(repo / "App", programs=("start",))
    os.mkfifo(repo / "App" / "pipe.pgx")
    os.mkfifo(repo / "Other.pjx")
    text = app.read_text().replace('<Program file="start.pgx" />', '<Program file="start.pgx" />\n    <Program file="pipe.pgx" />')
    app.write_text(text)
    ws, diags = load([str(repo)])
    msgs = {(d.code, os.path.basename(d.path)): d.message for d in diags}
    assert "named pipe" in msgs[("F001", "App.pjx")]  # listed: at the listing line, not "broken link"
    assert "named pipe" in msgs[("F001", "Other.pjx")]  # a FIFO project: reported, not ignored
    for special in ("/proc/self/environ", "/dev/zero", "/dev/urandom"):
        with pytest.raises(Refused) as err:
            read_bytes(special, Roots.user_given(), 1 << 20)
        assert err.value.code == "F001"


def test_check_refuses_by_real_path(tmp_path):
    inside = tmp_path / "in"
    inside.mkdir()
    (tmp_path / "s.txt").write_text("x")
    os.symlink(tmp_path / "s.txt", inside / "link.pgx")
    with pytest.raises(Refused) as err:
        check(str(inside / "link.pgx"), Roots([str(inside)]))
    assert err.value.code == "F014"
    assert check(str(tmp_path / "s.txt"), Roots([str(tmp_path)])) == os.path.realpath(tmp_path / "s.txt")


def test_runtime_library_paths_are_confined(tmp_path):
    out = _secret_tree(tmp_path)
    app = make_app(tmp_path / "repo" / "App")
    roots = Roots([str(tmp_path / "repo")])
    for path in ("Disk://../../outside/Good", "/etc/passwd", f"{out}/Good/Good.pjx", "Disk://etc/passwd"):
        assert resolve_library(path, str(app), [], roots) is None


def test_no_finding_prints_content_from_outside(tmp_path):
    """Every output format, every hostile path: the secret never reaches stdout or stderr."""
    out = _secret_tree(tmp_path)
    libs = [(f"l{i}", p.format(out=out)) for i, p in enumerate(HOSTILE_PATHS)]
    types = [(f"T{i}", p.format(out=out)) for i, p in enumerate(HOSTILE_PATHS)]
    app = make_app(tmp_path / "repo" / "App", libraries=libs, types=types)
    os.symlink(out / "Secret" / "Secret.pjx", app.parent / "Linked.pjx")
    os.symlink(out / "secret.txt", app.parent / "linked.pgx")
    os.symlink(out, tmp_path / "repo" / "link-out")
    for fmt in ("text", "json", "sarif", "junit", "github"):
        r = val3check("lint", "--format", fmt, ".", cwd=tmp_path / "repo")
        assert r.returncode in (0, 1), r.stderr
        assert SECRET not in r.stdout + r.stderr, fmt
        assert "root:" not in r.stdout and "PATH=" not in r.stdout
        if fmt == "json":
            assert {d["code"] for d in json.loads(r.stdout)["diagnostics"]} >= {"F014"}
    r = val3check("sim", "App", "--duration", "1", cwd=tmp_path / "repo")
    assert SECRET not in r.stdout + r.stderr and "Traceback" not in r.stderr


def test_excerpts_only_from_files_read_as_val3(tmp_path):
    (tmp_path / "notes.txt").write_text(f"{SECRET} <\n")
    r = val3check("lint", "notes.txt", cwd=tmp_path)
    assert r.returncode == 2
    assert "F006" in r.stdout and "not a VAL 3 file" in r.stdout and SECRET not in r.stdout  # named, never quoted
    broken = tmp_path / "App"
    make_app(broken)
    (broken / "start.pgx").write_text("<Programs>\n  <oops & </Programs>\n")
    r = val3check("lint", "App", cwd=tmp_path)
    assert "<oops &" in r.stdout  # a VAL 3 file of the application is still quoted
