"""impactlab.explore: the explorer's server started for a notebook, its page
shown inline (an IFrame of the address with the token), stopped on request."""
import http.client
import json
import urllib.parse

import pytest

import impactlab


def get(url, path):
    address = urllib.parse.urlsplit(url)
    token = urllib.parse.parse_qs(address.query)["token"][0]
    connection = http.client.HTTPConnection(address.hostname, address.port, timeout=30)
    connection.request("GET", path, headers={"Authorization": "token " + token})
    response = connection.getresponse()
    return response.status, response.read().decode()


def test_explore_serves_the_scene_inline_and_stops():
    with impactlab.explore("jin2003") as explorer:
        assert explorer.url.startswith("http://127.0.0.1:")
        assert '<iframe src="{}"'.format(explorer.url) in explorer._repr_html_()
        status, body = get(explorer.url, "/api/scene")
        assert status == 200
        assert json.loads(body)["scene_source"] == "jin2003"
    assert not explorer.running


def test_explore_takes_a_scene_object_with_its_keys():
    loaded = impactlab.scene("jin2003", V0=2.25)
    explorer = impactlab.explore(loaded)
    try:
        status, body = get(explorer.url, "/api/scene")
        values = {key["key"]: key["value"] for key in json.loads(body)["keys"]}
        assert values["V0"] == 2.25
    finally:
        explorer.stop()
    assert not explorer.running


def test_explore_refuses_a_bad_port_and_scene():
    with pytest.raises(ValueError, match="port"):
        impactlab.explore("jin2003", port=70000)
    with pytest.raises(ValueError, match="no_such_scene"):
        impactlab.explore("no_such_scene")


def post(url, path, body):
    address = urllib.parse.urlsplit(url)
    token = urllib.parse.parse_qs(address.query)["token"][0]
    connection = http.client.HTTPConnection(address.hostname, address.port, timeout=60)
    connection.request("POST", path, body=json.dumps(body),
                       headers={"Authorization": "token " + token,
                                "Content-Type": "application/json"})
    response = connection.getresponse()
    return response.status, json.loads(response.read().decode())


def finished(url, job_id):
    while True:
        status, body = get(url, "/api/jobs/{}?wait=1000".format(job_id))
        state = json.loads(body)
        if state["state"] != "running":
            return state


def test_the_exported_python_call_and_scene_file_give_the_page_s_numbers(tmp_path):
    values = {"V0": 3.25, "initial.theta": 0.01, "model": "paper"}
    options = {"periods": 6, "samples_per_period": 40}
    with impactlab.explore("jin2003") as explorer:
        status, started = post(explorer.url, "/api/jobs",
                               {"kind": "trajectory", "values": values, "options": options})
        assert status == 202
        shown = finished(explorer.url, started["id"])["result"]
        status, exported = post(explorer.url, "/api/export",
                                {"kind": "trajectory", "values": values, "options": options})
        assert status == 200
    call = exported["python"][0]
    assert call.startswith("impactlab.simulate(\"jin2003\"") and "**{\"initial.theta\": 0.01}" in call
    run = eval(call, {"impactlab": impactlab})
    assert list(run.trajectory.q) == shown["q"]
    assert list(run.trajectory.t) == shown["t"]
    # the scene file gives the same scene, and from it the same run
    path = tmp_path / "scene.toml"
    path.write_text(exported["scene_toml"])
    from_file = impactlab.simulate(str(path), periods=6, sample=shown["sample_step"])
    assert list(from_file.trajectory.q) == shown["q"]
