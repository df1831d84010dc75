"""Helpers to write small VAL 3 application trees in tmp_path (imported by the test_load_* files)."""

from __future__ import annotations

import os
from pathlib import Path

PJX_NS = "http://www.staubli.com/robotics/VAL3/Project/3"
PGX_NS = "http://www.staubli.com/robotics/VAL3/Program/2"
DTX_NS = "http://www.staubli.com/robotics/VAL3/Data/2"
XSI = 'xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"'


def write(path: Path, text: str, *, bom: bool = False, crlf: bool = False) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    if crlf:
        text = text.replace("\n", "\r\n")
    data = text.encode("utf-8")
    if bom:
        data = b"\xef\xbb\xbf" + data
    path.write_bytes(data)
    return path


def pjx(
    programs=("start.pgx", "stop.pgx"),
    data=(),
    libraries=(),
    types=(),
    params='version="s7.11" stackSize="5000" millimeterUnit="true"',
) -> str:
    lines = [
        '<?xml version="1.0" encoding="utf-8"?>',
        f'<Project xmlns="{PJX_NS}">',
        f"  <Parameters {params} />",
        "  <Programs>",
    ]
    lines += [f'    <Program file="{p}" />' for p in programs]
    lines += ["  </Programs>", "  <Database>"]
    lines += [f'    <Data file="{d}" />' for d in data]
    lines += ["  </Database>", "  <Libraries>"]
    lines += [f'    <Library alias="{a}" path="{p}" />' for a, p in libraries]
    lines += ["  </Libraries>", "  <Types>"]
    lines += [f'    <Type name="{n}" path="{p}" />' for n, p in types]
    lines += ["  </Types>", "</Project>", ""]
    return "\n".join(lines)


def pgx(name: str, code: str = "begin\nend", access: str = "private", extra: str = "") -> str:
    return (
        '<?xml version="1.0" encoding="utf-8"?>\n'
        f'<Programs {XSI} xmlns="{PGX_NS}">\n'
        f'  <Program name="{name}" access="{access}">\n'
        f"{extra}"
        f"    <Code><![CDATA[{code}]]></Code>\n"
        "  </Program>\n"
        "</Programs>\n"
    )


def dtx(body: str) -> str:
    return (
        '<?xml version="1.0" encoding="utf-8"?>\n'
        f'<Database {XSI} xmlns="{DTX_NS}">\n'
        "  <Datas>\n"
        f"{body}"
        "  </Datas>\n"
        "</Database>\n"
    )


def make_app(
    folder: Path,
    name: str | None = None,
    *,
    programs=("start", "stop"),
    data_body: str | None = None,
    libraries=(),
    types=(),
    **kw,
) -> Path:
    """An s7 application `folder/<name>.pjx` with empty start/stop programs."""
    name = name or folder.name
    files = [f"{p}.pgx" for p in programs]
    for p in programs:
        write(folder / f"{p}.pgx", pgx(p))
    data = ()
    if data_body is not None:
        data = (f"{name}.dtx",)
        write(folder / f"{name}.dtx", dtx(data_body))
    return write(folder / f"{name}.pjx", pjx(files, data, libraries, types, **kw))


def codes(diags, code=None):
    return [d for d in diags if code is None or d.code == code]


def rel(path: str, root: Path) -> str:
    return os.path.relpath(path, root)
