"""Issue 9: `val3check sim` on hostile applications and scenarios ends within its budgets with
a diagnostic, never a traceback, an 'internal error' or unbounded memory (items 2, 3, 5, 6, 7,
8, 9). Budgets are kept small so that each case takes at most a few seconds. In-process runs
read a wall clock of the test's (simsupport.StepClock, frozen_clock), so that what they check
never depends on the machine's speed (issue 28 item 11)."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from interpretation.simsupport import StepClock, build, errors, frozen_clock, run_folder, sim
from val3check.testing import write_app

ROOT = Path(__file__).resolve().parent.parent.parent


def val3check(*args, cwd, timeout=60):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    return subprocess.run([sys.executable, "-m", "val3check", *map(str, args)], capture_output=True, text=True,
                          cwd=cwd, env=env, timeout=timeout)


def clean(r, codes=(0, 1, 2)):
    assert r.returncode in codes, (r.returncode, r.stdout[-2000:], r.stderr[-2000:])
    assert "Traceback" not in r.stderr and "internal error" not in r.stdout + r.stderr, r.stdout + r.stderr


def _data(folder: Path, body: str, name: str = "Example") -> None:
    dtx = folder / f"{name}.dtx"
    dtx.write_text(dtx.read_text().replace("<Datas>\n", "<Datas>\n" + body), encoding="utf-8")


# ---- item 2: huge arrays -------------------------------------------------------------------------

@pytest.mark.parametrize("size", ["99999999", "9999 9999", "1" * 30, "9" * 5000])
def test_huge_array_sizes_are_lint_errors_and_never_allocated(tmp_path, size):
    folder = write_app(tmp_path, "begin\nend\n")
    _data(folder, f'    <Data name="nBig" access="public" xsi:type="array" type="num" size="{size}" />\n')
    r = val3check("lint", "Example", cwd=tmp_path)
    clean(r, (1,) if " " not in size else (0,))  # 9999 x 9999: T027, a warning
    assert re.search(r"Example\.dtx:4:5: T02[67]", r.stdout), r.stdout
    r = val3check("sim", "Example", "--max-wall", "10", cwd=tmp_path)
    clean(r)
    if " " in size:  # a warning: run, and refused by the memory budget before anything is allocated
        assert "nBig, about 1,526 MB" in r.stdout and "memory budget" in r.stdout and "0 VAL 3 lines" in r.stdout
    else:  # an error: not run
        assert r.returncode == 2 and "not run: the application has 1 error(s)" in r.stderr


def test_memory_is_budgeted_before_allocation(tmp_path):
    # T027 is a warning: sim runs, and refuses the 100 million points before allocating them
    folder = write_app(tmp_path, "begin\nend\n")
    _data(folder, '    <Data name="pBig" access="public" xsi:type="array" type="pointRx" size="9999 9999" />\n')
    result = run_folder(folder, check_lint=False, max_memory_mb=200, wall_clock=frozen_clock)
    assert result.end_reason == "budget" and "pBig" in result.end_message and "memory budget" in result.end_message
    assert [d.code for d in result.diagnostics] == ["R006"]


def test_locals_beyond_the_memory_budget_are_error_40_at_the_declaration(tmp_path):
    folder = build(tmp_path, "begin\n  call deep()\nend\n", programs={
        "deep": {"locals": ["pointRx l_p[9000]"], "code": "begin\n  call deep()\nend\n"}})
    pjx = folder / "Example.pjx"
    pjx.write_text(pjx.read_text().replace('stackSize="5000"', 'stackSize="999999999999"'))
    result = run_folder(folder, max_memory_mb=100, wall_clock=frozen_clock)
    assert errors(result) == [40]
    d = next(d for d in result.diagnostics if d.code == "R001")
    assert d.path.endswith("deep.pgx") and d.line == 3 and "l_p" in d.message


def test_the_wall_clock_budget_covers_loading(tmp_path):
    folder = write_app(tmp_path, "begin\nend\n")
    _data(folder, "".join(f'    <Data name="p{i}" access="public" xsi:type="array" type="pointRx" size="99 101" />\n'
                          for i in range(60)))
    # the clock passes the budget at its second reading, the first after the start: while loading
    result = run_folder(folder, check_lint=False, max_wall=0.5, wall_clock=StepClock(0.3))
    assert result.end_reason == "wall-clock"
    assert result.tasks == [] and result.lines == 0  # start() never began


# ---- item 3, N014: fatherId ---------------------------------------------------------------------

@pytest.mark.parametrize("father", ["fA[1e400]", "fA[" + "9" * 5000 + "]", "fA[nan]", "fA[-1]", "fZ[0]", "fA[",
                                    "tT[0]"])
def test_odd_father_ids(tmp_path, father):
    folder = write_app(tmp_path, "begin\n  pP.trsf.x = 1\nend\n")
    _data(folder, '    <Data name="fA" access="public" xsi:type="array" type="frame" size="1"><Value key="0" /></Data>\n'
                  '    <Data name="tT" access="public" xsi:type="array" type="tool" size="1"><Value key="0" /></Data>\n'
                  f'    <Data name="pP" access="public" xsi:type="array" type="pointRx" size="1"><Value key="0"'
                  f' fatherId="{father}" /></Data>\n')
    r = val3check("lint", "Example", cwd=tmp_path)
    clean(r, (0,))
    assert re.search(r"Example\.dtx:6:\d+: N014", r.stdout), r.stdout
    r = val3check("sim", "Example", "--duration", "1", cwd=tmp_path)
    clean(r)


# ---- items 5, 6, 7: programs ------------------------------------------------------------------

def test_huge_program_and_switch_are_too_large_not_a_crash(tmp_path):
    code = "begin\n" + "".join(f"  nX = nX + {i}\n" for i in range(20000)) + "end\n"
    folder = build(tmp_path, code, globals_=["num nX"])
    result = run_folder(folder, wall_clock=frozen_clock)
    d = next(d for d in result.diagnostics if d.code == "R004")
    assert "too large for the simulator" in d.message and d.line == 3  # the <Program> element


def test_switch_with_thousands_of_cases_runs(tmp_path):
    code = "begin\n  switch nX\n" + "".join(f"    case {i}\n      nY = {i}\n    break\n" for i in range(3000))
    code += "  endSwitch\nend\n"
    result = sim(tmp_path, code, globals_=["num nX", "num nY"], values={"nX": "2999"})
    assert errors(result) == [] and not [d for d in result.diagnostics if d.code == "R004"]
    from interpretation.simsupport import gv

    assert gv(result, "nY") == 2999


@pytest.mark.parametrize("literal", ["1e999", "-1e999", "9" * 5000])
def test_number_beyond_a_num_is_a_compile_error(tmp_path, literal):
    write_app(tmp_path, f"begin\n  nX = {literal}\nend\n", globals_=["num nX"])
    r = val3check("lint", "Example", cwd=tmp_path)
    clean(r, (1,))
    assert "F017" in r.stdout and "Example/start.pgx:5:8" in r.stdout
    r = val3check("sim", "Example", cwd=tmp_path)
    clean(r, (2,))


def test_number_beyond_a_num_in_a_library_is_not_simulated(tmp_path):
    from interpretation.simsupport import add_libraries, make_library

    make_library(tmp_path, "Lib", programs={"f": {"code": "begin\n  nX = 1e999\nend\n"}}, globals_=["num nX"])
    app = build(tmp_path, "begin\n  call l:f()\nend\n", name="App")
    add_libraries(app, {"l": "Disk://Lib"}, name="App", autoload="true")
    result = run_folder(app)
    assert [d.code for d in result.diagnostics if d.code in ("R001", "R004")] == ["R004"]
    assert not any("internal" in d.message for d in result.diagnostics)


def test_locals_larger_than_the_stack_are_error_41_at_the_declaration(tmp_path):
    result = sim(tmp_path, "begin\n  l_big[0] = 1\nend\n", locals_=["num l_big[2000]"])
    assert errors(result) == [41]
    d = next(d for d in result.diagnostics if d.code == "R001")
    assert d.path.endswith("start.pgx") and d.line == 3 and "internal" not in d.message


# ---- items 8, 9: scenarios --------------------------------------------------------------------

BAD_SCENARIOS = [
    "version = 1\n[[events]]\nat = nan\nset = {}\n",
    "version = 1\n[[events]]\nat = inf\nset = {}\n",
    "version = 1\n[[events]]\nat = 1e300\nset = {}\n",
    "[[keys]]\nat = 0\nkey = 270\nhold = nan\n",
    "[[serial]]\nsio = \"siX\"\nat = -inf\nsend = \"x\"\n",
    "[controller]\npower_delay = nan\n",
    "[controller]\nmonitor_speed = inf\n",
    "[controller]\nchanges = [{at = nan, powered = true}]\n",
    "[controller]\nchanges = [{at = 1, monitor_speed = nan}]\n",
    "[robot]\njoints = [nan, 0, 0, 0, 0, 0]\n",
    "a = " + "[" * 5000 + "]" * 5000 + "\n",
    "a = " + "{b = " * 3000 + "1" + "}" * 3000 + "\n",
    "[inputs]\naiX = nan\n",
]


@pytest.mark.parametrize("text", BAD_SCENARIOS)
def test_bad_scenario_values(tmp_path, text):
    write_app(tmp_path, "begin\nend\n", globals_=["aio aiX", "sio siX"])
    (tmp_path / "sc.toml").write_text(text)
    r = val3check("sim", "Example", "--scenario", "sc.toml", cwd=tmp_path, timeout=30)
    clean(r, (2,))
    assert "bad scenario" in r.stderr


@pytest.mark.parametrize("path", ["/dev/zero", "/dev/urandom", "fifo"])
def test_scenario_that_is_not_a_regular_file(tmp_path, path):
    write_app(tmp_path, "begin\nend\n")
    if path == "fifo":
        os.mkfifo(tmp_path / "fifo")
    r = val3check("sim", "Example", "--scenario", path, cwd=tmp_path, timeout=30)
    clean(r, (2,))
    assert "cannot read" in r.stderr


def test_reactions_that_loop_at_one_instant(tmp_path):
    scenario = ('version = 1\n[[events]]\nat = 0.1\nset = { diA = true }\n\n[[reactions]]\nwhen = "diA"\n'
                'becomes = true\nset = { diA = false }\n\n[[reactions]]\nwhen = "diA"\nbecomes = false\n'
                'set = { diA = true }\n')
    # 1 ms per reading: a loop that went on until the wall budget would end with "wall-clock"
    result = sim(tmp_path, "begin\n  delay(5)\nend\n", globals_=["dio diA"], links={"diA": "BasicIO-1\\%I0"},
                 scenario=scenario, duration=10, max_wall=20, wall_clock=StepClock(0.001))
    loop = [d for d in result.diagnostics if d.code == "R008"]
    assert len(loop) == 1 and loop[0].line == 6 and loop[0].time_us == 100_000
    assert result.end_reason == "budget"


@pytest.mark.parametrize("length,size", [(80, 1), (40, 2)])
def test_chains_of_user_types_are_refused_before_allocation(tmp_path, length, size):
    sys.path.insert(0, str(ROOT / "tests" / "loading"))
    from loadhelp import make_app

    from val3check.config import Settings
    from val3check.simulation import SimOptions, simulate
    from val3check.lint import run

    def body(t):
        return f'    <Data name="f" access="public" xsi:type="array" type="{t}" size="{size}" />\n'

    app = make_app(tmp_path / "App", types=[("T0", "Disk://T0")], data_body=body("T0"))
    for i in range(length):
        last = i == length - 1
        make_app(tmp_path / f"T{i}", programs=(), types=[] if last else [(f"T{i + 1}", f"Disk://T{i + 1}")],
                 data_body='    <Data name="n" access="public" xsi:type="array" type="num" size="1" />\n' if last
                 else body(f"T{i + 1}"))
    lr = run([str(app.parent)], Settings())
    ws = lr.workspace
    result = simulate(ws, ws.apps[ws.targets[0]], SimOptions(duration=1, max_wall=20, wall_clock=StepClock(0.001)))
    assert result.end_reason == "budget" and ("nested" in result.end_message or "memory budget" in result.end_message)
