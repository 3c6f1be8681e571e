#!/usr/bin/python3
"""The continuation diagram of `impactlab continue --plot` (or by hand).

    plot_continuation.py branch.csv out.png PARAM QNAME [bifurcation.csv]
                         [--y COLUMN LABEL]

q on the section against the parameter for every branch (stable parts solid,
unstable parts dashed, parts without multipliers dotted: an impulse on the
friction cone's edge; one colour per branch), or another column of
branch.csv with --y (e.g. `--y state3 "ball's spin rate (rad/s)"`), the
bifurcations of points.csv
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
           "stick_onset": ("^", "tab:brown"), "stick_end": ("v", "tab:brown"),
           "chatter_onset": ("D", "tab:pink")}
# a scene's boundaries (contact_boundary, ...): points.csv's type is their name
BOUNDARY_MARKER = ("X", "tab:olive")


def read(path):
    return plot_files.read_columns(path)


def marked_points(points, param, y="q"):
    """The located points of `points` (points.csv's columns) by type:
    {type: (parameters, y)}, and how many could not be located (empty y: no
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
                                 np.asarray(points[y], dtype=float)[rows])
    return marked, int(np.count_nonzero(~located))


def runs_of_values(values):
    """(start, stop) index pairs of the runs of equal values in an array."""
    edges = np.flatnonzero(np.diff(np.asarray(values, dtype=int))) + 1
    starts = np.concatenate(([0], edges))
    stops = np.concatenate((edges, [len(values)]))
    return zip(starts, stops)


def branches_of(branch_table):
    """branch.csv's columns split into one table per branch (its `branch`
    column)."""
    numbers = branch_table["branch"]
    return [plot_files.rows_where(branch_table, numbers == number)
            for number in np.unique(numbers)]


class MissingColumn(ValueError):
    """The column asked for (`y`, the script's --y) is not in the files."""


def draw_continuation(branches, points, meta, param, q_name, sweep=None, y="q", y_label=None):
    """The branches (a list of tables with the columns of branch.csv: param,
    q, stable, period, multiplier1_re) stable solid, unstable dashed and
    without multipliers dotted, the located points of `points` (points.csv's
    columns, or None) marked, and a sweep's points (bifurcation.csv's
    columns, or None) underneath in grey. `y` is the column drawn (q on the
    section unless said), `y_label` its axis label. ValueError naming `y`
    where the branches, or the sweep given, have no such column."""
    swept = plot_files.as_columns(sweep)
    for name, table in (("the branches", branches[0] if branches else None), ("the sweep", swept)):
        if table is not None and y not in table:
            raise MissingColumn(f"y = {y!r}: not a column of {name} ({', '.join(table)})")
    fig, ax = plt.subplots(figsize=(8, 6))
    if sweep is not None:
        ax.plot(swept[param], swept[y], ",", color="0.6", rasterized=True)
        ax.plot([], [], ".", color="0.6", label="sweep (brute force)")
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for index, table in enumerate(branches):
        rows = plot_files.as_columns(table)
        colour = colours[index % len(colours)]
        # 0 unstable, 1 stable, 2 no multipliers (the friction cone's edge)
        style = np.where(np.asarray(rows["stable"]) == 1, 1, 0)
        # branch.csv's multiplier1_re, or a Python result's complex multiplier1
        multiplier = rows["multiplier1_re"] if "multiplier1_re" in rows else rows.get("multiplier1")
        if multiplier is not None:
            style = np.where(np.isnan(np.real(np.asarray(multiplier, dtype=complex))), 2, style)
        for start, stop in runs_of_values(style):
            # overlap one point so that the pieces join
            piece = slice(start, min(stop + 1, len(style)))
            ax.plot(rows[param][piece], rows[y][piece], ("--", "-", ":")[style[start]],
                    color=colour, linewidth=1.4)
        period = int(np.ravel(rows["period"])[0])
        edge = "dotted: no multipliers, " if (style == 2).any() else ""
        ax.plot([], [], "-", color=colour, label=f"period {period} ({edge}dashed: unstable)")
    if points is not None:
        marked, not_located = marked_points(plot_files.as_columns(points), param, y)
        for kind, (where, value) in marked.items():
            marker, colour = MARKERS.get(kind, BOUNDARY_MARKER)
            ax.plot(where, value, marker, color=colour, markersize=8, linestyle="none",
                    label=kind.replace("_", " "))
        if not_located:
            ax.plot([], [], " ", label=f"{not_located} not located (points.csv)")
    ax.set_xlabel(plot_labels.key_label(meta, param))
    ax.set_ylabel((y_label or plot_labels.coordinate_labels(meta, q_name)[0]) + " on the section")
    ax.set_title(plot_labels.title(meta, "continuation", (param,)), fontsize=8)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), fontsize=8, ncol=3,
              frameon=False)
    fig.tight_layout()
    return fig


def main(argv):
    if len(argv) < 5 or argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0 if len(argv) > 1 and argv[1] in ("-h", "--help") else 2)
    arguments = argv[1:]
    y, y_label = "q", None
    if "--y" in arguments:
        at = arguments.index("--y")
        if len(arguments) < at + 3:
            print("plot_continuation.py: --y takes COLUMN LABEL", file=sys.stderr)
            sys.exit(2)
        y, y_label = arguments[at + 1], arguments[at + 2]
        del arguments[at:at + 3]
    branch_csv, png, param, q_name, *sweep = arguments
    directory = os.path.dirname(branch_csv)
    points_csv = os.path.join(directory, "points.csv")
    try:
        figure = draw_continuation(branches_of(read(branch_csv)),
                                   read(points_csv) if os.path.exists(points_csv) else None,
                                   plot_labels.read_meta(directory), param, q_name,
                                   read(sweep[0]) if sweep else None, y, y_label)
    except MissingColumn as error:
        print(f"plot_continuation.py: --{error}", file=sys.stderr)
        sys.exit(2)
    plot_files.save_figure(figure, png)


if __name__ == "__main__":
    main(sys.argv)
