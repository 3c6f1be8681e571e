"""Every entry point gives the numbers of the CLI's files bit for bit, for
the same scene and options."""
import math
import os
import subprocess

import numpy as np
import pytest

import impactlab
from conftest import read_csv, read_json, same_numbers



def same_events(events_csv, events):
    """The events array has events.csv's columns, in its order, with the same
    numbers bit for bit (kind as names)."""
    columns = list(events_csv)
    assert list(events.dtype.names) == columns
    for column in columns:
        if column != "kind":
            same_numbers(events_csv[column], events[column])
    assert list(events.kind_names()) == events_csv["kind"]


# what meta.json holds that a second run cannot reproduce, or that only a file has
FILE_ONLY = {"command", "created_utc", "files", "wall_time_s"}


def without(document, keys):
    return {k: v for k, v in document.items() if k not in keys}


def test_simulate_equals_cli_events_trajectory_and_meta(cli):
    out = cli("simulate", "jin2003", "--set", "V0=4.163", "--periods", "30", "--sample", "0.05")
    run = impactlab.simulate("jin2003", V0=4.163, periods=30, sample=0.05)
    events = read_csv(out / "events.csv")
    assert len(run.events) == len(events["t"]) > 10
    same_events(events, run.events)
    trajectory = read_csv(out / "trajectory.csv")
    same_numbers(trajectory["t"], run.trajectory.t)
    same_numbers(trajectory["q"], run.trajectory.q)
    same_numbers(trajectory["qdot"], run.trajectory.qdot)
    assert run.trajectory.mode == trajectory["mode"]
    assert without(read_json(out / "meta.json"), FILE_ONLY) == without(run.meta, FILE_ONLY)


def test_simulate_the_issue_example_equals_cli_events(cli):
    # chattering, accumulations and contact phases: every event column, bit for bit
    out = cli("simulate", "jin2003", "--set", "V0=4.163", "--periods", "100")
    run = impactlab.simulate("jin2003", V0=4.163, periods=100)
    events = read_csv(out / "events.csv")
    assert "accumulation" in events["kind"] and "contact_start" in events["kind"]
    assert len(run.events) == len(events["t"])
    same_events(events, run.events)


def test_simulate_paper_model_equals_cli_events_with_its_residuals(cli):
    # Model P's impact residuals are its extension of the core's record: the
    # events array carries them as events.csv does, at every impact
    out = cli("simulate", "jin2003", "--set", "model=paper", "--set", "V0=4.163", "--periods", "30")
    run = impactlab.simulate("jin2003", model="paper", V0=4.163, periods=30)
    events = read_csv(out / "events.csv")
    assert len(run.events) == len(events["t"]) > 10
    same_events(events, run.events)
    assert "instantaneous_residual" in events and "sliding_residual" in events
    impacts = [k for k, kind in enumerate(events["kind"]) if kind == "impact"]
    assert impacts
    assert all(math.isfinite(run.events["instantaneous_residual"][k]) for k in impacts)
    assert all(math.isfinite(run.events["sliding_residual"][k]) for k in impacts)


def test_scenes_equal_cli_list():
    listed = subprocess.run([os.environ["IMPACTLAB_CLI"], "scenes"], capture_output=True,
                            text=True, check=True).stdout.splitlines()
    # the built-in scenes; the program lists the model files it ships after them
    shipped = [k for k, line in enumerate(listed) if line.startswith("model files shipped")]
    listed = listed[:shipped[0]] if shipped else listed
    names = [line.split()[0] for line in listed]
    oscillators = [line.split()[1] for line in listed]
    assert [s["name"] for s in impactlab.scenes()] == names
    assert [s["oscillator"] for s in impactlab.scenes()] == oscillators


def test_scene_equals_cli_set(cli):
    out = cli("simulate", "jin2003", "--set", "V0=4.163", "--set", "omega=7", "--periods", "1")
    loaded = impactlab.scene("jin2003", V0=4.163, omega=7)
    assert loaded.record() == read_json(out / "meta.json")["scene"]
    assert loaded.values()["V0"] == 4.163 and loaded.values()["omega"] == 7.0


