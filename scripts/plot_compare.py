#!/usr/bin/env python3
"""Draws the picture of an `impactlab compare` run: the angular velocity just
before each impact against time, the contact intervals, and the stroboscopic
section, one colour per model.

usage: /usr/bin/python3 scripts/plot_compare.py COMPARE_DIR
Reads COMPARE_DIR/compare_impacts.csv, compare_contacts.csv and
compare_section.csv; writes COMPARE_DIR/compare.png (through a temporary
file, renamed when complete). Exits non-zero if anything fails. Axes carry
their quantities and units, and the title the scene and the parameters held
fixed (compare.json, scripts/plot_labels.py).
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plot_labels  # noqa: E402


def read_csv(path):
    with open(path, newline="") as handle:
        return list(csv.DictReader(handle))


def column(rows, name):
    """The finite values of a column and their row indices."""
    values = []
    for row in rows:
        text = row.get(name, "")
        values.append(float(text) if text not in ("", None) else None)
    return values


def main(directory):
    meta = plot_labels.read_meta(directory, ("compare.json",))
    q_label, rate_label = plot_labels.coordinate_labels(meta, "theta")
    impacts = read_csv(os.path.join(directory, "compare_impacts.csv"))
    contacts = read_csv(os.path.join(directory, "compare_contacts.csv"))
    section = read_csv(os.path.join(directory, "compare_section.csv"))
    header = open(os.path.join(directory, "compare_impacts.csv")).readline().strip().split(",")
    models = [name[len("t_"):] for name in header if name.startswith("t_")]

    figure, (top, middle, right) = plt.subplots(
        1, 3, figsize=(16, 4.8), gridspec_kw={"width_ratios": [2.2, 1.2, 1.2]})
    markers = ["o", "x", "+", "s"]
    for index, model in enumerate(models):
        times = column(impacts, "t_" + model)
        rates = column(impacts, "qdot_before_" + model)
        points = [(t, r) for t, r in zip(times, rates) if t is not None and r is not None]
        if points:
            top.plot([p[0] for p in points], [p[1] for p in points], markers[index % 4],
                     markersize=3, label=f"{model} ({len(points)} impacts)")
        spans = [(float(c["t_start"]), float(c["t_end"])) for c in contacts if c["model"] == model]
        middle.broken_barh([(a, b - a) for a, b in spans], (index - 0.4, 0.8))
        # short intervals are invisible as bars: mark their starts too
        middle.plot([a for a, _ in spans], [index] * len(spans), "|", markersize=14)
        q = column(section, "q_" + model)
        qdot = column(section, "qdot_" + model)
        pairs = [(a, b) for a, b in zip(q, qdot) if a is not None and b is not None]
        if pairs:
            right.plot([p[0] for p in pairs], [p[1] for p in pairs], markers[index % 4],
                       markersize=3, label=model)
    top.set_xlabel("$t$ (s)")
    top.set_ylabel(rate_label + " before impact")
    top.set_title("impacts, matched by order in compare_impacts.csv", fontsize=9)
    top.legend(fontsize=8)
    if not contacts:
        middle.text(0.5, 0.5, "no contact phase", transform=middle.transAxes, ha="center")
    middle.set_xlim(top.get_xlim())
    middle.set_yticks(range(len(models)))
    middle.set_yticklabels(models)
    middle.set_xlabel("$t$ (s)")
    middle.set_title("contact intervals")
    right.set_xlabel(q_label)
    right.set_ylabel(rate_label)
    right.set_title("strobe section t = t0 + kT", fontsize=9)
    right.legend(fontsize=8)
    figure.suptitle(plot_labels.title(meta, "the models compared", ("model",)), fontsize=8)
    figure.tight_layout()
    final = os.path.join(directory, "compare.png")
    temporary = final + ".tmp.png"
    figure.savefig(temporary, dpi=110)
    os.replace(temporary, final)


if __name__ == "__main__":
    if len(sys.argv) == 2 and sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0)
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
