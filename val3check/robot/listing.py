"""What `val3check robots` prints: the catalogue by family, or one model with its provenance."""

from __future__ import annotations

from .models import RobotModel

SERIES_TITLES = {
    "TX": "TX six-axis arms (CS8)",
    "TX2": "TX2 six-axis arms (CS9)",
    "RX": "RX six-axis arms",
    "TS2": "TS2 SCARA arms (CS9)",
    "TS": "TS SCARA arms (CS8)",
    "TP": "TP fast picker (four-axis, ceiling-mounted)",
}
TYPES = {"Rx": "pointRx, jointRx, configRx", "Rs": "pointRs, jointRs, configRs"}


def _n(v: float) -> str:
    return f"{v:g}"


def _range(lo: float, hi: float) -> str:
    return f"±{_n(hi)}" if lo == -hi else f"{_n(lo)}..{_n(hi)}"


def _table(head: list[str], rows: list[list[str]], right: bool = False, indent: str = "") -> list[str]:
    widths = [max(len(r[i]) for r in [head] + rows) for i in range(len(head))]
    return [indent + "  ".join((c.rjust(w) if right and k else c.ljust(w)) for k, (c, w) in enumerate(zip(r, widths))).rstrip()
            for r in [head] + rows]


def _arm_id(m: RobotModel) -> str:
    if m.srs_arm_id:
        return m.srs_arm_id
    return f"{m.srs_arm_id_hint}?" if m.srs_arm_id_hint else "-"


def _assumed_keys(m: RobotModel) -> str:
    short = {"ramp_s": "accel", "accelerations": "accel", "nominal_speeds": "speeds", "world_z_mm": "world",
             "axis4_sign": "j4 sign", "axis3_sign": "j3 sign", "stroke_mm": "stroke", "mount": "mount"}
    keys = []
    for a in m.provenance.assumptions:
        k = short.get(a.key, a.key)
        if k not in keys:
            keys.append(k)
    return ", ".join(keys) or "-"


def render_list(models: list[RobotModel], known_without_model: list[dict] | None = None) -> str:
    groups: dict[str, list[RobotModel]] = {}
    for m in models:
        groups.setdefault(m.series or ("other six-axis" if m.family == "six-axis" else "other SCARA"), []).append(m)
    lines: list[str] = []
    for series, members in groups.items():
        scara = members[0].family == "scara"
        axes = 4 if scara else 6
        head = ["arm", "arm.cfx", "reach"] + (["stroke"] if scara else []) + [f"j{i}" for i in range(1, axes + 1)] + ["assumed"]
        rows = []
        for m in members:
            star = "*" if "nominal_speeds" in m.assumed else ""
            cells = [m.name, _arm_id(m), f"{m.reach_mm:g} mm"] + ([f"{m.stroke_mm:g} mm"] if scara else [])
            for (lo, hi), v, u in zip(m.joint_limits, m.nominal_speeds, m.joint_units):
                unit = "°" if u == "deg" else " mm"
                cells.append(f"{_range(lo, hi)}{unit} {_n(v)}{'°' if u == 'deg' else ' mm'}/s{star}")
            cells.append(_assumed_keys(m))
            rows.append(cells)
        title = SERIES_TITLES.get(series, series)
        lines.append(f"{title}: VAL 3 types {TYPES[members[0].type_family]}")
        lines += _table(head, rows)
        lines.append("")
    if known_without_model:
        lines.append("Stäubli arms without public kinematic data (no model; arm.cfx ids name the closest one)")
        lines += _table(["arm", "arm.cfx", "closest model"], [[k["arm"], k["id"], k["closest"]] for k in known_without_model])
        lines.append("")
    lines.append("Joint ranges in degrees (mm for a SCARA's axis 3) and nominal speeds per second; reach from axis 1 to the")
    lines.append("flange, arm stretched. * speed assumed (not public). ? arm id inferred, not seen in a real arm.cfx.")
    lines.append("`assumed` lists what is not public: `val3check robots NAME` shows one model's facts with their sources, its")
    lines.append("assumptions and where sources disagree; --robot NAME|URDF|robot file picks it (robots/README.md).")
    return "\n".join(lines) + "\n"


