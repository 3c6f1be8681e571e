#!/usr/bin/python3
"""A grazing point's predicted scenario beside a brute-force sweep through it
(`impactlab continue --plot`, or by hand).

    plot_grazing.py grazing.json out.png PARAM [bifurcation.csv]

One row per grazing point of grazing.json (docs/analysis.md, "Discontinuity
map and normal form at a grazing point"). Left: the prediction, impact speed
against the distance |PARAM - p_g| past the graze on log axes: the normal
form's attractor at each of its distances (periodic orbits by their period,
chaotic ones as their spread of impact speeds, an orbit that leaves the
graze's neighbourhood marked along the top), the first impact's c sqrt|mu|
and the period-1 orbit's slope |mu|. Right: the sweep's section points on
the same distance axis, on the impacting side only: with a sweep on the
impact section (bifurcation.csv with a `wall` column) their impact speeds in
the gap's rate (|qdot| times |dh/dq|), drawn in grey under the prediction too;
with a stroboscopic sweep its q. The title carries the scene and the
scenario (continuation.json beside grazing.json).
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
    from . import plot_files, plot_labels
except ImportError:  # run as a script beside its modules
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import plot_files  # noqa: E402
    import plot_labels  # noqa: E402

KIND_STYLE = {"periodic": ("o", "tab:blue"), "chaotic": (".", "tab:orange"),
              "aperiodic": (".", "tab:purple")}


def sweep_past(point, sweep, param):
    """The sweep's rows past the graze (on the impacting side): their distances
    |p - p_g|, and their impact speeds in the gap's rate (an impact-section
    sweep) or their q (a stroboscopic one), with which of the two it is."""
    if sweep is None or param not in sweep:
        return None
    values = np.asarray(sweep[param], dtype=float)
    mu = values - point[param]
    rows = np.sign(mu) == point["impacting_side"]
    distance = np.abs(mu[rows])
    if "wall" in sweep:
        gradient = abs(point["discontinuity_map"]["gap_gradient"][0] or 1.0)
        speeds = np.abs(np.asarray(sweep["qdot"], dtype=float)[rows]) * gradient
        return distance, speeds, True
    return distance, np.asarray(sweep["q"], dtype=float)[rows], False


def draw_prediction(ax, point, param, past):
    distances = [abs(a["distance"]) for a in point["attractors"]]
    if not distances:
        return
    grid = np.geomspace(min(distances), max(distances), 100)
    if past is not None and past[2] and len(past[0]):
        shown = past[0] > 0
        ax.plot(past[0][shown], past[1][shown], ".", color="0.75", markersize=2,
                label="sweep's impacts")
    c = point.get("impact_speed_coefficient") or 0.0
    if c > 0:
        ax.plot(grid, c * np.sqrt(grid), "k-", linewidth=1,
                label=r"first impact $c\sqrt{|\mu|}$, $c$ = %.4g" % c)
    one = point.get("period_one", {})
    if one.get("side") == point["impacting_side"] and one.get("speed_slope"):
        ax.plot(grid, one["speed_slope"] * grid, "k--", linewidth=1,
                label="period-1 impacting orbit (unstable)")
    labelled = set()
    for a in point["attractors"]:
        d = abs(a["distance"])
        if a["kind"] == "escapes":
            ax.axvline(d, color="tab:red", alpha=0.25, linewidth=1)
            if "escapes" not in labelled:
                ax.plot([], [], color="tab:red", alpha=0.4, label="normal form leaves (jump)")
                labelled.add("escapes")
            continue
        marker, colour = KIND_STYLE.get(a["kind"], (".", "tab:gray"))
        speeds = [v for v in a["impact_speeds"] if v and v > 0]
        if not speeds:
            continue
        ax.plot([d] * len(speeds), speeds, marker, color=colour, markersize=4,
                label=None if a["kind"] in labelled else f"normal form: {a['kind']}")
        labelled.add(a["kind"])
        if a["kind"] == "periodic":
            ax.annotate(str(a["period"]), (d, max(speeds)), textcoords="offset points",
                        xytext=(0, 4), ha="center", fontsize=6, color=colour)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(f"distance past the graze |{param} - {point[param]:.10g}|")
    ax.set_ylabel("impact speed (gap rate)")
    ax.set_title(f"prediction: {point['scenario']} (rule: {point['rule']})", fontsize=8)
    ax.legend(fontsize=6, loc="lower right")


def draw_sweep(ax, point, param, past):
    if past is None or not len(past[0]):
        ax.text(0.5, 0.5, "no sweep given (--with-sweep bifurcation.csv),\n"
                "or none of its values past the graze", ha="center", va="center",
                transform=ax.transAxes, fontsize=8)
        ax.set_axis_off()
        return
    distance, values, impacts = past
    shown = distance > 0
    ax.plot(distance[shown], np.abs(values[shown]) if impacts else values[shown], ".",
            color="0.3", markersize=2)
    ax.set_xscale("log")
    if impacts:
        ax.set_yscale("log")
        ax.set_ylabel("impact speed (gap rate)")
    else:
        ax.set_ylabel("q on the sweep's section")
    ax.set_xlabel(f"distance past the graze |{param} - {point[param]:.10g}|")
    ax.set_title("brute-force sweep", fontsize=8)


def draw_grazing(points, meta, param, sweep=None):
    """The figure: one row per grazing point (grazing.json's entries),
    prediction left, sweep right; returns the matplotlib Figure."""
    shown = [p for p in points if p.get("available")]
    rows = max(1, len(shown))
    fig, axes = plt.subplots(rows, 2, figsize=(10, 4 * rows), squeeze=False)
    if not shown:
        axes[0][0].text(0.5, 0.5, "no normal form available", ha="center", va="center")
        for ax in axes[0]:
            ax.set_axis_off()
    for row, point in enumerate(shown):
        past = sweep_past(point, sweep, param)
        draw_prediction(axes[row][0], point, param, past)
        draw_sweep(axes[row][1], point, param, past)
        if past is not None and past[2] and len(past[0]):
            both = [axes[row][0].get_xlim(), axes[row][1].get_xlim()]
            limits = (min(b[0] for b in both), max(b[1] for b in both))
            for ax in axes[row]:
                ax.set_xlim(*limits)
            ylimits = [axes[row][0].get_ylim(), axes[row][1].get_ylim()]
            for ax in axes[row]:
                ax.set_ylim(min(y[0] for y in ylimits), max(y[1] for y in ylimits))
    fig.suptitle(plot_labels.title(meta, "grazing", (param,)) if meta else "grazing",
                 fontsize=8)
    fig.tight_layout()
    return fig


def main(argv):
    if len(argv) < 4 or argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0 if len(argv) > 1 and argv[1] in ("-h", "--help") else 2)
    grazing_json, png, param, *sweep = argv[1:]
    with open(grazing_json, encoding="utf-8") as handle:
        document = json.load(handle)
    directory = os.path.dirname(grazing_json)
    figure = draw_grazing(document["points"], plot_labels.read_meta(directory), param,
                          plot_files.read_columns(sweep[0]) if sweep else None)
    plot_files.save_figure(figure, png)


if __name__ == "__main__":
    main(sys.argv)
