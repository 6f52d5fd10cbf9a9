#!/usr/bin/env python3
"""A library's cold calls of api_bench's wheel against a fixed reference (docs/library.md, "The
cold call measures the patch on coarse cells").

The benchmark's wheel (warm_start_accuracy.py's handle: S1002 on UIC60 1:40, conformal, FASTSIM,
100 kN, 20 m/s), one cold handle, at 80 positions on the flange root (-5.600 ... -5.210 mm in
0.01 mm steps, the time step of BM_GaugeCornerWheelTimeStep and cold_call_positions.py, and the
same shifted by 0.005 mm) and 32 from the flange to the tread (-3.0 ... -7.0 mm in 0.25 mm steps,
and the same shifted by 0.125 mm).

  dump ACCURACY OUT.json   solve every position with the `railwear` module on PYTHONPATH
                           (ACCURACY: standard or reference) and write area, p_max, F_x, F_y
                           and the CPU of each call
  compare REF.json A.json [B.json ...]
                           each file's largest and mean differences from REF (area and p_max
                           relative, F_x and F_y in % of the load, as warm_start_accuracy.py),
                           p_max's RMS, and the CPU summed, per group of positions

Two libraries' modules cannot share one process: dump each with its own PYTHONPATH, e.g. the
reference once with main's build, then the standard preset with main's and with this build's:

  PYTHONPATH=<main's build>/api/python:tests/benchmarks python3 tests/benchmarks/cold_call_accuracy.py dump reference ref.json
  PYTHONPATH=<main's build>/api/python:tests/benchmarks python3 tests/benchmarks/cold_call_accuracy.py dump standard main.json
  PYTHONPATH=build/api/python:tests/benchmarks python3 tests/benchmarks/cold_call_accuracy.py dump standard this.json
  python3 tests/benchmarks/cold_call_accuracy.py compare ref.json main.json this.json
"""
import json
import sys

LOAD_N = 100e3
FLANGE_ROOT = [round(-5.6 + 0.01 * k, 3) for k in range(40)] + \
    [round(-5.595 + 0.01 * k, 3) for k in range(40)]
FLANGE_TO_TREAD = [round(-3.0 - 0.25 * k, 3) for k in range(17)] + \
    [round(-3.125 - 0.25 * k, 3) for k in range(15)]
GROUPS = (("flange root, 80 positions -5.60 .. -5.21 mm", FLANGE_ROOT),
          ("flange to tread, 32 positions -3 .. -7 mm", FLANGE_TO_TREAD))


def dump(accuracy, out):
    import railwear
    from warm_start_accuracy import handle, solve
    preset = {"standard": railwear.ACCURACY_STANDARD,
              "reference": railwear.ACCURACY_REFERENCE}[accuracy]
    p = handle(preset, warm=False)
    with open(out, "w") as f:
        json.dump({str(y): solve(p, y) for _, ys in GROUPS for y in ys}, f, indent=1)


def errors(a, b):
    return {"area": abs(a["area"] / b["area"] - 1) * 100,
            "p_max": abs(a["p_max"] / b["p_max"] - 1) * 100,
            "fx": abs(a["fx"] - b["fx"]) / LOAD_N * 100,
            "fy": abs(a["fy"] - b["fy"]) / LOAD_N * 100}


def compare(ref_path, paths):
    with open(ref_path) as f:
        ref = json.load(f)
    for path in paths:
        with open(path) as f:
            d = json.load(f)
        for name, ys in GROUPS:
            e = [errors(d[str(y)], ref[str(y)]) for y in ys]
            rms = (sum(x["p_max"] ** 2 for x in e) / len(e)) ** 0.5
            print(f"{path}, {name}: " + ", ".join(
                f"{n} {max(x[n] for x in e):.2f} / {sum(x[n] for x in e) / len(e):.2f} %"
                for n in ("area", "p_max", "fx", "fy"))
                + f" (largest / mean); p_max RMS {rms:.2f} %; "
                f"CPU {sum(d[str(y)]['cpu'] for y in ys):.2f} s")


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "dump":
        dump(sys.argv[2], sys.argv[3])
    elif len(sys.argv) >= 4 and sys.argv[1] == "compare":
        compare(sys.argv[2], sys.argv[3:])
    else:
        sys.exit(__doc__)
