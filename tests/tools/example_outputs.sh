#!/usr/bin/env bash
# Runs every shipped example with the railwear binary and stores its outputs, wall-clock times
# stripped, so that a refactor can be checked for "no change of behaviour":
#
#   bash tests/tools/example_outputs.sh build/app/railwear /tmp/before     # on the old tree
#   bash tests/tools/example_outputs.sh build/app/railwear /tmp/after      # on the new tree
#   diff -r /tmp/before /tmp/after && echo identical
#
# Contact scenes: `contact --json -` (times removed) and the per-cell pressure CSV, at the scene's
# accuracy. Wear scenes: two steps into a fresh database, then `history steps` and the last
# profile as CSV. Calibration configs: `calibrate --json -` (times removed) and the constants file.
# FEM configs (CalculiX, minutes each): the committed reference results via --report-only where
# they exist. Exit status: 0 when every example ran (the outputs are what is compared).
set -uo pipefail
bin=$(realpath "$1"); out=$2
here=$(cd "$(dirname "$0")" && pwd)
repo=${RAILWEAR_REPO:-$(git -C "$here" rev-parse --show-toplevel 2>/dev/null || pwd)}
mkdir -p "$out"
strip_times='del(.. | objects | .time_ms?, .seconds?, .time_s?, .elapsed_s?) | del(.. | objects | .stages?) | del(.. | objects | .created?, .ceres_full_report?)'
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$repo"
for f in examples/*.toml examples/fem/wheel_in_groove.toml examples/fem/rail_in_wheel_groove.toml; do
  name=$(echo "$f" | tr '/' '_')
  if grep -q '^\[wear\]' "$f"; then
    db="$work/$name.sqlite"
    "$bin" wear "$f" --db "$db" --steps 2 > /dev/null 2> "$out/$name.wear.stderr"
    echo "exit $?" > "$out/$name.wear.exit"
    run=$(sqlite3 "$db" "select name from runs limit 1")
    "$bin" history --db "$db" steps "$run" > "$out/$name.steps" 2>&1
    "$bin" history --db "$db" profile "$run" --format csv > "$out/$name.profile.csv" 2>&1
  else
    "$bin" contact "$f" --json - --csv "$work/p.csv" > "$work/j.json" 2> "$out/$name.stderr"
    echo "exit $?" > "$out/$name.exit"
    jq -S "$strip_times" "$work/j.json" > "$out/$name.json"
    cp "$work/p.csv" "$out/$name.pressure.csv" 2>/dev/null || true
    "$bin" contact "$f" 2>/dev/null | grep -v '^time ' > "$out/$name.summary"
  fi
done
for f in examples/calibration/synthetic.toml examples/calibration/contact_case_a.toml examples/calibration/contact_case_b.toml examples/calibration/paper_experiment.toml; do
  name=$(echo "$f" | tr '/' '_')
  "$bin" calibrate "$f" --json - --out "$work/c.toml" > "$work/j.json" 2> "$out/$name.stderr"
  echo "exit $?" > "$out/$name.exit"
  jq -S "$strip_times" "$work/j.json" > "$out/$name.json"
  grep -v '^# created:' "$work/c.toml" > "$out/$name.constants.toml"
done
for f in examples/fem/*.toml; do
  grep -q '^\[fem\]' "$f" || continue
  name=$(echo "$f" | tr '/' '_')
  for dir in examples/fem examples/fem/reference; do
    "$bin" fem-reference "$f" --report-only --out-dir "$dir" > "$out/$name.$(basename "$dir").report" 2>&1
    echo "exit $?" >> "$out/$name.$(basename "$dir").report"
  done
done
"$bin" init "$work/init.toml" > /dev/null 2>&1; cp "$work/init.toml" "$out/init.toml"
"$bin" accuracy examples/tread.toml --levels draft --repeats 1 --out "$work/acc" > /dev/null 2>&1
# Every column but the times and memory (columns 6-9).
for c in "$work"/acc/*.csv; do [ -f "$c" ] && cut -d, -f1-5,10- "$c" > "$out/accuracy_$(basename "$c")"; done
# Wall-clock figures in the logs: "15.12 s", "3.2 ms", "812 passes/s", progress ETA.
sed -i -E 's/[0-9.]+ ?(s|ms)\b/T/g; s/[0-9.e+]+ passes\/s/R/g; s/ETA [0-9:]+/ETA/g' "$out"/*stderr "$out"/*report
# The temporary folder and the repository path.
sed -i "s|$work|WORK|g; s|$repo|REPO|g" "$out"/*

echo "wrote $(ls "$out" | wc -l) files to $out"
