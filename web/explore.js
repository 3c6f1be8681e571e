// The explorer's page: controls from the scene's schema, the views drawn
// with uPlot (web/vendor/uplot/) from the server's JSON
// (api/explore_requests.hpp). It computes nothing itself: every number it
// draws comes from the server's jobs.
"use strict";

// ---- state a test can read: window.explorer -----------------------------------
const explorer = {
  scene: null,          // /api/scene: keys with unit, range, help, value
  values: {},           // the page's value of every key (what a request sends)
  data: {},             // the latest result of each view: trajectory, section, diagram, orbit
  diagram: null,        // the diagram's request: key, from, to, columns, points, transient
  zoomHistory: [],      // earlier diagram requests, for zoom out
  timings: [],          // {kind, end_to_end_ms, server_ms} of each finished job
  tickets: {},          // the number of the page's newest request of each kind
  client: Math.random().toString(36).slice(2),  // this page's name in the order of its requests
  plots: {},            // the uPlot of each view; plots.NAME.data[1]: its first series' [x, y]
  diagramYRange: null,  // the diagram's vertical range, a zoom's box; null: fitted
};
window.explorer = explorer;

// ---- the server --------------------------------------------------------------
// the token of the address the server printed, sent with every request
const token = new URLSearchParams(window.location.search).get("token") || "";

async function api(path, body) {
  const headers = {"Authorization": `token ${token}`};
  const response = await fetch(path, body === undefined ? {headers} : {
    method: "POST", headers: {...headers, "Content-Type": "application/json"}, body: JSON.stringify(body)});
  const text = await response.text();
  let json;
  try {
    json = JSON.parse(text);
  } catch (error) {  // a refusal of the HTTP layer itself (413: too large) has no JSON
    json = {error: {key: "", value: "", message: `${response.status} ${response.statusText} ${text}`.trim()}};
  }
  if (!response.ok) throw Object.assign(new Error(json.error ? json.error.message : response.statusText),
                                        {detail: json.error || {}, status: response.status});
  return json;
}

function setStatus(text, isError) {
  const status = document.getElementById("status");
  status.textContent = text;
  status.classList.toggle("error", Boolean(isError));
}

// Runs a job of `kind`: a newer one of the kind supersedes it (the server
// cancels it, the page stops polling it). `onItems` gets partial results.
async function runJob(kind, options, onItems) {
  const started = performance.now();
  const progress = document.getElementById(kind + "-progress");
  // the page's order of its requests of a kind: the server runs the newest
  // and refuses one that arrives after a newer one (409)
  const ticket = explorer.tickets[kind] = (explorer.tickets[kind] || 0) + 1;
  const current = () => explorer.tickets[kind] === ticket;
  const values = {...explorer.values};
  let id;
  for (;;) {
    try {
      id = (await api("/api/jobs", {kind, values, options, sequence: ticket, client: explorer.client})).id;
      break;
    } catch (error) {
      if (error.status === 409) return null;
      if (error.status === 503 && current()) {  // busy: the superseded jobs are ending
        await new Promise((resolve) => setTimeout(resolve, 50));
        continue;
      }
      if (current()) {
        showError(error);
        if (progress) progress.textContent = "refused";
      }
      return null;
    }
  }
  let seen = 0;
  for (;;) {
    if (!current()) return null;  // superseded
    let state;
    try {
      state = await api(`/api/jobs/${id}?from=${seen}&wait=1000`);
    } catch (error) {
      showError(error);
      return null;
    }
    if (!current()) return null;
    if (state.items.length > 0 && onItems) onItems(state.items);
    seen += state.items.length;
    if (progress) progress.textContent = state.state === "running" ? `${Math.round(100 * state.progress)} %` : "";
    if (state.state === "running") continue;
    if (state.state === "failed") {
      showError({message: state.error.message, detail: state.error});
      return null;
    }
    if (state.state !== "done") return null;
    const timing = {kind, end_to_end_ms: performance.now() - started, server_ms: state.server_ms};
    explorer.timings.push(timing);
    // what the result was computed for: a test runs the CLI on the same
    state.result.sent = {values, options};
    // the view sets drawn_ms, once the result is drawn
    state.result.timing = timing;
    setStatus(`${kind}: ${timing.server_ms.toFixed(0)} ms on the server, ${timing.end_to_end_ms.toFixed(0)} ms here`);
    return state.result;
  }
}

function showError(error) {
  setStatus(error.message, true);
  const key = error.detail && error.detail.key;
  document.querySelectorAll(".key .message").forEach((node) => { node.textContent = ""; });
  const node = key && document.querySelector(`.key[data-key="${CSS.escape(key)}"] .message`);
  if (node) node.textContent = error.message;
}

