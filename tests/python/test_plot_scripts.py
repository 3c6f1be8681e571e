"""The data the plot scripts draw, checked where a figure went wrong: a
continuation point that could not be located (empty q in points.csv) is not
drawn at q = 0, off the branch; axes carry quantities and units from the
run's record; a rest is named as one; points that did not settle are marked;
a branch's points without multipliers (the friction cone's edge) are
dotted, and another column is drawn with --y; every script answers --help."""
import importlib.util
import pathlib
import subprocess
import sys

import numpy as np
import pytest

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


def test_points_without_multipliers_are_dotted_and_another_column_drawn(tmp_path):
    plot = load("plot_continuation")
    branch = tmp_path / "branch.csv"
    branch.write_text("mu,q,qdot,state3,period,branch,stable,multiplier1_re\n"
                      "4,0.04,-0.02,20,2,0,0,\n5,0.04,-0.02,12,2,0,0,\n"
                      "14,0.04,-0.02,-60,2,0,1,0.98\n16,0.04,-0.02,-60,2,0,1,0.98\n")
    figure = plot.draw_continuation(plot.branches_of(plot.read(branch)), None, {}, "mu",
                                    "theta", y="state3", y_label="spin rate (rad/s)")
    lines = [line for line in figure.axes[0].get_lines() if len(line.get_xdata())]
    styles = {line.get_linestyle(): list(line.get_ydata()) for line in lines}
    # the edge's two points and the one that joins them to the stable part
    assert styles[":"] == [20.0, 12.0, -60.0]
    assert styles["-"] == [-60.0, -60.0]
    assert figure.axes[0].get_ylabel() == "spin rate (rad/s) on the section"
    # a sweep drawn underneath must have the column too: no θ under a spin axis
    sweep = {"mu": np.array([4.0, 5.0]), "q": np.array([0.04, 0.04])}
    with pytest.raises(ValueError, match="y = 'state3': not a column of the sweep"):
        plot.draw_continuation(plot.branches_of(plot.read(branch)), None, {}, "mu", "theta",
                               sweep, y="state3")
    # a column branch.csv lacks is bad input naming it
    done = subprocess.run([sys.executable, str(SCRIPTS / "plot_continuation.py"), str(branch),
                           str(tmp_path / "out.png"), "mu", "theta", "--y", "spin", "spin (rad/s)"],
                          capture_output=True, text=True)
    assert done.returncode == 2
    assert "--y = 'spin'" in done.stderr
    assert not (tmp_path / "out.png").exists()


def test_axes_carry_quantities_and_units_from_the_runs_record(cli):
    labels = load("plot_labels")
    out = cli("sweep", "jin2003", "--param", "omega=6:7:3", "--points", "4", "--transient", "2")
    meta = labels.read_meta(out)
    assert labels.key_label(meta, "omega") == r"$\omega$ (rad/s)"
    assert labels.key_label(meta, "V0") == r"$V_0$ (m/s)"
    # the dot over theta is mathtext's, not a combining character a font drops
    assert labels.coordinate_labels(meta, "theta") == (r"$\theta$ (rad)", r"$\dot\theta$ (rad/s)")
    title = labels.title(meta, "bifurcation diagram", ("omega",))
    assert title.startswith("bifurcation diagram: jin2003")
    assert "V0 = 1.5 m/s" in title and "model = newton" in title
    assert "omega =" not in title  # the varied key
    assert "e_t" not in title  # Model N does not read it
    assert "integrator" not in title and "initial" not in title
    # another oscillator's own units
    out = cli("poincare", "linear_impact", "--points", "4", "--transient", "2")
    meta = labels.read_meta(out)
    assert labels.coordinate_labels(meta, "x") == ("$x$ (length)", r"$\dot x$ (length/time)")
    assert labels.key_label(meta, "initial.x") == "$x_0$ (length)"


def test_the_balls_rest_on_the_table_is_named_as_one(cli):
    basins = load("plot_basins")
    files = load("plot_files")
    out = cli("basins", "bouncing_ball", "--set", "A=0.00981", "--x", "initial.y=0:0.1:12",
              "--y", "initial.y_dot=-1:1:8")
    meta = load("plot_labels").read_meta(out)
    names = [basins.describe(row, meta)
             for row in files.rows_of(files.read_columns(out / "attractors.csv"))]
    assert any(name.endswith("at rest on the table (sticking)") for name in names), names
    assert any("period 1, 1 impacts/period" in name for name in names), names


def test_the_diagrams_mark_points_that_did_not_settle(cli):
    sweep = load("plot_sweep")
    out = cli("sweep", "jin2003", "--set", "V0=1", "--param", "omega=5.45:5.55:3",
              "--no-lyapunov", "--max-transient", "150")
    summary = load("plot_files").read_columns(out / "summary.csv")
    marks = sweep.unfinished_values(summary, "omega")
    unsettled = summary["omega"][summary["transient_end"] == "not_settled"]
    assert len(unsettled) > 0
    np.testing.assert_array_equal(marks["transient not settled"], unsettled)
    assert "run stopped early" not in marks


def test_every_plot_script_answers_help():
    scripts = sorted(SCRIPTS.glob("plot_*.py")) + [
        SCRIPTS.parent / "notebooks_data" / "jin2003" / "plot_jin2003.py"]
    assert len(scripts) >= 8
    for script in scripts:
        completed = subprocess.run([sys.executable, str(script), "--help"], capture_output=True,
                                   text=True, check=False)
        assert completed.returncode == 0, (script.name, completed.stderr)
        assert script.name in completed.stdout or "usage" in completed.stdout.lower(), \
            (script.name, completed.stdout)


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
