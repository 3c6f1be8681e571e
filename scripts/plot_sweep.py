#!/usr/bin/python3
"""Plots of impactlab's analysis outputs (run by `impactlab ... --plot`, or by hand).

    plot_sweep.py bifurcation bifurcation.csv out.png PARAM QNAME
    plot_sweep.py classes     classes.csv     out.png PARAM1 PARAM2
    plot_sweep.py poincare    poincare.csv    out.png QNAME
    plot_sweep.py continuation branch.csv     out.png PARAM QNAME [bifurcation.csv]
    plot_sweep.py curve        curve.csv      out.png PARAM1 PARAM2 [classes.csv]
    plot_sweep.py basins       basins.csv     out.png XKEY YKEY
    plot_sweep.py lyapunov     lyapunov.csv   out.png [TIME_UNIT]

bifurcation: the section's q against the parameter, up and down sweeps in two
colours (hysteresis shows where they differ). classes: a colour map of the
period of the section map over the two parameters, with the largest Lyapunov
exponent beside it where computed. poincare: the section points in (q, qdot).
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read(path):
    data = np.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding="utf-8")
    return np.atleast_1d(data)


def bifurcation(csv, png, param, q_name):
    data = read(csv)
    fig, ax = plt.subplots(figsize=(8, 5))
    for direction, colour, size in (("up", "tab:blue", 1.0), ("down", "tab:red", 0.5)):
        rows = data[data["direction"] == direction]
        if len(rows):
            ax.plot(rows[param], rows["q"], ",", color=colour, markersize=size,
                    label=f"sweep {direction}", rasterized=True)
            ax.scatter([], [], color=colour, s=4, label=None)
    ax.set_xlabel(param)
    ax.set_ylabel(f"{q_name} on the section")
    ax.legend(markerscale=20, loc="best")
    ax.set_title("bifurcation diagram")
    fig.tight_layout()
    fig.savefig(png, dpi=150)


def classes(csv, png, param1, param2):
    data = read(csv)
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
        fig.colorbar(mesh, ax=ax, label="largest Lyapunov exponent (1/time)", extend="both")
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
    for ax in axes[0]:
        ax.set_xlabel(param1)
        ax.set_ylabel(param2)
    fig.tight_layout()
    fig.savefig(png, dpi=150)


def poincare(csv, png, q_name):
    data = read(csv)
    fig, ax = plt.subplots(figsize=(6, 5))
    ax.plot(data["q"], data["qdot"], ".", markersize=2)
    ax.set_xlabel(q_name)
    ax.set_ylabel(f"d{q_name}/dt")
    ax.set_title("Poincare section")
    fig.tight_layout()
    fig.savefig(png, dpi=150)


def main(argv):
    kind, csv, png, *names = argv[1:]
    if kind == "continuation":  # scripts/plot_continuation.py
        sys.path.insert(0, __import__("os").path.dirname(__file__))
        import plot_continuation
        plot_continuation.main([argv[0], csv, png, *names])
        return
    if kind == "basins":  # scripts/plot_basins.py
        sys.path.insert(0, __import__("os").path.dirname(__file__))
        import plot_basins
        plot_basins.main([argv[0], csv, png, *names])
        return
    if kind == "lyapunov":  # scripts/plot_lyapunov.py
        sys.path.insert(0, __import__("os").path.dirname(__file__))
        import plot_lyapunov
        plot_lyapunov.main([argv[0], csv, png, *names])
        return
    if kind == "curve":  # scripts/plot_curve.py
        sys.path.insert(0, __import__("os").path.dirname(__file__))
        import plot_curve
        plot_curve.main([argv[0], csv, png, *names])
        return
    {"bifurcation": bifurcation, "classes": classes, "poincare": poincare}[kind](csv, png, *names)


if __name__ == "__main__":
    main(sys.argv)