def test_simulate_event_array_is_a_view_without_copy():
    run = impactlab.simulate("jin2003", periods=5)
    assert run.events.base is not None
    assert not run.events.flags["OWNDATA"]
    assert run.events.dtype.names[:4] == ("t", "kind", "wall", "q")


@pytest.mark.parametrize("model", ["newton", "paper", "rigid"])
def test_simulate_event_array_bytes_outside_its_columns_are_zero(model):
    # the rows are the C++ records: their padding, and the fields a model's
    # files do not have, are zero, so that the same run gives the same bytes
    # (and NumPy saves the same file)
    run = impactlab.simulate("jin2003", model=model, V0=4.163, periods=30)
    events = run.events
    assert len(events) > 10
    read = np.zeros(events.dtype.itemsize, dtype=bool)
    for name in events.dtype.names:
        field, offset = events.dtype.fields[name][:2]
        read[offset:offset + field.itemsize] = True
    assert not read.all()
    rows = np.frombuffer(events.tobytes(), dtype=np.uint8).reshape(len(events), -1)
    assert not rows[:, ~read].any()
    again = impactlab.simulate("jin2003", model=model, V0=4.163, periods=30)
    assert again.events.tobytes() == events.tobytes()


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


def test_poincare_settling_transient_equals_cli(cli):
    # no transient given: both run until the decaying rest has settled
    out = cli("poincare", "jin2003", "--set", "omega=5.5", "--set", "V0=1")
    section = impactlab.poincare("jin2003", omega=5.5, V0=1)
    meta = read_json(out / "meta.json")
    assert section.transient_end == meta["transient"]["end"] == "settled"
    assert section.transient_periods == meta["transient"]["periods"] > 100
    rows = read_csv(out / "poincare.csv")
    for column in ("t", "q", "qdot"):
        same_numbers(rows[column], getattr(section, column))


def test_sweep_settling_columns_equal_cli(cli):
    out = cli("sweep", "jin2003", "--set", "V0=1", "--param", "omega=5.4:5.6:3", "--points", "8",
              "--max-transient", "500")
    # a point still converging after 500 periods: warned of, as the CLI does
    with pytest.warns(impactlab.PhysicalDiagnosticWarning,
                      match="1 of 3 points did not settle within max_transient = 500"):
        result = impactlab.sweep("jin2003", V0=1, param="omega=5.4:5.6:3", points=8,
                                 max_transient=500)
    summary = read_csv(out / "summary.csv")
    assert summary["transient_end"].count("not_settled") == 1
    same_numbers(summary["transient_periods"], result.summary["transient_periods"])
    assert result.summary["transient_end"] == summary["transient_end"]
    assert result.definition == read_json(out / "meta.json")["sweep"]


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
    # one truth for the classification tolerance: the same integrators recorded
    assert result.definition == read_json(out / "meta.json")["sweep"]
    # the same columns as attributes, and shaped like the map: [j, i] is V0's
    # j-th value and omega's i-th (classes.csv: omega fastest)
    assert result.summary.period is result.summary["period"]
    assert result.grids.period.shape == (2, 3)
    for row, (omega, v0) in enumerate(zip(classes["omega"], classes["V0"])):
        i, j = row % 3, row // 3
        assert result.grids.omega[j, i] == omega and result.grids.V0[j, i] == v0
        assert result.grids.period[j, i] == classes["period"][row]
        assert result.grids.termination[j, i] == classes["termination"][row]


@pytest.mark.parametrize("batch, width", [(True, 16), (False, 1)])
def test_sweep_2d_map_says_its_batch_width_as_the_cli(cli, batch, width):
    """The lanes per thread (batch on: 16 with the Taylor stepper) in the
    result's run as in meta.json's, and the same classes with or without."""
    grid = ["omega=6.5:7.5:3", "V0=3.5:4.5:2"]
    out = cli("sweep", "jin2003", "--param", grid[0], "--param", grid[1], "--points", "6",
              "--transient", "5", "--batch", "on" if batch else "off")
    result = impactlab.sweep("jin2003", param=grid, points=6, transient=5, batch=batch)
    assert result.run["batch_width"] == read_json(out / "meta.json")["run"]["batch_width"] == width
    assert result.run["threads"] == read_json(out / "meta.json")["run"]["threads"]
    classes = read_csv(out / "classes.csv")
    for column in ("period", "impacts_per_period", "lyapunov"):
        same_numbers(classes[column], result.summary[column])


