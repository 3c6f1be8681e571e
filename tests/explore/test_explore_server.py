"""`impactlab explore` as a way into the machine: every request needs the
token, the server's own Host and no foreign Origin; bad scene values are
refused with the scene's own message; no path reaches a file outside the
page's; many requests at once are answered in bounded time and start a
bounded number of jobs. And the views' numbers are the CLI's."""
import concurrent.futures
import json
import shlex
import subprocess
import time

from conftest import cli_binary, cli_refusal


def test_it_listens_on_loopback_and_prints_a_token(explorer):
    assert explorer.url.startswith("http://127.0.0.1:")
    assert len(explorer.token) == 32
    status, page, headers = explorer.request("GET", "/?token=" + explorer.token, token=False)
    assert status == 200 and 'id="plot-diagram"' in page
    # the page names its own files with the token; no cookie is set
    assert "web/explore.js?token=" + explorer.token in page
    assert "Set-Cookie" not in headers
    assert "default-src 'self'" in headers["Content-Security-Policy"]


def test_a_port_in_use_is_refused_with_one_line(explorer):
    completed = subprocess.run([cli_binary(), "explore", "--port", str(explorer.port)],
                               capture_output=True, text=True, timeout=30)
    assert completed.returncode == 2
    assert completed.stderr.strip() == \
        "impactlab: --port = {}: cannot listen on 127.0.0.1 there".format(explorer.port)


def test_a_request_without_the_token_is_refused(explorer):
    for path in ("/", "/api/scene", "/web/explore.js"):
        status, body, _ = explorer.request("GET", path, token=False)
        assert status == 403, path
        assert body["error"]["key"] == "token"
    status, _, _ = explorer.request("POST", "/api/jobs", {"kind": "trajectory"}, token=False)
    assert status == 403


def test_a_wrong_token_is_refused(explorer):
    wrong = "0" * 32 if explorer.token != "0" * 32 else "1" * 32
    status, _, _ = explorer.request("GET", "/api/scene?token=" + wrong, token=False)
    assert status == 403
    status, _, _ = explorer.request("GET", "/api/scene", token=False,
                                    headers={"Authorization": "token " + wrong})
    assert status == 403
    status, _, _ = explorer.request("GET", "/api/scene?token=" + explorer.token[:-1], token=False)
    assert status == 403
    # the right one in the address is accepted
    status, _, _ = explorer.request("GET", "/api/scene?token=" + explorer.token, token=False)
    assert status == 200


def test_a_foreign_host_is_refused(explorer):
    # DNS rebinding: a foreign name resolved to 127.0.0.1 arrives with its own Host
    for host in ("evil.example:{}".format(explorer.port), "127.0.0.1:1", "127.0.0.1", ""):
        status, body, _ = explorer.request("GET", "/api/scene", headers={"Host": host})
        assert status == 403, host
        assert body["error"]["key"] == "Host"
    status, _, _ = explorer.request("GET", "/api/scene",
                                    headers={"Host": "localhost:{}".format(explorer.port)})
    assert status == 200


def test_a_foreign_origin_is_refused(explorer):
    for origin in ("http://evil.example", "http://127.0.0.1:1", "null",
                   "https://127.0.0.1:{}".format(explorer.port)):
        status, body, _ = explorer.request("POST", "/api/jobs",
                                           {"kind": "trajectory", "options": {"periods": 1}},
                                           headers={"Origin": origin})
        assert status == 403, origin
        assert body["error"]["key"] == "Origin"
    status, _, _ = explorer.request("GET", "/api/scene",
                                    headers={"Origin": "http://127.0.0.1:{}".format(explorer.port)})
    assert status == 200


def test_an_oversized_request_is_refused(explorer):
    padding = "x" * (100 * 1024)
    status, _, _ = explorer.request("POST", "/api/jobs",
                                    '{"kind": "trajectory", "pad": "' + padding + '"}')
    assert status == 413


