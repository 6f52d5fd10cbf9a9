#!/usr/bin/env python3
"""The warm start's accuracy and cost over an MBS-like sequence (docs/library.md, "Warm start").

The benchmark's wheel (tests/api/rolling_wheel.h: S1002 on UIC60 1:40, 100 kN, 20 m/s, FASTSIM,
mu 0.3, conformal) stepped laterally from -3 to -7 mm as a time loop does, in steps cycling
through 0.05, 0.10, 0.15, 0.20 and 0.25 mm (28 positions; "--uniform": 17 positions 0.25 mm
apart, the sequence of the table "patch sized on draft cells"; "--fine": 17 positions 0.01 mm
apart from -5.6 mm, the steps of api_bench's BM_GaugeCornerWheelTimeStep, where a warm call
keeps its grid for several steps). At each position: a handle with
rw_set_warm_start(1) that has solved every earlier position, a cold handle at the preset, and a
cold handle at the reference preset. Prints a Markdown table of the largest and mean
differences (area and p_max relative, F_x and F_y of the net force on the rail in % of the load)
of the cold and the warm calls against the reference and of the warm against the cold, and the
CPU seconds the standard handles spent (time.process_time around their calculates).

Run from the repository root with the module on the path:
  PYTHONPATH=build/api/python python3 tests/benchmarks/warm_start_accuracy.py [--uniform|--fine]
      [--accuracy standard|draft]
"""
import sys
import time

import railwear

LOAD_N = 100e3
STEPS_MM = [0.05, 0.10, 0.15, 0.20, 0.25]


def positions_mm(uniform, fine=False):
    if fine:
        return [round(-5.6 - 0.01 * k, 6) for k in range(17)]
    if uniform:
        return [-3.0 - 0.25 * k for k in range(17)]
    out, y, k = [-3.0], -3.0, 0
    while True:
        y -= STEPS_MM[k % len(STEPS_MM)]
        k += 1
        if y < -7.0 - 1e-9:
            return out
        out.append(round(y, 6))


def handle(accuracy, warm):
    p = railwear.Problem(railwear.PROBLEM_WHEEL)
    p.set_profile_file(railwear.BODY_WHEEL, "builtin:S1002")
    p.set_profile_file(railwear.BODY_RAIL, "builtin:UIC60")
    p.set_geometry(rail_cant=1.0 / 40.0)
    p.set_model(kind=railwear.MODEL_CONFORMAL, accuracy=accuracy,
                effects=railwear.EFFECT_TANGENTIAL)
    p.set_friction(0.3)
    if warm:
        p.set_warm_start(True)
    return p


def solve(p, y_mm):
    p.set_state(lateral_m=y_mm * 1e-3, vertical_force_N=LOAD_N, speed_m_s=20.0)
    t0 = time.process_time()
    status = p.calculate()
    cpu = time.process_time() - t0
    if status != railwear.OK:
        raise RuntimeError(f"{y_mm} mm: status {status}")
    patches = [p.get_patch(i) for i in range(p.get_patch_count())]
    return {
        "area": sum(q["area_m2"] for q in patches),
        "p_max": max(q["p_max_Pa"] for q in patches),
        "fx": sum(q["force_on_rail_N"][0] for q in patches),
        "fy": sum(q["force_on_rail_N"][1] for q in patches),
        "patches": len(patches),
        "cpu": cpu,
    }


def errors(a, b):
    return {
        "area": abs(a["area"] / b["area"] - 1) * 100,
        "p_max": abs(a["p_max"] / b["p_max"] - 1) * 100,
        "fx": abs(a["fx"] - b["fx"]) / LOAD_N * 100,
        "fy": abs(a["fy"] - b["fy"]) / LOAD_N * 100,
    }


def main():
    uniform = "--uniform" in sys.argv
    accuracy = railwear.ACCURACY_DRAFT if "draft" in sys.argv else railwear.ACCURACY_STANDARD
    ref, cold, warm = (handle(railwear.ACCURACY_REFERENCE, False), handle(accuracy, False),
                       handle(accuracy, True))
    rows = {"cold vs reference": [], "warm vs reference": [], "warm vs cold": []}
    cpu = {"cold": 0.0, "warm": 0.0}
    ys = positions_mm(uniform, "--fine" in sys.argv)
    for y in ys:
        r, c, w = solve(ref, y), solve(cold, y), solve(warm, y)
        cpu["cold"] += c["cpu"]
        cpu["warm"] += w["cpu"]
        rows["cold vs reference"].append(errors(c, r))
        rows["warm vs reference"].append(errors(w, r))
        rows["warm vs cold"].append(errors(w, c))
        print(f"# {y:+.2f} mm: patches ref {r['patches']} cold {c['patches']} warm {w['patches']}"
              f", cpu cold {c['cpu'] * 1e3:.1f} ms warm {w['cpu'] * 1e3:.1f} ms; warm vs cold "
              + " ".join(f"{k} {v:.2f}" for k, v in rows["warm vs cold"][-1].items()),
              file=sys.stderr)
    print(f"{len(ys)} positions {ys[0]} .. {ys[-1]} mm")
    print("| | area, max / mean | p_max | F_x (of the load) | F_y (of the load) |")
    print("|---|---|---|---|---|")
    for name, errs in rows.items():
        cells = []
        for k in ("area", "p_max", "fx", "fy"):
            v = [e[k] for e in errs]
            cells.append(f"{max(v):.2f} / {sum(v) / len(v):.2f} %")
        print(f"| {name} | " + " | ".join(cells) + " |")
    print(f"CPU of the calculates: cold {cpu['cold']:.3f} s, warm {cpu['warm']:.3f} s "
          f"({cpu['warm'] / cpu['cold']:.2f}x)")


if __name__ == "__main__":
    main()
