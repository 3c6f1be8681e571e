#!/usr/bin/python3
"""Plots of impactlab's analysis outputs (run by `impactlab ... --plot`, or by hand).

    plot_sweep.py bifurcation bifurcation.csv out.png PARAM QNAME
    plot_sweep.py classes     classes.csv     out.png PARAM1 PARAM2
    plot_sweep.py poincare    poincare.csv    out.png QNAME
    plot_sweep.py continuation branch.csv     out.png PARAM QNAME [bifurcation.csv]
    plot_sweep.py curve        curve.csv      out.png PARAM1 PARAM2 [classes.csv]
    plot_sweep.py basins       basins.csv     out.png XKEY YKEY
    plot_sweep.py attractors   attractors.csv out.png PARAM QNAME
    plot_sweep.py lyapunov     lyapunov.csv   out.png [TIME_UNIT]

bifurcation: the section's q against the parameter, up and down sweeps in two
colours and markers (hysteresis shows where they differ); the values whose
run stopped early or whose transient did not settle (summary.csv beside it)
marked along the bottom. classes: a colour map of the period of the section
map over the two parameters, with the largest Lyapunov exponent beside it
where computed, and those points marked. poincare: the section points in
(q, qdot). Axes carry their quantities and units, and titles the scene and
the parameters held fixed, from the meta.json beside the CSV
(scripts/plot_labels.py).
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plot_labels  # noqa: E402


def read(path):
    data = np.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding="utf-8")
    return np.atleast_1d(data)


def unfinished_values(summary, param):
    """{label: parameter values} of the points that stopped early or did not
    settle, from summary.csv's termination and transient_end columns."""
    names = summary.dtype.names
    marks = {}
    if "termination" in names:
        stopped = summary["termination"] != "completed"
        if stopped.any():
            marks["run stopped early"] = np.asarray(summary[param][stopped], dtype=float)
    if "transient_end" in names:
        unsettled = summary["transient_end"] == "not_settled"
        if unsettled.any():
            marks["transient not settled"] = np.asarray(summary[param][unsettled], dtype=float)
    return marks


def bifurcation(csv, png, param, q_name):
    data = read(csv)
    meta = plot_labels.read_meta(os.path.dirname(csv))
    fig, ax = plt.subplots(figsize=(8, 5.5))
    # the down sweep's thin crosses under the up sweep's dots: where the two
    # agree a dot sits in a cross, where they differ (hysteresis) each shows
    for direction, colour, marker, size, layer in (("down", "tab:red", "x", 3.0, 2),
                                                   ("up", "tab:blue", ".", 2.0, 3)):
        rows = data[data["direction"] == direction]
        if len(rows):
            ax.plot(rows[param], rows["q"], marker, color=colour, markersize=size,
                    markeredgewidth=0.4, linestyle="none", label=f"sweep {direction}",
                    rasterized=True, zorder=layer)
    summary_csv = os.path.join(os.path.dirname(csv), "summary.csv")
    if os.path.exists(summary_csv):
        styles = {"run stopped early": ("black", "|"), "transient not settled": ("tab:orange", "^")}
        for label, values in unfinished_values(read(summary_csv), param).items():
            colour, marker = styles[label]
            ax.plot(values, np.zeros_like(values), marker, color=colour, markersize=9,
                    linestyle="none", label=f"{label} ({len(values)})",
                    transform=ax.get_xaxis_transform(), clip_on=False)
    ax.set_xlabel(plot_labels.key_label(meta, param))
    ax.set_ylabel(plot_labels.coordinate_labels(meta, q_name)[0] + " on the section")
    # the legend below the axes, off the data
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=4, markerscale=3,
              fontsize=8, frameon=False)
    ax.set_title(plot_labels.title(meta, "bifurcation diagram", (param,)), fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=150)


