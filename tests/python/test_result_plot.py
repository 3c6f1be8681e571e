"""A result's plot() draws what the CLI's --plot draws: the same PNG, byte
for byte, from the result's own numbers (the CLI's from its CSV files and
records), for every job the CLI draws; and it says what it cannot draw."""
import matplotlib
import pytest

import impactlab

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def drawn_as_by_the_cli(result, cli_png, tmp_path, **options):
    """result.plot() written beside the CLI's picture: the two files' bytes."""
    ours = tmp_path / ("python_" + cli_png.name)
    figure = result.plot(ours, **options)
    assert isinstance(figure, matplotlib.figure.Figure)
    assert cli_png.exists(), "the CLI drew no " + cli_png.name
    return cli_png.read_bytes(), ours.read_bytes()


def test_simulate(cli, tmp_path):
    out = cli("simulate", "jin2003", "--set", "V0=4", "--periods", "6", "--sample", "0.01",
              "--plot")
    run = impactlab.simulate("jin2003", V0=4, periods=6, sample=0.01)
    cli_png, ours = drawn_as_by_the_cli(run, out / "simulation.png", tmp_path)
    assert cli_png == ours


def test_simulate_without_samples_says_how_to_get_them():
    run = impactlab.simulate("jin2003", periods=2)
    with pytest.raises(ValueError, match="sample"):
        run.plot()


def test_poincare_and_its_lyapunov_spectrum(cli, tmp_path):
    out = cli("poincare", "linear_impact", "--points", "60", "--transient", "20",
              "--lyapunov-spectrum", "--plot")
    section = impactlab.poincare("linear_impact", points=60, transient=20,
                                 lyapunov_spectrum=True)
    cli_png, ours = drawn_as_by_the_cli(section, out / "poincare.png", tmp_path)
    assert cli_png == ours
    cli_png, ours = drawn_as_by_the_cli(section, out / "lyapunov.png", tmp_path,
                                        which="lyapunov")
    assert cli_png == ours
    # without the spectrum there is no second figure, and which names them
    plain = impactlab.poincare("linear_impact", points=5, transient=5)
    with pytest.raises(ValueError, match="lyapunov_spectrum=True"):
        plain.plot(which="lyapunov")
    with pytest.raises(ValueError, match="which = 'orbit'"):
        plain.plot(which="orbit")


def test_sweep_1d_with_its_unsettled_points_marked(cli, tmp_path):
    # the settling budget is short enough that some points do not settle:
    # their marks come from the summary, in both front ends
    out = cli("sweep", "jin2003", "--set", "V0=1", "--param", "omega=5.45:5.55:3",
              "--no-lyapunov", "--max-transient", "150", "--plot")
    result = impactlab.sweep("jin2003", V0=1, param="omega=5.45:5.55:3", lyapunov=False,
                             max_transient=150)
    assert "not_settled" in list(result.summary.transient_end)
    cli_png, ours = drawn_as_by_the_cli(result, out / "bifurcation.png", tmp_path)
    assert cli_png == ours


def test_sweep_2d(cli, tmp_path):
    out = cli("sweep", "jin2003", "--param", "omega=6:7:3", "--param", "V0=1:2:3", "--points",
              "8", "--plot")
    result = impactlab.sweep("jin2003", param=["omega=6:7:3", "V0=1:2:3"], points=8)
    cli_png, ours = drawn_as_by_the_cli(result, out / "classes.png", tmp_path)
    assert cli_png == ours


def test_basins(cli, tmp_path):
    out = cli("basins", "bouncing_ball", "--set", "A=0.00981", "--x", "initial.y=0:0.1:12",
              "--y", "initial.y_dot=-1:1:8", "--plot")
    result = impactlab.basins("bouncing_ball", A=0.00981, x="initial.y=0:0.1:12",
                              y="initial.y_dot=-1:1:8")
    cli_png, ours = drawn_as_by_the_cli(result, out / "basins.png", tmp_path)
    assert cli_png == ours


def test_attractors(cli, tmp_path):
    out = cli("attractors", "jin2003", "--param", "omega=3.9:4.1:3", "--samples", "24",
              "--box", "initial.theta=-0.06:0.06", "--box", "initial.theta_dot=-1:1", "--plot")
    result = impactlab.attractors("jin2003", param="omega=3.9:4.1:3", samples=24,
                                  box=["initial.theta=-0.06:0.06", "initial.theta_dot=-1:1"])
    cli_png, ours = drawn_as_by_the_cli(result, out / "attractors.png", tmp_path)
    assert cli_png == ours


