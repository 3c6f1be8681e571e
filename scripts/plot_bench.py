#!/usr/bin/python3
"""Work-precision plots of `impactlab bench`.

Usage: plot_bench.py DIR

Reads DIR/work_precision.csv and DIR/work_precision.json and writes, for each
bench case, DIR/<case>.png: the largest impact-time error over the first N
impacts against the CPU time per impact (left) and against the right-hand-side
evaluations per impact (right), one line per stepper over its tolerance
ladder; impactlab's steppers solid, SciPy's solve_ivp event loop dashed.
"""
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0 if len(sys.argv) == 2 else 2)
    directory = sys.argv[1]
    with open(os.path.join(directory, "work_precision.json")) as f:
        meta = json.load(f)
    with open(os.path.join(directory, "work_precision.csv")) as f:
        rows = list(csv.DictReader(f))
    for case in meta["cases"]:
        name = case["name"]
        reference = case["reference"]
        figure, (by_time, by_rhs) = plt.subplots(1, 2, figsize=(11, 4.5))
        series = {}
        for row in rows:
            if row["case"] != name or not row["max_time_error"] or not row["seconds_per_impact"]:
                continue
            if int(row["compared_impacts"]) < int(row["reference_impacts"]):
                continue
            key = (row["tool"], row["method"])
            error = max(float(row["max_time_error"]), 1e-17)
            series.setdefault(key, []).append(
                (float(row["rtol"]), error, float(row["seconds_per_impact"]) * 1e6,
                 float(row["rhs_per_impact"])))
        for (tool, method), points in sorted(series.items()):
            points.sort()
            style = "-o" if tool == "impactlab" else "--s"
            label = f"{tool} {method}"
            by_time.loglog([p[2] for p in points], [p[1] for p in points], style, label=label,
                           markersize=4)
            by_rhs.loglog([p[3] for p in points], [p[1] for p in points], style, label=label,
                          markersize=4)
        if reference["time_spread"] > 0:
            for axis in (by_time, by_rhs):
                axis.axhline(reference["time_spread"], color="grey", linewidth=0.8, linestyle=":",
                             label="reference spread")
        by_time.set_xlabel("CPU time per impact (µs, one core)")
        by_rhs.set_xlabel("right-hand-side evaluations per impact")
        for axis in (by_time, by_rhs):
            axis.set_ylabel("max impact-time error over the first "
                            f"{reference['impacts_compared']} impacts")
            axis.grid(True, which="major", alpha=0.3)
        by_time.legend(fontsize=7)
        figure.suptitle(f"{name}: work-precision (reference: {reference['method']})")
        figure.tight_layout()
        figure.savefig(os.path.join(directory, f"{name}.png"), dpi=110)
        plt.close(figure)


if __name__ == "__main__":
    main()
