"""Calls of instructions in the generated code (chapters 2-11).

What is simulated, and how, is the registry's (registry.py): a handler `I_name(T, A, ...)`
gets its arguments compiled for the catalogue's parameters (values, (container, key) pairs
for references, `Arr`/`Coll` for containers); a pure built-in `B_name(...)`; an inline form
(`INLINE_FORMS`) is written here because its arguments are variables or conditions, not
values. Library instructions (`alias:libLoad()`) and calls of programs are here and in
statements.py.
"""

from __future__ import annotations

from ...language import lookup
from ...parsing import ast
from ..not_simulated import ARM_LIMIT
from ..registry import system_symbol
from ..values import ENUM_CONSTANTS
from .overloads import overloads_with_arity
from .structures import UNKNOWN, Code, CompileError, VariableArg

# Functions whose value changes with time alone: a wait on them cannot be skipped over by
# jumping to the next event (the clock is stepped instead).
# The arm's position and progress change continuously while it moves (chapter 10): a wait on
# `getMoveId() >= 15.8` is evaluated every cycle, as on the controller.
TIME_DEPENDENT = frozenset({"clock", "getdate", "watch", "getmoveid", "herej", "here", "getspeed", "issettled"})

# What a wait condition may read of the cell besides inputs (the deadlock report's R009, which
# names the scenario entry): the operator's keys (4.3), the controller's state (chapter 8, 4.3)
# by the [controller] key that sets it.
KEY_READS = frozenset({"getkey", "iskeypressed"})
STATE_READS = {"esstatus": "es_status", "ispowered": "powered", "workingmode": "working_mode",
               "getmonitorspeed": "monitor_speed", "iscalibrated": "calibrated", "safetyfault": "safety_fault",
               "getprofile": "profile", "getlanguage": "language"}

# Instructions the compiler writes itself (registered as inline by their chapter module).
INLINE_FORMS = {
    # 2.5.4 - 2.5.6: any variable
    "size": "i_size", "isdefined": "i_isdefined", "insert": "i_insert", "delete": "i_delete", "append": "i_append",
    "resize": "i_resize", "first": "i_first", "last": "i_last", "next": "i_next", "prev": "i_prev",
    "getdata": "i_getdata",
    # 4.3: the screen is optional, get() writes a variable
    "put": "i_put", "putln": "i_putln", "title": "i_title", "get": "i_get",
    # 5.10: a condition evaluated again and again, a bool variable
    "wait": "i_wait", "watch": "i_watch", "setmutex": "i_setmutex",
}


