#!/usr/bin/env python3
"""How fast the explorer answers (docs/performance.md, "The explorer"): the
server-side and round-trip times of the two requests a slider move on
jin2003 makes (the time series and the section, as the page asks for them),
and a 400-column orbit diagram against the equivalent `impactlab sweep`.

Usage: explore_responsiveness.py IMPACTLAB [REPETITIONS]
(the round trip here is http.client's; the browser's own end-to-end time is
written by the test explore_browser to build/tests/explore_browser/explore_timings.json)."""
import json
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "tests" / "explore"))
os.environ["IMPACTLAB_CLI"] = os.path.abspath(sys.argv[1])
from conftest import Explorer  # noqa: E402  (after IMPACTLAB_CLI is set)

REPETITIONS = int(sys.argv[2]) if len(sys.argv) > 2 else 20
# the page's defaults: 20 periods sampled 64 times a period; 300 section
# points after 100 periods; a diagram of 32 points per value after 100 periods
TRAJECTORY = {"periods": 20, "samples_per_period": 64}
SECTION = {"transient": 100, "points": 300}
DIAGRAM = {"key": "V0", "from": 1.2, "to": 1.8, "columns": 400, "points": 32, "transient": 100,
           "threads": 1}


def timed_job(server, kind, values, options):
    started = time.perf_counter()
    state = server.job(kind, values, options, timeout=600)
    assert state["state"] == "done", state
    return state["server_ms"], 1e3 * (time.perf_counter() - started)


def main():
    server = Explorer()
    try:
        rows = {}
        for kind, options in (("trajectory", TRAJECTORY), ("section", SECTION)):
            times = [timed_job(server, kind, {"e_n": 0.3 + 0.001 * k}, options)
                     for k in range(REPETITIONS)]
            rows[kind] = {"server_ms_median": statistics.median(t[0] for t in times),
                          "round_trip_ms_median": statistics.median(t[1] for t in times),
                          "server_ms_max": max(t[0] for t in times)}
        diagram_server_ms, diagram_round_trip_ms = timed_job(server, "diagram", {}, DIAGRAM)
        rows["diagram_400"] = {"server_ms": diagram_server_ms, "round_trip_ms": diagram_round_trip_ms}
    finally:
        server.stop()
    with tempfile.TemporaryDirectory() as out:
        command = [os.environ["IMPACTLAB_CLI"], "sweep", "jin2003", "--param",
                   "V0={}:{}:{}".format(DIAGRAM["from"], DIAGRAM["to"], DIAGRAM["columns"]),
                   "--transient", str(DIAGRAM["transient"]), "--points", str(DIAGRAM["points"]),
                   "--threads", "1", "--quiet", "--out", out]
        started = time.perf_counter()
        subprocess.run(command, check=True)
        rows["sweep_400_wall_ms"] = 1e3 * (time.perf_counter() - started)
        with open(os.path.join(out, "meta.json")) as handle:
            rows["sweep_400_meta_wall_s"] = json.load(handle)["run"].get("wall_time_s")
    print(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
