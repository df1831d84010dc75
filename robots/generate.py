#!/usr/bin/env python3
"""Write the Stäubli arm models (`robots/*.urdf`, `robots/catalog.toml`) from the public facts.

    python robots/generate.py                 # (re)write robots/*.urdf and robots/catalog.toml
    python robots/generate.py --check         # exit 1 if a written file differs from what it would write
    python robots/generate.py --toml PATH --more PATH   # other copies of the facts

The facts come from `../shared/robots/staubli-arms.toml` (twelve six-axis arms, from the public
ROS-Industrial descriptions that quote Stäubli's data sheets) and `staubli-arms-more.toml`
(nineteen more arms, six-axis and SCARA, every number with its source S1..S9). Everything else
written here is this project's choice, stated as such in each model (`<assumption>` in the URDF's
<val3check> element, printed by `val3check robots NAME`, overridable by the user) and in
robots/README.md: the accelerations, the speeds no source gives, a SCARA's world frame and the
sign of its axis 4, the collision solids (cylinders sized per family, no meshes), the frame names.
Where sources disagree the model keeps one value and says which, why, and the other
(`<alternative>`).

Nothing here is imported by val3check at run time: the URDF files and catalog.toml are the models.
Each URDF also stores its arm's allowed-collision matrix, computed here by val3check/collision/acm.py
(`with_acm`; the `sim` extra is needed to run this script).
"""

from __future__ import annotations

import argparse
import math
import re
import sys
import tomllib
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import dynamics  # noqa: E402  (robots/dynamics.py: the speed and acceleration rules)


def _facts_dir() -> Path:
    """shared/robots beside the checkout (or beside a folder of worktrees holding it)."""
    for folder in HERE.parents:
        if (folder / "shared" / "robots").is_dir():
            return folder / "shared" / "robots"
    return HERE.parent.parent / "shared" / "robots"


FACTS = _facts_dir()
DEFAULT_TOML = FACTS / "staubli-arms.toml"
MORE_TOML = FACTS / "staubli-arms-more.toml"

# Acceleration assumption of the six-axis arms (robots/dynamics.py, robots/README.md): the nominal
# acceleration of a joint takes it from rest to its nominal speed in RAMP_S seconds. SCARA arms:
# dynamics.scara(reach), fitted to Stäubli's TS2 standard cycles.
RAMP_S = dynamics.SIX_AXIS_RAMP_S

# The catalogue, grouped by series (`val3check robots` keeps this order).
SERIES = {
    "TX": ("six-axis", "TX six-axis arms (CS8)"),
    "TX2": ("six-axis", "TX2 six-axis arms (CS9)"),
    "RX": ("six-axis", "RX six-axis arms"),
    "TS2": ("scara", "TS2 SCARA arms (CS9)"),
    "TS": ("scara", "TS SCARA arms (CS8)"),
    "TP": ("scara", "TP fast picker (four axes, ceiling)"),
}
ORDER = [
    "TX40", "TX60", "TX60L", "TX90", "TX90L", "TX90XL", "TX200", "TX200L",
    "TX2-40", "TX2-60", "TX2-60L", "TX2-90", "TX2-90L", "TX2-90XL", "TX2-140", "TX2-160", "TX2-160L",
    "RX90B", "RX90BL", "RX130B", "RX160", "RX160L",
    "TS2-40", "TS2-60", "TS2-80", "TS2-100", "TS2-100-L400",
    "TS40", "TS60", "TS80",
    "TP80",
]

# The sources of staubli-arms-more.toml, in short (its header has them in full).
REFERENCES = {
    "ROS-I": "ROS-Industrial Stäubli descriptions (github:ros-industrial/staubli, staubli_experimental), quoting "
             "Stäubli data sheets; gathered in shared/robots/staubli-arms.toml",
    "S1": "RoboDK robot library as copied into github:SaltworkerMLU/robotkinematicscatalogue@ea88ef98 (modified DH)",
    "S2": "github:ros-industrial/staubli_experimental@944764d4 (PR 54, TX2-160L; quotes data sheet D18180602_DE)",
    "S3": "github:bourumir-wyngs/rs-opw-kinematics@fb51d85b src/parameters_robots.rs (OPW sets)",
    "S4": "github:Jmeyer1292/opw_kinematics@8a32bda8 opw_parameters_examples.h",
    "S5": "github:4rtur1t0/ARTE@a8df0b12 robots/STAUBLI/*/parameters.m (educational toolbox)",
    "S6": "controller trees with usr/configs/arm.cfx: psi46/cmsrobot (ts2_60-S1), dc170/Staubli-TS60-RobotProgramming "
          "(ts60-S1), trigrass2/Val3_Polish (tx200-S3)",
    "S7": "CODESYS Staubli_Transformation library documentation (function block names only)",
    "S8": "github:glowbuzzer/gbr@0602bb72 (TS2-40 links)",
    "S9": "github:lequyphuong1903/robotics-staubliTS40simulation@c20c6fd5 (TS40 links)",
}