class CallCompiler:
    """The calls part of `ProgramCompiler` (program.py)."""

    def call_expr(self, node: ast.CallExpr, want: str | None = None) -> Code:
        """A call of an instruction, as the registry says it is simulated: an inline form the
        compiler writes itself, a handler, a pure built-in, or (a catalogue instruction nothing
        simulates) the not-simulated stop, whose arguments are not evaluated (they could
        block). `want`: the type the value is used as (a `$` call's value)."""
        func = node.func
        if type(func) is ast.SystemName:
            return self.system_call(node, func.name, want)
        if type(func) is ast.LibraryName:
            if func.name.startswith("$"):  # `lib:$name()`: a system instruction reached through a library
                return self.system_call(node, f"{func.alias}:{func.name}", want)
            return self.lib_instruction(node)
        name = func.name
        low = name.lower()
        registry = self.registry
        form = INLINE_FORMS.get(low)
        if form is not None and registry.is_inline(low):
            return getattr(self, form)(node)
        if low == "abs" and node.args and self._arg_type(node.args[0]) == "joint":  # 9.2.3 abs(joint)
            return Code(f"JABS({self.expr(node.args[0]).text})", "joint")
        handler = registry.handler(low)
        if handler is not None:
            return self.handler_call(node, handler)
        if registry.builtin_of(low) is not None:
            return self.builtin_call(node, low)
        ins = lookup(name)
        if ins is not None:
            if registry.not_simulated_kind(low) == ARM_LIMIT:
                return Code(f"ARM({name!r})", self._ret_type(name, node.args))
            return Code(f"NOTSIM({ins.name!r})", self._ret_type(name, node.args))
        raise self.err(f"unknown instruction '{name}'", node)

    def _ret_type(self, name: str, args) -> str:
        ins = lookup(name)
        if ins is None:
            return UNKNOWN
        ovs = ins.overloads_with_arity(len(args)) or list(ins.overloads)
        rets = {o.returns for o in ovs}
        return rets.pop() if len(rets) == 1 else UNKNOWN

    def _overload(self, name: str, node):
        ovs = overloads_with_arity(name, len(node.args))
        if not ovs:
            raise self.err(f"{name}: no form takes {len(node.args)} argument(s)", node)
        if len(ovs) == 1:
            return ovs[0]
        types = [self._arg_type(a) for a in node.args]
        for o in ovs:
            if all(p.type in ("*", t) or t == UNKNOWN or (p.type == "bool" and t == "dio") for p, t in zip(o.params, types)):
                return o
        return ovs[0]

    def _arg_type(self, a) -> str:
        """An argument's type, for choosing an instruction's form: semantic analysis's, else
        the compiler's."""
        t = self.semantic_type(a)
        if t is not None:
            return t
        try:
            tn = type(a)
            if tn in (ast.Name, ast.LibraryName):
                v = self.var_of(a)
                if v is not None:
                    return v.t
                low = a.name.lower()
                if low in ENUM_CONSTANTS:
                    return ENUM_CONSTANTS[low]
                return UNKNOWN
            if tn is ast.Struct:
                return UNKNOWN
            return self.expr(a).t
        except CompileError:
            return UNKNOWN

    def args_for(self, node, params) -> list[str]:
        """Arguments compiled for catalogue parameters: values, (container, key) pairs for
        references, Arr/Coll objects for containers."""
        out = []
        for a, p in zip(node.args, params):
            if p.container in ("array", "collection"):
                out.append(self.container_arg(a))
            elif p.ref:
                out.append(self.ref_arg(a))
            else:
                code, t = self.expr(a, want=p.type if p.type != "*" else None)
                out.append(self.coerce(code, t, p.type))
        return out

    def container_arg(self, a) -> str:
        """An array/collection argument; `a[i]` of a 1-D array passes the part from i (2.6.3)."""
        if type(a) is ast.Index:
            c, t, cont, ndim, _ = self.container_of(a.base)
            if cont == "array" and len(a.indices) == 1:
                return f"VIEW({c}, {self.expr(a.indices[0]).text})"
            raise self.err("only a 1-D array can be passed from an index", a)
        tn = type(a)
        if tn in (ast.Name, ast.LibraryName):
            v = self.var_of(a)
            if v is not None and v.cont == "element":
                c, k = self.elem_pair(v) if v.store != "py" else (None, None)
                if c is None:
                    raise self.err(f"'{a.name}' is not an array", a)
                return f"ELEMARR({c}, {k}, {v.t!r})"
        c, t, cont, ndim, _ = self.container_of(a)
        return c

    def handler_call(self, node, handler) -> Code:
        """`I_name(T, A, args...)`, with `yield from` for a blocking handler. A `raw` handler (an
        s8 instruction whose parameters are not public) gets the call's text instead, its
        arguments not evaluated, and the type its value is used as."""
        if handler.raw:
            used = "" if node is self.statement_call else (self.semantic_type(node) or "num")
            call = f"I_{handler.name}(T, A, {self.source_line(node)!r}, {used!r})"
            return Code(f"(yield from {call})" if handler.blocking else call, used or "void")
        ov = self._overload(handler.name, node)
        args = self.args_for(node, ov.params)
        call = f"I_{handler.name}(T, A{''.join(', ' + x for x in args)})"
        if handler.blocking:
            call = f"(yield from {call})"
        return Code(call, ov.returns)

    def builtin_call(self, node, low: str) -> Code:
        b = self.registry.builtin_of(low)
        if len(node.args) != len(b.params):
            raise self.err(f"{b.name} takes {len(b.params)} argument(s)", node)
        args = []
        for i, (a, p) in enumerate(zip(node.args, b.params)):
            if p.endswith("[]"):
                args.append(self.container_arg(a))
            elif i in b.outputs:
                args.append(self.ref_arg(a))
            else:
                code, t = self.expr(a, want=p)
                args.append(self.coerce(code, t, p))
        if not b.outputs and not any(p.endswith("[]") for p in b.params):
            return Code(f"B_{low}({', '.join(args)})", b.returns)
        return Code(f"BREF(B_{low}{''.join(', ' + x for x in args)})", b.returns)

    def system_call(self, node: ast.CallExpr, name: str, want: str | None) -> Code:
        """A `$name()` instruction of the system library: its handler with the arguments compiled
        as it says (registry.SystemHandler); one nothing runs goes on with an info (R041) and,
        when its value is used, the default value of the type it is used as."""
        h = self.registry.system_handler(name)
        value_unknown = h is not None and h.returns == "void" and node is not self.statement_call
        if h is not None and len(node.args) == len(h.params) and not value_unknown:
            args = []
            for a, how in zip(node.args, h.params):
                if how == "array":
                    args.append(self.container_arg(a))
                elif how == "ref":
                    args.append(self.ref_arg(a))
                else:
                    args.append(self.expr(a).text)
            call = f"{system_symbol(h.name)}(T, A{''.join(', ' + x for x in args)})"
            return Code(f"(yield from {call})" if h.blocking else call, h.returns)
        used = "" if node is self.statement_call else (want if want and want != UNKNOWN else "num")
        if used not in ("", "num", "bool", "string"):
            raise self.err(f"system instruction {name}: its value cannot be a {used} here (not simulated)", node)
        why = "" if h is None else ("its value, here used, is not known" if value_unknown
                                    else f"the simulator runs its form of {len(h.params)} argument(s)")
        return Code(f"SYSTEM(T, {name!r}, {self.source_line(node)!r}, {used!r}, {why!r})", used or "void")

    def source_line(self, node) -> str:
        """The program line of `node`, as written (at most 80 characters): what the reports say
        a task waits in, or an instruction the transcript records."""
        code = self.program.code or ""
        cmap = self.program.code_map
        text = ""
        for k, line in enumerate(code.split("\n"), 1):
            if cmap.to_file(k, 1).line == node.line:
                text = line.strip()
                break
        return text if len(text) <= 80 else text[:77] + "..."

    def lib_instruction(self, node: ast.CallExpr) -> tuple[str, str]:
        alias, name = node.func.alias, node.func.name
        low = name.lower()
        args = [self.expr(a).text for a in node.args]
        if low in ("libload", "libsave", "libdelete", "liblist"):
            return Code(f"(yield from I_lib(T, A, {alias!r}, {low!r}{''.join(', ' + x for x in args)}))", "num")
        if low in ("libpath", "libexist"):
            return Code(f"I_lib_now(T, A, {alias!r}, {low!r}{''.join(', ' + x for x in args)})", "string" if low == "libpath" else "bool")
        raise self.err(f"{alias}:{name}() is not a library instruction", node)

    # -- instructions with special argument forms (2.5.4 - 2.5.6: any variable) ------------------

    def var_arg(self, a) -> VariableArg:
        """A variable given to an instruction on any variable (size, insert...)."""
        if type(a) is ast.Index:
            ref = self.container_of(a.base)
            idx = ", ".join(self.expr(i).text for i in a.indices)
            return VariableArg(ref.code, f"({idx},)", ref.cont)
        tn = type(a)
        if tn in (ast.Name, ast.LibraryName):
            v = self.var_of(a)
            if v is None:
                raise self.err(f"unknown variable '{a.name}'", a)
            if v.cont == "element":
                if v.store == "py":
                    return VariableArg("None", "None", "element")
                c, k = self.elem_pair(v)
                return VariableArg(f"({c}, {k})", "None", "element")
            return VariableArg(self.cont_code(v), "None", v.cont)
        if tn is ast.Field:
            try:
                ref = self.container_of(a)
                return VariableArg(ref.code, "None", ref.cont)
            except CompileError:
                return VariableArg("None", "None", "element")
        raise self.err("expected a variable", a)

    def i_size(self, node):
        if len(node.args) == 2:
            c, idx, cont = self.var_arg(node.args[0])
            return Code(f"SIZE2({c}, {self.expr(node.args[1]).text})", "num")
        c, idx, cont = self.var_arg(node.args[0])
        return Code(f"SIZE({c}, {idx})", "num")

    def i_isdefined(self, node):
        a = node.args[0]
        if type(a) is ast.LibraryName:
            return Code(f"LIBDEF(A, {a.alias!r}, {a.name!r})", "bool")
        if type(a) is ast.Index and type(a.base) is ast.LibraryName:
            c, idx, cont = self.var_arg(a)
            return Code(f"(LIBDEF(A, {a.base.alias!r}, {a.base.name!r}) and ISDEF({c}, {idx}))", "bool")
        c, idx, cont = self.var_arg(a)
        return Code(f"ISDEF({c}, {idx})", "bool")

    def i_insert(self, node):
        if len(node.args) == 3:
            return self.builtin_or_missing(node, "insert")
        c, idx, cont = self.var_arg(node.args[0])
        return Code(f"INSERT(T, A, {c}, {idx})", "bool")

    def i_delete(self, node):
        if len(node.args) == 3:
            return self.builtin_or_missing(node, "delete")
        c, idx, cont = self.var_arg(node.args[0])
        return Code(f"DELETE(T, {c}, {idx})", "bool")

    def builtin_or_missing(self, node, low):
        if self.registry.builtin_of(low) is not None:
            return self.builtin_call(node, low)
        return Code(f"NOTSIM({low!r})", "string")

    def i_append(self, node):
        c, idx, cont = self.var_arg(node.args[0])
        return Code(f"APPEND(T, A, {c})", "void")

    def i_resize(self, node):
        c, idx, cont = self.var_arg(node.args[0])
        return Code(f"RESIZE(T, A, {c}, {self.expr(node.args[1]).text}, {self.expr(node.args[2]).text})", "void")

    def _coll_key_fn(self, node, fn):
        a = node.args[0]
        if type(a) is ast.Index:
            c, t, cont, ndim, _ = self.container_of(a.base)
            return Code(f"{fn}({c}, {self.expr(a.indices[0]).text})", "string")
        c, idx, cont = self.var_arg(a)
        return Code(f"{fn}({c}, None)", "string")

    def i_first(self, node):
        return self._coll_key_fn(node, "CFIRST")

    def i_last(self, node):
        return self._coll_key_fn(node, "CLAST")

    def i_next(self, node):
        return self._coll_key_fn(node, "CNEXT")

    def i_prev(self, node):
        return self._coll_key_fn(node, "CPREV")

    def i_getdata(self, node):
        name = self.expr(node.args[0]).text
        a = node.args[1]
        if type(a) is ast.Index:
            c, t, cont, ndim, _ = self.container_of(a.base)
            return Code(f"GETDATA(T, A, {name}, {c}, ({', '.join(self.expr(i).text for i in a.indices)},), {t!r})", "num")
        v = self.var_of(a) if type(a) in (ast.Name, ast.LibraryName) else None
        if v is not None and v.cont == "element":
            return Code(f"GETDATA(T, A, {name}, None, {self.ref_arg(a)}, {v.t!r})", "num")
        c, t, cont, ndim, _ = self.container_of(a)
        return Code(f"GETDATA(T, A, {name}, {c}, None, {t!r})", "num")

    def _cond_lambda(self, node) -> tuple[str, bool]:
        """A wait condition as a lambda, and whether it changes with time alone (clock())."""
        code = self.cond(node)
        if "yield" in code:
            raise self.err("a blocking instruction inside a wait condition is not simulated", node)
        tdep = any(type(n) is ast.CallExpr and type(n.func) is ast.Name and n.func.name.lower() in TIME_DEPENDENT
                   for n in ast.walk(node))
        return f"lambda: {code}", tdep

    def i_wait(self, node):
        fn, tdep = self._cond_lambda(node.args[0])
        what, hint, reads = self._wait_words(node)
        return Code(f"(yield from WAIT(T, {fn}, {tdep}, {what!r}, {hint!r}, frozenset({sorted(reads)!r})))", "void")

    def _wait_words(self, node) -> tuple[str, str, set[str]]:
        """What a wait waits for, in the program's words (its line, for the deadlock report),
        which part of the cell could make its condition true, with the scenario entry that plays
        it (inputs, keys, the controller's state: docs/scenario.md), and the globals it reads
        (interpretation/deadlock.py)."""
        text = self.source_line(node) or "wait"
        inputs: list[str] = []
        reads: set[str] = set()
        keys: list[str] = []
        state: dict[str, str] = {}
        for n in ast.walk(node.args[0]):
            tn = type(n)
            if tn is ast.CallExpr and type(n.func) is ast.Name:
                low = n.func.name.lower()
                if low in KEY_READS and n.func.name not in keys:
                    keys.append(n.func.name)
                elif low in STATE_READS:
                    state.setdefault(STATE_READS[low], n.func.name)
            if tn not in (ast.Name, ast.LibraryName):
                continue
            try:
                v = self.var_of(n)
            except CompileError:
                v = None
            if v is None or v.store in ("py", "box"):
                continue  # a local: only this task changes it
            if v.store not in ("g", "lib"):
                reads.add("?")  # a parameter by reference: whose global is not known here
                continue
            label = n.name if tn is ast.Name else f"{n.alias}:{n.name}"
            reads.add(label)
            if v.t in ("dio", "aio") and label not in inputs:
                inputs.append(label)
        hints = []
        if inputs:
            hints.append(f"the scenario can set {', '.join(inputs)}: [inputs] or [[events]] (docs/scenario.md)")
        if keys:
            hints.append(f"{', '.join(k + '()' for k in keys)} reads the operator's keys: the scenario's [[keys]] "
                         "(docs/scenario.md)")
        if state:
            fields = ", ".join(f"{k} ({f}())" for k, f in state.items())
            hints.append(f"the controller's state, {fields}: the scenario's [controller] table or its changes = "
                         f"[{{ at = ..., {next(iter(state))} = ... }}] (docs/scenario.md)")
        return text, "; ".join(hints), reads

    def i_watch(self, node):
        fn, tdep = self._cond_lambda(node.args[0])
        secs = self.expr(node.args[1]).text
        return Code(f"(yield from WATCH(T, {fn}, {secs}, {tdep}))", "bool")

    def i_setmutex(self, node):
        a = node.args[0]
        base = a.base if type(a) is ast.Index else a
        name = ""
        if type(base) in (ast.Name, ast.LibraryName):
            try:
                v = self.var_of(base)
            except CompileError:
                v = None
            if v is not None and v.store in ("g", "lib"):
                name = base.name if type(base) is ast.Name else f"{base.alias}:{base.name}"
        return Code(f"(yield from SETMUTEX(T, {self.ref_arg(a)}, {name!r}))", "void")

    def i_put(self, node):
        return self._page(node, "put")

    def i_putln(self, node):
        return self._page(node, "putln")

    def i_title(self, node):
        return self._page(node, "title")

    def _page(self, node, kind):
        args = [self.coerce(code, t, "num" if t == "aio" else UNKNOWN) for code, t in map(self.expr, node.args)]
        return Code(f"PAGE(T, {kind!r}{''.join(', ' + x for x in args)})", "void")

    def i_get(self, node):
        args = []
        for a in node.args:
            t = self._arg_type(a)
            if t == "screen":
                args.append(self.expr(a).text)
            else:
                args.append(self.ref_arg(a) + f", {t!r}")
        return Code(f"(yield from GET(T{''.join(', ' + x for x in args)}))", "num")
