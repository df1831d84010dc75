"""11.4 the absolute robot: getDefaultDH, getDH, setDH on the arm of the run.

11.4.4: getDH/getDefaultDH "renvoient les paramètres DH du bras dans les tableaux spécifiés. Les
paramètres d et a sont des translations en mm ; les paramètres alpha, beta et theta sont des
angles en degrés" (getDH the arm's current ones, getDefaultDH the standard ones of its type);
setDH "modifie la géométrie du bras avec les paramètres DH ... La modification est immédiate",
returns false "si la nouvelle géométrie n'a pas été appliquée parce qu'elle est trop différente
des paramètres de la géométrie standard", "attend que le mouvement soit vide", and "La taille des
tableaux DH doit correspondre au nombre d'axes du robot. Une entrée supplémentaire peut être
nécessaire dans le tableau d pour modifier la dimension de la bride : quand il est absent, setDH()
renvoie false et un message de diagnostic est envoyé à l'enregistreur".

The parameters are the model's in the form of 11.4.1 (robot/dh.py). After setDH everything that
uses the arm's kinematics follows for the rest of the run: here(), jointToPoint, pointToJoint,
the motion (movel, movec, movej to a point), the collision checks and the reports' arm. What the
simulation cannot do is said (R052): the arm's configuration file is not written.
"""

from __future__ import annotations

from ..interpretation.chapters.ch09_geometry import arm_of
from ..interpretation.not_simulated import ARM_LIMIT, SimLimit
from ..interpretation.waiting import WAIT
from ..language.runtime_errors import Val3RuntimeError
from ..robot import dh as _dh
from ..robot.absolute import with_dh
from ..robot.errors import IKUnsupported
from ..rules import codes
from .ch11_licences import require
from .runtime_notes import note

E = Val3RuntimeError
US = 1_000_000
GET_ORDER = ("theta", "d", "a", "alpha", "beta")  # getDH/getDefaultDH: no b[] (11.4.4, as written)
SET_ORDER = ("theta", "d", "a", "b", "alpha", "beta")


def _nominal(task, arm, what: str) -> _dh.DH:
    """The standard parameters of the arm (R002 when the manual's form does not apply to it)."""
    model = arm.model
    nominal = getattr(model, "dh_nominal", None)
    if nominal is not None:
        return nominal
    try:
        return _dh.nominal_dh(model)
    except IKUnsupported as exc:
        raise SimLimit(ARM_LIMIT, what, f"{what}: {exc}") from None


def _write(arrays, dh: _dh.DH, what: str) -> None:
    """Write the parameters into the program's arrays (theta, d, a, alpha, beta); d[6] when d has
    room for it. 70 for an array of fewer than six values."""
    for name, arr in zip(GET_ORDER, arrays):
        values = dh.values(name)
        want = 6
        if arr.size() < want:
            raise E(70, f"{what}: {name}[] holds {arr.size()} values for the 6 axes of the arm")
        if name == "d" and arr.size() >= 7:
            want = 7
        for i in range(want):
            arr.data[arr.off + i] = float(values[i])


def I_getdefaultdh(task, unit, theta, d, a, alpha, beta) -> None:
    """11.4.4 getDefaultDH: the standard parameters of the arm's type."""
    arm = arm_of(task, "getDefaultDH")
    _write((theta, d, a, alpha, beta), _nominal(task, arm, "getDefaultDH"), "getDefaultDH")


def I_getdh(task, unit, theta, d, a, alpha, beta) -> None:
    """11.4.4 getDH: the arm's current parameters (setDH's, else the standard ones)."""
    arm = arm_of(task, "getDH")
    nominal = _nominal(task, arm, "getDH")
    _write((theta, d, a, alpha, beta), getattr(arm.model, "dh", None) or nominal, "getDH")


def I_setdh(task, unit, theta, d, a, b, alpha, beta):
    """11.4.4 setDH: waits until the motion is empty, then changes the arm's geometry (true), or
    leaves it (false) when the arrays do not fit or the geometry is too different."""
    arm = arm_of(task, "setDH")
    nominal = _nominal(task, arm, "setDH")
    require(task, "absoluteRobot", "setDH")
    machine = task.machine
    clock = machine.clock
    done = lambda: arm.motion_done(clock.now)
    done.motion = True
    yield from WAIT(task, done, False, "setDH (the motion to be empty)")
    arrays = dict(zip(SET_ORDER, (theta, d, a, b, alpha, beta)))
    short = [n for n, arr in arrays.items() if arr.size() < 6]
    if short:
        return _refuse(task, f"{', '.join(f'{n}[]' for n in short)} hold fewer values than the 6 axes of the arm")
    values = {n: tuple(float(arr.data[arr.off + i]) for i in range(6)) for n, arr in arrays.items()}
    if d.size() >= 7:
        values["d"] = values["d"] + (float(d.data[d.off + 6]),)
    elif nominal.d[6]:
        return _refuse(task, "d[] has no 7th value, the flange dimension this arm's wrist needs")
    else:
        values["d"] = values["d"] + (0.0,)
    new = _dh.DH(**values)
    why = _dh.too_different(arm.model, nominal, new)
    if why is not None:
        return _refuse(task, why)
    base = getattr(arm, "base_model", None) or arm.model
    model = base if new == nominal else with_dh(base, new)
    arm.set_geometry(model, clock.time_of(task) / US)
    note(task, codes.OPTION_EFFECT_NOT_SIMULATED, "setDH: the new geometry is used for the rest of the run; the arm's configuration file, where "
                       "the controller also writes it for its next start (11.4.2), is not simulated", once="setDH")
    return True


def _refuse(task, why: str) -> bool:
    """setDH returns false, "un message de diagnostic est envoyé à l'enregistreur" (the logger)."""
    task.machine.transcript_add(task, "logMsg", f"setDH refused: {why}", None)
    return False


def register(registry) -> None:
    """11.4."""
    registry.instruction("getDefaultDH", I_getdefaultdh)
    registry.instruction("getDH", I_getdh)
    registry.instruction("setDH", I_setdh, blocking=True)
