"""Keys that the scene's model does not read (api/model_keys.hpp) from Python:
a sweep, basin map or continuation over one raises ValueError naming the
keyword and the key, with the CLI's reason; setting one gives one
UnreadKeyWarning and the run goes on."""
import os
import subprocess
import warnings

import pytest

import impactlab

NEWTON_E_T = "model = newton does not read e_t (read by model = paper|rigid)"


@pytest.mark.parametrize("call, message", [
    (lambda: impactlab.sweep("jin2003", param="e_t=-0.5:0:3"), "param = e_t: " + NEWTON_E_T),
    (lambda: impactlab.sweep("jin2003", param=["omega=6:7:2", "radius=0:0.01:2"]),
     "param = radius: model = newton does not read radius (read by model = rigid)"),
    (lambda: impactlab.basins("jin2003", x="initial.theta=-0.05:0.05:3", y="e_t=-0.5:0:3"),
     "y = e_t: " + NEWTON_E_T),
    (lambda: impactlab.continue_("jin2003", param="e_t=-0.5:0"), "param = e_t: " + NEWTON_E_T),
    (lambda: impactlab.continue_("jin2003", param="omega=6:7", param2="e_t=-0.5:0"),
     "param2 = e_t: " + NEWTON_E_T),
])
def test_a_key_the_model_does_not_read_is_refused_naming_the_keyword(call, message):
    with pytest.raises(ValueError) as raised:
        call()
    assert str(raised.value) == message


def test_the_refusal_is_the_cli_line_with_the_keyword_for_the_flag(tmp_path):
    completed = subprocess.run([os.environ["IMPACTLAB_CLI"], "sweep", "jin2003", "--param",
                                "e_t=-0.5:0:3", "--quiet", "--out", str(tmp_path / "x")],
                               capture_output=True, text=True, check=False)
    assert completed.returncode == 2
    assert completed.stderr == "impactlab: --param = e_t: " + NEWTON_E_T + "\n"


def test_model_p_reads_e_t_and_every_model_reads_mu():
    """The refusal is the model's: these plan and run."""
    for call in (lambda: impactlab.sweep("jin2003", param="e_t=-0.5:-0.4:2", model="paper",
                                         transient=1, points=2),
                 lambda: impactlab.sweep("jin2003", param="mu=0.5:0.6:2", transient=1,
                                         points=2)):
        with warnings.catch_warnings():
            warnings.simplefilter("error", impactlab.UnreadKeyWarning)
            result = call()
        assert len(result.summary["period"]) == 2


def _unread_key_warnings(call):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = call()
    return result, [w for w in caught if issubclass(w.category, impactlab.UnreadKeyWarning)]


def test_setting_a_key_the_model_does_not_read_warns_once_and_runs_on():
    result, caught = _unread_key_warnings(
        lambda: impactlab.simulate("jin2003", periods=1, e_t=-0.2))
    assert [str(w.message) for w in caught] == [
        "e_t = -0.2: " + NEWTON_E_T + "; the value changes nothing"]
    assert result.termination == "completed"
    _, caught = _unread_key_warnings(lambda: impactlab.scene("jin2003", radius=0.01, spin="free"))
    assert sorted(str(w.message).split(" = ")[0] for w in caught) == ["radius", "spin"]


def test_the_warning_is_the_cli_warning_line(tmp_path):
    completed = subprocess.run([os.environ["IMPACTLAB_CLI"], "simulate", "jin2003", "--set",
                                "e_t=-0.2", "--periods", "1", "--quiet", "--out",
                                str(tmp_path / "x")],
                               capture_output=True, text=True, check=False)
    assert completed.returncode == 0, completed.stderr
    _, caught = _unread_key_warnings(lambda: impactlab.scene("jin2003", e_t=-0.2))
    assert len(caught) == 1
    assert completed.stderr == "impactlab: warning: {}\n".format(caught[0].message)


def test_keys_the_model_reads_do_not_warn():
    for keys in ({"model": "paper", "e_t": -0.2}, {"mu": 0.3},
                 {"model": "rigid", "radius": 0.01, "spin": "free"}):
        _, caught = _unread_key_warnings(lambda: impactlab.scene("jin2003", **keys))
        assert caught == [], keys


def test_compare_runs_models_of_its_own_list_without_the_warning():
    _, caught = _unread_key_warnings(
        lambda: impactlab.compare("jin2003", models=["newton", "paper"], periods=1, e_t=-0.2))
    assert caught == []


def test_scene_keys_say_which_models_read_each_key():
    """Scene.keys(), Python's `impactlab scenes SCENE`."""
    read_by = {row["key"]: row["read_by"] for row in impactlab.scene("jin2003").keys()}
    assert read_by["e_t"] == ["paper", "rigid"]
    assert read_by["radius"] == read_by["spin"] == ["rigid"]
    assert read_by["mu"] == read_by["model"] == ["newton", "paper", "rigid"]
    assert all(row["read_by"] == [] for row in impactlab.scene("linear_impact").keys())
