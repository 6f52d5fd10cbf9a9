#!/usr/bin/env bash
# The merge time for N runs (issue 19): the example sweep's line 5 (examples/sweep/, 20 steps,
# 174 rows) run once, its database copied N times with the run renamed copy-NNN (sqlite3 CLI), and
# `railwear merge` timed twice: copying every run, then again (nothing to copy, every run
# compared with the one already there).
#   bash tests/tools/merge_time.sh build/app/railwear /tmp/merge_time [N=100]
set -euo pipefail
railwear=$(realpath "$1")
work=$2
n=${3:-100}
plan=$(realpath "$(dirname "$0")/../../examples/sweep/k_and_friction.toml")
rm -rf "$work" && mkdir -p "$work/runs" "$work/copies" && cd "$work"
"$railwear" sweep "$plan" --index 5 --out-dir runs > /dev/null 2> sweep.log
src=$(ls runs/0005-*.sqlite)
for i in $(seq -w 0 $((n - 1))); do
  cp "$src" "copies/r$i.sqlite"
  sqlite3 "copies/r$i.sqlite" "UPDATE runs SET name = 'copy-$i'"
done
for pass in first again; do
  start=$(date +%s.%N)
  "$railwear" merge study.sqlite copies/r*.sqlite > "merge_$pass.out" 2> "merge_$pass.err"
  end=$(date +%s.%N)
  echo "merge $pass: $(tail -1 "merge_$pass.err" | sed 's/^railwear: //'); wall $(echo "$start $end" | awk '{ printf "%.1f", $2 - $1 }') s"
done
