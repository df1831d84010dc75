"""Command line: `val3check lint`, `val3check sim`, `val3check reach`, `val3check robots`, `val3check html`,
`val3check rules`, `val3check rule CODE`, `val3check server` (the language server).

Exit codes (README): 0 nothing at or above --fail-on; 1 findings; 2 usage error, bad
configuration, or input that could not be read at all. `sim` (docs/sim.md): 0 the run raised
no runtime diagnostic at or above --fail-on; 1 it did; 2 the application was not run (usage,
unreadable input, lint errors, bad scenario).

Here: the parser and the dispatch; the commands in `lint_command.py` (lint, rules, rule) and
`sim_command.py` (sim, reach, robots), `html_command.py` (html), what they share in `common.py`.
"""

from __future__ import annotations

import argparse
import gc
import os
import sys

from .. import __version__
from ..reporting import FORMATS, SIM_FORMATS
from . import html_command
from .common import EXIT_OK, EXIT_USAGE


def _terminal_columns() -> int:
    """shutil.get_terminal_size().columns without importing shutil (and bz2 and lzma with it):
    argparse asks for it at every option added, help printed or not."""
    try:
        columns = int(os.environ["COLUMNS"])
    except (KeyError, ValueError):
        columns = 0
    if columns <= 0:
        try:
            columns = os.get_terminal_size(sys.__stdout__.fileno()).columns
        except (AttributeError, ValueError, OSError):
            columns = 0
        columns = columns or 80
    return columns


class _Formatter(argparse.HelpFormatter):
    def __init__(self, prog: str, indent_increment: int = 2, max_help_position: int = 24, width: int | None = None):
        super().__init__(prog, indent_increment, max_help_position,
                         _terminal_columns() - 2 if width is None else width)


class _Parser(argparse.ArgumentParser):
    def __init__(self, *args, formatter_class: type = _Formatter, **kwargs) -> None:  # noqa: ANN002, ANN003
        super().__init__(*args, formatter_class=formatter_class, **kwargs)

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


COMMANDS = ("lint", "sim", "reach", "robots", "html", "server", "rules", "rule")


def build_parser(only: str | None = None) -> argparse.ArgumentParser:
    """The command line's parser; `only`: a command whose options alone are built (the others'
    cost about 5 ms at every start: `lint` in a pre-commit hook parses only its own)."""
    p = _Parser(prog="val3check", description="Check Stäubli VAL 3 applications.")
    p.add_argument("--version", action="version", version=f"val3check {__version__}")
    sub = p.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    if only is None or only == "lint":
        _add_lint(sub)
    if only is None or only == "sim":
        _add_sim(sub)
    if only is None or only == "reach":
        _add_reach(sub)
    if only is None or only == "robots":
        _add_robots(sub)
    if only is None or only == "html":
        html = sub.add_parser("html", help="the HTML report of a run's JSON report (--sim-report), or of a report model "
                              "saved as JSON (docs/html-report.md)")
        html_command.add_arguments(html)
    if only is None or only == "server":
        server = sub.add_parser("server", help="run the language server for editors, over stdio (docs/editors.md)")
        server.add_argument("--stdio", action="store_true", help="talk LSP over standard input and output (the default and only transport)")
    if only is None or only == "rules":
        rules = sub.add_parser("rules", help="list the rule catalogue")
        _add_format(rules, ("text", "json"))
    if only is None or only == "rule":
        rule = sub.add_parser("rule", help="explain one rule, or every rule with --all")
        rule.add_argument("code", nargs="?", metavar="CODE")
        rule.add_argument("--all", action="store_true", help="explain every rule")
        _add_format(rule, ("text", "json"))
    return p


def _add_lint(sub) -> None:  # noqa: ANN001
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


def _add_sim(sub) -> None:  # noqa: ANN001
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


def _add_reach(sub) -> None:  # noqa: ANN001
    reach = sub.add_parser("reach", help="check that the arm reaches every point and joint of the data files (docs/motion.md)")
    reach.add_argument("app", metavar="APP", help="the application: its folder or .pjx")
    reach.add_argument("--robot", metavar="NAME|URDF", help="the arm model (default: the usr/configs/arm.cfx of the controller tree holding APP)")
    _add_format(reach, ("text", "json"))
    reach.add_argument("-o", "--output", metavar="FILE", help="write the report to FILE instead of standard output")
    reach.add_argument("--disk-root", action="append", default=[], metavar="DIR", help="folder where Disk:// libraries are also searched (repeatable)")
    reach.add_argument("--fail-on", choices=("error", "warning", "info", "never"), default="error", help="lowest finding severity that makes the exit code 1 (default: error; reach findings are warnings and infos, docs/motion.md)")


def _add_robots(sub) -> None:  # noqa: ANN001
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


def main(argv: list[str] | None = None) -> int:
    """Run the command `argv` (default: this process's command line, as the `val3check` script
    and `python -m val3check` do). Only the command's own modules are imported: `lint` loads
    nothing of `sim`."""
    given = sys.argv[1:] if argv is None else argv
    args = build_parser(given[0] if given and given[0] in COMMANDS else None).parse_args(argv)
    batch = argv is None and args.command == "lint"
    if batch:
        _short_lived()
    try:
        if args.command in ("lint", "rules", "rule"):
            from . import lint_command

            commands = {"lint": lint_command.lint, "rules": lint_command.rules, "rule": lint_command.rule}
            return commands[args.command](args)
        if args.command in ("sim", "robots", "reach"):
            from . import sim_command

            args.own_process = argv is None  # sim_command.freeze_before_run

            commands = {"sim": sim_command.sim, "robots": sim_command.robots, "reach": sim_command.reach}
            return commands[args.command](args)
        if args.command == "html":
            from . import html_command

            return html_command.html(args)
        if args.command == "server":
            return _server()
    except BrokenPipeError:  # `val3check rules | head`
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return EXIT_OK
    finally:
        if batch:
            gc.freeze()  # the exit's final collection then skips the run's objects
    build_parser().print_help()
    return EXIT_USAGE


def _short_lived() -> None:
    """`val3check lint` as a process of its own: the cyclic garbage collector stays off to the
    end. The run builds objects that live until it ends (trees, symbols: some 140,000 that the
    collector tracks on a 20,000-line application); its passes would only walk them, mostly
    once the run is over (about a tenth of the process's CPU, docs/performance.md). What the
    process leaves is freed at exit. Never for the language server or `sim` (long-lived), nor when `main` is
    called with arguments (tests, other programs: their collector is theirs)."""
    gc.disable()


def _server() -> int:
    from ..lsp import missing_packages

    missing = missing_packages()
    if missing:
        print(f"val3check: error: `val3check server` needs the lsp extra: pip install 'val3check[lsp]'"
              f" (missing: {', '.join(missing)})", file=sys.stderr)
        return EXIT_USAGE
    from ..lsp.server import main as serve

    return serve()  # 0 after shutdown and exit, 1 otherwise (LSP's `exit`)


