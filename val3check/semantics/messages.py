"""The wording of every compiler-check diagnostic (N, T, L codes), one function per message.

Messages name what is wrong with the user's own words (names as written), say what the manual
expects, and suggest the fix when there is an obvious one. Sections are those of the VAL 3 s7
reference manual.
"""

from __future__ import annotations

from collections.abc import Iterable


def a(word: str) -> str:
    """`word` with its indefinite article: "a num", "an element", "an aio"."""
    return ("an " if word[:1].lower() in "aeio" else "a ") + word

# ------------------------------------------------------------------------------ names (N)


def undefined_variable(name: str, suggestion: str | None = None) -> str:
    hint = f"; did you mean {suggestion}?" if suggestion else ""
    return f"undefined variable {name}: no parameter, local or global of this name (2.5.2){hint}"


def undefined_program(name: str, suggestion: str | None = None) -> str:
    hint = f"; did you mean {suggestion}?" if suggestion else ""
    return f"undefined program {name}: the application has no program of this name{hint}"


def undefined_instruction(name: str, suggestion: str | None) -> str:
    hint = f"; did you mean {suggestion}?" if suggestion else ""
    return f"unknown instruction {name}(): not a VAL 3 instruction nor a program of the application{hint}"


def variable_called(name: str) -> str:
    return f"{name} is a variable, not an instruction: write {name}[...] to read an element"


def unknown_instruction_s8(name: str, version: str) -> str:
    return (f"{name}() is not an instruction of the VAL 3 s7 manual nor a program of the application;"
            f" {version or 'this version'} may provide it: check it on the controller")


def unknown_instruction_s7(name: str) -> str:
    return (f"{name}() is not an instruction of the VAL 3 s7 manual nor a program of the application"
            " (a newer or optional instruction?): check it on the controller")


def undefined_alias(alias: str, suggestion: str | None = None) -> str:
    hint = f"; did you mean {suggestion}?" if suggestion else ""
    return f"undefined library identifier {alias}: the project declares no library {alias} (6.3){hint}"


def case_mismatch(kind: str, written: str, declared: str) -> str:
    return (f"{written} is spelt {declared} where the {kind} is declared: write it the same way"
            " (the controller may treat names as case-sensitive)")


def duplicate_local(kind: str, name: str, first_kind: str, first_line: int) -> str:
    return f"{kind} {name} has the same name as the {first_kind} declared on line {first_line}"


def invalid_name(kind: str, name: str, why: str) -> str:
    return f"invalid {kind} name {name!r}: {why} (2.5.1: 1 to 15 characters of a..z A..Z 0..9 _, starting with a letter)"


def start_stop_params(name: str, count: int) -> str:
    s = "s" if count > 1 else ""
    section = "2.2.3" if name.lower() == "start" else "2.2.4"
    return f"{name}() cannot have parameters ({section}); it declares {count} parameter{s}"


def undefined_type(kind: str, name: str, type_name: str) -> str:
    return (f"{kind} {name} has an unknown type {type_name!r}: neither a VAL 3 type nor a user type"
            " declared in the project (2.3, 7)")


def wrong_arm_family(kind: str, name: str, type_name: str, family: str, arm_family: str, arm_kind: str,
                     where: str) -> str:
    return (f"{kind} {name} is {a(type_name)} ({family} type), but the arm of this controller is a {arm_kind} arm"
            f" ({where}): its positions are {arm_family} types (9.7.2). The manual does not say that the controller"
            " refuses the other family (a library may offer forms for both kinds of arm), so this is a warning:"
            " check that the declaration is meant for another arm")


def mixed_families_unknown_arm(kind: str, name: str, type_name: str, counts: dict[str, int]) -> str:
    both = " and ".join(f"{n} {fam}" for fam, n in sorted(counts.items()))
    return (f"{kind} {name} is {a(type_name)}: this application declares positions of both arm families"
            f" ({both} declarations; Rx: six-axis arms, Rs: SCARA) and its arm is not known (no controller tree"
            " with usr/configs/arm.cfx): check that the declarations of the other family are meant")


# ------------------------------------------------------------------------------ types (T)


def operator_undefined(op: str, left: str, right: str | None = None) -> str:
    if right is None:
        word = "-" if op == "-" else op
        return f"operator {word} is not defined for {left}"
    hint = ""
    if op == "+" and "string" in (left, right) and "num" in (left, right):
        hint = ": convert the number with toString(\"\", n)"
    elif op == "+" and left == "point":
        hint = ": use compose() or appro() to move a point"
    return f"operator {op} is not defined between {left} and {right}{hint}"