def test_every_result_reads_its_columns_as_attributes():
    run = impactlab.simulate("jin2003", periods=5)
    assert run.events.t is not None and (run.events.t == run.events["t"]).all()
    branches = impactlab.continue_("linear_impact", param="omega=2:2.1").branches
    assert (branches[0].q == branches[0]["q"]).all()
    with pytest.raises(AttributeError, match="no column 'nope'; the columns: "):
        branches[0].nope
    sweep = impactlab.sweep("jin2003", param="omega=6:7:3", points=4, transient=2)
    assert sweep.summary.period is sweep.summary["period"]
    assert sweep.bifurcation.q is sweep.bifurcation["q"]


@pytest.mark.parametrize("cli_options, python_options", [
    ([], {}),                                                   # auto: the classification integrator
    (["--classification-tol", "off"], {"classification_tol": "off"}),  # the scene's
    (["--set", "integrator.rtol=1e-11"], {"integrator__rtol": 1e-11}),  # the user's key wins
])
def test_sweep_2d_classification_integrator_equals_cli(cli, cli_options, python_options):
    grid = ["omega=6.5:7.5:3", "V0=3.5:4.5:2"]
    out = cli("sweep", "jin2003", "--param", grid[0], "--param", grid[1], "--points", "6",
              "--transient", "5", "--no-lyapunov", *cli_options)
    result = impactlab.sweep("jin2003", param=grid, points=6, transient=5, lyapunov=False,
                             **python_options)
    meta = read_json(out / "meta.json")
    assert result.definition == meta["sweep"]
    integrator = meta["sweep"]["classification_integrator"]
    scene = impactlab.scene("jin2003").values()
    if cli_options:
        expected_rtol = 1e-11 if "--set" in cli_options else scene["integrator.rtol"]
        assert integrator["rtol"] == expected_rtol
    elif scene["integrator.classification_rtol"] > 0:
        assert integrator["rtol"] == scene["integrator.classification_rtol"]
        assert integrator["rtol"] > scene["integrator.rtol"]
    else:  # the scene states no classification tolerance (jin2003): its own
        assert integrator["rtol"] == scene["integrator.rtol"]
        assert "states no classification" in meta["sweep"]["classification_integrator_note"]
    assert meta["sweep"]["lyapunov_integrator"] is None
    classes = read_csv(out / "classes.csv")
    for column in ("period", "impacts_per_period", "contact"):
        same_numbers(classes[column], result.summary[column])


def test_periodic_equals_cli(cli):
    out = cli("periodic", "jin2003", "--transient", "50")
    orbit = impactlab.periodic("jin2003", transient=50)
    expected = read_json(out / "periodic.json")
    assert without(expected, FILE_ONLY) == without(orbit.meta, FILE_ONLY)
    assert orbit.multipliers.shape == (2,)


IMPACT_DAMPER = os.path.join(os.path.dirname(__file__), "..", "..", "oscillators", "model_file",
                             "examples", "impact_damper.toml")


def test_four_state_model_periodic_and_continue_equal_cli(cli):
    # a model file's tangent space is all its states: 4 multipliers, 4 x 4 monodromy
    out = cli("periodic", IMPACT_DAMPER, "--set", "omega=1.5")
    orbit = impactlab.periodic(IMPACT_DAMPER, omega=1.5)
    assert without(read_json(out / "periodic.json"), FILE_ONLY) == without(orbit.meta, FILE_ONLY)
    assert orbit.multipliers.shape == (4,) and orbit.monodromy.shape == (4, 4)
    out = cli("continue", IMPACT_DAMPER, "--param", "omega=1.5:1.6", "--max-points", "12")
    result = impactlab.continue_(IMPACT_DAMPER, param="omega=1.5:1.6", max_points=12)
    branch = read_csv(out / "branch.csv")
    one = result.branches[0]
    assert len(branch["omega"]) == len(one["omega"]) >= 2
    for column in ("omega", "q", "qdot", "state3", "state4", "stable", "newton_iterations"):
        same_numbers(branch[column], one[column])
    for k in (1, 2, 3, 4):
        same_numbers(branch["multiplier{}_re".format(k)], one["multiplier{}".format(k)].real)
        same_numbers(branch["multiplier{}_im".format(k)], one["multiplier{}".format(k)].imag)


