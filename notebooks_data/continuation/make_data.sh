#!/bin/sh
# Writes this folder's data (about 20 s on one core), from the repository root:
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
# grazing: the overdamped linear oscillator (zeta = 1.2) grazing at omega = 5, its
# discontinuity map and normal form (grazing.json), and impact-section sweeps
# through the graze, one a decade of the distance omega_g - omega (1e-3 ... 1e-7)
od="--set zeta=1.2 --set sigma=0.037267799624996496 --set integrator.method=taylor --set integrator.rtol=1e-14 --set integrator.atol=1e-16"
$impactlab continue linear_impact $od --param omega=5.5:4.5 --start -0.0333,0.0833 \
  --out overdamped_grazing --quiet
for decade in 3 4 5 6; do
  from=$(awk "BEGIN { printf \"%.15g\", 5 - 10^-$decade }")
  to=$(awk "BEGIN { printf \"%.15g\", 5 - 10^-($decade + 1) }")
  $impactlab sweep linear_impact $od --set initial.x=-0.0333 --set initial.x_dot=0.0833 \
    --param omega=$from:$to:24 --section impact:1 --points 40 --max-period 64 \
    --out overdamped_sweep_$decade --quiet
done
# jin2003's own graze: at omega = 8.5 the period-2 swing born from the hanging
# pendulum grazes both walls at V0 = 0.652035; a sweep through it on the
# impact section of the right wall
$impactlab continue jin2003 --set omega=8.5 --param V0=0.05:1.5 --start 0,0 --switch \
  --out jin2003_grazing --quiet
$impactlab sweep jin2003 --set omega=8.5 --param V0=0.6505:0.6545:81 --section impact:1 \
  --points 8 --out jin2003_grazing_sweep --quiet
