#!/bin/sh
# Writes this folder's data (about 5 s on one core), from the repository root:
#   sh notebooks_data/continuation/make_data.sh
set -e
cd "$(dirname "$0")"
impactlab=../../build/impactlab
$impactlab continue linear_impact --set sigma=0.2 --param omega=1.5:2.5 --out linear_impact --quiet
$impactlab sweep linear_impact --set sigma=0.2 --param omega=1.5:2.5:120 --points 16 \
  --out linear_impact_sweep1d --quiet
$impactlab continue jin2003 --param omega=5:9 --switch --out jin2003 --quiet
$impactlab sweep jin2003 --param omega=5:9:120 --points 16 --out jin2003_sweep1d --quiet
$impactlab continue jin2003 --param omega=5:9 --param2 V0=1.5:0.5 --out jin2003_curve --quiet
$impactlab sweep jin2003 --param omega=5:7.5:40 --param V0=0.5:1.5:25 --no-lyapunov \
  --out jin2003_sweep --quiet
