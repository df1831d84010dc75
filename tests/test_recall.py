"""Recall on planted errors (issue 3), fast version of bench/bench_recall.py: a few mutants of
every kind of bench/plant.py over four valid fixtures (s7 with a library and a user type, a
collection, s6) must all be found, with the right code, at the planted line and column."""

from __future__ import annotations

import hashlib
import shutil
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))

from bench_recall import lint_mutant, real_path  # noqa: E402
from plant import KINDS, plant_workspace  # noqa: E402

from val3check.config import Settings  # noqa: E402
from val3check.loading import load  # noqa: E402

FIXTURES = ROOT / "fixtures" / "valid"
APPS = ("Cell", "SerialParser", "Sorter", "S6Menu")
PER_KIND = 2


def _digest() -> str:
    h = hashlib.sha256()
    for path in sorted(FIXTURES.rglob("*")):
        if path.is_file():
            h.update(str(path).encode() + b"\0" + path.read_bytes())
    return h.hexdigest()


BEFORE = _digest()


@pytest.fixture(scope="module")
def outcomes(tmp_path_factory):
    root = real_path(str(FIXTURES))
    copy = tmp_path_factory.mktemp("recall") / "valid"
    shutil.copytree(root, copy)
    ws, _ = load([str(FIXTURES / app) for app in APPS])
    out = []
    for key in ws.targets:
        app = ws.apps[key]
        app_copy = str(copy / Path(real_path(app.path)).relative_to(root))
        for m in plant_workspace(ws, app, per_kind=PER_KIND, seed=3):
            out.append(lint_mutant(m, root, str(copy), app_copy, Settings()))
    return out


def test_every_kind_is_planted(outcomes):
    assert {o.mutant.kind for o in outcomes} == set(KINDS)
    assert not [o for o in outcomes if o.bad], "plant.py made a mutant that does not read back as planned"


def test_every_planted_error_is_found_at_its_place(outcomes):
    misses = [f"{o.mutant.kind} {o.mutant.code} {Path(o.mutant.path).name}:{o.mutant.line}:{o.mutant.col} "
              f"{o.mutant.before!r} -> {o.mutant.after!r}: {o.reported}" for o in outcomes if not o.found]
    assert misses == []


def test_the_inputs_are_not_modified(outcomes):
    assert _digest() == BEFORE
