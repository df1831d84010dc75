"""A 20,000-line application (BOM, CRLF, half CDATA, half escaped text, 2000 globals) loads
whole and exactly. How fast (the goal: at least 20,000 lines/s) is measured by
bench/bench_lint.py, not here: a test may not depend on the machine's speed (issue 28 item 11)."""

from __future__ import annotations

from .loadhelp import PGX_NS, XSI, dtx, pjx, write

from val3check.loading import load

N_PROGRAMS = 100
LINES_PER_PROGRAM = 200  # 20,000 code lines


def make_big_app(root):
    folder = root / "Big"
    names = [f"prog{i:03d}" for i in range(N_PROGRAMS)]
    body = ["begin"]
    for k in range(LINES_PER_PROGRAM - 2):
        body.append(f'  l_n = l_n + {k} // comment with "quotes" and <tags>')
    body.append("end")
    code = "\n".join(body)
    escaped = code.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
    for i, n in enumerate(names):
        inner = f"<![CDATA[{code}]]>" if i % 2 else escaped  # half CDATA, half escaped text
        write(
            folder / f"{n}.pgx",
            '<?xml version="1.0" encoding="utf-8"?>\n'
            f'<Programs {XSI} xmlns="{PGX_NS}">\n'
            f'  <Program name="{n}" access="public">\n'
            '    <Locals><Local name="l_n" type="num" xsi:type="array" size="1" /></Locals>\n'
            f"    <Code>{inner}</Code>\n"
            "  </Program>\n"
            "</Programs>\n",
            bom=True,
            crlf=True,
        )
    data = "".join(
        f'    <Data name="p{i}" access="public" xsi:type="array" type="pointRx" size="1">\n'
        f'      <Value key="0" x="{i}" y="2" z="3" rz="90" shoulder="lefty" fatherId="world[0]" />\n'
        "    </Data>\n"
        for i in range(2000)
    )
    write(folder / "Big.dtx", dtx(data), bom=True, crlf=True)
    write(folder / "Big.pjx", pjx([f"{n}.pgx" for n in names], ["Big.dtx"]), bom=True, crlf=True)
    return folder


def test_loading_a_big_application(tmp_path):
    folder = make_big_app(tmp_path)
    ws, diags = load([str(folder)])
    assert diags == []
    app = ws.apps[ws.targets[0]]
    code_lines = sum(p.code.count("\n") + 1 for p in app.programs.values())
    assert code_lines == N_PROGRAMS * LINES_PER_PROGRAM
    assert len(app.programs) == N_PROGRAMS and len(app.data) == 2000
    assert app.programs["prog001"].code == app.programs["prog000"].code  # CDATA and escaped text alike