# ---- assumptions (robots/README.md, "Assumptions") ------------------------------------------------

# Speeds no source gives, borrowed from the closest arm that has them: (from, why).
SPEEDS_FROM = {
    "TX2-40": ("TX40", "the TX40 (S5 ARTE TX40/parameters.m 'maximum absolute speed'): same geometry, its predecessor"),
    "TX2-140": ("TX2-160L", "the TX2-160L (S2, data sheet of the TX2-140/160 family): the family's only published figures; "
                            "the longest arm of the family, so cycle times err long"),
    "TX2-160": ("TX2-160L", "the TX2-160L (S2, data sheet of the TX2-140/160 family): same arm and family; the longer "
                            "forearm is slower, so cycle times err long"),
    "RX90B": ("TX90", "the TX90 (ROS-Industrial): the arm of the same size that succeeded it"),
    "RX90BL": ("TX90L", "the TX90L (ROS-Industrial): the arm of the same size that succeeded it"),
    "RX130B": ("RX160", "the RX160 (ROS-Industrial): the closest RX arm with published speeds (a larger one: cycle times "
                        "err long)"),
}

SCARA_WORLD = (
    "No public source places an RS/TS arm's world frame. Assumed: on axis 1, X along the arm stretched out at "
    "j1 = j2 = 0, Z up, and z = 0 at the flange face when j3 = 0 (the taught points of the real TS2-60 and TS60 "
    "controller trees of S6 fit a world z = 0 within about 60 mm of that height; nothing states it). Set the flange "
    "height at j3 = 0 in your world with world_z_mm"
)
SCARA_AXIS4 = (
    "Positive j4 turns the flange about its own Z axis (pointing down), clockwise seen from above: S1's convention "
    "(its row 4 has alpha = 180 deg); no Stäubli document checked. axis4_sign = 1 turns it the other way"
)
ACCEL_TEXT = dynamics.six_axis_text()
MOUNT_NOTE = ("the VAL 3 world frame is attached to the arm's base; the mount (arm.cfx, or an override) only places "
              "it in the cell")

# Where sources disagree: the model keeps `chosen` (the facts' value) and shows `other`.
ALTERNATIVES = {
    "TX2-60": [("limits.j3", "-152.5..152.5", "-142.5..142.5",
                "ROS-Industrial (Stäubli data sheet) against S1 (RoboDK); S1 gives the TX60's ±142.5 here but ±152.5 "
                "for the TX2-60L, which shares the joint: the data-sheet value is kept")],
    "TX60": [("limits.j5", "-122.5..132.5", "-122.5..133.5",
              "ROS-Industrial (Stäubli data sheet) against S1 (RoboDK): the data-sheet value is kept")],
    "TX60L": [("limits.j3", "-152.5..152.5", "-142.5..142.5",
               "ROS-Industrial (Stäubli data sheet) against S1 (RoboDK): the data-sheet value is kept"),
              ("limits.j5", "-122.5..132.5", "-122.5..133.5",
               "ROS-Industrial (Stäubli data sheet) against S1 (RoboDK): the data-sheet value is kept")],
    "TX2-160L": [("limits.j2", "-137.5..137.5", "-130..147.5",
                  "S2 quotes the 2021 data sheet D18180602 of the TX2-140/160 family; S1's ranges are those of its "
                  "TX2-90/TX2-140 files: S2 is kept"),
                 ("limits.j3", "-160..160", "-145..145", "as for j2: S2 (data sheet) kept, S1 shown"),
                 ("limits.j5", "-110..135", "-110..140", "as for j2: S2 (data sheet) kept, S1 shown"),
                 ("world_height_mm", "550", "375",
                  "S2 puts its world ('base') frame 375 mm above the mounting plane, the TX2-60's value, while its own "
                  "joint 1 is at 550 mm; S1 agrees with 550: 550 is kept")],
    "TX200": [("a1_mm", "250", "257",
               "S1, S5's TX200L and the burtasun TX200 description give 250, S5's TX200 alone 257: 250 is kept"),
              ("c4_mm", "194", "190",
               "S1 and S5 give 194; the burtasun description 190, but its limits and speeds are the TX90's copied "
               "verbatim: 194 is kept")],
    "TS2-100": [("limits.j2", "-141.5..141.5", "-160..160",
                 "S1 gives ±141.5 for the 200 mm stroke (FL200) and ±160 for its HB FL400 file (TS2-100-L400); this "
                 "model is the FL200 one")],
    "TS2-100-L400": [("limits.j2", "-160..160", "-141.5..141.5",
                      "S1's HB FL400 file gives ±160, its FL200 file ±141.5: this model is the FL400 one")],
    "TP80": [("axis3_sign", "1 (up)", "-1 (down)",
              "S1 adds j3 along +Z (the quill rises as j3 grows, as for the other SCARA arms); S5 ARTE turns Z down "
              "at joint 2 so that j3 lowers the flange: S1 kept, like the TS/TS2 arms"),
             ("axis4_sign", "-1 (about the flange Z, down)", "1 (about +Z, up)",
              "S1 turns joint 4 about the flange's Z (down); S5 ARTE about +Z: S1 kept, like the other SCARA arms")],
}

