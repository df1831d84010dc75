"""Command line: `val3check lint`, `val3check sim`, `val3check reach`, `val3check robots`, `val3check rules`,
`val3check rule CODE`, `val3check server` (the language server).

Exit codes (README): 0 nothing at or above --fail-on; 1 findings; 2 usage error, bad
configuration, or input that could not be read at all. `sim` (docs/sim.md): 0 the run raised
no runtime diagnostic at or above --fail-on; 1 it did; 2 the application was not run (usage,
unreadable input, lint errors, bad scenario).
"""

from __future__ import annotations

import argparse
import os
import sys

from . import __version__
from .reporting import FORMATS, SIM_FORMATS

EXIT_OK, EXIT_FINDINGS, EXIT_USAGE = 0, 1, 2
MAX_DURATION = 1e7  # seconds (about 115 days): --duration inf or nan is a usage error


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> None:  # argparse exits 2 too; keep its wording short
        self.print_usage(sys.stderr)
        print(f"val3check: error: {message}", file=sys.stderr)
        raise SystemExit(EXIT_USAGE)


def _codes(text: str) -> list[str]:
    return [c.strip().upper() for c in text.split(",") if c.strip()]


def _add_format(parser: argparse.ArgumentParser, choices, *also: str, default: str = "text") -> None:
    """`--output-format` (ruff's name) and `--format`, one option across the commands; `also`:
    further synonyms (`sim --report`)."""
    parser.add_argument("--output-format", "--format", *also, dest="format", choices=choices, default=default,
                        help=f"output format (default: {default})")


