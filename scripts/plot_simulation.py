#!/usr/bin/env python3
"""Draws a simulation's picture: the main coordinate against time with the
walls, impacts and contact phases marked, and the phase portrait.

usage: /usr/bin/python3 scripts/plot_simulation.py RUN_DIR [RUN_DIR ...]
Each RUN_DIR is an `impactlab simulate --sample DT --out RUN_DIR` output; the
picture is written to RUN_DIR/simulation.png. Axes carry their quantities
and units (the scene's, scripts/plot_labels.py), and the title the scene and
the parameters held fixed.
"""
import csv
import json
import math
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


def plot_run(run_dir):
    meta = json.load(open(os.path.join(run_dir, "meta.json")))
    samples = read_csv(os.path.join(run_dir, "trajectory.csv"))
    events = read_csv(os.path.join(run_dir, "events.csv"))
    q_name = meta["columns"]["events.csv"]["q"]
    t = [float(s["t"]) for s in samples]
    q = [float(s["q"]) for s in samples]
    qdot = [float(s["qdot"]) for s in samples]

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
    impacts = [e for e in events if e["kind"] == "impact"]
    history.plot([float(e["t"]) for e in impacts], [float(e["q"]) for e in impacts],
                 "o", ms=2.5, color="tab:red", label=f"impacts ({len(impacts)})")
    start = None
    shaded = False
    for e in events:
        if e["kind"] == "contact_start":
            start = float(e["t"])
        elif e["kind"] == "contact_end" and start is not None:
            history.axvspan(start, float(e["t"]), color="tab:orange", alpha=0.35,
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
    target = os.path.join(run_dir, "simulation.png")
    figure.savefig(target + ".tmp.png", dpi=110)
    os.replace(target + ".tmp.png", target)
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
