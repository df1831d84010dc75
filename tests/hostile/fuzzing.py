"""What the fuzz suite generates and what it checks (issue 9): shared by test_hostile_fuzz.py
(bounded, in CI) and bench/fuzz.py (the long run).

Every check runs one input through a phase of val3check in-process and asserts the promise:
the input ends cleanly -- a diagnostic or a result, never an exception, never an internal error
of the interpreter -- within its budgets, and no finding names or quotes a file outside the
folder the input was written to.
"""

from __future__ import annotations

import json
import math
import os
import re
import tempfile
from pathlib import Path

from hypothesis import strategies as st

ROOT = Path(__file__).resolve().parent.parent.parent
SEEDS = ROOT / "fixtures" / "valid"

# ---- seeds: real applications, file by file ------------------------------------------------------


def seed_apps() -> list[tuple[str, dict[str, bytes]]]:
    """Every application folder of fixtures/valid: (name, {file name: bytes})."""
    out = []
    for pjx in sorted(SEEDS.rglob("*.pjx")):
        folder = pjx.parent
        files = {p.name: p.read_bytes() for p in sorted(folder.iterdir()) if p.is_file()}
        out.append((folder.name, files))
    return out


SEED_APPS = seed_apps()

# Values a hostile or broken file writes where val3check expects something sensible.
HOSTILE_VALUES = [
    "", " ", "0", "-1", "99999999", "9999 9999", "1" * 30, "9" * 5000, "1e400", "-1e400", "nan", "inf",
    "1e-400", "0x10", "²", "٣", "1 2 3 4", "1,2", "\x00", "a\x07b", "x" * 20000, "fA[1e400]", "fA[", "world[0]",
    "Disk://../../../../../../etc/passwd", "/proc/self/environ", "../" * 12 + "etc/passwd", "/dev/zero",
    "Disk://", "USB0://x", "\\\\server\\share", "private", "reference", "collection", "array", "element",
    "true", "false", "lefty", "é" * 200, "<", "&amp;", "]]>", "{}", "'", '"',
]
HOSTILE_TOKENS = [
    b"<", b">", b"&", b"]]>", b"<![CDATA[", b'"', b"\xff", b"\x00", b"&#0;", b"&#x110000;", b"\r", b"xsi:",
    b"</Code>", b"<Code>", b' size="0"', b' size="99999999"', b' size="9999 9999"', b' fatherId="fA[1e400]"',
    b'<!DOCTYPE x [<!ENTITY e "e">]>', b"&e;", b'<!ENTITY % p SYSTEM "file:///etc/passwd">',
    b'<Library alias="z" path="Disk://../../../../etc/passwd" />', b'<Type name="Z" path="/proc/self/environ" />',
    b'<Program file="/etc/passwd" />', b'<Data file="../../../../etc/hostname" />', b"\xef\xbb\xbf", b"\xff\xfe",
    b"\n" * 50, b"1e999", b"9" * 400, b"begin", b"end", b"endIf", b"while true", b"call start()",
]


@st.composite
def mutated_app(draw) -> tuple[str, dict[str, bytes]]:
    """A real application with 1 to 4 mutations: truncation, a hostile token, a deleted or
    duplicated span, an attribute value replaced by a hostile one, random bytes."""
    name, files = draw(st.sampled_from(SEED_APPS))
    files = dict(files)
    for _ in range(draw(st.integers(1, 4))):
        victim = draw(st.sampled_from(sorted(files)))
        data = bytearray(files[victim])
        pos = draw(st.integers(0, len(data)))
        op = draw(st.integers(0, 5))
        if op == 0:
            data = data[:pos]
        elif op == 1:
            data[pos:pos] = draw(st.sampled_from(HOSTILE_TOKENS))
        elif op == 2:
            del data[pos:pos + draw(st.integers(1, 40))]
        elif op == 3:
            span = data[pos:pos + draw(st.integers(1, 200))]
            data[pos:pos] = span * draw(st.integers(1, 20))
        elif op == 4:
            text = bytes(data)
            quotes = [i for i in range(len(text)) if text[i] == 0x22]
            if len(quotes) >= 2:
                k = draw(st.integers(0, len(quotes) - 2))
                a, b = quotes[k], quotes[k + 1]
                value = draw(st.sampled_from(HOSTILE_VALUES)).encode("utf-8", "surrogatepass")
                data[a + 1:b] = value.replace(b'"', b"&quot;")
        else:
            data = bytearray(draw(st.binary(max_size=300)))
        files[victim] = bytes(data)
    return name, files


