"""Where the cases run: in this process (-j 1), in a pool of processes on this machine
(-j N), or on a Dask distributed cluster (--executor dask). Every executor runs the same
`worker.run_case` on the same self-contained cases, so results do not depend on the executor;
the caller sorts them. `on_done(outcome)` is called in this process as each case ends (progress,
--fail-fast); when `stop()` turns true no further case is started.

A case that raises is a "crash" result (worker.run_case). A pool process that dies (a crash
in native code, the kernel's OOM killer) breaks the pool: the cases it took down are run again
one at a time, each in a fresh process, and the one that dies again is reported as a crash."""

from __future__ import annotations

import math
import multiprocessing
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from typing import Callable

from .cases import Case
from .worker import CaseOutcome, run_case, run_chunk, summary_of

OnDone = Callable[[CaseOutcome], None]
Stop = Callable[[], bool]


WAIT_FOR_WORKERS_S = 120  # a cluster's first worker may still be queued as a batch job


class ExecutorError(Exception):
    """The executor cannot run (Dask missing, scheduler unreachable): a usage error."""


def run_serial(cases: list[Case], on_done: OnDone, stop: Stop) -> None:
    for case in cases:
        if stop():
            return
        on_done(run_case(case))


def _context():  # noqa: ANN202
    # spawn: a fresh interpreter per worker on every platform (no state inherited from the parent)
    return multiprocessing.get_context("spawn")


def run_pool(cases: list[Case], jobs: int, on_done: OnDone, stop: Stop) -> None:
    """At most `jobs` cases at a time, each submitted alone: a case lasts long against the
    pool's per-task cost (about a millisecond), and one task per case keeps every core busy to
    the end and isolates a worker that dies."""
    broken: list[Case] = []
    ex = ProcessPoolExecutor(max_workers=jobs, mp_context=_context())
    try:
        todo = list(cases)
        running: dict = {}
        while todo or running:
            while todo and len(running) < 2 * jobs and not stop():  # a short queue: --fail-fast stops soon
                case = todo.pop(0)
                running[ex.submit(run_case, case)] = case
            if not running:
                break
            done, _ = wait(running, return_when=FIRST_COMPLETED)
            for f in sorted(done, key=lambda f: running[f].key()):
                case = running.pop(f)
                if f.cancelled():
                    continue
                try:
                    on_done(f.result())
                except BrokenProcessPool:
                    broken.append(case)
            if stop():  # --fail-fast: the cases not started yet are not started
                for f in list(running):
                    if f.cancel():
                        running.pop(f)
                todo = []
            if broken:
                broken += list(running.values()) + todo
                running, todo = {}, []
    finally:
        ex.shutdown(wait=True, cancel_futures=True)
    for case in sorted(broken, key=Case.key):
        if stop():
            return
        on_done(_isolated(case))


def _isolated(case: Case) -> CaseOutcome:
    ex = ProcessPoolExecutor(max_workers=1, mp_context=_context())
    try:
        return ex.submit(run_case, case).result()
    except BrokenProcessPool:
        return CaseOutcome(summary_of(case, "crash", "the process running the case died (a crash in native code, "
                                      "or killed by the system: out of memory?)"))
    finally:
        ex.shutdown(wait=True)


def chunk_size(n_cases: int, n_workers: int) -> int:
    """Cases per Dask task: about 8 tasks per worker (the last task to end bounds the batch:
    small tasks balance it), at most 8 cases (progress and --fail-fast stay responsive), at
    least 1. A case costs 30 ms (3 simulated s of a small cell) to 0.6 s (60 s) of CPU; a task
    about 1 ms of the scheduler's time plus its cases' bytes: with a few cases per task the
    overhead stays under 1 % (bench/bench_batch.py, docs/batch.md)."""
    return max(1, min(8, math.ceil(n_cases / (8 * max(n_workers, 1)))))


def _alone(client, case: Case) -> CaseOutcome:  # noqa: ANN001 - a distributed.Client
    try:
        return client.submit(run_chunk, [case], pure=False).result()[0]
    except Exception as exc:  # noqa: BLE001
        return CaseOutcome(summary_of(case, "crash", f"Dask: {type(exc).__name__}: {exc}"))


def run_dask(cases: list[Case], address: str, on_done: OnDone, stop: Stop, chunk: int | None = None) -> None:
    try:
        from distributed import Client, as_completed
    except ImportError:
        raise ExecutorError("--executor dask needs the dask extra: pip install 'val3check[dask]'") from None
    try:
        client = Client(address, timeout="20s")
    except (OSError, TimeoutError, ValueError) as exc:
        raise ExecutorError(f"cannot reach the Dask scheduler at {address}: {exc}") from None
    try:
        threads = client.nthreads()
        if not threads:  # workers still starting (dask-jobqueue submits them as batch jobs)
            try:
                client.wait_for_workers(1, timeout=WAIT_FOR_WORKERS_S)
            except TimeoutError:
                raise ExecutorError(f"the Dask scheduler at {address} has no worker "
                                    f"(none joined in {WAIT_FOR_WORKERS_S} s)") from None
            threads = client.nthreads()
        many = sorted(w for w, n in threads.items() if n != 1)
        if many:
            # a case sets its process's current folder and measures its memory: one at a time per process
            raise ExecutorError(f"Dask workers must run one thread each (dask worker --nthreads 1); "
                                f"{len(many)} of {len(threads)} have more")
        size = chunk or chunk_size(len(cases), len(threads))
        chunks = [cases[i:i + size] for i in range(0, len(cases), size)]
        futures = client.map(run_chunk, chunks, pure=False)
        which = {f.key: c for f, c in zip(futures, chunks, strict=True)}
        for f in as_completed(futures):
            try:
                outcomes = f.result()
            except Exception:  # noqa: BLE001 - its worker died (KilledWorker), an error on the way
                # one case may have taken the task down: each runs again alone, one after the
                # other (two on the same worker would fall together), the culprit is the crash
                outcomes = [_alone(client, c) for c in which[f.key]]
            for o in outcomes:
                on_done(o)
            if stop():
                client.cancel(futures)
                break
    finally:
        client.close()
