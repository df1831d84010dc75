"""`val3check sim` with several applications, several arms, --sweep, --jobs, --executor or
--out-dir: the batch (docs/batch.md). cli.py parses the options and hands them here.

Exit codes: 0 every case passed; 1 a case failed at --fail-on, was not run (lint errors, no
start(), bad scenario), crashed or went over its budget; 2 the batch could not be made (usage, bad sweep file, no
application, executor unavailable)."""

from __future__ import annotations

import os
import sys
import time
from typing import Any

from .cases import Axes, CaseError, RunOptions, TooManyCases, list_cases, product_cases
from .outdir import OutDirError, prepare, write_case, write_summaries
from .outputs import KINDS
from .progress import Progress
from .summary import render_json, render_text
from .sweep import SweepError, load_sweep
from .worker import CaseOutcome, CaseSummary, summary_of

EXIT_OK, EXIT_FAILED, EXIT_USAGE = 0, 1, 2


def _err(message: str) -> int:
    print(f"val3check sim: error: {message}", file=sys.stderr)
    return EXIT_USAGE


def run(args: Any, settings: Any, tool_version: str, write: Any) -> int:
    """`write(text, output) -> bool`: the command line's writer (standard output or -o FILE)."""
    from ..lint import display_path, printable_path

    if args.init_scenario:
        return _err("--init-scenario writes the skeleton of one application: not with several, --sweep or --jobs")
    if args.format not in ("text", "json"):
        return _err(f"--report {args.format}: a batch prints its summary as text or json; --out-dir DIR writes"
                    " every format (summary.json, junit.xml, index.html) and each case's reports")
    kinds = tuple(k for k in KINDS if k in {x.strip().lower() for x in args.case_reports.split(",")})
    unknown = sorted({x.strip().lower() for x in args.case_reports.split(",")} - set(KINDS) - {""})
    if unknown or not kinds:
        return _err(f"--case-reports: {', '.join(unknown) or 'nothing'}; choose among {', '.join(KINDS)}")
    if getattr(args, "trace", None):
        return _err("--trace writes the trace of one run; in a batch, --out-dir DIR --case-reports json,trace"
                    " writes one per case")
    from .executors import executor_problem

    problem = executor_problem(args)
    if problem:
        return _err(problem)
    try:
        axes, sweep = _axes(args)
    except SweepError as exc:
        return _err(f"bad sweep file: {printable_path(str(exc))}")
    except CaseError as exc:
        return _err(str(exc))
    options = RunOptions(duration=args.duration, max_wall=args.max_wall, max_lines=args.max_lines,
                         max_memory_mb=args.max_memory, cycles=args.cycles, fail_on=settings.fail_on,
                         reports=bool(args.out_dir), case_reports=kinds)
    try:
        if sweep is not None and sweep.mode == "list":
            cases = list_cases(sweep, axes, settings, options)
        else:
            cases = product_cases(axes, settings, options)
    except SweepError as exc:
        return _err(f"bad sweep file: {printable_path(str(exc))}")
    except TooManyCases as exc:
        if sweep is not None and sweep.applications:  # at the sweep's applications
            e = sweep.applications[0]
            return _err(f"bad sweep file: {printable_path(str(SweepError(sweep.path, e.line, e.col, str(exc))))}")
        return _err(f"{exc}" if sweep is None else f"bad sweep file: {printable_path(sweep.path)}: {exc}")
    except CaseError as exc:
        return _err(str(exc))
    if args.out_dir:
        suffixes = [KINDS[k] for k in kinds]
        try:
            prepare(args.out_dir, [c.name() + s for c in cases for s in suffixes])
        except OutDirError as exc:
            return _err(f"--out-dir: {exc}")

    summaries: list[CaseSummary] = []
    reports: set[str] = set()  # the files written under --out-dir/cases
    progress = Progress(len(cases))
    failed = [False]

    unwritten: list[str] = []  # --out-dir files that could not be written (the batch goes on)

    def on_done(outcome: CaseOutcome) -> None:  # written at once: the reports are not kept in memory
        ok = outcome.summary.verdict == "pass"
        if args.out_dir and outcome.outputs:
            try:
                reports.update(write_case(args.out_dir, outcome))
            except OutDirError as exc:
                unwritten.append(str(exc))
        summaries.append(outcome.summary)
        failed[0] = failed[0] or not ok
        progress.update(ok)

    def stop() -> bool:
        return args.fail_fast and failed[0]

    from .executors import ExecutorError, run_dask, run_pool, run_serial

    start = time.monotonic()
    try:
        if args.executor == "dask":
            # no --scheduler: DASK_SCHEDULER_ADDRESS, else a local cluster, as Dask's Client() does
            run_dask(cases, args.scheduler, on_done, stop, workers=min(args.jobs or _cores(), len(cases)),
                     starting=progress.phase)
        else:
            jobs = min(args.jobs or _cores(), len(cases))
            progress.phase(f"running on {jobs} process{'es' if jobs > 1 else ''}")
            if jobs <= 1:
                run_serial(cases, on_done, stop)
            else:
                run_pool(cases, jobs, on_done, stop)
    except ExecutorError as exc:
        progress.finish()
        return _err(str(exc))
    except KeyboardInterrupt:
        progress.finish()
        print("val3check sim: interrupted", file=sys.stderr)
        return 130
    progress.finish()
    ran = {s.key for s in summaries}
    summaries += [summary_of(c, "skipped", "not run: --fail-fast stopped the batch at a failure")
                  for c in cases if c.key() not in ran]
    text = render_json(summaries, tool_version) if args.format == "json" else render_text(summaries)
    if not write(text, args.output):
        return EXIT_USAGE
    if args.out_dir:
        try:
            write_summaries(args.out_dir, summaries, reports, tool_version)
        except OutDirError as exc:
            unwritten.append(str(exc))
        if unwritten:
            return _err(f"--out-dir: {unwritten[0]}" + (f" (and {len(unwritten) - 1} more)" if len(unwritten) > 1 else ""))
        print(f"val3check sim: wrote the summary and {len(reports)} case report(s) in "
              f"{display_path(args.out_dir)} (index.html)", file=sys.stderr)
    if sys.stderr.isatty():
        print(f"val3check sim: {len(cases)} cases in {time.monotonic() - start:.1f} s", file=sys.stderr)
    return EXIT_FAILED if any(s.verdict in ("fail", "not-run", "crash", "over-budget") for s in summaries) else EXIT_OK


