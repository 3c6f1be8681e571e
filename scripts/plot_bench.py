#!/usr/bin/python3
"""Work-precision plots of `impactlab bench`.

Usage: plot_bench.py DIR

Reads DIR/work_precision.csv and DIR/work_precision.json and writes, for each
bench case, DIR/<case>.png: the largest impact-time error over the first N
impacts against the CPU time per impact (left) and against the right-hand-side
evaluations per impact (right), one line per stepper over its tolerance
ladder; impactlab's steppers solid, SciPy's solve_ivp event loop dashed.
"""
import json
import os
import sys

import matplotlib

if __name__ == "__main__":
    matplotlib.use("Agg")  # a script writes files; no window
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

try:  # in the Python package impactlab (impactlab.figures)
    from . import plot_files
except ImportError:  # run as a script beside its modules
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import plot_files  # noqa: E402


def draw_work_precision(rows, name, reference):
    """One case's work-precision figure. `rows`: work_precision.csv's
    columns (tool, method, rtol, max_time_error, seconds_per_impact,
    rhs_per_impact, compared_impacts, reference_impacts) of that case;
    `reference`: work_precision.json's (method, time_spread,
    impacts_compared). A row that compared fewer impacts than the reference
    has (it stopped early) is left out."""
    rows = plot_files.as_columns(rows)
    figure, (by_time, by_rhs) = plt.subplots(1, 2, figsize=(11, 4.5))
    error = np.asarray(rows["max_time_error"], dtype=float)
    seconds = np.asarray(rows["seconds_per_impact"], dtype=float)
    usable = (np.isfinite(error) & np.isfinite(seconds)
              & (np.asarray(rows["compared_impacts"], dtype=float)
                 >= np.asarray(rows["reference_impacts"], dtype=float)))
    tools = np.asarray(rows["tool"], dtype=str)
    methods = np.asarray(rows["method"], dtype=str)
    for tool, method in sorted(set(zip(tools[usable], methods[usable]))):
        mine = usable & (tools == tool) & (methods == method)
        order = np.argsort(np.asarray(rows["rtol"], dtype=float)[mine])
        shown = np.maximum(error[mine][order], 1e-17)
        style = "-o" if tool == "impactlab" else "--s"
        label = f"{tool} {method}"
        by_time.loglog(seconds[mine][order] * 1e6, shown, style, label=label, markersize=4)
        by_rhs.loglog(np.asarray(rows["rhs_per_impact"], dtype=float)[mine][order], shown, style,
                      label=label, markersize=4)
    if reference.get("time_spread", 0) > 0:
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
    return figure


def main():
    if len(sys.argv) != 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0 if len(sys.argv) == 2 else 2)
    directory = sys.argv[1]
    with open(os.path.join(directory, "work_precision.json"), encoding="utf-8") as handle:
        meta = json.load(handle)
    rows = plot_files.read_columns(os.path.join(directory, "work_precision.csv"))
    cases = np.asarray(rows["case"], dtype=str)
    for case in meta["cases"]:
        figure = draw_work_precision(plot_files.rows_where(rows, cases == case["name"]),
                                     case["name"], case["reference"])
        plot_files.save_figure(figure, os.path.join(directory, f"{case['name']}.png"))
        plt.close(figure)


if __name__ == "__main__":
    main()