# ---- VAL 3 programs -------------------------------------------------------------------------------

NUM_VARS = ["nX", "nY", "nI", "l_n"]
STR_VARS = ["sX", "l_s"]
GLOBALS = ["num nX", "num nY", "num nI", "string sX", "bool bX", "num nArr[5]", "string sColl[\"\"]", "dio diX",
           "aio aiX", "pointRx pP", "frame fF", "trsf trT", "joint jJ", "tool tT"]
LOCALS = ["num l_n", "string l_s", "num l_a[3]"]

_num_atom = st.one_of(
    st.sampled_from(NUM_VARS + ["nArr[0]", "nArr[nI]", "nArr[-1]", "nArr[7]", "size(nArr)", "pP.trsf.x", "jJ.j1",
                                "len(sX)", "asc(sX, 0)", "toNum(sX, nY, bX)", "getMonoClock()", "aiX"]),
    st.sampled_from(["0", "1", "-1", "0.5", "1e308", "1e-308", "4.9e-324", "12345678901234567890", "1e15", "360"]),
    st.integers(-10**6, 10**6).map(str),
)
_str_atom = st.one_of(
    st.sampled_from(STR_VARS + ['""', '"abc"', '"' + "é" * 70 + '"', 'chr(0)', 'chr(65)', 'sColl["k"]',
                                'toString("", nX)', 'left(sX, nY)', 'mid(sX, nX, nY)', 'right(sX, -1)',
                                'sX + sX', 'replace(sX, nX, nY, "z")', 'toString("5.3", nX)']),
)


def _num_expr(depth: int):
    if depth <= 0:
        return _num_atom
    sub = _num_expr(depth - 1)
    return st.one_of(
        _num_atom,
        st.tuples(sub, st.sampled_from(["+", "-", "*", "/", "%"]), sub).map(lambda t: f"({t[0]} {t[1]} {t[2]})"),
        st.tuples(st.sampled_from(["sin", "cos", "tan", "asin", "acos", "atan", "abs", "sqrt", "exp", "ln", "log",
                                   "roundUp", "roundDown", "round", "sel"]), sub)
        .map(lambda t: f"{t[0]}({t[1]})" if t[0] != "sel" else f"sel(bX, {t[1]}, 1)"),
        st.tuples(st.sampled_from(["min", "max", "power", "limit"]), sub, sub)
        .map(lambda t: f"{t[0]}({t[1]}, {t[2]})" if t[0] != "limit" else f"limit({t[1]}, 0, {t[2]})"),
    )


NUM = _num_expr(2)
BOOL = st.one_of(
    st.sampled_from(["true", "false", "bX", "diX", "!bX", "isDefined(sColl[sX])", "bX and diX", "bX xor true"]),
    st.tuples(NUM, st.sampled_from(["<", "<=", "==", "!=", ">", ">="]), NUM).map(lambda t: f"{t[0]} {t[1]} {t[2]}"),
)


