#!/usr/bin/env python3
"""Write the Stäubli arm models (`robots/*.urdf`) from the facts in `staubli-arms.toml`.

    python robots/generate.py                 # (re)write robots/*.urdf
    python robots/generate.py --check         # exit 1 if a written file differs from what it would write
    python robots/generate.py --toml PATH     # another copy of the facts

The facts (joint origins, axes, limits, nominal speeds, torques, world-frame height, SRS arm id)
come from `../shared/robots/staubli-arms.toml`, itself gathered from the public ROS-Industrial
descriptions that quote Stäubli's data sheets. Everything else written here is this project's own
choice and documented in robots/README.md: the accelerations (not published by Stäubli), the
collision solids (cylinders sized to cover the arm, no meshes) and the frame names.

Nothing here is imported by val3check at run time: the URDF files are the models.
"""

from __future__ import annotations

import argparse
import math
import sys
import tomllib
from pathlib import Path

HERE = Path(__file__).resolve().parent
DEFAULT_TOML = HERE.parent.parent / "shared" / "robots" / "staubli-arms.toml"

# Acceleration assumption (robots/README.md): the nominal acceleration of a joint is the one that
# takes it from rest to its nominal speed in RAMP_S seconds (a trapezoidal profile at accel = 100 %).
RAMP_S = 0.25

# Collision solids: radii in millimetres per size class (robots/README.md, "Collision geometry").
#   base: fixed base column; shoulder: housing of axes 1-2; arm: upper arm (link 2);
#   elbow: housing of axis 3; fore: forearm (axis 4 tube); wrist: axes 5-6 housing; flange: tool flange.
SIZES = {
    "small": dict(base=110, shoulder=110, arm=80, elbow=75, fore=65, wrist=50, flange=32),
    "medium": dict(base=160, shoulder=150, arm=110, elbow=100, fore=90, wrist=65, flange=40),
    "large": dict(base=230, shoulder=200, arm=150, elbow=140, fore=120, wrist=90, flange=63),
}
FLANGE_THICKNESS = 10.0


def size_class(arm: dict) -> str:
    c2 = arm["joint3"]["origin_mm"][2]
    if c2 >= 800:
        return "large"
    if c2 >= 420:
        return "medium"
    return "small"


def slug(name: str) -> str:
    return name.lower()


def _f(v: float) -> str:
    """Shortest exact text for a float (repr round-trips); integers without '.0'."""
    if float(v).is_integer():
        return str(int(v))
    return repr(float(v))


def _m(mm: float) -> str:
    return _f(round(mm / 1000.0, 12))


def _xyz_m(v) -> str:
    return " ".join(_m(c) for c in v)


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


def collision_solids(arm: dict) -> dict[str, list[tuple]]:
    """Per link: (name, radius, length, centre xyz in the link frame (mm), rpy, what it covers)."""
    r = SIZES[size_class(arm)]
    h = arm["shoulder_height_mm"]
    a1 = arm["joint2"]["origin_mm"][0]
    b = arm["joint3"]["origin_mm"][1]
    c2 = arm["joint3"]["origin_mm"][2]
    c3 = arm["joint4"]["origin_mm"][2] + arm["joint5"]["origin_mm"][2]
    c4 = arm["joint6"]["origin_mm"][2]
    along_y = f"{_f(math.pi / 2)} 0 0"  # cylinder axis along the link's y (axes 2, 3, 5)
    base_len = h - r["shoulder"]
    return {
        "base_link": [("base", r["base"], base_len, (0, 0, base_len / 2), "0 0 0")],
        # shoulder housing turning with axis 1: a vertical drum around axis 1 that also covers axis 2
        "link_1": [("shoulder", r["shoulder"] + a1, 2 * r["shoulder"], (0, 0, 0), "0 0 0")],
        # upper arm: from axis 2 to axis 3 plus the joint housings at both ends, and the axis 2 boss
        "link_2": [
            ("upper_arm", r["arm"], c2 + 2 * r["arm"], (0, b / 2, c2 / 2), "0 0 0"),
            ("shoulder_boss", r["arm"], 2 * r["arm"] + abs(b), (0, b / 2, 0), along_y),
        ],
        # elbow housing around axis 3
        "link_3": [("elbow", r["elbow"], 2 * r["elbow"], (0, 0, 0), along_y)],
        # forearm tube turning with axis 4, from the elbow to the wrist housing (which covers the
        # wrist centre): ending there lets the flange turn to 90 degrees beside it, as on the arm
        "link_4": [("forearm", r["fore"], c3 - r["wrist"], (0, 0, (c3 - r["wrist"]) / 2), "0 0 0")],
        # wrist: housing around axis 5 and the part between the wrist centre and the flange
        "link_5": [
            ("wrist", r["wrist"], 2 * r["wrist"], (0, 0, 0), along_y),
            ("wrist_nose", r["flange"] + 8, c4, (0, 0, c4 / 2), "0 0 0"),
        ],
        "link_6": [("flange", r["flange"], FLANGE_THICKNESS, (0, 0, -FLANGE_THICKNESS / 2), "0 0 0")],
    }


