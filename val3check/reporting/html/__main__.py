"""`python -m val3check.reporting.html MODEL.json -o report.html`, or `--demo` for a synthetic run.

For developers and integrators: renders a report model (docs/html-report.md) saved as JSON."""

from __future__ import annotations

import argparse
import json
import sys


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m val3check.reporting.html",
                                 description="Render a report model (docs/html-report.md) as a self-contained HTML page.")
    src = ap.add_mutually_exclusive_group(required=True)
    src.add_argument("model", nargs="?", help="the report model, a JSON file")
    src.add_argument("--demo", action="store_true", help="a synthetic pick-and-place run on a TX2-60")
    src.add_argument("--sim-report", metavar="RUN.json", help="the JSON report of `val3check sim --report json`")
    ap.add_argument("--fail-on", choices=("error", "warning", "info", "never"), default="error",
                    help="--sim-report: the lowest severity that fails the run (default: error)")
    ap.add_argument("--root", action="append", metavar="DIR",
                    help="--sim-report: a folder whose files the excerpts may quote (default: the application's)")
    ap.add_argument("--duration", type=float, default=60.0, help="--demo: simulated seconds (default 60)")
    ap.add_argument("--failing", action="store_true", help="--demo: the robot task stops on an error")
    ap.add_argument("--model-out", metavar="FILE", help="also write the model as JSON")
    ap.add_argument("-o", "--output", required=True, metavar="FILE", help="the HTML file to write")
    args = ap.parse_args(argv)

    from . import ModelError, render, synthetic_model

    source = args.model or args.sim_report or "demo"
    try:
        if args.demo:
            if not 0 < args.duration <= 3600:
                print("--duration: between 0 and 3600 seconds", file=sys.stderr)
                return 2
            model = synthetic_model(duration=args.duration, failing=args.failing)
        else:
            try:
                with open(source, encoding="utf-8") as fh:
                    model = json.load(fh)
            except OSError as exc:
                print(f"{source}: cannot read: {exc.strerror or exc}", file=sys.stderr)
                return 2
            except ValueError as exc:
                print(f"{source}: not JSON: {exc}", file=sys.stderr)
                return 2
            if args.sim_report:
                from ...robot import RobotError
                from .from_sim import model_from_sim_report

                try:
                    model = model_from_sim_report(model, fail_on=args.fail_on, roots=args.root)
                except RobotError as exc:
                    print(f"{source}: {exc}", file=sys.stderr)
                    return 2
        page = render(model)
    except ModelError as exc:
        print(f"{source}: {exc}", file=sys.stderr)
        return 2
    if args.model_out:
        with open(args.model_out, "w", encoding="utf-8") as fh:
            json.dump(model, fh, sort_keys=True, indent=1)
            fh.write("\n")
    with open(args.output, "w", encoding="utf-8", newline="\n") as fh:
        fh.write(page)
    return 0


if __name__ == "__main__":
    sys.exit(main())
