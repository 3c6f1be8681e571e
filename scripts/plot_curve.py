#!/usr/bin/python3
"""The two-parameter curve of `impactlab continue --param2 --plot` (or by hand).

    plot_curve.py curve.csv out.png PARAM1 PARAM2 [classes.csv]

The curve of the fold, period-doubling, grazing or contact onset/end point in
(PARAM1, PARAM2), its type read from curve.json beside curve.csv, drawn over the period map of a
2D sweep's classes.csv (the same two keys) when given. Axes carry their
quantities and units, and the title the scene and the parameters held fixed
(continuation.json beside curve.csv, scripts/plot_labels.py).
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


def curves_of(curve_table):
    """curve.csv's columns split into one table per curve: per branch (its
    `branch` column), and per start where a curve runs through a
    codimension-two point (its `start` column); one curve where there are
    neither."""
    if "branch" not in curve_table:
        return [curve_table]
    count = len(curve_table["branch"])
    starts = curve_table.get("start", np.array(["branch"] * count))
    keys = [(number, start) for number, start in zip(curve_table["branch"], starts)]
    order = list(dict.fromkeys(keys))  # each curve once, in the file's order
    return [plot_files.rows_where(curve_table, np.array([key == one for key in keys]))
            for one in order]


# how each codimension-two type of curve_points.csv is marked
CODIMENSION_TWO_MARKERS = {
    "grazing_period_doubling": ("D", "tab:purple", "grazing meets period doubling"),
    "grazing_fold": ("s", "tab:orange", "grazing meets fold"),
    "grazing_scenario_change": ("P", "tab:red", "grazing scenario changes"),
    "cusp": ("*", "tab:green", "cusp of folds"),
    "resonance_1_1": ("^", "tab:blue", "1:1 resonance"),
    "resonance_1_2": ("v", "tab:cyan", "1:2 resonance"),
    "degenerate_period_doubling": ("X", "tab:brown", "degenerate period doubling"),
}


def draw_curve(curves, kind, meta, param1, param2, classes=None, special_points=None):
    """The curves (tables with curve.csv's columns param1, param2, period) of
    the point of type `kind` in (param1, param2), over the period map of a
    2D sweep (classes.csv's columns, or None), with the codimension-two
    points located on them (curve_points.csv's columns, or None)."""
    fig, ax = plt.subplots(figsize=(7, 6))
    if classes is not None:
        data = plot_files.as_columns(classes)
        x = np.unique(data[param1])
        y = np.unique(data[param2])
        period = np.full((len(y), len(x)), np.nan)
        period[np.searchsorted(y, data[param2]), np.searchsorted(x, data[param1])] = np.where(
            data["period"] > 0, data["period"], np.nan)
        mesh = ax.pcolormesh(x, y, period, shading="nearest", cmap="tab10", vmin=0.5, vmax=10.5,
                             alpha=0.6)
        fig.colorbar(mesh, ax=ax, label="period of the section map, 2D sweep (blank: none found)")
    drawn = [plot_files.as_columns(curve) for curve in curves]
    drawn = [curve for curve in drawn if param1 in curve and len(curve[param1])]
    colours = ["black", "tab:red", "tab:blue", "tab:green"]
    for index, piece in enumerate(drawn):
        # one curve per branch (--switch: the doubled branches' curves too)
        period = f", period {int(np.ravel(piece['period'])[0])}" if "period" in piece else ""
        colour = colours[index % len(colours)]
        own_kind = str(np.ravel(piece["type"])[0]) if "type" in piece else kind
        start = str(np.ravel(piece["start"])[0]) if "start" in piece else "branch"
        origin = "continuation" if start == "branch" else "from the codimension-two point"
        ax.plot(piece[param1], piece[param2], "-", color=colour, linewidth=1.8,
                label=f"{own_kind.replace('_', ' ')} curve{period} ({origin})")
        if start == "branch":
            ax.plot(piece[param1][:1], piece[param2][:1], "o", color=colour, markersize=6,
                    label="start (located on the branch)" if index == 0 else None)
    if special_points is not None:
        points = plot_files.as_columns(special_points)
        types = np.atleast_1d(points.get("type", np.array([]))).astype(str)
        for name, (marker, colour, label) in CODIMENSION_TWO_MARKERS.items():
            chosen = types == name
            if np.any(chosen):
                ax.plot(np.atleast_1d(points[param1])[chosen], np.atleast_1d(points[param2])[chosen],
                        marker, color=colour, markersize=8, linestyle="none",
                        label=f"{label} (codimension two)")
    if drawn:
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), fontsize=8, ncol=2,
                  frameon=False)
    ax.set_xlabel(plot_labels.key_label(meta, param1))
    ax.set_ylabel(plot_labels.key_label(meta, param2))
    ax.set_title(plot_labels.title(meta, "two-parameter continuation", (param1, param2)),
                 fontsize=8)
    fig.tight_layout()
    return fig


def main(argv):
    if len(argv) < 5 or argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0 if len(argv) > 1 and argv[1] in ("-h", "--help") else 2)
    curve_csv, png, param1, param2, *sweep = argv[1:]
    directory = os.path.dirname(curve_csv)
    kind = "curve"
    curve_json = os.path.join(directory, "curve.json")
    if os.path.exists(curve_json):
        with open(curve_json, encoding="utf-8") as handle:
            kind = json.load(handle).get("type") or kind
    special = os.path.join(directory, "curve_points.csv")
    figure = draw_curve(curves_of(plot_files.read_columns(curve_csv)), kind,
                        plot_labels.read_meta(directory), param1, param2,
                        plot_files.read_columns(sweep[0]) if sweep else None,
                        plot_files.read_columns(special) if os.path.exists(special) else None)
    plot_files.save_figure(figure, png)


if __name__ == "__main__":
    main(sys.argv)