def urdf(name: str, arm: dict, source: str) -> str:
    h = arm["shoulder_height_mm"]
    if arm["joint1"]["origin_mm"] != [0, 0, h]:
        raise SystemExit(f"{name}: joint 1 is not on the world frame's vertical (shoulder_height_mm)")
    lines = [
        '<?xml version="1.0"?>',
        f"<!-- Stäubli {name}: generated by robots/generate.py from {source}; do not edit by hand. -->",
        "<!-- Units: metres, radians (URDF). val3check reads the <val3check> element below; other tools ignore it. -->",
        f'<robot name="staubli_{slug(name).replace("-", "_")}">',
        '  <material name="staubli_yellow"><color rgba="0.96 0.76 0.13 1"/></material>',
        '  <material name="grey"><color rgba="0.6 0.6 0.6 1"/></material>',
        "",
        f'  <val3check arm="{name}" srs_arm_id="{arm["srs_arm_id"]}" world_frame="world" flange_frame="flange"',
        f'             acceleration_rule="nominal speed reached in {_f(RAMP_S)} s from rest (assumed: not published by Staubli)">',
    ]
    for i in range(1, 7):
        j = arm[f"joint{i}"]
        acc = j["nominal_speed_deg_s"] / RAMP_S
        lines.append(
            f'    <joint name="joint_{i}" nominal_speed_deg_s="{_f(j["nominal_speed_deg_s"])}" '
            f'acceleration_deg_s2="{_f(acc)}" max_torque_nm="{_f(j["max_torque_nm"])}"/>'
        )
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
    solids = collision_solids(arm)
    links = ["base_link"] + [f"link_{i}" for i in range(1, 7)]
    for link in links:
        lines.append(f'  <link name="{link}">')
        for sname, radius, length, xyz, rpy in solids[link]:
            lines += _cyl(radius, length, xyz, rpy, sname)
        lines.append("  </link>")
    for i in range(1, 7):
        j = arm[f"joint{i}"]
        parent = "base_link" if i == 1 else f"link_{i - 1}"
        lo, hi = math.radians(j["min_deg"]), math.radians(j["max_deg"])
        vel = math.radians(j["nominal_speed_deg_s"])
        lines += [
            f'  <joint name="joint_{i}" type="revolute">',
            f'    <parent link="{parent}"/>',
            f'    <child link="link_{i}"/>',
            f'    <origin xyz="{_xyz_m(j["origin_mm"])}" rpy="0 0 0"/>',
            f'    <axis xyz="{" ".join(_f(a) for a in j["axis"])}"/>',
            f'    <!-- {_f(j["min_deg"])} .. {_f(j["max_deg"])} deg, {_f(j["nominal_speed_deg_s"])} deg/s -->',
            f'    <limit lower="{_f(lo)}" upper="{_f(hi)}" velocity="{_f(vel)}" effort="{_f(j["max_torque_nm"])}"/>',
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


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--toml", type=Path, default=DEFAULT_TOML)
    ap.add_argument("--out", type=Path, default=HERE)
    ap.add_argument("--check", action="store_true", help="compare instead of writing")
    args = ap.parse_args(argv)
    with open(args.toml, "rb") as fh:
        arms = tomllib.load(fh)
    stale = []
    for name, arm in arms.items():
        text = urdf(name, arm, "shared/robots/staubli-arms.toml")
        path = args.out / f"{slug(name)}.urdf"
        if args.check:
            if not path.is_file() or path.read_text(encoding="utf-8") != text:
                stale.append(path.name)
            continue
        path.write_text(text, encoding="utf-8", newline="\n")
        print(f"wrote {path.relative_to(args.out.parent) if args.out == HERE else path}")
    if stale:
        print("out of date: " + ", ".join(stale) + " (run python robots/generate.py)", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
