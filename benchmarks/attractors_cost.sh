#!/usr/bin/env bash
# What `attractors` costs against `basins` with the same number of runs, on
# jin2003 (Taylor, the scene's integrator; settling transient, 50 section
# points per run): alternated REPEATS times each (default 3), the median of
# each run's whole CPU time, user + system (the process included: the
# attractors' matching and its three files are part of its cost; CPU time,
# not wall time, so that other work on a shared machine counts less; one
# thread by default). Two pairs:
#   matched: the same 20 omega values and 100 initial angles each, the
#            samples drawn at random (attractors) or on a grid (basins
#            omega x initial.theta);
#   spec:    attractors over 20 omega values x 100 samples of the default box
#            against a 40 x 50 basins grid of (theta0, theta_dot0) at the
#            scene's omega.
# The two jobs integrate different initial states (and, for `spec`, other
# parameter values), so they take different numbers of steps: the line also
# gives the ratio of their steps (meta.json's counts) and the ratio of CPU
# time per step, the cost of the machinery itself.
# Prints one line per pair: the two medians (CPU s), attractors / basins, the
# steps' ratio, the per-step ratio, and every run's time.
# usage: benchmarks/attractors_cost.sh PROGRAM WORK_DIR [REPEATS] [THREADS]
set -eu
program=$1; work=$2; repeats=${3:-3}; threads=${4:-1}
mkdir -p "$work"
pairs=(
  "matched|attractors jin2003 --param omega=6:8:20 --samples 100 --box initial.theta=-0.06:0.06|basins jin2003 --x omega=6:8:20 --y initial.theta=-0.06:0.06:100"
  "spec|attractors jin2003 --param omega=6:8:20 --samples 100|basins jin2003 --x initial.theta=-0.0625:0.0625:40 --y initial.theta_dot=-0.9:1.1:50"
)
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
# user + system CPU seconds of one run of the command
seconds() { local TIMEFORMAT='%U + %S'; { time "$@" > /dev/null; } 2>&1 | tail -1 | bc -l; }
for entry in "${pairs[@]}"; do
  name=${entry%%|*}; rest=${entry#*|}
  attractors=${rest%%|*}; basins=${rest#*|}
  a=(); b=()
  for ((k = 0; k < repeats; ++k)); do
    # shellcheck disable=SC2086
    a+=("$(seconds "$program" $attractors --threads "$threads" --quiet --out "$work/attractors")")
    # shellcheck disable=SC2086
    b+=("$(seconds "$program" $basins --threads "$threads" --quiet --out "$work/basins")")
  done
  ma=$(printf '%s\n' "${a[@]}" | median)
  mb=$(printf '%s\n' "${b[@]}" | median)
  steps=$(/usr/bin/python3 -c "import json, sys; s = [json.load(open(p))['counts']['steps'] for p in sys.argv[1:]]; print(s[0] / s[1])" "$work/attractors/meta.json" "$work/basins/meta.json")
  printf '%-8s attractors %.2f s  basins %.2f s  ratio %.3f  steps ratio %.3f  per step %.3f  (runs: %s | %s)\n' \
    "$name" "$ma" "$mb" "$(echo "$ma / $mb" | bc -l)" "$steps" "$(echo "$ma / $mb / $steps" | bc -l)" \
    "${a[*]}" "${b[*]}"
done