// ---- plots: uPlot (web/vendor/uplot/, MIT) -----------------------------------
// Every plot is a uPlot in its "mode 2": each series has its own x and y
// ([null, [x, y], [x, y], ...] as the plot's data): lines drawn with uPlot's
// linear path (or in order, below), points alone with its points path.

// a range around [low, high] with 4 % to spare; [0, 1] where there is nothing
function padded(low, high) {
  if (!Number.isFinite(low) || !Number.isFinite(high)) return [0, 1];
  if (low === high) return [low - 0.5 * Math.abs(low || 1), high + 0.5 * Math.abs(high || 1)];
  const pad = 0.04 * (high - low);
  return [low - pad, high + pad];
}

// a quantity and its unit as an axis shows it: "theta [rad]"
function axisLabel(quantity, unit) {
  return unit ? `${quantity} [${unit}]` : quantity;
}

// a line through the points in their order, broken at a null: for an x
// that goes back and forth (a phase portrait), which uPlot's linear path,
// thinning points by pixel column of x, would draw wrongly
function pathInOrder(u, seriesIndex) {
  const [x, y] = u.data[seriesIndex];
  const stroke = new Path2D();
  let broken = true;
  for (let i = 0; i < x.length; ++i) {
    if (x[i] == null || y[i] == null) { broken = true; continue; }
    const px = u.valToPos(x[i], "x", true), py = u.valToPos(y[i], "y", true);
    if (broken) stroke.moveTo(px, py); else stroke.lineTo(px, py);
    broken = false;
  }
  return {stroke, fill: null, clip: null, band: null, gaps: null, flags: 0};
}

const line = (label, stroke, width, {dash, paths} = {}) =>
  ({label, stroke, width, dash, points: {show: false}, paths: paths || uPlot.paths.linear(),
    facets: [{scale: "x", auto: true}, {scale: "y", auto: true}]});
// points alone, `size` px across: uPlot's points path as the series' path
// (its point markers are for mode 1); `ring`: an outline `ring` px wide, not filled
const dots = (label, color, size, ring = 0) =>
  ({label, stroke: color, fill: ring ? null : color, width: ring, paths: uPlot.paths.points(),
    points: {show: false, size, width: ring},
    facets: [{scale: "x", auto: true}, {scale: "y", auto: true}]});

// One plot in `element`: `series` (line or dots), ranges from `xRange` and
// `yRange` (functions of the data's extent), `cursor` options and `hooks`
// where it takes the mouse.
function makePlot(element, width, height, xLabel, yLabel, series, {xRange, yRange, cursor, hooks} = {}) {
  const opts = {
    mode: 2, width, height,
    legend: {show: false},
    cursor: cursor || {show: false},
    hooks: hooks || {},
    scales: {x: {time: false, range: (u, low, high) => (xRange ? xRange(low, high) : padded(low, high))},
             y: {range: (u, low, high) => (yRange ? yRange(low, high) : padded(low, high))}},
    axes: [{label: xLabel, size: 40, labelSize: 16, grid: {stroke: "#eee", width: 1}},
           {label: yLabel, size: 56, labelSize: 16, grid: {stroke: "#eee", width: 1}}],
    series: [{}, ...series],
  };
  return new uPlot(opts, [null, ...series.map(() => [[], []])], element);
}

// a plot's data, series by series: [x, y] each
function setPlot(plot, ...columns) {
  plot.setData([null, ...columns]);
}

// once uPlot has drawn what it was given: it draws in a microtask queued by
// setData, which runs before this one
const drawn = () => new Promise((resolve) => queueMicrotask(resolve));

// a job's time from its request to its result drawn (ms), beside
// end_to_end_ms: that and the time since `arrived` (the result in hand)
async function recordDrawn(timing, arrived) {
  await drawn();
  timing.drawn_ms = timing.end_to_end_ms + (performance.now() - arrived);
}

// ---- controls from the schema -------------------------------------------------
function numberText(value) { return String(value); }

