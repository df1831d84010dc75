"""Generate a large, valid VAL 3 application for benchmarks (deterministic: fixed seed)."""

from __future__ import annotations

import random
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from val3check.testing import database_xml, program_file, project_xml  # noqa: E402

# Globals of the application, as VAL 3 Studio writes them (sNames has one value).
DATAS = """    <Data name="nCount" access="public" xsi:type="array" type="num" size="1" />
    <Data name="nGrid" access="public" xsi:type="array" type="num" size="10 10" />
    <Data name="sLog" access="public" xsi:type="array" type="string" size="1" />
    <Data name="bReady" access="public" xsi:type="array" type="bool" size="1" />
    <Data name="sNames" access="public" xsi:type="collection" type="string">
      <Value key="a" value="alpha" />
    </Data>"""
PARAMS = ("num x_nIn",)
LOCALS = ("num l_i", "num l_j", "string l_s")

BLOCKS = [
    "  // accumulate the grid\n  for l_i = 0 to 9\n    for l_j = 9 to 0 step -1\n      nGrid[l_i, l_j] = nGrid[l_i, l_j] + x_nIn * 2 - (l_i % 3)\n    endFor\n  endFor",
    "  if nCount > 10 and bReady == true\n    nCount = 0\n  elseIf nCount <= -1 or !bReady\n    nCount = abs(nCount)\n  else\n    nCount = nCount + 1\n  endIf",
    "  l_s = \"value \" + toString(\"\", nCount)\n  if len(l_s) > 4\n    sLog = left(l_s, 4)\n  endIf",
    "  switch nCount\n    case 1, 2\n      sLog = \"low\"\n    break\n    case 3\n      sLog = \"mid\"\n    break\n    default\n      sLog = \"high\"\n    break\n  endSwitch",
    "  l_i = 0\n  while l_i < 5\n    l_i = l_i + 1\n    nCount = nCount + sin(l_i * 10) * cos(30) / 2\n  endWhile",
    "  do\n    l_j = l_j + 1.5e-1\n  until l_j >= 3 xor bReady",
    "  l_s = first(sNames)\n  while l_s != \"\"\n    sLog = sNames[l_s]\n    l_s = next(sNames[l_s])\n  endWhile",
]


def generate(folder: Path, min_lines: int = 20_000, seed: int = 3) -> int:
    """Write the application into `folder`; return the number of VAL 3 code lines."""
    rng = random.Random(seed)
    folder.mkdir(parents=True, exist_ok=True)
    name = folder.name
    total, index, programs = 0, 0, []
    while total < min_lines:
        prog = f"prog{index:04d}"
        body = ["begin"]
        while len(body) < 200:
            body.extend(rng.choice(BLOCKS).split("\n"))
        if index > 0:
            body.append(f"  call prog{index - 1:04d}(nCount)")
        body.append("end")
        text = program_file(prog, "\n".join(body), PARAMS, LOCALS)
        (folder / f"{prog}.pgx").write_text(text, encoding="utf-8")
        programs.append(prog)
        total += len(body)
        index += 1
    for special in ("start", "stop"):
        code = "begin\n  call prog0000(1)\nend" if special == "start" else "begin\nend"
        # start() and stop() take no parameter and have no local
        (folder / f"{special}.pgx").write_text(program_file(special, code), encoding="utf-8")
        programs.append(special)
        total += code.count("\n") + 1
    (folder / f"{name}.pjx").write_text(project_xml(name, programs), encoding="utf-8")
    (folder / f"{name}.dtx").write_text(database_xml(DATAS), encoding="utf-8")
    return total
