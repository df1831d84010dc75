"""The watchdog of a batch's cases (issue 21 K; docs/batch.md, "Budgets"): each case runs in a
child process, one case at a time (the process is kept from case to case), and the process that
started it watches it. The simulator's own budgets stop a case in VAL 3 code (`--max-wall`,
`--max-memory`); a case stuck outside it (a parser, a mesh, native code that holds the
interpreter) is stopped here: past its wall budget plus a grace, or grown past its memory budget
plus a margin, its process is killed and the case is reported `over-budget`; the next case gets a
fresh process and the batch goes on. A child that dies by itself (a crash in native code, the
out-of-memory killer) is its case's `crash`, after one more try in a fresh process.

The child is `python -m val3check.batch.runner`: it reads cases on its standard input and writes
outcomes on the descriptor that was its standard output (its own standard output goes to
standard error: nothing a case prints can break a reply). A message is a length (8 bytes, big
endian) and a pickle. A case travels pickled inside its Ticket and only the child unpickles it:
a case that breaks on unpickling ends the child, never the process that runs the batch or a Dask
worker (which Dask would then retry on another worker, three times by default).
"""

from __future__ import annotations

import atexit
import os
import pickle
import queue
import struct
import subprocess
import sys
import threading
import time
from dataclasses import dataclass, replace

from .cases import Case
from .worker import CaseOutcome, CaseSummary, summary_of

WALL_GRACE_S = 2.0  # past --max-wall: the run ends at its budget, then reports (a 60 s run: 0.1 to 1 s)
WALL_GRACE_PART = 0.1  # and a tenth of --max-wall
MEMORY_MARGIN_MB = 128.0  # past --max-memory: what a report, a first URDF (pinocchio) or mesh (trimesh) load add
MEMORY_MARGIN_PART = 0.1
POLL_S = 0.05  # how often the watchdog looks
START_S = 120.0  # a child that does not start (imports) in this time is a crash
DIED = ("the process running the case died (a crash in native code, or killed by the system: out of memory?)")
_DOING = {"starting": "starting", "lint": "reading the application", "run": "running",
          "report": "writing the reports"}
_HEADER = struct.Struct(">Q")
_READY = b"ready"


@dataclass(frozen=True)
class Ticket:
    """A case as it travels to its runner: its summary's fields (plain data: what the watchdog
    reports when the case does not end), its budgets, and the case itself, pickled."""

    blank: CaseSummary
    case: bytes
    max_wall: float
    max_memory_mb: float


def ticket(case: Case) -> Ticket:
    return Ticket(summary_of(case, "crash"), pickle.dumps(case, pickle.HIGHEST_PROTOCOL), case.options.max_wall,
                  case.options.max_memory_mb)


def wall_budget(t: Ticket) -> float:
    return t.max_wall * (1 + WALL_GRACE_PART) + WALL_GRACE_S


def memory_budget_mb(t: Ticket) -> float:
    return t.max_memory_mb * (1 + MEMORY_MARGIN_PART) + MEMORY_MARGIN_MB


def _verdict(t: Ticket, verdict: str, reason: str) -> CaseOutcome:
    return CaseOutcome(replace(t.blank, verdict=verdict, reason=reason))


# ---- the process that runs the batch (or a Dask worker) ------------------------------------------


class Runner:
    """One child process running cases one after the other, under the watchdog."""

    def __init__(self) -> None:
        self.proc: subprocess.Popen | None = None
        self.replies: queue.Queue = queue.Queue()
        self.aborted = False  # abort(): no child is started any more
        self.ready = False  # the child has said it is ready

    def run(self, t: Ticket) -> CaseOutcome:
        """The case's outcome, or the watchdog's verdict on it; never raises for the case."""
        for _ in range(2):  # a child that dies: once more, alone in a fresh one
            outcome = self._once(t)
            if outcome is not None:
                return outcome
        return _verdict(t, "crash", DIED)

    def _once(self, t: Ticket) -> CaseOutcome | None:
        if not self._started():
            return None
        base = _rss(self.proc.pid)
        try:
            _send(self.proc.stdin, t.case)
        except OSError:  # the child is gone
            self.close()
            return None
        deadline, limit = time.monotonic() + wall_budget(t), base + memory_budget_mb(t) * 1024 * 1024
        step = "starting"
        while True:
            try:
                reply = self.replies.get(timeout=POLL_S)
            except queue.Empty:
                reply = ...
            if reply is None:  # the child ended (died) before it replied
                self.close()
                return None
            if reply is not ...:
                kind, value = pickle.loads(reply)
                if kind == "step":  # each step of the case has the wall budget (a run's reports, its own)
                    step, deadline = value, time.monotonic() + wall_budget(t)
                    continue
                return value if kind == "outcome" else _verdict(t, "crash", value)
            if time.monotonic() > deadline:
                self.close()
                return _verdict(t, "over-budget", f"stopped by the watchdog: still {_DOING.get(step, step)} after"
                                f" {wall_budget(t):g} s (--max-wall {t.max_wall:g} s and its grace), outside VAL 3 code")
            proc = self.proc
            if proc is None:  # aborted meanwhile
                return None
            if base and _rss(proc.pid) > limit:
                self.close()
                return _verdict(t, "over-budget", f"stopped by the watchdog: its process grew by more than"
                                f" {memory_budget_mb(t):g} MB (--max-memory {t.max_memory_mb:g} MB and its margin),"
                                " outside VAL 3 code")

    def spawn(self) -> None:
        """Start the child if none runs (it ends with the thread that starts it: start runners
        from a thread that outlives them). Its start-up is awaited when its first case comes."""
        if self.aborted or (self.proc is not None and self.proc.poll() is None):
            return
        self.close()
        env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p and os.path.isdir(p)),
                   VAL3CHECK_RUNNER_PARENT=str(os.getpid()))
        self.proc = subprocess.Popen([sys.executable, "-m", "val3check.batch.runner"], stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, env=env)
        self.ready = False
        self.replies = queue.Queue()
        threading.Thread(target=_read_replies, args=(self.proc.stdout, self.replies), daemon=True).start()

    def _started(self) -> bool:
        self.spawn()
        if self.proc is None:
            return False
        if self.ready:
            return True
        try:
            ready = self.replies.get(timeout=START_S)
        except queue.Empty:
            ready = None
        if ready != _READY:
            self.close()
            return False
        self.ready = True
        return True

    def abort(self) -> None:
        """End the child and start no other (the batch is interrupted)."""
        self.aborted = True
        self.close()

    def close(self) -> None:
        """End the child (at once: a case it runs is abandoned)."""
        proc, self.proc = self.proc, None
        if proc is None:
            return
        if proc.poll() is None:
            proc.kill()
        proc.wait()
        for f in (proc.stdin, proc.stdout):
            try:
                f.close()
            except OSError:
                pass