# Arm ids of Stäubli arms that have no public kinematic data: (id, arm, closest model, why).
KNOWN_WITHOUT_MODEL = [
    ("tx2_200", "TX2-200", "TX200", "the TX2-200 exists (S7 names a tx2_200_S3_R1 model) but no public source gives "
                                    "its geometry; the TX200 is the closest arm of that size"),
    ("tx2_200l", "TX2-200L", "TX200L", "the TX2-200L exists (S7 names a tx2_200l_S3_R1 model) but no public source "
                                       "gives its geometry; the TX200L is the closest arm of that size"),
]

# ---- collision solids ----------------------------------------------------------------------------

# Six-axis: radii in millimetres per size class (robots/README.md, "Collision geometry").
#   base: fixed base column; shoulder: housing of axes 1-2; arm: upper arm (link 2);
#   elbow: housing of axis 3; fore: forearm (axis 4 tube); wrist: axes 5-6 housing; flange: tool flange.
SIZES = {
    "xsmall": dict(base=90, shoulder=90, arm=65, elbow=60, fore=52, wrist=42, flange=25),
    "small": dict(base=110, shoulder=110, arm=80, elbow=75, fore=65, wrist=50, flange=32),
    "medium": dict(base=160, shoulder=150, arm=110, elbow=100, fore=90, wrist=65, flange=40),
    "large": dict(base=230, shoulder=200, arm=150, elbow=140, fore=120, wrist=90, flange=63),
    "xlarge": dict(base=320, shoulder=280, arm=200, elbow=180, fore=160, wrist=120, flange=80),
}
# SCARA: base column, the two arms (cylinders lying along them), the quill (axis 3/4 shaft), flange.
SCARA_SIZES = {
    "small": dict(base=90, arm=55, quill=14, flange=25),
    "medium": dict(base=110, arm=70, quill=16, flange=30),
    "large": dict(base=130, arm=85, quill=20, flange=35),
}
SCARA_CLEARANCE = 40.0  # mm between the flange at the top of its stroke and the underside of arm 2 (estimate)
FLANGE_THICKNESS = 10.0


def size_class(arm: dict) -> str:
    c2 = arm["joint3"]["origin_mm"][2]
    a1 = arm["joint2"]["origin_mm"][0]
    if c2 >= 900:
        return "xlarge"
    if a1 >= 150:
        return "large"
    if c2 >= 420 or a1 >= 50:
        return "medium"
    if c2 >= 280:
        return "small"
    return "xsmall"


def scara_size_class(arm: dict) -> str:
    reach = arm["link1_mm"] + arm["link2_mm"]
    return "small" if reach <= 460 else "medium" if reach <= 650 else "large"


def slug(name: str) -> str:
    return name.lower()


def series_of(name: str) -> str:
    m = re.match(r"^(TX2(?=-)|TX|RX|TS2(?=-)|TS|TP)-?\d", name)
    if not m:
        raise SystemExit(f"{name}: no known series (TX, TX2, RX, TS, TS2, TP)")
    return m.group(1)


def _f(v: float) -> str:
    """Shortest exact text for a float (repr round-trips); integers without '.0'."""
    if float(v).is_integer():
        return str(int(v))
    return repr(float(v))


def _m(mm: float) -> str:
    return _f(round(mm / 1000.0, 12))


def _xyz_m(v) -> str:
    return " ".join(_m(c) for c in v)


def _x(text: str) -> str:
    """XML attribute text."""
    return text.replace("&", "&amp;").replace('"', "&quot;").replace("<", "&lt;").replace(">", "&gt;")


def _cyl(radius_mm: float, length_mm: float, xyz_mm, rpy: str = "0 0 0", name: str = "") -> list[str]:
    """A cylinder as both collision and visual element (URDF cylinders lie along their local z)."""
    out = []
    for tag in ("collision", "visual"):
        label = f' name="{name}"' if name else ""
        out += [
            f"    <{tag}{label}>",
            f'      <origin xyz="{_xyz_m(xyz_mm)}" rpy="{rpy}"/>',
            f'      <geometry><cylinder radius="{_m(radius_mm)}" length="{_m(length_mm)}"/></geometry>',
        ]
        if tag == "visual":
            out.append('      <material name="staubli_yellow"/>' if name != "flange" else '      <material name="grey"/>')
        out.append(f"    </{tag}>")
    return out