def test_bad_scene_values_are_refused_with_the_scenes_own_message(explorer):
    cases = [({"no_such_key": 1}, ("--set", "no_such_key=1")),
             ({"V0": "nan"}, ("--set", "V0=nan")),
             ({"e_n": 1.5}, ("--set", "e_n=1.5")),
             ({"model": "quantum"}, ("--set", "model=quantum"))]
    for values, assignment in cases:
        status, body, _ = explorer.request("POST", "/api/jobs",
                                           {"kind": "trajectory", "values": values})
        assert status == 400, values
        assert body["error"]["message"] == cli_refusal("simulate", "jin2003", *assignment), values
        assert body["error"]["key"] == list(values)[0]
    # a clash of keys (b >= l) is found where the system is built: the job fails with it
    state = explorer.job("trajectory", {"b": 0.9})
    assert state["state"] == "failed" and state["error"]["key"] == "b"
    assert state["error"]["message"] == cli_refusal("simulate", "jin2003", "--set", "b=0.9")
    # JSON's own non-numbers are no values either
    status, body, _ = explorer.request("POST", "/api/jobs",
                                       '{"kind": "trajectory", "values": {"V0": NaN}}')
    assert status == 400 and body["error"]["key"] == "body"
    status, body, _ = explorer.request("POST", "/api/jobs",
                                       {"kind": "trajectory", "values": {"V0": [1, 2]}})
    assert status == 400 and body["error"]["key"] == "V0"


def test_the_work_one_request_may_start_is_bounded(explorer):
    for kind, options, key in (("trajectory", {"periods": 1e7}, "periods"),
                               ("trajectory", {"periods": 5000, "samples_per_period": 4096}, "periods"),
                               ("section", {"points": 10 ** 7}, "points"),
                               ("diagram", {"key": "V0", "from": 1, "to": 2, "columns": 10 ** 6}, "columns"),
                               ("diagram", {"key": "V0", "from": 1, "to": 2, "points": 10 ** 6}, "points"),
                               ("diagram", {"key": "model", "from": 1, "to": 2}, "key"),
                               ("diagram", {"key": "e_n", "from": 0, "to": 3}, None),
                               ("nothing", {}, "kind")):
        status, body, _ = explorer.request("POST", "/api/jobs", {"kind": kind, "options": options})
        assert status == 400, (kind, options, body)
        if key:
            assert body["error"]["key"] == key, body


def test_no_path_reaches_a_file_outside_the_page(explorer):
    for path in ("/../../etc/passwd", "/web/../../etc/passwd", "/web/..%2F..%2Fetc%2Fpasswd",
                 "/web/%2e%2e/%2e%2e/etc/passwd", "/%2e%2e/%2e%2e/etc/passwd",
                 "/web/%252e%252e%252fetc%252fpasswd", "/web//etc/passwd", "/etc/passwd",
                 "/web/explore.js/../../../etc/passwd", "/web/vendor/../../../etc/passwd",
                 "/web/vendor/uplot/../../explore.js", "/web/vendor/uplot/%2e%2e/LICENSE",
                 "/web/vendor/uplot/.hidden", "/web/vendor/uplot"):
        status, body, _ = explorer.request("GET", path)
        assert status in (400, 403, 404), path
        assert "root:" not in str(body), path
        assert "explorer" not in str(body), path
    status, body, _ = explorer.request("GET", "/web/explore.js")
    assert status == 200 and "explorer" in body


def test_the_plotting_library_is_served_from_the_programs_files(explorer):
    # uPlot (web/vendor/uplot/), as the page names it
    status, page, _ = explorer.request("GET", "/")
    assert "web/vendor/uplot/uPlot.iife.min.js?token=" + explorer.token in page
    status, body, headers = explorer.request("GET", "/web/vendor/uplot/uPlot.iife.min.js")
    assert status == 200 and "uPlot" in body
    assert headers["Content-Type"].startswith("text/javascript")
    status, body, headers = explorer.request("GET", "/web/vendor/uplot/uPlot.min.css")
    assert status == 200 and headers["Content-Type"].startswith("text/css")
    status, body, _ = explorer.request("GET", "/web/vendor/uplot/LICENSE")
    assert status == 200 and "MIT" in body


