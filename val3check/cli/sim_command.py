"""`val3check sim`, `val3check reach`, `val3check robots`: the simulator's commands (docs/sim.md)."""

from __future__ import annotations

import argparse
import os
import sys

from .. import __version__
from .common import EXIT_FINDINGS, EXIT_OK, EXIT_USAGE, MAX_DURATION, settings_of, shown, write


_GLOB_CHARS = set("*?[")


def wants_batch(args: argparse.Namespace) -> bool:
    """Whether the command line asks for a batch (docs/batch.md); otherwise `sim` runs one
    application, without importing the batch's modules."""
    return bool(len(args.app) > 1 or args.sweep or len(args.robot or []) > 1 or args.out_dir or args.jobs is not None
                or args.executor != "local" or any(_GLOB_CHARS & set(a) for a in args.app))


def sim(args: argparse.Namespace) -> int:
    """Lint first (in-process); run only an application without error-level findings."""
    batch = wants_batch(args)
    if not batch:
        args.app = args.app[0] if args.app else "."
        args.robot = args.robot[0] if args.robot else None
    settings = settings_of(args, args.app[0] if batch and args.app else "." if batch else args.app)
    if settings is None:
        return EXIT_USAGE
    if args.fail_on:
        settings.fail_on = args.fail_on
    settings.disk_roots = [os.path.abspath(d) for d in args.disk_root] + settings.disk_roots
    if not 0 < args.duration <= MAX_DURATION or not 0 < args.max_wall <= MAX_DURATION or args.max_lines < 1:
        print(f"val3check: error: --duration and --max-wall must be positive numbers of seconds (at most {MAX_DURATION:g}),"
              " --max-lines a positive number", file=sys.stderr)
        return EXIT_USAGE
    if args.cycles is not None and args.cycles < 1:
        print("val3check: error: --cycles must be a positive number of cycles", file=sys.stderr)
        return EXIT_USAGE
    if not 0 < args.max_memory <= 1 << 20:
        print("val3check: error: --max-memory must be a positive number of MB", file=sys.stderr)
        return EXIT_USAGE
    from ..rules.catalogue import catalogue

    bad = settings.unknown_codes(list(catalogue()))
    if bad:
        print(f"val3check: error: unknown rule code or prefix: {', '.join(bad)} (see `val3check rules`)", file=sys.stderr)
        return EXIT_USAGE
    from ..simulation.requirements import install_hint, missing_sim_packages

    missing = missing_sim_packages() if not args.init_scenario else []
    if missing:
        print(f"val3check: error: {install_hint(missing)}", file=sys.stderr)
        return EXIT_USAGE
    if args.explore is not None:
        from ..batch.explore.command import run as run_explore

        if not batch:
            args.app, args.robot = [args.app], [args.robot] if args.robot else []
        return run_explore(args, settings, __version__, write)
    if args.jitter is not None:
        print("val3check: error: --jitter goes with --explore N", file=sys.stderr)
        return EXIT_USAGE
    if batch:
        from ..batch.command import run as run_batch

        return run_batch(args, settings, __version__, write)

    from ..reporting import render
    from ..simulation import case as sim_case

    def say(note: str) -> None:
        print(f"val3check sim: note: {shown(note)}", file=sys.stderr)

    spec = sim_case.CaseSpec(args.app, settings, robot=args.robot, scenario=args.scenario, cell=args.cell,
                             duration=args.duration, cycles=args.cycles, max_wall=args.max_wall,
                             max_lines=args.max_lines, max_memory_mb=args.max_memory)
    if args.init_scenario:
        done = sim_case.lint_case(spec, say)
        if done.refused is None:
            return init_scenario(done.lint.workspace, done.app, args.init_scenario)
    else:
        from ..reporting.progress import Progress

        spec.progress = lambda: Progress.for_stream(sys.stderr, args.duration)  # only on a terminal
        if getattr(args, "own_process", False):
            spec.step = freeze_before_run
        done = sim_case.run_case(spec, say)
    if done.refused == sim_case.UNREADABLE:
        sys.stdout.write(render("text", done.lint.result))
        print(f"val3check sim: error: no application could be read at {shown(args.app)}", file=sys.stderr)
        return EXIT_USAGE
    if done.refused == sim_case.SEVERAL:
        print(f"val3check sim: error: {done.message}", file=sys.stderr)
        return EXIT_USAGE
    if done.refused == sim_case.LINT_ERRORS:
        from ..result import LintResult

        r = done.lint.result  # only the errors that keep it from running, not every warning
        sys.stderr.write(render("text", LintResult(done.errors, r.files, r.applications, r.rules, r.tool_version,
                                                   r.quotable)))
        print(f"val3check sim: not run: the application has {len(done.errors)} error(s) (val3check lint); fix them"
              " first", file=sys.stderr)
        return EXIT_USAGE
    if done.refused == sim_case.NO_START:
        print(f"val3check sim: not run: {done.message}", file=sys.stderr)
        return EXIT_USAGE
    if done.refused == sim_case.ROBOT:
        print(f"val3check sim: --robot: {shown(done.message)}", file=sys.stderr)
        return EXIT_USAGE
    if done.refused == sim_case.SCENARIO:
        print(f"val3check sim: bad scenario: {shown(done.message)}", file=sys.stderr)
        return EXIT_USAGE
    from ..reporting.sim_render import sim_pieces
    from ..reporting.sim_report import build_report
    from ..reporting.sim_verdict import closing_line, failed
    from ..rules.catalogue import catalogue

    report = build_report(done.result, settings, catalogue(), __version__)
    if not write(sim_pieces(args.format, report, fail_on=settings.fail_on, scenario=args.scenario), args.output):
        return EXIT_USAGE
    if args.trace and not write_trace(report, args.trace):
        return EXIT_USAGE
    written = [shown(p) for p in (args.output, args.trace) if p and p != "-"]
    if written or args.format != "text":  # the text report on standard output ends with the line itself
        print(f"val3check sim: {closing_line(report, settings.fail_on, written)}", file=sys.stderr)
    return EXIT_FINDINGS if failed(report, settings.fail_on) else EXIT_OK


