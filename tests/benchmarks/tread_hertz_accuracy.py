#!/usr/bin/env python3
"""The fast tread path against the full path (docs/library.md, "The fast tread path").

Runs examples/rolling_tread_hertz.toml (kind = "hertz", draft: the fast tread path of
core/contact/hertz_tread.h) at a row of lateral shifts, and the same scene with
--model halfspace --accuracy standard (the full path's planar grid), through the CLI, and prints
a Markdown table: whether the fast path applied (and the gap deviation it measured), and the
differences in area, p_max, the contact point's lateral position and the creep forces (in % of
mu Q). Rows where the fast path did not apply compare its fallback (kind = "auto") instead.

Run from the repository root:  python3 tests/benchmarks/tread_hertz_accuracy.py [build/app/railwear]
"""
import json
import os
import re
import subprocess
import sys
import tempfile

SHIFTS_MM = ["-28", "-24", "-20", "-16", "-14", "-13", "-12", "-10.4", "-9", "-8", "-7", "-6"]
LOAD_N, FRICTION = 100e3, 0.3  # the scene's


def solve(binary, scene, extra, out):
    subprocess.run([binary, "contact", scene, "--json", out] + extra, check=True,
                   stdout=subprocess.DEVNULL)
    with open(out) as f:
        return json.load(f)


def main():
    binary = sys.argv[1] if len(sys.argv) > 1 else "build/app/railwear"
    with open("examples/rolling_tread_hertz.toml") as f:
        template = f.read()
    mu_q = FRICTION * LOAD_N
    print("| lateral shift | fast path (gap deviation) | area | p_max | contact y "
          "| F_x / (mu Q) | F_s / (mu Q) |")
    print("|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for y in SHIFTS_MM:
            scene = os.path.join(tmp, "tread.toml")
            with open(scene, "w") as f:
                f.write(template.replace("lateral_shift_mm = -20.0", f"lateral_shift_mm = {y}"))
            fast = solve(binary, scene, [], os.path.join(tmp, "fast.json"))
            full = solve(binary, scene, ["--model", "halfspace", "--accuracy", "standard"],
                         os.path.join(tmp, "full.json"))
            if len(fast["patches"]) != 1 or len(full["patches"]) != 1:
                print(f"| {y} mm | patches {len(fast['patches'])} and {len(full['patches'])} |")
                continue
            a, b = fast["patches"][0], full["patches"][0]
            m = re.search(r"by (\d+) %", a["model_reason"])
            applied = "yes" if a["model"] == "hertz" else "no: falls back"
            dev = f" ({m.group(1)} %)" if m else ""
            fa, fb = a["creep_force_N"], b["creep_force_N"]
            print(f"| {y} mm | {applied}{dev} "
                  f"| {100 * (a['area_mm2'] / b['area_mm2'] - 1):+.1f} % "
                  f"| {100 * (a['p_max_MPa'] / b['p_max_MPa'] - 1):+.1f} % "
                  f"| {a['contact_y_mm'] - b['contact_y_mm']:+.2f} mm "
                  f"| {100 * (fa['x'] - fb['x']) / mu_q:+.1f} % "
                  f"| {100 * (fa['y'] - fb['y']) / mu_q:+.1f} % |")


if __name__ == "__main__":
    main()
