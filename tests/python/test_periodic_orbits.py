"""impactlab.periodic(all=True) gives the orbits of the CLI's
`periodic --all` (orbits.csv, periodic.json) bit for bit, each orbit's
multipliers as complex numbers, and bad input raises ValueError naming the
Python option."""
import numpy as np
import pytest

import impactlab
from conftest import read_csv, read_json, same_numbers

BOX = ["initial.y=0.02:0.08", "initial.y_dot=-1:1"]


def test_orbits_equal_the_cli_files(cli):
    out = cli("periodic", "bouncing_ball", "--all", "--period", "1", "--starts", "30",
              "--box", BOX[0], "--box", BOX[1], "--seed", "7")
    result = impactlab.periodic("bouncing_ball", all=True, period=1, starts=30, box=BOX, seed=7)
    rows = read_csv(out / "orbits.csv")
    assert list(rows) == list(result.orbits)
    for column, values in rows.items():
        same_numbers(values, result.orbits[column])
    meta = read_json(out / "periodic.json")
    assert result.meta["orbits"] == meta["orbits"]
    assert result.meta["starts"] == meta["starts"]
    assert result.meta["request"] == meta["request"]
    assert result.state_names == ["y", "y_dot"]
    # the state by its components' names, and each orbit's multipliers
    assert {"y", "y_dot", "multiplier1_re", "multiplier2_im"} <= set(result.orbits)
    assert len(result.multipliers) == len(result.orbits.id) >= 2
    for row, multipliers in enumerate(result.multipliers):
        assert multipliers.dtype == np.complex128
        assert multipliers[0] == complex(result.orbits.multiplier1_re[row],
                                         result.orbits.multiplier1_im[row])
        assert bool(result.orbits.stable[row]) == bool(np.all(np.abs(multipliers) < 1))
    # every start accounted for, and no orbit twice
    starts = meta["starts"]
    assert sum(starts[k] for k in ("new_orbit", "known_orbit", "not_converged", "stopped")) == 30
    assert starts["new_orbit"] == len(result.orbits.id)
    points = np.column_stack([result.orbits.y, result.orbits.y_dot])
    for i in range(len(points)):
        for j in range(i):
            assert np.hypot(*(points[i] - points[j])) > 1e-6


def test_the_same_seed_draws_the_same_orbits_and_another_may_not():
    first = impactlab.periodic("bouncing_ball", all=True, starts=10, seed=3)
    again = impactlab.periodic("bouncing_ball", all=True, starts=10, seed=3)
    assert first.meta["starts"] == again.meta["starts"]
    same_numbers(first.orbits.y, again.orbits.y)


@pytest.mark.parametrize("keywords, option", [
    (dict(starts=0), "starts"),
    (dict(box="initial.y=1"), "box"),
    (dict(box="initial.nope=0:1"), "box"),
    (dict(box="initial.y=-1:0.1"), "box"),  # below the table
    (dict(box="A=0:0.01"), "box"),  # a parameter: the orbits are those of one system
    (dict(box=3), "box"),
    (dict(starts=3, max_iterations=1), "starts"),  # no start converges
    (dict(all="yes"), "all"),
])
def test_bad_input_names_the_python_option(keywords, option):
    with pytest.raises(ValueError, match="^" + option + " = "):
        impactlab.periodic("bouncing_ball", **{"all": True, **keywords})


def test_no_orbit_says_so():
    with pytest.raises(ValueError, match="periodic all: no orbit of period 1 from 3 starts"):
        impactlab.periodic("bouncing_ball", all=True, starts=3, max_iterations=1)


def test_continue_all_continues_every_orbit_once():
    """continue_(all=True): each branch names the orbit it continues; the
    fold's pair, both found, gives one branch (the other orbit is on it)."""
    result = impactlab.continue_("linear_impact", param="omega=1.86:1.95", all=True, starts=100,
                                 box=["initial.x=-4:0.5", "initial.x_dot=-4:4"], sigma=0.5)
    orbit_ids = [branch["orbit"] for branch in result.branches]
    assert len(set(orbit_ids)) == len(orbit_ids)
    assert len(orbit_ids) + len(result.not_continued) == len(result.orbits) >= 3
    assert list(result.points["type"]).count("fold") == 1


def test_continue_all_bad_input_names_the_python_option():
    with pytest.raises(ValueError, match="^starts = "):
        impactlab.continue_("linear_impact", param="omega=1.86:1.95", all=True, starts=0)
    with pytest.raises(ValueError, match="^param2 = "):
        impactlab.continue_("linear_impact", param="omega=1.86:1.95", all=True,
                            param2="sigma=0.2:0.3")
