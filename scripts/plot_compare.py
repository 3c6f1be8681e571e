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


def finite_pairs(table, first, second):
    """The rows where both columns hold a number (a model with fewer impacts
    leaves its columns' later fields empty)."""
    if first not in table or second not in table:
        return np.empty(0), np.empty(0)
    a = np.asarray(table[first], dtype=float)
    b = np.asarray(table[second], dtype=float)
    both = np.isfinite(a) & np.isfinite(b)
    return a[both], b[both]


def draw_compare(impacts, contacts, section, meta):
    """The models compared: the rate just before each impact against time
    (`impacts`: compare_impacts.csv's columns t_MODEL, qdot_before_MODEL),
    the contact intervals (`contacts`: model, t_start, t_end) and the strobe
    section (`section`: q_MODEL, qdot_MODEL), one colour per model."""
    impacts, contacts, section = (plot_files.as_columns(table)
                                  for table in (impacts, contacts, section))
    q_label, rate_label = plot_labels.coordinate_labels(meta, "theta")
    models = [name[len("t_"):] for name in impacts if name.startswith("t_")]
    contact_model = np.asarray(contacts.get("model", []), dtype=str)

    figure, (top, middle, right) = plt.subplots(
        1, 3, figsize=(16, 4.8), gridspec_kw={"width_ratios": [2.2, 1.2, 1.2]})
    markers = ["o", "x", "+", "s"]
    for index, model in enumerate(models):
        times, rates = finite_pairs(impacts, "t_" + model, "qdot_before_" + model)
        if len(times):
            top.plot(times, rates, markers[index % 4], markersize=3,
                     label=f"{model} ({len(times)} impacts)")
        mine = contact_model == model
        starts = np.asarray(contacts.get("t_start", []), dtype=float)[mine]
        ends = np.asarray(contacts.get("t_end", []), dtype=float)[mine]
        middle.broken_barh(list(zip(starts, ends - starts)), (index - 0.4, 0.8))
        # short intervals are invisible as bars: mark their starts too
        middle.plot(starts, [index] * len(starts), "|", markersize=14)
        q, qdot = finite_pairs(section, "q_" + model, "qdot_" + model)
        if len(q):
            right.plot(q, qdot, markers[index % 4], markersize=3, label=model)
    top.set_xlabel("$t$ (s)")
    top.set_ylabel(rate_label + " before impact")
    top.set_title("impacts, matched by order in compare_impacts.csv", fontsize=9)
    top.legend(fontsize=8)
    if not len(contact_model):
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
    return figure


def main(directory):
    tables = [plot_files.read_columns(os.path.join(directory, name)) for name in
              ("compare_impacts.csv", "compare_contacts.csv", "compare_section.csv")]
    figure = draw_compare(*tables, plot_labels.read_meta(directory, ("compare.json",)))
    plot_files.save_figure(figure, os.path.join(directory, "compare.png"))


if __name__ == "__main__":
    if len(sys.argv) == 2 and sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0)
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
