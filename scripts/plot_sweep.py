#!/usr/bin/python3
"""Plots of impactlab's analysis outputs (run by `impactlab ... --plot`, or by hand).

    plot_sweep.py bifurcation bifurcation.csv out.png PARAM QNAME
    plot_sweep.py classes     classes.csv     out.png PARAM1 PARAM2
    plot_sweep.py poincare    poincare.csv    out.png QNAME
    plot_sweep.py continuation branch.csv     out.png PARAM QNAME [bifurcation.csv]
    plot_sweep.py curve        curve.csv      out.png PARAM1 PARAM2 [classes.csv]
    plot_sweep.py grazing      grazing.json   out.png PARAM [bifurcation.csv]
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

Each figure is drawn by a draw_* function over columns that returns the
matplotlib Figure; this script feeds it from the CSV files, the Python
package's result.plot() from a result (impactlab.figures).
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


def unfinished_values(summary, param):
    """{label: parameter values} of the points that stopped early or did not
    settle, from summary.csv's termination and transient_end columns."""
    marks = {}
    if "termination" in summary:
        stopped = np.asarray(summary["termination"], dtype=str) != "completed"
        if stopped.any():
            marks["run stopped early"] = np.asarray(summary[param][stopped], dtype=float)
    if "transient_end" in summary:
        unsettled = np.asarray(summary["transient_end"], dtype=str) == "not_settled"
        if unsettled.any():
            marks["transient not settled"] = np.asarray(summary[param][unsettled], dtype=float)
    return marks


def draw_bifurcation(points, summary, meta, param, q_name):
    """The bifurcation diagram: `points` (bifurcation.csv's columns: param,
    q, direction) and the points of `summary` (summary.csv's, or None) that
    stopped early or did not settle, marked along the bottom."""
    data = plot_files.as_columns(points)
    fig, ax = plt.subplots(figsize=(8, 5.5))
    # the down sweep's thin crosses under the up sweep's dots: where the two
    # agree a dot sits in a cross, where they differ (hysteresis) each shows
    for direction, colour, marker, size, layer in (("down", "tab:red", "x", 3.0, 2),
                                                   ("up", "tab:blue", ".", 2.0, 3)):
        rows = np.asarray(data["direction"], dtype=str) == direction
        if rows.any():
            ax.plot(data[param][rows], data["q"][rows], marker, color=colour, markersize=size,
                    markeredgewidth=0.4, linestyle="none", label=f"sweep {direction}",
                    rasterized=True, zorder=layer)
    if summary is not None:
        styles = {"run stopped early": ("black", "|"), "transient not settled": ("tab:orange", "^")}
        for label, values in unfinished_values(plot_files.as_columns(summary), param).items():
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
    return fig


def bifurcation(csv, png, param, q_name):
    directory = os.path.dirname(csv)
    summary_csv = os.path.join(directory, "summary.csv")
    summary = plot_files.read_columns(summary_csv) if os.path.exists(summary_csv) else None
    figure = draw_bifurcation(plot_files.read_columns(csv), summary,
                              plot_labels.read_meta(directory), param, q_name)
    plot_files.save_figure(figure, png)


def draw_classes(table, meta, param1, param2):
    """The 2D map: the period of the section map over (param1, param2) from
    `table` (classes.csv's columns), the largest Lyapunov exponent and the
    share of sticking impacts beside it where computed, and the points that
    stopped early or did not settle marked on every panel."""
    data = plot_files.as_columns(table)
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
    sticks = grid(np.asarray(data["stick_fraction"], dtype=float)) \
        if "stick_fraction" in data else np.full((len(y), len(x)), np.nan)
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
    words = {name: np.asarray(data[name], dtype=str) for name in ("termination", "transient_end")
             if name in data}
    marks = []
    if "termination" in words:
        marks.append((words["termination"] != "completed", "x", "black", "run stopped early"))
    if "transient_end" in words:
        marks.append((words["transient_end"] == "not_settled", "^", "tab:orange",
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
    return fig


def classes(csv, png, param1, param2):
    figure = draw_classes(plot_files.read_columns(csv),
                          plot_labels.read_meta(os.path.dirname(csv)), param1, param2)
    plot_files.save_figure(figure, png)


def draw_poincare(table, meta, q_name):
    """The section points (poincare.csv's columns q, qdot) in the phase plane."""
    data = plot_files.as_columns(table)
    fig, ax = plt.subplots(figsize=(6, 5))
    ax.plot(data["q"], data["qdot"], ".", markersize=3)
    q_label, rate_label = plot_labels.coordinate_labels(meta, q_name)
    ax.set_xlabel(q_label)
    ax.set_ylabel(rate_label)
    ax.set_title(plot_labels.title(meta, "Poincare section"), fontsize=7)
    fig.tight_layout()
    return fig


def poincare(csv, png, q_name):
    figure = draw_poincare(plot_files.read_columns(csv),
                           plot_labels.read_meta(os.path.dirname(csv)), q_name)
    plot_files.save_figure(figure, png)


def main(argv):
    if len(argv) < 4 or argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0 if len(argv) > 1 and argv[1] in ("-h", "--help") else 2)
    kind, csv, png, *names = argv[1:]
    # the other figures' own scripts, beside this one
    others = {"continuation": "plot_continuation", "basins": "plot_basins",
              "attractors": "plot_attractors", "lyapunov": "plot_lyapunov",
              "curve": "plot_curve", "grazing": "plot_grazing"}
    if kind in others:
        __import__(others[kind]).main([argv[0], csv, png, *names])
        return
    {"bifurcation": bifurcation, "classes": classes, "poincare": poincare}[kind](csv, png, *names)


if __name__ == "__main__":
    main(sys.argv)