function addControl(form, spec) {
  const row = document.createElement("div");
  row.className = "key";
  row.dataset.key = spec.key;
  row.title = spec.help + (spec.range ? ` ${spec.range}` : "");
  const label = document.createElement("label");
  label.textContent = spec.key + " ";
  const unit = document.createElement("span");
  unit.className = "unit";
  unit.textContent = (spec.unit ? `[${spec.unit}] ` : "") + (spec.range || "") + " " + spec.help;
  label.appendChild(unit);
  row.appendChild(label);
  let input;
  if (spec.text && spec.choices.length > 0) {
    input = document.createElement("select");
    for (const choice of spec.choices) input.add(new Option(choice, choice, false, choice === spec.value));
    input.addEventListener("change", () => changeKey(spec.key, input.value));
  } else if (spec.slider) {
    // a slider over the key's range, 1000 steps (an open bound left out),
    // and beside it an entry for an exact value
    const steps = 1000, step = (spec.upper - spec.lower) / steps;
    const slider = document.createElement("input");
    slider.type = "range";
    slider.name = spec.key;
    slider.min = spec.lower_open ? spec.lower + step : spec.lower;
    slider.max = spec.upper_open ? spec.upper - step : spec.upper;
    slider.step = step;
    slider.value = spec.value;
    const exact = document.createElement("input");
    exact.type = "text";
    exact.className = "value";
    exact.value = numberText(spec.value);
    slider.addEventListener("input", () => {
      exact.value = numberText(Number(slider.value));
      changeKey(spec.key, Number(slider.value));
    });
    exact.addEventListener("change", () => {
      slider.value = exact.value;
      changeKey(spec.key, exact.value.trim());
    });
    row.appendChild(slider);
    row.appendChild(exact);
  } else {
    input = document.createElement("input");
    input.type = "text";
    input.value = spec.text ? spec.value : numberText(spec.value);
    // sent as typed: the scene's own parser and checks judge it
    input.addEventListener("change", () => changeKey(spec.key, input.value.trim()));
  }
  if (input) { input.name = spec.key; row.appendChild(input); }
  const message = document.createElement("div");
  message.className = "message";
  row.appendChild(message);
  form.appendChild(row);
}

function changeKey(key, value) {
  explorer.values[key] = value;
  document.querySelectorAll(".key .message").forEach((node) => { node.textContent = ""; });
  updateSeries();
}

function readNumber(id) { return Number(document.getElementById(id).value); }

// ---- the views -----------------------------------------------------------------
function trajectoryOptions() {
  return {periods: readNumber("periods"), samples_per_period: readNumber("samples-per-period")};
}
function sectionOptions() {
  return {transient: readNumber("section-transient"), points: readNumber("section-points")};
}

function drawPhase() {
  const trajectory = explorer.data.trajectory;
  const orbit = explorer.data.orbit && explorer.data.orbit.orbit;
  setPlot(explorer.plots.phase, trajectory ? [trajectory.q, trajectory.qdot] : [[], []],
          orbit ? [orbit.q, orbit.qdot] : [[], []]);
}

async function updateTrajectory() {
  const result = await runJob("trajectory", trajectoryOptions());
  if (!result) return;
  const arrived = performance.now();
  explorer.data.trajectory = result;
  // each wall a dashed line over the run's time, broken between walls
  const wallT = [], wallQ = [], ends = [result.t[0], result.t[result.t.length - 1]];
  for (const wall of result.walls) wallT.push(...ends, null), wallQ.push(wall.q, wall.q, null);
  setPlot(explorer.plots.trajectory, [result.t, result.q], [result.impacts.t, result.impacts.q],
          [wallT, wallQ]);
  drawPhase();
  await recordDrawn(result.timing, arrived);
}

async function updateSection() {
  const result = await runJob("section", sectionOptions());
  if (!result) return;
  const arrived = performance.now();
  explorer.data.section = result;
  setPlot(explorer.plots.section, [result.q, result.qdot]);
  await recordDrawn(result.timing, arrived);
}

function updateSeries() {
  updateTrajectory();
  updateSection();
}

// the diagram: columns drawn as they arrive; the clicked point marked
function drawDiagram() {
  const plot = explorer.plots.diagram, columns = explorer.data.diagramColumns || [];
  const x = [], y = [];
  for (const column of columns) for (const q of column.q) { x.push(column.value); y.push(q); }
  const selection = explorer.selection;
  setPlot(plot, [x, y], selection ? [[selection.value], [selection.q]] : [[], []]);
}

async function runDiagram(request) {
  explorer.diagram = request;
  explorer.data.diagramColumns = [];
  explorer.data.diagram = null;
  explorer.diagramYRange = request.yRange || null;
  document.getElementById("diagram-from").value = request.from;
  document.getElementById("diagram-to").value = request.to;
  // the key and its unit under the horizontal axis
  const spec = explorer.scene.keys.find((k) => k.key === request.key);
  explorer.plots.diagram.axes[0].label = axisLabel(request.key, spec && spec.unit);
  drawDiagram();
  const {yRange, ...options} = request;
  const result = await runJob("diagram", options, (columns) => {
    explorer.data.diagramColumns.push(...columns);
    drawDiagram();
  });
  if (result) {
    explorer.data.diagram = result;
    drawDiagram();
  }
}

