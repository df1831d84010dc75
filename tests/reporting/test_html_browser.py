"""The HTML report in a real browser: Debian's Chromium, headless, through Playwright.

Each test loads a report from a file:// URL, waits for the page's rendered flag and checks the
DOM, that nothing was logged as an error and that nothing was requested; screenshots go to
pytest's temporary folder (`--basetemp` to keep them). They skip when Chromium or Playwright is
absent, unless VAL3CHECK_REQUIRE_BROWSER=1 (.ci/run).
"""

from __future__ import annotations

import json
import random
from pathlib import Path

import browser_client
import pytest

from val3check.cli import main
from synthetic_run import synthetic_model
from val3check.reporting.html import model_from_sim_report, render
from val3check.robot import load_robot
from val3check.robot.chain import chain_fk
from val3check.simulation.report_scene import ReportScene

ROOT = Path(__file__).resolve().parents[2]

_WHY = browser_client.skip_reason()
if _WHY and browser_client.required():
    raise RuntimeError(f"VAL3CHECK_REQUIRE_BROWSER is set but the browser tests cannot run: {_WHY}")
pytestmark = [pytest.mark.browser, pytest.mark.skipif(_WHY is not None, reason=_WHY or "")]


@pytest.fixture(scope="module")
def chromium():
    with browser_client.Chromium() as c:
        yield c


@pytest.fixture(scope="module")
def model():
    return synthetic_model(duration=60.0)


