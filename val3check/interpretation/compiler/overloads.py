"""The forms of an instruction the compiler can bind arguments to: the s7 catalogue's
(language/instructions.toml), the s8 forms and instructions whose parameters are known
(language/s8.toml), and the simulator's reading of an s8 form whose parameters are not public.
"""

from __future__ import annotations

from ...language import lookup, s8
from ...language.instructions import Overload, Param

# s8 forms whose parameters are not public, as the simulator binds them (docs/sim.md, "s8 and
# the system library"): sioSet with a third argument (language/s8.toml: "a length?") sends the
# first nTaille values of the array.
READINGS = {
    "sioset": (Overload("num", (Param("siSortie", "sio"), Param("nDonnées", "num", "array", ref=True),
                                Param("nTaille", "num")), "s8", "the simulator's reading of the s8 form"),),
}


def overloads_with_arity(name: str, arity: int) -> list[Overload]:
    low = name.lower()
    ins = lookup(name)
    found = list(ins.overloads_with_arity(arity)) if ins is not None else []
    for form in s8.forms(low):
        if form.params_known and form.overload.accepts_arity(arity):
            found.append(form.overload)
    extra = s8.instruction(low)
    if ins is None and extra is not None and extra.instruction is not None:
        found += [o for o in extra.instruction.overloads if o.accepts_arity(arity)]
    found += [o for o in READINGS.get(low, ()) if o.accepts_arity(arity)]
    return found


def is_s8_only(name: str) -> bool:
    """An instruction s7 does not have and s8 does (language/s8.toml)."""
    return lookup(name) is None and s8.instruction(name.lower()) is not None