def test_compare(cli, tmp_path):
    out = cli("compare", "jin2003", "--models", "newton,rigid", "--periods", "10")
    comparison = impactlab.compare("jin2003", models=["newton", "rigid"], periods=10)
    cli_png, ours = drawn_as_by_the_cli(comparison, out / "compare.png", tmp_path)
    assert cli_png == ours


def test_continuation_over_a_sweep(cli, tmp_path):
    sweep_out = cli("sweep", "linear_impact", "--set", "sigma=0.2", "--param", "omega=2:2.5:6",
                    "--points", "8")
    sweep = impactlab.sweep("linear_impact", sigma=0.2, param="omega=2:2.5:6", points=8)
    moved = tmp_path / "sweep"
    sweep_out.rename(moved)
    out = cli("continue", "linear_impact", "--set", "sigma=0.2", "--param", "omega=2:2.5",
              "--switch", "--with-sweep", str(moved / "bifurcation.csv"))
    result = impactlab.continue_("linear_impact", sigma=0.2, param="omega=2:2.5", switch=True)
    cli_png, ours = drawn_as_by_the_cli(result, out / "continuation.png", tmp_path, sweep=sweep)
    assert cli_png == ours
    with pytest.raises(ValueError, match="param2"):
        result.plot(which="curve")
    with pytest.raises(ValueError, match="sweep"):
        result.plot(sweep="bifurcation.csv")


def test_two_parameter_curve(cli, tmp_path):
    arguments = dict(param="A=0.0112:0.025", start=[0.044286522498880876, -0.6269934342801218],
                     param2="r=0.8:0.75", curve="period_doubling")
    out = cli("continue", "bouncing_ball", "--param", arguments["param"], "--start",
              "0.044286522498880876,-0.6269934342801218", "--param2", arguments["param2"],
              "--curve", "period_doubling", "--plot")
    result = impactlab.continue_("bouncing_ball", **arguments)
    cli_png, ours = drawn_as_by_the_cli(result, out / "continuation.png", tmp_path)
    assert cli_png == ours
    cli_png, ours = drawn_as_by_the_cli(result, out / "curve.png", tmp_path, which="curve")
    assert cli_png == ours


def test_work_precision_draws_each_methods_ladder():
    # the CLI's bench runs its own fixed cases; the figure of one case is
    # drawn by the same function: one line per method, its rtols in order
    result = impactlab.bench("linear_impact", methods=["dopri5", "taylor"],
                             rtols=(1e-9, 1e-6), periods=20, reference_periods=10,
                             max_reference_impacts=10)
    figure = result.plot()
    by_time = figure.axes[0]
    lines = {line.get_label(): line for line in by_time.get_lines()}
    assert set(lines) == {"impactlab dopri5", "impactlab taylor"}
    for method in ("dopri5", "taylor"):
        rows = sorted((rtol, seconds, error) for name, rtol, seconds, error in zip(
            result.method, result.rtol, result.seconds_per_impact, result.impact_time_error)
            if name == method)
        assert list(lines["impactlab " + method].get_xdata()) == \
            pytest.approx([seconds * 1e6 for _, seconds, _ in rows])
        assert list(lines["impactlab " + method].get_ydata()) == \
            pytest.approx([max(error, 1e-17) for _, _, error in rows])
    assert by_time.get_xlabel() == "CPU time per impact (µs, one core)"


def test_a_job_the_cli_draws_nothing_for_says_so():
    found = impactlab.periodic("linear_impact", period=1)
    with pytest.raises(TypeError, match="draws no figure"):
        found.plot()


def test_curve_with_a_codimension_two_point(cli, tmp_path):
    # the grazing curve with its grazing-period-doubling point marked, and
    # (switch) the period-doubling curve from it
    out = cli("continue", "linear_impact", "--set", "sigma=0", "--set", "initial.x=-0.5",
              "--param", "omega=1.5:0.8", "--param2", "sigma=0:-0.04", "--curve", "grazing",
              "--switch", "--plot")
    result = impactlab.continue_("linear_impact", sigma=0, initial__x=-0.5,
                                 param="omega=1.5:0.8", param2="sigma=0:-0.04", curve="grazing",
                                 switch=True)
    assert len(result.curve_points["type"]) == 1
    cli_png, ours = drawn_as_by_the_cli(result, out / "curve.png", tmp_path, which="curve")
    assert cli_png == ours
