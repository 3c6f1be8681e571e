#!/usr/bin/python3
"""Axis labels, units and titles for impactlab's plot scripts, read from the
meta.json (or continuation.json) the program writes beside its CSV files.

    plot_labels.py META.json KEY ...     prints each key's axis label

A key's label is its symbol and its unit from the scene record
(meta["scene"]["keys"][KEY]["unit"]): "$\\omega$ (rad/s)". The section's
coordinates take the units of the scene's initial state (initial.theta,
initial.theta_dot), so a model file's own units show as it states them. A
title names the scene, its model and the parameters held fixed.
"""
import json
import os
import sys

# mathtext symbols of the built-in scenes' keys; any other key is shown as named
SYMBOLS = {
    "omega": r"$\omega$", "V0": r"$V_0$", "e_n": r"$e_n$", "e_t": r"$e_t$", "mu": r"$\mu$",
    "theta": r"$\theta$", "theta_dot": r"$\dot\theta$", "zeta": r"$\zeta$",
    "sigma": r"$\sigma$", "x": r"$x$", "x_dot": r"$\dot x$", "y": r"$y$", "y_dot": r"$\dot y$",
    "t": r"$t$", "radius": r"$r_b$", "A": r"$A$", "r": r"$r$", "d": r"$d$", "m": r"$m$",
    "l": r"$l$", "b": r"$b$", "g": r"$g$", "F": r"$F$", "beta": r"$\beta$",
}

# keys that set up a run rather than the physics: left out of titles
SETUP_PREFIXES = ("integrator.", "limits.", "initial.")
SETUP_KEYS = {"name", "description", "t0", "accumulation_tol"}

# where a body rests when an attractor is a rest in contact, by oscillator
REST_PLACES = {"bouncing_ball": "on the table", "linear_impact": "against the stop",
               "pendulum_walls": "on a wall"}


def read_meta(directory, names=("meta.json", "continuation.json")):
    """The run's record beside its CSV files ({} where there is none)."""
    for name in names:
        path = os.path.join(directory, name)
        if os.path.exists(path):
            with open(path) as handle:
                return json.load(handle)
    return {}


def scene_keys(meta):
    return meta.get("scene", {}).get("keys", {})


def unit_of(meta, key):
    """The key's unit in the scene record; "" where it has none."""
    return scene_keys(meta).get(key, {}).get("unit", "")


def symbol(key):
    """The key's symbol: initial.theta is theta at t0, a dotted key keeps its name."""
    if key.startswith("initial."):
        base = key[len("initial."):]
        shown = SYMBOLS.get(base, base)
        return shown[:-1] + r"_0$" if shown.startswith("$") else shown + "(t0)"
    return SYMBOLS.get(key, key)


def with_unit(text, unit):
    return f"{text} ({unit})" if unit else text


def key_label(meta, key):
    """An axis label for a scene key: "$\\omega$ (rad/s)"."""
    return with_unit(symbol(key), unit_of(meta, key))


def coordinate_labels(meta, q_name):
    """Axis labels of the main coordinate and its rate, in the units of the
    scene's initial state: ("$\\theta$ (rad)", "$\\dot\\theta$ (rad/s)")."""
    rate = q_name + "_dot"
    rate_symbol = SYMBOLS.get(rate, f"d{q_name}/dt")
    return (with_unit(SYMBOLS.get(q_name, q_name), unit_of(meta, "initial." + q_name)),
            with_unit(rate_symbol, unit_of(meta, "initial." + rate)))


def fixed_parameters(meta, varied=()):
    """["V0 = 1.5 m/s", "omega = 7 rad/s", ...]: the scene's physical keys,
    not those varied, those that set up the run or those its model does not
    read."""
    shown = []
    for key, entry in scene_keys(meta).items():
        if key in varied or key in SETUP_KEYS or key.startswith(SETUP_PREFIXES):
            continue
        if entry.get("read", True) is False:
            continue
        value = entry.get("value")
        text = f"{value:g}" if isinstance(value, (int, float)) else str(value)
        unit = entry.get("unit", "")
        shown.append(f"{key} = {text}" + (f" {unit}" if unit else ""))
    return shown


def title(meta, what, varied=()):
    """The figure's title: what it shows, the scene, and the parameters held
    fixed, wrapped to the figure."""
    source = meta.get("scene", {}).get("source", "")
    head = f"{what}: {os.path.basename(source)}" if source else what
    lines = [head]
    line = ""
    # wrapped between parameters, never inside one
    for item in fixed_parameters(meta, varied):
        if line and len(line) + 2 + len(item) > 110:
            lines.append(line + ",")
            line = ""
        line = f"{line}, {item}" if line else item
    if line:
        lines.append(line)
    return "\n".join(lines)


def rest_place(meta):
    return REST_PLACES.get(meta.get("scene", {}).get("oscillator", ""), "in contact")


def main(argv):
    if len(argv) < 3 or argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0 if len(argv) > 1 and argv[1] in ("-h", "--help") else 2
    with open(argv[1]) as handle:
        meta = json.load(handle)
    for key in argv[2:]:
        print(key_label(meta, key))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
