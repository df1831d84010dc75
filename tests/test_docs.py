"""Every example of README.md and docs/*.md is executed (issue 16 item 1).

Each fenced block says how it is checked with a comment on the line before it:

    <!-- doc-check: KIND ARGUMENTS -->

| kind | the block | what is checked |
|---|---|---|
| `commands` (default for `sh`) | command lines | each runs in a sandbox (an application `MyCell`, a controller tree, `prog.pgx`, a scenario `cell.toml`, copies of `fixtures/valid/Cell`, `fixtures/valid/PickPlace` and its scenario, its own `.git`): exit code 0 or 1, never a usage error; `[optional parts]` are left out and their options checked; `pip install` names existing extras; a `python script.py` or `python -m module` that would run for minutes is only asked for `--help`, which must list its options |
| `help` | command lines | as `commands`, but no line is run: options are checked against `--help` / the parser |
| `usage SUBCOMMAND` | a usage synopsis | every option it shows is an option of `val3check SUBCOMMAND` |
| `config` | TOML | a valid configuration (`val3check.toml`, or `pyproject.toml` for `[tool.val3check]`) naming only existing rules |
| `scenario` | TOML | runs with `val3check sim` on an application declaring every signal it names |
| `cell` | TOML | read by `val3check.collision.read_cell` (its mesh files made) |
| `sweep` | TOML | a valid sweep file (`val3check.batch.sweep.load_sweep`, docs/batch.md) |
| `output ARGS` | text | exactly what `val3check ARGS` prints in a copy of `docs/examples` (its own repository) |
| `json-keys sim` / `json-keys html-model` | a JSON outline | its keys are those of a real sim JSON report / of the HTML report model's schema |
| `python-api NAME=module[:Class] ...` | Python | its imports run; every `NAME.attr` it uses exists |
| `python-protocol module:Class` | Python | a class whose members all exist on the real class |
| `precommit` | YAML | a pre-commit configuration of the hook of `.pre-commit-hooks.yaml`, `rev` a revision every clone has (`HEAD`) |
| `suppression` | a VAL 3 comment | suppresses its code on the next line |
| `problem-matcher` | a VS Code tasks.json | its regular expression reads every line of real concise output |
| `json` | JSON | parses |
| `skip REASON` | anything | not run (another language: Lua, Emacs Lisp, JavaScript) |

Finally no example anywhere names a rule code that does not exist.
"""

from __future__ import annotations

import ast
import importlib
import inspect
import json
import os
import re
import shlex
import shutil
import subprocess
import sys
import tomllib
from dataclasses import dataclass
from pathlib import Path

import pytest

from val3check.rules.catalogue import catalogue
from val3check.testing import write_app

ROOT = Path(__file__).resolve().parent.parent
DOCS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
EXAMPLES = ROOT / "docs" / "examples"
_FENCE = re.compile(r"^```(\S*)\s*$")
_MARK = re.compile(r"^<!--\s*doc-check:\s*(\S+)\s*(.*?)\s*-->\s*$")
DEFAULT_KIND = {"sh": "commands"}


@dataclass
class Block:
    path: Path
    line: int
    lang: str
    kind: str
    args: str
    text: str

    @property
    def id(self) -> str:
        return f"{self.path.relative_to(ROOT)}:{self.line}"


def blocks() -> list[Block]:
    out = []
    for path in DOCS:
        lines = path.read_text(encoding="utf-8").split("\n")
        i = 0
        while i < len(lines):
            m = _FENCE.match(lines[i])
            if not m:
                i += 1
                continue
            j = i + 1
            while j < len(lines) and not lines[j].startswith("```"):
                j += 1
            mark = _MARK.match(lines[i - 1]) if i else None
            kind, args = (mark.group(1), mark.group(2)) if mark else (DEFAULT_KIND.get(m.group(1), ""), "")
            out.append(Block(path, i + 1, m.group(1), kind, args, "\n".join(lines[i + 1:j]) + "\n"))
            i = j + 1
    return out


BLOCKS = blocks()