ALONG_Y = f"{_f(math.pi / 2)} 0 0"  # cylinder axis along the link's y (axes 2, 3, 5)
ALONG_X = f"0 {_f(math.pi / 2)} 0"  # cylinder axis along the link's x (the arms of a SCARA)


def collision_solids(arm: dict) -> dict[str, list[tuple]]:
    """Six-axis, per link: (name, radius, length, centre xyz in the link frame (mm), rpy)."""
    r = SIZES[size_class(arm)]
    h = arm["shoulder_height_mm"]
    a1 = arm["joint2"]["origin_mm"][0]
    b = arm["joint3"]["origin_mm"][1]
    c2 = arm["joint3"]["origin_mm"][2]
    c3 = arm["joint4"]["origin_mm"][2] + arm["joint5"]["origin_mm"][2]
    c4 = arm["joint6"]["origin_mm"][2]
    base_len = h - r["shoulder"]
    return {
        "base_link": [("base", r["base"], base_len, (0, 0, base_len / 2), "0 0 0")],
        # shoulder housing turning with axis 1: a vertical drum around axis 1 that also covers axis 2
        "link_1": [("shoulder", r["shoulder"] + a1, 2 * r["shoulder"], (0, 0, 0), "0 0 0")],
        # upper arm: from axis 2 to axis 3 plus the joint housings at both ends, and the axis 2 boss
        "link_2": [
            ("upper_arm", r["arm"], c2 + 2 * r["arm"], (0, b / 2, c2 / 2), "0 0 0"),
            ("shoulder_boss", r["arm"], 2 * r["arm"] + abs(b), (0, b / 2, 0), ALONG_Y),
        ],
        # elbow housing around axis 3
        "link_3": [("elbow", r["elbow"], 2 * r["elbow"], (0, 0, 0), ALONG_Y)],
        # forearm tube turning with axis 4, from the elbow to the wrist housing (which covers the
        # wrist centre): ending there lets the flange turn to 90 degrees beside it, as on the arm
        "link_4": [("forearm", r["fore"], c3 - r["wrist"], (0, 0, (c3 - r["wrist"]) / 2), "0 0 0")],
        # wrist: housing around axis 5 and the part between the wrist centre and the flange
        "link_5": [
            ("wrist", r["wrist"], 2 * r["wrist"], (0, 0, 0), ALONG_Y),
            ("wrist_nose", r["flange"] + 8, c4, (0, 0, c4 / 2), "0 0 0"),
        ],
        "link_6": [("flange", r["flange"], FLANGE_THICKNESS, (0, 0, -FLANGE_THICKNESS / 2), "0 0 0")],
    }


def scara_collision_solids(arm: dict) -> dict[str, list[tuple]]:
    """SCARA, per link (frames: base_link at the facts' base; link_1/link_2 at axes 1/2 in that
    plane; link_3/link_4 on axis 4 at the flange's height): the arms lie at an estimated level
    just above the flange's highest position."""
    r = SCARA_SIZES[scara_size_class(arm)]
    l1, l2, stroke = arm["link1_mm"], arm["link2_mm"], arm["stroke_mm"]
    z0 = arm["flange_z_at_j3_zero_mm"]
    level = z0 + stroke + SCARA_CLEARANCE + r["arm"]  # the arms' centre line
    lo, hi = min(0.0, level - r["arm"]), max(0.0, level + r["arm"])
    quill = stroke + SCARA_CLEARANCE + 2 * r["arm"]
    return {
        "base_link": [("base", r["base"], hi - lo, (0, 0, (hi + lo) / 2), "0 0 0")],
        "link_1": [("arm_1", r["arm"], l1 + 2 * r["arm"], (l1 / 2, 0, level), ALONG_X)],
        "link_2": [("arm_2", r["arm"], l2 + 2 * r["arm"], (l2 / 2, 0, level), ALONG_X)],
        "link_3": [("quill", r["quill"], quill, (0, 0, quill / 2), "0 0 0")],
        "link_4": [("flange", r["flange"], FLANGE_THICKNESS, (0, 0, FLANGE_THICKNESS / 2), "0 0 0")],
    }


# ---- the facts, one record per arm ---------------------------------------------------------------


def load_facts(toml: Path, more: Path) -> dict[str, dict]:
    """name -> the arm's facts, with "origin" ("ROS-I" or "more") and its sources."""
    arms: dict[str, dict] = {}
    for path, origin in ((toml, "ROS-I"), (more, "more")):
        with open(path, "rb") as fh:
            data = tomllib.load(fh)
        for name, arm in data.items():
            if name in arms:
                raise SystemExit(f"{name}: in both {toml.name} and {more.name}")
            arms[name] = dict(arm, origin=origin)
    missing = [n for n in ORDER if n not in arms]
    extra = [n for n in arms if n not in ORDER]
    if missing or extra:
        raise SystemExit(f"ORDER does not match the facts: missing {missing}, not placed {extra}")
    return {n: arms[n] for n in ORDER}


