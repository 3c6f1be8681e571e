// The explorer's page: controls from the scene's schema, the views drawn on
// canvases from the server's JSON (api/explore_requests.hpp). It computes
// nothing itself: every number it draws comes from the server's jobs.
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
  plots: {},
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

// ---- plots on canvases -------------------------------------------------------
function niceTicks(low, high, count) {
  const span = high - low;
  if (!(span > 0)) return [low];
  const raw = span / count, power = Math.pow(10, Math.floor(Math.log10(raw)));
  const step = [1, 2, 5, 10].map((m) => m * power).find((s) => s >= raw);
  const ticks = [];
  for (let v = Math.ceil(low / step) * step; v <= high + 1e-9 * step; v += step) ticks.push(Number(v.toPrecision(12)));
  return ticks;
}

function extent(arrays, fallback) {
  let low = Infinity, high = -Infinity;
  for (const values of arrays) for (const v of values) if (Number.isFinite(v)) { low = Math.min(low, v); high = Math.max(high, v); }
  if (low === Infinity) return fallback || [0, 1];
  if (low === high) return [low - 0.5 * Math.abs(low || 1), high + 0.5 * Math.abs(high || 1)];
  const pad = 0.04 * (high - low);
  return [low - pad, high + pad];
}

// One canvas plot: `layers` of lines or points in data coordinates, axes by
// `x` and `y` ranges (auto when null).
class Plot {
  constructor(canvas, xLabel, yLabel) {
    this.canvas = canvas;
    this.xLabel = xLabel;
    this.yLabel = yLabel;
    this.layers = [];
    this.hlines = [];
    this.margin = {left: 58, right: 10, top: 8, bottom: 34};
    this.xRange = null;
    this.yRange = null;
  }
  toPixel(x, y) {
    const {left, right, top, bottom} = this.margin, w = this.canvas.width, h = this.canvas.height;
    return [left + (x - this.x[0]) / (this.x[1] - this.x[0]) * (w - left - right),
            h - bottom - (y - this.y[0]) / (this.y[1] - this.y[0]) * (h - top - bottom)];
  }
  toData(px, py) {
    const {left, right, top, bottom} = this.margin, w = this.canvas.width, h = this.canvas.height;
    return [this.x[0] + (px - left) / (w - left - right) * (this.x[1] - this.x[0]),
            this.y[0] + (h - bottom - py) / (h - top - bottom) * (this.y[1] - this.y[0])];
  }
  draw() {
    const context = this.canvas.getContext("2d"), w = this.canvas.width, h = this.canvas.height;
    this.x = this.xRange || extent(this.layers.map((l) => l.x));
    this.y = this.yRange || extent(this.layers.map((l) => l.y).concat([this.hlines]));
    context.clearRect(0, 0, w, h);
    context.fillStyle = "white";
    context.fillRect(0, 0, w, h);
    const {left, right, top, bottom} = this.margin;
    context.save();
    context.beginPath();
    context.rect(left, top, w - left - right, h - top - bottom);
    context.clip();
    for (const q of this.hlines) {
      const [, py] = this.toPixel(this.x[0], q);
      context.strokeStyle = "#000";
      context.setLineDash([5, 4]);
      context.beginPath(); context.moveTo(left, py); context.lineTo(w - right, py); context.stroke();
      context.setLineDash([]);
    }
    for (const layer of this.layers) {
      context.strokeStyle = context.fillStyle = layer.color || "#1f77b4";
      context.lineWidth = layer.width || 1;
      if (layer.mode === "line") {
        context.beginPath();
        for (let i = 0; i < layer.x.length; ++i) {
          const [px, py] = this.toPixel(layer.x[i], layer.y[i]);
          if (i === 0) context.moveTo(px, py); else context.lineTo(px, py);
        }
        context.stroke();
      } else {
        const size = layer.size || 2;
        for (let i = 0; i < layer.x.length; ++i) {
          const [px, py] = this.toPixel(layer.x[i], layer.y[i]);
          context.fillRect(px - size / 2, py - size / 2, size, size);
        }
      }
    }
    context.restore();
    // axes and ticks
    context.strokeStyle = "#444"; context.fillStyle = "#222"; context.font = "11px sans-serif";
    context.strokeRect(left, top, w - left - right, h - top - bottom);
    context.textAlign = "center";
    for (const t of niceTicks(this.x[0], this.x[1], 6)) {
      const [px] = this.toPixel(t, this.y[0]);
      context.fillText(String(t), px, h - bottom + 13);
    }
    context.textAlign = "right";
    for (const t of niceTicks(this.y[0], this.y[1], 5)) {
      const [, py] = this.toPixel(this.x[0], t);
      context.fillText(String(t), left - 4, py + 4);
    }
    context.textAlign = "center";
    context.fillText(this.xLabel, left + (w - left - right) / 2, h - 4);
    context.save(); context.translate(11, top + (h - top - bottom) / 2); context.rotate(-Math.PI / 2);
    context.fillText(this.yLabel, 0, 0); context.restore();
  }
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
  const phase = explorer.plots.phase;
  phase.layers = [];
  const trajectory = explorer.data.trajectory;
  if (trajectory) phase.layers.push({mode: "line", x: trajectory.q, y: trajectory.qdot, color: "#1f77b4", width: 0.7});
  const orbit = explorer.data.orbit && explorer.data.orbit.orbit;
  if (orbit) phase.layers.push({mode: "line", x: orbit.q, y: orbit.qdot, color: "#d62728", width: 2});
  phase.draw();
}

