#!/usr/bin/env bash
# Throughput of `railwear sweep --mpi` on one machine (issue 19): a plan of 8 short runs (the
# example sweep's base scene, examples/sweep/small_wear.toml, at 8 wear coefficients; 1 thread
# per run) run under `mpirun -n 1` and `mpirun -n 2`, each into a fresh folder and merged by
# rank 0, REPEATS times (default 3) in turn; prints every wall time, the medians and their
# ratio (target >= 1.8 on 2 idle cores), with the CPU time of each sweep (mpirun and its ranks:
# what dispatching costs) and the load average at its end. Not a test: a figure for the README.
# Only meaningful on idle cores: with Linux's autogroup scheduling every process of one session
# shares one slice of a busy machine, so a second rank gains nothing while others compute. On a
# shared machine (as root), give the benchmark's own session the cores for its minute or two:
#   setsid -w bash -c 'echo -20 > /proc/self/autogroup &&
#     bash tests/tools/sweep_throughput.sh build/app/railwear /tmp/sweep_throughput 5'
#   bash tests/tools/sweep_throughput.sh build/app/railwear /tmp/sweep_throughput [REPEATS=3]
set -euo pipefail
railwear=$(realpath "$1")
work=$2
repeats=${3:-3}
base=$(realpath "$(dirname "$0")/../../examples/sweep/small_wear.toml")
rm -rf "$work" && mkdir -p "$work" && cd "$work"
cat > plan.toml <<PLAN
# 8 short runs: the example sweep's base scene at 8 wear coefficients.
[sweep]
scene = "$base"
out_dir = "runs"

[[axis]]
key = "wear.k"
values = [1.0e-4, 1.1e-4, 1.2e-4, 1.3e-4, 1.4e-4, 1.5e-4, 1.6e-4, 1.7e-4]
PLAN
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
declare -A times
for r in $(seq 1 "$repeats"); do
  for ranks in 1 2; do
    rm -rf runs runs.sqlite
    TIMEFORMAT='%R %U %S'  # bash's time: wall, then the CPU time of mpirun and its ranks
    { time mpirun -n "$ranks" --oversubscribe --bind-to none "$railwear" sweep plan.toml --mpi \
      > "run_${ranks}_$r.out" 2> "run_${ranks}_$r.err"; } 2> "time_${ranks}_$r.txt"
    read -r t user sys < "time_${ranks}_$r.txt"
    times[$ranks]="${times[$ranks]:-} $t"
    echo "repeat $r, $ranks rank(s): 8 runs and their merge in $t s wall, $(echo "$user $sys" | awk '{ printf "%.2f", $1 + $2 }') s CPU (load $(cut -d' ' -f1 /proc/loadavg))"
  done
done
median() { tr ' ' '\n' | grep -v '^$' | sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
m1=$(echo "${times[1]}" | median)
m2=$(echo "${times[2]}" | median)
echo "median wall: 1 rank $m1 s, 2 ranks $m2 s; throughput 2 ranks / 1 rank: $(echo "$m1 $m2" | awk '{ printf "%.2f", $1 / $2 }')x (target >= 1.8)"