def _add_config(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--config", metavar="FILE", help="configuration file (default: val3check.toml or pyproject.toml found upwards)")
    parser.add_argument("--isolated", action="store_true", help="ignore every configuration file")


def _add_disk_root(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--disk-root", action="append", default=[], metavar="DIR",
                        help="folder where Disk:// libraries and types are also searched (repeatable)")


def _patterns(text: str) -> list[str]:
    return [p.strip() for p in text.split(",") if p.strip()]


def _add_batch(sim: argparse.ArgumentParser) -> None:
    """`sim` on several cases (docs/batch.md, val3check/batch)."""
    b = sim.add_argument_group("batch (several applications, arms, scenarios: docs/batch.md)")
    b.add_argument("--sweep", metavar="FILE", help="sweep file (TOML): the applications, arms, scenarios, cells and overrides to combine")
    b.add_argument("-j", "--jobs", type=int, metavar="N", help="cases run at once in processes on this machine (default: the number of cores)")
    b.add_argument("--executor", choices=("local", "dask"), default="local", help="where cases run: local processes, or a Dask cluster (the dask extra)")
    b.add_argument("--scheduler", metavar="ADDRESS", help="the Dask scheduler's address, tcp://host:8786 (with --executor dask; default: DASK_SCHEDULER_ADDRESS, else a local cluster of -j processes)")
    b.add_argument("--out-dir", metavar="DIR", help="write the summary (text, JSON, JUnit, index.html) and each case's report under DIR")
    b.add_argument("--fail-fast", action="store_true", help="stop at the first case that does not pass")
    b.add_argument("--case-reports", default="json", metavar="KINDS", help="what --out-dir writes for each case, comma-separated: json, html, trace (default: json)")
    e = sim.add_argument_group("exploration (timings of the scenario: docs/explore.md)")
    e.add_argument("--explore", type=int, metavar="N", help="run N variants of the --scenario's times and delays; write each failure, shrunk, as a scenario that reproduces it (in --out-dir, default val3check-explore)")
    e.add_argument("--jitter", type=float, metavar="SECONDS", help="move each time and delay by up to ± SECONDS (default: the scenario's [explore] jitter; its ranges win)")
    e.add_argument("--seed", type=int, default=0, metavar="K", help="the seed of the draws: the same command gives the same variants anywhere (default: 0)")


def build_parser() -> argparse.ArgumentParser:
    p = _Parser(prog="val3check", description="Check Stäubli VAL 3 applications.")
    p.add_argument("--version", action="version", version=f"val3check {__version__}")
    sub = p.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)

    lint = sub.add_parser("lint", help="check applications (.pjx, .pgx, folders, controller trees)")
    lint.add_argument("paths", nargs="*", metavar="PATH", help="files or folders (default: .)")
    _add_format(lint, FORMATS)
    lint.add_argument("-o", "--output", metavar="FILE", help="write the report to FILE instead of standard output")
    lint.add_argument("--fail-on", choices=("error", "warning", "info", "never"), help="lowest severity that makes the exit code 1 (default: error)")
    lint.add_argument("--exit-zero", action="store_true", help="exit 0 even when findings are reported (2 still means the input could not be read)")
    lint.add_argument("-q", "--quiet", action="store_true", help="print the findings and nothing else (no summary, no notes)")
    lint.add_argument("--select", type=_codes, metavar="CODES", help="comma-separated codes or prefixes to enable (replaces the configured list)")
    lint.add_argument("--extend-select", type=_codes, metavar="CODES", help="codes or prefixes to enable in addition")
    lint.add_argument("--ignore", type=_codes, metavar="CODES", help="codes or prefixes to disable (added to the configured list)")
    lint.add_argument("--exclude", type=_patterns, metavar="PATTERNS", help="comma-separated gitignore patterns of paths to skip (replaces the configured list and the default, **/usr/templates/)")
    lint.add_argument("--extend-exclude", type=_patterns, metavar="PATTERNS", help="gitignore patterns to skip in addition")
    lint.add_argument("--force-exclude", action=argparse.BooleanOptionalAction, default=None,
                      help="skip the paths named on the command line too when they match an exclusion (as pre-commit hooks need)")
    _add_disk_root(lint)
    _add_config(lint)
    lint.add_argument("--statistics", action="store_true", help="show counts per rule instead of each finding")
    lint.add_argument("--fix", action="store_true", help="apply the fixes that are certain (rules marked [fix] in `val3check rules`), then report what is left")
    lint.add_argument("--diff", action="store_true", help="print the fixes --fix would make as a unified diff, change nothing; exit 1 when there are some")
    lint.add_argument("--baseline", metavar="FILE", help="do not report the findings this baseline file records (see --update-baseline)")
    lint.add_argument("--update-baseline", action="store_true", help="record every finding of this run in the --baseline file, and exit 0")
    lint.add_argument("--show-settings", action="store_true", help="show the configuration, the applications and the rules of this run, and exit")
    lint.add_argument("--show-files", action="store_true", help="list the files that would be checked, and exit")
    lint.add_argument("--stdin-filename", metavar="PATH", help="check the text read from standard input as if it were the file PATH, "
                      "in the context of its application (for editors); only its findings are reported; "
                      "`-` among the paths stands for standard input, as in ruff")
    lint.add_argument("--color", choices=("auto", "always", "never"), default="auto",
                      help="colour the text output (auto: on a terminal; NO_COLOR and FORCE_COLOR are honoured)")

    sim = sub.add_parser("sim", help="run an application in the virtual controller (docs/sim.md)")
    sim.add_argument("app", nargs="*", metavar="APP", help="the application: its folder or .pjx (default: .); several"
                     " applications, folders of applications, controller trees or globs run as a batch (docs/batch.md)")
    sim.add_argument("--duration", type=float, default=60.0, metavar="S", help="simulated seconds to run at most (default: 60)")
    sim.add_argument("--cycles", type=int, metavar="N", help="end the run when the arm starts its cycle N + 1 (the loop of the task that moves it; docs/motion.md)")
    _add_format(sim, SIM_FORMATS, "--report")
    sim.add_argument("-o", "--output", metavar="FILE", help="write the report to FILE instead of standard output")
    sim.add_argument("--trace", metavar="FILE", help="also write the run as an MCAP trace for Foxglove (docs/trace.md)")
    sim.add_argument("--scenario", metavar="FILE", help="I/O scenario (TOML, docs/scenario.md)")
    sim.add_argument("--init-scenario", metavar="FILE", help="write a scenario skeleton listing what the application reads "
                     "or waits on (inputs, sio, keys, controller state) with their defaults, and exit")
    sim.add_argument("--max-wall", type=float, default=60.0, metavar="S", help="wall-clock budget in seconds (default: 60)")
    sim.add_argument("--max-lines", type=int, default=50_000_000, metavar="N", help="budget of executed VAL 3 lines")
    sim.add_argument("--max-memory", type=float, default=512.0, metavar="MB",
                     help="memory budget in MB, loading included (default: 512)")
    sim.add_argument("--fail-on", choices=("error", "warning", "info", "never"), help="lowest runtime diagnostic severity that makes the exit code 1 (default: error)")
    _add_disk_root(sim)
    sim.add_argument("--cell", metavar="FILE", help="the cell around the arm, checked for collisions (TOML, docs/cell.md; default: val3check-cell.toml beside the application; none: the arm against itself only)")
    sim.add_argument("--robot", action="append", metavar="NAME|URDF", help="the arm model: a catalogue name (case-insensitive, `val3check robots`), a URDF, an arm.cfx, or none (default: the usr/configs/arm.cfx of the controller tree holding APP, else none); repeat it to run a batch on each arm")
    _add_config(sim)
    _add_batch(sim)

    reach = sub.add_parser("reach", help="check that the arm reaches every point and joint of the data files (docs/motion.md)")
    reach.add_argument("app", metavar="APP", help="the application: its folder or .pjx")
    reach.add_argument("--robot", metavar="NAME|URDF", help="the arm model (default: the usr/configs/arm.cfx of the controller tree holding APP)")
    _add_format(reach, ("text", "json"))
    reach.add_argument("-o", "--output", metavar="FILE", help="write the report to FILE instead of standard output")
    reach.add_argument("--disk-root", action="append", default=[], metavar="DIR", help="folder where Disk:// libraries are also searched (repeatable)")
    reach.add_argument("--fail-on", choices=("error", "warning", "info", "never"), default="error", help="lowest finding severity that makes the exit code 1 (default: error; reach findings are warnings and infos, docs/motion.md)")

    robots = sub.add_parser("robots", help="list the arm models by family (reach, joint limits, speeds, assumptions), show "
                            "one, or fit one's accelerations to a measured cycle (robots fit APP --robot ROBOT "
                            "--measured-cycle S -o FILE)")
    robots.add_argument("robot", nargs="*", metavar="ROBOT",
                        help="an arm name (case-insensitive: tx2-60, TX2_60, ts60-L200…), a URDF, an arm.cfx or a robot file "
                             "(.toml): show that model, its facts and assumptions; or `fit APP`: fit the accelerations of "
                             "--robot to the cycle measured on the cell (docs/sim.md, \"Fitting the accelerations\")")
    robots.add_argument("--robot", dest="robot_opt", metavar="ROBOT", help="same as ROBOT")
    robots.add_argument("--app", metavar="PATH", help="show the arm chosen from the controller tree holding PATH (usr/configs/arm.cfx)")
    _add_format(robots, ("text", "json"))
    robots.add_argument("--measured-cycle", type=float, metavar="S",
                        help="fit: the cycle time measured on the cell, in seconds (the loop the reports give)")
    robots.add_argument("--scenario", metavar="FILE", help="fit: the I/O scenario of the run (TOML, docs/scenario.md)")
    robots.add_argument("--duration", type=float, default=60.0, metavar="S",
                        help="fit: simulated seconds of each run at most (default: 60)")
    robots.add_argument("--cycles", type=int, metavar="N", help="fit: end each run after N cycles")
    robots.add_argument("-o", "--output", metavar="FILE", help="fit: write the robot file to FILE (default: standard output)")

    server = sub.add_parser("server", help="run the language server for editors, over stdio (docs/editors.md)")
    server.add_argument("--stdio", action="store_true", help="talk LSP over standard input and output (the default and only transport)")

    rules = sub.add_parser("rules", help="list the rule catalogue")
    _add_format(rules, ("text", "json"))
    rule = sub.add_parser("rule", help="explain one rule, or every rule with --all")
    rule.add_argument("code", nargs="?", metavar="CODE")
    rule.add_argument("--all", action="store_true", help="explain every rule")
    _add_format(rule, ("text", "json"))
    return p


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    try:
        if args.command == "lint":
            return _lint(args)
        if args.command == "sim":
            return _sim(args)
        if args.command == "robots":
            return _robots(args)
        if args.command == "reach":
            return _reach(args)
        if args.command == "rules":
            return _rules(args)
        if args.command == "rule":
            return _rule(args)
        if args.command == "server":
            return _server()
    except BrokenPipeError:  # `val3check rules | head`
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return EXIT_OK
    build_parser().print_help()
    return EXIT_USAGE


