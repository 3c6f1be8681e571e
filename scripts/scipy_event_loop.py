#!/usr/bin/python3
"""The event loop a researcher would write with SciPy, for `impactlab bench`.

Usage: scipy_event_loop.py SPEC.json RESULT.json

For each case of the spec (an oscillator, its scene's key values, a time span)
and each SciPy method and relative tolerance of its ladder, the oscillator is
integrated by scipy.integrate.solve_ivp with one terminal event per wall
(the gap to the wall, direction -1, as in SciPy's own bouncing-ball example);
at each impact the integration stops, Newton's impact law resets the velocity,
and solve_ivp is called again from the impact. The largest step is the one
impactlab uses (1/16 of the shorter of the forcing and natural periods), so
that a grazing dip between two steps is not stepped over. The result lists,
for each run, its impacts (time, velocity before) and its wall time; the
errors are computed by impactlab against the same references as its own runs.
Each run's CPU time (time.thread_time) and wall time are reported.

Units follow the scenes: the pendulum in SI (rad, s), the linear impact
oscillator non-dimensional, the bouncing ball in SI (m, s).
"""
import json
import math
import platform
import sys
import time

import numpy as np
import scipy
from scipy.integrate import solve_ivp

PAINLEVE_MARGIN = 1e-9  # as src/contact/painleve.hpp


class Pendulum:
    """Jin, Hu & Bishop (2003), Model N: m l^2 th'' + d th' + m l g_e sin th = 0."""

    def __init__(self, k):
        self.m, self.l, self.b, self.d = k["m"], k["l"], k["b"], k["d"]
        self.g, self.V0, self.omega = k["g"], k["V0"], k["omega"]
        self.e_n, self.mu = k["e_n"], k["mu"]
        self.theta0 = math.asin(self.b / self.l)
        self.y0 = [k["initial.theta"], k["initial.theta_dot"]]
        natural = 2 * math.pi * math.sqrt(self.l / self.g)
        self.max_step = min(2 * math.pi / self.omega, natural) / 16

    def rhs(self, t, y):
        g_e = self.g - self.V0 * self.omega * math.cos(self.omega * t)
        return [y[1], -(self.d * y[1] + self.m * self.l * g_e * math.sin(y[0]))
                / (self.m * self.l * self.l)]

    def events(self):
        def right(t, y):  # gap to the wall x = +b (m)
            return self.b - self.l * math.sin(y[0])

        def left(t, y):  # gap to the wall x = -b (m)
            return self.b + self.l * math.sin(y[0])

        for event in (right, left):
            event.terminal = True
            event.direction = -1
        return [right, left]

    def impact(self, which, t, y):
        """Newton's law with Coulomb friction (Model N); None on a Painleve stop."""
        wall = 1 if which == 0 else -1
        gamma_t = self.V0 * math.sin(self.omega * t) - self.l * math.sin(y[0]) * y[1]
        s = 1.0 if gamma_t > 0 else -1.0 if gamma_t < 0 else 0.0
        w_n = -wall * self.l * math.cos(self.theta0)
        w_t = -wall * self.l * math.sin(self.theta0)
        if not (w_n - s * self.mu * w_t) / w_n > PAINLEVE_MARGIN:
            return None
        return [wall * self.theta0, -self.e_n * y[1]]


class LinearImpact:
    """x'' + 2 zeta x' + x = A cos(omega t), stop at x = sigma, x'+ = -r x'-."""

    def __init__(self, k):
        self.zeta, self.A, self.omega = k["zeta"], k["A"], k["omega"]
        self.sigma, self.r = k["sigma"], k["r"]
        self.y0 = [k["initial.x"], k["initial.x_dot"]]
        self.max_step = min(2 * math.pi / self.omega, 2 * math.pi) / 16

    def rhs(self, t, y):
        return [y[1], self.A * math.cos(self.omega * t) - 2 * self.zeta * y[1] - y[0]]

    def events(self):
        def stop(t, y):  # gap to the stop
            return self.sigma - y[0]

        stop.terminal = True
        stop.direction = -1
        return [stop]

    def impact(self, which, t, y):
        return [self.sigma, -self.r * y[1]]