def _srs(arm: dict) -> tuple[str, bool]:
    if "srs_arm_id" in arm:
        return arm["srs_arm_id"], True
    return arm.get("srs_arm_id_hint", ""), False


def _sources(name: str, arm: dict) -> list[tuple[str, str]]:
    if arm["origin"] == "ROS-I":
        ros = "ROS-I: the ROS-Industrial description, quoting Stäubli's data sheet (staubli-arms.toml)"
        return [("geometry", ros), ("limits", ros), ("speeds", ros), ("torques", ros),
                ("srs_arm_id", "staubli-arms.toml (no real CS9 arm.cfx seen: tx2-60 or tx2_60, both are accepted)")]
    src = arm["sources"]
    return [(k, src[k]) for k in ("geometry", "limits", "speeds", "torques", "opw", "srs_arm_id") if k in src]


def _refs(texts: list[str]) -> list[str]:
    used = set()
    for t in texts:
        used |= set(re.findall(r"\b(S\d|ROS-I)\b", t))
        if "ROS-Industrial" in t:
            used.add("ROS-I")
    return [k for k in REFERENCES if k in used]


def provenance_lines(name: str, arm: dict, assumptions: list[tuple[str, str, str]], missing: list[tuple[str, str]]) -> list[str]:
    facts = _sources(name, arm)
    if name in dynamics.PUBLISHED_CYCLES:  # the figure the SCARA rule is fitted to
        cpm = dynamics.PUBLISHED_CYCLES[name]
        facts.append(("standard_cycle", f"{cpm} cycles per minute ({60 / cpm:.3f} s): {dynamics.CYCLE_SOURCE}"))
    lines = [f'    <fact key="{k}" text="{_x(t)}"/>' for k, t in facts]
    alts = ALTERNATIVES.get(name, [])
    texts = [t for _, t in facts] + [t for *_, t in alts] + [t for *_, t in assumptions]
    lines += [f'    <reference id="{k}" text="{_x(REFERENCES[k])}"/>' for k in _refs(texts)]
    lines += [f'    <assumption key="{k}" value="{_x(v)}" text="{_x(t)}"/>' for k, v, t in assumptions]
    lines += [f'    <alternative key="{k}" chosen="{_x(c)}" other="{_x(o)}" text="{_x(t)}"/>' for k, c, o, t in alts]
    lines += [f'    <missing key="{k}" text="{_x(t)}"/>' for k, t in missing]
    return lines


def six_axis_speeds(name: str, arm: dict, arms: dict[str, dict]) -> tuple[list[float], tuple[str, str] | None]:
    if all("nominal_speed_deg_s" in arm[f"joint{i}"] for i in range(1, 7)):
        return [arm[f"joint{i}"]["nominal_speed_deg_s"] for i in range(1, 7)], None
    src, why = SPEEDS_FROM[name]
    return [arms[src][f"joint{i}"]["nominal_speed_deg_s"] for i in range(1, 7)], (src, why)


# ---- URDF ----------------------------------------------------------------------------------------


def _header(name: str, kind: str, arm: dict, extra_attrs: str, rule: str) -> list[str]:
    srs, confirmed = _srs(arm)
    srs_attr = f'srs_arm_id="{srs}"' if confirmed else f'srs_arm_id_hint="{srs}"'
    source = "shared/robots/staubli-arms.toml" if arm["origin"] == "ROS-I" else "shared/robots/staubli-arms-more.toml"
    return [
        '<?xml version="1.0"?>',
        f"<!-- Stäubli {name}: generated by robots/generate.py from {source}; do not edit by hand. -->",
        "<!-- Units: metres, radians (URDF). val3check reads the <val3check> element below; other tools ignore it. -->",
        f'<robot name="staubli_{slug(name).replace("-", "_")}">',
        '  <material name="staubli_yellow"><color rgba="0.96 0.76 0.13 1"/></material>',
        '  <material name="grey"><color rgba="0.6 0.6 0.6 1"/></material>',
        "",
        f'  <val3check arm="{name}" kind="{kind}" series="{series_of(name)}" {srs_attr}{extra_attrs} world_frame="world" flange_frame="flange"',
        f'             acceleration_rule="{_x(rule)}">',
    ]


def _links(solids: dict[str, list[tuple]]) -> list[str]:
    lines = []
    for link, items in solids.items():
        lines.append(f'  <link name="{link}">')
        for sname, radius, length, xyz, rpy in items:
            lines += _cyl(radius, length, xyz, rpy, sname)
        lines.append("  </link>")
    return lines


