#!/usr/bin/env bash
# From a fresh clone: installs missing Debian packages, builds Release, runs the
# main job on the built-in default scene (jin2003, the pendulum between two
# walls of Jin, Hu & Bishop 2003) and says where the results and pictures are.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
scripts/build.sh

out="$PWD/out/demo"
echo
echo "== jin2003 at V0 = 1.5 m/s (the paper's default scene), 100 forcing periods"
build/impactlab simulate jin2003 --periods 100 --sample 0.005 --out "$out/jin2003"
echo
echo "== jin2003 at V0 = 4.163 m/s: chattering, sustained contact, release"
build/impactlab simulate jin2003 --set V0=4.163 --periods 20 --sample 0.001 --out "$out/jin2003-V0-4.163"

echo
echo "== the same under the paper's sliding-impact model (Model P)"
build/impactlab simulate jin2003 --set V0=4.163 --set model=paper --periods 20 --sample 0.001 \
  --out "$out/jin2003-V0-4.163-paper"

/usr/bin/python3 scripts/plot_simulation.py "$out/jin2003" "$out/jin2003-V0-4.163" \
  "$out/jin2003-V0-4.163-paper"

echo
echo "== the paper's Fig. 4 under Model P, Model N and the rigid-body model (about 5 s on 2 cores)"
build/impactlab reproduce jin2003 --out notebooks_data/jin2003

echo
echo "Results:"
for run in "$out/jin2003" "$out/jin2003-V0-4.163" "$out/jin2003-V0-4.163-paper"; do
  echo "  $run/events.csv      every impact and contact event"
  echo "  $run/trajectory.csv  sampled state"
  echo "  $run/meta.json       scene, integrator, counts, provenance"
  echo "  $run/simulation.png  the picture"
done
echo "  notebooks_data/jin2003/REPORT.md   the paper's Fig. 4 ranges beside the toolkit's"
echo "  notebooks_data/jin2003/fig4*.png   the figures (jin2003.ipynb draws them from the CSVs)"
