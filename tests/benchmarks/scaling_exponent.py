#!/usr/bin/env python3
"""Scaling exponent of time per solve against cell count, from Google Benchmark JSON.

Reads the JSON of contact_bench (--benchmark_format=json, from stdin or a file) and, for each
benchmark family and series (BM_HalfspaceSolve and BM_ConformalSolve per preconditioner label,
BM_GaugeCorner per model), fits log(time) = a + k log(cells) by least squares over the sizes and
prints the exponent k with the local slopes between neighbouring sizes. With repetitions, the
median aggregate is used. The cell count is the benchmark's "cells" counter (all grid cells);
Hertz (no cells) is left out. With --cpu the CPU time is fitted instead of the real time (on
a shared, loaded machine the CPU time is the steadier of the two).

  build/tests/benchmarks/contact_bench --benchmark_repetitions=3 \\
      --benchmark_report_aggregates_only=true --benchmark_format=json \\
      | python3 tests/benchmarks/scaling_exponent.py
"""
import collections
import json
import math
import sys

TO_MS = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}


def series_of(bench):
    family = bench.get("run_name", bench["name"]).split("/")[0]
    label = bench.get("label", "")
    if family == "BM_GaugeCorner":
        label = label.split(" ")[0]  # "model preset" -> model
    return family, label


def main():
    args = [a for a in sys.argv[1:] if a != "--cpu"]
    time_key = "cpu_time" if "--cpu" in sys.argv[1:] else "real_time"
    source = open(args[0]) if args and args[0] != "-" else sys.stdin
    data = json.load(source)
    points = collections.defaultdict(list)
    for b in data["benchmarks"]:
        if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median":
            continue
        cells = b.get("cells", 0)
        if not cells or cells <= 0:
            continue
        points[series_of(b)].append((cells, b[time_key] * TO_MS[b["time_unit"]]))
    print(f"{'benchmark':<20} {'series':<22} {'sizes':>5} {'cells':>17} {'exponent':>8}  "
          "local slopes")
    for (family, label), pts in sorted(points.items()):
        pts.sort()
        if len(pts) < 2:
            continue
        xs = [math.log(c) for c, _ in pts]
        ys = [math.log(t) for _, t in pts]
        mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
        sxx = sum((x - mx) ** 2 for x in xs)
        k = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else float("nan")
        local = [(ys[i + 1] - ys[i]) / (xs[i + 1] - xs[i]) for i in range(len(xs) - 1)
                 if xs[i + 1] > xs[i]]
        span = f"{pts[0][0]:.0f}-{pts[-1][0]:.0f}"
        print(f"{family:<20} {label:<22} {len(pts):>5} {span:>17} {k:>8.2f}  "
              + " ".join(f"{s:.2f}" for s in local))


if __name__ == "__main__":
    main()
