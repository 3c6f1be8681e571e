"""Oscillators defined in a scene file's [model] section, from
Python: a scene path runs like a built-in scene name, gives the CLI's numbers
bit for bit, and the physics of the built-in oscillator it rewrites."""
import os

import pytest

import impactlab
from conftest import read_csv, same_numbers

SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXAMPLES = os.path.join(SOURCE, "oscillators", "model_file", "examples")
LINEAR_MODEL = os.path.join(EXAMPLES, "linear_impact_model.toml")

# ω at the period doubling of the linear impact oscillator's period-1 orbit
# (ζ = 0.05, r = 0.8, σ = 0.2, A = 1), from the closed form of
# tests/analysis/continuation_test.cpp (PeriodOneOrbit: 1 + tr M + det M = 0)
PERIOD_DOUBLING_OMEGA = 2.2652971759636387


@pytest.fixture(autouse=True)
def own_cache(tmp_path_factory, monkeypatch):
    monkeypatch.setenv("IMPACTLAB_CACHE_DIR", str(tmp_path_factory.getbasetemp() / "model_cache"))


def test_simulate_a_model_file_equals_cli_events(cli):
    out = cli("simulate", LINEAR_MODEL, "--set", "r=0.5", "--set", "sigma=0", "--set", "omega=0.5",
              "--periods", "10")
    run = impactlab.simulate(LINEAR_MODEL, r=0.5, sigma=0.0, omega=0.5, periods=10)
    events = read_csv(out / "events.csv")
    assert "accumulation" in events["kind"] and "contact_end" in events["kind"]
    assert len(run.events) == len(events["t"])
    for column in ("t", "wall", "q", "qdot_before", "qdot_after"):
        same_numbers(events[column], run.events[column])
    assert list(run.events.kind_names()) == events["kind"]


def test_a_model_file_gives_the_built_in_oscillators_events():
    # the same oscillator in C++ (oscillators/linear_impact): impacts, chatter,
    # sticking and release at the same times
    mine = impactlab.simulate(LINEAR_MODEL, r=0.5, sigma=0.0, omega=0.5, periods=10)
    built_in = impactlab.simulate("linear_impact", r=0.5, sigma=0.0, omega=0.5, periods=10,
                                  **{"integrator.method": "dopri5"})
    assert list(mine.events.kind_names()) == list(built_in.events.kind_names())
    assert len(mine.events) > 50
    worst = max(abs(a - b) for a, b in zip(mine.events["t"], built_in.events["t"]))
    assert worst <= 1e-12


def test_continue_on_a_model_file_finds_the_closed_form_period_doubling(cli):
    out = cli("continue", LINEAR_MODEL, "--param", "omega=2:2.5")
    result = impactlab.continue_(LINEAR_MODEL, param="omega=2:2.5")
    points = read_csv(out / "points.csv")
    assert points["type"] == result.points["type"]
    for column in ("omega", "q", "qdot", "error_estimate"):
        same_numbers(points[column], result.points[column])
    doubling = [w for t, w in zip(result.points["type"], result.points["omega"])
                if t == "period_doubling"]
    assert len(doubling) == 1
    assert abs(doubling[0] - PERIOD_DOUBLING_OMEGA) <= 1e-9 * PERIOD_DOUBLING_OMEGA


def test_a_bad_model_file_raises_value_error_at_its_line_and_column(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('[model]\nstates = ["x", "v"]\nforcing_frequency = "1"\n'
                   '[model.rhs]\nx = "v"\nv = "-x + y"\n')
    with pytest.raises(ValueError, match=str(bad) + ":6:11: unknown symbol 'y'"):
        impactlab.simulate(str(bad))


def duffing_without_sticking(folder):
    """The shipped Duffing oscillator without its wall's sticking table (the
    file's last section): it chatters into no_progress at some F."""
    with open(os.path.join(EXAMPLES, "duffing_stop.toml")) as shipped:
        model = shipped.read()
    scene = folder / "no_sticking.toml"
    scene.write_text(model[:model.index("[model.walls.sticking]")])
    return scene


def test_a_sweep_warns_of_its_points_that_stop_early(tmp_path):
    # the sweep says how many points stopped, as the CLI does, and as its
    # summary has them
    scene = duffing_without_sticking(tmp_path)
    with pytest.warns(impactlab.PhysicalDiagnosticWarning, match="points stopped early") as caught:
        result = impactlab.sweep(str(scene), r=0.2, sigma=0.1, param="F=0.2:3:20",
                                 lyapunov=False)
    stopped = sum(t != "completed" for t in result.summary["termination"])
    assert stopped > 0
    assert "{} of 20 points stopped early".format(stopped) in str(caught[0].message)


def test_basins_warn_of_their_points_that_stop_early(tmp_path):
    # its basins over (F, x0): the points that stopped are counted in a
    # warning, as grid['termination'] has them
    scene = duffing_without_sticking(tmp_path)
    with pytest.warns(impactlab.PhysicalDiagnosticWarning, match="points stopped early") as caught:
        result = impactlab.basins(str(scene), r=0.2, sigma=0.1, x="F=0.2:3:10",
                                  y="initial.x=-0.5:0:2")
    stopped = sum(t != "completed" for t in result.grid["termination"])
    assert stopped > 0
    assert "{} of 20 points stopped early".format(stopped) in str(caught[0].message)