YOUNG_THRESHOLD = 10_000  # the collector's first threshold during a run (Python's default: 700)


def freeze_before_run(step: str) -> None:
    """`val3check sim` as a process of its own: once linted, what the process holds (modules, the
    application's trees and symbols) lives to the end; frozen, the collector's full passes during
    the run no longer walk it. The run allocates millions of short-lived objects, nearly all freed
    by their count: the young generation is collected every 10,000 allocations rather than 700
    (docs/performance.md, "Start-up and the interpreter"). Not when `main` is called with
    arguments (tests, other programs: their collector is theirs)."""
    if step == "run":
        import gc

        gc.freeze()
        gc.set_threshold(YOUNG_THRESHOLD, *gc.get_threshold()[1:])


def write_trace(report, path: str) -> bool:
    from ..reporting.mcap_trace import write_trace

    try:
        write_trace(report, path)
    except OSError as exc:
        print(f"val3check sim: error: cannot write the trace {shown(path)}: {shown(exc.strerror or str(exc))}",
              file=sys.stderr)
        return False
    return True


def init_scenario(workspace, app, path: str) -> int:  # noqa: ANN001
    from ..simulation.scenario_skeleton import skeleton

    if os.path.lexists(path):
        print(f"val3check sim: error: {shown(path)} exists; --init-scenario writes a new file", file=sys.stderr)
        return EXIT_USAGE
    if not write(skeleton(workspace, app, shown(os.path.relpath(app.path))), path):
        return EXIT_USAGE
    print(f"val3check sim: wrote the scenario skeleton {shown(path)}; run it with --scenario {shown(path)}",
          file=sys.stderr)
    return EXIT_OK