def test_every_block_says_how_it_is_checked():
    unmarked = [b.id for b in BLOCKS if not b.kind]
    assert unmarked == [], "add <!-- doc-check: KIND --> before these blocks (tests/test_docs.py lists the kinds)"


def test_no_example_names_a_rule_that_does_not_exist():
    known = set(catalogue())
    bad = []
    for b in BLOCKS:
        for n, line in enumerate(b.text.split("\n"), 1):
            for code in re.findall(r"(?<![A-Za-z0-9_%])([FNTLSR]\d{3})(?![0-9])", line):
                if code not in known:
                    bad.append(f"{b.id}+{n}: {code}")
    assert bad == []


def _val3check(args: list[str], cwd: Path, stdin=subprocess.DEVNULL, timeout: float = 300):  # noqa: ANN001
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    for k in ("NO_COLOR", "FORCE_COLOR"):
        env.pop(k, None)
    return subprocess.run([sys.executable, "-m", "val3check", *args], cwd=cwd, env=env, capture_output=True, text=True,
                          stdin=stdin, timeout=timeout)


# -- sandboxes ---------------------------------------------------------------------------------

def _sandbox(tmp: Path) -> Path:
    box = tmp / "box"
    box.mkdir()
    (box / ".git").mkdir()  # its own repository root
    write_app(box, 'begin\n  putln("hello")\n  nCount = nCount + 1\nend\n', name="MyCell", globals_=["num nCount"])
    shutil.copytree(ROOT / "fixtures" / "valid" / "controller", box / "controller")
    shutil.copytree(ROOT / "fixtures" / "valid" / "Cell", box / "fixtures" / "valid" / "Cell")
    shutil.copytree(ROOT / "fixtures" / "valid" / "PickPlace", box / "fixtures" / "valid" / "PickPlace")
    (box / "fixtures" / "scenarios").mkdir()
    shutil.copy(ROOT / "fixtures" / "scenarios" / "pickplace.toml", box / "fixtures" / "scenarios")
    (box / "prog.pgx").write_bytes((box / "MyCell" / "start.pgx").read_bytes())
    (box / "cell.toml").write_text('version = 1\ndescription = "the README\'s example"\n')
    return box


def _examples(tmp: Path) -> Path:
    box = tmp / "examples"
    shutil.copytree(EXAMPLES, box)
    (box / ".git").mkdir()
    return box


# -- commands ----------------------------------------------------------------------------------

def _strip_comment(line: str) -> str:
    out, quote = [], None
    for i, ch in enumerate(line):
        if quote:
            quote = None if ch == quote else quote
        elif ch in "'\"":
            quote = ch
        elif ch == "#" and (i == 0 or line[i - 1].isspace()):
            break
        out.append(ch)
    return "".join(out).strip()


def _options(text: str) -> list[str]:
    return re.findall(r"(?<![\w-])(--?[A-Za-z][\w-]*)", text)


def _subparser(name: str):  # noqa: ANN202
    from val3check.cli import build_parser

    parser = build_parser()
    sub = next(a for a in parser._actions if a.__class__.__name__ == "_SubParsersAction")  # noqa: SLF001
    return sub.choices[name]


def _check_val3check_options(words: list[str], where: str) -> None:
    command = next((w for w in words if not w.startswith("-")), None)
    if command is None:
        return
    known = set(_subparser(command)._option_string_actions)  # noqa: SLF001
    unknown = [o for o in _options(" ".join(words)) if o not in known and o != "--version"]
    assert not unknown, f"{where}: val3check {command} has no option {unknown}"


def _help_mentions(cmd: list[str], options: list[str], where: str) -> None:
    r = subprocess.run(cmd + ["--help"], cwd=ROOT, capture_output=True, text=True, timeout=120,
                       env=dict(os.environ, PYTHONPATH=str(ROOT)))
    assert r.returncode == 0, f"{where}: {' '.join(cmd)} --help failed: {r.stderr}"
    missing = [o for o in options if o not in r.stdout]
    assert not missing, f"{where}: {' '.join(cmd)} does not know {missing}"