def _targets(paths: list[str]) -> list[str]:
    """Files as pre-commit passes them: a .dtx stands for its application folder; keep order, no repeats."""
    out: list[str] = []
    for path in paths or ["."]:
        if path.lower().endswith(".dtx") and os.path.isfile(path):
            folder = os.path.dirname(os.path.abspath(path))
            if any(n.lower().endswith(".pjx") for n in os.listdir(folder)):
                path = folder
        if path not in out:
            out.append(path)
    return out


def _settings(args: argparse.Namespace, first_path: str, quiet: bool = False):
    from .config import ConfigError, Settings, find_config, load_settings

    try:
        settings = Settings()
        if args.config:
            if not os.path.lexists(args.config):
                raise ConfigError(f"{args.config}: configuration file not found")
            settings = load_settings(args.config)
        elif not args.isolated:
            found = find_config(first_path, warn=None if quiet else
                                lambda m: print(f"val3check: warning: {_shown(m)}", file=sys.stderr))
            if found:
                settings = load_settings(found)
    except ConfigError as exc:
        print(f"val3check: error: {_shown(str(exc))}", file=sys.stderr)
        return None
    return settings


def _write(text: str, output: str | None) -> bool:
    # Reports are UTF-8; a character that cannot be encoded (a lone surrogate from a file name
    # that is not UTF-8) is escaped rather than ending the run with UnicodeEncodeError.
    if output is None:
        try:
            sys.stdout.write(text)
        except UnicodeEncodeError:
            enc = sys.stdout.encoding or "utf-8"
            sys.stdout.write(text.encode(enc, "backslashreplace").decode(enc))
        sys.stdout.flush()
        return True
    try:
        with open(output, "w", encoding="utf-8", errors="backslashreplace", newline="\n") as fh:
            fh.write(text)
    except (OSError, ValueError) as exc:
        print(f"val3check: error: cannot write {_shown(output)}: {getattr(exc, 'strerror', None) or exc}",
              file=sys.stderr)
        return False
    return True


