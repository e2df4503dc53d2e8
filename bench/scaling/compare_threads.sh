#!/bin/bash
# One thread against two, in short runs, for one or more builds of
# bench_anchors_ours side by side (issue 38: "a second core that pays"):
# 10 000 free bodies, the pile of 1000 without and with sleeping, each run
# its own process on both cores, interleaved so that builds meet the same
# machine. Before each run it prints how busy the machine was (both cores,
# over 0.3 s): other processes on the second core make two threads lose, so
# compare only rows taken at 0-1 %.
#   bench/scaling/compare_threads.sh BENCH_ANCHORS_OURS [MORE_BUILDS...]
# Environment: ROUNDS (1), SCENES (';'-separated bench_anchors_ours
# arguments), CPUS (0,1), STEPS_FREE (300), STEPS_PILE (1500).
set -eu
steps_free=${STEPS_FREE:-300}
steps_pile=${STEPS_PILE:-1500}
rounds=${ROUNDS:-1}
cpus=${CPUS:-0,1}
busy() {
  local a b
  read -r _ a1 a2 a3 a4 a5 _ < /proc/stat
  sleep 0.3
  read -r _ b1 b2 b3 b4 b5 _ < /proc/stat
  local total=$(( (b1 + b2 + b3 + b4 + b5) - (a1 + a2 + a3 + a4 + a5) ))
  local idle=$(( (b4 + b5) - (a4 + a5) ))
  echo $(( 100 * (total - idle) / (total > 0 ? total : 1) ))
}
IFS=';' read -ra scenes <<< "${SCENES:-free --n 10000 --steps $steps_free;pile --n 1000 --sleep 0 --steps $steps_pile;pile --n 1000 --sleep 1 --steps $steps_pile}"
for round in $(seq "$rounds"); do
  for scene in "${scenes[@]}"; do
    for bin in "$@"; do
      for threads in 1 2; do
        before=$(busy)
        # shellcheck disable=SC2086
        line=$(taskset -c "$cpus" "$bin" --scene $scene --reps 1 --threads "$threads" 2>&1 | grep '^REP' || true)
        mean=$(echo "$line" | sed -n 's/.* mean_ms=\([^ ]*\).*/\1/p')
        printf '%-44s round=%d %-36s threads=%d mean_ms=%-7s machine_busy_before=%s%%\n' \
          "$bin" "$round" "$scene" "$threads" "${mean:-failed}" "$before"
      done
    done
  done
done
