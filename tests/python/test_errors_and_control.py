"""Bad input raises ValueError naming the key; a run can be cancelled from a
progress callback or by Ctrl-C; the GIL is released during a run; a run
stopped by a physical diagnostic returns its result and warns."""
import math
import os
import signal
import sys
import threading
import time

import pytest

import impactlab
from conftest import read_csv, same_numbers


@pytest.mark.parametrize("keys, named", [
    ({"omegaa": 7.0}, "omegaa"),                 # unknown key
    ({"e_n": 1.5}, "e_n"),                       # out of range
    ({"V0": math.nan}, "V0"),                    # NaN
    ({"V0": float("inf")}, "V0"),                # not finite
    ({"V0": [1.0, 2.0]}, "V0"),                  # wrong type
    ({"V0": True}, "V0"),                        # a bool is not a number
    ({"integrator__method": "euler9"}, "integrator.method"),  # bad choice
])
def test_bad_scene_key_raises_value_error_naming_key_and_value(keys, named):
    """The message begins with the key it names: "KEY = VALUE: reason"."""
    with pytest.raises(ValueError) as raised:
        impactlab.scene("jin2003", **keys)
    assert str(raised.value).startswith(named + " = "), str(raised.value)
    with pytest.raises(ValueError) as raised:
        impactlab.simulate("jin2003", periods=1, **keys)
    assert str(raised.value).startswith(named + " = "), str(raised.value)


def test_scene_message_equals_the_cli_set_message(cli, tmp_path):
    import subprocess
    completed = subprocess.run([os.environ["IMPACTLAB_CLI"], "simulate", "jin2003", "--set",
                                "e_n=1.5", "--out", str(tmp_path / "x"), "--quiet"],
                               capture_output=True, text=True, check=False)
    assert completed.returncode == 2
    with pytest.raises(ValueError) as raised:
        impactlab.scene("jin2003", e_n=1.5)
    assert str(raised.value).startswith("e_n = 1.5: "), str(raised.value)
    assert str(raised.value) in completed.stderr


def test_unknown_scene_raises_value_error():
    with pytest.raises(ValueError) as raised:
        impactlab.scene("no_such_scene")
    assert str(raised.value).startswith("scene = no_such_scene: "), str(raised.value)


@pytest.mark.parametrize("call, named", [
    (lambda: impactlab.simulate("jin2003", periods=-1), "periods"),
    (lambda: impactlab.simulate("jin2003", periods=math.nan), "periods"),
    (lambda: impactlab.simulate("jin2003", periods="10"), "periods"),
    (lambda: impactlab.simulate("jin2003", sample=0), "sample"),
    (lambda: impactlab.poincare("jin2003", section="sideways"), "section"),
    (lambda: impactlab.poincare("jin2003", points=0), "points"),
    (lambda: impactlab.sweep("jin2003", param="omega=7:6"), "param"),
    (lambda: impactlab.sweep("jin2003", param="nokey=1:2:3"), "param"),
    (lambda: impactlab.sweep("jin2003", param="omega=6:7:3", direction="sideways"), "direction"),
    (lambda: impactlab.sweep("jin2003", param="omega=6:7:3", threads=0), "threads"),
    (lambda: impactlab.sweep("jin2003", param=["omega=6:7:3", "V0=1:2:2"],
                             classification_tol="sometimes"), "classification_tol"),
    (lambda: impactlab.periodic("jin2003", period="two"), "period"),
    (lambda: impactlab.compare("jin2003", models=["newton", "newton"]), "models"),
    (lambda: impactlab.simulate("jin2003", progress=42), "progress"),
    (lambda: impactlab.simulate("jin2003", period=5), "period"),  # an unknown keyword
    (lambda: impactlab.sweep("jin2003", param="omega=6:7:3", point=5), "point"),
    # a keyword of the wrong type or past the largest double is a ValueError
    # naming it (TypeError and OverflowError before), and the option table's
    # ranges hold as on the command line
    (lambda: impactlab.sweep("jin2003", param=123), "param"),
    (lambda: impactlab.sweep("jin2003", param=[]), "param"),
    (lambda: impactlab.sweep("jin2003", param=("omega=6:7:3", 5)), "param"),
    (lambda: impactlab.simulate("jin2003", periods=10**400), "periods"),
    (lambda: impactlab.simulate("jin2003", t_end=-10**400), "t_end"),
    (lambda: impactlab.poincare("jin2003", transient=10**400), "transient"),
    (lambda: impactlab.sweep("jin2003", param="omega=6:7:3", transient=-1), "transient"),
    (lambda: impactlab.basins("jin2003", x="initial.theta=-0.1:0.1:3",
                              y="initial.theta_dot=-1:1:3", transient=-1), "transient"),
    (lambda: impactlab.continue_("linear_impact", param="omega=2"), "param"),
    (lambda: impactlab.continue_("linear_impact", param="omega=2:nan"), "param"),
    (lambda: impactlab.continue_("linear_impact", param="nokey=2:3"), "param"),
    (lambda: impactlab.continue_("linear_impact", param="omega=2:3", section="impact"), "section"),
    (lambda: impactlab.continue_("linear_impact", param="omega=2:3", start=[0.1]), "start"),
    (lambda: impactlab.continue_("linear_impact", param="omega=2:3", param2="sigma=0.2"),
     "param2"),
    (lambda: impactlab.continue_("linear_impact", param="omega=2:3", param2="omega=3:4"),
     "param2"),
    (lambda: impactlab.continue_("linear_impact", param="omega=2:3", param2="r=0.8:1.5"), "r"),
    (lambda: impactlab.continue_("linear_impact", param="omega=2:3", curve="fold"), "curve"),
    (lambda: impactlab.continue_("linear_impact", param="omega=2:3", param2="r=0.8:0.6",
                                 curve="torus"), "curve"),
    # a curve type the branch has no located point of (no contact phase at r = 0.8)
    (lambda: impactlab.continue_("linear_impact", param="omega=2:2.5", param2="sigma=0.2:0.3",
                                 curve="contact_end"), "curve"),
])
def test_bad_option_raises_value_error_naming_it(call, named):
    """The message begins with the key it names: "KEY = VALUE: reason"."""
    with pytest.raises(ValueError) as raised:
        call()
    assert str(raised.value).startswith(named + " = "), str(raised.value)