def _statements(depth: int):
    simple = st.one_of(
        st.tuples(st.sampled_from(NUM_VARS + ["nArr[nI]", "pP.trsf.x", "jJ.j3", "nArr[0]"]), NUM)
        .map(lambda t: f"{t[0]} = {t[1]}"),
        st.tuples(st.sampled_from(STR_VARS + ['sColl["k"]', "sColl[sX]"]), _str_atom).map(lambda t: f"{t[0]} = {t[1]}"),
        BOOL.map(lambda b: f"bX = {b}"),
        BOOL.map(lambda b: f"diX = {b}"),
        NUM.map(lambda n: f"delay({n})"),
        NUM.map(lambda n: f"aiX = {n}"),
        _str_atom.map(lambda s: f"putln({s})"),
        NUM.map(lambda n: f"put({n})"),
        st.sampled_from([
            "call sub(nX)", "call sub(nArr[nI])", "call start()", "return", "wait(bX)", "watch(bX, 0.1)",
            'taskCreate "t1", 10, sub(nY)', 'taskCreate "t1", nX, sub(nY)', 'taskKill("t1")', 'taskSuspend("t1")',
            'taskResume("t1", 0)', "resize(nArr, 1, nX)", 'insert(sColl["a"])', 'delete(sColl["a"])',
            "cls()", "userPage()", "l_a[l_n] = 1", "pP = compose(pP, fF, trT)", "trT = trT * trT",
            "jJ = herej()", "nX = getKey()", 'sX = toString("", nX)', "nX = size(l_a)", "nX = l_a[3]",
            "nY = nArr[nArr[nArr[0]]]",
        ]),
    )
    if depth <= 0:
        return simple
    block = st.lists(_statements(depth - 1), min_size=0, max_size=4).map(lambda xs: "\n".join(xs))
    return st.one_of(
        simple,
        st.tuples(BOOL, block, block).map(lambda t: f"if {t[0]}\n{t[1]}\nelse\n{t[2]}\nendIf"),
        st.tuples(NUM, NUM, NUM, block).map(lambda t: f"for nI = {t[0]} to {t[1]} step {t[2]}\n{t[3]}\nendFor"),
        st.tuples(BOOL, block).map(lambda t: f"while {t[0]}\n{t[1]}\nendWhile"),
        st.tuples(block, BOOL).map(lambda t: f"do\n{t[0]}\nuntil {t[1]}"),
        st.tuples(NUM, block, block).map(
            lambda t: f"switch {t[0]}\ncase 1, 2\n{t[1]}\nbreak\ndefault\n{t[2]}\nbreak\nendSwitch"),
    )


PROGRAM = st.lists(_statements(2), min_size=1, max_size=8).map(lambda xs: "begin\n" + "\n".join(xs) + "\nend\n")
SUB = st.lists(_statements(1), min_size=0, max_size=4).map(lambda xs: "begin\n" + "\n".join(xs) + "\nend\n")


# ---- configuration and scenario documents --------------------------------------------------------

def _toml_value(v) -> str:  # noqa: ANN001
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return "nan" if math.isnan(v) else ("inf" if v > 0 else "-inf") if math.isinf(v) else repr(v)
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{_key(k)} = {_toml_value(x)}" for k, x in v.items()) + "}"
    raise TypeError(v)


def _key(k: str) -> str:
    return k if k and all(c.isalnum() or c in "-_" for c in k) else _toml_value(k)


def toml_text(doc: dict) -> str:
    """A TOML document: top-level scalars first, then tables ([name]) and arrays of tables."""
    lines, tables = [], []
    for k, v in doc.items():
        if isinstance(v, dict):
            tables.append(f"[{_key(k)}]\n" + "".join(f"{_key(a)} = {_toml_value(b)}\n" for a, b in v.items()))
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            for x in v:
                tables.append(f"[[{_key(k)}]]\n" + "".join(f"{_key(a)} = {_toml_value(b)}\n" for a, b in x.items()))
        else:
            lines.append(f"{_key(k)} = {_toml_value(v)}\n")
    return "".join(lines) + "\n".join(tables)


SCALARS = st.one_of(
    st.booleans(), st.integers(-2**63, 2**63 - 1), st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from(HOSTILE_VALUES), st.text(max_size=20),
)
VALUES = st.recursive(SCALARS, lambda inner: st.one_of(st.lists(inner, max_size=4),
                                                       st.dictionaries(st.text(max_size=8), inner, max_size=4)),
                      max_leaves=12)

CONFIG_KEYS = ["select", "extend-select", "ignore", "per-file-ignores", "severity", "fail-on", "disk-roots",
               "exclude", "max-file-size", "tool", "unknown"]
CONFIG = st.dictionaries(st.sampled_from(CONFIG_KEYS), VALUES, max_size=5)

SIGNALS = ["diX", "doY", "aiX", "siX", "nX", "missing", "BasicIO-1\\%I0", "io:bIn0"]
SCENARIO_KEYS = ["version", "description", "inputs", "events", "reactions", "keys", "serial", "controller", "io",
                 "robot", "bogus"]
