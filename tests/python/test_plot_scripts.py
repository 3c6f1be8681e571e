"""The data the plot scripts draw, checked where a figure went wrong: a
continuation point that could not be located (empty q in points.csv) is not
drawn at q = 0, off the branch."""
import importlib.util
import pathlib

import numpy as np

SCRIPTS = pathlib.Path(__file__).resolve().parents[2] / "scripts"


def load(name):
    spec = importlib.util.spec_from_file_location(name, SCRIPTS / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_a_point_not_located_is_not_drawn(tmp_path):
    plot = load("plot_continuation")
    header = "type,omega,q,qdot,error_estimate,located\n"
    # every q empty: numpy reads the column as booleans, False where empty
    only_failed = tmp_path / "only_failed.csv"
    only_failed.write_text(header + "grazing,6.1,,,0.01,0\n")
    marked, not_located = plot.marked_points(plot.read(only_failed), "omega")
    assert marked == {}
    assert not_located == 1
    # beside a located point: only that one is drawn, where it is
    mixed = tmp_path / "mixed.csv"
    mixed.write_text(header + "fold,5.5,0.25,0.1,1e-12,1\ngrazing,6.1,,,0.01,0\n")
    marked, not_located = plot.marked_points(plot.read(mixed), "omega")
    assert list(marked) == ["fold"]
    np.testing.assert_array_equal(marked["fold"][0], [5.5])
    np.testing.assert_array_equal(marked["fold"][1], [0.25])
    assert not_located == 1


def test_lyapunov_convergence_leaves_out_collapsed_directions(tmp_path):
    plot = load("plot_lyapunov")
    csv = tmp_path / "lyapunov.csv"
    csv.write_text("# running estimate ...\nt,lambda1,lambda2\n1.0,0.5,-inf\n2.0,0.25,-inf\n")
    lines = plot.running_lines(plot.read(csv))
    assert lines["lambda2"] is None  # -inf: drawn as a legend entry only
    np.testing.assert_array_equal(lines["lambda1"][0], [1.0, 2.0])
    np.testing.assert_array_equal(lines["lambda1"][1], [0.5, 0.25])
    # the time unit from the run's record: s where omega is in rad/s
    assert plot.time_unit({"scene": {"keys": {"omega": {"unit": "rad/s"}}}}) == "s"
    assert plot.time_unit({"scene": {"keys": {"omega": {"value": 2.0}}}}) == "time unit"
