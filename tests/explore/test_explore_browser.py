"""The explorer's page in headless Chromium (python3-selenium, chromium-driver):
a slider moved redraws the time series with what `impactlab simulate` gives
for that value; a box dragged on the orbit diagram recomputes it over the
box's range; a clicked point shows the orbit `impactlab periodic` finds.
Screenshots go to $IMPACTLAB_TEST_OUTPUT (CTest sets it) or a temporary
folder; the slider's end-to-end times to explore_timings.json there."""
import json
import math
import os
import shutil
import subprocess
import time

import pytest

from conftest import Explorer, cli_binary

try:
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By
    from selenium.webdriver.common.keys import Keys
except ImportError:
    webdriver = None

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
DRIVER = shutil.which("chromedriver")
if webdriver is None or CHROMIUM is None or DRIVER is None:
    pytest.skip("headless Chromium is missing (python3-selenium, chromium, chromium-driver: "
                "scripts/deps.sh installs them); the browser test does not run",
                allow_module_level=True)


@pytest.fixture(scope="module")
def output_folder(tmp_path_factory):
    folder = os.environ.get("IMPACTLAB_TEST_OUTPUT")
    if folder:
        os.makedirs(folder, exist_ok=True)
        return folder
    return str(tmp_path_factory.mktemp("explore_browser"))


@pytest.fixture(scope="module")
def page():
    server = Explorer()
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for argument in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                     "--window-size=1400,1500", "--force-device-scale-factor=1"):
        options.add_argument(argument)
    driver = webdriver.Chrome(service=Service(DRIVER), options=options)
    driver.set_script_timeout(120)
    driver.get(server.url)
    yield driver, server
    driver.quit()
    server.stop()


def wait_for(driver, script, timeout=120):
    """The value of `script` (JavaScript returning a value) once it is truthy."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        value = driver.execute_script(script)
        if value:
            return value
        time.sleep(0.05)
    raise AssertionError("timed out waiting for: " + script)


def run_cli(*arguments, out):
    completed = subprocess.run([cli_binary(), *arguments, "--quiet", "--out", str(out)],
                               capture_output=True, text=True)
    assert completed.returncode in (0, 3), completed.stderr


def changed_keys(driver, sent_values):
    """`--set KEY=VALUE` for each key the page sent away from the scene's value."""
    initial = driver.execute_script(
        "return Object.fromEntries(window.explorer.scene.keys.map(k => [k.key, k.value]))")
    words = []
    for key, value in sent_values.items():
        if value != initial[key]:
            words += ["--set", "{}={}".format(key, repr(value) if isinstance(value, float) else value)]
    return words


def read_column(path, name):
    with open(path) as handle:
        header = handle.readline().strip().split(",")
        index = header.index(name)
        return [float(line.split(",")[index]) for line in handle]