def render_detail(m: RobotModel) -> str:
    scara = m.family == "scara"
    first = f"{m.name}" + (f"  (arm.cfx: {_arm_id(m)})" if m.srs_arm_id or m.srs_arm_id_hint else "")
    kind = "SCARA (RS/TS, manual 9.7.5)" if scara else "six-axis arm (RX/TX)"
    out = [first, f"{kind}: VAL 3 types {TYPES[m.type_family]}", f"model: {m.source}",
           f"reach: {m.reach_mm:g} mm (axis 1 to the flange, arm stretched)"
           + (f"; axis 3 stroke {m.stroke_mm:g} mm" if scara and m.stroke_mm else ""),
           f"mount: {m.mount}", ""]
    sp = "*" if "nominal_speeds" in m.assumed else ""
    ac = "*" if m.accelerations_assumed else ""
    if scara:
        head = ["axis", "unit", "min", "max", "speed /s", "accel /s²", "torque"]
        rows = [[f"j{i + 1}", "mm" if u == "mm" else "°", _n(lo), _n(hi), _n(v) + sp, _n(a) + ac, "-" if t is None else _n(t)]
                for i, ((lo, hi), v, a, t, u) in enumerate(zip(m.joint_limits, m.nominal_speeds, m.accelerations,
                                                               m.max_torques, m.joint_units))]
    else:
        head = ["axis", "min °", "max °", "speed °/s", "accel °/s²", "torque N·m"]
        rows = [[f"j{i + 1}", _n(lo), _n(hi), _n(v) + sp, _n(a) + ac, "-" if t is None else _n(t)]
                for i, ((lo, hi), v, a, t) in enumerate(zip(m.joint_limits, m.nominal_speeds, m.accelerations, m.max_torques))]
    out += _table(head, rows, right=True)
    out += ["", f"accelerations: {m.acceleration_note}" + ("; no measured values: a cycle time holds within the "
                                                          "range of accelerations ½ to 2 times these" if ac else "")]
    o, sc = m.opw, m.scara
    if o is not None:
        out.append(
            "kinematics: ortho-parallel base, spherical wrist (closed-form inverse, 8 branches); "
            f"a1={_n(o.a1)} a2={_n(o.a2)} b={_n(o.b)} c1={_n(o.c1)} c2={_n(o.c2)} c3={_n(o.c3)} c4={_n(o.c4)} mm"
        )
    elif sc is not None:
        out.append(f"kinematics: SCARA, closed-form inverse (2 branches: righty when sin(j2) > 0, lefty otherwise, 9.7.5); "
                   f"l1={_n(round(sc.l1, 9))} l2={_n(round(sc.l2, 9))} mm, flange at z={_n(round(sc.z0, 9) + 0.0)} mm "
                   "in world when j3 = 0")
    else:
        out.append(f"kinematics: forward only; no closed-form inverse ({m.opw_reason})")
    if o is not None or sc is not None:
        z = m.fk([0.0] * m.axes)
        out.append("here(flange, world) at zero: {" + ", ".join(_n(round(v, 9) + 0.0) for v in z) + "}")
    pv = m.provenance
    if pv.facts:
        out += ["", "public facts (source of each value):"]
        out += _table(["", ""], [[f.key, f.text] for f in pv.facts], indent="  ")[1:]
    if pv.assumptions:
        out += ["", "assumptions (not public: stated here, never facts; set your own values in a robot file, "
                    "robots/README.md \"Your values\"):"]
        for a in pv.assumptions:
            who = "" if a.by == "model" else f" [{a.by}]"
            out.append(f"  {a.key} = {a.value}{who}: {a.text}")
    if pv.alternatives:
        out += ["", "where sources disagree (the model's value, then the other):"]
        for a in pv.alternatives:
            out.append(f"  {a.key}: {a.chosen} (kept), {a.other} (other): {a.text}")
    if pv.missing:
        out += ["", "not public (absent from the model):"]
        out += [f"  {x.key}: {x.text}" for x in pv.missing]
    if pv.references:
        out += ["", "sources:"]
        out += [f"  {r.key}: {r.text}" for r in pv.references]
    if m.notes:
        out += ["", "chosen from:"]
        out += [f"  {n}" for n in m.notes]
    return "\n".join(out) + "\n"
