#!/usr/bin/env bash
# Wear rate against curve radius (issue 15): the R 600 vehicle example
# (examples/curve_r600_vehicles.toml) on R 300, 600 and 1200 m at the same cant and the same
# unbalanced acceleration (each vehicle's speed scaled by sqrt(R / 600 m)), one wear step each.
# Prints each rail's worn area and W2/W3 per MGT of step 1 (the rate of the first 0.1 mm).
#   usage: tests/tools/radius_study.sh [RAILWEAR] [WORKDIR]
set -euo pipefail
bin=${1:-build/app/railwear}
work=${2:-$(mktemp -d)}
here=$(cd "$(dirname "$0")/../.." && pwd)
mkdir -p "$work"
printf '%-8s %-6s %12s %12s %12s %12s\n' radius_m rail MGT area_mm2_MGT W2_mm_MGT W3_mm_MGT
for radius in 300 600 1200; do
  scale=$(awk -v r="$radius" 'BEGIN { printf "%.6f", sqrt(r / 600.0) }')
  scene="$work/r$radius.toml"
  awk -v r="$radius" -v s="$scale" '
    /^radius_m = / { print "radius_m = " r; next }
    /^speed_m_s = / { printf "speed_m_s = %.4f\n", $3 * s; next }
    { print }' "$here/examples/curve_r600_vehicles.toml" > "$scene"
  db="$work/r$radius.sqlite"
  rm -f "$db" "$db-wal" "$db-shm"
  "$bin" wear "$scene" --db "$db" --steps 1 > "$work/r$radius.log" 2>&1
  run=$(sed -n 's/^name = "\(.*\)"/\1/p' "$scene" | head -1)
  "$bin" history --db "$db" sql "SELECT s.mgt, s.worn_area_mm2, s.w2_mm, s.w3_mm, l.worn_area_mm2, l.w2_mm, l.w3_mm FROM steps s JOIN low_rail_steps l USING (run_id, step) WHERE s.step = 1" --tsv 2>/dev/null | tail -1 |
    awk -F"\t" -v r="$radius" '{
      printf "%-8s %-6s %12.5f %12.3f %12.4f %12.4f\n", r, "high", $1, $2 / $1, $3 / $1, $4 / $1
      printf "%-8s %-6s %12.5f %12.3f %12.4f %12.4f\n", r, "low", $1, $5 / $1, $6 / $1, $7 / $1 }'
done
