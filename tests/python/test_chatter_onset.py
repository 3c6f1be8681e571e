"""continue_'s onset of complete chatter in Python: the point the branch
locates and the curve followed from it, the same numbers as the CLI's files
(the method and its accuracy are checked in
tests/analysis/chatter_onset_test.cpp)."""
import impactlab

from conftest import read_csv, same_numbers

ARGUMENTS = dict(param="omega=0.3:0.5", section="strobe:3.14159", param2="sigma=0.5:0.52",
                 curve="chatter_onset")


def test_chatter_onset_point_and_curve_equal_cli(cli):
    out = cli("continue", "linear_impact", "--set", "r=0.5", "--set", "sigma=0.5",
              "--param", ARGUMENTS["param"], "--section", ARGUMENTS["section"],
              "--param2", ARGUMENTS["param2"], "--curve", ARGUMENTS["curve"])
    result = impactlab.continue_("linear_impact", r=0.5, sigma=0.5, **ARGUMENTS)
    points = read_csv(out / "points.csv")
    assert points["type"] == list(result.points["type"]) == ["chatter_onset", "fold"]
    same_numbers(points["omega"], list(result.points["omega"]))
    curve = read_csv(out / "curve.csv")
    (followed,) = result.curves
    assert set(curve["type"]) == {followed["type"]} == {"chatter_onset"}
    same_numbers(curve["omega"], list(followed["omega"]))
    same_numbers(curve["sigma"], list(followed["sigma"]))
    assert curve["sigma"][-1] == 0.52
