"""11.5 the continuous axis: resetTurn, and the joint range the option gives the axis.

11.5.1: "L'axe 6 (pour les bras RX/TX) ou 4 (pour les bras RS/TS) peut être 'continu' ... le
nombre de tours qu'il a effectués au cours du cycle est sans importance ... si l'axe commence le
cycle de l'application dans la position 0° et le finit dans la position 720° (2 tours), le cycle
suivant peut remettre instantanément la position à 0°". 11.5.2 resetTurn(jReference): "se
comporte comme l'instruction resetMotion() standard, attend l'arrêt du bras et ajuste la position
de l'axe continu afin de la rapprocher le plus possible de la position de référence spécifiée. Elle
renvoie la position effective du bras après l'exécution de l'instruction. L'opération
d'ajustement s'effectue indifféremment avec le bras sous tension ou hors tension et prend environ
50 ms."

So the continuous axis turns past the software limits of the arm's data sheet (the manual's own
example ends a cycle at 720°, beyond the TX2's ±270°): with the option, the simulation gives the
axis no software limit (±100 turns). The option is in use when the application calls resetTurn
(scanned before the run) or the scenario says `[options] continuousAxis = true`; `false` keeps the
data sheet's range and makes resetTurn error 250.

resetTurn here: resetMotion(), wait for the arm to stop, 50 ms, then the continuous axis's value
changes by the whole turns that bring it nearest the reference (the arm does not move: its
commanded position is the same physical position), from that instant on; the calibration data the
controller writes (R052) are not simulated.
"""

from __future__ import annotations

import re
from dataclasses import replace

import numpy as np

from ..interpretation.chapters.ch09_geometry import arm_of, check_axes, jd, jt, millimeter_unit
from ..interpretation.waiting import DELAY, WAIT
from ..rules import codes
from .ch11_licences import require
from .runtime_notes import note

US = 1_000_000
TURNS = 100  # the continuous axis's range in the simulation: ±TURNS turns
ADJUST_S = 0.05  # "prend environ 50 ms"
_CALL = re.compile(r"\bresetTurn\s*\(", re.IGNORECASE)


def continuous_axis(model) -> int:
    """The index of the continuous axis: 6 on RX/TX arms, 4 on RS/TS (11.5.1)."""
    return 3 if getattr(model, "family", "six-axis") == "scara" else 5


def uses_reset_turn(ws, app) -> bool:
    """Whether the application (or a library it declares) calls resetTurn."""
    apps = [app, *(ws.library(app, alias) for alias in app.libraries)]
    for a in filter(None, apps):
        for program in getattr(a, "programs", {}).values():
            if program.code and _CALL.search(program.code):
                return True
    return False


def set_continuous(arm, on: bool) -> None:
    """Give the arm's continuous axis no software limit (±TURNS turns), or its model's range back."""
    model = getattr(arm, "base_model", None)
    if model is None:
        return
    k = continuous_axis(model)
    nominal = getattr(arm, "nominal_limits", None) or tuple(model.joint_limits)
    arm.nominal_limits = nominal
    limits = list(nominal)
    if on:
        limits[k] = (-360.0 * TURNS, 360.0 * TURNS)
    if tuple(limits) == tuple(arm.model.joint_limits):
        return
    arm.base_model = replace(model, joint_limits=tuple(limits))
    current = replace(arm.model, joint_limits=tuple(limits))
    current.__dict__.pop("_spec", None)
    arm.base_model.__dict__.pop("_spec", None)
    arm.model = current
    arm._kin = {}
    arm._queue = None  # made again at first use, with the range


def I_resetturn(task, unit, reference: dict):
    """11.5.2 resetTurn(jReference): resetMotion(), wait for the arm to stop, adjust the continuous
    axis by whole turns nearest the reference (50 ms); returns the arm's position."""
    arm = arm_of(task, "resetTurn")
    ref = jt(reference)
    check_axes(arm, ref, "resetTurn")
    require(task, "continuousAxis", "resetTurn")
    machine = task.machine
    clock = machine.clock
    mm = millimeter_unit(unit)
    q = arm.sync(clock.time_of(task))
    q.reset_motion(clock.time_of(task) / US)
    stopped = lambda: arm.queue_time(clock.now) >= arm.queue.profile.t_end - 1e-9
    stopped.motion = True
    yield from WAIT(task, stopped, False, "resetTurn (the arm to stop)")
    yield from DELAY(task, ADJUST_S)
    now = clock.time_of(task)
    k = continuous_axis(arm.model)
    value = float(arm.actual_position(now / US)[k])
    wanted = float(arm.joints_in(ref, mm)[k] + arm.layers.turns.latest[k])  # the reference, model units
    turns = round((wanted - value) / 360.0)
    if turns:
        delta = np.zeros(arm.axes)
        delta[k] = 360.0 * turns
        arm.layers.turns.add(now / US, delta)
    note(task, codes.OPTION_EFFECT_NOT_SIMULATED, "resetTurn: the continuous axis's value changes by whole turns as the manual says; the arm's "
                       "calibration data the controller writes for its next start (11.5.2) are not simulated",
         once="resetTurn")
    return jd(arm.joints_at(now, mm))


def register(registry) -> None:
    """11.5."""
    registry.instruction("resetTurn", I_resetturn, blocking=True)