def urdf(name: str, arm: dict, arms: dict[str, dict]) -> str:
    """A six-axis arm."""
    h = arm["shoulder_height_mm"]
    if arm["joint1"]["origin_mm"] != [0, 0, h]:
        raise SystemExit(f"{name}: joint 1 is not on the world frame's vertical (shoulder_height_mm)")
    speeds, borrowed = six_axis_speeds(name, arm, arms)
    torques = [arm[f"joint{i}"].get("max_torque_nm") for i in range(1, 7)]
    assumptions = [("ramp_s", _f(RAMP_S), ACCEL_TEXT)]
    if borrowed:
        assumptions.append(("nominal_speeds", " ".join(_f(v) for v in speeds),
                            f"No public source gives the {name}'s joint speeds (deg/s): those of {borrowed[1]}"))
    missing = [] if all(t is not None for t in torques) else [("max_torques", "no public source gives this arm's joint torques")]
    lines = _header(name, "six-axis", arm, "", f"nominal speed reached in {_f(RAMP_S)} s from rest (assumed: not "
                    "published by Staubli; no public figure constrains it)")
    for i in range(1, 7):
        acc = speeds[i - 1] / RAMP_S
        torque = f' max_torque_nm="{_f(torques[i - 1])}"' if torques[i - 1] is not None else ""
        lines.append(f'    <joint name="joint_{i}" nominal_speed_deg_s="{_f(speeds[i - 1])}" acceleration_deg_s2="{_f(acc)}"{torque}/>')
    lines += provenance_lines(name, arm, assumptions, missing)
    # Link pairs never checked against each other besides those val3check computes (adjacent, always
    # or never in collision: robots/README.md, "Allowed collisions"): where these cylinders, centred
    # on the arm's plane, meet while the real casings pass beside each other.
    lines += [
        '    <disable_collisions link1="base_link" link2="link_2" reason="user"/>'
        "  <!-- the upper arm swings beside the base column -->",
        '    <disable_collisions link1="link_4" link2="link_6" reason="user"/>'
        "  <!-- the flange turns inside the forearm's fork -->",
    ]
    lines.append("  </val3check>")
    lines.append("")
    lines += _links(collision_solids(arm))
    for i in range(1, 7):
        j = arm[f"joint{i}"]
        parent = "base_link" if i == 1 else f"link_{i - 1}"
        lo, hi = math.radians(j["min_deg"]), math.radians(j["max_deg"])
        vel = math.radians(speeds[i - 1])
        effort = torques[i - 1] if torques[i - 1] is not None else 0
        lines += [
            f'  <joint name="joint_{i}" type="revolute">',
            f'    <parent link="{parent}"/>',
            f'    <child link="link_{i}"/>',
            f'    <origin xyz="{_xyz_m(j["origin_mm"])}" rpy="0 0 0"/>',
            f'    <axis xyz="{" ".join(_f(a) for a in j["axis"])}"/>',
            f'    <!-- {_f(j["min_deg"])} .. {_f(j["max_deg"])} deg, {_f(speeds[i - 1])} deg/s{" (assumed)" if borrowed else ""} -->',
            f'    <limit lower="{_f(lo)}" upper="{_f(hi)}" velocity="{_f(vel)}" effort="{_f(effort)}"/>',
            "  </joint>",
        ]
    # VAL 3 frames. world: on axis 1 at the height of axis 2; flange: the joint 6 frame (Z out of the flange).
    lines += [
        "",
        "  <!-- VAL 3 world frame: on axis 1 at the height of axis 2 (shoulder_height_mm above the mounting plane). -->",
        '  <link name="world"/>',
        '  <joint name="base_link-world" type="fixed">',
        '    <parent link="base_link"/>',
        '    <child link="world"/>',
        f'    <origin xyz="0 0 {_m(h)}" rpy="0 0 0"/>',
        "  </joint>",
        "  <!-- VAL 3 flange frame: the joint 6 frame, Z leaving the flange along axis 6. -->",
        '  <link name="flange"/>',
        '  <joint name="link_6-flange" type="fixed">',
        '    <parent link="link_6"/>',
        '    <child link="flange"/>',
        '    <origin xyz="0 0 0" rpy="0 0 0"/>',
        "  </joint>",
        "</robot>",
        "",
    ]
    return "\n".join(lines)