def _pip(words: list[str], where: str) -> None:
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    extras = set(pyproject["project"]["optional-dependencies"])
    for w in words:
        for extra in re.findall(r"\[([\w,-]+)\]", w):
            assert set(extra.split(",")) <= extras, f"{where}: no extra {extra!r} in pyproject.toml"


def _run_line(line: str, box: Path, where: str, run: bool) -> None:
    for part in line.split("&&"):
        part = part.strip()
        optional = re.findall(r"\[(--[^\]]*)\]", part)
        bare = re.sub(r"\s*\[--[^\]]*\]", "", part)
        env_vars = re.findall(r"^((?:[A-Z_][A-Z0-9_]*=\S+\s+)+)", bare)
        if env_vars:
            bare = bare[len(env_vars[0]):]
            for name in re.findall(r"([A-Z_][A-Z0-9_]*)=", env_vars[0]):
                assert subprocess.run(["grep", "-rq", name, str(ROOT / "tests"), str(ROOT / "bench")]).returncode == 0, (
                    f"{where}: nothing reads {name}")
        words = shlex.split(bare)
        if not words:
            continue
        head = os.path.basename(words[0])
        if head in ("pip", "pip3") or words[:3] == [words[0], "-m", "pip"]:
            _pip(words, where)
            continue
        if head.startswith("python") and words[1:3] == ["-m", "venv"]:
            continue
        if head == "val3check":
            _check_val3check_options(words[1:] + [o for opt in optional for o in _options(opt)], where)
            if run:
                r = _val3check(words[1:], box)
                assert r.returncode in (0, 1), f"{where}: `{part}` exited {r.returncode}: {r.stdout[-800:]}{r.stderr[-800:]}"
            continue
        if head.startswith("python"):
            if words[1:3] == ["-m", "pytest"]:
                targets = [w for w in words[3:] if not w.startswith("-")]
                assert all((ROOT / t).exists() for t in targets), f"{where}: no {targets}"
                continue
            cmd = [sys.executable, *words[1:3]] if words[1] == "-m" else [sys.executable, str(ROOT / words[1])]
            rest = words[3:] if words[1] == "-m" else words[2:]
            if words[1] != "-m":
                assert (ROOT / words[1]).exists(), f"{where}: no {words[1]}"
            opts = _options(" ".join(rest + optional))
            _help_mentions(cmd, opts, where)
            if run and words[1] == "-m":
                env = dict(os.environ, PYTHONPATH=str(ROOT))
                r = subprocess.run(cmd + rest, cwd=box, capture_output=True, text=True, timeout=300, env=env)
                assert r.returncode in (0, 1), f"{where}: `{part}` exited {r.returncode}: {r.stderr[-800:]}"
            continue
        raise AssertionError(f"{where}: cannot check the command {part!r}")


def _commands(block: Block, tmp: Path, run: bool) -> None:
    box = _sandbox(tmp)
    for n, raw in enumerate(block.text.split("\n")):
        line = _strip_comment(raw)
        if line:
            _run_line(line, box, f"{block.id}+{n + 1}", run)


# -- the other kinds ---------------------------------------------------------------------------

def _config(block: Block, tmp: Path) -> None:
    from val3check.config import find_config, load_settings

    name = "pyproject.toml" if "[tool.val3check]" in block.text else "val3check.toml"
    (tmp / name).write_text(block.text, encoding="utf-8")
    settings = load_settings(find_config(str(tmp)))
    assert settings.unknown_codes(list(catalogue())) == []