function diagramRequestFromInputs() {
  return {key: document.getElementById("diagram-key").value,
          from: readNumber("diagram-from"), to: readNumber("diagram-to"),
          columns: readNumber("diagram-columns"), points: readNumber("diagram-points"),
          transient: readNumber("diagram-transient"), threads: readNumber("diagram-threads")};
}

// a box dragged (uPlot's selection, at least 5 px) zooms the diagram: recomputed
// at full resolution over the box's range, the box's range of the coordinate kept
function zoomDiagram(u) {
  const {left, top, width, height} = u.select;
  if (width < 5 && height < 5) return;
  const from = u.posToVal(left, "x"), to = u.posToVal(left + width, "x");
  const low = u.posToVal(top + height, "y"), high = u.posToVal(top, "y");
  u.setSelect({left: 0, top: 0, width: 0, height: 0}, false);
  if (!explorer.diagram) return;
  explorer.zoomHistory.push(explorer.diagram);
  runDiagram({...explorer.diagram, from: Math.min(from, to), to: Math.max(from, to),
              yRange: [Math.min(low, high), Math.max(low, high)]});
}

// a click (a press and release within 5 px) picks the nearest point within 8 px
function attachDiagramClick(u) {
  let down = null;
  u.over.addEventListener("mousedown", (event) => { down = [event.clientX, event.clientY]; });
  u.over.addEventListener("mouseup", (event) => {
    if (!down) return;
    const moved = Math.hypot(event.clientX - down[0], event.clientY - down[1]);
    down = null;
    if (moved >= 5) return;
    const box = u.over.getBoundingClientRect();
    pickPoint(event.clientX - box.left, event.clientY - box.top);
  });
}

// (px, py): CSS pixels in the plotting area
function pickPoint(px, py) {
  const u = explorer.plots.diagram;
  let best = null, bestDistance = 64;  // (8 px)²
  for (const column of explorer.data.diagramColumns || []) {
    const cx = u.valToPos(column.value, "x");
    for (let i = 0; i < column.q.length; ++i) {
      const distance = (cx - px) ** 2 + (u.valToPos(column.q[i], "y") - py) ** 2;
      if (distance < bestDistance) {
        bestDistance = distance;
        best = {key: explorer.diagram.key, value: column.value, t: column.t[i], q: column.q[i], qdot: column.qdot[i]};
      }
    }
  }
  if (best) showOrbit(best);
}

function complexText(z) {
  return z.im === 0 ? z.re.toPrecision(8) : `${z.re.toPrecision(8)} ${z.im < 0 ? "−" : "+"} ${Math.abs(z.im).toPrecision(8)}i`;
}

async function showOrbit(point) {
  explorer.selection = point;
  drawDiagram();
  document.getElementById("orbit-text").textContent = `${point.key} = ${point.value}: searching…`;
  const result = await runJob("orbit", {...point, transient: readNumber("diagram-transient")});
  if (!result) return;
  explorer.data.orbit = result;
  explorer.orbitRequest = point;
  const periodic = result.periodic;
  const lines = [
    `${point.key} = ${point.value}, from the section point t = ${point.t}, q = ${point.q}, qdot = ${point.qdot}`,
    `period ${periodic.request.period} (${periodic.request.period_source}); ` +
      (periodic.converged ? `converged in ${periodic.iterations} Newton iterations, residual ${periodic.residual.toExponential(2)}`
                          : `not converged: ${periodic.failure}`),
    `orbit point on the section: ${periodic.state_names.map((n, i) => `${n} = ${periodic.state[i]}`).join(", ")}`,
    periodic.converged
      ? `Floquet multipliers: ${periodic.floquet_multipliers.map((z) => `${complexText(z)} (|μ| = ${z.abs.toPrecision(6)})`).join(", ")}`
      : "Floquet multipliers: none (the iterate is not an orbit)",
    `largest Lyapunov exponent: ${result.lyapunov_text} per time unit ${result.lyapunov_note ? "(" + result.lyapunov_note + ")" : ""}`,
  ];
  document.getElementById("orbit-text").textContent = lines.join("\n");
  drawPhase();
}