TIMES = st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-5, 10**12), st.sampled_from([0, 0.1, 1]))
_event = st.fixed_dictionaries({"at": TIMES}, optional={"set": st.dictionaries(st.sampled_from(SIGNALS), SCALARS,
                                                                                max_size=3)})
_reaction = st.fixed_dictionaries(
    {"when": st.sampled_from(SIGNALS)},
    optional={"becomes": SCALARS, "after": TIMES, "set": st.dictionaries(st.sampled_from(SIGNALS), SCALARS, max_size=2)})
_key_press = st.fixed_dictionaries({}, optional={"at": TIMES, "key": st.integers(-5, 2000), "text": SCALARS,
                                                 "hold": TIMES})
_serial = st.fixed_dictionaries({"sio": st.sampled_from(SIGNALS)},
                                optional={"at": TIMES, "send": SCALARS, "bytes": st.lists(st.integers(-1, 300)),
                                          "when_sent": SCALARS, "after": TIMES})
SCENARIO = st.fixed_dictionaries({}, optional={
    "version": st.one_of(st.just(1), SCALARS),
    "inputs": st.dictionaries(st.sampled_from(SIGNALS), SCALARS, max_size=4),
    "events": st.lists(_event, max_size=4),
    "reactions": st.lists(_reaction, max_size=3),
    "keys": st.lists(_key_press, max_size=3),
    "serial": st.lists(_serial, max_size=2),
    "controller": st.dictionaries(st.sampled_from(["working_mode", "powered", "power_delay", "monitor_speed", "date",
                                                   "changes", "profiles", "languages", "bogus"]), VALUES, max_size=4),
    "io": st.dictionaries(st.sampled_from(SIGNALS), VALUES, max_size=2),
    "robot": st.dictionaries(st.sampled_from(["joints", "bogus"]), VALUES, max_size=2),
    "bogus": VALUES,
})


# ---- the checks ---------------------------------------------------------------------------------------

def known_codes() -> set[str]:
    from val3check.rules.catalogue import catalogue

    return set(catalogue())


_KNOWN: set[str] | None = None


def check_lint_result(run, folder: Path) -> None:  # noqa: ANN001
    """Every finding has a known code, a position, and a path inside `folder`; every format renders."""
    global _KNOWN
    if _KNOWN is None:
        _KNOWN = known_codes()
    from val3check.reporting import FORMATS, render

    for d in run.result.diagnostics:
        assert d.code in _KNOWN, d
        assert d.line >= 0 and d.col >= 0, d
        assert os.path.realpath(os.path.abspath(d.path)).startswith(os.path.realpath(folder)), d
    for fmt in FORMATS:
        render(fmt, run.result)


def lint_files(files: dict[str, bytes], settings=None):  # noqa: ANN001
    """Write `files` (relative path -> bytes) in a fresh folder and lint it: (run, folder)."""
    from val3check.config import Settings
    from val3check.lint import run

    tmp = Path(tempfile.mkdtemp(prefix="val3fuzz"))
    (tmp / ".git").mkdir()  # the repository: nothing above it may be read
    for rel, data in files.items():
        p = tmp / rel
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_bytes(data)
    old = os.getcwd()
    os.chdir(tmp)
    try:
        result = run(["."], settings or Settings())
        check_lint_result(result, tmp)
    finally:
        os.chdir(old)
    return result, tmp


def check_sim(ws, app, *, scenario=None, duration: float = 1.0, max_wall: float = 2.0):  # noqa: ANN001
    """Run the application with small budgets: it ends (a result) without an internal error of
    the interpreter, and once the wall budget is spent it stops at once. The wall clock is the
    test's (1 ms per reading): the run is the same on every machine (issue 28 item 11)."""
    from val3check.simulation import SimOptions, simulate

    from interpretation.simsupport import StepClock

    clock = StepClock(0.001)
    result = simulate(ws, app, SimOptions(duration=duration, max_wall=max_wall, max_lines=200_000,
                                          max_memory_mb=300, wall_clock=clock), scenario)
    spent = round(max_wall / clock.step)
    assert clock.reads <= spent + 1000, f"the clock was read {clock.reads - spent} times after the wall budget"
    for d in result.diagnostics:
        assert d.error != 61 and "internal error" not in d.message, d
    return result


