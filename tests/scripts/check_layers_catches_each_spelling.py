#!/usr/bin/env python3
"""The layer check on tests/data/layer_violation/, a tree with one deliberate
violation per include spelling: it must report exactly these, no more and no
fewer, so a check that silently finds nothing (or finds noise) fails.

Usage: check_layers_catches_each_spelling.py CHECK_LAYERS_PY TREE"""
import subprocess
import sys

EXPECTED = {
    "analysis/downward_unprefixed.hpp:5: io/scene.hpp is a project header: include it as <impactlab/...>",
    "src/core/engine_order.hpp:5: engine/core (layer 1.1) includes impactlab/simulate/simulator.hpp "
    "of engine/simulate (layer 1.4)",
    "src/core/src_prefixed.hpp:5: engine/core (layer 1.1) includes src/integrate/taylor_stepper.hpp "
    "of engine/integrate (layer 1.2)",
    "src/io/angle_prefixed.hpp:5: io (layer 2) includes impactlab/api/oscillator_registry.hpp "
    "of scene API (layer 5)",
    "src/io/angle_unprefixed.hpp:5: io (layer 2) includes api/oscillator_registry.hpp of scene API (layer 5)",
    "src/io/parent_relative.hpp:5: io (layer 2) includes ../../api/oscillator_registry.hpp "
    "of scene API (layer 5)",
    "src/io/quoted_unprefixed.hpp:5: io (layer 2) includes api/oscillator_registry.hpp of scene API (layer 5)",
}

check = subprocess.run([sys.executable, sys.argv[1], sys.argv[2]], capture_output=True, text=True)
lines = check.stdout.splitlines()
reported = set(lines[:-1])
missing, extra = EXPECTED - reported, reported - EXPECTED
for line in sorted(missing):
    print("not reported:", line)
for line in sorted(extra):
    print("reported but not planted:", line)
if check.returncode != 1:
    print("exit status", check.returncode, "(1 expected)")
if missing or extra or check.returncode != 1 or lines[-1] != "layers: 7 offending include(s)":
    sys.exit(1)
print("the layer check reports each of the 7 planted includes")