async function updateTrajectory() {
  const result = await runJob("trajectory", trajectoryOptions());
  if (!result) return;
  explorer.data.trajectory = result;
  const plot = explorer.plots.trajectory;
  plot.layers = [{mode: "line", x: result.t, y: result.q, color: "#1f77b4"},
                 {mode: "points", x: result.impacts.t, y: result.impacts.q, color: "#d62728", size: 3}];
  plot.hlines = result.walls.map((wall) => wall.q);
  plot.draw();
  drawPhase();
}

async function updateSection() {
  const result = await runJob("section", sectionOptions());
  if (!result) return;
  explorer.data.section = result;
  const plot = explorer.plots.section;
  plot.layers = [{mode: "points", x: result.q, y: result.qdot, color: "#2ca02c", size: 3}];
  plot.draw();
}

function updateSeries() {
  updateTrajectory();
  updateSection();
}

// the diagram: columns drawn as they arrive
function drawDiagram() {
  const plot = explorer.plots.diagram, columns = explorer.data.diagramColumns || [];
  const x = [], y = [];
  for (const column of columns) for (const q of column.q) { x.push(column.value); y.push(q); }
  plot.layers = [{mode: "points", x, y, color: "#222", size: 1.6}];
  const request = explorer.diagram;
  plot.xRange = request ? [Math.min(request.from, request.to), Math.max(request.from, request.to)] : null;
  plot.xLabel = request ? request.key : "";
  plot.draw();
  if (explorer.selection) {
    const [px, py] = plot.toPixel(explorer.selection.value, explorer.selection.q);
    const context = plot.canvas.getContext("2d");
    context.strokeStyle = "#d62728"; context.lineWidth = 2;
    context.strokeRect(px - 5, py - 5, 10, 10);
  }
}

async function runDiagram(request) {
  explorer.diagram = request;
  explorer.data.diagramColumns = [];
  explorer.data.diagram = null;
  explorer.plots.diagram.yRange = request.yRange || null;
  document.getElementById("diagram-from").value = request.from;
  document.getElementById("diagram-to").value = request.to;
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

// drag: a box zooms into the diagram; a click picks the nearest point
function attachDiagramMouse() {
  const plot = explorer.plots.diagram, canvas = plot.canvas;
  let start = null;
  const position = (event) => {
    const box = canvas.getBoundingClientRect();
    return [(event.clientX - box.left) * canvas.width / box.width, (event.clientY - box.top) * canvas.height / box.height];
  };
  canvas.addEventListener("mousedown", (event) => { start = position(event); });
  canvas.addEventListener("mousemove", (event) => {
    if (!start) return;
    const [px, py] = position(event);
    drawDiagram();
    const context = canvas.getContext("2d");
    context.strokeStyle = "#06c"; context.lineWidth = 1;
    context.strokeRect(start[0], start[1], px - start[0], py - start[1]);
  });
  canvas.addEventListener("mouseup", (event) => {
    if (!start) return;
    const end = position(event), begin = start;
    start = null;
    if (Math.abs(end[0] - begin[0]) < 5 && Math.abs(end[1] - begin[1]) < 5) {
      pickPoint(end);
      return;
    }
    const [x0, y0] = plot.toData(begin[0], begin[1]), [x1, y1] = plot.toData(end[0], end[1]);
    if (explorer.diagram) explorer.zoomHistory.push(explorer.diagram);
    runDiagram({...explorer.diagram, from: Math.min(x0, x1), to: Math.max(x0, x1),
                yRange: [Math.min(y0, y1), Math.max(y0, y1)]});
  });
}

function pickPoint([px, py]) {
  const plot = explorer.plots.diagram;
  let best = null, bestDistance = 64;  // (8 px)²
  for (const column of explorer.data.diagramColumns || []) {
    for (let i = 0; i < column.q.length; ++i) {
      const [cx, cy] = plot.toPixel(column.value, column.q[i]);
      const distance = (cx - px) ** 2 + (cy - py) ** 2;
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
    `Floquet multipliers: ${periodic.floquet_multipliers.map((z) => `${complexText(z)} (|μ| = ${z.abs.toPrecision(6)})`).join(", ")}`,
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
  const q = scene.main_coordinate;
  explorer.plots.trajectory = new Plot(document.getElementById("plot-trajectory"), "t", q);
  explorer.plots.phase = new Plot(document.getElementById("plot-phase"), q, q + "_dot");
  explorer.plots.section = new Plot(document.getElementById("plot-section"), q, q + "_dot");
  explorer.plots.diagram = new Plot(document.getElementById("plot-diagram"), "", q);
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
    explorer.plots.diagram.yRange = null;
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
  attachDiagramMouse();
  for (const plot of Object.values(explorer.plots)) plot.draw();
  setStatus("ready");
  updateSeries();
}

start().catch((error) => setStatus(`cannot start: ${error.message}`, true));