def test_a_moved_slider_draws_what_simulate_gives(page, output_folder, tmp_path):
    driver, _ = page
    wait_for(driver, "return window.explorer.data.trajectory && window.explorer.data.section")
    slider = driver.find_element(By.CSS_SELECTOR, '.key[data-key="e_n"] input[type=range]')
    before = driver.execute_script("return window.explorer.values.e_n")
    for _ in range(25):
        slider.send_keys(Keys.ARROW_RIGHT)
    value = driver.execute_script("return window.explorer.values.e_n")
    assert value != before
    # the drawn series are the ones computed for the slider's last value
    wait_for(driver, "const d = window.explorer.data; return d.trajectory.sent.values.e_n === {0!r}"
                     " && d.section.sent.values.e_n === {0!r}".format(value))
    # the uPlot's own data (its first series, [x, y]): what it draws
    plotted = driver.execute_script(
        "const d = window.explorer.plots.trajectory.data[1]; return [d[0], d[1]];")
    omega = driver.execute_script("return window.explorer.values.omega")
    sample = 2.0 * math.pi / omega / 64
    run_cli("simulate", "jin2003", "--set", "e_n={!r}".format(value), "--periods", "20",
            "--sample", repr(sample), out=tmp_path)
    assert read_column(tmp_path / "trajectory.csv", "t") == plotted[0]
    assert read_column(tmp_path / "trajectory.csv", "q") == plotted[1]
    driver.save_screenshot(os.path.join(output_folder, "explore_slider.png"))
    # the times of the requests a slider move makes, one move at a time:
    # the time series and the section redrawn, end to end and on the server
    moves = []
    for _ in range(10):
        count = driver.execute_script("return window.explorer.timings.length")
        slider.send_keys(Keys.ARROW_LEFT)
        timings = wait_for(driver, "const t = window.explorer.timings.slice({}); "
                                   "return t.length >= 2 && t".format(count))
        moves.append({timing["kind"]: timing for timing in timings})
    def median(kind, field):
        values = sorted(move[kind][field] for move in moves)
        return values[len(values) // 2]
    # drawn_ms: end to end with the plots drawn
    summary = {kind: {field: median(kind, field) for field in ("server_ms", "end_to_end_ms", "drawn_ms")}
               for kind in ("trajectory", "section")}
    with open(os.path.join(output_folder, "explore_timings.json"), "w") as handle:
        json.dump({"median_of_10_slider_moves": summary, "moves": moves}, handle, indent=1)
    assert all(set(move) == {"trajectory", "section"} for move in moves)


def test_a_dragged_box_zooms_the_orbit_diagram(page, output_folder):
    driver, _ = page
    driver.execute_script("""
        document.getElementById('diagram-key').value = 'V0';
        document.getElementById('diagram-from').value = 1.0;
        document.getElementById('diagram-to').value = 3.0;
        document.getElementById('diagram-columns').value = 60;
        document.getElementById('diagram-points').value = 16;
        document.getElementById('diagram-transient').value = 60;""")
    driver.find_element(By.ID, "diagram-run").click()
    wait_for(driver, "return window.explorer.data.diagram")
    columns = driver.execute_script("return window.explorer.data.diagramColumns.length")
    assert columns == 60
    # the plotting area (uPlot's .u-over, CSS pixels)
    area = driver.find_element(By.CSS_SELECTOR, "#plot-diagram .u-over")
    width, height = area.size["width"], area.size["height"]
    # a box from x = 30 % to 60 % of the plotting area; the range it stands for, read from the plot
    start, end = (int(0.3 * width), int(0.25 * height)), (int(0.6 * width), int(0.75 * height))
    expected = driver.execute_script(
        "const u = window.explorer.plots.diagram;"
        "return [arguments[0], arguments[1]].map(([x, y]) => [u.posToVal(x, 'x'), u.posToVal(y, 'y')])",
        list(start), list(end))
    ActionChains(driver).move_to_element_with_offset(area, start[0] - width // 2, start[1] - height // 2) \
        .click_and_hold().move_by_offset(end[0] - start[0], end[1] - start[1]).release().perform()
    request = wait_for(driver, "return window.explorer.diagram.from !== 1.0 && window.explorer.diagram")
    assert math.isclose(request["from"], min(expected[0][0], expected[1][0]), rel_tol=0, abs_tol=2e-2)
    assert math.isclose(request["to"], max(expected[0][0], expected[1][0]), rel_tol=0, abs_tol=2e-2)
    assert 1.4 < request["from"] < request["to"] < 2.4
    # the box's range of the coordinate kept
    span = abs(expected[0][1] - expected[1][1])
    assert math.isclose(request["yRange"][0], min(expected[0][1], expected[1][1]), abs_tol=0.02 * span)
    assert math.isclose(request["yRange"][1], max(expected[0][1], expected[1][1]), abs_tol=0.02 * span)
    wait_for(driver, "return window.explorer.data.diagram")
    values = driver.execute_script("return window.explorer.data.diagramColumns.map(c => c.value)")
    # recomputed at full resolution over the new range
    assert len(values) == 60
    assert min(values) == request["from"] and math.isclose(max(values), request["to"], rel_tol=1e-12)
    driver.save_screenshot(os.path.join(output_folder, "explore_zoomed.png"))


def test_a_clicked_point_shows_the_orbit_periodic_finds(page, output_folder, tmp_path):
    driver, _ = page
    wait_for(driver, "return window.explorer.data.diagram")
    # the zoomed view keeps the box's range of the coordinate: fitted to the new points
    driver.find_element(By.ID, "diagram-fit").click()
    area = driver.find_element(By.CSS_SELECTOR, "#plot-diagram .u-over")
    width, height = area.size["width"], area.size["height"]
    # the first point of the first column inside the view (CSS pixels in the plotting area)
    pixel = driver.execute_script("""
        const u = window.explorer.plots.diagram, w = arguments[0], h = arguments[1];
        for (const c of window.explorer.data.diagramColumns.slice().sort((a, b) => a.index - b.index))
          for (const q of c.q) {
            const x = u.valToPos(c.value, 'x'), y = u.valToPos(q, 'y');
            if (x > 5 && x < w - 5 && y > 5 && y < h - 5) return [Math.round(x), Math.round(y)];
          }
        return null;""", width, height)
    assert pixel is not None
    ActionChains(driver).move_to_element_with_offset(area, pixel[0] - width // 2, pixel[1] - height // 2) \
        .click().perform()
    orbit = wait_for(driver, "return window.explorer.data.orbit")
    point = orbit["sent"]["options"]
    assert "Floquet multipliers" in driver.find_element(By.ID, "orbit-text").text
    run_cli("periodic", "jin2003", *changed_keys(driver, orbit["sent"]["values"]),
            "--set", "{}={!r}".format(point["key"], point["value"]),
            "--set", "t0={!r}".format(point["t"]), "--set", "initial.theta={!r}".format(point["q"]),
            "--set", "initial.theta_dot={!r}".format(point["qdot"]),
            "--transient", repr(float(point["transient"])), out=tmp_path)
    with open(tmp_path / "periodic.json") as handle:
        record = json.load(handle)
    assert record["state"] == orbit["periodic"]["state"]
    assert record["floquet_multipliers"] == orbit["periodic"]["floquet_multipliers"]
    driver.save_screenshot(os.path.join(output_folder, "explore.png"))
    # the export of the orbit names that command
    driver.find_element(By.CSS_SELECTOR, '[data-export="orbit"]').click()
    exported = wait_for(driver, "return window.explorer.data.export")
    assert exported["commands"][0].startswith("impactlab periodic jin2003 --set")
