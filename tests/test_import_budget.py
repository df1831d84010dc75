"""`val3check lint` must start fast: it imports no robotics or numeric package."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
HEAVY = ("pinocchio", "trimesh", "fcl", "mcap", "numpy", "scipy", "example_robot_data", "dask", "distributed")


def test_lint_imports_nothing_heavy():
    code = (
        "import sys, runpy\n"
        "sys.argv = ['val3check', 'lint', 'fixtures/valid/Cell', '--format', 'json']\n"
        "try:\n    runpy.run_module('val3check', run_name='__main__')\nexcept SystemExit:\n    pass\n"
        f"heavy = sorted(m for m in sys.modules if m.split('.')[0] in {HEAVY!r})\n"
        "print('HEAVY', heavy, file=sys.stderr)\n"
    )
    r = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert "HEAVY []" in r.stderr, r.stderr


def test_lint_process_runs_without_the_cyclic_collector_and_main_leaves_it_alone(tmp_path):
    """`val3check lint` as a process keeps the collector off to the end and freezes what is left
    (cli._short_lived); `main(argv)` called by another program leaves its collector as it was."""
    code = (
        "import gc, sys, runpy\n"
        "sys.argv = ['val3check', 'lint', 'fixtures/valid/Cell']\n"
        "try:\n    runpy.run_module('val3check', run_name='__main__')\nexcept SystemExit:\n    pass\n"
        "print('GC', gc.isenabled(), gc.get_freeze_count() > 0, file=sys.stderr)\n"
        "from val3check.cli import main\n"
        "gc.enable()\n"
        "main(['lint', 'fixtures/valid/Cell'])\n"
        "print('MAIN', gc.isenabled(), file=sys.stderr)\n"
    )
    r = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert "GC False True" in r.stderr, r.stderr
    assert "MAIN True" in r.stderr, r.stderr


def test_lint_process_imports_without_the_cyclic_collector():
    """`python -m val3check lint` turns the collector off before its first import of the command
    line (val3check/__main__.py); another command keeps it on."""
    code = (
        "import gc, sys, runpy\n"
        "seen = []\n"
        "sys.addaudithook(lambda e, a: seen.append(gc.isenabled()) if e == 'import' and a[0] == 'val3check.cli' "
        "else None)\n"
        "sys.argv = ['val3check', sys.argv[1], 'fixtures/valid/Cell']\n"
        "try:\n    runpy.run_module('val3check', run_name='__main__')\nexcept SystemExit:\n    pass\n"
        "print('IMPORTED', seen[:1], file=sys.stderr)\n"
    )
    r = subprocess.run([sys.executable, "-c", code, "lint"], cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert "IMPORTED [False]" in r.stderr, r.stderr
    r = subprocess.run([sys.executable, "-c", code, "rules"], cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert "IMPORTED [True]" in r.stderr, r.stderr


def test_lint_leaves_out_what_it_does_not_use():
    """Not the sim command's module, nor shutil (bz2, lzma) for argparse's terminal width, nor json
    unless an s8 application has user pages (cli._terminal_columns, loading.bindings), nor typing
    (annotations only: `if TYPE_CHECKING`), nor difflib unless a name is not found, nor threading
    (the parser's lock is `_thread`'s)."""
    code = (
        "import sys, runpy\n"
        "sys.argv = ['val3check', 'lint', 'fixtures/valid/Cell']\n"
        "try:\n    runpy.run_module('val3check', run_name='__main__')\nexcept SystemExit:\n    pass\n"
        "print('LOADED', sorted(m for m in ('val3check.cli.sim_command', 'shutil', 'bz2', 'lzma', 'json',"
        " 'typing', 'difflib', 'threading')"
        " if m in sys.modules), file=sys.stderr)\n"
    )
    r = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert "LOADED []" in r.stderr, r.stderr


def _sim_modules(tmp_path, *extra: str) -> str:
    """Standard error of `val3check sim` (the bundled pick-and-place, 1 s, its cell) run as a
    process of its own, ending with the modules it imported and whether its collector froze."""
    code = (
        "import gc, sys, runpy\n"
        f"sys.argv = ['val3check', 'sim', 'fixtures/valid/PickPlace', '--robot', 'tx2-60', '--scenario',"
        f" 'fixtures/scenarios/pickplace.toml', '--duration', '1', '--max-wall', '600', '--report', 'json', '-o',"
        f" {str(tmp_path / 'r.json')!r}, *{list(extra)!r}]\n"
        "try:\n    runpy.run_module('val3check', run_name='__main__')\nexcept SystemExit:\n    pass\n"
        "roots = sorted({m.split('.')[0] for m in sys.modules})\n"
        "print('ROOTS', roots, file=sys.stderr)\n"
        "print('BATCH', sorted(m for m in sys.modules if m.startswith('val3check.batch')), file=sys.stderr)\n"
        "print('FROZEN', gc.get_freeze_count() > 0, gc.get_threshold(), file=sys.stderr)\n"
    )
    r = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert (tmp_path / "r.json").is_file(), r.stderr
    return r.stderr


def test_sim_imports_only_what_its_run_uses(tmp_path):
    """One application: none of the batch's modules (cli.sim_command.wants_batch); no trace: not
    mcap; a cell without meshes: not trimesh; no pinocchio (the arm's kinematics are our own),
    no Dask. The process freezes its collector once linted and collects its young generation less
often (cli.sim_command.freeze_before_run)."""
    err = _sim_modules(tmp_path)
    roots = err.split("ROOTS ")[1].splitlines()[0]
    for name in ("mcap", "trimesh", "pinocchio", "dask", "distributed", "example_robot_data"):
        assert f"'{name}'" not in roots, (name, roots)
    assert "'numpy'" in roots and "'fcl'" in roots, roots  # what the run does use: the check sees imports
    assert "BATCH []" in err, err
    assert "FROZEN True (10000, 10, 10)" in err, err


def test_sim_imports_mcap_when_it_writes_a_trace(tmp_path):
    err = _sim_modules(tmp_path, "--trace", str(tmp_path / "t.mcap"))
    assert "'mcap'" in err.split("ROOTS ")[1].splitlines()[0], err
    assert (tmp_path / "t.mcap").stat().st_size > 0


def test_sim_called_as_a_function_leaves_the_collector_alone(tmp_path):
    """`main(argv)` from another program (tests, tools): no freeze, thresholds left as they were
    (their collector is theirs)."""
    code = (
        "import gc, sys\n"
        "from val3check.cli import main\n"
        f"main(['sim', 'fixtures/valid/Supervisor', '--duration', '1', '--report', 'json', '-o', {str(tmp_path / 'r.json')!r}])\n"
        "print('FROZEN', gc.get_freeze_count() > 0, gc.get_threshold(), file=sys.stderr)\n"
    )
    r = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert "FROZEN False (700, 10, 10)" in r.stderr, r.stderr


def test_sim_with_its_page_leaves_out_numpy_ma_and_the_html_entities(tmp_path):
    """numpy.ma (48 M instructions) is imported by np.unique without return_index (motion_records,
    tracking ask for it), `html` (its entity table, 8 M) by html.escape (the page escapes itself)."""
    code = (
        "import sys, runpy\n"
        "sys.argv = ['val3check', 'sim', 'fixtures/valid/PickPlace', '--robot', 'tx2-60', '--scenario',"
        f" 'fixtures/scenarios/pickplace.toml', '--duration', '4', '--max-wall', '600', '--report', 'html', '-o',"
        f" {str(tmp_path / 'r.html')!r}]\n"
        "try:\n    runpy.run_module('val3check', run_name='__main__')\nexcept SystemExit:\n    pass\n"
        "print('LOADED', sorted(m for m in ('numpy.ma', 'html', 'html.entities') if m in sys.modules), file=sys.stderr)\n"
    )
    r = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert (tmp_path / "r.html").is_file(), r.stderr
    assert "LOADED []" in r.stderr, r.stderr
