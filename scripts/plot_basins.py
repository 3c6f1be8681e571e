#!/usr/bin/python3
"""The basins of attraction of `impactlab basins --plot` (or by hand).

    plot_basins.py basins.csv out.png XKEY YKEY

Each grid point coloured by the attractor it settles on, with a legend of the
attractors (attractors.csv beside basins.csv: period, impacts per period,
contact, canonical section point); attractor 0 (none found) in white. A
rest is named as one: "at rest on the table" where the body sticks on a wall
(contact, no impacts), "at rest" where it hangs free of the walls. Axes carry
their quantities and units, and the title the scene and the parameters held
fixed (meta.json beside basins.csv, scripts/plot_labels.py).
"""
import os
import sys

import matplotlib

if __name__ == "__main__":
    matplotlib.use("Agg")  # a script writes files; no window
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

try:  # in the Python package impactlab (impactlab.figures)
    from . import plot_files, plot_labels
except ImportError:  # run as a script beside its modules
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import plot_files  # noqa: E402
    import plot_labels  # noqa: E402


def describe(row, meta):
    attractor = int(row["attractor"])
    if attractor == 0:
        return "0: none found"
    impacts = float(row["impacts_per_period"])
    if int(row["period"]) == 1 and impacts == 0.0:
        # a fixed point without impacts: a rest, in contact or free of the walls
        where = f"at rest {plot_labels.rest_place(meta)} (sticking)" if int(row["contact"]) \
            else "at rest, free of the walls"
        return f"{attractor}: {where}"
    text = f"{attractor}: period {int(row['period'])}, {impacts:.3g} impacts/period"
    if int(row["contact"]):
        text += ", contact"
    return text + f" (q {float(row['q']):.4g}, qdot {float(row['qdot']):.4g})"


def draw_basins(grid_table, attractor_table, meta, x_key, y_key):
    """The basins: `grid_table` (basins.csv's columns: x_key, y_key,
    attractor) coloured by attractor, with a legend of `attractor_table`
    (attractors.csv's columns)."""
    data = plot_files.as_columns(grid_table)
    attractors = plot_files.as_columns(attractor_table)
    x = np.unique(data[x_key])
    y = np.unique(data[y_key])
    grid = np.full((len(y), len(x)), np.nan)
    grid[np.searchsorted(y, data[y_key]), np.searchsorted(x, data[x_key])] = data["attractor"]
    count = int(max(np.nanmax(grid), 1))
    palette = plt.get_cmap("tab20")
    colours = ["white"] + [palette(k % 20) for k in range(count)]
    fig, ax = plt.subplots(figsize=(8, 6))
    ax.pcolormesh(x, y, grid, shading="nearest", cmap=ListedColormap(colours), vmin=-0.5,
                  vmax=count + 0.5)
    handles = [Patch(facecolor=colours[int(row["attractor"])], edgecolor="0.5",
                     label=describe(row, meta)) for row in plot_files.rows_of(attractors)]
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.12), fontsize=8,
              ncol=1 if len(handles) < 6 else 2)
    ax.set_xlabel(plot_labels.key_label(meta, x_key))
    ax.set_ylabel(plot_labels.key_label(meta, y_key))
    ax.set_title(plot_labels.title(meta, "basins of attraction", (x_key, y_key)), fontsize=8)
    fig.tight_layout()
    return fig


def main(argv):
    if len(argv) < 5 or argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0 if len(argv) > 1 and argv[1] in ("-h", "--help") else 2)
    basins_csv, png, x_key, y_key = argv[1:5]
    directory = os.path.dirname(basins_csv)
    figure = draw_basins(plot_files.read_columns(basins_csv),
                         plot_files.read_columns(os.path.join(directory, "attractors.csv")),
                         plot_labels.read_meta(directory), x_key, y_key)
    plot_files.save_figure(figure, png)


if __name__ == "__main__":
    main(sys.argv)
