"""`val3check sim APP --scenario S --explore N`: variants of the scenario's timings, run on the
batch's executors, failures grouped by cause, each shrunk to a reproducer (docs/explore.md).

Exit codes: 0 no variant failed; 1 a variant (or the nominal run) failed; 2 usage, a bad
scenario, an application that cannot run, an executor that cannot start."""

from __future__ import annotations

import math
import os
import sys
from dataclasses import dataclass, replace
from typing import Any

from ..cases import Axes, CaseError, RunOptions, product_cases, safe_name
from ..outdir import OutDirError, inside, write_file
from ..progress import Progress
from .findings import Cause, Group, causes, size
from .report import SUMMARY_FILES, Exploration, render_html, render_json, render_junit, render_text, reproducer
from .search import observe, variants
from .shrink import shrink
from .timings import Timing, timings, variant_text

EXIT_OK, EXIT_FAILED, EXIT_USAGE = 0, 1, 2
DEFAULT_OUT_DIR = "val3check-explore"
FAILURES_DIR = "failures"
MAX_VARIANTS = 100_000
MAX_VALUES = 10_000_000  # variants × times: what the variants hold in memory
MAX_SHRUNK = 20  # causes shrunk; the others keep their smallest variant seen (at most 400 runs each)


class ExploreError(Exception):
    """A usage error (exit 2), said as it is."""


def _err(message: str) -> int:
    print(f"val3check sim: error: {message}", file=sys.stderr)
    return EXIT_USAGE


def run(args: Any, settings: Any, tool_version: str, write: Any) -> int:
    """`write(text, output) -> bool`: the command line's writer (standard output or -o FILE)."""
    from ...lint import display_path
    from ...simulation.scenario import ScenarioError, load_scenario

    try:
        _check(args)
    except ExploreError as exc:
        return _err(str(exc))
    try:
        scenario = load_scenario(args.scenario)
    except ScenarioError as exc:
        return _err(f"bad scenario: {exc}")
    options = RunOptions(duration=args.duration, max_wall=args.max_wall, max_lines=args.max_lines,
                         max_memory_mb=args.max_memory, cycles=args.cycles, fail_on=settings.fail_on, reports=False)
    try:
        cases = product_cases(Axes(apps=list(args.app) or ["."], arms=list(args.robot or []),
                                   scenarios=[args.scenario], cells=[args.cell] if args.cell else [], overrides=[]),
                              settings, options)
    except CaseError as exc:
        return _err(str(exc))
    if len(cases) != 1:
        return _err(f"--explore explores one application; {len(cases)} found: name one")
    base = cases[0]
    nominal_run = _nominal(base, args, settings)
    if isinstance(nominal_run, str):
        return _err(nominal_run)
    explore = scenario.data.get("explore", {}) if isinstance(scenario.data.get("explore"), dict) else {}
    jitter = args.jitter if args.jitter is not None else explore.get("jitter", 0.0)
    max_cycle = explore.get("max_cycle_time")
    ts = timings(scenario.data, scenario.text, float(jitter) if _seconds(jitter) else 0.0)
    if not any(t.lo < t.hi for t in ts):
        return _err(f"--explore: nothing to vary in {display_path(args.scenario)}: no time or delay with a range"
                    " (give --jitter SECONDS, [explore] jitter, or a range such as after = { min = 0.1, max = 0.4 };"
                    " docs/explore.md)")
    if args.explore * len(ts) > MAX_VALUES:
        return _err(f"--explore {args.explore} variants of {len(ts)} times: more than {MAX_VALUES:,} values; explore"
                    " fewer variants or a smaller scenario")
    out_dir = args.out_dir or DEFAULT_OUT_DIR
    try:
        _prepare(out_dir)
    except OutDirError as exc:
        return _err(f"--out-dir: {exc}")
    seen = observe(nominal_run)

    runs = _Runs(base, scenario.text, ts, args, Progress(0, unit="runs"))
    chosen = variants(ts, seen, args.explore, args.seed)
    nominal = tuple(t.nominal for t in ts)
    try:
        results = runs.run([nominal] + chosen)
        groups = _groups(ts, [nominal] + chosen, results, max_cycle)
        for n, g in enumerate(groups):
            if not g.nominal and n >= MAX_SHRUNK:
                g.shrunk = g.smallest
            elif not g.nominal:
                g.shrunk, g.runs = shrink(ts, g.smallest, runs.still_fails(g.cause.key, max_cycle))
            else:
                g.shrunk = nominal
            g.shrunk_cause = next((c for c in causes(runs.run([g.shrunk])[0], max_cycle) if c.key == g.cause.key),
                                  g.cause)
    except _ExecutorFailed as exc:
        runs.progress.finish()
        return _err(str(exc))
    except KeyboardInterrupt:
        runs.progress.finish()
        print("val3check sim: interrupted", file=sys.stderr)
        return 130
    runs.progress.finish()
    ex = Exploration(application=base.app, scenario=base.scenario, command=_command(args, base), seed=args.seed,
                     jitter=float(jitter), max_cycle=max_cycle, timings=ts, variants=len(chosen), runs=runs.count,
                     groups=groups, tool_version=tool_version)
    try:
        for i, g in enumerate(groups, 1):
            g.reproducer = f"{FAILURES_DIR}/{i:02d}-{safe_name(g.cause.code)}-{safe_name(_stem(g.cause.path))}" \
                           f"-{g.cause.line}.toml"
            write_file(out_dir, g.reproducer, reproducer(ex, g, variant_text(scenario.text, ts, g.shrunk)).encode())
        texts = (render_text(ex), render_json(ex), render_junit(ex), render_html(ex))
        for name, text in zip(SUMMARY_FILES, texts, strict=True):
            write_file(out_dir, name, text.encode("utf-8"))
    except OutDirError as exc:
        return _err(f"--out-dir: {exc}")
    ex.out_dir = display_path(out_dir)
    if not write(render_json(ex) if args.format == "json" else render_text(ex), args.output):
        return EXIT_USAGE
    print(f"val3check sim: wrote the summary and {len(groups)} reproducer(s) in {display_path(out_dir)}"
          " (index.html)", file=sys.stderr)
    return EXIT_FAILED if groups else EXIT_OK


