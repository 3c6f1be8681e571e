"""impactlab.attractors gives the numbers of the CLI's attractors.csv,
attractor_points.csv, samples.csv and meta.json bit for bit, and bad input
raises ValueError naming the Python option."""
import pytest

import impactlab
from conftest import read_csv, read_json, same_numbers

# the linear impact oscillator over a short omega range, 8 samples per value
PARAM = "omega=2.0:2.2:3"
BOX = ["initial.x=-0.5:0.1", "initial.x_dot=-0.5:0.5"]


def test_attractors_equal_the_cli_files(cli):
    out = cli("attractors", "linear_impact", "--param", PARAM, "--samples", "8",
              "--box", BOX[0], "--box", BOX[1], "--seed", "5", "--threads", "2")
    result = impactlab.attractors("linear_impact", param=PARAM, samples=8, box=BOX, seed=5,
                                  threads=2)
    for name, table in (("attractors.csv", result.attractors),
                        ("attractor_points.csv", result.points),
                        ("samples.csv", result.samples)):
        rows = read_csv(out / name)
        assert list(rows) == list(table), name
        for column, values in rows.items():
            if isinstance(values[0], str):
                assert list(table[column]) == values, (name, column)
            else:
                same_numbers(values, table[column])
    meta = read_json(out / "meta.json")
    assert result.meta["sweep"] == meta["sweep"]
    assert result.meta["counts"] == meta["counts"]
    assert result.meta["attractor_events"] == meta["attractor_events"]
    assert result.attractor_events == meta["attractor_events"]["events"]
    assert result.param == "omega"
    # every value's fractions add up to one
    for value in set(result.attractors["omega"]):
        here = result.attractors["omega"] == value
        assert abs(result.attractors["fraction"][here].sum() - 1.0) < 1e-12


@pytest.mark.parametrize("keywords, option", [
    (dict(param="omega=2:2.2:3", samples=0), "samples"),
    (dict(param="omega=2:2.2", samples=4), "param"),
    (dict(param="omega=2:2.2:3", box="initial.nope=0:1"), "box"),
    (dict(param="omega=2:2.2:3", box="initial.x=-0.5:0.5"), "box"),  # past the stop at 0.2
    (dict(param="omega=2:2.2:3", box=3), "box"),
    (dict(param="omega=2:2.2:3", match_tol=0), "match_tol"),
])
def test_bad_input_names_the_python_option(keywords, option):
    with pytest.raises(ValueError, match="^" + option + " = "):
        impactlab.attractors("linear_impact", **keywords)


def test_plot_draws_the_bands_and_the_points(cli):
    """--plot runs scripts/plot_attractors.py on the files it wrote."""
    out = cli("attractors", "linear_impact", "--param", PARAM, "--samples", "4",
              "--box", BOX[0], "--plot")
    assert (out / "attractors.png").stat().st_size > 10000