// ---- export --------------------------------------------------------------------
async function exportView(kind) {
  const options = kind === "trajectory" ? trajectoryOptions() : kind === "section" ? sectionOptions()
    : kind === "diagram" ? (({yRange, ...rest}) => rest)(explorer.diagram || diagramRequestFromInputs())
    : {...(explorer.orbitRequest || {}), transient: readNumber("diagram-transient")};
  try {
    const exported = await api("/api/export", {kind, values: explorer.values, options});
    explorer.data.export = exported;
    document.getElementById("export-text").textContent =
      `# the command line\n${exported.commands.join("\n")}\n\n# Python\nimport impactlab\n${exported.python.join("\n")}\n\n# the scene file\n${exported.scene_toml}`;
    const link = document.getElementById("export-download");
    link.href = URL.createObjectURL(new Blob([exported.scene_toml], {type: "application/toml"}));
    link.hidden = false;
  } catch (error) {
    showError(error);
  }
}

// ---- start -----------------------------------------------------------------------
async function start() {
  const scene = await api("/api/scene");
  explorer.scene = scene;
  document.getElementById("scene-name").textContent = `${scene.scene_source} (${scene.oscillator})`;
  const form = document.getElementById("keys");
  for (const spec of scene.keys) {
    explorer.values[spec.key] = spec.value;
    addControl(form, spec);
  }
  // the axes: the main coordinate and its rate, in the units of the scene's
  // initial keys for them; time in t0's
  const q = scene.main_coordinate;
  const unit = (key) => (scene.keys.find((k) => k.key === key) || {}).unit;
  const tLabel = axisLabel("t", unit("t0")), qLabel = axisLabel(q, unit(`initial.${q}`));
  const rateLabel = axisLabel(q + "_dot", unit(`initial.${q}_dot`));
  const element = (id) => document.getElementById(id);
  explorer.plots.trajectory = makePlot(element("plot-trajectory"), 720, 260, tLabel, qLabel, [
    line(q, "#1f77b4", 1), dots("impacts", "#d62728", 5),
    line("walls", "#000", 1, {dash: [5, 4], paths: pathInOrder})]);
  explorer.plots.phase = makePlot(element("plot-phase"), 350, 300, qLabel, rateLabel, [
    line("trajectory", "#1f77b4", 0.7, {paths: pathInOrder}),
    line("periodic orbit", "#d62728", 2, {paths: pathInOrder})]);
  explorer.plots.section = makePlot(element("plot-section"), 350, 300, qLabel, rateLabel, [
    dots("section", "#2ca02c", 4)]);
  explorer.plots.diagram = makePlot(element("plot-diagram"), 720, 320, "", qLabel, [
    dots("orbit diagram", "#222", 2.5), dots("clicked point", "#d62728", 12, 2)], {
    // the horizontal range the one asked for; the vertical one a zoom's box, or fitted
    xRange: (low, high) => (explorer.diagram
      ? [Math.min(explorer.diagram.from, explorer.diagram.to), Math.max(explorer.diagram.from, explorer.diagram.to)]
      : padded(low, high)),
    yRange: (low, high) => explorer.diagramYRange || padded(low, high),
    cursor: {show: true, x: false, y: false, points: {show: false},
             drag: {x: true, y: true, setScale: false, dist: 5}},
    hooks: {setSelect: [zoomDiagram]},
  });
  // the diagram's key: the numeric keys; V0 by default where there is one
  const keySelect = document.getElementById("diagram-key");
  for (const spec of scene.keys) if (!spec.text) keySelect.add(new Option(spec.key, spec.key));
  const initialKey = scene.keys.some((spec) => spec.key === "V0") ? "V0" : keySelect.options[0].value;
  keySelect.value = initialKey;
  const setRange = () => {
    const value = explorer.values[keySelect.value];
    document.getElementById("diagram-from").value = value * 0.8;
    document.getElementById("diagram-to").value = value * 1.2;
  };
  keySelect.addEventListener("change", setRange);
  setRange();
  document.getElementById("diagram-run").addEventListener("click", () => {
    explorer.zoomHistory = [];
    runDiagram(diagramRequestFromInputs());
  });
  document.getElementById("diagram-fit").addEventListener("click", () => {
    explorer.diagramYRange = null;
    drawDiagram();
  });
  document.getElementById("diagram-back").addEventListener("click", () => {
    const previous = explorer.zoomHistory.pop();
    if (previous) runDiagram(previous);
  });
  for (const id of ["periods", "samples-per-period"]) document.getElementById(id).addEventListener("change", updateTrajectory);
  for (const id of ["section-transient", "section-points"]) document.getElementById(id).addEventListener("change", updateSection);
  document.querySelectorAll("[data-export]").forEach((button) =>
    button.addEventListener("click", () => exportView(button.dataset.export)));
  attachDiagramClick(explorer.plots.diagram);
  setStatus("ready");
  updateSeries();
}

start().catch((error) => setStatus(`cannot start: ${error.message}`, true));