def _seconds(v: object) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and 0 <= v <= 1e7


def _check(args: Any) -> None:
    if not args.scenario:
        raise ExploreError("--explore varies the times of a scenario: give --scenario FILE")
    if not 1 <= args.explore <= MAX_VARIANTS:
        raise ExploreError(f"--explore N: a number of variants from 1 to {MAX_VARIANTS:,}")
    if args.jitter is not None and not _seconds(args.jitter):
        raise ExploreError("--jitter: a number of seconds, 0 or more")
    if args.sweep or len(args.app) > 1 or len(args.robot or []) > 1:
        raise ExploreError("--explore explores one application, one arm and one scenario: not with --sweep,"
                           " several applications or several --robot")
    if args.format not in ("text", "json"):
        raise ExploreError(f"--report {args.format}: --explore prints its summary as text or json; --out-dir DIR"
                           " has every format (summary.json, junit.xml, index.html) and the reproducers")
    if args.init_scenario or args.trace or args.fail_fast:
        raise ExploreError("--explore goes without --init-scenario, --trace and --fail-fast")
    from ..executors import executor_problem

    problem = executor_problem(args)
    if problem:
        raise ExploreError(problem)


def _prepare(out_dir: str) -> None:
    """The out folder, and its failures/ folder: folders, not links or files."""
    try:
        os.makedirs(out_dir, exist_ok=True)
    except (OSError, ValueError) as exc:
        raise OutDirError(f"cannot create {out_dir}: {getattr(exc, 'strerror', None) or exc}") from None
    if not os.path.isdir(out_dir):
        raise OutDirError(f"{out_dir} is not a folder")
    failures = os.path.join(out_dir, FAILURES_DIR)
    if os.path.islink(failures) or os.path.lexists(failures) and not os.path.isdir(failures):
        raise OutDirError(f"{failures} is a link or a file: the reproducers go in a folder of {out_dir} (remove it)")
    inside(out_dir, FAILURES_DIR)


