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
# rbsim is the default contact solver (soft_step); rbsim-si and
# rbsim-si-nosleep are rbsim with contact.solver: sequential_impulses.
#
# Stacking cases run this repository's bench/stacks instead (rbsim, Bullet
# and ODE through its own adapters, the same REP/ROW format; build
# bench_stacks_rbsim, bench_stacks_bullet and bench_stacks_ode in BUILD_DIR):
# "pyramid:N" (the large pyramid, N cubes at its base: pyramid:90 is 4095
# cubes) and "stacks/SCENE:N" for either of its scenes ("stacks/stack:20" is
# the anchors' tower through bench/stacks, "stack:20" still the harness's).
# Their rows are labelled by the binaries: bullet-f64 (the double-precision
# Bullet), and NAME-nosleep without sleeping; mujoco has no adapter there.
# STEPS, if set, overrides every case's step count (the pyramid's 10 s take
# minutes per rep on one core; ANCHORS_BUILD_DIR is not read for stacking
# cases alone).
set -eu
build=$1
anchors=$2
reps=${3:-3}
cpu=${CPU:-1}
cases=${CASES:-"pile:100 pile:1000 pile:4000 stack:10 stack:20 spheres:1000"}
engines=${ENGINES:-"rbsim rbsim-nosleep bullet bullet-nosleep ode"}
steps=${STEPS:+--steps $STEPS}
for case in $cases; do
  scene=${case%%:*}
  n=${case##*:}
  stacks=
  case $scene in
    pyramid) stacks=$build/bench/stacks ;;
    stacks/*) stacks=$build/bench/stacks; scene=${scene#stacks/} ;;
  esac
  for engine in $engines; do
    if [ -n "$stacks" ]; then
      case $engine in
        rbsim) cmd="$stacks/bench_stacks_rbsim --sleep 1" ;;
        rbsim-nosleep) cmd="$stacks/bench_stacks_rbsim --sleep 0" ;;
        rbsim-si) cmd="$stacks/bench_stacks_rbsim --sleep 1 --solver sequential_impulses --label rbsim-si" ;;
        rbsim-si-nosleep) cmd="$stacks/bench_stacks_rbsim --sleep 0 --solver sequential_impulses --label rbsim-si-nosleep" ;;
        rbsim-before) cmd="${BEFORE:?BEFORE=build dir of the earlier commit}/bench/stacks/bench_stacks_rbsim --sleep 1 --label rbsim-before" ;;
        rbsim-before-nosleep) cmd="${BEFORE:?BEFORE=build dir of the earlier commit}/bench/stacks/bench_stacks_rbsim --sleep 0 --label rbsim-before-nosleep" ;;
        bullet) cmd="$stacks/bench_stacks_bullet --sleep 1" ;;
        bullet-nosleep) cmd="$stacks/bench_stacks_bullet --sleep 0" ;;
        ode) cmd="$stacks/bench_stacks_ode" ;;
        mujoco) echo "ROW | mujoco | $scene | $n | no bench/stacks adapter |"; continue ;;
        *) echo "unknown engine $engine" >&2; exit 2 ;;
      esac
      # The peers' adapters are built only where their libraries are.
      if [ ! -x "${cmd%% *}" ]; then
        echo "ROW | $engine | $scene | $n | not built (${cmd%% *}) |"
        continue
      fi
    else
      case $engine in
        rbsim) cmd="$build/bench/bench_anchors_ours --sleep 1" ;;
        rbsim-nosleep) cmd="$build/bench/bench_anchors_ours --sleep 0 --label rbsim-nosleep" ;;
        rbsim-si) cmd="$build/bench/bench_anchors_ours --solver sequential_impulses --sleep 1 --label rbsim-si" ;;
        rbsim-si-nosleep) cmd="$build/bench/bench_anchors_ours --solver sequential_impulses --sleep 0 --label rbsim-si-nosleep" ;;
        rbsim-before) cmd="${BEFORE:?BEFORE=build dir of the earlier commit}/bench/bench_anchors_ours --sleep 1 --label rbsim-before" ;;
        rbsim-before-nosleep) cmd="${BEFORE:?BEFORE=build dir of the earlier commit}/bench/bench_anchors_ours --sleep 0 --label rbsim-before-nosleep" ;;
        bullet) cmd="$anchors/bench_bullet --sleep 1" ;;
        bullet-nosleep) cmd="$anchors/bench_bullet --sleep 0 --label bullet-nosleep" ;;
        ode) cmd="$anchors/bench_ode" ;;
        mujoco) cmd="$anchors/bench_mujoco" ;;
        *) echo "unknown engine $engine" >&2; exit 2 ;;
      esac
    fi
    # shellcheck disable=SC2086 # $cmd and $steps are commands/options split on purpose
    taskset -c "$cpu" $cmd --scene "$scene" --n "$n" --reps "$reps" $steps 2>&1 | grep '^ROW' || \
      echo "ROW | $engine | $scene | $n | failed |"
  done
done