# ---- TOML texts, cell files and meshes (issue 21) --------------------------------------------------

TOML_HOSTILE = st.sampled_from([
    "a = " + "[" * 200 + "]" * 200, "a = " + "{b=" * 100 + "1" + "}" * 100, "a" + ".a" * 300 + " = 1",
    "[" + "t." * 300 + "t]", "x = " + "9" * 4400, "x = 0x" + "f" * 20, "x = -9223372036854775809", "x = 1e999",
    'x = "\\u0000"', "x = '''\n[[[[\n'''", 'x = """\\\n"""', "[[a]]\n[a]", "x = 1979-13-45", "\ufeffx = 1",
    "x = [1, 'a', {b = 2}]", "# " + "[" * 100,
])
TOML_TEXT = st.one_of(
    st.text(max_size=300),
    st.lists(st.one_of(TOML_HOSTILE, st.text(max_size=30)), max_size=6).map("\n".join),
    VALUES.map(lambda v: toml_text({"k": v})),
)

CELL_SEED = (ROOT / "fixtures" / "valid" / "PickPlace" / "val3check-cell.toml").read_bytes()
SCENARIO_SEED = (ROOT / "fixtures" / "scenarios" / "pickplace.toml").read_bytes()
CELL_NUMBERS = st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-2**63, 2**63 - 1),
                         st.sampled_from([0, -1, 1e-9, 1e6, 1e6 + 1, 1e40, 1e100, 1e308, 36000, 36001]))
_SOLID = st.fixed_dictionaries({"shape": st.sampled_from(["box", "cylinder", "sphere", "mesh", "cone", 5])}, optional={
    "name": st.one_of(st.text(max_size=10), st.sampled_from(["a\x00b", "x" * 300, "é"])),
    "size": st.lists(CELL_NUMBERS, max_size=4), "radius": CELL_NUMBERS, "length": CELL_NUMBERS,
    "file": st.sampled_from(["m.stl", "m.obj", "m.glb", "../m.stl", "a\x00.stl", "/etc/passwd", "missing.stl", "m"]),
    "scale": st.one_of(CELL_NUMBERS, st.lists(CELL_NUMBERS, max_size=4)), "solid": st.one_of(st.booleans(), SCALARS),
    "at": st.one_of(st.lists(CELL_NUMBERS, max_size=7),
                    st.dictionaries(st.sampled_from(["x", "y", "z", "rx", "ry", "rz", "w"]), CELL_NUMBERS, max_size=4)),
    "frame": st.sampled_from(["world", "fA", "fA[2]", "lib:f", "f[", "x" * 300]),
    "tool": st.sampled_from(["flange", "tGripper", "t[1]", "", "\x1b"]),
    "grasp": st.sampled_from(["close", "open", "x"]), "cleared_by": SCALARS, "touch_links": VALUES, "bogus": VALUES,
})
CELL = st.fixed_dictionaries({}, optional={
    "version": st.one_of(st.just(1), SCALARS), "unit": st.sampled_from(["mm", "inch", "m", 1]),
    "margin_mm": CELL_NUMBERS, "touch_mm": CELL_NUMBERS, "description": SCALARS,
    "obstacle": st.lists(_SOLID, max_size=3), "tool": st.lists(_SOLID, max_size=2), "part": st.lists(_SOLID, max_size=2),
    "bogus": VALUES,
})


@st.composite
def mutated(draw, seed: bytes, tokens: list[bytes]) -> bytes:
    """`seed` with 1 to 3 mutations: truncation, a hostile token, a deleted, duplicated or
    replaced span, bytes overwritten."""
    data = bytearray(seed)
    for _ in range(draw(st.integers(1, 3))):
        pos = draw(st.integers(0, len(data)))
        op = draw(st.integers(0, 4))
        if op == 0:
            data = data[:pos]
        elif op == 1:
            data[pos:pos] = draw(st.sampled_from(tokens))
        elif op == 2:
            del data[pos:pos + draw(st.integers(1, 40))]
        elif op == 3:
            span = data[pos:pos + draw(st.integers(1, 100))]
            data[pos:pos] = span * draw(st.integers(1, 30))
        else:
            chunk = draw(st.binary(min_size=1, max_size=8))
            data[pos:pos + len(chunk)] = chunk
    return bytes(data)


