"""Where the cases run: in child processes on this machine (-j N: N at once; -j 1 one after
the other), or on a Dask distributed cluster (--executor dask). Every case runs `worker.run_case`
in a child process under the watchdog of runner.py, on the same self-contained cases, so results
do not depend on the executor; the caller sorts them. `on_done(outcome)` is called in this
process as each case ends (progress, --fail-fast); when `stop()` turns true no further case is
started.

A case that raises is a "crash" result (worker.run_case); one stuck or too big outside VAL 3
code is stopped by the watchdog ("over-budget"); a child process that dies (a crash in native
code, the kernel's OOM killer) is its case's "crash" after one more try in a fresh process
(runner.Runner). Nothing a case does ends this process, a Dask worker, or the batch."""

from __future__ import annotations

import math
import queue
import threading
from collections import deque
from dataclasses import replace
from typing import Callable

from .cases import Case
from .runner import Runner, Ticket, give_back, run_tickets, take, ticket
from .worker import CaseOutcome

OnDone = Callable[[CaseOutcome], None]
Stop = Callable[[], bool]


WAIT_FOR_WORKERS_S = 120  # a cluster's first worker may still be queued as a batch job


class ExecutorError(Exception):
    """The executor cannot run (Dask missing, scheduler unreachable): a usage error."""


def run_pool(cases: list[Case], jobs: int, on_done: OnDone, stop: Stop) -> None:
    """At most `jobs` cases at a time, in order, each in one of `jobs` child processes kept from
    case to case (a thread here watches each). A case is pickled only when its turn comes."""
    todo = deque(cases)
    lock = threading.Lock()
    halt = threading.Event()
    done: queue.Queue = queue.Queue()
    runners = [take() for _ in range(max(1, min(jobs, len(cases))))]
    for r in runners:
        r.spawn()  # from this thread, which outlives the batch (the children end with the thread that starts them)

    def work(runner: Runner) -> None:
        try:
            while not halt.is_set():
                with lock:
                    if not todo:
                        break
                    case = todo.popleft()
                seen = threading.Event()  # the next case starts once this one is taken in (--fail-fast)
                done.put((runner.run(ticket(case)), seen))
                while not seen.wait(0.1):
                    if runner.aborted:
                        return
            give_back(runner)  # idle, for a next batch of this process
        except BaseException as exc:  # noqa: BLE001 - reported in the main thread
            runner.close()
            done.put(exc)
        finally:
            done.put(None)

    threads = [threading.Thread(target=work, args=(r,), daemon=True) for r in runners]
    for t in threads:
        t.start()
    working = len(threads)
    try:
        while working:
            try:
                got = done.get(timeout=0.5)  # a timeout: Ctrl-C is seen here
            except queue.Empty:
                continue
            if got is None:
                working -= 1
            elif isinstance(got, BaseException):
                raise got
            else:
                outcome, seen = got
                try:
                    on_done(outcome)
                    if stop():  # --fail-fast: the cases not started yet are not started
                        halt.set()
                finally:
                    seen.set()
    except BaseException:
        halt.set()
        for r in runners:
            r.abort()  # a case still running is abandoned (Ctrl-C, an error here)
        raise
    finally:
        halt.set()
        for t in threads:
            t.join()


def run_serial(cases: list[Case], on_done: OnDone, stop: Stop) -> None:
    """One case after the other, each in a child process under the watchdog (`-j 1`)."""
    run_pool(cases, 1, on_done, stop)


def chunk_size(n_cases: int, n_workers: int) -> int:
    """Cases per Dask task: about 8 tasks per worker (the last task to end bounds the batch:
    small tasks balance it), at most 8 cases (progress and --fail-fast stay responsive), at
    least 1. A case costs 30 ms (3 simulated s of a small cell) to 0.6 s (60 s) of CPU; a task
    about 1 ms of the scheduler's time plus its cases' bytes: with a few cases per task the
    overhead stays under 1 % (bench/bench_batch.py, docs/batch.md)."""
    return max(1, min(8, math.ceil(n_cases / (8 * max(n_workers, 1)))))


