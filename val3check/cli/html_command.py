"""`val3check html MODEL.json -o report.html`, or `--sim-report RUN.json`: the HTML report
(docs/html-report.md) of a report model saved as JSON, or of the JSON report of a run, whose arm
and cell are rebuilt here (simulation/report_scene.py: the page writer reads plain data)."""

from __future__ import annotations

import argparse
import sys

MAX_MODEL_BYTES = 512 * 1024 * 1024  # a report model of a long run with its trajectories


def add_arguments(ap: argparse.ArgumentParser) -> None:
    """The command's arguments."""
    src = ap.add_mutually_exclusive_group(required=True)
    src.add_argument("model", nargs="?", help="the report model, a JSON file")
    src.add_argument("--sim-report", metavar="RUN.json", help="the JSON report of `val3check sim --report json`")
    ap.add_argument("--fail-on", choices=("error", "warning", "info", "never"), default="error",
                    help="--sim-report: the lowest severity that fails the run (default: error)")
    ap.add_argument("--root", action="append", metavar="DIR",
                    help="--sim-report: a folder whose files the excerpts may quote (default: the application's)")
    ap.add_argument("--model-out", metavar="FILE", help="also write the model as JSON")
    ap.add_argument("-o", "--output", required=True, metavar="FILE", help="the HTML file to write")


def html(args: argparse.Namespace) -> int:
    """Render the page; 2 (a message, never a traceback) for a file that is not a model or report."""
    import json  # here: `val3check lint` imports this module's parser options, not json

    from ..reporting.html import ModelError, render

    source = args.model or args.sim_report
    try:
        from ..confine import Refused, Roots, read_bytes

        try:
            model = json.loads(read_bytes(source, Roots.user_given(), MAX_MODEL_BYTES).decode("utf-8"))
        except Refused as exc:
            print(f"{source}: cannot read: {exc.reason}", file=sys.stderr)
            return 2
        except RecursionError:
            print(f"{source}: not a report: its arrays or objects are nested too deeply", file=sys.stderr)
            return 2
        except ValueError as exc:  # UnicodeDecodeError included
            print(f"{source}: not JSON: {str(exc)[:200]}", file=sys.stderr)
            return 2
        if args.sim_report:
            from ..reporting.html.from_sim import model_from_sim_report
            from ..robot import RobotError
            from ..simulation.report_scene import ReportScene

            try:
                model = model_from_sim_report(model, ReportScene(), fail_on=args.fail_on, roots=args.root)
            except RobotError as exc:
                print(f"{source}: {exc}", file=sys.stderr)
                return 2
        page = render(model)
    except ModelError as exc:
        print(f"{source}: {exc}", file=sys.stderr)
        return 2
    except RecursionError:  # a model that check_model let through, nested too deeply to render
        print(f"{source}: not a report: its values are nested too deeply", file=sys.stderr)
        return 2
    except (KeyError, IndexError, TypeError, AttributeError, ValueError) as exc:
        # check_model covers what the page needs, not every type of every key a hand-written
        # file may get wrong: such a file is refused, said so, never a traceback
        from ..excerpt import excerpt

        print(f"{source}: not a report model the page can show ({type(exc).__name__}: {excerpt(str(exc), 120)}); "
              "see docs/html-report.md and docs/html-report.schema.json", file=sys.stderr)
        return 2
    if args.model_out:
        from ..reporting.html.series import dump_json

        with open(args.model_out, "w", encoding="utf-8") as fh:
            dump_json(model, fh)  # as json.dump(sort_keys, indent=1), the series from their arrays
            fh.write("\n")
    with open(args.output, "w", encoding="utf-8", newline="\n") as fh:
        fh.write(page)
    return 0
