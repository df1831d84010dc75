"""`load` never raises: mutated and truncated files, odd attributes, odd trees."""

from __future__ import annotations

import random

from .loadhelp import make_app

from val3check.loading import load

ITERATIONS = int(__import__("os").environ.get("VAL3CHECK_FUZZ_ITERATIONS", "150"))
KNOWN_CODES = {f"F{n:03d}" for n in range(1, 14)} | {f"L{n:03d}" for n in range(1, 6)}

BODY = """    <Data name="pPick" access="public" xsi:type="array" type="pointRx" size="2 3">
      <Value key="0 1" x="500" y="-40" shoulder="lefty" fatherId="fPallet[0]" />
    </Data>
    <Data name="part" access="public" xsi:type="collection" type="Part">
      <Value key="a"><Field name="n" xsi:type="array" type="num" size="1"><Value key="0" value="1" /></Field></Value>
    </Data>
"""


def test_mutations_never_raise(tmp_path):
    rng = random.Random(1234)
    app = make_app(tmp_path / "App", data_body=BODY, libraries=[("lib", "Disk://lib")], types=[("Part", "./Part")])
    folder = app.parent
    originals = {p: p.read_bytes() for p in folder.iterdir()}
    tokens = [
        b"<",
        b">",
        b"&",
        b"]]>",
        b"<![CDATA[",
        b'"',
        b"\xff",
        b"\x00",
        b"&#0;",
        b"&#x110000;",
        b"\r",
        b"xsi:",
        b"</Code>",
        b' size="0"',
    ]
    for _ in range(ITERATIONS):
        for p, data in originals.items():
            p.write_bytes(data)
        victim = rng.choice(sorted(originals))
        data = bytearray(originals[victim])
        op = rng.randrange(4)
        pos = rng.randrange(len(data) + 1)
        if op == 0:
            data = data[:pos]
        elif op == 1:
            data[pos:pos] = rng.choice(tokens)
        elif op == 2 and data:
            del data[pos : pos + rng.randrange(1, 20)]
        else:
            data = bytes(rng.randrange(256) for _ in range(rng.randrange(50)))
        victim.write_bytes(bytes(data))
        ws, diags = load([str(folder)])
        assert {d.code for d in diags} <= KNOWN_CODES
        for d in diags:
            assert d.line >= 0 and d.col >= 0 and d.path.startswith(str(tmp_path))


def test_odd_inputs_never_raise(tmp_path):
    (tmp_path / "empty").mkdir()
    (tmp_path / "f.pjx").write_text("")
    (tmp_path / "weird name é.pgx").write_text("<Programs/>")
    for paths in ([], [str(tmp_path / "f.pjx")], [str(tmp_path)], [str(tmp_path / "weird name é.pgx")], ["/dev/null"]):
        ws, diags = load(paths)
        assert {d.code for d in diags} <= KNOWN_CODES
