#!/bin/sh
# The contact issue's comparison: rbsim beside Bullet (with and without
# deactivation), ODE and MuJoCo on the anchors harness's scenes, one process
# per case, pinned to one core, printing the harness's table rows. Run it on
# a quiet machine; absolute times drift, so compare rows of the same run.
#   bench/compare_anchors.sh BUILD_DIR ANCHORS_BUILD_DIR [REPS]
# Build the anchors harness first (it is not part of this repository; its
# own README says how).
# Environment: CASES overrides the list ("scene:n ..."), ENGINES the engines
# ("rbsim bullet bullet-nosleep ode mujoco"), CPU the core (1). To compare a
# change with the code before it in one run, build the earlier commit too and
# add rbsim-before and rbsim-before-nosleep to ENGINES with BEFORE=its build dir.
set -eu
build=$1
anchors=$2
reps=${3:-3}
cpu=${CPU:-1}
cases=${CASES:-"pile:100 pile:1000 pile:4000 stack:10 stack:20 spheres:1000"}
engines=${ENGINES:-"rbsim rbsim-nosleep bullet bullet-nosleep ode"}
for case in $cases; do
  scene=${case%%:*}
  n=${case##*:}
  for engine in $engines; do
    case $engine in
      rbsim) cmd="$build/bench/bench_anchors_ours --sleep 1" ;;
      rbsim-nosleep) cmd="$build/bench/bench_anchors_ours --sleep 0 --label rbsim-nosleep" ;;
      rbsim-before) cmd="${BEFORE:?BEFORE=build dir of the earlier commit}/bench/bench_anchors_ours --sleep 1 --label rbsim-before" ;;
      rbsim-before-nosleep) cmd="${BEFORE:?BEFORE=build dir of the earlier commit}/bench/bench_anchors_ours --sleep 0 --label rbsim-before-nosleep" ;;
      bullet) cmd="$anchors/bench_bullet --sleep 1" ;;
      bullet-nosleep) cmd="$anchors/bench_bullet --sleep 0 --label bullet-nosleep" ;;
      ode) cmd="$anchors/bench_ode" ;;
      mujoco) cmd="$anchors/bench_mujoco" ;;
      *) echo "unknown engine $engine" >&2; exit 2 ;;
    esac
    # shellcheck disable=SC2086 # $cmd is a command with its options
    taskset -c "$cpu" $cmd --scene "$scene" --n "$n" --reps "$reps" 2>&1 | grep '^ROW' || \
      echo "ROW | $engine | $scene | $n | failed |"
  done
done