def _shown(path: str) -> str:
    from .lint import printable_path

    return printable_path(path)


def _sim(args: argparse.Namespace) -> int:
    """Lint first (in-process); run only an application without error-level findings."""
    from .batch.command import wanted

    batch = wanted(args)
    if not batch:
        args.app = args.app[0] if args.app else "."
        args.robot = args.robot[0] if args.robot else None
    settings = _settings(args, args.app[0] if batch and args.app else "." if batch else args.app)
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
    from .rules.catalogue import catalogue

    bad = settings.unknown_codes(list(catalogue()))
    if bad:
        print(f"val3check: error: unknown rule code or prefix: {', '.join(bad)} (see `val3check rules`)", file=sys.stderr)
        return EXIT_USAGE
    from .simulation.requirements import install_hint, missing_sim_packages

    missing = missing_sim_packages() if not args.init_scenario else []
    if missing:
        print(f"val3check: error: {install_hint(missing)}", file=sys.stderr)
        return EXIT_USAGE
    if args.explore is not None:
        from .batch.explore.command import run as run_explore

        if not batch:
            args.app, args.robot = [args.app], [args.robot] if args.robot else []
        return run_explore(args, settings, __version__, _write)
    if args.jitter is not None:
        print("val3check: error: --jitter goes with --explore N", file=sys.stderr)
        return EXIT_USAGE
    if batch:
        from .batch.command import run as run_batch

        return run_batch(args, settings, __version__, _write)

    from .reporting import render
    from .simulation import case as sim_case

    def say(note: str) -> None:
        print(f"val3check sim: note: {_shown(note)}", file=sys.stderr)

    spec = sim_case.CaseSpec(args.app, settings, robot=args.robot, scenario=args.scenario, cell=args.cell,
                             duration=args.duration, cycles=args.cycles, max_wall=args.max_wall,
                             max_lines=args.max_lines, max_memory_mb=args.max_memory)
    if args.init_scenario:
        done = sim_case.lint_case(spec, say)
        if done.refused is None:
            return _init_scenario(done.lint.workspace, done.app, args.init_scenario)
    else:
        from .reporting.progress import Progress

        spec.progress = lambda: Progress.for_stream(sys.stderr, args.duration)  # only on a terminal
        done = sim_case.run_case(spec, say)
    if done.refused == sim_case.UNREADABLE:
        sys.stdout.write(render("text", done.lint.result))
        print(f"val3check sim: error: no application could be read at {_shown(args.app)}", file=sys.stderr)
        return EXIT_USAGE
    if done.refused == sim_case.SEVERAL:
        print(f"val3check sim: error: {done.message}", file=sys.stderr)
        return EXIT_USAGE
    if done.refused == sim_case.LINT_ERRORS:
        from .result import LintResult

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
        print(f"val3check sim: --robot: {_shown(done.message)}", file=sys.stderr)
        return EXIT_USAGE
    if done.refused == sim_case.SCENARIO:
        print(f"val3check sim: bad scenario: {_shown(done.message)}", file=sys.stderr)
        return EXIT_USAGE
    from .reporting.sim_render import render_sim
    from .reporting.sim_report import build_report
    from .reporting.sim_verdict import closing_line, failed
    from .rules.catalogue import catalogue

    report = build_report(done.result, settings, catalogue(), __version__)
    if not _write(render_sim(args.format, report, fail_on=settings.fail_on, scenario=args.scenario), args.output):
        return EXIT_USAGE
    if args.trace and not _write_trace(report, args.trace):
        return EXIT_USAGE
    written = [_shown(p) for p in (args.output, args.trace) if p and p != "-"]
    if written or args.format != "text":  # the text report on standard output ends with the line itself
        print(f"val3check sim: {closing_line(report, settings.fail_on, written)}", file=sys.stderr)
    return EXIT_FINDINGS if failed(report, settings.fail_on) else EXIT_OK


