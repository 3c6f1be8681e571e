#!/usr/bin/python3
"""The two-parameter curve of `impactlab continue --param2 --plot` (or by hand).

    plot_curve.py curve.csv out.png PARAM1 PARAM2 [classes.csv]

The curve of the fold, period-doubling or grazing point in (PARAM1, PARAM2),
its type read from curve.json beside curve.csv, drawn over the period map of a
2D sweep's classes.csv (the same two keys) when given. Axes carry their
quantities and units, and the title the scene and the parameters held fixed
(continuation.json beside curve.csv, scripts/plot_labels.py).
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plot_labels  # noqa: E402


def read(path):
    data = np.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding="utf-8",
                         deletechars="")
    return np.atleast_1d(data)


def main(argv):
    if len(argv) < 5 or argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0 if len(argv) > 1 and argv[1] in ("-h", "--help") else 2)
    curve_csv, png, param1, param2, *sweep = argv[1:]
    meta = plot_labels.read_meta(os.path.dirname(curve_csv))
    fig, ax = plt.subplots(figsize=(7, 6))
    if sweep:
        data = read(sweep[0])
        x = np.unique(data[param1])
        y = np.unique(data[param2])
        period = np.full((len(y), len(x)), np.nan)
        period[np.searchsorted(y, data[param2]), np.searchsorted(x, data[param1])] = np.where(
            data["period"] > 0, data["period"], np.nan)
        mesh = ax.pcolormesh(x, y, period, shading="nearest", cmap="tab10", vmin=0.5, vmax=10.5,
                             alpha=0.6)
        fig.colorbar(mesh, ax=ax, label="period of the section map, 2D sweep (blank: none found)")
    kind = "curve"
    curve_json = os.path.join(os.path.dirname(curve_csv), "curve.json")
    if os.path.exists(curve_json):
        with open(curve_json, encoding="utf-8") as handle:
            kind = json.load(handle).get("type") or kind
    curve = read(curve_csv)
    if len(curve) and curve.dtype.names and param1 in curve.dtype.names:
        # one curve per branch (--switch: the doubled branches' curves too)
        branches = curve["branch"] if "branch" in curve.dtype.names else np.zeros(len(curve))
        colours = ["black", "tab:red", "tab:blue", "tab:green"]
        for index, number in enumerate(np.unique(branches)):
            piece = curve[branches == number]
            period = f", period {int(piece['period'][0])}" if "period" in piece.dtype.names else ""
            colour = colours[index % len(colours)]
            ax.plot(piece[param1], piece[param2], "-", color=colour, linewidth=1.8,
                    label=f"{kind.replace('_', ' ')} curve{period} (continuation)")
            ax.plot(piece[param1][:1], piece[param2][:1], "o", color=colour, markersize=6,
                    label="start (located on the branch)" if index == 0 else None)
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), fontsize=8, ncol=2,
                  frameon=False)
    ax.set_xlabel(plot_labels.key_label(meta, param1))
    ax.set_ylabel(plot_labels.key_label(meta, param2))
    ax.set_title(plot_labels.title(meta, "two-parameter continuation", (param1, param2)),
                 fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=150)


if __name__ == "__main__":
    main(sys.argv)
