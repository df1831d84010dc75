"""Text output of `val3check robots`."""

from __future__ import annotations

from ..robot.models import RobotModel


def _n(v: float) -> str:
    return f"{v:g}"


def _range(lo: float, hi: float) -> str:
    return f"±{_n(hi)}" if lo == -hi else f"{_n(lo)}..{_n(hi)}"


def render_list(models: list[RobotModel]) -> str:
    head = ["arm", "arm.cfx", "reach"] + [f"j{i}" for i in range(1, 7)]
    rows = []
    for m in models:
        cells = [m.name, m.srs_arm_id or "-", f"{m.reach_mm:g} mm"]
        cells += [f"{_range(lo, hi)}° {_n(v)}°/s" for (lo, hi), v in zip(m.joint_limits, m.nominal_speeds)]
        rows.append(cells)
    widths = [max(len(r[i]) for r in [head] + rows) for i in range(len(head))]
    lines = ["  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip() for r in [head] + rows]
    lines.append("")
    lines.append("Joint limits in degrees and nominal speeds in degrees per second; reach from axis 1 to the")
    lines.append("flange, arm stretched. `val3check robots NAME` shows one model; --robot NAME|URDF picks it.")
    return "\n".join(lines) + "\n"


def render_detail(m: RobotModel) -> str:
    out = [f"{m.name}" + (f"  (arm.cfx: {m.srs_arm_id})" if m.srs_arm_id else ""), f"model: {m.source}",
           f"reach: {m.reach_mm:g} mm (axis 1 to the flange, arm stretched)", ""]
    head = ["axis", "min °", "max °", "speed °/s", "accel °/s²", "torque N·m"]
    rows = [
        [f"j{i + 1}", _n(lo), _n(hi), _n(v), _n(a), "-" if t is None else _n(t)]
        for i, ((lo, hi), v, a, t) in enumerate(zip(m.joint_limits, m.nominal_speeds, m.accelerations, m.max_torques))
    ]
    widths = [max(len(r[i]) for r in [head] + rows) for i in range(len(head))]
    out += ["  ".join(c.rjust(w) if k else c.ljust(w) for k, (c, w) in enumerate(zip(r, widths))) for r in [head] + rows]
    out += ["", f"accelerations: {m.acceleration_note}"]
    o = m.opw
    if o is not None:
        out.append(
            "kinematics: ortho-parallel base, spherical wrist (closed-form inverse, 8 branches); "
            f"a1={_n(o.a1)} a2={_n(o.a2)} b={_n(o.b)} c1={_n(o.c1)} c2={_n(o.c2)} c3={_n(o.c3)} c4={_n(o.c4)} mm"
        )
        z = m.fk([0.0] * 6)
        out.append("here(flange, world) at zero: {" + ", ".join(_n(round(v, 9) + 0.0) for v in z) + "}")
    else:
        out.append(f"kinematics: forward only; no closed-form inverse ({m.opw_reason})")
    return "\n".join(out) + "\n"