def _scenario(block: Block, tmp: Path) -> None:
    data = tomllib.loads(block.text)
    names: set[str] = set(data.get("inputs", {}))
    for ev in data.get("events", []):
        names |= set(ev.get("set", {}))
    for r in data.get("reactions", []):
        names |= {r["when"]} | set(r.get("set", {}))
    names |= set(data.get("io", {}))
    names |= {p["when"] for p in data.get("pushes", []) if "when" in p}  # compliant moves (11.1)
    sios = {s["sio"] for s in data.get("serial", [])}
    rows, k = [], 0
    for name in sorted(names | sios):
        kind = "sio" if name in sios else "aio" if name.lower().startswith("a") else "dio"
        link = name if "\\" in name else f"BasicIO-9\\%X{k}"
        k += 1
        if "\\" in name:  # named by its link: a global linked there
            rows.append(f'    <Data name="dLink{k}" access="public" xsi:type="array" type="{kind}" size="1">'
                        f'<Value key="0" link="{link}" /></Data>')
            continue
        rows.append(f'    <Data name="{name}" access="public" xsi:type="array" type="{kind}" size="1">'
                    f'<Value key="0" link="{link}" /></Data>')
    from val3check.testing import database_xml

    folder = write_app(tmp, 'begin\n  putln("cell")\nend\n', name="App")
    (folder / "App.dtx").write_text(database_xml("\n".join(rows)), encoding="utf-8")
    (tmp / "scenario.toml").write_text(block.text, encoding="utf-8")
    r = _val3check(["sim", "App", "--duration", "1", "--robot", "tx2-60", "--scenario", "scenario.toml"], tmp)
    assert r.returncode in (0, 1), r.stderr


def _cell(block: Block, tmp: Path) -> None:
    from val3check.collision import read_cell

    for mesh in re.findall(r'file\s*=\s*"([^"]+)"', block.text):
        target = tmp / mesh
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text("solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                          "endloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 0 0 1\n"
                          "endloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 1 0 0\n"
                          "endloop\nendfacet\nfacet normal 1 1 1\nouter loop\nvertex 1 0 0\nvertex 0 0 1\nvertex 0 1 0\n"
                          "endloop\nendfacet\nendsolid t\n")
    (tmp / "cell.toml").write_text(block.text, encoding="utf-8")
    read_cell(str(tmp / "cell.toml"), app_dir=str(tmp), app_unit="mm")


def _output(block: Block, tmp: Path) -> None:
    box = _examples(tmp)
    r = _val3check(shlex.split(block.args), box)
    assert r.returncode in (0, 1), r.stderr
    assert r.stdout == block.text, f"{block.id}: `val3check {block.args}` prints:\n{r.stdout}"


def _outline(text: str) -> dict:
    text = re.sub(r"\[\s*\.\.\.\s*\]", "[]", text)
    text = re.sub(r"\{\s*\.\.\.\s*\}", "{}", text)
    return json.loads(text)


def _json_keys(block: Block, tmp: Path) -> None:
    outline = _outline(block.text)
    if block.args == "sim":
        folder = write_app(tmp, 'begin\n  putln("hi")\nend\n', name="Cell")
        r = _val3check(["sim", str(folder), "--duration", "1", "--robot", "tx2-60", "--report", "json"], tmp)
        real = json.loads(r.stdout)

        def same(a: dict, b: dict, where: str) -> None:
            assert set(a) == set(b), f"{block.id} {where}: the outline has {sorted(a)}, a report {sorted(b)}"
            for k, v in a.items():
                if isinstance(v, dict) and v and isinstance(b.get(k), dict):
                    same(v, b[k], f"{where}.{k}")

        same(outline, real, "")
    elif block.args == "html-model":
        schema = json.loads((ROOT / "docs" / "html-report.schema.json").read_text(encoding="utf-8"))
        props = schema["properties"]
        assert set(outline) <= set(props), set(outline) - set(props)
        assert set(schema.get("required", [])) <= set(outline)
    else:
        raise AssertionError(f"{block.id}: unknown json-keys {block.args!r}")


def _import_lines(text: str) -> list[str]:
    try:
        tree = ast.parse(text)
    except SyntaxError:
        out, lines, i = [], text.split("\n"), 0
        while i < len(lines):
            line = lines[i]
            if re.match(r"^(from|import)\s", line):
                stmt = line
                while stmt.count("(") > stmt.count(")") and i + 1 < len(lines):
                    i += 1
                    stmt += "\n" + lines[i]
                out.append(stmt)
            i += 1
        return out
    return [ast.unparse(n) for n in tree.body if isinstance(n, (ast.Import, ast.ImportFrom))]