def test_compare_equals_cli(cli):
    out = cli("compare", "jin2003", "--models", "newton,rigid", "--periods", "10")
    comparison = impactlab.compare("jin2003", models=["newton", "rigid"], periods=10)
    for name, text in (("compare_impacts.csv", comparison.impacts_csv),
                       ("compare_contacts.csv", comparison.contacts_csv),
                       ("compare_section.csv", comparison.section_csv)):
        assert (out / name).read_text() == text
    # the summary's table and the numbers hold each run's wall time: all else is equal
    def table_without_wall_time(text):
        return [line.rsplit("|", 2)[0] if line.startswith("|") else line
                for line in text.splitlines()]

    assert table_without_wall_time((out / "summary.md").read_text()) == \
        table_without_wall_time(comparison.summary)
    numbers = read_json(out / "compare.json")["numbers"]
    for model in numbers["models"].values():
        model.pop("wall_time_s")
    for model in comparison.numbers["models"].values():
        model.pop("wall_time_s")
    assert numbers == comparison.numbers
    assert set(numbers["models"]) == {"newton", "rigid"}
    impacts = read_csv(out / "compare_impacts.csv")
    for model, run in comparison.runs.items():
        impact_times = run["events"]["t"][run["events"].kind_names() == "impact"]
        same_numbers([t for t in impacts["t_" + model] if t == t], impact_times)


def test_bench_equals_cli_work_precision(tmp_path):
    # the CLI's quick study; its cases linear_impact and jin2003_periodic are the
    # built-in scenes as they are (the first against the closed form, the second
    # against the quad-precision Taylor reference); work_precision.csv prints
    # 6 significant digits, the counts in full
    out = tmp_path / "bench"
    subprocess.run([os.environ["IMPACTLAB_CLI"], "bench", "--quick", "--no-scipy", "--no-plots",
                    "--quiet", "--out", str(out)], check=True)
    columns = read_csv(out / "work_precision.csv")
    all_rows = [dict(zip(columns, values)) for values in zip(*columns.values())]
    for case, scene_name, reference in (("linear_impact", "linear_impact", "closed_form"),
                                        ("jin2003_periodic", "jin2003", "taylor_quad+rk8pd")):
        rows = [row for row in all_rows if row["case"] == case and row["method"] != "exact"]
        methods = sorted({row["method"] for row in rows})
        result = impactlab.bench(scene_name, methods=methods, rtols=(1e-6, 1e-8, 1e-10),
                                 periods=50, reference_periods=20, max_reference_impacts=20)
        assert result.reference_method == reference
        ours = {(m, r): i for i, (m, r) in enumerate(zip(result.method, result.rtol))}
        assert len(ours) == len(rows) > 0
        for row in rows:
            i = ours[(row["method"], row["rtol"])]
            assert row["impacts"] == result.impacts[i]
            assert row["compared_impacts"] == result.impacts_compared[i]
            for column, ours_column in (("rhs_per_impact", result.rhs_per_impact),
                                        ("steps_per_impact", result.steps_per_impact),
                                        ("max_time_error", result.impact_time_error),
                                        ("max_velocity_error", result.impact_velocity_error)):
                assert row[column] == float(format(ours_column[i], ".6g")), (case, row, column)


