#!/usr/bin/env bash
# Runs the standard commands (simulate, poincare, sweep 1D and 2D, periodic,
# continue with --param2 and --switch, basins, compare, reproduce) on every
# built-in scene and shipped model file with two impactlab programs, and
# compares their files: data files with cmp, JSON files with json_same.py
# (their times and command line left out). One line per run; exit 1 if any
# differs. Pictures are not compared.
# usage: benchmarks/compare_outputs.sh OLD_PROGRAM NEW_PROGRAM WORK_DIR
set -u
old=$1; new=$2; work=$3
here="$(cd "$(dirname "$0")" && pwd)"
examples="$here/../oscillators/model_file/examples"
rm -rf "$work"; mkdir -p "$work"
cases=(
  "sim_jin|simulate jin2003 --set V0=4.163 --periods 100 --sample 0.01"
  "sim_jin_paper|simulate jin2003 --set V0=4.163 --periods 100 --set model=paper --sample 0.01"
  "sim_jin_rigid|simulate jin2003 --set model=rigid --set spin=free --set radius=0.02 --set V0=4 --periods 30"
  "sim_jin_rk|simulate jin2003 --set integrator.method=rkf78 --periods 50"
  "sim_lin|simulate linear_impact --periods 100 --sample 0.05"
  "sim_lin_exact|simulate linear_impact --set integrator.method=exact --periods 100"
  "sim_ball|simulate bouncing_ball --periods 100"
  "sim_duffing|simulate $examples/duffing_stop.toml --periods 50"
  "sim_damper|simulate $examples/impact_damper.toml --periods 50"
  "sim_ballmodel|simulate $examples/bouncing_ball_model.toml --periods 50"
  "sim_linmodel|simulate $examples/linear_impact_model.toml --periods 50"
  "poi_jin|poincare jin2003 --section impact:1 --points 200 --lyapunov"
  "poi_jin_strobe|poincare jin2003 --points 100"
  "poi_jin_q|poincare jin2003 --section q=0:up --points 50"
  "poi_paper|poincare jin2003 --set model=paper --set V0=4 --points 50 --lyapunov"
  "poi_lin|poincare linear_impact --points 100 --lyapunov"
  "poi_ball|poincare bouncing_ball --points 100"
  "poi_damper|poincare $examples/impact_damper.toml --points 50 --lyapunov"
  "poi_duffing|poincare $examples/duffing_stop.toml --points 50"
  "sw1_jin|sweep jin2003 --param omega=5:9:40 --points 16 --transient 50"
  "sw1_jin_lyap|sweep jin2003 --param V0=1:4:20 --lyapunov --points 16 --transient 50"
  "sw2_jin|sweep jin2003 --param omega=5:9:8 --param V0=1:4:6 --points 16 --transient 50"
  "sw1_lin|sweep linear_impact --param omega=2:2.6:30"
  "sw1_ball|sweep bouncing_ball --param A=0.005:0.02:20"
  "sw1_linmodel|sweep $examples/linear_impact_model.toml --param omega=2:2.6:15"
  "per_jin|periodic jin2003 --period 2"
  "per_lin|periodic linear_impact --set omega=2.27"
  "per_ball|periodic bouncing_ball"
  "per_linmodel|periodic $examples/linear_impact_model.toml"
  "con_jin|continue jin2003 --param omega=5:9"
  "con_jin2|continue jin2003 --param omega=5:9 --param2 V0=1.5:0.5 --max-step 0.04"
  "con_lin|continue linear_impact --param omega=2:2.4"
  "con_lin_switch|continue linear_impact --param omega=2:2.5 --switch"
  "con_lin_impact|continue linear_impact --param omega=2:2.5 --section impact:1 --param2 sigma=0.2:0.35 --curve grazing"
  "con_lin_graze|continue linear_impact --param omega=2:2.5 --param2 sigma=0.2:0.35 --curve grazing"
  "con_ball2|continue bouncing_ball --param A=0.0112:0.02 --start 0.044286522498880876,-0.6269934342801218 --param2 r=0.8:0.5 --max-step 0.00008"
  "con_linmodel|continue $examples/linear_impact_model.toml --param omega=2:2.4"
  "bas_ball|basins bouncing_ball --set A=0.00981 --x initial.y=0:0.1:30 --y initial.y_dot=-1:1:20"
  "bas_jin|basins jin2003 --x initial.theta=-0.05:0.05:12 --y initial.theta_dot=-1:1:10 --points 16 --transient 50"
  "cmp_jin|compare jin2003 --periods 30"
  "rep_jin|reproduce jin2003 --quiet"
)
fail=0
for entry in "${cases[@]}"; do
  name=${entry%%|*}; args=${entry#*|}
  for side in old new; do
    program=$old; [ $side = new ] && program=$new
    # shellcheck disable=SC2086
    (cd "$work" && timeout 900 "$program" $args --out "$work/$side/$name" --quiet > "$work/$side.$name.stdout" 2> "$work/$side.$name.stderr"; echo $? > "$work/$side.$name.status")
  done
  verdict=same
  if ! cmp -s "$work/old.$name.status" "$work/new.$name.status"; then verdict="exit $(cat $work/old.$name.status) vs $(cat $work/new.$name.status)"; fi
  files=0
  for f in $(cd "$work/old/$name" 2>/dev/null && find . -type f ! -name '*.png' ! -name '*.json' | sort); do
    files=$((files+1))
    if ! cmp -s "$work/old/$name/$f" "$work/new/$name/$f"; then verdict="differs: $f"; fi
  done
  # JSON files: the same apart from times and the command line
  for f in $(cd "$work/old/$name" 2>/dev/null && find . -type f -name '*.json' | sort); do
    files=$((files+1))
    if ! /usr/bin/python3 "$here/json_same.py" "$work/old/$name/$f" "$work/new/$name/$f" > "$work/jsondiff.$name.$(basename $f)" 2>&1; then verdict="differs: $f"; fi
  done
  for f in $(cd "$work/new/$name" 2>/dev/null && find . -type f ! -name '*.png' | sort); do
    [ -e "$work/old/$name/$f" ] || verdict="only new: $f"
  done
  [ "$verdict" = same ] || fail=1
  echo "$name: $files data files, exit $(cat $work/new.$name.status): $verdict"
done
exit $fail