def _alone(client, t: Ticket) -> CaseOutcome:  # noqa: ANN001 - a distributed.Client
    try:
        return client.submit(run_tickets, [t], pure=False).result()[0]
    except Exception as exc:  # noqa: BLE001
        return CaseOutcome(replace(t.blank, reason=f"Dask: {type(exc).__name__}: {exc}"))


def executor_problem(args) -> str | None:  # noqa: ANN001
    """What is wrong with the executor options of a batch or an exploration (-j, --executor,
    --scheduler), None when nothing."""
    if args.jobs is not None and args.jobs < 1:
        return "--jobs must be a positive number of processes"
    if args.executor == "dask" and args.jobs is not None and (args.scheduler or dask_address()):
        return ("--jobs sizes the local executor or a local Dask cluster; with a scheduler, the workers' "
                "processes set the parallelism")
    if args.scheduler and args.executor != "dask":
        return "--scheduler goes with --executor dask"
    return None


def dask_address() -> str | None:
    """The scheduler Dask's own configuration names (DASK_SCHEDULER_ADDRESS, or its config files)."""
    try:
        import dask
    except ImportError:
        return None
    return dask.config.get("scheduler-address", None) or None


def run_dask(cases: list[Case], address: str | None, on_done: OnDone, stop: Stop, chunk: int | None = None,
             workers: int = 1, starting: Callable[[str], None] | None = None) -> None:
    """The cases on a Dask cluster: the scheduler at `address`; None: the one Dask's configuration
    names (DASK_SCHEDULER_ADDRESS), else a local cluster of `workers` processes of one thread,
    as Dask's own `Client()` starts one, closed at the end. `starting(what)`: told before the
    cluster is reached or started (the progress line)."""
    try:
        import dask
        from distributed import Client, LocalCluster, as_completed
    except ImportError:
        raise ExecutorError("--executor dask needs the dask extra: pip install 'val3check[dask]'") from None
    address = address or dask.config.get("scheduler-address", None) or None
    cluster = None
    try:
        if address is None:
            if starting:
                starting(f"starting a local Dask cluster of {workers} worker process(es)")
            cluster = LocalCluster(n_workers=max(1, workers), threads_per_worker=1, processes=True,
                                   dashboard_address=None)
            client = Client(cluster)
        else:
            if starting:
                starting(f"connecting to the Dask scheduler at {address}")
            client = Client(address, timeout="20s")
    except (OSError, TimeoutError, ValueError) as exc:
        if cluster is not None:
            cluster.close()
        raise ExecutorError(f"cannot reach the Dask scheduler at {address}: {exc}" if address else
                            f"cannot start a local Dask cluster: {exc}") from None
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
        if starting:
            starting(f"running on {len(threads)} Dask worker process{'es' if len(threads) > 1 else ''}")
        # each case runs in a child of the Dask worker, under the watchdog (runner.py): a case
        # stuck, too big or crashing ends that child, never the worker, so Dask has no task to
        # retry (its distributed.scheduler.allowed-failures, 3 by default, is left to workers
        # lost for other reasons: a node going away)
        tickets = [ticket(c) for c in cases]
        chunks = [tickets[i:i + size] for i in range(0, len(tickets), size)]
        futures = client.map(run_tickets, chunks, pure=False)
        which = {f.key: c for f, c in zip(futures, chunks, strict=True)}
        for f in as_completed(futures):
            try:
                outcomes = f.result()
            except Exception:  # noqa: BLE001 - its worker was lost (KilledWorker), an error on the way
                # each case runs again alone, one after the other; one that fails again is the crash
                outcomes = [_alone(client, t) for t in which[f.key]]
            for o in outcomes:
                on_done(o)
            if stop():
                client.cancel(futures)
                break
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