def condition_not_bool(keyword: str, got: str) -> str:
    return f"the condition of {keyword} must be a bool, not {a(got)} (2.2.5)"


def assign_mismatch(target: str, got: str) -> str:
    hint = ""
    if target == "string" and got == "num":
        hint = ": convert it with toString(\"\", n)"
    elif target == "num" and got == "string":
        hint = ": convert it with toNum()"
    return f"cannot assign {a(got)} to {a(target)}{hint}"


def assign_in_expression() -> str:
    return ("`=` assigns; use `==` to compare: `=` is not allowed in a condition or an instruction"
            " parameter (3.1.2, 3.2.2, 3.4.2)")


def s8_signature(message: str) -> str:
    return f"{message}; this is the s7 manual's signature, and s8 may add other forms: check it on the controller"


def s8_reading(message: str) -> str:
    return (f"{message}; this signature is read from real s8 code (val3check/language/s8.toml), not from a"
            " manual: check it on the controller")


def arity(what: str, expected: str, got: int, signatures: Iterable[str] = ()) -> str:
    sigs = list(signatures)
    tail = ""
    if sigs:
        tail = "; expected " + " or ".join(sigs[:4]) + (" ..." if len(sigs) > 4 else "")
    word = "argument" if got == 1 else "arguments"
    return f"{what} takes {expected}, not {got} {word}{tail}"


def argument_type(index: int, what: str, param: str, expected: str, got: str) -> str:
    return f"argument {index} of {what} ({param}) must be {a(expected)}, not {a(got)}"


def argument_type_overloads(index: int, what: str, got: str, signatures: Iterable[str]) -> str:
    sigs = list(signatures)
    return (f"no form of {what} takes {a(got)} as argument {index}; expected "
            + " or ".join(sigs[:4]) + (" ..." if len(sigs) > 4 else ""))


def needs_variable(index: int, what: str, param: str, container: str = "") -> str:
    kind = a(f"{container} variable") if container else "a variable"
    return (f"argument {index} of {what} ({param}) is passed by reference: it must be {kind},"
            " not a constant or the result of an expression (2.6.2, 2.6.3)")


def container_mismatch(index: int, what: str, param: str, expected: str, got: str) -> str:
    return f"argument {index} of {what} ({param}) must be {a(expected)}, not {a(got)} (2.6.3)"


def index_count(name: str, dims: int, got: int) -> str:
    if dims == 0:
        return f"{name} is an element: it takes at most one index [0], not {got} (2.5.3)"
    return f"{name} is a {dims}-D array: it takes {dims} {'index' if dims == 1 else 'indices'}, not {got} (2.5.3)"


def not_indexable(what: str) -> str:
    return f"{what} is not a variable with values to index: [] only follows an array or a collection (2.5.3)"


def index_not_num(name: str, got: str) -> str:
    return f"{name} is an array: its indices are numbers, not {a(got)} (2.5.3)"


def key_not_string(name: str, got: str) -> str:
    hint = ": a collection is indexed by a string key (2.5.3)"
    return f"{name} is a collection: its key must be a string, not {a(got)}{hint}"


def missing_index(name: str, what: str) -> str:
    if what == "collection":
        return f"{name} is a collection: name one of its values with a key, {name}[\"key\"] (2.5.3)"
    return f"{name} is {what}: name one of its values with an index, {name}[i] (2.3.4, 2.5.3)"


def no_field(type_name: str, field: str, known: Iterable[str] = ()) -> str:
    names = list(known)
    if not names:
        return f"{type_name} has no fields: .{field} cannot follow it (2.5.3)"
    return f"{type_name} has no field {field}; its fields are {', '.join(names)}"


def not_assignable(what: str) -> str:
    return f"cannot assign to {what}: the left side of = must be a variable, an element or a field of it"


def case_type(got: str, expected: str) -> str:
    return f"case value of type {got} in a switch on a {expected}: case values must have the switch's type (2.2.5)"


def for_counter(got: str) -> str:
    return f"the counter of for must be a num variable, not {got} (2.2.5)"


def for_bound(which: str, got: str) -> str:
    return f"the {which} of for must be a num, not {a(got)} (2.2.5)"


def dio_assign() -> str:
    return ("`=` between two dio was removed in VAL 3 s7 (3.5.2): write diOut = (diIn == true)"
            " to copy the state of an input")


def literal_arity(type_name: str, lo: int, hi: int, got: int) -> str:
    want = str(hi)
    return f"{a(type_name)} value has at most {want} fields, this {{...}} has {got} (2.4.2)"


def literal_not_structured(expected: str) -> str:
    return f"a {{...}} value cannot be {a(expected)}: only structured types are written with braces (2.4.2)"