def scara_urdf(name: str, arm: dict) -> str:
    """A SCARA (RS/TS, manual 9.7.5): two revolute joints, the prismatic axis 3, revolute axis 4."""
    l1, l2, z0 = arm["link1_mm"], arm["link2_mm"], arm["flange_z_at_j3_zero_mm"]
    j = [arm[f"joint{i}"] for i in range(1, 5)]
    if (j[0]["origin_mm"] != [0, 0, 0] or j[1]["origin_mm"] != [l1, 0, 0] or j[2]["origin_mm"] != [l2, 0, z0]
            or j[2].get("type") != "prismatic" or any(jj["axis"][:2] != [0, 0] for jj in j)):
        raise SystemExit(f"{name}: not the SCARA layout of staubli-arms-more.toml's header")
    reach = l1 + l2
    speeds, ramp = dynamics.scara(reach)
    native = "ceiling" if series_of(name) == "TP" else "floor"
    assumptions = [
        ("ramp_s", _f(ramp), dynamics.scara_accel_text(name, reach, ramp)),
        ("nominal_speeds", " ".join(_f(v) for v in speeds), dynamics.scara_speed_text(reach)),
        ("world_z_mm", "0", SCARA_WORLD),
        ("axis4_sign", "-1", SCARA_AXIS4),
    ]
    missing = [("max_torques", "no public source gives this arm's joint torques or axis 3 force")]
    extra = f' stroke_mm="{_f(arm["stroke_mm"])}"' + (f' native_mount="{native}"' if native != "floor" else "")
    lines = _header(name, "scara", arm, extra, f"SCARA rule: nominal speed reached in {_f(ramp)} s from rest, fitted "
                    "to Stäubli's TS2 standard cycles (assumed: no joint acceleration is published)")
    for i in range(1, 5):
        if i == 3:
            lines.append(f'    <joint name="joint_3" nominal_speed_mm_s="{_f(speeds[2])}" '
                         f'acceleration_mm_s2="{_f(round(speeds[2] / ramp, 1))}"/>')
        else:
            lines.append(f'    <joint name="joint_{i}" nominal_speed_deg_s="{_f(speeds[i - 1])}" '
                         f'acceleration_deg_s2="{_f(round(speeds[i - 1] / ramp, 1))}"/>')
    lines += provenance_lines(name, arm, assumptions, missing)
    lines.append("  </val3check>")
    lines.append("")
    lines += _links(scara_collision_solids(arm))
    for i in range(1, 5):
        jj = j[i - 1]
        parent = "base_link" if i == 1 else f"link_{i - 1}"
        if i == 3:
            lo, hi = jj["min_mm"] / 1000.0, jj["max_mm"] / 1000.0
            vel, rng = speeds[2] / 1000.0, f'{_f(jj["min_mm"])} .. {_f(jj["max_mm"])} mm, {_f(speeds[2])} mm/s (assumed)'
            kind = "prismatic"
        else:
            lo, hi = math.radians(jj["min_deg"]), math.radians(jj["max_deg"])
            vel, rng = math.radians(speeds[i - 1]), f'{_f(jj["min_deg"])} .. {_f(jj["max_deg"])} deg, {_f(speeds[i - 1])} deg/s (assumed)'
            kind = "revolute"
        lines += [
            f'  <joint name="joint_{i}" type="{kind}">',
            f'    <parent link="{parent}"/>',
            f'    <child link="link_{i}"/>',
            f'    <origin xyz="{_xyz_m(jj["origin_mm"])}" rpy="0 0 0"/>',
            f'    <axis xyz="{" ".join(_f(a) for a in jj["axis"])}"/>',
            f"    <!-- {rng} -->",
            f'    <limit lower="{_f(lo)}" upper="{_f(hi)}" velocity="{_f(vel)}" effort="0"/>',
            "  </joint>",
        ]
    lines += [
        "",
        "  <!-- VAL 3 world frame (assumed, see <assumption key=\"world_z_mm\">): on axis 1, at the flange's height when j3 = 0. -->",
        '  <link name="world"/>',
        '  <joint name="base_link-world" type="fixed">',
        '    <parent link="base_link"/>',
        '    <child link="world"/>',
        f'    <origin xyz="0 0 {_m(z0)}" rpy="0 0 0"/>',
        "  </joint>",
        "  <!-- VAL 3 flange frame: the joint 4 frame turned half a turn about X: Z leaves the flange, downwards. -->",
        '  <link name="flange"/>',
        '  <joint name="link_4-flange" type="fixed">',
        '    <parent link="link_4"/>',
        '    <child link="flange"/>',
        f'    <origin xyz="0 0 0" rpy="{_f(math.pi)} 0 0"/>',
        "  </joint>",
        "</robot>",
        "",
    ]
    return "\n".join(lines)


