#!/usr/bin/python3
"""The convergence of a Lyapunov spectrum (run by `impactlab poincare
--lyapunov-spectrum --plot`, or by hand):

    plot_lyapunov.py lyapunov.csv out.png [TIME_UNIT]

Draws each exponent's running estimate (lyapunov.csv: t, lambda1..lambdaN,
after a comment line) against the time at which it was taken, t in the run's
time unit and the exponents in its inverse (TIME_UNIT, or read from the
meta.json beside lyapunov.csv). An exponent at -inf (a direction the contact
collapsed) cannot be drawn: the legend says so.
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


def read(path):
    """lyapunov.csv's columns (its comment line skipped)."""
    return plot_files.read_columns(path, comment_lines=1)


def running_lines(data):
    """{name: (t, finite running values) or None where the exponent ends at
    -inf}, of `data`'s columns t, lambda1..lambdaN."""
    lines = {}
    for name in [name for name in data if name != "t"]:
        values = np.asarray(data[name], dtype=float)
        if len(values) and values[-1] == -np.inf:
            lines[name] = None
            continue
        finite = np.isfinite(values)
        lines[name] = (np.asarray(data["t"])[finite], values[finite])
    return lines


def time_unit(record):
    """The run's time unit: "s" where the forcing frequency omega is in
    rad/s, "time unit" for a nondimensional scene (or without a record)."""
    unit = record.get("scene", {}).get("keys", {}).get("omega", {}).get("unit", "")
    return unit.split("/", 1)[1] if unit.startswith("rad/") else "time unit"


def draw_spectrum(running, record, unit=None):
    """Each exponent's running estimate (`running`: lyapunov.csv's columns t,
    lambda1..lambdaN) against the time at which it was taken."""
    unit = unit or time_unit(record)
    fig, ax = plt.subplots(figsize=(7, 5.5))
    for name, line in running_lines(plot_files.as_columns(running)).items():
        label = name.replace("lambda", "λ")
        if line is None:
            ax.plot([], [], " ", label=f"{label} = −∞ (collapsed by the contact)")
            continue
        t, values = line
        ax.plot(t, values, label=f"{label} → {values[-1]:.4g}" if len(values) else label)
    ax.axhline(0.0, color="0.6", linewidth=0.8)
    ax.set_xlabel(f"time t ({unit})")
    ax.set_ylabel(f"running estimate of λᵢ (1/{unit})")
    ax.set_title(plot_labels.title(record, "convergence of the Lyapunov spectrum"), fontsize=8)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.15), ncol=2, fontsize=8, frameon=False)
    fig.tight_layout()
    return fig


def main(argv):
    if len(argv) < 3 or argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0 if len(argv) > 1 and argv[1] in ("-h", "--help") else 2)
    csv, png, *rest = argv[1:]
    record = plot_labels.read_meta(os.path.dirname(os.path.abspath(csv)), ("meta.json",))
    figure = draw_spectrum(read(csv), record, rest[0] if rest else None)
    plot_files.save_figure(figure, png)


if __name__ == "__main__":
    main(sys.argv)