def _read_replies(stream, replies: queue.Queue) -> None:  # noqa: ANN001
    while (data := _recv(stream)) is not None:
        replies.put(data)
    replies.put(None)


def _rss(pid: int) -> int:
    """The resident size of process `pid` in bytes (Linux); 0 where it cannot be read (the memory
    watch is then off: the simulator's own budget still holds in VAL 3 code)."""
    try:
        with open(f"/proc/{pid}/statm", "rb") as fh:
            return int(fh.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError, AttributeError):
        return 0


# ---- runners kept between batches of one process ----------------------------------------------------

_IDLE: list[Runner] = []
_IDLE_LOCK = threading.Lock()


def take() -> Runner:
    """A runner whose child has started and waits, left by an earlier batch of this process (a
    program or a test suite running several batches), else a new one."""
    with _IDLE_LOCK:
        while _IDLE:
            r = _IDLE.pop()
            if r.proc is not None and r.proc.poll() is None:
                return r
    return Runner()


def give_back(runner: Runner) -> None:
    """Keep a runner that finished its last case for the next batch; its child ends with this
    process (its standard input closes) or at exit."""
    if runner.proc is None or runner.proc.poll() is not None:
        return
    with _IDLE_LOCK:
        _IDLE.append(runner)


@atexit.register
def _close_idle() -> None:
    with _IDLE_LOCK:
        while _IDLE:
            _IDLE.pop().close()


# ---- Dask: each worker process keeps one runner ----------------------------------------------------

_RUNNER: Runner | None = None


def run_tickets(tickets: list[Ticket]) -> list[CaseOutcome]:
    """Several cases in one Dask task, each under the watchdog, in this worker's runner."""
    global _RUNNER
    if _RUNNER is None:
        _RUNNER = Runner()
        atexit.register(_RUNNER.close)
    return [_RUNNER.run(t) for t in tickets]


# ---- messages -------------------------------------------------------------------------------------


def _send(stream, data: bytes) -> None:  # noqa: ANN001
    stream.write(_HEADER.pack(len(data)) + data)
    stream.flush()


def _recv(stream) -> bytes | None:  # noqa: ANN001
    try:
        head = stream.read(_HEADER.size)
        if len(head) < _HEADER.size:
            return None
        (n,) = _HEADER.unpack(head)
        data = stream.read(n)
    except (OSError, ValueError):
        return None
    return data if len(data) == n else None


# ---- the child ------------------------------------------------------------------------------------


def main() -> int:
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the batch's to handle: it ends this process
    try:  # Linux: killed with the thread that started it, even when this one is stuck in C code
        import ctypes

        ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError, ValueError):
        pass
    if str(os.getppid()) != os.environ.get("VAL3CHECK_RUNNER_PARENT", str(os.getppid())):  # gone already
        return 0
    out = os.fdopen(os.dup(sys.stdout.fileno()), "wb")
    os.dup2(sys.stderr.fileno(), sys.stdout.fileno())  # what a case prints goes to standard error
    from . import worker
    from ..reporting import sim_json, sim_report  # noqa: F401 - loaded before the first case's clock starts
    from ..simulation import case, run  # noqa: F401 - with them the motion core and numpy: what every run loads

    _send(out, _READY)
    worker.STEP = lambda name: _send(out, pickle.dumps(("step", name)))
    stdin = sys.stdin.buffer
    while (data := _recv(stdin)) is not None:
        try:
            reply = ("outcome", worker.run_case(pickle.loads(data)))
        except BaseException as exc:  # noqa: BLE001 - a case that cannot even be unpickled
            reply = ("error", f"{type(exc).__name__}: {exc}")
        _send(out, pickle.dumps(reply, pickle.HIGHEST_PROTOCOL))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
