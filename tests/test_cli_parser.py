"""The command line's parser built for one command (cli.build_parser(only)) parses as the whole one."""

from __future__ import annotations

import argparse
import contextlib
import io

import pytest

from val3check.cli import COMMANDS, build_parser

ARGVS = [
    ["lint"], ["lint", "a", "b", "--format", "json", "--select", "F,T001", "--no-force-exclude", "--disk-root", "d"],
    ["lint", "--fix", "--diff", "-q", "--statistics", "--color", "never", "--exclude", "x,y"],
    ["sim", "app", "--robot", "tx2-60", "--duration", "5", "--report", "html", "-o", "r.html", "--sweep", "s.toml"],
    ["reach", "app", "--robot", "tx2-60"], ["robots", "fit", "app", "--measured-cycle", "2.5"],
    ["html", "--help"], ["server", "--stdio"], ["rules", "--format", "json"], ["rule", "F001"], ["rule", "--all"],
    ["lint", "--bogus"], ["sim", "--duration", "x"], ["lint", "--help"], ["sim", "--help"],
]


def _parse(parser: argparse.ArgumentParser, argv: list[str]) -> tuple:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            ns = vars(parser.parse_args(argv))
        except SystemExit as e:
            ns = {"exit": e.code}
    return ns, out.getvalue(), err.getvalue()


@pytest.mark.parametrize("argv", ARGVS, ids=lambda a: " ".join(a))
def test_the_parser_of_one_command_parses_as_the_whole_parser(argv, monkeypatch):
    monkeypatch.setenv("COLUMNS", "100")
    assert argv[0] in COMMANDS
    assert _parse(build_parser(argv[0]), argv) == _parse(build_parser(), argv)


def test_every_command_is_built_alone():
    whole = build_parser()
    sub = next(a for a in whole._actions if isinstance(a, argparse._SubParsersAction))
    assert tuple(sub.choices) == COMMANDS
    for name in COMMANDS:
        one = build_parser(name)
        sub = next(a for a in one._actions if isinstance(a, argparse._SubParsersAction))
        assert tuple(sub.choices) == (name,)