def test_continue_equals_cli_branch_and_points(cli):
    out = cli("continue", "linear_impact", "--set", "sigma=0.2", "--param", "omega=2:2.5",
              "--switch")
    result = impactlab.continue_("linear_impact", sigma=0.2, param="omega=2:2.5", switch=True)
    branch = read_csv(out / "branch.csv")
    rows = 0
    for number, one in enumerate(result.branches):
        mine = [i for i, b in enumerate(branch["branch"]) if b == number]
        rows += len(mine)
        pick = lambda column: [branch[column][i] for i in mine]  # noqa: E731
        for column in ("omega", "q", "qdot", "impacts", "contact_phases", "stable",
                       "min_impact_speed", "min_flight_gap", "newton_iterations"):
            same_numbers(pick(column), one[column])
        same_numbers(pick("period"), [one["period"]] * len(mine))
        for k in (1, 2):
            same_numbers(pick("multiplier{}_re".format(k)), one["multiplier{}".format(k)].real)
            same_numbers(pick("multiplier{}_im".format(k)), one["multiplier{}".format(k)].imag)
    assert rows == len(branch["omega"]) > 10
    points = read_csv(out / "points.csv")
    assert points["type"] == result.points["type"] and "period_doubling" in points["type"]
    for column in ("omega", "q", "qdot", "period", "branch", "error_estimate", "located",
                   "graze_time", "graze_witness"):
        same_numbers(points[column], result.points[column])


def test_two_parameter_curves_equal_cli(cli):
    # the ball's period-doubling curve in (A, r) and, with switch, the doubled
    # branch's: curve.csv's rows, curve by curve, bit for bit
    arguments = dict(param="A=0.0112:0.025", start=[0.044286522498880876, -0.6269934342801218],
                     param2="r=0.8:0.75", curve="period_doubling", switch=True)
    out = cli("continue", "bouncing_ball", "--param", arguments["param"], "--start",
              "0.044286522498880876,-0.6269934342801218", "--param2", arguments["param2"],
              "--curve", "period_doubling", "--switch")
    result = impactlab.continue_("bouncing_ball", **arguments)
    assert result.curve_note == ""
    table = read_csv(out / "curve.csv")
    assert len(result.curves) >= 2 and [c["period"] for c in result.curves][:2] == [1, 2]
    rows = 0
    for one in result.curves:
        assert one["type"] == "period_doubling"
        mine = [i for i, b in enumerate(table["branch"]) if b == one["branch"]]
        rows += len(mine)
        pick = lambda column: [table[column][i] for i in mine]  # noqa: E731
        for column in ("A", "r", "q", "qdot", "graze_time", "impacts", "newton_iterations"):
            same_numbers(pick(column), one[column])
        same_numbers(pick("period"), [one["period"]] * len(mine))
        for k in (1, 2):
            same_numbers(pick("multiplier{}_re".format(k)), one["multiplier{}".format(k)].real)
            same_numbers(pick("multiplier{}_im".format(k)), one["multiplier{}".format(k)].imag)
    assert rows == len(table["A"]) > 10


def test_contact_end_curve_equals_cli(cli):
    # the plastic stop's contact end, located on the branch, and its curve in
    # (omega, sigma) from its own defining condition: curve.csv bit for bit
    out = cli("continue", "linear_impact", "--set", "r=0", "--param", "omega=1.5:1.8",
              "--param2", "sigma=0.2:0.3", "--curve", "contact_end")
    result = impactlab.continue_("linear_impact", r=0, param="omega=1.5:1.8",
                                 param2="sigma=0.2:0.3", curve="contact_end")
    points = read_csv(out / "points.csv")
    assert points["type"] == result.points["type"] and "contact_end" in points["type"]
    assert result.curve_note == ""
    table = read_csv(out / "curve.csv")
    (curve,) = result.curves
    assert curve["type"] == "contact_end" and len(table["omega"]) > 5
    for column in ("omega", "sigma", "q", "qdot", "impacts", "newton_iterations"):
        same_numbers(table[column], curve[column])
    for k in (1, 2):
        same_numbers(table["multiplier{}_re".format(k)], curve["multiplier{}".format(k)].real)
        same_numbers(table["multiplier{}_im".format(k)], curve["multiplier{}".format(k)].imag)


