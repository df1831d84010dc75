"""Issue 25 class 6: a project file named `.pjx` (a dot-file: a project without a name) is read
like any project file, whether the folder or the file is named: everything the user names is
checked or reported."""

from __future__ import annotations

from support import lint

from .loadhelp import make_app


def _dot_app(tmp_path):
    pjx = make_app(tmp_path / "repo" / "Cell", programs=("start", "stop", "pick"))
    dot = pjx.with_name(".pjx")
    pjx.rename(dot)
    return dot


def test_a_folder_with_a_dot_pjx_is_an_application(tmp_path):
    dot = _dot_app(tmp_path)
    run = lint([tmp_path / "repo"], cwd=tmp_path)
    assert run.result.applications == ["repo/Cell/.pjx"]
    assert [d.code for d in run.result.diagnostics] == []  # not "no project file" (F009)
    assert run.workspace.apps[str(dot)].name == "Cell"


def test_its_findings_are_reported(tmp_path):
    dot = _dot_app(tmp_path)
    dot.write_text(dot.read_text().replace("pick.pgx", "place.pgx"))
    found = lint([dot], cwd=tmp_path).result.diagnostics
    assert [(d.code, d.path) for d in found if d.code == "F001"] == [("F001", "repo/Cell/.pjx")]