@pytest.mark.parametrize("call, line", [
    (lambda: impactlab.poincare("jin2003", transient=1e9),
     "transient = 1000000000: needs at least 1.6e+10 steps, over limits.max_steps = 100000000 "
     "(raise it with set limits.max_steps=N)"),
    (lambda: impactlab.simulate("jin2003", t_end=1e300),
     "t_end = 1e+300: needs at least 1.78e+301 steps, over limits.max_steps = 100000000 "
     "(raise it with set limits.max_steps=N)"),
    (lambda: impactlab.sweep("jin2003", param="model=0:1:5"),
     "param = model: not a numeric key of oscillator pendulum_walls"),
    (lambda: impactlab.sweep("jin2003", param=["omega=5:9:10000000", "V0=1:2:10000000"]),
     "param = omega=5:9:10000000 V0=1:2:10000000: the grid would write 1e+14 rows, over "
     "limits.max_rows = 10000000 (raise it with set limits.max_rows=N)"),
    (lambda: impactlab.sweep("jin2003", param="omega=5:9:1000000"),
     "points = 50: 1e+06 values x 50 points would write 5e+07 rows, over "
     "limits.max_rows = 10000000 (raise it with set limits.max_rows=N)"),
    (lambda: impactlab.basins("jin2003", x="initial.theta=-0.1:0.1:10000000",
                              y="initial.theta_dot=-1:1:10000000"),
     "x/y = initial.theta=-0.1:0.1:10000000 initial.theta_dot=-1:1:10000000: the grid would "
     "write 1e+14 rows, over limits.max_rows = 10000000 (raise it with set limits.max_rows=N)"),
])
def test_library_message_names_the_python_keyword(call, line):
    """The library names an option by its own name, the Python keyword."""
    with pytest.raises(ValueError) as raised:
        call()
    assert str(raised.value) == line


def test_progress_callback_is_called_with_growing_fractions():
    fractions = []
    impactlab.simulate("jin2003", periods=50, progress=fractions.append)
    assert len(fractions) >= 10
    assert fractions == sorted(fractions) and 0.0 < fractions[-1] <= 1.0


def test_progress_true_without_tqdm_draws_a_plain_line(monkeypatch, capsys):
    # tqdm made unimportable: progress=True still shows progress, on stderr
    monkeypatch.setitem(sys.modules, "tqdm", None)
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)
    impactlab.simulate("jin2003", periods=50, progress=True)
    err = capsys.readouterr().err
    shown = [int(part.split(": ")[1].rstrip("%\n")) for part in err.split("\r") if part]
    assert all(part.startswith("simulate: ") for part in err.split("\r") if part)
    assert len(shown) >= 10 and shown == sorted(shown) and shown[-1] >= 90
    assert err.endswith("\n")


def test_exception_in_progress_callback_cancels_the_run():
    calls = []

    def interrupt(fraction):
        calls.append(fraction)
        if len(calls) == 3:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        impactlab.simulate("jin2003", periods=100000, progress=interrupt)
    assert len(calls) == 3  # stopped at once, not after the run
    # the interpreter and the module are fine afterwards
    assert len(impactlab.simulate("jin2003", periods=5).events) > 0


def test_sweep_is_cancelled_by_its_progress_callback():
    def interrupt(fraction):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        impactlab.sweep("jin2003", param="omega=6:8:40", points=5, transient=5, threads=2,
                        progress=interrupt)
    # the threads have stopped and the module runs the next sweep as usual
    assert len(impactlab.sweep("jin2003", param="omega=6:8:4", points=5, transient=5,
                               threads=2).summary["period"]) == 4