def classes(csv, png, param1, param2):
    data = read(csv)
    meta = plot_labels.read_meta(os.path.dirname(csv))
    x = np.unique(data[param1])
    y = np.unique(data[param2])
    ix = np.searchsorted(x, data[param1])
    iy = np.searchsorted(y, data[param2])

    def grid(values):
        cells = np.full((len(y), len(x)), np.nan)
        cells[iy, ix] = values
        return cells

    period = grid(np.where(data["period"] > 0, data["period"], np.nan))
    lyapunov = grid(np.asarray(data["lyapunov"], dtype=float))
    merged = np.isneginf(lyapunov)  # rest on a wall: nearby states merge
    lyapunov[~np.isfinite(lyapunov)] = np.nan
    names = data.dtype.names
    sticks = grid(np.asarray(data["stick_fraction"], dtype=float)) \
        if "stick_fraction" in names else np.full((len(y), len(x)), np.nan)
    show_lyapunov = np.isfinite(lyapunov).any() or merged.any()
    show_sticks = bool(np.isfinite(sticks).any() and np.nanmax(sticks) > 0.0)
    panels = 1 + int(show_lyapunov) + int(show_sticks)
    fig, axes = plt.subplots(1, panels, figsize=(6 * panels, 5), squeeze=False)
    mesh = axes[0, 0].pcolormesh(x, y, period, shading="nearest", cmap="tab10", vmin=0.5,
                                 vmax=10.5)
    fig.colorbar(mesh, ax=axes[0, 0], label="period of the section map (blank: none found)")
    axes[0, 0].set_title("period")
    panel = 1
    if show_lyapunov:
        ax = axes[0, panel]
        panel += 1
        # the colour range of the bulk of the map: a few transients far out
        # would otherwise wash it out (arrows on the bar mark those beyond it)
        finite = np.abs(lyapunov[np.isfinite(lyapunov)])
        limit = np.percentile(finite, 98) if finite.size else 1.0
        limit = limit if limit > 0.0 else 1.0
        mesh = ax.pcolormesh(x, y, lyapunov, shading="nearest", cmap="coolwarm",
                             vmin=-limit, vmax=limit)
        fig.colorbar(mesh, ax=ax, label="largest Lyapunov exponent (1/time unit)", extend="both")
        # -inf (contact phases merge nearby states) in black
        ax.pcolormesh(x, y, np.where(merged, 1.0, np.nan), shading="nearest",
                      cmap="gray", vmin=1.0, vmax=2.0)
        ax.set_title("largest Lyapunov exponent (black: -inf, contact; blank: none)")
    if show_sticks:
        ax = axes[0, panel]
        mesh = ax.pcolormesh(x, y, sticks, shading="nearest", cmap="viridis", vmin=0.0,
                             vmax=1.0)
        fig.colorbar(mesh, ax=ax, label="share of impacts that stick (friction stops the slip)")
        ax.set_title("sticking impacts")
    # points whose run stopped early or whose transient did not settle, on
    # every panel: their classes are not the attractor's
    marks = []
    if "termination" in names:
        marks.append((data["termination"] != "completed", "x", "black", "run stopped early"))
    if "transient_end" in names:
        marks.append((data["transient_end"] == "not_settled", "^", "tab:orange",
                      "transient not settled"))
    for ax in axes[0]:
        for where, marker, colour, label in marks:
            if where.any():
                ax.plot(data[param1][where], data[param2][where], marker, color=colour,
                        markersize=4, linestyle="none", label=f"{label} ({where.sum()})")
        ax.set_xlabel(plot_labels.key_label(meta, param1))
        ax.set_ylabel(plot_labels.key_label(meta, param2))
    if any(where.any() for where, *_ in marks):
        axes[0, 0].legend(loc="upper center", bbox_to_anchor=(0.5, -0.12), fontsize=8,
                          frameon=False, ncol=2)
    fig.suptitle(plot_labels.title(meta, "classes of the section map", (param1, param2)),
                 fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=150)


def poincare(csv, png, q_name):
    data = read(csv)
    meta = plot_labels.read_meta(os.path.dirname(csv))
    fig, ax = plt.subplots(figsize=(6, 5))
    ax.plot(data["q"], data["qdot"], ".", markersize=3)
    q_label, rate_label = plot_labels.coordinate_labels(meta, q_name)
    ax.set_xlabel(q_label)
    ax.set_ylabel(rate_label)
    ax.set_title(plot_labels.title(meta, "Poincare section"), fontsize=7)
    fig.tight_layout()
    fig.savefig(png, dpi=150)


def main(argv):
    if len(argv) < 4 or argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0 if len(argv) > 1 and argv[1] in ("-h", "--help") else 2)
    kind, csv, png, *names = argv[1:]
    if kind == "continuation":  # scripts/plot_continuation.py
        import plot_continuation
        plot_continuation.main([argv[0], csv, png, *names])
        return
    if kind == "basins":  # scripts/plot_basins.py
        import plot_basins
        plot_basins.main([argv[0], csv, png, *names])
        return
    if kind == "attractors":  # scripts/plot_attractors.py
        import plot_attractors
        plot_attractors.main([argv[0], csv, png, *names])
        return
    if kind == "lyapunov":  # scripts/plot_lyapunov.py
        sys.path.insert(0, __import__("os").path.dirname(__file__))
        import plot_lyapunov
        plot_lyapunov.main([argv[0], csv, png, *names])
        return
    if kind == "curve":  # scripts/plot_curve.py
        import plot_curve
        plot_curve.main([argv[0], csv, png, *names])
        return
    {"bifurcation": bifurcation, "classes": classes, "poincare": poincare}[kind](csv, png, *names)


if __name__ == "__main__":
    main(sys.argv)
