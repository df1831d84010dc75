"""The geometry of VAL 3 chapter 9 (joint, trsf, frame, tool, point, config), in plain `math`.

Pure functions and small value/node types; no interpreter state. Runtime errors are raised as
`val3check.language.runtime_errors.Val3RuntimeError(code, detail)` with the codes of 12.1.

Modules
-------
- `rotation`  rotation matrices, VAL 3 angles and their canonical form (9.3.2), quaternions,
              poses (R, p, exact angles); the numerical core.
- `trsf`      `Trsf` and 9.3.3/9.3.4: ``*``, ``!`` (``inverse()``/``~``), ``==``, `distance`,
              `interpolate_l`, `interpolate_c`, `align`.
- `frames`    `Frame`/`Tool` nodes, `new_world()`/`new_flange()`, `position`, `link`, `assign`
              (``=``), errors 160/161/163/164/165.
- `points`    `Point`, `position`, `distance`, `compose`, `appro`, `link`, `assign`,
              `set_frame` (9.4.4); error 162.
- `jointops`  joint ``+ - == != < >``, `abs_`, `herej`, `is_in_range` (9.2).
- `config_values`  config tuples, `same`/`free` resolution (9.7).
- `arm`       the `Kinematics` protocol; `here`, `joint_to_point`, `point_to_joint`,
              `config_of` (9.6.3, 9.7.6).
- `by_val3_name`   the same by VAL 3 name, overloads dispatched on type.

Value shapes for the interpreter
--------------------------------
- ``num``: float. Lengths are in the application's unit (mm or inch, 2.1.4.1); nothing here
  converts. Angles in degrees.
- ``trsf``: `Trsf(x, y, z, rx, ry, rz)`, a mutable slotted class of floats (``tr.x = 5`` is
  fine); operations never return or keep their arguments. `Trsf.from_dict`/`to_dict` convert
  from/to the current ``{"x": .., ..., "rz": ..}`` dicts; `as_tuple()`, iteration.
  ``==`` compares the fields exactly (9.3.3 states no tolerance, unlike joint).
- ``joint``: a tuple of floats (j1..j6, or j1..j4 on RS/TS arms); `jointops.from_dict/to_dict`.
- ``config``: a tuple of strings, ``("lefty", "epositive", "wpositive")`` or ``("righty",)``;
  `config_values.from_dict/to_dict`.
- ``frame``: a `Frame` node ``(trsf, ref, name, local, is_root)``; ``ref`` is the parent node
  (shared by reference, not copied). A frame VARIABLE must hold one node for its whole life:
  ``f1 = f2`` is ``assign(f1_node, f2_node)`` (copies trsf and reference into f1's node, so
  whatever is linked to f1 follows), never a rebinding. ``f.trsf`` field writes go straight to
  the node. Create globals with ``Frame(trsf, ref_node, name=...)`` (``ref_node`` from the
  .dtx reference, world by default) and locals with ``Frame(local=True)`` (no reference).
- ``tool``: a `Tool` node, the same plus ``gripper`` (the interpreter's dio link object; put
  valve1 there for globals, 9.5.1), ``otime``, ``ctime``. open()/close() are the
  interpreter's: waitEndMove, ``tool.gripper`` := true/false, delay(otime/ctime) (9.5.4).
- ``point``: a `Point` ``(trsf, config, ref, name, local)``; ``p1 = p2`` is
  ``points.assign(p1, p2)``; results of compose/appro/here/jointToPoint are new `Point`s to
  assign. A by-value parameter is ``Point.copy()`` / ``frames.copy_node(node, local=True)``.
- ``world``/``flange``: one `new_world()` and one `new_flange()` per application; the
  program may write their fields, the next computation through them raises 161/160.
- ``local=True`` marks nodes/points held by local variables: linking or assigning a global to
  a local reference raises 165.
- Fields can also be read and written by name (``tr["x"]``, ``p["trsf"]``, ``t["otime"]``): the
  interpreter's (container, key) places. The interpreter keeps a point's ``config`` as a dict
  of its fields and converts at the instruction boundary (val3check/interpretation/chapters/ch09_geometry.py).

Kinematics protocol (provided by val3check/robot/)
--------------------------------------------------
``fk(joints_deg) -> (x, y, z, rx, ry, rz)``: the flange in world, length unit and degrees;
``ik(pose, config, near) -> list[joints]``: joint solutions putting the flange at `pose` (same
6-tuple shape), `config` with `same` fields already resolved against `near` (so only concrete
or free values), `near` = jInitial (choose the nearest turn for multi-turn axes), solutions out
of the software limits left out (or the model offers ``in_range``/``in_limits(joints) -> bool``);
``config_of(joints) -> ("lefty", "epositive", "wpositive")`` (9.7.4; RS/TS: ``("righty",)``).
See `arm.Kinematics`.

Calls, by VAL 3 instruction (module `by_val3_name` has them all by their VAL 3 names)
-----------------------------------------------------------------------------------------
=================================  ==========================================================
``tr1 * tr2``, ``!tr``             ``tr1 * tr2``, ``tr.inverse()``
``distance(tr1, tr2)``             ``trsf.distance(tr1, tr2)``
``interpolateL(a, b, s)``          ``trsf.interpolate_l(a, b, s)``  (70 if s not in ]-1, 2[)
``interpolateC(a, m, b, s)``       ``trsf.interpolate_c(a, m, b, s)`` (70: arc undefined, 180°)
``align(tr, ref)``                 ``trsf.align(tr, ref)``
``position(f, fRef)``              ``frames.position(f, fRef)`` (tools likewise)
``link(f, fRef)``                  ``frames.link(f, fRef)``     (tools likewise)
``setFrame(pO, pX, pY, f)``        ``points.set_frame(pO, pX, pY, f) -> 0/1/2``
``position(p, fRef)``              ``points.position(p, fRef)``
``distance(p1, p2)``               ``points.distance(p1, p2)``
``compose(p, fRef, tr)``           ``points.compose(p, fRef, tr)``
``appro(p, tr)``                   ``points.appro(p, tr)``
``link(p, fRef)``                  ``points.link(p, fRef)``
``here(t, fRef)``                  ``arm.here(kin, current_joints, t, fRef)``
``herej()``                        ``jointops.herej(current_joints)``
``jointToPoint(t, fRef, j)``       ``arm.joint_to_point(kin, t, fRef, j)``
``pointToJoint(t, jI, p, jR)``     ``ok, j = arm.point_to_joint(kin, t, jI, p)``; if ok: jR = j
``config(j)``                      ``arm.config_of(kin, j)``
``abs(j)``, ``j1 < j2``, ...       ``jointops.abs_``, ``lt``, ``gt``, ``eq``, ``ne``, ``add``, ``sub``
``isInRange(j)``                   ``jointops.is_in_range(j, limits)``
=================================  ==========================================================
"""

from __future__ import annotations

from .arm import Kinematics
from .frames import Frame, Tool, new_flange, new_world
from .points import Point
from .trsf import Trsf

__all__ = ["Frame", "Kinematics", "Point", "Tool", "Trsf", "new_flange", "new_world"]