def test_ctrl_c_interrupts_a_long_run():
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    started = time.monotonic()
    try:
        with pytest.raises(KeyboardInterrupt):
            # about 100 s of run, looked at each hundredth (about 1 s)
            impactlab.simulate("jin2003", periods=2_000_000)
    finally:
        timer.cancel()
    assert time.monotonic() - started < 30.0


def test_gil_is_released_during_a_run():
    ticks = []
    running = threading.Event()

    def count():
        while not running.is_set():
            pass
        while running.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    counter.start()
    seen = []

    def progress(fraction):
        running.set()
        seen.append(len(ticks))

    # with no callback the run takes the GIL only every 20 ms; with one, at
    # each hundredth: the other thread must advance between hundredths
    impactlab.simulate("jin2003", periods=20000, progress=progress)
    running.clear()
    counter.join()
    assert seen[-1] - seen[0] > 10, seen


def test_physical_diagnostic_returns_result_and_warns():
    with pytest.warns(impactlab.PhysicalDiagnosticWarning, match="stopped_by_model"):
        run = impactlab.simulate("jin2003", mu=15)
    assert run.termination == "stopped_by_model"
    assert run.meta["run"]["termination"] == "stopped_by_model"
    assert run.events.kind_names()[-1] == "painleve"


def test_unconverged_periodic_warns_why_as_the_cli_says():
    # chaotic at omega = 6.3: no period detected, period 1 tried, and one
    # Newton iteration cannot converge from the transient's end (the CLI's
    # Periodic.AnUnconvergedSearchSaysWhyAndPrintsNoMultipliers)
    with pytest.warns(impactlab.PhysicalDiagnosticWarning,
                      match="the period was not detected in 64 stroboscopic points") as caught:
        orbit = impactlab.periodic("jin2003", omega=6.3, max_iterations=1)
    assert not orbit.converged
    assert orbit.multipliers.size == 0
    assert orbit.monodromy.shape == (2, 2)
    assert "max_iterations reached" in orbit.meta["failure"]
    assert orbit.meta["failure"] in str(caught[0].message)


def test_dir_shows_the_api_and_the_version_is_the_programs():
    listed = dir(impactlab)
    for name in ("simulate", "poincare", "sweep", "basins", "periodic", "continue_", "Scene"):
        assert name in listed
    for module in ("np", "math", "warnings", "re", "sys", "numbers"):
        assert module not in listed
    run = impactlab.simulate("jin2003", periods=1)
    assert impactlab.__version__ == run.meta["impactlab_version"]


def test_a_saved_scene_runs_as_the_scene_it_was_saved_from(tmp_path, cli):
    original = impactlab.scene("jin2003", V0=4.163, omega=6.71, initial__theta=0.01)
    text = original.to_toml()
    assert "V0 = 4.163  # [m/s]" in text
    path = tmp_path / "saved.toml"
    original.save(path)
    assert path.read_text() == text
    loaded = impactlab.scene(str(path))
    assert loaded.values() == original.values()
    # the program runs the file as Python runs the scene it came from
    out = cli("simulate", str(path), "--periods", "20")
    run = impactlab.simulate(original, periods=20)
    events = read_csv(out / "events.csv")
    assert len(events["t"]) == len(run.events) > 10
    same_numbers(events["t"], run.events["t"])
    same_numbers(events["qdot_after"], run.events["qdot_after"])
    with pytest.raises(OSError):
        original.save(tmp_path / "no_such_folder" / "saved.toml")
    assert not (tmp_path / "no_such_folder").exists()


def test_options_that_exclude_each_other_are_refused_as_the_cli_refuses_them():
    # the CLI: "--transient excludes --max-transient"
    with pytest.raises(ValueError, match="max_transient = 300.0: excludes transient"):
        impactlab.poincare("jin2003", transient=100, max_transient=300)
    with pytest.raises(ValueError, match="excludes transient"):
        impactlab.sweep("jin2003", param="omega=6:7:3", transient=10, transient_impacts=5)
    # one of them, or the other at its default, runs
    assert impactlab.poincare("jin2003", transient=5, points=2).transient_end == "fixed"


def test_scenes_lists_the_builtin_scenes():
    listed = impactlab.scenes()
    assert "jin2003" in [s["name"] for s in listed]
    assert all(s["oscillator"] for s in listed)


def test_bench_error_falls_with_tolerance_against_the_closed_form():
    result = impactlab.bench("linear_impact", methods=["rk8pd"], rtols=[1e-5, 1e-11], periods=20,
                             reference_periods=10, max_reference_impacts=10)
    assert result.reference_method == "closed_form"
    assert list(result.impacts_compared) == [result.reference_impacts] * 2
    assert result.impact_time_error[1] < result.impact_time_error[0]
    with pytest.raises(ValueError) as raised:
        impactlab.bench("jin2003", methods=["exact"])
    assert str(raised.value).startswith("methods = "), str(raised.value)