CELL_TOKENS = [b"[", b"]", b"{", b"}", b"=", b'"', b"\n", b".", b"9" * 4400, b"1e400", b"-1", b"nan", b"[[obstacle]]",
               b"\\u0000", b"\xff", b"0x" + b"f" * 20, b"[" * 100, b"a." * 100]
MESH_TOKENS = [b"\x00" * 4, b"\xff\xff\xff\xff", b"solid", b"facet", b"f 1 2 3 4 5", b"v nan inf 1e400",
               b'"uri":"x.bin",', b'"count":999999999,', b'"children":[0],', b"mtllib ../x.mtl\n", b"[" * 50]


def mesh_seeds() -> dict[str, bytes]:
    from .meshfiles import cube_glb, obj, stl_ascii, stl_binary

    return {"stl": stl_binary(), "ascii.stl": stl_ascii(), "obj": obj(), "glb": cube_glb(nodes=2)}


# ---- the language server's messages ---------------------------------------------------------------

JSON = st.recursive(
    st.one_of(st.none(), st.booleans(), st.integers(-2**70, 2**70), st.floats(allow_nan=False), st.text(max_size=30)),
    lambda inner: st.one_of(st.lists(inner, max_size=4), st.dictionaries(st.text(max_size=10), inner, max_size=4)),
    max_leaves=15)
LSP_METHODS = ["initialize", "initialized", "shutdown", "textDocument/didOpen", "textDocument/didChange",
               "textDocument/didClose", "textDocument/didSave", "textDocument/hover", "textDocument/definition",
               "textDocument/documentSymbol", "workspace/didChangeWorkspaceFolders", "$/cancelRequest",
               "$/setTrace", "workspace/executeCommand", "textDocument/completion", "no/such"]
_DOC = st.fixed_dictionaries({}, optional={"uri": st.one_of(st.text(max_size=20), JSON), "text": JSON,
                                           "version": JSON, "languageId": JSON})
PARAMS = st.one_of(JSON, st.fixed_dictionaries({}, optional={
    "textDocument": st.one_of(_DOC, JSON), "position": st.one_of(
        st.fixed_dictionaries({"line": st.integers(-5, 2**40), "character": st.integers(-5, 2**40)}), JSON),
    "contentChanges": st.one_of(JSON, st.lists(st.fixed_dictionaries({"text": st.one_of(st.text(max_size=50), JSON)},
                                                                    optional={"range": JSON}), max_size=2)),
    "capabilities": JSON, "rootUri": JSON, "workspaceFolders": JSON, "event": JSON, "id": JSON}))
# ids are numbered by the test (unique); a message may lose its id, or have one that is not an id
MESSAGE = st.fixed_dictionaries(
    {"method": st.one_of(st.sampled_from([m for m in LSP_METHODS if m != "initialize"]), st.text(max_size=15))},
    optional={"params": PARAMS, "jsonrpc": st.sampled_from(["2.0", "2.0", "2.0", "1.0", 2]), "id": st.just(True),
              "bogus": JSON})

# framing: pieces that never hold a valid Content-Length the test did not write, so that the
# sentinel request after them can always be found
_VALID_LENGTH = re.compile(rb"content-length[ \t]*:[ \t]*\d", re.I)
_BAD_VALUES = [b"abc", b"-5", b"1e3", b"", b" ", b"99999999999999", b"0x10", "\u0661\u0662".encode(), b"5 5",
               b"+5", b"\xff"]
GARBAGE = st.one_of(
    st.binary(max_size=120),
    st.sampled_from([b"\r\n", b"\n", b"\r\n\r\n", b"Content-Length:", b"Content-Type: text/plain\r\n",
                     b"content-length :", b"{", b"}", b'{"jsonrpc": "2.0", "id": 99, "method": "shutdown"}',
                     b"Content-Length: abc\r\n\r\n", b"Content-Length: \r\n"]),
).filter(lambda b: not _VALID_LENGTH.search(b))