def _resolve(spec: str):  # noqa: ANN202
    module, _, attr = spec.partition(":")
    obj = importlib.import_module(module)
    return getattr(obj, attr) if attr else obj


def _python_api(block: Block, tmp: Path) -> None:
    names: dict = {}
    for stmt in _import_lines(block.text):
        exec(stmt, names)  # noqa: S102 - the doc's own import lines
    for pair in block.args.split():
        var, spec = pair.split("=", 1)
        obj = _resolve(spec)
        used = set(re.findall(rf"(?<![\w.]){re.escape(var)}\.([A-Za-z_]\w*)", block.text))
        source = inspect.getsource(obj) if inspect.isclass(obj) else ""
        # a class's attributes include those its methods set (`self.findings = []`)
        fields = getattr(obj, "__dataclass_fields__", {})  # a dataclass's fields without default
        missing = sorted(a for a in used if not hasattr(obj, a) and a not in fields
                         and not re.search(rf"self\.{a}\b\s*[:=]", source))
        assert not missing, f"{block.id}: {spec} has no {missing}"


def _python_protocol(block: Block, tmp: Path) -> None:
    cls = _resolve(block.args)
    tree = ast.parse(block.text)
    (defined,) = [n for n in tree.body if isinstance(n, ast.ClassDef)]
    members = [n.name for n in defined.body if isinstance(n, ast.FunctionDef)]
    members += [n.target.id for n in defined.body if isinstance(n, ast.AnnAssign) and isinstance(n.target, ast.Name)]
    real = set(dir(cls)) | set(getattr(cls, "__annotations__", {}))
    assert [m for m in members if m not in real] == [], f"{block.id}: {block.args}"


def _precommit(block: Block, tmp: Path) -> None:
    import yaml

    config = yaml.safe_load(block.text)
    hooks = {h["id"]: h for h in yaml.safe_load((ROOT / ".pre-commit-hooks.yaml").read_text(encoding="utf-8"))}
    for repo in config["repos"]:
        for hook in repo["hooks"]:
            if repo["repo"] == "local":
                ours = hooks[hook["id"]]
                assert hook["entry"] == ours["entry"] and hook["files"] == ours["files"]
            else:
                assert hook["id"] in hooks
                # a revision every clone has: no tag (issue 28 item 5), pinned by `autoupdate --freeze`
                assert repo["rev"] == "HEAD", "the README's rev must exist in any clone"


def _suppression(block: Block, tmp: Path) -> None:
    from support import lint

    comment = block.text.strip()
    code = re.search(r"\[([A-Z]\d{3})\]", comment).group(1)
    assert code == "F101", "the example is checked with a syntax error"
    write_app(tmp, f"begin\n  {comment}\n  n = 1 +\nend\n")
    assert code not in [d.code for d in lint([tmp / "Example"], cwd=tmp).result.diagnostics]
    write_app(tmp, "begin\n  n = 1 +\nend\n")
    assert code in [d.code for d in lint([tmp / "Example"], cwd=tmp).result.diagnostics]


def _problem_matcher(block: Block, tmp: Path) -> None:
    tasks = json.loads(block.text)
    (task,) = tasks["tasks"]
    pattern = task["problemMatcher"]["pattern"]
    regexp = re.compile(pattern["regexp"])  # the subset of JavaScript regular expressions Python shares
    box = _examples(tmp)
    r = _val3check(shlex.split(task["command"])[1:] + ["Cell"], box)
    lines = r.stdout.rstrip("\n").split("\n")
    findings, summary = lines[:-2], lines[-1]
    assert lines[-2] == "" and summary.startswith("Found ")
    assert regexp.match(summary) is None
    by_code = {}
    for line in findings:
        m = regexp.match(line)
        assert m, f"the matcher misses {line!r}"
        by_code.setdefault(m.group(pattern["code"]), []).append(m)
    whole = by_code["F004"][0]
    assert whole.group(pattern["file"]) == "Cell/Apps/Pick/stop.pgx" and whole.group(pattern["line"]) is None
    f101 = by_code["F101"][0]
    assert (f101.group(pattern["file"]), f101.group(pattern["line"]), f101.group(pattern["column"])) == (
        "Cell/Apps/Pick/start.pgx", "10", "3")
    assert f101.group(pattern["severity"]) == "error"
    assert f101.group(pattern["message"]) == "'endWhile' without 'while'"
    assert {m.group(pattern["severity"]) for ms in by_code.values() for m in ms} == {"error", "warning"}


