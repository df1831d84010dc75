"""11.1 compliant moves: movejf, movelf, isCompliant on the arm of the run (compliance.py models the
force balance; docs/motion.md, "Compliant moves").

11.1.5 movejf/movelf record a compliant command "vers la position jPosition avec l'outil tUtil,
les paramètres mDesc et une commande de force nForce" and return its identifier; "Une erreur
d'exécution est générée si mDesc ou nForce a des valeurs invalides, si jPosition est en dehors des
butées logicielles, si le mouvement précédent demande un lissage, ou si une commande de mouvement
précédemment enregistrée ne peut être exécutée". 11.1.4: "Il n'est pas possible d'utiliser du
lissage au début ou à la fin d'un mouvement compliant : le bras marquera nécessairement un arrêt
en début et fin de chaque mouvement compliant"; "Le paramètre d'effort sur le bras ne peut pas
dépasser 1000%".

Errors (12.1), at the instruction, with R053: nForce beyond ±1000 or not a number, 70 ("Valeur de
paramètre d'instruction invalide"); the previous command still asks for a blend (recorded with
blend joint or Cartesian, and no waitEndMove since), 154 ("Instruction de mouvement invalide :
vérifier le descripteur de mouvement": the manual gives no code of its own). The move's own blend
is not used (the arm stops at its end). The rest is movej's and movel's (10.6). Without the
compliance licence (scenario [options]): 250.
"""

from __future__ import annotations

import math

import numpy as np

from ..geometry import frames as geo_frames
from ..interpretation.chapters.ch09_geometry import jt
from ..language.runtime_errors import Val3RuntimeError
from ..lengths import INCH_MM
from ..motion.commands import Target
from ..rules import codes
from .ch10_motion import _arm, _check_family, _point, _record, _tool
from .ch11_licences import require
from .compliance import CompliantMove, meets_surface, pose_between
from .runtime_notes import note

E = Val3RuntimeError
US = 1_000_000
MAX_FORCE = 1000.0  # % of the nominal load (11.1.4)


def _checks(task, arm, name: str, force: float) -> None:
    """The limitations of 11.1.4 the instruction enforces, before it records anything."""
    require(task, "compliance", name)
    if not isinstance(force, (int, float)) or not math.isfinite(force) or abs(force) > MAX_FORCE:
        raise E(70, f"{name}: nForce = {force:g} is beyond ±{MAX_FORCE:g} % of the nominal load (11.1.4)", rule=codes.COMPLIANT_MOVE_LIMITATION)
    q = arm.queue
    if q is not None and q.open is not None:
        prev = q.open.request
        raise E(154, f"{name}: the previous motion ({prev.kind}, line {prev.source.line}) asks for a blend "
                     f"(mdesc.blend = {prev.mdesc.blend}): a compliant move starts from rest (11.1.4); use blend = "
                     "off or waitEndMove() before it", rule=codes.COMPLIANT_MOVE_LIMITATION)


def _start(arm) -> np.ndarray:
    """Where the next command starts (model units, the queue's coordinates)."""
    q = arm.queue
    if q.pending:
        return np.array(q.pending[-1].geometry.q_end, dtype=float)
    return np.array(q.path.q_rest, dtype=float)


def _compliant(task, unit, kind: str, target, tool, mdesc: dict, force: float):
    """Record a compliant command (blend off) and hand it to the arm's compliance."""
    name = kind + "f"
    arm = _arm(task, name)
    geo_frames.check_defined(tool)
    _check_family(arm, target, name)
    _checks(task, arm, name, force)
    note(task, codes.OPTION_EFFECT_NOT_SIMULATED, f"{name}: the controller's memory for compliant moves is not known: the error for a compliant "
                       "move too long for it (11.1.4) is never raised", once="compliant-memory")
    mm = getattr(unit.model, "millimeter_unit", True)
    s = 1.0 if mm else INCH_MM
    tool_m = _tool(tool)
    tool_mm = None
    if tool_m is not None:
        tool_mm = tool_m.copy()
        tool_mm[:3, 3] *= s
    comp = arm.compliance
    q = arm.queue
    contact = None
    if kind == "movej":
        tg = Target.joint(jt(target))
        if comp.surfaces:
            q0 = _start(arm)
            goal = np.array(arm.joints_in(jt(target), mm))
            contact = meets_surface(comp.surfaces, q.kin, "movej", q0, goal, tool_mm)
            if contact is not None:  # the move ends where the tool meets the surface
                app0 = np.asarray(arm.joints_out(q0 + arm.layers.turns.latest, mm))
                tg = Target.joint(tuple(float(v) for v in app0 + contact[0] * (np.asarray(jt(target)) - app0)))
    else:
        tg = _point(task, target, name)
        if comp.surfaces:
            q0 = _start(arm)
            goal = np.array(tg.pose, dtype=float)
            goal[:3, 3] *= s
            contact = meets_surface(comp.surfaces, q.kin, "movel", q0, goal, tool_mm)
            if contact is not None:
                start = q.kin.tcp(q0[None], tool_mm)[0]
                pose = pose_between(start, goal, contact[0])
                pose[:3, 3] /= s
                tg = Target(pose=pose, config=tg.config, name=tg.name, frame=tg.frame)
    md = dict(mdesc)
    md["blend"] = "off"  # 11.1.4: the arm stops at the end of a compliant move
    ident = yield from _record(task, unit, kind, tg, None, tool, tool_m, md)
    command = arm.queue.history[-1]
    if command.id == ident and command.state != "failed":
        comp.report = task.machine.diags.append
        comp.moves.append(CompliantMove(command, float(force), tool_mm, contact))
    return ident


def I_movejf(task, unit, target, tool, mdesc: dict, force: float):
    """11.1.5 movejf(joint, tool, mdesc, nForce): a compliant joint move; its identifier."""
    return (yield from _compliant(task, unit, "movej", target, tool, mdesc, force))


def I_movelf(task, unit, target, tool, mdesc: dict, force: float):
    """11.1.5 movelf(point, tool, mdesc, nForce): a compliant straight line; its identifier."""
    return (yield from _compliant(task, unit, "movel", target, tool, mdesc, force))


def I_iscompliant(task, unit) -> bool:
    """11.1.5 isCompliant(): the arm is on a compliant move (and no stop holds it)."""
    arm = task.machine.arm
    if not arm.has_model or getattr(arm, "compliance", None) is None or arm.queue_in_use is None:
        return False
    now = task.machine.clock.time_of(task)
    q = arm._sync(now)
    arm.compliance.update(q, arm.layers, now / US)
    return arm.compliance.is_compliant(q, arm.layers, now / US)


def register(registry) -> None:
    """11.1."""
    registry.instruction("movejf", I_movejf, blocking=True)
    registry.instruction("movelf", I_movelf, blocking=True)
    registry.instruction("isCompliant", I_iscompliant)
