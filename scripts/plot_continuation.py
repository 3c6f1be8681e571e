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

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plot_labels  # noqa: E402

MARKERS = {"fold": ("s", "tab:green"), "branch_point": ("P", "tab:cyan"),
           "period_doubling": ("o", "tab:red"),
           "neimark_sacker": ("D", "tab:purple"), "grazing": ("*", "black"),
           "contact_onset": ("^", "tab:orange"), "contact_end": ("v", "tab:orange"),
           "stick_onset": ("^", "tab:brown"), "stick_end": ("v", "tab:brown")}
# a scene's boundaries (contact_boundary, ...): points.csv's type is their name
BOUNDARY_MARKER = ("X", "tab:olive")


def read(path):
    data = np.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding="utf-8")
    return np.atleast_1d(data)


def marked_points(points, param):
    """The located points of points.csv by type: {type: (parameters, q)}, and
    how many could not be located (empty q: no state to draw them at; a
    column of empty fields reads as False, which would draw them at q = 0)."""
    located = np.asarray(points["located"]) == 1 if "located" in points.dtype.names else \
        np.ones(len(points), dtype=bool)
    marked = {}
    for kind in np.unique(points["type"]) if len(points) else []:
        rows = points[(points["type"] == kind) & located]
        if len(rows):
            marked[str(kind)] = (np.asarray(rows[param], dtype=float),
                                 np.asarray(rows["q"], dtype=float))
    return marked, int(np.count_nonzero(~located))


def runs(mask):
    """(start, stop) index pairs of the runs of equal values in a boolean array."""
    edges = np.flatnonzero(np.diff(mask.astype(int))) + 1
    starts = np.concatenate(([0], edges))
    stops = np.concatenate((edges, [len(mask)]))
    return zip(starts, stops)


def main(argv):
    if len(argv) < 5 or argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0 if len(argv) > 1 and argv[1] in ("-h", "--help") else 2)
    branch_csv, png, param, q_name, *sweep = argv[1:]
    branch = read(branch_csv)
    meta = plot_labels.read_meta(os.path.dirname(branch_csv))
    fig, ax = plt.subplots(figsize=(8, 6))
    if sweep:
        points = read(sweep[0])
        ax.plot(points[param], points["q"], ",", color="0.6", rasterized=True)
        ax.plot([], [], ".", color="0.6", label="sweep (brute force)")
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for index in np.unique(branch["branch"]):
        rows = branch[branch["branch"] == index]
        colour = colours[int(index) % len(colours)]
        stable = rows["stable"] == 1
        for start, stop in runs(stable):
            # overlap one point so that the stable and unstable pieces join
            piece = rows[start:min(stop + 1, len(rows))]
            ax.plot(piece[param], piece["q"], "-" if stable[start] else "--", color=colour,
                    linewidth=1.4)
        ax.plot([], [], "-", color=colour, label=f"period {rows['period'][0]} (dashed: unstable)")
    points_csv = os.path.join(os.path.dirname(branch_csv), "points.csv")
    if os.path.exists(points_csv):
        marked, not_located = marked_points(read(points_csv), param)
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
    fig.savefig(png, dpi=150)


if __name__ == "__main__":
    main(sys.argv)
