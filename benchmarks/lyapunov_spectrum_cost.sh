#!/usr/bin/env bash
# What the Lyapunov spectrum costs against the largest exponent alone, on the
# same run: `poincare --lyapunov` and `poincare --lyapunov-spectrum`,
# alternated REPEATS times each (default 5) per scene, and the median of each
# run's own wall time (meta.json's wall_time_s: the section run and the
# tangent run, and for the spectrum the writing of lyapunov.csv's rows as
# they come; no process start). A fixed transient of 100 periods, so that
# both variants run the same periods. Prints one line per scene:
# the two medians (s) and their ratio spectrum / largest.
# usage: benchmarks/lyapunov_spectrum_cost.sh PROGRAM WORK_DIR [REPEATS]
set -eu
program=$1; work=$2; repeats=${3:-5}
here="$(cd "$(dirname "$0")" && pwd)"
examples="$here/../oscillators/model_file/examples"
mkdir -p "$work"
cases=(
  "jin2003 (N = 2, taylor)|jin2003 --transient 100 --points 10000"
  "linear_impact chaotic (N = 2, exact flow)|linear_impact --set omega=2.6 --transient 100 --points 40000"
  "impact_damper.toml (N = 4, dopri5)|$examples/impact_damper.toml --transient 100 --points 1500"
)
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
wall_time() { /usr/bin/python3 -c "import json, sys; print(json.load(open(sys.argv[1]))['wall_time_s'])" "$1"; }
for entry in "${cases[@]}"; do
  name=${entry%%|*}; arguments=${entry#*|}
  largest=(); spectrum=()
  for ((k = 0; k < repeats; ++k)); do
    # shellcheck disable=SC2086
    "$program" poincare $arguments --lyapunov --quiet --out "$work/largest"
    largest+=("$(wall_time "$work/largest/meta.json")")
    # shellcheck disable=SC2086
    "$program" poincare $arguments --lyapunov-spectrum --quiet --out "$work/spectrum"
    spectrum+=("$(wall_time "$work/spectrum/meta.json")")
  done
  a=$(printf '%s\n' "${largest[@]}" | median)
  b=$(printf '%s\n' "${spectrum[@]}" | median)
  printf '%-45s largest %.3f s  spectrum %.3f s  ratio %.3f\n' "$name" "$a" "$b" \
    "$(echo "$b / $a" | bc -l)"
done
