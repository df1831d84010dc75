"""Command line: `val3check lint`, `val3check rules`, `val3check rule CODE`.

Exit codes (README): 0 nothing at or above --fail-on; 1 findings; 2 usage error, bad
configuration, or input that could not be read at all.
"""

from __future__ import annotations

import argparse
import os
import sys

from . import __version__

EXIT_OK, EXIT_FINDINGS, EXIT_USAGE = 0, 1, 2
FORMATS = ("text", "json", "sarif", "junit", "github")


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


def _lint(args: argparse.Namespace) -> int:
    from .config import ConfigError, Settings, find_config, load_settings

    paths = _targets(args.paths)
    try:
        settings = Settings()
        if args.config:
            if not os.path.isfile(args.config):
                raise ConfigError(f"{args.config}: configuration file not found")
            settings = load_settings(args.config)
        elif not args.isolated:
            found = find_config(paths[0])
            if found:
                settings = load_settings(found)
    except ConfigError as exc:
        print(f"val3check: error: {exc}", file=sys.stderr)
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
    if to_file:
        try:
            with open(args.output, "w", encoding="utf-8", newline="\n") as fh:
                fh.write(text)
        except OSError as exc:
            print(f"val3check: error: cannot write {args.output}: {exc.strerror or exc}", file=sys.stderr)
            return EXIT_USAGE
    else:
        sys.stdout.write(text)
        sys.stdout.flush()
    return exit_code(outcome, settings.fail_on)


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
