"""Issue 21: the fuzz suite on sweep files and the batch (generators in fuzzing_batch.py).
Generated sweeps (hostile paths, globs, arms, overrides, random text) in a repository holding a
link loop and links leading out: the cases are made or the sweep refused at its file, the batch
command ends with 0, 1 or 2 and no traceback, and no byte of a secret beside the repository is
carried, printed or written.

Bounded for CI as test_hostile_fuzz.py (its profile: VAL3CHECK_FUZZ_EXAMPLES examples,
derandomized); the batch command's property runs a third of them (each runs cases).
`python bench/fuzz.py -k sweep` runs them longer with fresh inputs."""

from __future__ import annotations

import os

from hypothesis import event, given, settings

from .fuzzing_batch import SWEEP, check_cases, cleanup, make_cases, make_repository, run_sweep
from .test_hostile_fuzz import EXAMPLES  # loads the val3check-ci profile


@given(SWEEP)
def test_sweep_files_make_cases_inside_their_repository_or_are_refused(text):
    tmp = make_repository()
    try:
        event(check_cases(make_cases(text, tmp), tmp))
    finally:
        cleanup(tmp)


@settings(max_examples=max(3, EXAMPLES // 3))
@given(SWEEP)
def test_the_batch_command_ends_cleanly_on_any_sweep(text):
    from val3check.batch import cases, sweep

    tmp = make_repository()
    limits = sweep.MAX_CASES, cases.MAX_CASES
    sweep.MAX_CASES = cases.MAX_CASES = 4  # a few cases each: the property is about what surrounds them
    try:
        code, _, err = run_sweep(text, tmp)
        event(f"exit {code}" + (f": {err.split(': ')[2][:30]}" if code == 2 and err.count(": ") >= 2 else ""))
    finally:
        sweep.MAX_CASES, cases.MAX_CASES = limits
        cleanup(tmp)


def test_the_repository_of_the_fuzz_suite_holds_what_it_promises():
    """The generators' repository: a link loop, a link leading out, a cell leading out."""
    tmp = make_repository()
    try:
        repo = tmp / "repo"
        assert os.path.realpath(repo / "loop" / "l1") == os.path.realpath(repo / "loop")
        assert not os.path.realpath(repo / "link-out").startswith(os.path.realpath(repo))
        assert os.path.islink(repo / "apps" / "A" / "val3check-cell.toml")
    finally:
        cleanup(tmp)
