"""Command line: `val3check lint`, `val3check sim`, `val3check reach`, `val3check robots`, `val3check rules`,
`val3check rule CODE`.

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


def build_parser() -> argparse.ArgumentParser:
    p = _Parser(prog="val3check", description="Check Stäubli VAL 3 applications.")
    p.add_argument("--version", action="version", version=f"val3check {__version__}")
    sub = p.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)

    lint = sub.add_parser("lint", help="check applications (.pjx, .pgx, folders, controller trees)")
    lint.add_argument("paths", nargs="*", metavar="PATH", help="files or folders (default: .)")
    lint.add_argument("--format", "--output-format", dest="format", choices=FORMATS, default="text")
    lint.add_argument("-o", "--output", metavar="FILE", help="write the report to FILE instead of standard output")
    lint.add_argument("--fail-on", choices=("error", "warning", "info", "never"), help="lowest severity that makes the exit code 1 (default: error)")
    lint.add_argument("--select", type=_codes, metavar="CODES", help="comma-separated codes or prefixes to enable (replaces the configured list)")
    lint.add_argument("--extend-select", type=_codes, metavar="CODES", help="codes or prefixes to enable in addition")
    lint.add_argument("--ignore", type=_codes, metavar="CODES", help="codes or prefixes to disable (added to the configured list)")
    lint.add_argument("--disk-root", action="append", default=[], metavar="DIR", help="folder where Disk:// libraries and types are also searched (repeatable)")
    lint.add_argument("--config", metavar="FILE", help="configuration file (default: val3check.toml or pyproject.toml found upwards)")
    lint.add_argument("--isolated", action="store_true", help="ignore every configuration file")
    lint.add_argument("--statistics", action="store_true", help="show counts per rule instead of each finding")
    lint.add_argument("--color", choices=("auto", "always", "never"), default="auto")

    sim = sub.add_parser("sim", help="run an application in the virtual controller (docs/sim.md)")
    sim.add_argument("app", metavar="APP", help="the application: its folder or .pjx")
    sim.add_argument("--duration", type=float, default=60.0, metavar="S", help="simulated seconds to run at most (default: 60)")
    sim.add_argument("--cycles", type=int, metavar="N", help="end the run when the arm starts its cycle N + 1 (the loop of the task that moves it; docs/motion.md)")
    sim.add_argument("--report", choices=SIM_FORMATS, default="text", help="report format (default: text)")
    sim.add_argument("-o", "--output", metavar="FILE", help="write the report to FILE instead of standard output")
    sim.add_argument("--scenario", metavar="FILE", help="I/O scenario (TOML, docs/scenario.md)")
    sim.add_argument("--max-wall", type=float, default=60.0, metavar="S", help="wall-clock budget in seconds (default: 60)")
    sim.add_argument("--max-lines", type=int, default=50_000_000, metavar="N", help="budget of executed VAL 3 lines")
    sim.add_argument("--max-memory", type=float, default=512.0, metavar="MB",
                     help="memory budget in MB, loading included (default: 512)")
    sim.add_argument("--fail-on", choices=("error", "warning", "info", "never"), help="lowest runtime diagnostic severity that makes the exit code 1 (default: error)")
    sim.add_argument("--disk-root", action="append", default=[], metavar="DIR", help="folder where Disk:// libraries are also searched (repeatable)")
    sim.add_argument("--robot", metavar="NAME|URDF", help="the arm model: a catalogue name (case-insensitive, `val3check robots`), a URDF, an arm.cfx, or none (default: the usr/configs/arm.cfx of the controller tree holding APP, else none)")
    sim.add_argument("--config", metavar="FILE", help="configuration file (default: val3check.toml or pyproject.toml found upwards)")
    sim.add_argument("--isolated", action="store_true", help="ignore every configuration file")

    reach = sub.add_parser("reach", help="check that the arm reaches every point and joint of the data files (docs/motion.md)")
    reach.add_argument("app", metavar="APP", help="the application: its folder or .pjx")
    reach.add_argument("--robot", metavar="NAME|URDF", help="the arm model (default: the usr/configs/arm.cfx of the controller tree holding APP)")
    reach.add_argument("--format", choices=("text", "json"), default="text")
    reach.add_argument("-o", "--output", metavar="FILE", help="write the report to FILE instead of standard output")
    reach.add_argument("--disk-root", action="append", default=[], metavar="DIR", help="folder where Disk:// libraries are also searched (repeatable)")
    reach.add_argument("--fail-on", choices=("error", "warning", "info", "never"), default="error", help="lowest finding severity that makes the exit code 1 (default: error; reach findings are warnings and infos, docs/motion.md)")

    robots = sub.add_parser("robots", help="list the arm models by family (reach, joint limits, speeds, assumptions) or show one")
    robots.add_argument("robot", nargs="?", metavar="ROBOT",
                        help="an arm name (case-insensitive: tx2-60, TX2_60, ts60-L200…), a URDF, an arm.cfx or a robot file "
                             "(.toml): show that model, its facts and assumptions")
    robots.add_argument("--robot", dest="robot_opt", metavar="ROBOT", help="same as ROBOT")
    robots.add_argument("--app", metavar="PATH", help="show the arm chosen from the controller tree holding PATH (usr/configs/arm.cfx)")
    robots.add_argument("--format", choices=("text", "json"), default="text")

    rules = sub.add_parser("rules", help="list the rule catalogue")
    rules.add_argument("--format", choices=("text", "json"), default="text")
    rule = sub.add_parser("rule", help="explain one rule")
    rule.add_argument("code", metavar="CODE")
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


def _settings(args: argparse.Namespace, first_path: str):
    from .config import ConfigError, Settings, find_config, load_settings

    try:
        settings = Settings()
        if args.config:
            if not os.path.lexists(args.config):
                raise ConfigError(f"{args.config}: configuration file not found")
            settings = load_settings(args.config)
        elif not args.isolated:
            found = find_config(first_path, warn=lambda m: print(f"val3check: warning: {_shown(m)}", file=sys.stderr))
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
    settings = _settings(args, args.app)
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

    missing = missing_sim_packages()
    if missing:
        print(f"val3check: error: {install_hint(missing)}", file=sys.stderr)
        return EXIT_USAGE

    from .diagnostics import Severity
    from .lint import run
    from .reporting import render

    outcome = run([args.app], settings)
    apps = [outcome.workspace.apps[k] for k in outcome.workspace.targets]
    if outcome.unreadable or not apps:
        sys.stdout.write(render("text", outcome.result))
        print(f"val3check sim: error: no application could be read at {_shown(args.app)}", file=sys.stderr)
        return EXIT_USAGE
    if len(apps) != 1:
        print(f"val3check sim: error: {_shown(args.app)} holds {len(apps)} applications; name one of them",
              file=sys.stderr)
        return EXIT_USAGE
    errors = [d for d in outcome.result.diagnostics if d.severity is not None and d.severity >= Severity.ERROR]
    if errors:
        from .result import LintResult

        r = outcome.result  # only the errors that keep it from running, not every warning
        sys.stderr.write(render("text", LintResult(errors, r.files, r.applications, r.rules, r.tool_version,
                                                   r.quotable)))
        print(f"val3check sim: not run: the application has {len(errors)} error(s) (val3check lint); fix them first",
              file=sys.stderr)
        return EXIT_USAGE
    app = apps[0]
    if not any(n.lower() == "start" for n in app.programs):
        print(f"val3check sim: not run: {app.name} has no start() program (2.1.2)", file=sys.stderr)
        return EXIT_USAGE

    from .simulation.scenario import ScenarioError, load_scenario
    from .reporting.sim_report import build_report
    from .robot import RobotError
    from .rules.catalogue import catalogue
    from .simulation import SimOptions, choose_sim_robot, simulate

    try:
        robot, note = choose_sim_robot(args.robot, app.path)
    except RobotError as exc:
        print(f"val3check sim: --robot: {_shown(str(exc))}", file=sys.stderr)
        return EXIT_USAGE
    if note:
        print(f"val3check sim: note: {_shown(note)}", file=sys.stderr)
    scenario = None
    try:
        if args.scenario:
            scenario = load_scenario(args.scenario)
        options = SimOptions(duration=args.duration, max_wall=args.max_wall, max_lines=args.max_lines,
                             max_memory_mb=args.max_memory, disk_roots=list(settings.disk_roots), robot=robot,
                             cycles=args.cycles)
        result = simulate(outcome.workspace, app, options, scenario)
    except ScenarioError as exc:
        print(f"val3check sim: bad scenario: {_shown(str(exc))}", file=sys.stderr)
        return EXIT_USAGE
    report = build_report(result, settings, catalogue(), __version__)
    if args.report == "json":
        from .reporting.sim_json import render as render_sim
    else:
        from .reporting.sim_text import render as render_sim
    if not _write(render_sim(report), args.output):
        return EXIT_USAGE
    if settings.fail_on == "never":
        return EXIT_OK
    threshold = Severity.parse(settings.fail_on)
    return EXIT_FINDINGS if any(d.severity >= threshold for d in report.diagnostics) else EXIT_OK


def _lint(args: argparse.Namespace) -> int:
    paths = _targets(args.paths)
    settings = _settings(args, paths[0])
    if settings is None:
        return EXIT_USAGE
    if args.select is not None:
        settings.select = args.select
    if args.extend_select:
        settings.extend_select += args.extend_select
    if args.ignore:
        settings.ignore += args.ignore
    if args.fail_on:
        settings.fail_on = args.fail_on
    settings.disk_roots = [os.path.abspath(d) for d in args.disk_root] + settings.disk_roots

    from .rules.catalogue import catalogue

    bad = settings.unknown_codes(list(catalogue()))
    if bad:
        print(f"val3check: error: unknown rule code or prefix: {', '.join(bad)} (see `val3check rules`)", file=sys.stderr)
        return EXIT_USAGE

    from .lint import exit_code, run
    from .reporting import render

    outcome = run(paths, settings)
    to_file = args.output is not None
    color = args.color == "always" or (
        args.color == "auto" and not to_file and sys.stdout.isatty() and "NO_COLOR" not in os.environ
    )
    text = render(args.format, outcome.result, color=color, statistics=args.statistics)
    if not _write(text, args.output):
        return EXIT_USAGE
    return exit_code(outcome, settings.fail_on)


def _reach(args: argparse.Namespace) -> int:
    """`val3check reach`: no run; 1 when a finding is at or above --fail-on (as lint)."""
    from .loading import LoadOptions, load
    from .robot import RobotError, choose_robot

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
    """`val3check robots`: the catalogue, or one model in detail (val3check/robot)."""
    from .robot import RobotError, load_robot, names
    from .reporting.robot_text import render_detail, render_list
    from .robot.catalog import known_without_model

    args.robot = args.robot or args.robot_opt
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


def _rules(args: argparse.Namespace) -> int:
    from .rules.catalogue import FAMILIES, catalogue

    rules = catalogue()
    if args.format == "json":
        import json

        items = [
            {"code": r.code, "name": r.name, "family": r.family_name, "severity": r.severity.label, "manual": r.manual, "summary": r.summary}
            for r in rules.values()
        ]
        sys.stdout.write(json.dumps({"rules": items, "version": 1}, indent=2, sort_keys=True, ensure_ascii=False) + "\n")
        return EXIT_OK
    for letter, family in FAMILIES.items():
        members = [r for r in rules.values() if r.family == letter]
        if not members:
            continue
        print(f"{letter}  {family}")
        for r in members:
            manual = f"  (manual {r.manual})" if r.manual else ""
            print(f"  {r.code}  {r.severity.label:<7}  {r.name}: {r.summary}{manual}")
    return EXIT_OK


def _rule(args: argparse.Namespace) -> int:
    from .rules.catalogue import catalogue

    rules = catalogue()
    rule = rules.get(args.code.strip().upper())
    if rule is None:
        print(f"val3check: error: no rule {args.code!r} (see `val3check rules`)", file=sys.stderr)
        return EXIT_USAGE
    out = [f"{rule.code} {rule.name}", "", f"Family: {rule.family_name}", f"Default severity: {rule.severity.label}"]
    if rule.manual:
        out.append(f"Manual: section {rule.manual} (VAL 3 s7 reference manual)")
    out += ["", rule.summary, ""]
    if rule.explanation:
        out += [rule.explanation, ""]
    for title, examples in (("Fails", rule.bad), ("Passes", rule.good)):
        for ex in examples:
            out.append(f"{title}: {ex.description}" if ex.description else f"{title}:")
            body = ex.code if ex.code is not None else "\n".join(f"--- {name}\n{text}" for name, text in sorted(ex.files.items()))
            out += ["    " + line for line in body.rstrip("\n").split("\n")]
            out.append("")
    sys.stdout.write("\n".join(out).rstrip("\n") + "\n")
    return EXIT_OK
