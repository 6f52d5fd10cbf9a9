#!/usr/bin/env python3
"""CPU time of each cold call along api_bench's time step (docs/library.md, "The cold call").

The benchmark's wheel (S1002 on UIC60 1:40, conformal, standard, FASTSIM, 100 kN, 20 m/s,
friction 0.3) on one handle without warm start, at -5.60 mm + 0.01 mm * k for k = 0..39 (the
positions of BM_GaugeCornerWheelTimeStep), `rounds` times; prints each position's lowest CPU
time of `calculate` (time.process_time) and its patch count.

Run: PYTHONPATH=build/api/python python3 tests/benchmarks/cold_call_positions.py [rounds]
"""
import sys
import time

import railwear
from warm_start_accuracy import LOAD_N, handle  # (the benchmark's wheel, this directory)


def main():
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 2
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


if __name__ == "__main__":
    main()
