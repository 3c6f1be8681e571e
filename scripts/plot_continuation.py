#!/usr/bin/python3
"""The continuation diagram of `impactlab continue --plot` (or by hand).

    plot_continuation.py branch.csv out.png PARAM QNAME [bifurcation.csv]

q on the section against the parameter for every branch (stable parts solid,
unstable parts dashed, one colour per branch), the bifurcations of points.csv
(found beside branch.csv) marked and labelled, and, when given, the points of a
brute-force sweep's bifurcation.csv of the same range underneath in grey.
Each kind of point has its own marker (a branch point and a boundary such as
contact_boundary are told apart from folds); the legend sits below the axes.
Axes carry their quantities and units, and the title the scene and the
parameters held fixed (continuation.json beside branch.csv,
scripts/plot_labels.py).
"""
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

MARKERS = {"fold": ("s", "tab:green"), "branch_point": ("P", "tab:cyan"),
           "period_doubling": ("o", "tab:red"),
           "neimark_sacker": ("D", "tab:purple"), "grazing": ("*", "black"),
           "contact_onset": ("^", "tab:orange"), "contact_end": ("v", "tab:orange"),
           "stick_onset": ("^", "tab:brown"), "stick_end": ("v", "tab:brown")}
# a scene's boundaries (contact_boundary, ...): points.csv's type is their name
BOUNDARY_MARKER = ("X", "tab:olive")


def read(path):
    return plot_files.read_columns(path)


def marked_points(points, param):
    """The located points of `points` (points.csv's columns) by type:
    {type: (parameters, q)}, and how many could not be located (empty q: no
    state to draw them at)."""
    count = len(points["type"])
    located = np.asarray(points["located"]) == 1 if "located" in points else \
        np.ones(count, dtype=bool)
    types = np.asarray(points["type"])
    marked = {}
    for kind in np.unique(types) if count else []:
        rows = (types == kind) & located
        if rows.any():
            marked[str(kind)] = (np.asarray(points[param], dtype=float)[rows],
                                 np.asarray(points["q"], dtype=float)[rows])
    return marked, int(np.count_nonzero(~located))


def runs(mask):
    """(start, stop) index pairs of the runs of equal values in a boolean array."""
    edges = np.flatnonzero(np.diff(mask.astype(int))) + 1
    starts = np.concatenate(([0], edges))
    stops = np.concatenate((edges, [len(mask)]))
    return zip(starts, stops)


def branches_of(branch_table):
    """branch.csv's columns split into one table per branch (its `branch`
    column)."""
    numbers = branch_table["branch"]
    return [plot_files.rows_where(branch_table, numbers == number)
            for number in np.unique(numbers)]


def draw_continuation(branches, points, meta, param, q_name, sweep=None):
    """The branches (a list of tables with the columns of branch.csv: param,
    q, stable, period) stable solid and unstable dashed, the located points
    of `points` (points.csv's columns, or None) marked, and a sweep's points
    (bifurcation.csv's columns, or None) underneath in grey."""
    fig, ax = plt.subplots(figsize=(8, 6))
    if sweep is not None:
        swept = plot_files.as_columns(sweep)
        ax.plot(swept[param], swept["q"], ",", color="0.6", rasterized=True)
        ax.plot([], [], ".", color="0.6", label="sweep (brute force)")
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for index, table in enumerate(branches):
        rows = plot_files.as_columns(table)
        colour = colours[index % len(colours)]
        stable = np.asarray(rows["stable"]) == 1
        for start, stop in runs(stable):
            # overlap one point so that the stable and unstable pieces join
            piece = slice(start, min(stop + 1, len(stable)))
            ax.plot(rows[param][piece], rows["q"][piece], "-" if stable[start] else "--",
                    color=colour, linewidth=1.4)
        period = int(np.ravel(rows["period"])[0])
        ax.plot([], [], "-", color=colour, label=f"period {period} (dashed: unstable)")
    if points is not None:
        marked, not_located = marked_points(plot_files.as_columns(points), param)
        for kind, (where, q) in marked.items():
            marker, colour = MARKERS.get(kind, BOUNDARY_MARKER)
            ax.plot(where, q, marker, color=colour, markersize=8, linestyle="none",
                    label=kind.replace("_", " "))
        if not_located:
            ax.plot([], [], " ", label=f"{not_located} not located (points.csv)")
    ax.set_xlabel(plot_labels.key_label(meta, param))
    ax.set_ylabel(plot_labels.coordinate_labels(meta, q_name)[0] + " on the section")
    ax.set_title(plot_labels.title(meta, "continuation", (param,)), fontsize=8)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), fontsize=8, ncol=3,
              frameon=False)
    fig.tight_layout()
    return fig


def main(argv):
    if len(argv) < 5 or argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0 if len(argv) > 1 and argv[1] in ("-h", "--help") else 2)
    branch_csv, png, param, q_name, *sweep = argv[1:]
    directory = os.path.dirname(branch_csv)
    points_csv = os.path.join(directory, "points.csv")
    figure = draw_continuation(branches_of(read(branch_csv)),
                               read(points_csv) if os.path.exists(points_csv) else None,
                               plot_labels.read_meta(directory), param, q_name,
                               read(sweep[0]) if sweep else None)
    plot_files.save_figure(figure, png)


if __name__ == "__main__":
    main(sys.argv)