def test_continue_on_the_impact_section_equals_cli(cli):
    out = cli("continue", "linear_impact", "--set", "sigma=0.2", "--param", "omega=2:2.4",
              "--section", "impact:+1")
    result = impactlab.continue_("linear_impact", sigma=0.2, param="omega=2:2.4",
                                 section="impact:+1")
    branch = read_csv(out / "branch.csv")
    (one,) = result.branches
    for column in ("omega", "q", "qdot", "impacts", "stable", "newton_iterations"):
        same_numbers(branch[column], one[column])
    assert len(branch["omega"]) > 10 and one["stop_reason"] == "end_of_range"
    points = read_csv(out / "points.csv")
    assert points["type"] == result.points["type"] and "period_doubling" in points["type"]
    for column in ("omega", "q", "qdot", "error_estimate"):
        same_numbers(points[column], result.points[column])


def test_continue_on_the_impact_section_with_a_curve_equals_cli(cli):
    # the branch ends where the section's own impact grazes (located on the
    # stroboscopic map), and that grazing's curve in (omega, sigma)
    out = cli("continue", "linear_impact", "--param", "omega=2:2.5", "--section", "impact:+1",
              "--param2", "sigma=0.2:0.3", "--curve", "grazing")
    result = impactlab.continue_("linear_impact", param="omega=2:2.5", section="impact:+1",
                                 param2="sigma=0.2:0.3", curve="grazing")
    (one,) = result.branches
    assert one["stop_reason"] == "signature_change"
    points = read_csv(out / "points.csv")
    assert points["type"] == result.points["type"] and "grazing" in points["type"]
    for column in ("omega", "q", "qdot", "error_estimate", "graze_time", "graze_witness"):
        same_numbers(points[column], result.points[column])
    assert result.curve_note == ""
    table = read_csv(out / "curve.csv")
    (curve,) = result.curves
    assert curve["type"] == "grazing" and len(table["omega"]) > 10
    for column in ("omega", "sigma", "q", "qdot", "graze_time", "impacts", "newton_iterations"):
        same_numbers(table[column], curve[column])
    for k in (1, 2):
        same_numbers(table["multiplier{}_re".format(k)], curve["multiplier{}".format(k)].real)
        same_numbers(table["multiplier{}_im".format(k)], curve["multiplier{}".format(k)].imag)


def test_codimension_two_points_equal_cli(cli):
    # the grazing curve in (omega, sigma) of the one-impact orbit at sigma = 0
    # meets the period doubling of the orbit it grazes: curve_points.csv's row
    # and Python's curve_points, bit for bit
    # with switch, the period-doubling curve through it too: curve.csv's rows
    # of that curve (start grazing_period_doubling) and Python's curve
    out = cli("continue", "linear_impact", "--set", "sigma=0", "--set", "initial.x=-0.5",
              "--param", "omega=1.5:0.8", "--param2", "sigma=0:-0.04", "--curve", "grazing",
              "--switch")
    result = impactlab.continue_("linear_impact", sigma=0, initial__x=-0.5,
                                 param="omega=1.5:0.8", param2="sigma=0:-0.04", curve="grazing",
                                 switch=True)
    curves = read_csv(out / "curve.csv")
    (through,) = [one for one in result.curves if one["start"] == "grazing_period_doubling"]
    assert through["type"] == "period_doubling"
    rows = [i for i, start in enumerate(curves["start"]) if start == "grazing_period_doubling"]
    assert len(rows) == len(through["omega"]) > 5
    assert {curves["type"][i] for i in rows} == {"period_doubling"}
    for column in ("omega", "sigma", "q", "qdot", "newton_iterations"):
        same_numbers([curves[column][i] for i in rows], through[column])
    table = read_csv(out / "curve_points.csv")
    assert table["type"] == list(result.curve_points["type"]) == ["grazing_period_doubling"]
    for column in ("omega", "sigma", "q", "qdot", "error_estimate", "located", "graze_time",
                   "branch", "period"):
        same_numbers(table[column], result.curve_points[column])
    for k in (1, 2):
        same_numbers(table["multiplier{}_re".format(k)],
                     result.curve_points["multiplier{}".format(k)].real)
