"""Generate a large, valid VAL 3 application for benchmarks (deterministic: fixed seed)."""

from __future__ import annotations

import random
from pathlib import Path

PJX = """<?xml version="1.0" encoding="utf-8"?>
<Project xmlns="http://www.staubli.com/robotics/VAL3/Project/3">
  <Parameters version="s7.11" stackSize="5000" millimeterUnit="true" />
  <Programs>
{programs}
  </Programs>
  <Database>
    <Data file="{name}.dtx" />
  </Database>
  <Libraries />
</Project>
"""

DTX = """<?xml version="1.0" encoding="utf-8"?>
<Database xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xmlns="http://www.staubli.com/robotics/VAL3/Data/2">
  <Datas>
    <Data name="nCount" access="public" xsi:type="array" type="num" size="1" />
    <Data name="nGrid" access="public" xsi:type="array" type="num" size="10 10" />
    <Data name="sLog" access="public" xsi:type="array" type="string" size="1" />
    <Data name="bReady" access="public" xsi:type="array" type="bool" size="1" />
    <Data name="sNames" access="public" xsi:type="collection" type="string">
      <Value key="a" value="alpha" />
    </Data>
  </Datas>
</Database>
"""

PGX = """<?xml version="1.0" encoding="utf-8"?>
<Programs xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xmlns="http://www.staubli.com/robotics/VAL3/Program/2">
  <Program name="{name}" access="public">
    <Parameters xmlns="http://www.staubli.com/robotics/VAL3/Param/1">
      <Parameter name="x_nIn" type="num" xsi:type="element" />
    </Parameters>
    <Locals>
      <Local name="l_i" type="num" xsi:type="array" size="1" />
      <Local name="l_j" type="num" xsi:type="array" size="1" />
      <Local name="l_s" type="string" xsi:type="array" size="1" />
    </Locals>
    <Code><![CDATA[{code}]]></Code>
  </Program>
</Programs>
"""

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
        (folder / f"{prog}.pgx").write_text(PGX.format(name=prog, code="\n".join(body)), encoding="utf-8")
        programs.append(prog)
        total += len(body)
        index += 1
    for special in ("start", "stop"):
        code = "begin\n  call prog0000(1)\nend" if special == "start" else "begin\nend"
        text = PGX.format(name=special, code=code)
        head, _, rest = text.partition("    <Parameters")
        text = head + rest[rest.index("    <Code>"):]  # start() and stop() take no parameter and no local
        (folder / f"{special}.pgx").write_text(text, encoding="utf-8")
        programs.append(special)
        total += code.count("\n") + 1
    entries = "\n".join(f'    <Program file="{p}.pgx" />' for p in programs)
    (folder / f"{name}.pjx").write_text(PJX.format(programs=entries, name=name), encoding="utf-8")
    (folder / f"{name}.dtx").write_text(DTX, encoding="utf-8")
    return total
