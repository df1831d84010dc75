"""`val3check lint`, `val3check rules`, `val3check rule CODE`: the checker's commands (README)."""

from __future__ import annotations

import argparse
import os
import sys

from .common import EXIT_FINDINGS, EXIT_OK, EXIT_USAGE, settings_of, shown, targets, use_color, write


def lint_settings(args: argparse.Namespace, paths: list[str]):  # noqa: ANN202
    """The configuration with the command line's options applied; None after a usage error."""
    settings = settings_of(args, paths[0], quiet=args.quiet)
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

    from ..rules.catalogue import catalogue

    bad = settings.unknown_codes(list(catalogue()))
    if bad:
        print(f"val3check: error: unknown rule code or prefix: {', '.join(bad)} (see `val3check rules`)", file=sys.stderr)
        return None
    return settings


def lint(args: argparse.Namespace) -> int:
    if "-" in (args.paths or []):  # ruff's spelling of standard input
        if not args.stdin_filename:
            print("val3check: error: `-` (standard input) needs --stdin-filename PATH, the file whose text is read"
                  " (its application is read from the disk)", file=sys.stderr)
            return EXIT_USAGE
        args.paths = [p for p in args.paths if p != "-"]
    if args.stdin_filename and not args.paths:
        args.paths = [args.stdin_filename]
    paths = targets(args.paths)
    settings = lint_settings(args, paths)
    if settings is None:
        return EXIT_USAGE
    if args.show_settings or args.show_files:
        from ..lint import discover
        from ..reporting.settings import render_files, render_settings
        from ..rules.catalogue import catalogue

        found = discover(paths, settings)
        if args.show_files:
            text = render_files(found)
        else:
            text = render_settings(settings, found, catalogue(), json_format=args.format == "json")
        return EXIT_OK if write(text, args.output) else EXIT_USAGE

    from ..lint import exit_code, run
    from ..reporting import render

    baseline_path = os.path.abspath(args.baseline) if args.baseline else settings.baseline
    if args.update_baseline:
        return update_baseline(paths, settings, baseline_path, args.quiet)
    baseline = None
    if baseline_path:
        from ..baseline import BaselineError, read_baseline

        try:
            baseline = read_baseline(baseline_path)
        except BaselineError as exc:
            print(f"val3check: error: {shown(str(exc))}", file=sys.stderr)
            return EXIT_USAGE
    overlay = only = None
    if args.stdin_filename:
        only = os.path.abspath(args.stdin_filename)
        if not os.path.isfile(only):
            print(f"val3check: error: --stdin-filename {shown(args.stdin_filename)}: no such file; the file must exist "
                  "(its application is read from the disk, its text from standard input)", file=sys.stderr)
            return EXIT_USAGE
        overlay = {only: sys.stdin.buffer.read(settings.max_file_size + 1)}
    outcome = run(paths, settings, baseline=baseline, overlay=overlay, only=only)
    if (args.fix or args.diff) and not outcome.unreadable:
        if overlay is not None:
            print("val3check: error: --fix and --diff edit files: not with --stdin-filename", file=sys.stderr)
            return EXIT_USAGE
        from ..fixes import plan
        from ..lint import display_path

        fixes = plan(outcome.findings)
        if args.diff:
            if not write(fixes.diff(display_path), args.output):
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
    color = use_color(args.color, args.output is not None)
    text = render(args.format, outcome.result, color=color, statistics=args.statistics, quiet=args.quiet,
                  exit_code=code)
    if not write(text, args.output):
        return EXIT_USAGE
    if outcome.nothing_to_check and not args.quiet:
        print("val3check: nothing to check: the paths given are excluded (exclude, extend-exclude, --force-exclude)",
              file=sys.stderr)
    return code


def update_baseline(paths: list[str], settings, baseline_path: str, quiet: bool) -> int:  # noqa: ANN001
    from ..baseline import Baseline, BaselineError
    from ..lint import display_path, run

    if not baseline_path:
        print("val3check: error: --update-baseline needs --baseline FILE (or `baseline` in the configuration)",
              file=sys.stderr)
        return EXIT_USAGE
    outcome = run(paths, settings)
    if outcome.unreadable:
        from ..reporting import render

        sys.stdout.write(render("text", outcome.result))
        print("val3check: error: the baseline was not written: the input could not be read", file=sys.stderr)
        return EXIT_USAGE
    try:
        Baseline.of(baseline_path, outcome.findings).write()
    except BaselineError as exc:
        print(f"val3check: error: {shown(str(exc))}", file=sys.stderr)
        return EXIT_USAGE
    if not quiet:
        n = len(outcome.findings)
        print(f"val3check: recorded {n} finding{'s' if n != 1 else ''} in {display_path(baseline_path)}", file=sys.stderr)
    return EXIT_OK


def rules(args: argparse.Namespace) -> int:
    from ..reporting.rules import listing_json, listing_text
    from ..rules.catalogue import catalogue

    rules = catalogue()
    sys.stdout.write(listing_json(rules) if args.format == "json" else listing_text(rules))
    return EXIT_OK


def rule(args: argparse.Namespace) -> int:
    from ..reporting.rules import explain_json, explain_text
    from ..rules.catalogue import catalogue

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