def literal_field(type_name: str, index: int, expected: str, got: str) -> str:
    return f"field {index} of {a(type_name)} value must be {a(expected)}, not {a(got)} (2.4.2)"


def call_of_instruction(name: str) -> str:
    return f"{name} is an instruction, not a program: write {name}(...) without call (2.2.5)"


def program_without_call(name: str) -> str:
    return f"{name} is a program: run it with call {name}(...); a program returns no value (2.2.5)"


def program_as_value(name: str) -> str:
    return f"{name} is a program, not a variable: run it with call {name}(...)"


def instruction_as_value(name: str) -> str:
    return f"{name} is an instruction: call it with parentheses, {name}(...)"


def library_prefix_needed(name: str) -> str:
    return f"{name}() is called through a library identifier: alias:{name}(...) (6.7)"


def library_prefix_unexpected(alias: str, name: str) -> str:
    return f"{name}() is not a library instruction: {alias}:{name}() is not allowed (6.7)"


def no_value(name: str) -> str:
    return f"{name}() returns no value: it cannot be used in an expression"


def unexpected_index(index: int, what: str, param: str, kind: str) -> str:
    return (f"argument {index} of {what} ({param}): unexpected {kind}; give the variable without"
            " [] (2.5.4, 2.6.3)")


def resize_not_allowed(name: str, instruction: str, why: str) -> str:
    return f"{instruction}() cannot change the size of {name}: {why} (2.5.4, 2.5.5)"


def task_local_reference(name: str, param: str) -> str:
    return (f"local variable {name} is passed by reference ({param}) to a task: a task cannot use a"
            " local variable by reference, it may be deleted before the task ends (5.10)")


def task_name(keyword: str, name: str, why: str, certain: bool = True) -> str:
    if not certain:
        return (f"task name \"{name}\": {why}; on an s7 controller {keyword} would stop with runtime error 29"
                " (5.10: 1 to 15 characters of a..z A..Z 0..9 _)")
    return (f"task name \"{name}\" is invalid: {why}; {keyword} stops with runtime error 29 (5.10: 1 to 15"
            " characters of a..z A..Z 0..9 _)")


def task_priority(text: str) -> str:
    return f"task priority {text} is outside 1 to 100: taskCreate stops with a runtime error (5.10)"


def task_overrun_local(name: str) -> str:
    return f"the overrun flag of taskCreateSync must be a global variable, not the local {name} (5.10)"


# ------------------------------------------------------------------------------ libraries (L)


def undefined_library_symbol(alias: str, name: str, lib: str, suggestion: str | None = None) -> str:
    hint = f"; did you mean {alias}:{suggestion}?" if suggestion else ""
    return (f"{alias}:{name} is not in the interface of library {lib}: it has no public program or"
            f" global named {name} (6.2){hint}")


def private_library_symbol(alias: str, name: str, lib: str, kind: str) -> str:
    return (f"{alias}:{name} is a private {kind} of library {lib}: only public programs and globals"
            " can be used from outside the library (6.2)")


def library_symbol_not_program(alias: str, name: str) -> str:
    return f"{alias}:{name} is data of the library, not a program: it cannot be called"


def library_symbol_not_data(alias: str, name: str) -> str:
    return f"{alias}:{name} is a program of the library, not data: run it with call {alias}:{name}(...)"


def undefined_user_field(type_name: str, field: str, known: Iterable[str]) -> str:
    names = list(known)
    tail = f"; its fields are {', '.join(names[:12])}{' ...' if len(names) > 12 else ''}" if names else ""
    return f"user type {type_name} has no field {field} (7.2: the fields are the public globals of its application){tail}"


def private_user_field(type_name: str, field: str) -> str:
    return f"{field} is a private global of user type {type_name}'s application: it is not a field of the type (7.2)"


# ------------------------------------------------------------------------------ s8 (T030, T031)


def s8_only(what: str, target: str) -> str:
    return (f"{what} is s8 only (CS9 controllers) and this application targets {target}: it runs on a CS9,"
            " a CS8 refuses it; say which controller you target in the configuration (target = \"CS9\" or"
            " target = \"CS8 s7.11\")")


def s8_on_s7_target(what: str, target: str) -> str:
    return f"{what} is s8 only (CS9 controllers): the target {target} does not have it"


def guessed(kind: str, name: str, path: str, where: str) -> str:
    """The note a finding carries when it depends on a library or user type found by guessing."""
    return (f"{kind} {name} was found by guessing: '{path}' leads nowhere and the application of that name in"
            f" the repository, {where}, is used (F016); if it is not the right one, this finding is wrong,"
            " so it is at most a warning")
