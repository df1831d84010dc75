"""Every finding of `val3check lint` on the bundled inputs, written into one folder, so that a
speed-up of the parser or the checks can be held byte for byte against main (issue 29):

    python bench/lint_outputs.py /tmp/before      # on main
    python bench/lint_outputs.py /tmp/after       # on the branch
    python bench/lint_outputs.py --compare /tmp/before /tmp/after

What it writes, each in the text, JSON and SARIF formats:
- `val3check lint` as a process on each folder of fixtures/ (and fixtures/ itself), docs/examples,
  tests/robot and the generated application of bench/generate.py (exit code and standard error too);
- in process, every example of the rule catalogue (rules/*.toml, but the runtime R rules, which
  `sim` runs) and `--fuzz` programs (default 400) drawn from tests/hostile/fuzzing.py with
  hypothesis derandomized, so both sides lint the same programs (they are written out too).
Paths are relative to the folder linted, so two checkouts compare equal.
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))
sys.path.insert(0, str(ROOT / "tests"))
FORMATS = ("text", "json", "sarif")


def _targets() -> list[Path]:
    out = [ROOT / "fixtures", ROOT / "docs" / "examples", ROOT / "tests" / "robot"]
    for group in ("broken", "valid", "explore"):
        out += sorted(p for p in (ROOT / "fixtures" / group).iterdir() if p.is_dir())
    return out


def _cli(target: Path, cwd: Path, out: Path, name: str) -> None:
    env = {**os.environ, "NO_COLOR": "1", "COLUMNS": "100"}
    for fmt in FORMATS:
        r = subprocess.run([sys.executable, "-m", "val3check", "lint", "--format", fmt, str(target)], cwd=cwd,
                           capture_output=True, env=env, check=False)
        here = Path(cwd).resolve().as_uri().encode()  # SARIF's base: the checkout's or temporary folder
        (out / f"{name}.{fmt}").write_bytes(r.stdout.replace(here, b"file:///CWD") + b"\n--- stderr\n" + r.stderr
                                            + f"\n--- rc {r.returncode}\n".encode())


def _in_process(folder: Path, target: str, settings, out: Path, name: str) -> None:  # noqa: ANN001
    from val3check.lint import run
    from val3check.reporting import render

    old = os.getcwd()
    os.chdir(folder)  # rendered here too: SARIF resolves the paths shown against the current folder
    try:
        result = run([target], settings).result
        texts = {fmt: render(fmt, result).replace(folder.resolve().as_uri(), "file:///TMP") for fmt in FORMATS}
    finally:
        os.chdir(old)
    for fmt, text in texts.items():
        (out / f"{name}.{fmt}").write_text(text, encoding="utf-8")


def _catalogue(out: Path) -> int:
    import re

    from val3check.config import Settings, load_settings
    from val3check.rules.catalogue import catalogue
    from val3check.testing import write_app, write_files

    n = 0
    for rule in catalogue().values():
        if rule.family == "R":
            continue
        for kind, examples in (("bad", rule.bad), ("good", rule.good)):
            for i, ex in enumerate(examples):
                tmp = Path(tempfile.mkdtemp(prefix="val3lo"))
                try:
                    if ex.code is not None:
                        folder = write_app(tmp, ex.code, globals_=ex.globals, locals_=ex.locals,
                                           programs=ex.programs, version=ex.version)
                        target = str(folder.relative_to(tmp))
                    else:
                        files = {k: re.sub(rb"\\x([0-9A-Fa-f]{2})", lambda m: bytes([int(m.group(1), 16)]),
                                           v.encode()) if ex.byte_escapes else v for k, v in ex.files.items()}
                        write_files(tmp, files)
                        target = ex.target
                    settings = Settings()
                    if ex.config is not None:
                        (tmp / "val3check.toml").write_text(ex.config, encoding="utf-8")
                        settings = load_settings(str(tmp / "val3check.toml"))
                    if rule.opt_in:
                        settings.extend_select.append(rule.code)
                    _in_process(tmp, target, settings, out, f"rule-{rule.code}-{kind}{i}")
                    n += 1
                finally:
                    shutil.rmtree(tmp)
    return n


def _fuzz(out: Path, count: int) -> int:
    from hypothesis import Phase, given, settings
    from hostile.fuzzing import PROGRAM, SUB
    from hostile.test_hostile_fuzz import GLOBALS, LOCALS

    drawn: list[tuple[str, str]] = []

    @settings(max_examples=count, derandomize=True, database=None, phases=[Phase.generate], deadline=None)
    @given(PROGRAM, SUB)
    def draw(code: str, sub: str) -> None:
        drawn.append((code, sub))

    draw()
    from val3check.config import Settings
    from val3check.testing import write_app

    for i, (code, sub) in enumerate(drawn):
        tmp = Path(tempfile.mkdtemp(prefix="val3lo"))
        try:
            folder = write_app(tmp, code, globals_=GLOBALS, locals_=LOCALS,
                               programs={"sub": {"params": ["num& x_n"], "code": sub}})
            (out / f"fuzz-{i:04}.val3").write_text(code + "\n--- sub\n" + sub, encoding="utf-8")
            _in_process(tmp, str(folder.relative_to(tmp)), Settings(), out, f"fuzz-{i:04}")
        finally:
            shutil.rmtree(tmp)
    return len(drawn)


def generate_all(out: Path, fuzz: int) -> None:
    from generate import generate

    out = out.resolve()
    out.mkdir(parents=True, exist_ok=True)
    for t in _targets():
        _cli(t.relative_to(ROOT), ROOT, out, "cli-" + str(t.relative_to(ROOT)).replace("/", "_"))
    with tempfile.TemporaryDirectory() as tmp:
        app = Path(tmp) / "BigApp"
        generate(app)
        _cli(Path("BigApp"), Path(tmp), out, "cli-generated")
    print(f"{len(_targets()) + 1} folders", flush=True)
    print(f"{_catalogue(out)} catalogue examples", flush=True)
    print(f"{_fuzz(out, fuzz)} fuzz programs", flush=True)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--compare", action="store_true", help="compare two folders written by this script")
    ap.add_argument("--fuzz", type=int, default=400, help="how many generated programs (default 400)")
    ap.add_argument("folders", nargs="+", type=Path)
    a = ap.parse_args()
    if a.compare:
        from sim_outputs import compare

        return compare(*a.folders)
    generate_all(a.folders[0], a.fuzz)
    return 0


if __name__ == "__main__":
    sys.exit(main())
