"""Issue 21, hostile input round 2, the batch's surfaces: a sweep's arms (A), the cell beside an
application in a batch (B), globs (E), a sweep's size (F), NUL bytes in paths and --out-dir (I),
a case stuck outside VAL 3 code (K). Each test fails without its fix."""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path

import pytest

from val3check.cli import main

ROOT = Path(__file__).resolve().parent.parent.parent
PICKPLACE = ROOT / "fixtures" / "valid" / "PickPlace"
SCENARIO = ROOT / "fixtures" / "scenarios" / "pickplace.toml"
SECRET = "TOPSECRET-do-not-print"
FAST = ["--duration", "2"]


@pytest.fixture
def repo(tmp_path, monkeypatch):
    """tmp/repo: a git repository holding apps/A (PickPlace without its cell) and the scenario;
    tmp/outside: secrets, beside the repository."""
    (tmp_path / "outside").mkdir()
    (tmp_path / "outside" / "cell.toml").write_text(f'unit = "{SECRET}"\n')
    (tmp_path / "outside" / "secret.urdf").write_text(f"<robot name='{SECRET}'><link name='{SECRET}'/></robot>\n")
    repo = tmp_path / "repo"
    (repo / ".git").mkdir(parents=True)
    shutil.copytree(PICKPLACE, repo / "apps" / "A")
    (repo / "apps" / "A" / "val3check-cell.toml").unlink()
    shutil.copy(SCENARIO, repo / "pickplace.toml")
    monkeypatch.chdir(repo)
    return repo


def sim(capsys, *args):
    code = main(["sim", *map(str, args)])
    out, err = capsys.readouterr()
    assert "Traceback" not in err and SECRET not in out + err, out + err
    return code, out, err


# -- B: the cell beside an application, in a batch as in the single run ------------------------

def test_a_cell_file_beside_the_application_leading_out_is_refused_in_a_batch_as_alone(repo, capsys):
    os.symlink(repo.parent / "outside" / "cell.toml", repo / "apps" / "A" / "val3check-cell.toml")
    args = ["apps/A", "--robot", "tx2-60", "--scenario", "pickplace.toml", *FAST]
    code, single, _ = sim(capsys, *args, "--report", "json")
    (r030,) = [d for d in json.loads(single)["diagnostics"] if d["code"] == "R030"]
    assert "outside the application" in r030["message"]
    for jobs in ("1", "2"):
        code, out, err = sim(capsys, *args, "-j", jobs, "--out-dir", f"out{jobs}", "--format", "json")
        (case,) = json.loads(out)["cases"]
        assert "R030" in case["reason"] and "outside the application" in case["reason"], case
        (report,) = (repo / f"out{jobs}" / "cases").iterdir()
        assert report.read_text() == single  # byte for byte the single run's report
        assert SECRET not in "".join(p.read_text() for p in (repo / f"out{jobs}").rglob("*") if p.is_file())


def test_what_a_case_carries_never_holds_a_refused_file(repo):
    """The bytes of a cell leading out never travel with the case (to a Dask cluster); a link
    does, with a stand-in of no content for its target."""
    from val3check.batch.cases import Axes, RunOptions, product_cases
    from val3check.config import Settings

    os.symlink(repo.parent / "outside" / "cell.toml", repo / "apps" / "A" / "val3check-cell.toml")
    (case,) = product_cases(Axes(["apps/A"], ["tx2-60"], [], [], []), Settings(), RunOptions())
    assert not any(SECRET.encode() in data for _, data in case.files)
    assert dict(case.links) == {str(repo / "apps" / "A" / "val3check-cell.toml"): str(repo.parent / "outside" / "cell.toml")}
    assert dict(case.stubs) == {str(repo.parent / "outside" / "cell.toml"): 0}


def test_a_cell_and_its_meshes_reached_through_links_inside_run_as_alone(repo, capsys):
    """A cell file that is a link to a file inside the application, naming a mesh through a link
    inside too, and one leading out: the case's report is the single run's."""
    folder = repo / "apps" / "A"
    (folder / "cells").mkdir()
    shutil.copy(PICKPLACE / "val3check-cell.toml", folder / "cells" / "main.toml")
    with open(folder / "cells" / "main.toml", "a") as fh:
        fh.write('\n[[obstacle]]\nname = "guard"\nshape = "mesh"\nfile = "guard.stl"\nsolid = false\nat = [900, 900, 0, 0, 0, 0]\n'
                 '\n[[obstacle]]\nname = "leak"\nshape = "mesh"\nfile = "leak.stl"\nat = [900, -900, 0, 0, 0, 0]\n')
    (folder / "meshes").mkdir()
    (folder / "meshes" / "guard.stl").write_text("solid g\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 10 0 0\n"
                                                "vertex 0 10 0\nendloop\nendfacet\nendsolid g\n")
    os.symlink("../meshes/guard.stl", folder / "cells" / "guard.stl")
    os.symlink(repo.parent / "outside" / "cell.toml", folder / "cells" / "leak.stl")
    os.symlink("cells/main.toml", folder / "val3check-cell.toml")
    args = ["apps/A", "--robot", "tx2-60", "--scenario", "pickplace.toml", *FAST]
    _, single, _ = sim(capsys, *args, "--report", "json")
    assert "leak.stl" in single and "guard.stl" not in single  # the leak refused, the guard read
    sim(capsys, *args, "-j", "1", "--out-dir", "out")
    (report,) = (repo / "out" / "cases").iterdir()
    assert report.read_text() == single