def test_many_requests_at_once_stay_bounded_and_the_server_responsive(explorer):
    def one(k):
        started = time.monotonic()
        if k % 2:
            status, _, _ = explorer.request("GET", "/api/scene", timeout=60)
        else:
            status, _, _ = explorer.request("POST", "/api/jobs",
                                            {"kind": "section", "values": {"V0": 1.5 + k * 1e-3},
                                             "options": {"points": 50, "transient": 50}},
                                            timeout=60)
        return status, time.monotonic() - started

    def resident_mib():
        with open("/proc/{}/status".format(explorer.process.pid)) as status_file:
            for line in status_file:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) / 1024.0
        raise AssertionError("no VmRSS for the server")

    resident = []
    for burst in range(2):
        started = time.monotonic()
        with concurrent.futures.ThreadPoolExecutor(max_workers=200) as pool:
            answers = list(pool.map(one, range(200)))
        elapsed = time.monotonic() - started
        statuses = {status for status, _ in answers}
        # every request answered: accepted, or refused as busy (at most 8 jobs at once)
        assert statuses <= {200, 202, 503}, statuses
        assert elapsed < 30, elapsed
        assert max(seconds for _, seconds in answers) < 30
        resident.append(resident_mib())
    # memory bounded: a second burst like the first does not grow the server
    # by more than a tenth of what it holds (jobs and their results are let go)
    assert resident[1] <= 1.1 * resident[0] + 16.0, resident
    # and right after it, a request is answered at once
    started = time.monotonic()
    status, _, _ = explorer.request("GET", "/api/scene")
    assert status == 200 and time.monotonic() - started < 2.0


def test_a_newer_job_of_a_kind_cancels_the_older(explorer):
    # a diagram of some seconds, superseded once its first columns are in
    options = {"key": "V0", "from": 1.0, "to": 2.0, "columns": 1000, "points": 100,
               "transient": 400}
    status, first, _ = explorer.request("POST", "/api/jobs", {"kind": "diagram", "options": options})
    assert status == 202
    while True:
        status, state, _ = explorer.request("GET", "/api/jobs/{}?wait=1000".format(first["id"]))
        if state["item_count"] > 0 or state["state"] != "running":
            break
    assert state["state"] == "running"
    second = explorer.job("diagram", options={**options, "columns": 3, "transient": 10})
    assert second["state"] == "done" and len(second["all_items"]) == 3
    deadline = time.monotonic() + 30
    while True:
        status, state, _ = explorer.request("GET", "/api/jobs/{}?wait=500".format(first["id"]))
        if state["state"] != "running" or time.monotonic() > deadline:
            break
    assert state["state"] == "cancelled"
    assert state["item_count"] < 1000


def read_csv_columns(path):
    import csv
    with open(path, newline="") as handle:
        rows = list(csv.reader(line for line in handle if not line.startswith("#")))
    return {name: [row[i] for row in rows[1:]] for i, name in enumerate(rows[0])}


def run_exported(command, out):
    words = shlex.split(command)
    assert words[0] == "impactlab"
    completed = subprocess.run([cli_binary(), *words[1:], "--quiet", "--out", str(out)],
                               capture_output=True, text=True)
    assert completed.returncode in (0, 3), completed.stderr


