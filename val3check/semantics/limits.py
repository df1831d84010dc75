"""The manual's limits on what an application declares and writes, and the references of its
data files: checked here, apart from the type checker, because they concern sizes and numbers
rather than types.

| code | rule |
|---|---|
| T026 | an array dimension beyond 9999 values (2.5.4; on s8 beyond what s8 code uses, a warning) |
| T027 | an array of more than 9999 values in all, each dimension within the limit (2.5.4) |
| F017 | a numeric constant beyond the range of a num (3.2.1) |
| N014 | a fatherId that names no frame or tool of the application, or is malformed (9.4.1) |

`check_application(workspace, app)` is called by `semantics.analyse` for every target.
"""

from __future__ import annotations

import math

from ..diagnostics import Diagnostic, Severity
from ..language.target import Target, target_for
from ..language.version_facts import over
from ..loading.model import Application, Container, Data, Value, Workspace
from ..loading.attribute_text import HUGE, parse_father
from ..loading.types import base_type
from ..parsing import ast as A
from ..rules import codes

# What a fatherId may look like: `name` or `name[index]` (2-D: "i j" or "i,j"; a collection: "key"):
# loading.attribute_text.parse_father.


def check_application(workspace: Workspace, app: Application, target: Target | None = None) -> list[Diagnostic]:
    """`target`: what `app` is checked for (its project file's version by default): the limit on
    sizes is the s7 manual's, certain up to s7 (language/version_facts.py)."""
    major = (target if target is not None else target_for(app.version, None)).major
    out: list[Diagnostic] = []
    for d in app.data.values():
        if d.container is Container.ARRAY:
            _sizes(out, f"global {d.name}", d.sizes, d.origin, major)
    for prog in app.programs.values():
        for loc in prog.locals:
            if loc.container is not Container.COLLECTION:
                _sizes(out, f"local {loc.name} of {prog.name}()", loc.sizes, loc.origin, major)
        if prog.body is not None:
            _numbers(out, prog.body, prog.origin.path)
    if app.globals_known:
        _fathers(out, app)
    return out


def _shown(n: int) -> str:
    return "more than 10^12" if n >= HUGE else str(n)


def _sizes(out: list[Diagnostic], what: str, sizes: tuple[int, ...], origin, major: int | None) -> None:  # noqa: ANN001
    """T026 for a dimension beyond the limit of the version; T027 for the values in all."""
    if not sizes:
        return
    big = [n for n in sizes if over("values", n, major)]
    if big:
        p = over("values", big[0], major, f"{_shown(big[0])} values")
        sure = "a variable holds at most 9999 values (manual 2.5.4)" if p.certain else "the s8 limit is not known"
        out.append(Diagnostic(
            codes.ARRAY_DIMENSION_OVER_LIMIT, f"{what}: a dimension of {p.why}; {sure}",
            origin.path, origin.line, origin.col, at_most=None if p.certain else Severity.WARNING,
        ))
        return
    total = math.prod(sizes)
    p = over("values", total, major, f"{' x '.join(map(str, sizes))} = {total} values")
    if p is not None:
        out.append(Diagnostic(
            codes.ARRAY_VALUES_OVER_LIMIT,
            f"{what}: {p.why}; the manual limits the size of a variable (2.5.4) and does not say whether an"
            " array of 2 or 3 dimensions counts its values in all",
            origin.path, origin.line, origin.col,
        ))


def _numbers(out: list[Diagnostic], body, path: str) -> None:  # noqa: ANN001
    for node in A.walk(body):
        if type(node) is A.Number and math.isinf(node.value):
            text = node.text if len(node.text) <= 40 else f"{node.text[:20]}... ({len(node.text)} characters)"
            out.append(Diagnostic(
                codes.NUMBER_OUT_OF_RANGE,
                f"numeric constant {text} is beyond the range of a num (a double: about ±1.8e308, 14 significant"
                " digits, manual 3.2.1): the program does not compile",
                path, node.line, node.col, node.end_line, node.end_col,
            ))


_WANT = {"frame": "frame", "point": "frame", "tool": "tool"}


def _fathers(out: list[Diagnostic], app: Application) -> None:
    lower = {n.lower(): d for n, d in app.data.items()}
    for d in app.data.values():
        want = _WANT.get(base_type(d.type))
        if want is None:
            continue
        for v in d.values:
            if v.father:
                problem = _father_problem(v.father, want, app.data, lower)
                if problem:
                    out.append(_father_diag(d, v, problem))


def _father_diag(d: Data, v: Value, problem: str) -> Diagnostic:
    shown = v.father if len(v.father or "") <= 60 else (v.father or "")[:60] + "..."
    return Diagnostic(
        codes.FATHER_NOT_FOUND,
        f"{d.name}[{v.key}]: fatherId '{shown}' {problem}; the value has no reference"
        f" {'tool' if base_type(d.type) == 'tool' else 'frame'} (a use of it stops the task, manual 9.4.1)",
        v.origin.path, v.origin.line, v.origin.col,
    )


def _father_problem(father: str, want: str, data: dict[str, Data], lower: dict[str, Data]) -> str | None:
    m = parse_father(father)
    if m is None:
        return "is not a reference (expected name or name[index])"
    name, idx = m
    low = name.lower()
    if low in ("world", "flange") and name not in data:  # as the simulator resolves it
        if (low == "world") == (want == "frame"):
            return None
        return f"names {low}, which is a {'frame' if low == 'world' else 'tool'}; a {want} is needed"
    target = data.get(name) or lower.get(low)
    if target is None:
        return "names no global of the application"
    t = base_type(target.type)
    if t != want:
        return f"names {target.name}, a {t}; a {want} is needed"
    if target.container is Container.COLLECTION:
        key = (idx or "").strip().strip('"')
        if idx is None or not any(val.key == key for val in target.values):
            return f"names no value of the collection {target.name}"
        return None
    dims = target.sizes or (1,)
    parts = (idx or "0").replace(",", " ").split()
    try:
        nums = [float(p) for p in parts]
    except ValueError:
        return f"has an index that is not a number ({_short(idx)})"
    if not nums or not all(math.isfinite(x) for x in nums):
        return f"has an index that is not a number ({_short(idx or '')})"
    if len(nums) != len(dims) or any(not 0 <= int(x) < n for x, n in zip(nums, dims)):
        return f"is outside {target.name} (size {' '.join(map(str, dims))})"
    return None


def _short(text: str | None) -> str:
    text = text or ""
    return text if len(text) <= 30 else text[:30] + "..."