def _write_trace(report, path: str) -> bool:
    from .reporting.mcap_trace import write_trace

    try:
        write_trace(report, path)
    except OSError as exc:
        print(f"val3check sim: error: cannot write the trace {_shown(path)}: {_shown(exc.strerror or str(exc))}",
              file=sys.stderr)
        return False
    return True


def _use_color(choice: str, to_file: bool) -> bool:
    """--color always/never wins; then NO_COLOR (set and not empty) turns colour off and
    FORCE_COLOR (set and not empty) on; else colour on a terminal only."""
    if choice != "auto":
        return choice == "always"
    if to_file or os.environ.get("NO_COLOR"):
        return False
    if os.environ.get("FORCE_COLOR"):
        return True
    return sys.stdout.isatty()


def _lint_settings(args: argparse.Namespace, paths: list[str]):  # noqa: ANN202
    """The configuration with the command line's options applied; None after a usage error."""
    settings = _settings(args, paths[0], quiet=args.quiet)
    if settings is None:
        return None
    if args.select is not None:
        settings.select = args.select
    if args.extend_select:
        settings.extend_select += args.extend_select
    if args.ignore:
        settings.ignore += args.ignore
    if args.fail_on:
        settings.fail_on = args.fail_on
    if args.exclude is not None:
        settings.exclude = args.exclude
    if args.extend_exclude:
        settings.extend_exclude += args.extend_exclude
    if args.force_exclude is not None:
        settings.force_exclude = args.force_exclude
    settings.disk_roots = [os.path.abspath(d) for d in args.disk_root] + settings.disk_roots

    from .rules.catalogue import catalogue

    bad = settings.unknown_codes(list(catalogue()))
    if bad:
        print(f"val3check: error: unknown rule code or prefix: {', '.join(bad)} (see `val3check rules`)", file=sys.stderr)
        return None
    return settings


def _init_scenario(workspace, app, path: str) -> int:  # noqa: ANN001
    from .simulation.scenario_skeleton import skeleton

    if os.path.lexists(path):
        print(f"val3check sim: error: {_shown(path)} exists; --init-scenario writes a new file", file=sys.stderr)
        return EXIT_USAGE
    if not _write(skeleton(workspace, app, _shown(os.path.relpath(app.path))), path):
        return EXIT_USAGE
    print(f"val3check sim: wrote the scenario skeleton {_shown(path)}; run it with --scenario {_shown(path)}",
          file=sys.stderr)
    return EXIT_OK