def test_the_exported_simulate_command_gives_the_numbers_the_page_showed(explorer, tmp_path):
    values = {"V0": 2.375, "e_n": 0.45}
    options = {"periods": 7, "samples_per_period": 50}
    state = explorer.job("trajectory", values, options)
    assert state["state"] == "done", state
    shown = state["result"]
    status, exported, _ = explorer.request("POST", "/api/export",
                                           {"kind": "trajectory", "values": values, "options": options})
    assert status == 200
    command = exported["commands"][0]
    assert "--set V0=2.375" in command and "--set e_n=0.45" in command
    assert "impactlab.simulate(\"jin2003\"" in exported["python"][0]
    assert "V0 = 2.375" in exported["scene_toml"]
    run_exported(command, tmp_path)
    trajectory = read_csv_columns(tmp_path / "trajectory.csv")
    assert len(trajectory["t"]) == len(shown["t"]) > 300
    assert [float(v) for v in trajectory["q"]] == shown["q"]
    assert [float(v) for v in trajectory["t"]] == shown["t"]
    assert [float(v) for v in trajectory["qdot"]] == shown["qdot"]


def test_the_exported_poincare_and_sweep_commands_give_the_page_s_numbers(explorer, tmp_path):
    values = {"V0": 3.1}
    section = explorer.job("section", values, {"transient": 40, "points": 30})["result"]
    _, exported, _ = explorer.request("POST", "/api/export", {"kind": "section", "values": values,
                                                              "options": {"transient": 40, "points": 30}})
    run_exported(exported["commands"][0], tmp_path / "section")
    rows = read_csv_columns(tmp_path / "section" / "poincare.csv")
    assert [float(v) for v in rows["q"]] == section["q"]
    assert [float(v) for v in rows["qdot"]] == section["qdot"]

    options = {"key": "V0", "from": 1.5, "to": 2.5, "columns": 6, "points": 5, "transient": 30}
    diagram = explorer.job("diagram", {}, options)
    assert diagram["state"] == "done"
    _, exported, _ = explorer.request("POST", "/api/export",
                                      {"kind": "diagram", "values": {}, "options": options})
    assert "--param V0=1.5:2.5:6" in exported["commands"][0]
    run_exported(exported["commands"][0], tmp_path / "sweep")
    rows = read_csv_columns(tmp_path / "sweep" / "bifurcation.csv")
    columns = sorted(diagram["all_items"], key=lambda column: column["index"])
    assert [float(v) for v in rows["V0"]] == [c["value"] for c in columns for _ in c["q"]]
    assert [float(v) for v in rows["q"]] == [q for c in columns for q in c["q"]]


def test_a_clicked_point_gives_the_periodic_orbit_and_exponent_the_cli_gives(explorer, tmp_path):
    diagram = explorer.job("diagram", {}, {"key": "V0", "from": 1.4, "to": 1.6, "columns": 3,
                                           "points": 4, "transient": 100})
    column = diagram["all_items"][0]
    point = {"key": "V0", "value": column["value"], "t": column["t"][0], "q": column["q"][0],
             "qdot": column["qdot"][0], "transient": 100}
    orbit = explorer.job("orbit", {}, point)
    assert orbit["state"] == "done", orbit
    shown = orbit["result"]
    assert shown["periodic"]["converged"]
    assert len(shown["orbit"]["q"]) > 100
    _, exported, _ = explorer.request("POST", "/api/export",
                                      {"kind": "orbit", "values": {}, "options": point})
    periodic, lyapunov = exported["commands"]
    run_exported(periodic, tmp_path / "periodic")
    with open(tmp_path / "periodic" / "periodic.json") as handle:
        record = json.load(handle)
    assert record["state"] == shown["periodic"]["state"]
    assert record["floquet_multipliers"] == shown["periodic"]["floquet_multipliers"]
    run_exported(lyapunov, tmp_path / "lyapunov")
    with open(tmp_path / "lyapunov" / "meta.json") as handle:
        meta = json.load(handle)
    assert meta["lyapunov"]["largest_exponent_per_time"] == shown["lyapunov"]
    assert shown["lyapunov"] is not None and shown["lyapunov"] < 0  # a stable orbit