def _json(block: Block, tmp: Path) -> None:
    json.loads(block.text)


def _sweep(block: Block, tmp: Path) -> None:
    from val3check.batch.sweep import load_sweep

    (tmp / "sweep.toml").write_text(block.text, encoding="utf-8")
    load_sweep(str(tmp / "sweep.toml"))


CHECKS = {
    "sweep": _sweep,
    "commands": lambda b, t: _commands(b, t, run=True), "help": lambda b, t: _commands(b, t, run=False),
    "config": _config, "scenario": _scenario, "cell": _cell, "output": _output, "json-keys": _json_keys,
    "python-api": _python_api, "python-protocol": _python_protocol, "precommit": _precommit,
    "suppression": _suppression, "problem-matcher": _problem_matcher, "json": _json,
}


def _usage(block: Block, tmp: Path) -> None:
    known = set(_subparser(block.args)._option_string_actions)  # noqa: SLF001
    unknown = [o for o in _options(block.text) if o not in known]
    assert not unknown, f"{block.id}: val3check {block.args} has no option {unknown}"


CHECKS["usage"] = _usage


@pytest.mark.parametrize("block", [b for b in BLOCKS if b.kind and b.kind != "skip"], ids=lambda b: b.id)
def test_example(block, tmp_path):
    check = CHECKS.get(block.kind)
    assert check is not None, f"{block.id}: unknown doc-check kind {block.kind!r}"
    check(block, tmp_path)


def test_skipped_blocks_say_why():
    assert all(b.args for b in BLOCKS if b.kind == "skip")


ARCHITECTURE = ROOT / "docs" / "architecture.md"


def _defines(module: str, name: str) -> bool:
    base = ROOT / "val3check" / Path(*module.split("."))
    path = base / "__init__.py" if base.is_dir() else base.with_suffix(".py")
    if not path.is_file():
        return False
    tree = ast.parse(path.read_text(encoding="utf-8"))
    return any(isinstance(n, ast.ClassDef) and n.name == name
               or isinstance(n, (ast.Assign, ast.AnnAssign)) and name in {t.id for t in
                   (n.targets if isinstance(n, ast.Assign) else [n.target]) if isinstance(t, ast.Name)}
               for n in tree.body)


def test_the_glossary_names_real_classes():
    """docs/architecture.md, "Words": every class it names (`package.module.Class`) exists."""
    text = ARCHITECTURE.read_text(encoding="utf-8")
    words = text[text.index("\n## Words\n"):text.index("\n## ", text.index("\n## Words\n") + 1)]
    named = re.findall(r"`([a-z_]+(?:\.[a-z_]+)+)\.([A-Z][A-Za-z]+)`", words)
    assert len(named) >= 40
    assert [f"{m}.{c}" for m, c in named if not _defines(m, c)] == []


def test_the_architecture_names_only_files_that_exist():
    """docs/architecture.md's map of the packages: every `file.py` and `folder/` it names exists."""
    files = {p.relative_to(ROOT).as_posix() for top in ("val3check", "tests") for p in (ROOT / top).rglob("*")}
    names = set(re.findall(r"`([a-z_0-9/]+(?:\.py|/))`", ARCHITECTURE.read_text(encoding="utf-8")))
    missing = [n for n in sorted(names) if not any(f == n.rstrip("/") or f.endswith("/" + n.rstrip("/")) for f in files)]
    assert missing == []
