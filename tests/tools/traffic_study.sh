#!/usr/bin/env bash
# Gauge-face wear against traffic (issue 15's must-show "after running-in, the W2 rate between 5
# and 10 MGT is within a factor 2 of the rate between 1 and 5 MGT"): the main job's scene
# (examples/curve_r600_vehicles.toml: coach and Y25 wagon, R 600 m, both rails) run to MGT
# (default 10) instead of 1, then each rail's W2 and W3 interpolated linearly in MGT between the
# stored steps at 1, 5 and MGT, and the rates between them. A run that stops early (a vehicle's
# curving without an equilibrium on the worn rails: the log's last line says why) is reported up
# to its last stored step L, at 1, (1 + L) / 2 and L MGT. Too long for a test (tens of minutes).
#   usage: tests/tools/traffic_study.sh [RAILWEAR] [WORKDIR] [MGT]
#   (TRAFFIC_STUDY_REUSE=1: analyse WORKDIR/traffic.sqlite of an earlier run without running;
#    TRAFFIC_STUDY_SPREAD=adaptive: the adaptive spread rule at its default tolerance instead of the
#    scene's own rule (the piecewise-linear rule on 16 nodes), adaptiveT: at tolerance T (e.g.
#    adaptive0.0025), TRAFFIC_STUDY_SPREAD=N: N fixed
#    Gauss-Hermite nodes, TRAFFIC_STUDY_SPREAD=linearM: the fixed piecewise-linear rule,
#    spread_nodes = M (linear64: the curve's converged reference); TRAFFIC_STUDY_STEP_MM=D: the
#    step limit max_depth_per_step_mm = D instead of the scene's 0.1 mm; TRAFFIC_STUDY_TIME=heun:
#    the second-order time step, time_step = "heun", instead of the scene's Euler step; docs/wear.md)
set -euo pipefail
bin=${1:-build/app/railwear}
work=${2:-$(mktemp -d)}
total=${3:-10}
here=$(cd "$(dirname "$0")/../.." && pwd)
mkdir -p "$work"
scene="$work/traffic.toml"
spread=${TRAFFIC_STUDY_SPREAD:-}
case "$spread" in
  "") rule="" ;;
  adaptive) rule="integration_tolerance = 0.005" ;;
  adaptive*[!0-9.]* | adaptive.*) echo "TRAFFIC_STUDY_SPREAD = '$spread': expected adaptiveT, T a tolerance such as 0.0025" >&2; exit 2 ;;
  adaptive*) rule="integration_tolerance = ${spread#adaptive}" ;;
  linear*[!0-9]* | linear) echo "TRAFFIC_STUDY_SPREAD = '$spread': expected linearM, M a node count" >&2; exit 2 ;;
  linear*) rule="spread_rule = \"piecewise_linear\"\nspread_nodes = ${spread#linear}" ;;
  *[!0-9]*) echo "TRAFFIC_STUDY_SPREAD = '$spread': expected 'adaptive', a node count or linearM" >&2; exit 2 ;;
  *) rule="quadrature_points = $spread" ;;
esac
step_mm=${TRAFFIC_STUDY_STEP_MM:-}
case "$step_mm" in
  "" | [0-9]*) ;;
  *) echo "TRAFFIC_STUDY_STEP_MM = '$step_mm': expected a step limit in mm such as 0.05" >&2; exit 2 ;;
esac
time_step=${TRAFFIC_STUDY_TIME:-}
case "$time_step" in
  "" | euler | heun) ;;
  *) echo "TRAFFIC_STUDY_TIME = '$time_step': expected euler or heun" >&2; exit 2 ;;
esac
# The scene's rule lines give way to the chosen rule (none chosen: they stay).
awk -v t="$total" -v r="$rule" -v d="$step_mm" -v ts="$time_step" '/^total_MGT = / {
    print "total_MGT = " t; if (ts != "") print "time_step = \"" ts "\""; next }
  d != "" && /^max_depth_per_step_mm = / { print "max_depth_per_step_mm = " d; next }
  r != "" && /^(quadrature_points|integration_tolerance|spread_rule|spread_nodes) = / {
    if (!done) print r; done = 1; next }
  { print }' \
  "$here/examples/curve_r600_vehicles.toml" > "$scene"
db="$work/traffic.sqlite"
if [ "${TRAFFIC_STUDY_REUSE:-0}" != 1 ]; then
  rm -f "$db" "$db-wal" "$db-shm"
  start=$(date +%s)
  "$bin" wear "$scene" --db "$db" > "$work/traffic.log" 2>&1 ||
    { echo "the run stopped early:"; grep "error" "$work/traffic.log" | tail -1; }
  echo "wear run: $(( $(date +%s) - start )) s wall ($work/traffic.log)"
fi
"$bin" history --db "$db" sql "SELECT s.mgt, s.w2_mm, s.w3_mm, l.w2_mm, l.w3_mm FROM steps s JOIN low_rail_steps l USING (run_id, step) ORDER BY s.step" --tsv 2>/dev/null |
  awk -F"\t" -v t="$total" '
    NR == 1 { next }  # the header
    { n++; m[n] = $1; v[n, 1] = $2; v[n, 2] = $3; v[n, 3] = $4; v[n, 4] = $5 }
    function at(x, k,   i, f) {
      for (i = 2; i <= n; i++) if (m[i] >= x) { f = (x - m[i-1]) / (m[i] - m[i-1]); return v[i-1, k] + f * (v[i, k] - v[i-1, k]) }
      return v[n, k]
    }
    END {
      split("high W2,high W3,low W2,low W3", name, ",")
      mid = 5; end = t
      if (m[n] < t * (1 - 1e-9)) { end = m[n]; mid = (1 + end) / 2; printf "stopped at %.3g MGT: checkpoints 1, %.3g, %.3g MGT\n", end, mid, end }
      lm = sprintf("%.3g", mid); le = sprintf("%.3g", end)
      printf "%-8s %9s %9s %9s %14s %14s %7s\n", "measure", "at 1 MGT", "at " lm, "at " le, "rate 1-" lm, "rate " lm "-" le, "ratio"
      for (k = 1; k <= 4; k++) {
        a = at(1, k); b = at(mid, k); c = at(end, k); r1 = (b - a) / (mid - 1); r2 = (c - b) / (end - mid)
        printf "%-8s %9.3f %9.3f %9.3f %14.4f %14.4f %7s\n", name[k], a, b, c, r1, r2, (r1 > 1e-6 ? sprintf("%.2f", r2 / r1) : "-")
      }
      printf "(mm and mm/MGT; %d stored steps)\n", n
    }'
