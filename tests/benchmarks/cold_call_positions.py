#!/usr/bin/env python3
"""CPU time of each cold call along api_bench's time step (docs/library.md, "The cold call").

The benchmark's wheel (S1002 on UIC60 1:40, conformal, standard, FASTSIM, 100 kN, 20 m/s,
friction 0.3) on one handle without warm start, at -5.60 mm + 0.01 mm * k for k = 0..39 (the
positions of BM_GaugeCornerWheelTimeStep), `rounds` times; prints each position's lowest CPU
time of `calculate` (time.process_time) and its patch count. With --reference, also each
position's differences from a cold handle at the reference preset (area and p_max relative, F_x
and F_y of the net force on the rail in % of the load, as warm_start_accuracy.py), and their
largest and mean values over the 40 positions and over those from -5.35 mm (the cliff of
docs/library.md, "The cold call").

Run: PYTHONPATH=build/api/python python3 tests/benchmarks/cold_call_positions.py [rounds]
         [--reference]
"""
import sys
import time

import railwear
from warm_start_accuracy import LOAD_N, errors, handle, solve  # (the benchmark's wheel)


def main():
    args = [a for a in sys.argv[1:] if a != "--reference"]
    rounds = int(args[0]) if args else 2
    p = handle(railwear.ACCURACY_STANDARD, warm=False)
    cpu = [[] for _ in range(40)]
    patches = [0] * 40
    for _ in range(rounds):
        for k in range(40):
            p.set_state(lateral_m=-5.6e-3 + 1e-5 * k, vertical_force_N=LOAD_N, speed_m_s=20.0)
            t0 = time.process_time()
            status = p.calculate()
            cpu[k].append(time.process_time() - t0)
            if status != railwear.OK:
                raise RuntimeError(f"k = {k}: status {status}")
            patches[k] = p.get_patch_count()
    for k in range(40):
        print(f"{-5.6 + 0.01 * k:.2f} mm  {1e3 * min(cpu[k]):7.1f} ms  patches {patches[k]}")
    if "--reference" in sys.argv:
        ref = handle(railwear.ACCURACY_REFERENCE, warm=False)
        errs = []
        for k in range(40):
            y_mm = round(-5.6 + 0.01 * k, 2)
            errs.append((y_mm, errors(solve(p, y_mm), solve(ref, y_mm))))
            print(f"{y_mm:.2f} mm against the reference: "
                  + " ".join(f"{n} {v:.2f} %" for n, v in errs[-1][1].items()))
        for name, rows in (("all 40", errs), ("from -5.35 mm", [e for e in errs if e[0] >= -5.355])):
            print(f"{name}: " + ", ".join(
                f"{n} {max(e[n] for _, e in rows):.2f} / {sum(e[n] for _, e in rows) / len(rows):.2f} %"
                for n in ("area", "p_max", "fx", "fy")) + " (largest / mean)")


if __name__ == "__main__":
    main()
