"""Parameters of old (s5/s6) program files whose container is not written.

The s6 layout (shared/formats/srs-project-files.md, "The older s6 layout") describes a
parameter by `name`, `type` and `byVal` only: nothing says whether a by-reference parameter is
an element (2.6.2) or a whole array (2.6.3), and the loader reads it as an element. Before s7 a
reference parameter is a link to the caller's variable, which the program may index: real s6
programs write `x_sPaste[l_i] = ...` on such a parameter. Lint leaves its container unknown
(semantics/symbols.py); the simulator must choose one to bind the argument, and chooses from
the program's own use: a by-reference parameter that is indexed, or handed on where an array is
expected (an instruction's array parameter, another program's array parameter), is an array
reference (2.6.3: the caller's array, or its part from the index given); any other stays an
element reference (2.6.2).
"""

from __future__ import annotations

from ...language import lookup
from ...loading.model import Application, Container, Parameter
from ...parsing import ast


def array_parameters(app: Application) -> dict[str, dict[str, int]]:
    """For an s6 application: program name -> {parameter name: dimensions} of the by-reference
    element parameters its code uses as arrays ({} for any other layout)."""
    if app.layout != "s6":
        return {}
    candidates = {name: {p.name for p in prog.parameters if p.container is Container.ELEMENT and p.by_reference}
                  for name, prog in app.programs.items()}
    found: dict[str, dict[str, int]] = {name: {} for name in app.programs}
    calls: list[tuple[str, str, str, int]] = []  # (caller, its parameter, callee, argument index)
    for name, prog in app.programs.items():
        mine = candidates[name]
        if not mine or prog.body is None:
            continue
        for node in ast.walk(prog.body):
            tn = type(node)
            if tn is ast.Index and type(node.base) is ast.Name and node.base.name in mine:
                dims = found[name]
                dims[node.base.name] = max(dims.get(node.base.name, 1), len(node.indices))
            elif tn is ast.CallExpr and type(node.func) is ast.Name:
                for i, a in enumerate(node.args):
                    if type(a) is ast.Name and a.name in mine and _instruction_wants_array(node.func.name, i,
                                                                                          len(node.args)):
                        found[name].setdefault(a.name, 1)
            elif tn in (ast.Call, ast.TaskCreate, ast.TaskCreateSync) and type(node.target) is ast.Name:
                callee = _program(app, node.target.name)
                if callee is None:
                    continue
                for i, a in enumerate(node.args):
                    if type(a) is ast.Name and a.name in mine and i < len(callee.parameters):
                        p = callee.parameters[i]
                        if p.container is Container.ARRAY:
                            found[name].setdefault(a.name, p.dimensions or 1)
                        elif p.container is Container.ELEMENT and p.by_reference:
                            calls.append((name, a.name, callee.name, i))
    changed = True
    while changed:  # a parameter handed on to a parameter used as an array is one too
        changed = False
        for caller, param, callee, i in calls:
            target = app.programs[callee].parameters[i].name
            dims = found[callee].get(target)
            if dims is not None and param not in found[caller]:
                found[caller][param] = dims
                changed = True
    return {name: dims for name, dims in found.items() if dims}


def effective_parameters(app: Application, prog, arrays: dict[str, dict[str, int]]) -> list[Parameter]:
    """The parameters of `prog` as the simulator binds them (`arrays`: array_parameters(app))."""
    mine = arrays.get(prog.name)
    if not mine:
        return prog.parameters
    return [Parameter(p.name, p.type, Container.ARRAY, mine[p.name], True, p.origin) if p.name in mine else p
            for p in prog.parameters]


def _program(app: Application, name: str):
    prog = app.programs.get(name)
    if prog is None:
        low = name.lower()
        prog = next((q for n, q in app.programs.items() if n.lower() == low), None)
    return prog


def _instruction_wants_array(name: str, index: int, arity: int) -> bool:
    ins = lookup(name)
    if ins is None:
        return False
    overloads = [o for o in ins.overloads if o.accepts_arity(arity) and index < len(o.params)]
    return bool(overloads) and all(o.params[index].container == "array" for o in overloads)