def _lint(args: argparse.Namespace) -> int:
    if "-" in (args.paths or []):  # ruff's spelling of standard input
        if not args.stdin_filename:
            print("val3check: error: `-` (standard input) needs --stdin-filename PATH, the file whose text is read"
                  " (its application is read from the disk)", file=sys.stderr)
            return EXIT_USAGE
        args.paths = [p for p in args.paths if p != "-"]
    if args.stdin_filename and not args.paths:
        args.paths = [args.stdin_filename]
    paths = _targets(args.paths)
    settings = _lint_settings(args, paths)
    if settings is None:
        return EXIT_USAGE
    if args.show_settings or args.show_files:
        from .lint import discover
        from .reporting.settings import render_files, render_settings
        from .rules.catalogue import catalogue

        found = discover(paths, settings)
        if args.show_files:
            text = render_files(found)
        else:
            text = render_settings(settings, found, catalogue(), json_format=args.format == "json")
        return EXIT_OK if _write(text, args.output) else EXIT_USAGE

    from .lint import exit_code, run
    from .reporting import render

    baseline_path = os.path.abspath(args.baseline) if args.baseline else settings.baseline
    if args.update_baseline:
        return _update_baseline(paths, settings, baseline_path, args.quiet)
    baseline = None
    if baseline_path:
        from .baseline import BaselineError, read_baseline

        try:
            baseline = read_baseline(baseline_path)
        except BaselineError as exc:
            print(f"val3check: error: {_shown(str(exc))}", file=sys.stderr)
            return EXIT_USAGE
    overlay = only = None
    if args.stdin_filename:
        only = os.path.abspath(args.stdin_filename)
        if not os.path.isfile(only):
            print(f"val3check: error: --stdin-filename {_shown(args.stdin_filename)}: no such file; the file must exist "
                  "(its application is read from the disk, its text from standard input)", file=sys.stderr)
            return EXIT_USAGE
        overlay = {only: sys.stdin.buffer.read(settings.max_file_size + 1)}
    outcome = run(paths, settings, baseline=baseline, overlay=overlay, only=only)
    if (args.fix or args.diff) and not outcome.unreadable:
        if overlay is not None:
            print("val3check: error: --fix and --diff edit files: not with --stdin-filename", file=sys.stderr)
            return EXIT_USAGE
        from .fixes import plan
        from .lint import display_path

        fixes = plan(outcome.findings)
        if args.diff:
            if not _write(fixes.diff(display_path), args.output):
                return EXIT_USAGE
            if not args.quiet:
                print(f"val3check: {fixes.count} fix{'es' if fixes.count != 1 else ''} would be made"
                      f" in {len(fixes.edits)} file{'s' if len(fixes.edits) != 1 else ''}", file=sys.stderr)
            return EXIT_FINDINGS if fixes.count else EXIT_OK
        try:
            fixes.write()
        except OSError as exc:
            print(f"val3check: error: cannot write a fixed file: {exc}", file=sys.stderr)
            return EXIT_USAGE
        if fixes.count:
            outcome = run(paths, settings, baseline=baseline)
        if not args.quiet:
            print(f"val3check: fixed {fixes.count} finding{'s' if fixes.count != 1 else ''}"
                  f" in {len(fixes.edits)} file{'s' if len(fixes.edits) != 1 else ''}", file=sys.stderr)
            for d, why in fixes.not_fixed:
                print(f"val3check: not fixed: {display_path(d.path)}:{d.line}: {d.code}: {why}", file=sys.stderr)
    code = exit_code(outcome, settings.fail_on)
    if args.exit_zero and code == EXIT_FINDINGS:
        code = EXIT_OK
    color = _use_color(args.color, args.output is not None)
    text = render(args.format, outcome.result, color=color, statistics=args.statistics, quiet=args.quiet,
                  exit_code=code)
    if not _write(text, args.output):
        return EXIT_USAGE
    if outcome.nothing_to_check and not args.quiet:
        print("val3check: nothing to check: the paths given are excluded (exclude, extend-exclude, --force-exclude)",
              file=sys.stderr)
    return code