def _cores() -> int:
    """The cores this process may use (a container's or taskset's limit), else the machine's."""
    try:
        return len(os.sched_getaffinity(0)) or 1
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def _axes(args: Any) -> tuple[Axes, Any]:
    """The command line's values, and the sweep file's; an axis given by both is an error."""
    sweep = load_sweep(args.sweep) if args.sweep else None
    if sweep is not None:
        check_files(sweep)
    cli_cell = args.cell  # `sim --cell FILE|none`
    axes = Axes(apps=list(args.app), arms=list(args.robot or []), scenarios=[args.scenario] if args.scenario else [],
                cells=[cli_cell] if cli_cell else [], overrides=[])
    if sweep is None:
        axes.apps = axes.apps or ["."]
        return axes, None
    if sweep.mode == "product":
        both = (("applications", axes.apps, sweep.applications), ("arms", axes.arms, sweep.arms),
                ("scenarios", axes.scenarios, sweep.scenarios), ("cells", axes.cells, sweep.cells))
        for name, given, from_sweep in both:
            if given and from_sweep:
                raise CaseError(f"{name} are given both on the command line and in {args.sweep}: keep one")
        if sweep.applications and not args.app:
            axes.apps = _sweep_apps(sweep)
        axes.apps = axes.apps or ["."]
        axes.arms = axes.arms or [sweep.resolve(e) if sweep.is_arm_file(e) else e.value for e in sweep.arms]
        axes.scenarios = axes.scenarios or [None if e is None else sweep.resolve(e) for e in sweep.scenarios]
        axes.cells = axes.cells or ["none" if e is None else sweep.resolve(e) for e in sweep.cells]
        axes.overrides = sweep.overrides
    elif args.app:
        raise CaseError(f"{args.sweep} lists its cases ([[case]]): name no application on the command line")
    return axes, sweep


def _sweep_apps(sweep: Any) -> list[str]:
    """The sweep's applications, globs expanded inside its repository; a pattern that leads
    outside or matches nothing is reported at its line."""
    from .cases import check_sweep_app, sweep_apps

    for e in sweep.applications:  # every entry inside the repository before any is expanded
        check_sweep_app(sweep, e)
    out: list[str] = []
    for e in sweep.applications:
        out += [p for p in sweep_apps(sweep, e) if p not in out]
    return out


def check_files(sweep: Any) -> None:
    """Every scenario, cell and arm file of the sweep, at its line and column: inside the sweep's
    repository (checked before anything is opened), and an existing file."""
    entries = [("scenario", e) for e in sweep.scenarios] + [("cell", e) for e in sweep.cells]
    entries += [("arm", e) for e in sweep.arms if sweep.is_arm_file(e)]
    for case in sweep.cases:
        entries += [(k, case[k]) for k in ("scenario", "cell") if case.get(k) is not None]
        if "arm" in case and sweep.is_arm_file(case["arm"]):
            entries.append(("arm", case["arm"]))
    for kind, e in entries:
        if e is None:
            continue
        if not os.path.isfile(sweep.path_of(e)):
            raise SweepError(sweep.path, e.line, e.col, f"{kind} {e.value}: no such file")