@pytest.fixture(scope="module")
def report(model, tmp_path_factory):
    path = tmp_path_factory.mktemp("html") / "report.html"
    path.write_text(render(model), encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def loaded(chromium, report):
    page = chromium.open(report)
    yield page
    page.page.close()


def _clean(page) -> None:
    assert page.console_errors == []
    assert page.requests == [page.url], page.requests  # the page itself, nothing else
    assert page.refused == []
    assert page.evaluate("document.body.dataset.failures") == "0"


def test_report_renders_everything_with_no_error_and_no_request(loaded, model, tmp_path_factory):
    _clean(loaded)
    counts = loaded.evaluate("""() => ({
        diags: document.querySelectorAll('#diagnostics li.diag').length,
        excerpts: document.querySelectorAll('#diagnostics pre.excerpt .hit').length,
        motions: document.querySelectorAll('table.motions tbody tr').length,
        transcript: document.querySelectorAll('table.transcript tbody tr').length,
        jointPlots: document.querySelectorAll('#joint-plots svg.chart').length,
        tcpPlots: document.querySelectorAll('#tcp-plot svg.chart').length,
        series: Array.from(document.querySelectorAll('#joint-plots path.series, #tcp-plot path.series'))
                     .map((p) => p.getAttribute('d').length),
        ganttRects: document.querySelectorAll('#gantt svg rect').length,
        ioRects: document.querySelectorAll('#io-lanes svg rect').length,
        bars: document.querySelectorAll('.cyclebars svg rect[role=button]').length,
        jointRows: document.querySelectorAll('#jointnow tr').length,
        status: document.querySelector('.verdict .badge').textContent,
    })""")
    assert counts["diags"] == len(model["diagnostics"]) == 2 and counts["excerpts"] == 1
    assert counts["motions"] == len(model["motions"]) > 100
    assert counts["transcript"] == len(model["transcript"])
    assert counts["jointPlots"] == 12 and counts["tcpPlots"] == 1
    assert len(counts["series"]) == 13 and min(counts["series"]) > 500  # every curve has its points
    assert counts["ganttRects"] > 50 and counts["ioRects"] > 20
    assert counts["bars"] == len(model["cycles"][0]["iterations"])
    assert counts["jointRows"] == 6 and counts["status"] == "PASSED"
    shots = tmp_path_factory.mktemp("screenshots")
    loaded.page.screenshot(path=str(shots / "report-top.png"))
    loaded.page.locator("#view3d-section").screenshot(path=str(shots / "report-3d.png"))
    assert (shots / "report-3d.png").stat().st_size > 20_000


def _painted(page, rgb_min, rgb_max) -> int:
    """Pixels of the 3D canvas within a colour box (the arm is yellow, obstacles blue-grey)."""
    return page.evaluate("""([lo, hi]) => {
        const c = document.getElementById('view3d');
        const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
        let n = 0;
        for (let i = 0; i < d.length; i += 4)
            if (d[i] >= lo[0] && d[i] <= hi[0] && d[i+1] >= lo[1] && d[i+1] <= hi[1] && d[i+2] >= lo[2] && d[i+2] <= hi[2]) n++;
        return n;
    }""", [rgb_min, rgb_max])


def test_3d_view_draws_the_arm_and_the_cell(loaded):
    yellow = _painted(loaded, [120, 80, 0], [255, 200, 60])  # the arm, shaded
    steel = _painted(loaded, [60, 75, 90], [150, 175, 200])  # the obstacles, shaded
    assert yellow > 2000 and steel > 2000, (yellow, steel)


def test_3d_forward_kinematics_is_the_arm_models(loaded, model):
    robot = load_robot("tx2-60")
    arm = model["scene"]["arm"]
    rng = random.Random(3)
    for _ in range(10):
        q = [rng.uniform(lo, hi) for lo, hi in robot.joint_limits]
        poses = loaded.evaluate("(q) => window.val3checkReport.linkPoses(q)", q)
        F = robot.fk_matrix(q)
        assert max(abs(poses["flange"][i][k] - F[i][k]) for i in range(3) for k in range(4)) < 1e-6
        P = chain_fk(arm, q)
        for link, M in P.items():
            assert max(abs(poses[link][i][k] - M[i][k]) for i in range(3) for k in range(4)) < 1e-6, link


def test_keyboard_and_mouse_drive_the_time_window_and_the_3d_view(chromium, report, model):
    page = chromium.open(report)
    p = page.page
    window = lambda: p.locator("#tw-range").text_content()
    assert window() == "0.000 – 60.000 s"
    p.locator("#joint-plots svg.chart").first.focus()
    p.keyboard.press("+")
    p.wait_for_function("() => document.getElementById('tw-range').textContent !== '0.000 – 60.000 s'")
    assert window() == "15.000 – 45.000 s"
    p.keyboard.press("ArrowRight")
    p.wait_for_function("() => document.getElementById('tw-range').textContent === '18.000 – 48.000 s'")
    p.keyboard.press("0")
    p.wait_for_function("() => document.getElementById('tw-range').textContent === '0.000 – 60.000 s'")
    # a motion's number zooms on it, and the row of the motion under the cursor is marked
    m = model["motions"][2]
    pad = (m["end"] - m["start"]) * 0.1
    zoomed = f"{m['start'] - pad:.3f} – {m['end'] + pad:.3f} s"
    p.locator("table.motions tbody tr:nth-child(3) button.goto").click()
    p.wait_for_function("(w) => document.getElementById('tw-range').textContent === w", arg=zoomed)
    assert p.locator("table.motions tbody tr.now").count() == 1
    assert p.locator("#view3d-state").text_content().endswith("motion 3 (movel, line 16)")
    # drag across a plot: zoom on the range
    p.wait_for_timeout(800)  # the smooth scroll to the plots
    p.locator("#tcp-plot svg.chart").scroll_into_view_if_needed()
    box = p.locator("#tcp-plot svg.chart").bounding_box()
    y = box["y"] + box["height"] / 2
    p.mouse.move(box["x"] + box["width"] * 0.3, y)
    p.mouse.down()
    p.mouse.move(box["x"] + box["width"] * 0.6, y, steps=5)
    p.mouse.up()
    p.wait_for_function("(w) => document.getElementById('tw-range').textContent !== w", arg=zoomed)
    a, b = (float(x) for x in window().replace(" s", "").split(" – "))
    assert 0 < b - a < 0.6
    # play: time moves; space on the focused 3D view pauses
    p.locator("#tw-reset").click()
    p.locator("#play").click()
    p.wait_for_function("() => parseFloat(document.getElementById('scrub-time').textContent) > 1.25")
    p.locator("#view3d").focus()
    p.keyboard.press(" ")
    assert p.locator("#play").get_attribute("aria-pressed") == "false"
    t = p.locator("#scrub-time").text_content()
    p.wait_for_timeout(200)
    assert p.locator("#scrub-time").text_content() == t
    before = _painted(page, [120, 80, 0], [255, 200, 60])
    for _ in range(6):
        p.keyboard.press("ArrowLeft")
    p.keyboard.press("-")
    assert _painted(page, [120, 80, 0], [255, 200, 60]) != before  # the view turned
    _clean(page)
    p.close()


def test_failing_run_shows_the_error_and_the_stopped_task(chromium, tmp_path):
    model = synthetic_model(duration=30.0, failing=True)
    path = tmp_path / "failing.html"
    path.write_text(render(model), encoding="utf-8")
    page = chromium.open(path)
    _clean(page)
    p = page.page
    assert p.locator(".verdict .badge").text_content() == "FAILED"
    assert p.locator("#diagnostics li.sev-error").count() == 1
    assert "error 154" in p.locator("#diagnostics li.sev-error .msg").text_content()
    # the stopped segment of the robot task is drawn with its hatch pattern
    assert page.evaluate("""() => Array.from(document.querySelectorAll('#gantt svg rect'))
        .some((r) => (r.getAttribute('fill') || '').startsWith('url(#v3h'))""")
    p.screenshot(path=str(tmp_path / "failing.png"), full_page=False)
    p.close()


def test_print_layout_hides_the_controls(chromium, report):
    page = chromium.open(report)
    p = page.page
    p.emulate_media(media="print")
    hidden = page.evaluate("""() => ['.timebar', '.controls', 'nav.toc', '#diagnostics button.goto', 'table.motions button']
        .map((s) => getComputedStyle(document.querySelector(s)).display)""")
    assert hidden == ["none"] * 4 + ["inline-block"]  # the motion numbers stay, as text
    assert page.evaluate("getComputedStyle(document.querySelector('.scroll.tall')).overflow") == "visible"
    pdf = p.pdf(format="A4")
    assert pdf.startswith(b"%PDF") and len(pdf) > 50_000
    _clean(page)
    p.close()


def test_long_run_is_decimated_and_still_draws(chromium, model, tmp_path):
    # a ten-minute run: repeat the one-minute trajectory ten times
    import copy

    long = copy.deepcopy(model)
    tr = long["trajectory"]
    n = len(tr["times"])
    reps = 10
    tr["times"] = [round(k * 0.004, 6) for k in range(n * reps)]
    for key in ("positions", "velocities"):
        tr[key] = [col * reps for col in tr[key]]
    tr["tcp_speed"] = tr["tcp_speed"] * reps
    long["verdict"]["simulated_duration"] = tr["times"][-1]
    path = tmp_path / "long.html"
    text = render(long)
    path.write_text(text, encoding="utf-8")
    assert len(text.encode()) < 5_000_000
    page = chromium.open(path)
    _clean(page)
    assert page.evaluate("V3.data.traj.decimated") is True
    assert page.page.locator("#joints ul.legend li", has_text="min/max of").count() == 1
    lengths = page.evaluate("Array.from(document.querySelectorAll('#joint-plots path.series')).map((p) => p.getAttribute('d').length)")
    assert len(lengths) == 12 and min(lengths) > 500
    page.page.close()


def test_3d_view_names_the_solid_under_the_pointer(loaded):
    p = loaded.page
    p.evaluate("() => V3.time.setCursor(0)")
    names = loaded.evaluate("""() => {
        const v = V3.view, c = document.getElementById('view3d'), seen = new Set();
        for (let x = 0; x < c.clientWidth; x += 6) for (let y = 0; y < c.clientHeight; y += 6) {
            const n = v.pick(x, y); if (n) seen.add(n);
        }
        return Array.from(seen).sort();
    }""")
    for expected in ("arm: link_2 (upper_arm)", "cell: pick table", "cell: pillar", "tool tGripper: body"):
        assert expected in names, names


@pytest.mark.parametrize("app, options", [("Cell", ["--robot", "tx2-60"]), ("Supervisor", [])])
def test_report_of_a_real_application(chromium, app, options, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(ROOT)
    main(["sim", f"fixtures/valid/{app}", "--report", "json", "--duration", "20", *options])
    report = json.loads(capsys.readouterr().out)
    path = tmp_path / f"{app}.html"
    path.write_text(render(model_from_sim_report(report, ReportScene())), encoding="utf-8")
    page = chromium.open(path)
    _clean(page)
    p = page.page
    assert p.locator("#diagnostics li.diag").count() == len(report["diagnostics"])
    assert p.locator("table.transcript tbody tr").count() == len(report["transcript"])
    assert p.locator("#io-lanes svg.chart").count() == (1 if report["io_log"] else 0)
    if report["robot"]:
        assert _painted(page, [120, 80, 0], [255, 200, 60]) > 2000  # the arm, standing at its initial position
        assert p.locator("#jointnow tr").count() == 6
    else:
        assert p.locator("#view3d").count() == 0 and "No 3D scene" in p.locator("#view3d-section").text_content()
    p.screenshot(path=str(tmp_path / f"{app}.png"), full_page=True)
    p.close()


def test_sim_report_html_of_the_pick_and_place_cell(chromium, tmp_path, monkeypatch):
    """`val3check sim --report html` on the bundled cell that moves: everything filled from the
    real run, no console error, no request; the screenshots are looked at when this changes."""
    monkeypatch.chdir(ROOT)
    out = tmp_path / "report.html"
    code = main(["sim", "fixtures/valid/PickPlace", "--robot", "tx2-60", "--scenario",
                 "fixtures/scenarios/pickplace.toml", "--report", "html", "-o", str(out)])
    assert code == 0
    page = chromium.open(out)
    _clean(page)
    counts = page.evaluate("""() => ({
        motions: document.querySelectorAll('table.motions tbody tr').length,
        jointPlots: document.querySelectorAll('#joint-plots svg.chart').length,
        tcpPlots: document.querySelectorAll('#tcp-plot svg.chart').length,
        series: Array.from(document.querySelectorAll('#joint-plots path.series, #tcp-plot path.series'))
                     .map((p) => p.getAttribute('d').length),
        ganttLanes: Array.from(document.querySelectorAll('#gantt .lane-label, #gantt text')).map((e) => e.textContent),
        ganttRects: document.querySelectorAll('#gantt svg rect').length,
        ioRects: document.querySelectorAll('#io-lanes svg rect').length,
        bars: document.querySelectorAll('.cyclebars svg rect[role=button]').length,
        clearances: Array.from(document.querySelectorAll('table.motions tbody tr'))
                         .filter((r) => /^[0-9.]+ /.test(r.lastElementChild.textContent)).length,
        status: document.querySelector('.verdict .badge').textContent,
        verdict: document.querySelector('.verdict').textContent,
    })""")
    assert counts["motions"] > 100 and counts["jointPlots"] == 12 and counts["tcpPlots"] == 1
    assert len(counts["series"]) == 13 and min(counts["series"]) > 500
    assert counts["ganttRects"] > 100 and counts["ioRects"] > 50 and counts["bars"] >= 18
    assert counts["status"] == "PASSED" and "median of 18 complete cycles" in counts["verdict"]
    assert any("robot" in t for t in counts["ganttLanes"])
    # the cell found beside the application (val3check-cell.toml): every motion has its clearance,
    # and the arm shows through the fence around it
    assert counts["clearances"] == counts["motions"]
    assert _painted(page, [120, 80, 0], [255, 200, 60]) > 2000  # the arm
    p = page.page
    # the cell as the checks placed it: nothing left undrawn (no note), the cube carried at 3.0 s
    # (close at 2.248 s, open at 3.352 s), then on the pallet until doPalletFull clears it
    assert p.locator(".verdict [role=note]").count() == 0
    # (the solids the view drew: the fence in front of them is what the pointer would pick)
    zoom = "const v = V3.view; v.target = [350, 0, -100]; v.dist = 1500; v.draw();"
    drawn = "new Set(V3.view.prims.filter((p) => p.pts && p.part.name === 'part: cube').map((p) => p.part)).size"
    cubes = [p.evaluate(f"() => {{ V3.time.setCursor({t}); {zoom} return {drawn}; }}") for t in (2.0, 3.0, 11.5, 27.0)]
    assert cubes == [0, 1, 4, 0]  # none yet; carried; three on the pallet and one carried; pallet cleared at 26.5 s
    p.evaluate(f"() => {{ V3.time.setCursor(11.5); {zoom} }}")
    p.locator("#view3d").screenshot(path=str(tmp_path / "pickplace-3d-parts.png"))
    p.evaluate("() => { V3.time.setCursor(0); V3.view.resetView(); }")
    p.screenshot(path=str(tmp_path / "pickplace.png"), full_page=True)
    p.close()


def test_page_of_the_pick_and_place_cell_s_json_report(chromium, tmp_path, monkeypatch, capsys):
    """`val3check html --sim-report run.json` on the bundled example's JSON
    report (issue 28 item 4): the motions, cycles, joint and TCP plots and the arm's timeline of the
    run, the arm and the cell in the 3D view; what the JSON lacks is said at the top."""
    monkeypatch.chdir(ROOT)
    run = tmp_path / "run.json"
    assert main(["sim", "fixtures/valid/PickPlace", "--robot", "tx2-60", "--scenario",
                 "fixtures/scenarios/pickplace.toml", "--report", "json", "-o", str(run)]) == 0
    out = tmp_path / "report.html"
    assert main(["html", "--sim-report", str(run), "-o", str(out)]) == 0
    capsys.readouterr()
    page = chromium.open(out)
    _clean(page)
    counts = page.evaluate("""() => ({
        motions: document.querySelectorAll('table.motions tbody tr').length,
        jointPlots: document.querySelectorAll('#joint-plots svg.chart').length,
        tcpPlots: document.querySelectorAll('#tcp-plot svg.chart').length,
        bars: document.querySelectorAll('.cyclebars svg rect[role=button]').length,
        clearances: Array.from(document.querySelectorAll('table.motions tbody tr'))
                         .filter((r) => /^[0-9.]+ /.test(r.lastElementChild.textContent)).length,
        verdict: document.querySelector('.verdict').textContent,
        text: document.body.textContent,
        where: document.querySelector('table.motions tbody tr td:nth-child(2)').textContent,
    })""")
    assert counts["where"] == "start.pgx:15"  # the program with the line
    report = json.loads(run.read_text())
    motions = len(report["motion"]["motions"])  # the JSON's own count (the timing decides how many fit)
    assert motions > 100 and counts["motions"] == motions
    assert counts["jointPlots"] == 12 and counts["tcpPlots"] == 1
    assert counts["bars"] >= 18 and counts["clearances"] == motions
    assert "median of 18 complete cycles" in counts["verdict"]
    for absent in ("No motion in this run", "did not move", "no complete loop iteration"):
        assert absent not in counts["text"]
    assert "does not record what each task was doing" in counts["text"]
    assert _painted(page, [120, 80, 0], [255, 200, 60]) > 2000  # the arm
    page.page.screenshot(path=str(tmp_path / "pickplace-from-json.png"), full_page=True)
    page.page.close()


def test_real_run_with_a_cell_draws_its_obstacles_and_tool(chromium, tmp_path):
    """A real run with the cell the collision checks give it (`result.collision.cell`): the
    obstacles (one in the application's frame fPallet) and the tool's solids in the 3D view."""
    from types import SimpleNamespace

    from val3check.collision.cellfile import read_cell
    from val3check.reporting.html.from_run import model_from_run

    from .runhelp import CELL, pickplace

    result, report = pickplace(20.0)
    result.collision = SimpleNamespace(cell=read_cell(CELL), by_motion={})
    try:
        model = model_from_run(report)
    finally:
        del result.collision
    path = tmp_path / "cell.html"
    path.write_text(render(model), encoding="utf-8")
    page = chromium.open(path)
    _clean(page)
    assert _painted(page, [60, 75, 90], [150, 175, 200]) > 2000  # the table, the pallet, the post
    assert _painted(page, [120, 80, 0], [255, 200, 60]) > 2000  # the arm
    page.page.evaluate("() => V3.time.setCursor(2.62)")  # the arm over the pick position
    names = page.evaluate("""() => {
        const v = V3.view, c = document.getElementById('view3d'), seen = new Set();
        for (let x = 0; x < c.clientWidth; x += 6) for (let y = 0; y < c.clientHeight; y += 6) {
            const n = v.pick(x, y); if (n) seen.add(n);
        }
        return Array.from(seen).sort();
    }""")
    page.page.locator("#view3d-section").screenshot(path=str(tmp_path / "cell-3d.png"))
    page.page.close()
    for expected in ("cell: table", "cell: pallet", "cell: post", "tool tGripper: jaws", "arm: link_2"):
        assert any(n.startswith(expected) for n in names), (expected, names)


def _where(page, name: str):
    """The centre (CSS pixels) of what the 3D view draws for solids named `name`, and how many
    probe points hit it (none: not drawn)."""
    return page.evaluate("""(name) => {
        const v = V3.view, c = document.getElementById('view3d');
        let n = 0, x = 0, y = 0;
        for (let i = 0; i < c.clientWidth; i += 4) for (let j = 0; j < c.clientHeight; j += 4)
            if (v.pick(i, j) === name) { n++; x += i; y += j; }
        return n ? [x / n, y / n, n] : [null, null, 0];
    }""", name)


def test_3d_view_moves_obstacles_with_their_frame_and_draws_the_parts(chromium, tmp_path):
    """A real run (runhelp.MOVING): the block hangs on fBlock, which the program moves from x = -400
    to x = 400 between two motions; the brick is carried from close() to open() and left at pPlace.
    At four times the view shows each where the collision checks had it, and says nothing is
    missing."""
    from val3check.reporting.html.from_run import model_from_run

    from .runhelp import moving_run

    result, report = moving_run(tmp_path)
    path = tmp_path / "moving.html"
    path.write_text(render(model_from_run(report)), encoding="utf-8")
    page = chromium.open(path)
    _clean(page)
    p = page.page
    assert p.locator(".verdict [role=note]").count() == 0  # no warning about frames or parts
    close, open_ = (e.time_us / 1e6 for e in result.motion.tool_events)
    moved = result.motion.motions[3].start  # fBlock's new value, from this motion on
    green = ([0, 60, 40], [40, 170, 130])  # the parts (#009E73, shaded)
    seen = {}
    for label, t in (("before", close - 0.1), ("carried", (close + moved) / 2), ("moved", (moved + open_) / 2),
                     ("left", open_ + 0.1)):
        p.evaluate(f"() => {{ V3.time.setCursor({t}); const v = V3.view; v.target = [200, 100, 0]; v.dist = 2200; v.draw(); }}")
        seen[label] = (_where(page, "cell: block"), _where(page, "part: brick"), _painted(page, *green))
        p.locator("#view3d").screenshot(path=str(tmp_path / f"moving-{label}.png"))
    p.close()
    (bx0, by0, nb0), (_, _, np0), g0 = seen["before"]
    (bx1, by1, nb1), (px1, py1, np1), g1 = seen["carried"]
    (bx2, by2, nb2), (px2, py2, np2), g2 = seen["moved"]
    (bx3, by3, nb3), (_, _, np3), g3 = seen["left"]
    assert nb0 and nb1 and nb2 and nb3
    assert (bx0, by0) == (bx1, by1)  # fBlock unchanged until the motion after the program moved it
    assert abs(bx2 - bx1) + abs(by2 - by1) > 50 and (bx2, by2) == (bx3, by3)  # 800 mm further, then still
    assert np0 == 0  # not taken yet: no part (the green of the axes' y only)
    assert np1 and np2 and np3 and min(g1, g2, g3) > g0 + 200, (g0, g1, g2, g3)
    assert abs(px2 - px1) + abs(py2 - py1) > 20  # it rides with the flange