def with_acm(text: str) -> str:
    """The URDF with its allowed-collision matrix stored in its <val3check> element, computed by
    val3check/collision/acm.py from this very text (so that no run computes it again: the run
    uses it only while the digest of its inputs, `inputs`, is the arm's). Needs the `sim` extra."""
    import tempfile

    sys.path.insert(0, str(HERE.parent))  # this checkout's val3check
    from val3check.collision.acm import ACM, acm_inputs, compute_acm, read_acm, stored_lines
    from val3check.collision.armmodel import ArmModel
    from val3check.robot import from_urdf

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "arm.urdf"
        path.write_text(text, encoding="utf-8")
        user, head = read_acm(str(path))
        if head is not None:
            raise SystemExit(f"{path}: the generated text already has an <acm>")
        robot = from_urdf(path)
        arm = ArmModel(robot, acm=ACM())  # its solids and links, the matrix computed below
        acm = compute_acm(arm.links, arm.bodies, robot.joint_limits, user=user)
        inputs = acm_inputs(arm.links, arm.bodies, robot.joint_limits, user, acm.trials, acm.seed)
    lines = ["    <!-- allowed-collision matrix: computed from this file's solids and limits, not a fact (robots/README.md,",
             '         "Allowed collisions"); used only while `inputs` is the digest of what it was computed from -->',
             *stored_lines(acm, inputs)]
    return text.replace("  </val3check>\n", "\n".join(lines) + "\n  </val3check>\n", 1)


# ---- catalog.toml ------------------------------------------------------------------------------


def _q(s: str) -> str:
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"') + '"'


def catalog_toml(arms: dict[str, dict]) -> str:
    lines = [
        "# Generated by robots/generate.py from shared/robots/staubli-arms*.toml: do not edit by hand.",
        "# The arm models of this folder, and the arm ids a controller writes in usr/configs/arm.cfx",
        '# (<String name="arm" value="ts2_60-S1"/>). An id is compared lower-case, with "_" and "-" alike and',
        '# without its "-S<n>" suffix; `confirmed = false` means the id is inferred, not seen in a real arm.cfx.',
        "# `family` is the VAL 3 type family: Rx (pointRx, jointRx, configRx: six-axis RX/TX arms) or Rs",
        "# (pointRs, jointRs, configRs: SCARA RS/TS arms, manual 9.7.5). Plain data: tomllib reads it without",
        "# val3check's robot package.",
        "version = 1",
        "",
        "[families]  # VAL 3 type family of an arm id by its prefix (an id no model matches is still classified)",
        'Rx = ["tx", "rx"]',
        'Rs = ["ts", "rs", "tp"]',
        "",
    ]
    for name, arm in arms.items():
        kind = "scara" if arm.get("kind") == "scara" else "six-axis"
        srs, confirmed = _srs(arm)
        lines += [
            "[[arm]]",
            f"name = {_q(name)}",
            f"file = {_q(slug(name) + '.urdf')}",
            f"kind = {_q(kind)}",
            f"family = {_q('Rs' if kind == 'scara' else 'Rx')}",
            f"series = {_q(series_of(name))}",
            f"ids = [{_q(srs)}]",
            f"confirmed = {'true' if confirmed else 'false'}",
        ]
        if kind == "scara":
            lines.append(f"stroke_mm = {_f(arm['stroke_mm'])}")
        lines.append("")
    for arm_id, name, closest, why in KNOWN_WITHOUT_MODEL:
        kind = "scara" if arm_id[:2] in ("ts", "rs", "tp") else "six-axis"
        lines += [
            "[[known]]  # a Stäubli arm without public kinematic data: no model",
            f"id = {_q(arm_id)}",
            f"arm = {_q(name)}",
            f"family = {_q('Rs' if kind == 'scara' else 'Rx')}",
            f"closest = {_q(closest)}",
            f"why = {_q(why)}",
            "",
        ]
    return "\n".join(lines).rstrip("\n") + "\n"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--toml", type=Path, default=DEFAULT_TOML, help="staubli-arms.toml")
    ap.add_argument("--more", type=Path, default=MORE_TOML, help="staubli-arms-more.toml")
    ap.add_argument("--out", type=Path, default=HERE)
    ap.add_argument("--check", action="store_true", help="compare instead of writing")
    args = ap.parse_args(argv)
    arms = load_facts(args.toml, args.more)
    files = {}
    for name, arm in arms.items():
        text = scara_urdf(name, arm) if arm.get("kind") == "scara" else urdf(name, arm, arms)
        files[f"{slug(name)}.urdf"] = with_acm(text)
    files["catalog.toml"] = catalog_toml(arms)
    stale = []
    for fname, text in files.items():
        path = args.out / fname
        if args.check:
            if not path.is_file() or path.read_text(encoding="utf-8") != text:
                stale.append(fname)
            continue
        path.write_text(text, encoding="utf-8", newline="\n")
        print(f"wrote {path.relative_to(args.out.parent) if args.out == HERE else path}")
    if args.check:
        written = {p.name for p in args.out.glob("*.urdf")} | ({"catalog.toml"} if (args.out / "catalog.toml").is_file() else set())
        stale += sorted(written - set(files))  # a model whose facts are gone
    if stale:
        print("out of date: " + ", ".join(stale) + " (run python robots/generate.py)", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