def _framed(body: bytes) -> bytes:
    return b"Content-Length: %d\r\n\r\n" % len(body) + body


@st.composite
def frame_piece(draw) -> bytes:
    """A frame, well formed or not, or bytes between frames."""
    kind = draw(st.integers(0, 4))
    body = draw(st.one_of(JSON.map(lambda v: json.dumps(v).encode("utf-8")), st.binary(max_size=80)))
    if _VALID_LENGTH.search(body):
        body = b"{}"
    if kind == 0:
        return _framed(body)
    if kind == 1:  # a header that is not a length
        return b"Content-Length: " + draw(st.sampled_from(_BAD_VALUES)) + b"\r\n\r\n" + body
    if kind == 2:  # a length shorter than the body
        return b"Content-Length: %d\r\n\r\n" % draw(st.integers(0, max(0, len(body) - 1))) + body
    if kind == 3:  # another header first, or none
        return draw(st.sampled_from([b"Content-Type: application/vscode-jsonrpc\r\n", b"X: y\r\n", b""])) + _framed(body)
    return draw(GARBAGE)


def lsp_requests(messages: list[dict]) -> tuple[bytes, dict]:
    """Frames of `messages` (a test's ids numbered from 1), and the ids of the requests that
    must be answered (a dict with a method and an id)."""
    out, asked = [], {}
    for n, m in enumerate(messages, 1):
        m = dict(m)
        if m.pop("id", None):
            m["id"] = n
            asked[n] = m["method"]
        m.setdefault("jsonrpc", "2.0")
        out.append(_framed(json.dumps(m).encode("utf-8")))
    return b"".join(out), asked


def check_lsp_output(messages: list[dict]) -> dict:
    """The server's messages are JSON-RPC 2.0: responses by id (none answered twice), and no
    internal error (a crash of a handler)."""
    answered: dict = {}
    for m in messages:
        assert m.get("jsonrpc") == "2.0", m
        if "method" in m:
            assert "id" not in m, m  # the server sends notifications only
            assert m["method"] in ("textDocument/publishDiagnostics", "window/logMessage"), m
            continue
        assert ("result" in m) != ("error" in m), m
        if "error" in m:
            assert m["error"]["code"] != -32603, m
        if m["id"] is not None:
            assert m["id"] not in answered, f"answered twice: {m}"
            answered[m["id"]] = m
    return answered


LSP_URIS = ["{app}/start.pgx", "{app}/sub.pgx", "{app}/Example.dtx", "{app}/Example.pjx", "{outside}/start.pgx",
            "{root}/link.pgx", "file:///etc/passwd", "file:///proc/self/environ", "untitled:Untitled-1",
            "untitled:Untitled-2", "http://example.com/a.pgx", "file://host/x.pgx", "file:///a%00b.pgx", "", "%%%"]
DOC_TEXT = st.one_of(
    st.text(max_size=200),
    st.sampled_from(["", "\ud800", "<Programs>", "\x00", "é" * 50]),
    PROGRAM.map(lambda code: program_text("start", code)),
    st.tuples(PROGRAM, st.text(max_size=3)).map(lambda t: program_text("start", t[0]) + t[1]),
)


def program_text(name: str, code: str) -> str:
    from val3check.testing import program_file

    return program_file(name, code)


@st.composite
def lsp_operations(draw) -> list[tuple]:
    """Editor operations on documents named by LSP_URIS: (kind, uri, text or position)."""
    ops = []
    for _ in range(draw(st.integers(1, 5))):
        uri = draw(st.sampled_from(LSP_URIS))
        kind = draw(st.sampled_from(["open", "open", "change", "close", "save", "hover", "definition", "symbols"]))
        if kind in ("open", "change"):
            ops.append((kind, uri, draw(DOC_TEXT)))
        else:
            ops.append((kind, uri, {"line": draw(st.one_of(st.integers(0, 12), st.integers(0, 2**31 - 1))),
                                    "character": draw(st.one_of(st.integers(0, 40), st.integers(0, 2**31 - 1)))}))
    return ops
