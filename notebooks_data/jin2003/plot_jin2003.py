#!/usr/bin/python3
"""Draws Fig. 4 of Jin, Hu & Bishop (2003) from the CSVs that
`impactlab reproduce jin2003` writes, one panel per impact model.

    /usr/bin/python3 plot_jin2003.py DIRECTORY

writes fig4a.png ... fig4d.png into DIRECTORY (each under a temporary name,
renamed when complete). jin2003.ipynb imports the same functions.
"""
import csv
import json
import os
import sys

import matplotlib
import matplotlib.pyplot as plt
import numpy as np

MODEL_LABELS = {"paper": "Model P (the paper's sliding impact)",
                "newton": "Model N (Newton impacts, contact phases)",
                "rigid": "rigid-body model"}
PAPER_RANGES = {"omega": [(6.6, 7.08)], "V0": [(1.5, 1.6), (3.971, 4.163)]}


def model_label(model):
    """A model specification ("rigid:radius=0.01:spin=free") as a title."""
    name, *settings = model.split(":")
    label = MODEL_LABELS.get(name, name)
    return f"{label}, {', '.join(settings)}" if settings else label


def read_rows(directory, name):
    """The rows of a CSV as a dict of columns (numbers as floats, NaN if empty)."""
    with open(os.path.join(directory, name), newline="") as handle:
        rows = list(csv.DictReader(handle))
    columns = {}
    for key in rows[0].keys() if rows else []:
        values = [row[key] for row in rows]
        try:
            columns[key] = np.array([float(v) if v != "" else np.nan for v in values])
        except ValueError:
            columns[key] = np.array(values)
    return columns


def read_sidecar(directory, name):
    with open(os.path.join(directory, name)) as handle:
        return json.load(handle)


def models_in(columns):
    seen = []
    for model in columns["model"]:
        if model not in seen:
            seen.append(model)
    return seen


def residual_figure(directory, figure):
    """Fig. 4(a) or (b): the sliding residual of every steady-state impact."""
    data = read_rows(directory, figure + ".csv")
    meta = read_sidecar(directory, figure + ".json")
    grid = meta["grid"]
    parameter = grid["parameter"]
    fixed_name, fixed_value = next(iter(grid["fixed"].items()))
    models = models_in(data)
    fig, axes = plt.subplots(1, len(models), figsize=(5.5 * len(models), 4.2), sharey=True,
                             squeeze=False)
    scene = meta["scene"]["keys"]
    g = scene["g"]["value"]
    for axis, model in zip(axes[0], models):
        chosen = data["model"] == model
        sliding = chosen & (data["sliding_impact"] == 1)
        axis.plot(data[parameter][chosen & ~sliding], data["sliding_residual"][chosen & ~sliding],
                  ".", ms=2, color="tab:blue", label="instantaneous impact")
        if sliding.any():
            axis.plot(data[parameter][sliding], data["sliding_residual"][sliding], ".", ms=2,
                      color="tab:red", label="sliding impact")
        axis.axhline(0.0, color="black", lw=0.8)
        for low, high in PAPER_RANGES[parameter]:
            axis.axvspan(low, high, color="orange", alpha=0.2, lw=0)
        threshold = g / fixed_value
        axis.axvline(threshold, color="gray", ls=":", lw=1)
        axis.set_title(model_label(model), fontsize=10)
        unit = grid["unit"]
        symbol = "ω" if parameter == "omega" else "V0"
        axis.set_xlabel(f"{symbol} ({unit})")
        axis.set_xlim(grid["from"], grid["to"])
    axes[0][0].set_ylabel("sliding residual v_c0 − v_y0 (m/s)")
    axes[0][0].legend(loc="upper left", fontsize=8, markerscale=4)
    fixed_symbol = "ω" if fixed_name == "omega" else "V0"
    fixed_unit = "rad/s" if fixed_name == "omega" else "m/s"
    fig.suptitle(f"Fig. 4({'a' if figure == 'fig4a' else 'b'}): {fixed_symbol} = {fixed_value} "
                 f"{fixed_unit}; orange: the paper's sliding ranges; dotted: V0 ω = g",
                 fontsize=10)
    fig.tight_layout()
    return fig


def history_figure(directory, figure):
    """Fig. 4(c) or (d): the bob's horizontal displacement against time."""
    data = read_rows(directory, figure + ".csv")
    meta = read_sidecar(directory, figure + ".json")
    b = meta["wall_position_m"]
    models = models_in(data)
    fig, axes = plt.subplots(len(models), 1, figsize=(9, 2.6 * len(models)), sharex=True,
                             squeeze=False)
    for axis, model in zip(axes[:, 0], models):
        chosen = data["model"] == model
        t, x = data["t"][chosen], data["x"][chosen]
        axis.plot(t, x, lw=0.9, color="tab:blue")
        on_wall = chosen & (data["mode"] != "free")
        axis.plot(data["t"][on_wall], data["x"][on_wall], ".", ms=2, color="tab:red",
                  label="on a wall (slipping)")
        for wall in (b, -b):
            axis.axhline(wall, color="gray", ls="--", lw=0.8)
        # a ball of radius r touches a wall with its centre at x = ±(b − r)
        radius = dict(s.split("=") for s in model.split(":")[1:]).get("radius")
        if radius is not None and float(radius) > 0.0:
            for centre in (b - float(radius), float(radius) - b):
                axis.axhline(centre, color="gray", ls=":", lw=0.8)
        axis.set_ylabel("x (m)")
        axis.set_title(model_label(model), fontsize=10)
        if on_wall.any():
            axis.legend(loc="upper right", fontsize=8, markerscale=4)
    axes[-1, 0].set_xlabel("t (s)")
    which = "Fig. 4(c)" if figure == "fig4c" else "Fig. 4(d), zoom"
    fig.suptitle(f"{which}: V0 = {meta['V0_m_per_s']} m/s, ω = "
                 f"{meta['omega_rad_per_s']} rad/s; walls at x = ±{b} m", fontsize=10)
    fig.tight_layout()
    return fig


def save(fig, path):
    temporary = path + ".tmp.png"
    fig.savefig(temporary, dpi=130)
    plt.close(fig)
    os.replace(temporary, path)


def main(directory):
    for figure in ("fig4a", "fig4b"):
        save(residual_figure(directory, figure), os.path.join(directory, figure + ".png"))
    for figure in ("fig4c", "fig4d"):
        save(history_figure(directory, figure), os.path.join(directory, figure + ".png"))
    print(f"plots: {directory}/fig4a.png ... fig4d.png")


if __name__ == "__main__":
    if len(sys.argv) == 2 and sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0)
    if len(sys.argv) != 2:
        sys.exit("usage: plot_jin2003.py DIRECTORY")
    matplotlib.use("Agg")  # files only; the notebook keeps its inline backend
    main(sys.argv[1])