def _nominal(base: Any, args: Any, settings: Any) -> Any:
    """The nominal run, here (its I/O log and task states give the boundaries); a reason when it
    cannot run."""
    from ...lint import printable_path
    from ...simulation import case as sim_case

    spec = sim_case.CaseSpec(base.app_path, settings, robot=args.robot[0] if args.robot else None,
                             scenario=args.scenario, cell=args.cell, duration=args.duration, cycles=args.cycles,
                             max_wall=args.max_wall, max_lines=args.max_lines, max_memory_mb=args.max_memory,
                             exact=True)
    done = sim_case.run_case(spec)
    if done.refused is None:
        return done.result
    if done.refused == sim_case.SCENARIO:  # the whole scenario checked, at its lines, before anything varies
        return f"bad scenario: {printable_path(done.message)}"
    if done.errors:
        d = done.errors[0]
        return (f"--explore: the application cannot run: {len(done.errors)} lint error(s), the first: "
                f"{printable_path(d.path)}:{d.line}:{d.col}: {d.code} {d.message}")
    return f"--explore: the application cannot run: {printable_path(done.message or done.refused)}"


def _command(args: Any, base: Any) -> list[str]:
    """The plain `val3check sim` that runs a reproducer (its scenario path last)."""
    cmd = ["val3check", "sim", base.app]
    if args.robot:
        cmd += ["--robot", args.robot[0]]
    if args.cell:
        cmd += ["--cell", args.cell]
    if args.duration != 60.0:
        cmd += ["--duration", f"{args.duration:g}"]
    if args.cycles:
        cmd += ["--cycles", str(args.cycles)]
    if args.fail_on:
        cmd += ["--fail-on", args.fail_on]
    return cmd + ["--scenario"]


def _stem(path: str) -> str:
    return os.path.splitext(os.path.basename(path))[0] if path else "run"


def _groups(ts: list[Timing], vs: list[tuple], results: list, max_cycle: float | None) -> list[Group]:
    """The causes of the runs, grouped: the nominal's first (variant 0), then by rule, file, line."""
    groups: dict[tuple, Group] = {}
    for k, (values, summary) in enumerate(zip(vs, results, strict=True)):
        for c in causes(summary, max_cycle):
            g = groups.setdefault(c.key, Group(c, nominal=k == 0, smallest=values))
            g.count += 1 if k else 0
            if k:
                g.variants.append(k)
            if size(ts, values) < size(ts, g.smallest) and not g.nominal:
                g.smallest = values
    return sorted(groups.values(), key=lambda g: (not g.nominal, _order(g.cause)))


def _order(c: Cause) -> tuple:
    return (c.path, c.line, c.code)


class _ExecutorFailed(Exception):
    pass


@dataclass
class _Runs:
    """Runs variants on the executor, each once (a variant asked again is answered from memory)."""

    base: Any
    text: str
    ts: list[Timing]
    args: Any
    progress: Progress
    count: int = 0

    def __post_init__(self) -> None:
        self.memo: dict[tuple, Any] = {}

    def run(self, vs: list[tuple]) -> list:
        todo = list(dict.fromkeys(v for v in vs if v not in self.memo))
        if todo:
            self._execute(todo)
        return [self.memo[v] for v in vs]

    def still_fails(self, key: tuple, max_cycle: float | None):
        def check(vs: list[tuple]) -> list[bool]:
            return [any(c.key == key for c in causes(s, max_cycle)) for s in self.run(vs)]
        return check

    def _execute(self, todo: list[tuple]) -> None:
        from ..executors import ExecutorError, run_dask, run_pool

        by_tag: dict[str, tuple] = {}
        cases = []
        for v in todo:
            tag = f"{self.count + len(cases) + 1:06d}"
            by_tag[tag] = v
            data = variant_text(self.text, self.ts, v).encode("utf-8")
            files = tuple((p, data if p == self.base.scenario_path else b) for p, b in self.base.files)
            cases.append(replace(self.base, scenario=f"{self.base.scenario}#{tag}", files=files))
        self.count += len(cases)
        self.progress.total += len(cases)

        def on_done(outcome: Any) -> None:
            s = outcome.summary
            self.memo[by_tag[s.scenario.rsplit("#", 1)[1]]] = s
            self.progress.update(s.verdict == "pass")

        try:
            if self.args.executor == "dask":
                # no --scheduler: DASK_SCHEDULER_ADDRESS, else a local cluster, as `sim -j` does
                run_dask(cases, self.args.scheduler, on_done, lambda: False,
                         workers=min(self.args.jobs or _cores(), len(cases)))
            else:
                run_pool(cases, min(self.args.jobs or _cores(), len(cases)), on_done, lambda: False)
        except ExecutorError as exc:
            raise _ExecutorFailed(str(exc)) from None


def _cores() -> int:
    try:
        return len(os.sched_getaffinity(0)) or 1
    except AttributeError:
        return os.cpu_count() or 1
