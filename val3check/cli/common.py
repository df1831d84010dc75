"""What the commands share: exit codes, the configuration, writing a report, paths shown."""

from __future__ import annotations

import argparse
import os
import sys

EXIT_OK, EXIT_FINDINGS, EXIT_USAGE = 0, 1, 2
MAX_DURATION = 1e7  # seconds (about 115 days): --duration inf or nan is a usage error


def targets(paths: list[str]) -> list[str]:
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


def settings_of(args: argparse.Namespace, first_path: str, quiet: bool = False):
    from ..config import ConfigError, Settings, find_config, load_settings

    try:
        settings = Settings()
        if args.config:
            if not os.path.lexists(args.config):
                raise ConfigError(f"{args.config}: configuration file not found")
            settings = load_settings(args.config)
        elif not args.isolated:
            found = find_config(first_path, warn=None if quiet else
                                lambda m: print(f"val3check: warning: {shown(m)}", file=sys.stderr))
            if found:
                settings = load_settings(found)
    except ConfigError as exc:
        print(f"val3check: error: {shown(str(exc))}", file=sys.stderr)
        return None
    return settings


def write(text, output: str | None) -> bool:
    # `text`: a str, or its pieces (a report written as it is made, reporting/sim_render.py).
    # Reports are UTF-8; a character that cannot be encoded (a lone surrogate from a file name
    # that is not UTF-8) is escaped rather than ending the run with UnicodeEncodeError.
    pieces = [text] if isinstance(text, str) else text
    if output is None:
        for piece in pieces:
            try:
                sys.stdout.write(piece)
            except UnicodeEncodeError:
                enc = sys.stdout.encoding or "utf-8"
                sys.stdout.write(piece.encode(enc, "backslashreplace").decode(enc))
        sys.stdout.flush()
        return True
    try:
        fh = open(output, "w", encoding="utf-8", errors="backslashreplace", newline="\n")
    except (OSError, ValueError) as exc:  # ValueError: a path with a NUL
        return _cannot_write(output, exc)
    try:
        for piece in pieces:  # a fault while making a piece is not a write error: it propagates
            _put(fh.write, piece)
        _put(fh.close)  # the last buffer is written here
    except BaseException as exc:
        _discard(fh)  # no half report left behind as if it were whole
        if isinstance(exc, _WriteFailed):
            return _cannot_write(output, exc.args[0])
        raise
    return True


class _WriteFailed(Exception):
    pass


def _put(call, *args) -> None:
    try:
        call(*args)
    except OSError as exc:
        raise _WriteFailed(exc) from None


def _cannot_write(output: str, exc: Exception) -> bool:
    print(f"val3check: error: cannot write {shown(output)}: {getattr(exc, 'strerror', None) or exc}", file=sys.stderr)
    return False


def _discard(fh) -> None:
    # closed without its last buffer; only a regular file is removed (-o /dev/null, a pipe stay)
    try:
        fh.close()
    except OSError:
        pass
    try:
        if os.path.isfile(fh.name):
            os.unlink(fh.name)
    except OSError:
        pass


def shown(path: str) -> str:
    from ..lint import printable_path

    return printable_path(path)


def use_color(choice: str, to_file: bool) -> bool:
    """--color always/never wins; then NO_COLOR (set and not empty) turns colour off and
    FORCE_COLOR (set and not empty) on; else colour on a terminal only."""
    if choice != "auto":
        return choice == "always"
    if to_file or os.environ.get("NO_COLOR"):
        return False
    if os.environ.get("FORCE_COLOR"):
        return True
    return sys.stdout.isatty()


