#!/bin/sh
# Issue 16's scaling figure: ms per step of the anchors' pile scene against
# N = 100 … 10 000 boxes, on one thread and on two, one process per point,
# pinned to both cores, without sleeping (every body solved every step).
# Writes BUILD_DIR/bench/scaling.csv and, with plot_scaling.py, an SVG plot.
#   bench/scaling/run_scaling.sh BUILD_DIR [STEPS] [OUT_DIR]
# Environment: SIZES overrides the list of N, THREADS the thread counts
# ("1 2"), CPUS the cores (0,1). Run it on a quiet machine.
set -eu
build=$1
steps=${2:-1500}
out=${3:-$build/bench}
sizes=${SIZES:-"100 200 500 1000 2000 5000 10000"}
threads=${THREADS:-"1 2"}
cpus=${CPUS:-0,1}
csv="$out/scaling.csv"
echo "n,threads,steps,mean_ms,p99_ms,contacts" > "$csv"
for n in $sizes; do
  for t in $threads; do
    line=$(taskset -c "$cpus" "$build/bench/bench_anchors_ours" --scene pile --n "$n" --reps 1 \
             --sleep 0 --steps "$steps" --threads "$t" --max-wall 900 2>&1 | grep '^REP' || true)
    mean=$(echo "$line" | sed -n 's/.* mean_ms=\([^ ]*\).*/\1/p')
    p99=$(echo "$line" | sed -n 's/.* p99_ms=\([^ ]*\).*/\1/p')
    contacts=$(echo "$line" | sed -n 's/.* contacts=\([^ ]*\).*/\1/p')
    echo "$n,$t,$steps,${mean:-failed},${p99:-},${contacts:-}" | tee -a "$csv"
  done
done
python3 "$(dirname "$0")/plot_scaling.py" "$csv" "$out/scaling.svg"
