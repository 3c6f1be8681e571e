"""The rigid-body pendulum in the analyses from Python: the numbers of the
CLI's files bit for bit (periodic with the spin free: three multipliers, one
of them the neutral spin's 1; continue with the spin held, and through the
stick end onto the friction cone's edge), a sweep over the friction
coefficient, and the refusals as ValueError naming the option."""
import pytest

import impactlab
from conftest import read_csv, read_json, same_numbers

FILE_ONLY = {"command", "created_utc", "files", "wall_time_s"}
FREE = ["--set", "model=rigid", "--set", "spin=free", "--set", "radius=0.02", "--set", "V0=4"]
FREE_KEYS = {"model": "rigid", "spin": "free", "radius": 0.02, "V0": 4}


def without(document, keys):
    return {k: v for k, v in document.items() if k not in keys}


def test_periodic_with_the_spin_free_equals_cli(cli):
    out = cli("periodic", "jin2003", "--period", "6", *FREE)
    orbit = impactlab.periodic("jin2003", period=6, **FREE_KEYS)
    assert without(read_json(out / "periodic.json"), FILE_ONLY) == without(orbit.meta, FILE_ONLY)
    assert orbit.converged
    assert orbit.multipliers.shape == (3,) and orbit.monodromy.shape == (3, 3)
    assert abs(orbit.multipliers[0] - 1.0) < 1e-9
    assert orbit.state_names == ["theta", "theta_dot", "spin_rate", "spin_angle",
                                 "friction_work"]
    assert len(orbit.state) == len(orbit.state_names)


def test_continue_with_the_spin_held_equals_cli(cli):
    out = cli("continue", "jin2003", "--period", "6", "--param", "omega=7:6.95", *FREE)
    result = impactlab.continue_("jin2003", period=6, param="omega=7:6.95", **FREE_KEYS)
    document = read_json(out / "continuation.json")
    assert result.neutral_component["index"] == document["neutral_component"]["index"] == 3
    assert result.neutral_component["value"] == document["neutral_component"]["value"]
    branch = read_csv(out / "branch.csv")
    one = result.branches[0]
    for column in ("omega", "q", "qdot", "state3", "stable"):
        same_numbers(branch[column], one[column])
    for k in (1, 2, 3):
        same_numbers(branch["multiplier{}_re".format(k)], one["multiplier{}".format(k)].real)


def test_friction_sweep_equals_cli(cli):
    out = cli("sweep", "jin2003", "--param", "mu=0.2:1.2:4", *FREE)
    sweep = impactlab.sweep("jin2003", param="mu=0.2:1.2:4", **FREE_KEYS)
    summary = read_csv(out / "summary.csv")
    same_numbers(summary["mu"], sweep.summary["mu"])
    same_numbers(summary["period"], sweep.summary["period"])


def test_continue_through_the_stick_end_equals_cli_and_draws_the_spin(cli):
    keys = {"model": "rigid", "spin": "free", "radius": 0.02, "V0": 2, "mu": 16}
    options = [word for key, value in keys.items() for word in ("--set", f"{key}={value}")]
    out = cli("continue", "jin2003", "--period", "2", "--param", "mu=16:12", "--transient",
              "2000", *options)
    result = impactlab.continue_("jin2003", period=2, param="mu=16:12", transient=2000, **keys)
    branch = read_csv(out / "branch.csv")
    one = result.branches[0]
    for column in ("mu", "q", "qdot", "state3", "stable"):
        same_numbers(branch[column], one[column])
    same_numbers(branch["multiplier1_re"], one["multiplier1"].real)
    assert list(result.points["type"]) == ["stick_end"]
    # below the stick end the branch is on the friction cone's edge: drawn dotted
    figure = result.plot(y="state3", y_label="spin rate (rad/s)")
    styles = {line.get_linestyle() for line in figure.axes[0].get_lines()
              if len(line.get_xdata())}
    assert {"-", ":"} <= styles
    assert figure.axes[0].get_ylabel() == "spin rate (rad/s) on the section"
    with pytest.raises(ValueError, match="y = 'spin'"):
        result.plot(y="spin")


def test_refusals_name_the_option():
    with pytest.raises(ValueError, match="spin"):
        impactlab.periodic("jin2003", model="rigid", spin="free", radius=0.0)
    with pytest.raises(ValueError, match="mu = 20"):
        impactlab.periodic("jin2003", model="rigid", mu=20, **{"initial.theta": 0.07148944988552054,
                                                               "initial.theta_dot": 0.0})
