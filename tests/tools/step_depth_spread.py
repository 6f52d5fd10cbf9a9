#!/usr/bin/env python3
"""Where each wear step wears, and how wide: the step-limit study's diagnostic (docs/wear.md,
"Why the step limit matters: each step's wear is a narrow band that wanders").

For every stored step of a run, the step's own depth field (the `step_depth_mm` distribution of
the high rail, profiles_db/SCHEMA.md) gives
  - its peak (the step limit, when the high rail sets the step) and the peak's arc length s;
  - its effective width, the step's worn area over its peak depth [mm]: the width of a
    rectangle with the step's area and peak (a narrow band: a few mm; the whole worn zone: 10+);
  - the peak's jump from the step before [mm of s].
Per traffic window (0-1, 1-5, 5-MGT) it prints the medians, and the sum of the steps' peaks
against the deepest accumulated wear's growth over the window: a peak that stays in place adds
up to the accumulated depth, one that wanders adds up to several times it. And at the window's
last step the accumulated depth field's short-wave part: the RMS of the depth less its 4 mm
moving average (wavelengths below some 8 mm) over s = 15-40 mm of the unworn arc length (the
gauge corner's worn zone), in um and relative to the deepest wear: a roughness coarse steps
might leave behind.

  usage: tests/tools/step_depth_spread.py DB [DB ...]   (each DB a traffic_study.sh run's
         traffic.sqlite, or any wear database; its first run is read, read-only)
"""
import sqlite3
import statistics
import struct
import sys


def floats(blob):
    return struct.unpack(f"<{len(blob) // 8}d", blob)


def steps_of(db):
    con = sqlite3.connect(f"file:{db}?mode=ro", uri=True)
    run = con.execute("SELECT MIN(id) FROM runs").fetchone()[0]
    mgt = dict(con.execute("SELECT step, mgt FROM steps WHERE run_id = ?", (run,)))
    deepest = dict(con.execute("SELECT step, max_depth_mm FROM steps WHERE run_id = ?", (run,)))
    accumulated = {step: (floats(v), floats(s)) for step, v, s in con.execute(
        "SELECT step, value, s FROM distributions WHERE run_id = ? AND kind = 'wear_depth_mm'",
        (run,)) if s is not None}
    out = []
    for step, value, s in con.execute(
            "SELECT step, value, s FROM distributions WHERE run_id = ? AND kind = 'step_depth_mm' "
            "ORDER BY step", (run,)):
        if s is None:
            sys.exit(f"{db}: step {step} has no arc lengths (a schema-1 database): expected s")
        depth, arc = floats(value), floats(s)
        k = max(range(len(depth)), key=lambda i: depth[i])
        if depth[k] <= 0:
            continue
        ds_mm = (arc[1] - arc[0]) * 1e3
        out.append({"step": step, "mgt": mgt[step], "peak": depth[k], "s": arc[k] * 1e3,
                    "width": sum(depth) * ds_mm / depth[k], "deepest": deepest[step],
                    "short_wave": short_wave_um(*accumulated[step])})
    return out


def short_wave_um(depth_mm, s_m, half_window_mm=2.0, zone_mm=(15.0, 40.0)):
    s = [x * 1e3 for x in s_m]
    h = int(round(half_window_mm / (s[1] - s[0])))
    residual = [depth_mm[i] - sum(depth_mm[i - h:i + h + 1]) / (2 * h + 1)
                for i in range(h, len(s) - h) if zone_mm[0] <= s[i] <= zone_mm[1]]
    return 1e3 * (sum(r * r for r in residual) / len(residual)) ** 0.5


def main(dbs):
    if not dbs:
        sys.exit(__doc__)
    print(f"{'database':44s} {'MGT':>7s} {'steps':>5s} {'width':>6s} {'jump':>5s} "
          f"{'sum of peaks':>12s} {'deepest':>8s} {'short wave':>16s}")
    for db in dbs:
        rows = steps_of(db)
        if not rows:
            sys.exit(f"{db}: no step_depth_mm rows: expected a wear run's database")
        last = rows[-1]["mgt"]
        for lo, hi in [(0.0, 1.0), (1.0, 5.0), (5.0, last)]:
            w = [r for r in rows if lo < r["mgt"] <= hi]
            if len(w) < 2:
                continue
            jumps = [abs(w[i]["s"] - w[i - 1]["s"]) for i in range(1, len(w))]
            print(f"{db[-44:]:44s} {lo:3.0f}-{hi:<3.0f} {len(w):5d} "
                  f"{statistics.median(r['width'] for r in w):6.1f} {statistics.median(jumps):5.1f} "
                  f"{sum(r['peak'] for r in w):12.3f} {w[-1]['deepest'] - (w[0]['deepest'] - w[0]['peak']):8.3f} "
                  f"{w[-1]['short_wave']:7.1f} ({100 * w[-1]['short_wave'] / 1e3 / w[-1]['deepest']:4.2f} %)")
    print("(width: median effective width of a step's wear, its worn area over its peak, mm; jump: "
          "median move of the peak from the step before, mm of arc length; sum of peaks and "
          "deepest: the steps' peak depths summed and the deepest accumulated wear's growth over "
          "the window, mm; short wave: at the window's last step, the RMS of the accumulated depth less its "
          "4 mm moving average over s = 15-40 mm, um, and its share of the deepest wear)")


if __name__ == "__main__":
    main(sys.argv[1:])
