#!/usr/bin/python3
"""The attractors of `impactlab attractors --plot` (or by hand).

    plot_attractors.py attractors.csv out.png PARAM QNAME

Left: each attractor's basin fraction as a band stacked on the others against
the parameter (attractor 0, the samples that settled on no periodic
attractor, in grey at the bottom), with the fractions' standard errors as
bars at each band's top. Right: the attractors' section points
(attractor_points.csv beside attractors.csv), the main coordinate against the
parameter, coloured by attractor id as in the bands; the legend gives each
id's (m, n) label (period, impacts per cycle) where it is first found.
Appear, vanish, merge and split events (meta.json's "attractor_events") are
marked by dotted lines. Axes carry their quantities and units, and the title
the scene and the parameters held fixed (meta.json, scripts/plot_labels.py).
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


def colour(attractor):
    """Attractor 0 grey, the others from the tab20 cycle by id."""
    if attractor == 0:
        return "0.75"
    return plt.get_cmap("tab20")((attractor - 1) % 20)


def first_label(rows, attractor):
    """'id: (m, n)' at the first value where the attractor is found."""
    first = np.flatnonzero(np.asarray(rows["attractor"]) == attractor)[0]
    text = f"{attractor}: ({int(rows['period'][first])}, {int(rows['impacts_per_cycle'][first])})"
    if int(rows["contact"][first]):
        text += " contact"
    return text


def draw_attractors(attractor_table, point_table, meta, param, q_name):
    """The basin fractions of `attractor_table` (attractors.csv's columns:
    param, attractor, period, impacts_per_cycle, contact, fraction,
    fraction_error) as stacked bands against the parameter, beside the
    section points of `point_table` (attractor_points.csv's: param,
    attractor, q) coloured by id; meta.json's attractor_events as dotted
    lines."""
    rows = plot_files.as_columns(attractor_table)
    points = plot_files.as_columns(point_table)
    ids_of_rows = np.asarray(rows["attractor"]).astype(int)
    values = np.unique(rows[param])
    ids = sorted(set(ids_of_rows))

    fig, (bands, sections) = plt.subplots(1, 2, figsize=(11, 4.2))
    # the fractions stacked, attractor 0 first, then by id
    bottom = np.zeros(len(values))
    for attractor in ids:
        fraction = np.zeros(len(values))
        error = np.zeros(len(values))
        mine = ids_of_rows == attractor
        where = np.searchsorted(values, rows[param][mine])
        fraction[where] = rows["fraction"][mine]
        error[where] = rows["fraction_error"][mine]
        label = "0: none periodic" if attractor == 0 else first_label(rows, attractor)
        if len(values) > 1:
            bands.fill_between(values, bottom, bottom + fraction, color=colour(attractor),
                               step=None, linewidth=0, label=label)
        else:
            bands.bar(values, fraction, bottom=bottom, color=colour(attractor), label=label)
        present = fraction > 0
        bands.errorbar(values[present], (bottom + fraction)[present], yerr=error[present],
                       fmt="none", ecolor="k", elinewidth=0.6, capsize=1.5)
        bottom += fraction
    if len(values) > 1:
        bands.set_xlim(values[0], values[-1])
    bands.set_ylim(0, 1)
    bands.set_xlabel(plot_labels.key_label(meta, param))
    bands.set_ylabel("basin fraction (of the samples)")
    bands.legend(fontsize=6, loc="upper left", bbox_to_anchor=(1.0, 1.0), title="id: (m, n)",
                 title_fontsize=6)

    point_ids = np.asarray(points["attractor"]).astype(int)
    for attractor in ids:
        if attractor == 0:
            continue
        mine = point_ids == attractor
        sections.plot(points[param][mine], points["q"][mine], "o", markersize=2.5,
                      color=colour(attractor), label=str(attractor))
    q_label, _ = plot_labels.coordinate_labels(meta, q_name)
    sections.set_xlabel(plot_labels.key_label(meta, param))
    sections.set_ylabel(q_label + " on the section")
    for event in meta.get("attractor_events", {}).get("events", []):
        middle = 0.5 * (event["from_value"] + event["to_value"])
        for axes in (bands, sections):
            axes.axvline(middle, color="k", linestyle=":", linewidth=0.6)
    fig.suptitle(plot_labels.title(meta, "Attractors and their basin fractions",
                                   varied=(param,)), fontsize=7)
    fig.tight_layout()
    return fig


def main(argv):
    if len(argv) < 5 or argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0 if len(argv) > 1 and argv[1] in ("-h", "--help") else 2)
    attractors_csv, png, param, q_name = argv[1:5]
    directory = os.path.dirname(attractors_csv)
    figure = draw_attractors(plot_files.read_columns(attractors_csv),
                             plot_files.read_columns(os.path.join(directory,
                                                                  "attractor_points.csv")),
                             plot_labels.read_meta(directory), param, q_name)
    plot_files.save_figure(figure, png)


if __name__ == "__main__":
    main(sys.argv)
