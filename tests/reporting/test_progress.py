"""The progress display of `sim` (reporting/progress.py): on stderr, only on a terminal, only for a
run longer than a second of wall time; never in the report or a pipe."""

from __future__ import annotations

import io
import os
import pty
import select
import subprocess
import sys
from pathlib import Path

from val3check.cli import main
from val3check.reporting.progress import Progress

ROOT = Path(__file__).resolve().parents[2]


class FakeTTY(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_shown_after_a_second_at_most_ten_times_a_second_then_cleared():
    t = [0.0]
    out = FakeTTY()
    p = Progress(out, clock=lambda: t[0], total_s=60.0)
    p(0.5, lambda: 1)
    assert out.getvalue() == ""  # a short run shows nothing
    t[0] = 1.2
    p(30.0, lambda: 12)
    assert out.getvalue() == "\rval3check sim:    30.000 of 60 s simulated,    1.2 s wall, 12 motions done\x1b[K"
    t[0] = 1.25
    p(31.0, lambda: 13)  # too soon to redraw
    assert out.getvalue().count("\r") == 1
    p.close()
    assert out.getvalue().endswith("\r\x1b[K")


def test_not_a_terminal_no_display():
    assert Progress.for_stream(io.StringIO()) is None
    assert isinstance(Progress.for_stream(FakeTTY()), Progress)


def test_sim_on_a_terminal_shows_progress_on_stderr_only(tmp_path):
    master, slave = pty.openpty()
    report = tmp_path / "out.txt"
    with open(report, "w") as out:
        # shown from the start and at every call (not after a second of wall time): what it shows
        # does not depend on how fast this machine simulates 60 s
        proc = subprocess.Popen(
            [sys.executable, "-c", "import sys; import val3check.reporting.progress as p; p.SHOW_AFTER_S = "
             "p.EVERY_S = 0.0; from val3check.cli import main; sys.exit(main(sys.argv[1:]))",
             "sim", "fixtures/valid/PickPlace", "--robot", "tx2-60",
             "--scenario", "fixtures/scenarios/pickplace.toml", "--duration", "60"],
            cwd=ROOT, stdout=out, stderr=slave, stdin=subprocess.DEVNULL)
    os.close(slave)
    seen = b""
    while True:
        ready, _, _ = select.select([master], [], [], 120)
        if not ready:
            break
        try:
            chunk = os.read(master, 4096)
        except OSError:  # the child closed the terminal
            break
        if not chunk:
            break
        seen += chunk
    os.close(master)
    assert proc.wait(timeout=120) == 0
    text = seen.decode()
    assert "of 60 s simulated," in text and "motions done" in text and "checking collisions: motion" in text and text.endswith("\r\x1b[K")
    assert "simulated," not in report.read_text()  # the report itself is untouched


def test_sim_into_a_pipe_or_a_file_shows_nothing(capsys, monkeypatch):
    monkeypatch.chdir(ROOT)
    main(["sim", "fixtures/valid/PickPlace", "--robot", "tx2-60", "--scenario", "fixtures/scenarios/pickplace.toml",
          "--duration", "90"])
    captured = capsys.readouterr()
    assert "motions done" not in captured.err and "motions done" not in captured.out


def test_the_collision_checks_after_the_motions_show_their_phase(monkeypatch, capsys):
    """Issue 28 item 3: the line does not freeze at the last simulated time while the motions'
    collisions are checked: it says which motion of how many it checks."""
    monkeypatch.chdir(ROOT)
    out, t = FakeTTY(), [0.0]

    def clock() -> float:  # a second per look: every call is shown
        t[0] += 1.0
        return t[0]

    monkeypatch.setattr(Progress, "for_stream", classmethod(lambda cls, stream, total_s=None: cls(
        out, clock=clock, total_s=total_s)))
    assert main(["sim", "fixtures/valid/PickPlace", "--robot", "tx2-60", "--scenario",
                 "fixtures/scenarios/pickplace.toml", "--duration", "30"]) == 0
    capsys.readouterr()
    shown = out.getvalue().split("\r")
    phases = [i for i, s in enumerate(shown) if "checking collisions: motion " in s]
    simulated = [i for i, s in enumerate(shown) if "s simulated" in s]
    assert phases and simulated and phases[0] > simulated[-1]  # after the simulated time
    total = shown[phases[0]].split(" of ")[1].split(",")[0]
    assert int(total) > 20
    assert [shown[i].split(",")[0] for i in phases] == [
        f"val3check sim: checking collisions: motion {k} of {total}" for k in range(1, int(total) + 1)]
    assert out.getvalue().endswith("\r\x1b[K")


def test_a_phase_is_shown_no_more_than_ten_times_a_second():
    t = [0.0]
    out = FakeTTY()
    p = Progress(out, clock=lambda: t[0])
    t[0] = 2.0
    p.phase("checking collisions: motion 1 of 3")
    p.phase("checking collisions: motion 2 of 3")  # the same instant: not redrawn
    assert out.getvalue() == "\rval3check sim: checking collisions: motion 1 of 3,    2.0 s wall\x1b[K"