class BouncingBall:
    """y'' = -g over a table z = A sin(omega t); (y' - z')+ = -r (y' - z')-."""

    def __init__(self, k):
        self.g, self.A, self.omega, self.r = k["g"], k["A"], k["omega"], k["r"]
        self.y0 = [k["initial.y"], k["initial.y_dot"]]
        self.max_step = 2 * math.pi / self.omega / 16

    def rhs(self, t, y):
        return [y[1], -self.g]

    def events(self):
        def table(t, y):  # gap to the table (m)
            return y[0] - self.A * math.sin(self.omega * t)

        table.terminal = True
        table.direction = -1
        return [table]

    def impact(self, which, t, y):
        z = self.A * math.sin(self.omega * t)
        z_dot = self.A * self.omega * math.cos(self.omega * t)
        return [z, z_dot - self.r * (y[1] - z_dot)]


OSCILLATORS = {"pendulum_walls": Pendulum, "linear_impact": LinearImpact,
               "bouncing_ball": BouncingBall}


def run(system, method, rtol, atol, t0, t_end, max_impacts):
    """One event-loop run; returns impacts [(t, qdot_before)], counts, termination."""
    events = system.events()
    t, y = t0, list(system.y0)
    impacts, nfev, steps, stalled = [], 0, 0, 0
    termination = "completed"
    while t < t_end and len(impacts) < max_impacts:
        sol = solve_ivp(system.rhs, (t, t_end), y, method=method, rtol=rtol, atol=atol,
                        events=events, max_step=system.max_step)
        nfev += sol.nfev
        steps += len(sol.t) - 1
        if sol.status == -1:
            termination = "failed: " + sol.message
            break
        hit = [i for i, times in enumerate(sol.t_events) if len(times) > 0]
        if not hit:
            break
        which = min(hit, key=lambda i: sol.t_events[i][0])
        te, ye = float(sol.t_events[which][0]), [float(v) for v in sol.y_events[which][0]]
        impacts.append((te, ye[1]))
        after = system.impact(which, te, ye)
        if after is None:
            termination = "stopped_by_model"
            break
        # an accumulation of impacts (chattering) never ends in this loop
        stalled = stalled + 1 if te - t <= 1e-12 * max(1.0, abs(t)) else 0
        if stalled > 100:
            termination = "no_progress"
            break
        t, y = te, after
    return impacts, nfev, steps, termination


def main():
    spec_path, result_path = sys.argv[1], sys.argv[2]
    with open(spec_path) as f:
        spec = json.load(f)
    points = []
    total = sum(len(c["methods"]) * len(c["rtols"]) for c in spec["cases"])
    done = 0
    for case in spec["cases"]:
        system = OSCILLATORS[case["oscillator"]](case["keys"])
        for method in case["methods"]:
            for rtol in case["rtols"]:
                atol = rtol * case["atol_ratio"]
                start, start_cpu = time.perf_counter(), time.thread_time()
                impacts, nfev, steps, termination = run(
                    system, method, rtol, atol, case["t0"], case["t_end"], case["max_impacts"])
                cpu = time.thread_time() - start_cpu
                wall = time.perf_counter() - start
                points.append({"case": case["name"], "method": method, "rtol": rtol,
                               "atol": atol, "wall_s": wall, "cpu_s": cpu, "nfev": nfev, "steps": steps,
                               "termination": termination, "impacts": impacts})
                done += 1
                if not spec.get("quiet", False):
                    print(f"scipy {case['name']} {method} rtol={rtol:g}: {len(impacts)} impacts, "
                          f"{wall:.2f} s  [{done}/{total}]", file=sys.stderr)
    result = {"points": points,
              "versions": {"python": platform.python_version(), "numpy": np.__version__,
                           "scipy": scipy.__version__}}
    with open(result_path, "w") as f:
        json.dump(result, f)


if __name__ == "__main__":
    main()
