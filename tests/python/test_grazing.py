"""continue_'s grazing points in Python: the normal form's columns of points
and grazing.json's entries, the same numbers as the CLI's files, and
plot(which="grazing") beside a sweep."""
import math

import impactlab
import pytest

from conftest import read_csv, read_json, same_numbers


def test_grazing_entries_equal_cli(cli):
    out = cli("continue", "linear_impact", "--param", "omega=2:2.5", "--section", "impact:+1")
    result = impactlab.continue_("linear_impact", param="omega=2:2.5", section="impact:+1")
    points = read_csv(out / "points.csv")
    assert points["scenario"] == list(result.points["scenario"]) == ["", "jump"]
    # the grazing row's numbers (the period doubling's row leaves them empty in the file)
    for column in ("impacting_side", "impact_speed_coefficient", "period_one_speed_slope",
                   "period_one_side"):
        same_numbers([points[column][1]], [result.points[column][1]])
        assert math.isnan(points[column][0])
    (entry,) = result.grazing
    (written,) = read_json(out / "grazing.json")["points"]
    assert entry["scenario"] == written["scenario"] == "jump"
    assert entry["row"] == written["row"] == 1
    same_numbers([entry["impact_speed_coefficient"], entry["gap_per_parameter"]],
                 [written["impact_speed_coefficient"], written["gap_per_parameter"]])
    same_numbers(entry["normal_form"]["root_vector"], written["normal_form"]["root_vector"])
    assert len(entry["attractors"]) == 25


def test_no_normal_forms(cli):
    result = impactlab.continue_("linear_impact", param="omega=2:2.5", section="impact:+1",
                                 no_normal_forms=True)
    assert list(result.points["scenario"]) == ["", "unavailable"]
    assert result.grazing[0]["available"] is False


def test_plot_grazing_beside_a_sweep(tmp_path):
    pytest.importorskip("matplotlib")
    result = impactlab.continue_("linear_impact", param="omega=2:2.5", section="impact:+1")
    sweep = impactlab.sweep("linear_impact", param=["omega=2.44:2.4482:4"], section="impact:1",
                            points=8)
    path = tmp_path / "grazing.png"
    result.plot(str(path), which="grazing", sweep=sweep)
    assert path.exists() and path.stat().st_size > 1000
    with pytest.raises(ValueError, match="grazing"):
        impactlab.continue_("linear_impact", param="omega=2:2.4",
                            section="impact:+1").plot(which="grazing")
