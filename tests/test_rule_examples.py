"""Every example of every rule in rules/ behaves: bad ones trigger the rule, good ones do not."""

from __future__ import annotations

import re

import pytest

from val3check.config import Settings, load_settings
from val3check.rules.catalogue import FAMILIES, catalogue
from support import lint

from val3check.testing import code_position, write_app, write_files

RULES = catalogue()


def _cases():
    for rule in RULES.values():
        for kind, examples in (("bad", rule.bad), ("good", rule.good)):
            for i, ex in enumerate(examples):
                yield pytest.param(rule, kind, ex, id=f"{rule.code}-{kind}{i}")


def _bytes(text: str) -> bytes:
    return re.sub(rb"\\x([0-9A-Fa-f]{2})", lambda m: bytes([int(m.group(1), 16)]), text.encode("utf-8"))


def _run(tmp_path, ex, rule=None):
    if ex.code is not None:
        folder = write_app(tmp_path, ex.code, globals_=ex.globals, locals_=ex.locals, programs=ex.programs,
                           version=ex.version)
        target = folder
    else:
        write_files(tmp_path, {k: _bytes(v) if ex.byte_escapes else v for k, v in ex.files.items()})
        target = tmp_path / ex.target
    settings = Settings()
    if ex.config is not None:
        (tmp_path / "val3check.toml").write_text(ex.config, encoding="utf-8")
        settings = load_settings(str(tmp_path / "val3check.toml"))
    if rule is not None and rule.opt_in:  # an opt-in rule's examples run with the rule selected
        settings.extend_select.append(rule.code)
    return lint([target], settings, cwd=tmp_path)


def _simulate(tmp_path, ex):
    """Runtime (R) rules fire when the application runs: their examples go through `sim`
    (`code`: a generated application; `files`: an application tree, `target` the one run)."""
    from interpretation.simsupport import run_folder, sim

    robot = None
    if ex.robot:
        from val3check.robot import load_robot

        from pathlib import Path

        # a catalogue name, or a URDF of the repository (tests/data/robots/...)
        root = Path(__file__).resolve().parent.parent
        robot = load_robot(str(root / ex.robot) if ex.robot.endswith(".urdf") else ex.robot)
    opts = {}
    if ex.cell is not None:  # collision rules: the cell of the run
        (tmp_path / "cell.toml").write_text(ex.cell, encoding="utf-8")
        opts = {"cell": str(tmp_path / "cell.toml"), "collisions": True}
    if ex.code is None:
        write_files(tmp_path, ex.files)
        return run_folder(tmp_path / ex.target, tmp_path=tmp_path, duration=ex.duration, robot=robot,
                          **opts).diagnostics
    result = sim(tmp_path, ex.code, globals_=ex.globals, locals_=ex.locals, programs=ex.programs,
                 scenario=ex.scenario, duration=ex.duration, links=ex.links or None, robot=robot, **opts)
    return result.diagnostics


@pytest.mark.parametrize("rule,kind,ex", list(_cases()))
def test_example(tmp_path, rule, kind, ex):
    if rule.family == "R":
        found = _simulate(tmp_path, ex)
    else:
        found = _run(tmp_path, ex, rule).result.diagnostics
    hits = [d for d in found if d.code == rule.code]
    if kind == "good":
        assert not hits, f"{rule.code} fired on its good example: {hits}"
        return
    assert hits, f"{rule.code} did not fire on its bad example; got {found}"
    if ex.severity is not None:  # shown with another severity than the rule's (a finding from a guess...)
        assert {d.severity.label for d in hits} == {ex.severity}, f"{rule.code}: expected {ex.severity}: {hits}"
    got = [(d.path.replace("\\", "/"), d.line, d.col) for d in hits]
    for spec in ex.expect:
        parts = spec.split(":")
        if ex.code is not None and len(parts) == 3:  # a position in another file (the cell file: R030...)
            where = (parts[0], int(parts[1]), int(parts[2]))
        elif ex.code is not None:
            pgx = (tmp_path / "Example" / "start.pgx").read_text(encoding="utf-8")
            line, col = code_position(int(parts[0]), int(parts[1]), pgx)
            where = ("Example/start.pgx", line, col)
        else:
            where = (parts[0], int(parts[1]), int(parts[2]))
        # lint reports display paths, sim absolute ones: compare the tail
        assert any(p.endswith(where[0]) and (l, c) == where[1:] for p, l, c in got), (
            f"{rule.code}: expected at {where}, got {got}"
        )


def test_every_rule_has_both_examples():
    for rule in RULES.values():
        assert rule.bad, f"{rule.code} has no failing example"
        assert rule.good, f"{rule.code} has no passing example"


def test_codes_names_and_families():
    names = [r.name for r in RULES.values()]
    assert len(names) == len(set(names)), "rule names must be unique"
    for rule in RULES.values():
        assert rule.family in FAMILIES, rule.code
        assert len(rule.code) == 4 and rule.code[1:].isdigit(), rule.code
        assert rule.name == rule.name.lower() and " " not in rule.name, rule.code
        assert rule.summary.strip() and rule.explanation.strip(), rule.code


def test_opt_in_rules_are_the_ones_their_files_say():
    from val3check.rules.catalogue import OPT_IN

    assert {r.code for r in RULES.values() if r.opt_in} == set(OPT_IN)


def test_an_opt_in_rule_runs_only_when_named(tmp_path):
    from val3check.rules.catalogue import OPT_IN

    code = next(iter(sorted(OPT_IN)))
    assert not Settings().enabled(code)
    assert not Settings(select=[code[0]]).enabled(code)  # a prefix does not select it
    assert Settings(extend_select=[code]).enabled(code)
    assert Settings(select=[code]).enabled(code)
    assert not Settings(extend_select=[code], ignore=[code]).enabled(code)
