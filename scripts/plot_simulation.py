#!/usr/bin/env python3
"""Draws a simulation's picture: the main coordinate against time with the
walls, impacts and contact phases marked, and the phase portrait.

usage: /usr/bin/python3 scripts/plot_simulation.py RUN_DIR [RUN_DIR ...]
Each RUN_DIR is an `impactlab simulate --sample DT --out RUN_DIR` output; the
picture is written to RUN_DIR/simulation.png. Axes carry their quantities
and units (the scene's, scripts/plot_labels.py), and the title the scene and
the parameters held fixed.
"""
import json
import math
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


def draw_simulation(samples, events, meta):
    """The main coordinate against time (`samples`: trajectory.csv's columns
    t, q, qdot) with the walls, the impacts and the contact phases of
    `events` (events.csv's columns kind, t, q; kind by name), and the phase
    portrait; `meta` is the run's record (meta.json)."""
    samples = plot_files.as_columns(samples)
    events = plot_files.as_columns(events)
    q_name = meta["columns"]["events.csv"]["q"]
    t, q, qdot = samples["t"], samples["q"], samples["qdot"]
    figure, (history, phase) = plt.subplots(
        1, 2, figsize=(12, 4.5), gridspec_kw={"width_ratios": [2.2, 1]})
    history.plot(t, q, lw=0.8, color="tab:blue", label=plot_labels.symbol(q_name))
    keys = meta["scene"]["keys"]
    oscillator = meta["scene"]["oscillator"]
    if oscillator == "pendulum_walls":
        wall = meta["derived"]["theta0_rad"]
        for side in (1, -1):
            history.axhline(side * wall, color="k", lw=0.8, ls="--", label=None if side < 0 else "walls")
    elif oscillator == "linear_impact":
        history.axhline(keys["sigma"]["value"], color="k", lw=0.8, ls="--", label="stop")
    elif oscillator == "bouncing_ball":
        amplitude, omega = keys["A"]["value"], keys["omega"]["value"]
        history.plot(t, [amplitude * math.sin(omega * ti) for ti in t], color="k", lw=0.8,
                     label="table")
    kinds = np.asarray(events["kind"], dtype=str)
    impacts = kinds == "impact"
    history.plot(events["t"][impacts], events["q"][impacts], "o", ms=2.5, color="tab:red",
                 label=f"impacts ({int(impacts.sum())})")
    start = None
    shaded = False
    for kind, time in zip(kinds, events["t"]):
        if kind == "contact_start":
            start = float(time)
        elif kind == "contact_end" and start is not None:
            history.axvspan(start, float(time), color="tab:orange", alpha=0.35,
                            label=None if shaded else "sustained contact")
            shaded = True
            start = None
    q_label, rate_label = plot_labels.coordinate_labels(meta, q_name)
    history.set_xlabel(plot_labels.with_unit("$t$", plot_labels.unit_of(meta, "t0")))
    history.set_ylabel(q_label)
    history.legend(loc="upper center", bbox_to_anchor=(0.5, -0.15), fontsize=8, ncol=4,
                   frameon=False)
    history.set_title(plot_labels.title(meta, "simulation")
                      + f"   [{meta['integrator']['method']}, rtol {meta['integrator']['rtol']:g}]",
                      fontsize=8)
    phase.plot(q, qdot, lw=0.5, color="tab:blue")
    phase.set_xlabel(q_label)
    phase.set_ylabel(rate_label)
    phase.set_title("phase portrait", fontsize=9)
    figure.tight_layout()
    return figure


def plot_run(run_dir):
    with open(os.path.join(run_dir, "meta.json"), encoding="utf-8") as handle:
        meta = json.load(handle)
    figure = draw_simulation(plot_files.read_columns(os.path.join(run_dir, "trajectory.csv")),
                             plot_files.read_columns(os.path.join(run_dir, "events.csv")), meta)
    target = os.path.join(run_dir, "simulation.png")
    plot_files.save_figure(figure, target)
    plt.close(figure)
    print(f"wrote {target}")


if __name__ == "__main__":
    if len(sys.argv) >= 2 and sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0)
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    for directory in sys.argv[1:]:
        plot_run(directory)
