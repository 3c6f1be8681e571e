"""Every entry point gives the numbers of the CLI's files bit for bit, for
the same scene and options."""
import pytest

import impactlab
from conftest import read_csv, read_json, same_numbers

EVENT_COLUMNS = ["t", "wall", "q", "qdot_before", "qdot_after", "normal_impulse",
                 "tangential_velocity", "normal_force", "friction_work", "instantaneous_residual",
                 "sliding_residual", "tangential_velocity_after"]

# what meta.json holds that a second run cannot reproduce, or that only a file has
FILE_ONLY = {"command", "created_utc", "files", "wall_time_s"}


def without(document, keys):
    return {k: v for k, v in document.items() if k not in keys}


def test_simulate_equals_cli_events_trajectory_and_meta(cli):
    out = cli("simulate", "jin2003", "--set", "V0=4.163", "--periods", "30", "--sample", "0.05")
    run = impactlab.simulate("jin2003", V0=4.163, periods=30, sample=0.05)
    events = read_csv(out / "events.csv")
    assert len(run.events) == len(events["t"]) > 10
    for column in EVENT_COLUMNS:
        same_numbers(events[column], run.events[column])
    assert list(run.events.kind_names()) == events["kind"]
    trajectory = read_csv(out / "trajectory.csv")
    same_numbers(trajectory["t"], run.trajectory.t)
    same_numbers(trajectory["q"], run.trajectory.q)
    same_numbers(trajectory["qdot"], run.trajectory.qdot)
    assert run.trajectory.mode == trajectory["mode"]
    assert without(read_json(out / "meta.json"), FILE_ONLY) == without(run.meta, FILE_ONLY)


def test_simulate_event_array_is_a_view_without_copy():
    run = impactlab.simulate("jin2003", periods=5)
    assert run.events.base is not None
    assert not run.events.flags["OWNDATA"]
    assert run.events.dtype.names[:4] == ("t", "kind", "wall", "q")


def test_dotted_keys_two_spellings_equal_cli(cli):
    out = cli("simulate", "jin2003", "--set", "initial.theta=0.01", "--periods", "10")
    events = read_csv(out / "events.csv")
    for run in (impactlab.simulate("jin2003", initial__theta=0.01, periods=10),
                impactlab.simulate("jin2003", periods=10, **{"initial.theta": 0.01})):
        same_numbers(events["t"], run.events["t"])
        same_numbers(events["qdot_after"], run.events["qdot_after"])


def test_poincare_equals_cli(cli):
    out = cli("poincare", "jin2003", "--section", "impact", "--points", "20", "--transient", "20")
    section = impactlab.poincare("jin2003", section="impact", points=20, transient=20)
    rows = read_csv(out / "poincare.csv")
    assert len(rows["t"]) == 20
    for column in ("k", "t", "q", "qdot", "wall", "phase"):
        same_numbers(rows[column], getattr(section, column))


def test_sweep_1d_both_directions_equals_cli(cli):
    out = cli("sweep", "jin2003", "--param", "omega=6.5:7.5:4", "--direction", "both",
              "--points", "8", "--transient", "10", "--threads", "2")
    result = impactlab.sweep("jin2003", param="omega=6.5:7.5:4", direction="both", points=8,
                             transient=10, threads=2)
    bifurcation = read_csv(out / "bifurcation.csv")
    summary = read_csv(out / "summary.csv")
    for column in ("omega", "k", "t", "q", "qdot", "wall"):
        same_numbers(bifurcation[column], result.bifurcation[column])
    assert result.bifurcation["direction"] == bifurcation["direction"]
    for column in ("omega", "period", "impacts_per_period", "contact", "lyapunov", "points"):
        same_numbers(summary[column], result.summary[column])
    assert result.summary["termination"] == summary["termination"]
    assert result.summary["direction"] == summary["direction"]
    assert result.definition == read_json(out / "meta.json")["sweep"]


def test_sweep_2d_map_equals_cli(cli):
    out = cli("sweep", "jin2003", "--param", "omega=6.5:7.5:3", "--param", "V0=3.5:4.5:2",
              "--points", "6", "--transient", "5")
    result = impactlab.sweep("jin2003", param=["omega=6.5:7.5:3", "V0=3.5:4.5:2"], points=6,
                             transient=5)
    classes = read_csv(out / "classes.csv")
    for column in ("omega", "V0", "period", "impacts_per_period", "contact", "lyapunov"):
        same_numbers(classes[column], result.summary[column])


def test_periodic_equals_cli(cli):
    out = cli("periodic", "jin2003", "--transient", "50")
    orbit = impactlab.periodic("jin2003", transient=50)
    expected = read_json(out / "periodic.json")
    assert without(expected, FILE_ONLY) == without(orbit.meta, FILE_ONLY)
    assert orbit.multipliers.shape == (2,)


def test_compare_equals_cli(cli):
    out = cli("compare", "jin2003", "--models", "newton,rigid", "--periods", "10")
    comparison = impactlab.compare("jin2003", models=["newton", "rigid"], periods=10)
    for name, text in (("compare_impacts.csv", comparison.impacts_csv),
                       ("compare_contacts.csv", comparison.contacts_csv),
                       ("compare_section.csv", comparison.section_csv)):
        assert (out / name).read_text() == text
    assert (out / "summary.md").read_text() == comparison.summary
    assert read_json(out / "compare.json")["numbers"] == comparison.numbers
