#!/usr/bin/env python3
"""Runs the 21 Manchester A-2.2 scenes and prints the docs/manchester.md table (Markdown).

    python3 examples/manchester/table.py build/app/railwear > table.md

Per case and wheel: the patches (largest normal force first) with their contact position in the
rail profile's frame (y, z), the longitudinal position x of the pressure centre (ahead of the
wheel's centre: the yawed wheel's lead), the contact angle, area and peak pressure; the wheel's
net force on its rail in the track frame (x forward, Y right, z down: the left wheel's lateral
force is mirrored into the track's Y), and L/V.
"""
import json
import pathlib
import subprocess
import sys

binary = sys.argv[1] if len(sys.argv) > 1 else "build/app/railwear"
here = pathlib.Path(__file__).resolve().parent


def wheel_row(w):
    patches = sorted(w["patches"], key=lambda p: -p["normal_force_N"])
    where = "; ".join(
        f"{p['contact_y_mm']:.1f}, {p['contact_z_mm']:.2f} / x {p['contact_x_mm']:.1f} / "
        f"{p['contact_angle_deg']:.1f}° / {p['area_mm2']:.1f} mm² / {p['p_max_MPa']:.0f} MPa"
        for p in patches)
    net = w["forces"]["total"]["track"]["net"]
    lv = w["flange_climb_check"]["l_over_v"]
    flag = " ⚠" if w["flange_climb"] else ""
    return f"{where} | {net['x']:.0f}, {net['y']:.0f}, {net['z']:.0f} | {lv:.3f}{flag}"


print("| case | y_ws mm | yaw mrad | right: y, z mm / x mm / angle / area / p_max | right: F on rail "
      "(x, Y, z) N | right L/V | left: y, z mm / x mm / angle / area / p_max | left: F on rail "
      "(x, Y, z) N | left L/V |")
print("|---|---|---|---|---|---|---|---|---|")
for n in range(1, 22):
    scene = here / f"case_{n:02d}.toml"
    out = subprocess.run([binary, "contact", str(scene), "--json", "-"], capture_output=True,
                         text=True, check=True).stdout
    j = json.loads(out)
    text = scene.read_text()
    y = float(text.split("lateral_displacement_mm = ")[1].split()[0])
    yaw = float(text.split("yaw_mrad = ")[1].split()[0])
    w = j["wheels"]
    print(f"| {n} | {y} | {yaw} | {wheel_row(w['right'])} | {wheel_row(w['left'])} |")