def reach(args: argparse.Namespace) -> int:
    """`val3check reach`: no run; 1 when a finding is at or above --fail-on (as lint)."""
    from ..loading import LoadOptions, load
    from ..robot import RobotError, choose_robot
    from ..simulation.requirements import install_hint, missing_sim_packages

    missing = missing_sim_packages()  # the reach check computes with the sim extra (numpy): none on a light install
    if missing:
        print(f"val3check: error: {install_hint(missing, 'reach')}", file=sys.stderr)
        return EXIT_USAGE
    ws, _diags = load([args.app], LoadOptions(disk_roots=[os.path.abspath(d) for d in args.disk_root]))
    apps = [ws.apps[k] for k in ws.targets]
    if len(apps) != 1:
        what = "no application" if not apps else f"{len(apps)} applications"
        print(f"val3check reach: error: {args.app} holds {what}; name one application", file=sys.stderr)
        return EXIT_USAGE
    try:
        model = choose_robot(args.robot, apps[0].path)
    except RobotError as exc:
        print(f"val3check reach: --robot: {exc}", file=sys.stderr)
        return EXIT_USAGE
    from ..motion.reach import check_reach
    from ..reporting.reach import render_json, render_text

    try:
        report = check_reach(ws, apps[0], model)
    except RobotError as exc:  # no closed-form inverse kinematics for this arm
        print(f"val3check reach: {exc}", file=sys.stderr)
        return EXIT_USAGE
    text = render_json(report) if args.format == "json" else render_text(report)
    if not write(text, args.output):
        return EXIT_USAGE
    if args.fail_on == "never":
        return EXIT_OK
    rank = {"info": 1, "warning": 2, "error": 3}
    return EXIT_FINDINGS if any(rank[e.severity] >= rank[args.fail_on] for e in report.problems()) else EXIT_OK


def robots(args: argparse.Namespace) -> int:
    """`val3check robots`: the catalogue, or one model in detail (val3check/robot); `robots fit`."""
    from ..robot import RobotError, load_robot, names
    from ..robot.catalog import known_without_model
    from ..robot.listing import render_detail, render_list

    if args.robot[:1] == ["fit"]:
        from ..simulation.fit import command

        if len(args.robot) != 2:
            print("val3check robots fit: error: one application is needed: val3check robots fit APP --robot ROBOT "
                  "--measured-cycle S", file=sys.stderr)
            return EXIT_USAGE
        return command(args.robot[1], args.robot_opt, args.measured_cycle, args.scenario, args.duration, args.cycles,
                       args.output)
    fit_only = [o for o, v in (("--measured-cycle", args.measured_cycle), ("--scenario", args.scenario),
                               ("--cycles", args.cycles), ("-o", args.output)) if v is not None]
    if len(args.robot) > 1 or fit_only:
        print(f"val3check robots: error: {' '.join(fit_only) or ' '.join(args.robot[1:])}: only with "
              "`val3check robots fit APP` (one ROBOT otherwise)", file=sys.stderr)
        return EXIT_USAGE
    args.robot = (args.robot[0] if args.robot else None) or args.robot_opt
    try:
        if args.robot or args.app:
            models = [load_robot(args.robot or None, args.app)]
        else:
            models = [load_robot(n) for n in names()]
    except RobotError as exc:
        print(f"val3check: error: {shown(str(exc))}", file=sys.stderr)
        return EXIT_USAGE
    detail = bool(args.robot or args.app)
    if args.format == "json":
        import json

        body = {"robots": [m.describe() for m in models], "version": 1}
        if not detail:
            body["without_model"] = known_without_model()
        sys.stdout.write(json.dumps(body, indent=2, ensure_ascii=False) + "\n")
        return EXIT_OK
    sys.stdout.write(render_detail(models[0]) if detail else render_list(models, known_without_model()))
    return EXIT_OK


