#!/usr/bin/env bash
# How ensemble percentiles change from 32 to 64 samples (issue 19 point 4): the example
# ensemble's uncertain inputs (examples/sweep/ensemble.toml: the Archard coefficient log-normal
# with the literature's scatter, friction uniform 0.3-0.5, lateral spread normal) on one curve
# class (yaw 4 mrad) of examples/sweep/small_wear.toml shortened to PASSES (default 3e4), drawn
# by a Latin hypercube with seed 1 at 32 and at 64 samples, each swept under
# `mpirun -n RANKS` (default 2) and merged; prints the 5/50/95 % bands of W3 and the worn area
# at the final MGT for both, and their relative change. Not a test: a figure for the README.
#   bash tests/tools/ensemble_samples.sh build/app/railwear /tmp/ensemble_samples [PASSES] [RANKS]
set -euo pipefail
railwear=$(realpath "$1")
work=$2
passes=${3:-3e4}
ranks=${4:-2}
base=$(realpath "$(dirname "$0")/../../examples/sweep/small_wear.toml")
rm -rf "$work" && mkdir -p "$work" && cd "$work"
sed "s/^total_passes = .*/total_passes = $passes/" "$base" > base.toml
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
for n in 32 64; do
  cat > "plan$n.toml" <<PLAN
[sweep]
scene = "base.toml"
out_dir = "runs$n"
samples = $n
seed = 1

[[axis]]
key = "wear.k"
distribution = { kind = "lognormal" }

[[axis]]
key = "traffic[0].friction"
distribution = { kind = "uniform", min = 0.3, max = 0.5 }

[[axis]]
key = "traffic[0].lateral_shift_mm.std"
distribution = { kind = "normal", mean = 1.0, std = 0.3, min = 0.2 }
PLAN
  # A line whose run fails (a contact solve that does not converge for some sampled inputs)
  # stops the MPI merge: the complete runs are then merged by hand and banded without the plan.
  if ! mpirun -n "$ranks" --oversubscribe --bind-to none "$railwear" sweep "plan$n.toml" --mpi \
    > "sweep$n.out" 2> "sweep$n.err"; then
    grep '^railwear: error' "sweep$n.err" || true
    "$railwear" merge "runs$n.sqlite" "runs$n"/*.sqlite > /dev/null
  fi
  echo "$n samples: $("$railwear" history --db "runs$n.sqlite" sql \
    "SELECT count(*) FROM runs WHERE state = 'complete'" --tsv | tail -1) complete runs"
  "$railwear" history --db "runs$n.sqlite" bands --points 2 \
    --measures w3_mm,worn_area_mm2 --format csv 2> /dev/null | tail -n +2 \
    | awk -F, -v n="$n" '$3 > 0 { print n, $2, $3, $5, $6, $7 }' > "bands$n.txt"
done
echo "samples measure MGT p5 p50 p95"
cat bands32.txt bands64.txt
echo "change 32 -> 64 samples (relative):"
paste -d' ' bands32.txt bands64.txt | awk '{ printf "%s p5 %+.1f %%, p50 %+.1f %%, p95 %+.1f %%\n",
  $2, 100 * ($10 / $4 - 1), 100 * ($11 / $5 - 1), 100 * ($12 / $6 - 1) }'