def _update_baseline(paths: list[str], settings, baseline_path: str, quiet: bool) -> int:  # noqa: ANN001
    from .baseline import Baseline, BaselineError
    from .lint import display_path, run

    if not baseline_path:
        print("val3check: error: --update-baseline needs --baseline FILE (or `baseline` in the configuration)",
              file=sys.stderr)
        return EXIT_USAGE
    outcome = run(paths, settings)
    if outcome.unreadable:
        from .reporting import render

        sys.stdout.write(render("text", outcome.result))
        print("val3check: error: the baseline was not written: the input could not be read", file=sys.stderr)
        return EXIT_USAGE
    try:
        Baseline.of(baseline_path, outcome.findings).write()
    except BaselineError as exc:
        print(f"val3check: error: {_shown(str(exc))}", file=sys.stderr)
        return EXIT_USAGE
    if not quiet:
        n = len(outcome.findings)
        print(f"val3check: recorded {n} finding{'s' if n != 1 else ''} in {display_path(baseline_path)}", file=sys.stderr)
    return EXIT_OK


def _reach(args: argparse.Namespace) -> int:
    """`val3check reach`: no run; 1 when a finding is at or above --fail-on (as lint)."""
    from .loading import LoadOptions, load
    from .robot import RobotError, choose_robot
    from .simulation.requirements import install_hint, missing_sim_packages

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
    from .motion.reach import check_reach
    from .reporting.reach import render_json, render_text

    try:
        report = check_reach(ws, apps[0], model)
    except RobotError as exc:  # no closed-form inverse kinematics for this arm
        print(f"val3check reach: {exc}", file=sys.stderr)
        return EXIT_USAGE
    text = render_json(report) if args.format == "json" else render_text(report)
    if not _write(text, args.output):
        return EXIT_USAGE
    if args.fail_on == "never":
        return EXIT_OK
    rank = {"info": 1, "warning": 2, "error": 3}
    return EXIT_FINDINGS if any(rank[e.severity] >= rank[args.fail_on] for e in report.problems()) else EXIT_OK


def _robots(args: argparse.Namespace) -> int:
    """`val3check robots`: the catalogue, or one model in detail (val3check/robot); `robots fit`."""
    from .robot import RobotError, load_robot, names
    from .robot.listing import render_detail, render_list
    from .robot.catalog import known_without_model

    if args.robot[:1] == ["fit"]:
        from .simulation.fit import command

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
        print(f"val3check: error: {_shown(str(exc))}", file=sys.stderr)
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


def _server() -> int:
    from .lsp import missing_packages

    missing = missing_packages()
    if missing:
        print(f"val3check: error: `val3check server` needs the lsp extra: pip install 'val3check[lsp]'"
              f" (missing: {', '.join(missing)})", file=sys.stderr)
        return EXIT_USAGE
    from .lsp.server import main as serve

    return serve()  # 0 after shutdown and exit, 1 otherwise (LSP's `exit`)


def _rules(args: argparse.Namespace) -> int:
    from .reporting.rules import listing_json, listing_text
    from .rules.catalogue import catalogue

    rules = catalogue()
    sys.stdout.write(listing_json(rules) if args.format == "json" else listing_text(rules))
    return EXIT_OK


def _rule(args: argparse.Namespace) -> int:
    from .reporting.rules import explain_json, explain_text
    from .rules.catalogue import catalogue

    rules = catalogue()
    if args.all == bool(args.code):
        print("val3check: error: name one rule (`val3check rule F101`) or give --all", file=sys.stderr)
        return EXIT_USAGE
    if args.all:
        chosen = list(rules.values())
    else:
        rule = rules.get(args.code.strip().upper())
        if rule is None:
            print(f"val3check: error: no rule {args.code!r} (see `val3check rules`)", file=sys.stderr)
            return EXIT_USAGE
        chosen = [rule]
    if args.format == "json":
        sys.stdout.write(explain_json(chosen, single=not args.all))
    else:
        sys.stdout.write("\n".join(explain_text(r) for r in chosen))
    return EXIT_OK
