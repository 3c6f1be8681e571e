"""impactlab.basins gives the numbers of the CLI's basins.csv and
attractors.csv bit for bit, names the key of a bad grid, and can be cancelled
from its progress callback."""
import math

import pytest

import impactlab
from conftest import read_csv, read_json, same_numbers

# the bouncing ball of tests/analysis/basins_test.cpp (Γ = Aω²/g = 0.9): rest
# on the table and a period-1 bouncing orbit coexist; a 6 x 4 grid of initial
# states
GRID_X, GRID_Y = "initial.y=0:0.1:6", "initial.y_dot=-1:1:4"


def test_basins_equal_cli_basins_and_attractors(cli):
    out = cli("basins", "bouncing_ball", "--set", "A=0.00981", "--x", GRID_X, "--y", GRID_Y,
              "--threads", "2")
    result = impactlab.basins("bouncing_ball", x=GRID_X, y=GRID_Y, threads=2, A=0.00981)
    grid = read_csv(out / "basins.csv")
    assert len(grid["attractor"]) == 24
    for column in ("initial.y", "initial.y_dot", "attractor", "period", "impacts_per_period",
                   "contact"):
        same_numbers(grid[column], result.grid[column])
    assert result.grid["termination"] == grid["termination"]
    attractors = read_csv(out / "attractors.csv")
    assert len(attractors["attractor"]) == len(result.attractors) >= 2  # rest and bouncing
    for column in result.attractors.dtype.names:
        same_numbers(attractors[column], result.attractors[column])
    # the labels as a (Ny, Nx) grid, the first key fastest, and the axes
    assert result.labels.shape == (4, 6)
    same_numbers(grid["attractor"], result.labels.ravel())
    same_numbers(grid["initial.y"][:6], result.x)
    same_numbers(grid["initial.y_dot"][::6], result.y)
    assert result.x[0] == 0.0 and result.x[-1] == 0.1 and result.y[0] == -1.0 and result.y[-1] == 1.0
    assert result.axes == ("initial.y", "initial.y_dot")
    assert result.attractors["basin_points"].sum() == 24
    meta = read_json(out / "meta.json")
    assert result.meta["sweep"] == meta["sweep"]
    assert result.meta["counts"] == meta["counts"]
    # the basin measures of the 6 x 4 grid: 4 x 4 boxes (the shorter side)
    assert result.basin_measures == meta["basin_measures"] == result.meta["basin_measures"]
    assert result.basin_measures["box_size"] == 4


def test_basin_measures_equal_the_cli_measures(cli):
    """The measures of a 12 x 8 grid with 4 x 4 boxes are the CLI's meta.json's
    numbers (scales 1 and 2: an exponent without an error)."""
    x, y = "initial.y=0:0.1:12", "initial.y_dot=-1:1:8"
    out = cli("basins", "bouncing_ball", "--set", "A=0.00981", "--x", x, "--y", y,
              "--threads", "2", "--entropy-box", "4")
    result = impactlab.basins("bouncing_ball", x=x, y=y, threads=2, entropy_box=4, A=0.00981)
    measures = read_json(out / "meta.json")["basin_measures"]
    assert result.basin_measures == measures
    assert measures["box_size"] == 4 and measures["scales"] == [1, 2]
    assert measures["uncertainty_exponent_error"] is None
    assert 0.0 <= measures["basin_entropy"] <= math.log(measures["labels"])
    with pytest.raises(ValueError, match="entropy_box"):
        impactlab.basins("bouncing_ball", x=x, y=y, entropy_box=9, A=0.00981)


@pytest.mark.parametrize("x, key, shown", [
    ("colour=0:1:4", "x", "x = colour"),                 # no such key
    ("initial.y=0:0.1:0", "x", "initial.y=0:0.1:0"),     # N = 0
    ("initial.y=nan:0.1:4", "x", "initial.y=nan:0.1:4"),  # NaN
    ("initial.y=0:0.1", "x", "initial.y=0:0.1"),         # malformed
    ("initial.y_dot=0:1:4", "y", "y = initial.y_dot"),   # the same key as y
])
def test_bad_grid_raises_value_error_naming_the_key(x, key, shown):
    """The message begins with the keyword it names: "KEY = VALUE: reason"."""
    with pytest.raises(ValueError) as raised:
        impactlab.basins("bouncing_ball", x=x, y="initial.y_dot=-1:1:4")
    assert str(raised.value).startswith(key + " = "), str(raised.value)
    assert shown in str(raised.value)


@pytest.mark.parametrize("options, named", [
    ({"attractor_tol": 0.0}, "attractor_tol"),
    ({"attractor_tol": math.nan}, "attractor_tol"),
    ({"threads": 0}, "threads"),
    ({"x": 3}, "x"),
])
def test_bad_option_raises_value_error_naming_it(options, named):
    arguments = {"x": GRID_X, "y": GRID_Y, **options}
    with pytest.raises(ValueError) as raised:
        impactlab.basins("bouncing_ball", **arguments)
    assert str(raised.value).startswith(named + " = "), str(raised.value)


def test_basins_are_cancelled_by_their_progress_callback():
    def interrupt(fraction):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        impactlab.basins("bouncing_ball", x="initial.y=0:0.1:20", y=GRID_Y, threads=2,
                         progress=interrupt)
    assert impactlab.basins("bouncing_ball", x="initial.y=0:0.1:2", y="initial.y_dot=0:1:2",
                            points=5, transient=5).labels.shape == (2, 2)


def test_batch_off_gives_the_batch_grid_and_says_its_width():
    """batch=False runs the trajectories one at a time: the same grid as the
    batch's lanes (the default with the Taylor stepper on the pendulum), bit
    for bit; meta records the lanes per thread."""
    grid = dict(x="initial.theta=-0.04:0.04:4", y="initial.theta_dot=-0.5:0.5:3", transient=20,
                points=8, V0=4.163)
    lanes = impactlab.basins("jin2003", batch=True, **grid)
    alone = impactlab.basins("jin2003", batch=False, **grid)
    assert impactlab.basins("jin2003", **grid).meta["run"]["batch_width"] == 16  # on by default
    assert lanes.meta["run"]["batch_width"] == 16
    assert alone.meta["run"]["batch_width"] == 1
    for column in ("attractor", "period", "impacts_per_period", "contact"):
        same_numbers(lanes.grid[column], alone.grid[column])
    for column in lanes.attractors.dtype.names:
        same_numbers(lanes.attractors[column], alone.attractors[column])
    assert impactlab.basins("jin2003", batch="off", **grid).meta["run"]["batch_width"] == 1


@pytest.mark.parametrize("value", ["maybe", 1, None])
def test_a_bad_batch_raises_naming_it(value):
    with pytest.raises(ValueError, match="batch"):
        impactlab.basins("jin2003", x="initial.theta=-0.04:0.04:2",
                         y="initial.theta_dot=-0.5:0.5:2", batch=value)
