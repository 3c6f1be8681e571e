"""Timings of the Python package against the CLI and the C++ API
(docs/performance.md, "From Python"). Run from the repository root after
scripts/build.sh:

    PYTHONPATH=build/python /usr/bin/python3 benchmarks/python_api_call.py [--sweep-repeats N]

Prints medians; the machine may be loaded, so the sweep runs alternate
(Python, CLI, Python, CLI, ...) and their ratio is what counts.
"""
import argparse
import json
import os
import statistics
import subprocess
import tempfile
import time
import timeit

import impactlab


def median_seconds(function, repeats, number):
    return statistics.median(timeit.repeat(function, repeat=repeats, number=number)) / number


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--sweep-repeats", type=int, default=3)
    parser.add_argument("--cli", default="build/impactlab")
    options = parser.parse_args()

    run_100 = median_seconds(lambda: impactlab.simulate("jin2003", V0=4.163, periods=100), 7, 3)
    print(f"simulate('jin2003', V0=4.163, periods=100): median {run_100 * 1e3:.2f} ms")

    scene = impactlab.scene("jin2003")
    tiny = median_seconds(lambda: impactlab.simulate(scene, periods=0.01), 15, 2000)
    print(f"tiny run (0.01 periods) from Python, Scene passed: median {tiny * 1e6:.2f} us per call")
    tiny_named = median_seconds(lambda: impactlab.simulate("jin2003", periods=0.01), 7, 200)
    print(f"tiny run from Python, scene by name (loads it): median {tiny_named * 1e6:.2f} us per call")

    python_times, cli_times = [], []
    with tempfile.TemporaryDirectory() as directory:
        for _ in range(options.sweep_repeats):
            start = time.perf_counter()
            result = impactlab.sweep("jin2003", param="omega=6:8:400", threads=2)
            python_times.append(time.perf_counter() - start)
            start = time.perf_counter()
            subprocess.run([options.cli, "sweep", "jin2003", "--param", "omega=6:8:400",
                            "--threads", "2", "--quiet", "--out", directory], check=True)
            cli_times.append(time.perf_counter() - start)
            # the same plan on both sides (section, transient, points, ...)
            with open(os.path.join(directory, "meta.json")) as meta:
                assert json.load(meta)["sweep"] == result.definition
    python_sweep, cli_sweep = statistics.median(python_times), statistics.median(cli_times)
    print(f"sweep of 400 omega values, 2 threads: Python median {python_sweep:.3f} s, "
          f"CLI median {cli_sweep:.3f} s, ratio {python_sweep / cli_sweep:.3f} "
          f"(runs: Python {[round(t, 3) for t in python_times]}, CLI {[round(t, 3) for t in cli_times]})")


if __name__ == "__main__":
    main()
