// gcs serve: the page. It asks the server (`/api/check`, `/api/solve`, `/api/compile`) with
// the editor's text and shows what it answers: the diagnostics, reports and plan of the text,
// and the drawing `gcs draw` makes at the controls' values. No framework, no build step.
"use strict";

const $ = (id) => document.getElementById(id);

const page = {
  name: "",
  // The last text that checked without errors: what the controls and the drawing are of.
  text: null,
  controls: null,
  // The controls' values, by name: params and defaults in their units, branches by index.
  params: new Map(),
  sketch: new Map(),
  branches: new Map(),
  defaults: new Map(),
  traces: new Set(),
  view: "iso",
  checks: 0,
  // The solve wanted next (the input time it answers), and whether one is on its way.
  wanted: null,
  busy: false,
};

async function post(path, body) {
  const response = await fetch(path, {
    method: "POST",
    headers: { "Content-Type": "application/json" },
    body: JSON.stringify(body),
  });
  const answer = await response.json();
  if (!response.ok) throw new Error(answer.error || `${path}: HTTP ${response.status}`);
  return answer;
}

function element(tag, attributes = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attributes)) {
    if (k === "class") e.className = v;
    else if (k === "text") e.textContent = v;
    else e.setAttribute(k, v);
  }
  for (const c of children) e.append(c);
  return e;
}

// ---- the model's text: checked on each change ------------------------------------------------

let checkTimer = null;

function edited() {
  clearTimeout(checkTimer);
  checkTimer = setTimeout(check, 250);
}

async function check() {
  const text = $("editor").value;
  const seq = ++page.checks;
  let v;
  try {
    v = await post("/api/check", { text });
  } catch (e) {
    setStatus(`cannot check: ${e.message}`, true);
    return;
  }
  if (seq !== page.checks) return; // a later edit's check is on its way
  showDiagnostics(v);
  $("report").textContent = v.report || "";
  $("explain").textContent = v.explain || "";
  if (v.ok) {
    page.text = text;
    setStatus("checked", false);
    buildControls(v.controls);
    wantSolve(performance.now());
  } else {
    page.text = null;
    setStatus(v.status || "the model has errors", true);
    setControlsEnabled(false);
    showTab("diagnostics-pane");
    setDrawing("stale", "The model has errors: not solved", [(v.status || "").replace(/^error: /, "")]);
    $("timing").textContent = "";
  }
}

function setStatus(text, error) {
  const s = $("check-status");
  s.textContent = text;
  s.classList.toggle("error", error);
}

function showDiagnostics(v) {
  const list = $("diagnostics");
  list.replaceChildren();
  const diags = v.diagnostics || [];
  for (const d of diags) {
    const loc = d.start ? `${d.start[0]}:${d.start[1]}` : "";
    const li = element(
      "li",
      { class: `diagnostic ${d.severity}`, "data-line": d.start ? d.start[0] : "", "data-column": d.start ? d.start[1] : "" },
      element("span", { class: "loc", text: loc }),
      " ",
      element("span", { class: "severity", text: `${d.severity}:` }),
      ` ${d.message}`,
    );
    if (d.start) li.addEventListener("click", () => goTo(d.start[0], d.start[1]));
    list.append(li);
  }
  if (diags.length === 0) list.append(element("li", { class: "none", text: "No diagnostics." }));
  const errors = diags.filter((d) => d.severity === "error").length;
  $("diagnostic-count").textContent = diags.length ? `(${errors} error${errors === 1 ? "" : "s"}, ${diags.length - errors} warning${diags.length - errors === 1 ? "" : "s"})` : "";
  let rendered = v.rendered || "";
  if (v.status) rendered += `${v.status}\n`;
  $("rendered").textContent = rendered;
}

// Puts the editor's caret at a line and column (1-based, in characters).
function goTo(line, column) {
  const editor = $("editor");
  const lines = editor.value.split("\n");
  let offset = 0;
  for (let k = 0; k < line - 1 && k < lines.length; k++) offset += lines[k].length + 1;
  offset += column - 1;
  editor.focus();
  editor.setSelectionRange(offset, offset);
}

// ---- controls ---------------------------------------------------------------------------------

function unitOf(p) {
  return p.unit === "deg" ? "°" : "";
}

// The value of a param or default as the language writes it: degrees for an angle.
function valueText(value, unit) {
  return unit === "deg" ? `${value}deg` : `${value}`;
}

function buildControls(controls) {
  page.controls = controls;
  // A param keeps its value while its sketch value stays; a branch its index while it has it;
  // an edited default its value while it exists.
  const params = new Map();
  for (const p of controls.params) {
    const kept = page.sketch.get(p.name) === p.value && page.params.has(p.name);
    params.set(p.name, kept ? page.params.get(p.name) : p.value);
  }
  page.params = params;
  page.sketch = new Map(controls.params.map((p) => [p.name, p.value]));
  const branches = new Map();
  for (const b of controls.branches) {
    const i = page.branches.get(b.name);
    branches.set(b.name, i !== undefined && i < b.count ? i : b.default);
  }
  page.branches = branches;
  const defaults = new Map();
  for (const d of controls.defaults) {
    if (page.defaults.has(d.name)) defaults.set(d.name, page.defaults.get(d.name));
  }
  page.defaults = defaults;
  const points = new Set(controls.points);
  page.traces = new Set([...page.traces].filter((t) => points.has(t)));

  const paramsBox = $("params");
  paramsBox.replaceChildren();
  for (const p of controls.params) paramsBox.append(paramControl(p));
  if (controls.params.length === 0) paramsBox.append(element("span", { class: "empty", text: "No params." }));

  const branchesBox = $("branches");
  branchesBox.replaceChildren();
  for (const b of controls.branches) branchesBox.append(branchControl(b));
  if (controls.branches.length === 0) branchesBox.append(element("span", { class: "empty", text: "No branch variables." }));

  const defaultsBox = $("defaults");
  defaultsBox.replaceChildren();
  for (const d of controls.defaults) defaultsBox.append(defaultControl(d));
  if (controls.defaults.length === 0) defaultsBox.append(element("span", { class: "empty", text: "No defaults." }));

  $("view-box").hidden = controls.space !== "3d";
  buildTraces(controls);
  setControlsEnabled(true);
}

function setControlsEnabled(on) {
  for (const id of ["params-box", "branches-box", "defaults-box", "view-box", "trace-box"]) $(id).disabled = !on;
}

function paramControl(p) {
  const value = page.params.get(p.name);
  const slider = element("input", {
    type: "range", id: `param-${p.name}`, "data-param": p.name,
    min: Math.min(p.min, value), max: Math.max(p.max, value), step: p.step, value,
    "aria-label": `param ${p.name}`,
  });
  const field = element("input", {
    type: "number", id: `param-${p.name}-value`, step: "any", value, "aria-label": `param ${p.name} value`,
  });
  slider.addEventListener("input", () => {
    const t0 = performance.now();
    const v = Number(slider.value);
    page.params.set(p.name, v);
    field.value = v;
    wantSolve(t0);
  });
  field.addEventListener("change", () => {
    const t0 = performance.now();
    const v = Number(field.value);
    if (field.value === "" || !Number.isFinite(v)) return;
    if (v < Number(slider.min)) slider.min = v;
    if (v > Number(slider.max)) slider.max = v;
    slider.value = v;
    page.params.set(p.name, v);
    wantSolve(t0);
  });
  return element(
    "div", { class: "param", title: `${p.name}: ${p.dim}, sketch value ${p.value}${unitOf(p)}` },
    element("label", { class: "name", for: `param-${p.name}`, text: p.name }),
    element("span", { class: "cell" }, slider),
    element("span", { class: "cell" }, field),
    element("span", { class: "unit", text: p.unit === "deg" ? "deg" : p.dim === "length" ? "length" : "" }),
  );
}

function branchControl(b) {
  const select = element("select", { id: `branch-${b.name}`, "data-branch": b.name, "aria-label": `branch ${b.name}` });
  for (let i = 0; i < b.count; i++) {
    const meaning = b.meanings[i] || "";
    // Only a default the sketch reaches is the sketch's.
    const mark = i !== b.default ? "" : b.from_sketch ? " (sketch)" : " (default)";
    const option = element("option", { value: i, text: `${i}: ${meaning}${mark}` });
    select.append(option);
  }
  select.value = page.branches.get(b.name);
  select.addEventListener("change", () => {
    const t0 = performance.now();
    page.branches.set(b.name, Number(select.value));
    wantSolve(t0);
  });
  return element("div", { class: "branch" }, element("label", { class: "name", for: `branch-${b.name}`, text: b.name }), select);
}

function defaultControl(d) {
  const edited = page.defaults.has(d.name);
  const field = element("input", {
    type: "number", id: `default-${d.name}`, "data-default": d.name, step: "any",
    value: edited ? page.defaults.get(d.name) : d.value, "aria-label": `default ${d.name}`,
  });
  const reset = element("button", { type: "button", text: "sketch", title: "Back to the sketch's value (the least motion)" });
  field.addEventListener("change", () => {
    const t0 = performance.now();
    const v = Number(field.value);
    if (!Number.isFinite(v) || field.value === "") return;
    page.defaults.set(d.name, v);
    wantSolve(t0);
  });
  reset.addEventListener("click", () => {
    page.defaults.delete(d.name);
    field.value = d.value;
    wantSolve(performance.now());
  });
  return element(
    "div", { class: "default" },
    element("label", { class: "name", for: `default-${d.name}`, text: d.name }),
    element("span", { class: "field" }, field, element("span", { class: "unit", text: d.unit === "deg" ? "deg" : "" }), reset),
    element("span", { class: "meaning", text: d.meaning }),
  );
}

function buildTraces(controls) {
  const select = $("sweep-param");
  const was = select.value;
  select.replaceChildren();
  for (const p of controls.params) select.append(element("option", { value: p.name, text: p.name }));
  if (controls.params.some((p) => p.name === was)) select.value = was;
  else forgetSweepRange();
  syncSweepRange(select.value);
  const box = $("traces");
  box.replaceChildren();
  for (const name of controls.points) {
    const box1 = element("input", { type: "checkbox", id: `trace-${name}`, "data-trace": name });
    box1.checked = page.traces.has(name);
    box1.addEventListener("change", () => {
      if (box1.checked) page.traces.add(name);
      else page.traces.delete(name);
      wantSolve(performance.now());
    });
    box.append(element("label", { class: "trace-point" }, box1, ` ${name}`));
  }
  $("trace-box").hidden = controls.params.length === 0 || controls.points.length === 0;
}

// The sweep's range is the param's slider's until it is edited.
function syncSweepRange(name) {
  const p = page.controls && page.controls.params.find((q) => q.name === name);
  if (!p) return;
  if (!$("sweep-from").dataset.edited) $("sweep-from").value = p.min;
  if (!$("sweep-to").dataset.edited) $("sweep-to").value = p.max;
  $("sweep-unit").textContent = p.unit === "deg" ? "deg" : "";
}

function forgetSweepRange() {
  delete $("sweep-from").dataset.edited;
  delete $("sweep-to").dataset.edited;
}

function sweepText() {
  const name = $("sweep-param").value;
  const p = page.controls.params.find((q) => q.name === name);
  if (!p || page.traces.size === 0) return null;
  const steps = Math.max(1, Math.round(Number($("sweep-steps").value) || 60));
  return `${name}=${valueText(Number($("sweep-from").value), p.unit)}..${valueText(Number($("sweep-to").value), p.unit)}:${steps}`;
}

// ---- solving and drawing ----------------------------------------------------------------------

// Asks for a solve at the controls' values; `t0` is when the input that asks it happened. While
// one solve is on its way, the later inputs are merged into the next.
function wantSolve(t0) {
  if (page.text === null) return;
  page.wanted = { t0 };
  if (!page.busy) pump();
}

async function pump() {
  page.busy = true;
  while (page.wanted) {
    const { t0 } = page.wanted;
    page.wanted = null;
    const request = solveRequest();
    const sent = performance.now();
    let v;
    let via = "";
    try {
      [v, via] = await solveOn(request);
    } catch (e) {
      v = { ok: false, stage: "request", errors: [e.message] };
    }
    show(v, { input: t0, sent, answered: performance.now(), via }, request);
  }
  page.busy = false;
}

// ---- the live socket: solving while a control moves --------------------------------------------

// The WebSocket `/api/live` carries `/api/solve`'s requests and answers, one message each way: in
// the browser a message on an open socket costs a fraction of a fetch, which builds, checks and
// hands back a whole request through the network process. While it is not open, solves are
// POSTed as before.
const live = {
  socket: null, // the open socket
  opening: false,
  waiting: [], // the solves sent on it and not answered yet, in order: { resolve, reject }
  tried: -Infinity, // when it was last opened
};

function openLive() {
  if (live.socket || live.opening || typeof WebSocket === "undefined") return;
  if (performance.now() - live.tried < 2000) return;
  live.tried = performance.now();
  live.opening = true;
  let ws;
  try {
    ws = new WebSocket(`${location.protocol === "https:" ? "wss" : "ws"}://${location.host}/api/live`);
  } catch {
    live.opening = false;
    return;
  }
  ws.addEventListener("open", () => {
    live.opening = false;
    live.socket = ws;
  });
  ws.addEventListener("message", (event) => {
    const waiter = live.waiting.shift();
    if (waiter) waiter.resolve(event.data);
  });
  ws.addEventListener("close", () => {
    live.opening = false;
    if (live.socket === ws) live.socket = null;
    for (const waiter of live.waiting.splice(0)) waiter.reject(new SocketClosed());
  });
}

class SocketClosed extends Error {
  constructor() {
    super("the live socket closed");
  }
}

// `/api/solve`'s answer to `request`, and how it was asked: over the live socket when it is
// open ("socket"), else POSTed ("http"), as when the socket closes before answering.
async function solveOn(request) {
  const ws = live.socket;
  if (ws && ws.readyState === WebSocket.OPEN) {
    try {
      const text = await new Promise((resolve, reject) => {
        ws.send(JSON.stringify(request));
        live.waiting.push({ resolve, reject });
      });
      const { status, answer } = JSON.parse(text);
      if (status !== 200) throw new Error((answer && answer.error) || `/api/solve: HTTP ${status}`);
      return [answer, "socket"];
    } catch (e) {
      if (!(e instanceof SocketClosed) && ws.readyState === WebSocket.OPEN) throw e;
    }
  }
  openLive();
  return [await post("/api/solve", request), "http"];
}

function solveRequest() {
  const c = page.controls;
  const request = {
    text: page.text,
    set: c.params.map((p) => `${p.name}=${valueText(page.params.get(p.name), p.unit)}`),
    branch: c.branches.map((b) => `${b.name}=${page.branches.get(b.name)}`),
    default: c.defaults
      .filter((d) => page.defaults.has(d.name))
      .map((d) => `${d.name}=${valueText(page.defaults.get(d.name), d.unit)}`),
  };
  const sweep = sweepText();
  if (sweep) {
    request.sweep = sweep;
    request.trace = [...page.traces];
  }
  if (c.space === "3d") request.view = page.view;
  return request;
}

// Shows a solve's answer; `times` are when the input that asked it happened, when it was sent
// and when it was answered (performance.now()).
function show(v, times, request) {
  const drawing = $("drawing");
  if (v.ok) {
    drawSvg(drawing, v.svg);
    drawing.dataset.scale = v.fit.scale;
    drawing.dataset.cornerX = v.fit.corner[0];
    drawing.dataset.cornerY = v.fit.corner[1];
    drawing.dataset.view = v.view;
    drawing.dataset.set = request.set.join(" ");
    drawing.dataset.branch = request.branch.join(" ");
    drawing.dataset.draws = Number(drawing.dataset.draws) + 1;
    setDrawing("current", "", []);
    drawing.getBoundingClientRect(); // laid out: the picture is there to be painted
    const drawn = performance.now();
    const ms = drawn - times.input;
    const timing = $("timing");
    timing.textContent = `solved and drawn in ${ms.toFixed(1)} ms`;
    timing.title = `from the input: ${(times.sent - times.input).toFixed(1)} ms waiting for the solve before, ` +
      `${(times.answered - times.sent).toFixed(1)} ms asking the server (${times.via === "socket" ? "on the live socket" : "by a POST"}), ` +
      `${(drawn - times.answered).toFixed(1)} ms drawing`;
    timing.dataset.ms = ms.toFixed(3);
    timing.dataset.waited = (times.sent - times.input).toFixed(3);
    timing.dataset.answered = (times.answered - times.sent).toFixed(3);
    timing.dataset.drawing = (drawn - times.answered).toFixed(3);
    timing.dataset.via = times.via;
    $("solution").textContent = JSON.stringify(v.solution, null, 2);
    showSweep(v.sweep);
  } else {
    const head = v.stage === "solve" ? "Does not solve at these values" : v.stage === "inputs" ? "Refused" : "Not solved";
    setDrawing(v.stage === "solve" ? "failed" : "stale", head, v.errors || []);
    $("timing").textContent = `failed after ${(performance.now() - times.input).toFixed(1)} ms`;
    $("solution").textContent = (v.errors || []).map((e) => `error: ${e}`).join("\n");
    showSweep(null);
  }
}

// Puts the SVG `text` (the server's drawing) in `box`. The picture already there is updated in
// place: its elements that match the new ones (the same tag at the same place) are kept, with only
// their changed attributes and texts set, and the others replaced. Dragging a slider then changes
// a few coordinates in the page instead of building a new picture, which would also restyle the
// whole page (the SVG carries its own <style>). The result is the same tree as `text` parsed.
const svgParser = document.createElement("template");

function drawSvg(box, text) {
  svgParser.innerHTML = text;
  const fresh = svgParser.content.firstElementChild;
  const old = box.firstElementChild;
  if (fresh && old && sameElement(old, fresh) && box.childNodes.length === 1) updateNode(old, fresh);
  else if (fresh) box.replaceChildren(fresh);
  else box.replaceChildren();
  svgParser.content.replaceChildren();
}

function sameElement(a, b) {
  return a.namespaceURI === b.namespaceURI && a.localName === b.localName;
}

// Makes `old` (in the page) equal to `fresh` (just parsed): its attributes, then its children,
// pair by pair.
function updateNode(old, fresh) {
  for (const a of fresh.attributes) {
    if (old.getAttributeNS(a.namespaceURI, a.localName) !== a.value) old.setAttributeNS(a.namespaceURI, a.name, a.value);
  }
  for (let k = old.attributes.length - 1; k >= 0; k--) {
    const a = old.attributes[k];
    if (!fresh.hasAttributeNS(a.namespaceURI, a.localName)) old.removeAttributeNS(a.namespaceURI, a.localName);
  }
  let o = old.firstChild;
  let f = fresh.firstChild;
  while (o && f) {
    const nextO = o.nextSibling;
    const nextF = f.nextSibling;
    if (o.nodeType === Node.ELEMENT_NODE && f.nodeType === Node.ELEMENT_NODE && sameElement(o, f)) {
      updateNode(o, f);
    } else if (o.nodeType === f.nodeType && o.nodeType !== Node.ELEMENT_NODE) {
      if (o.nodeValue !== f.nodeValue) o.nodeValue = f.nodeValue;
    } else {
      old.replaceChild(f, o);
    }
    o = nextO;
    f = nextF;
  }
  while (o) {
    const next = o.nextSibling;
    o.remove();
    o = next;
  }
  while (f) {
    const next = f.nextSibling;
    old.append(f);
    f = next;
  }
}

// The drawing's state: `current` (the picture is of the controls' values), or `failed` or
// `stale` (the picture left is greyed, and the message says why it is not current).
function setDrawing(state, head, errors) {
  const drawing = $("drawing");
  drawing.dataset.state = drawing.firstElementChild || state === "current" ? state : "empty";
  const status = $("drawing-status");
  if (status.firstChild) status.replaceChildren();
  if (state !== "current") {
    status.append(element("strong", { text: `${head}${drawing.firstElementChild ? " — the picture greyed below is the last that solved" : ""}` }));
    status.append(errors.filter((e) => e).map((e) => `error: ${e}`).join("\n"));
  }
}

function showSweep(sweep) {
  const s = $("sweep-status");
  if (!sweep) {
    s.textContent = page.traces.size ? "" : "Tick a point to trace its curve over the sweep.";
    s.classList.remove("gaps");
    return;
  }
  const failed = sweep.failed.length;
  if (failed === 0) {
    s.textContent = `${sweep.samples} samples of ${sweep.param}, all solved.`;
    s.classList.remove("gaps");
  } else {
    const first = sweep.failed[0];
    s.textContent = `${failed} of ${sweep.samples} samples of ${sweep.param} did not solve (gaps in the curve); the first, at ${sweep.param} = ${first.value}: ${first.error}`;
    s.classList.add("gaps");
  }
}

// The model's coordinates under the pointer (a planar model: the drawing's fit inverted).
function trackCursor(event) {
  const drawing = $("drawing");
  const svg = drawing.querySelector("svg");
  if (!svg || drawing.dataset.view !== "xy" || !page.controls || page.controls.space !== "2d") {
    $("cursor").textContent = "";
    return;
  }
  const m = svg.getScreenCTM();
  if (!m) return;
  const p = new DOMPoint(event.clientX, event.clientY).matrixTransform(m.inverse());
  const scale = Number(drawing.dataset.scale);
  const x = p.x / scale + Number(drawing.dataset.cornerX);
  const y = Number(drawing.dataset.cornerY) - p.y / scale;
  $("cursor").textContent = `x = ${x.toFixed(3)}, y = ${y.toFixed(3)}`;
}

// ---- the Rust module --------------------------------------------------------------------------

let codeUrl = null;

async function showCode() {
  let v;
  try {
    v = await post("/api/compile", { text: $("editor").value });
  } catch (e) {
    v = { ok: false, errors: [e.message] };
  }
  const code = $("code");
  const link = $("code-download");
  if (codeUrl) URL.revokeObjectURL(codeUrl);
  codeUrl = null;
  if (v.ok) {
    code.textContent = v.code;
    codeUrl = URL.createObjectURL(new Blob([v.code], { type: "text/x-rust" }));
    link.href = codeUrl;
    link.download = v.file;
    link.textContent = `Download ${v.file}`;
    link.hidden = false;
    $("code-title").textContent = `gcs compile ${page.name}`;
  } else {
    code.textContent = [...(v.errors || []).map((e) => `error: ${e}`), v.rendered || ""].join("\n");
    link.hidden = true;
    $("code-title").textContent = "No module: the model has errors";
  }
  $("code-dialog").showModal();
}

function downloadModel() {
  const url = URL.createObjectURL(new Blob([$("editor").value], { type: "text/plain" }));
  const a = element("a", { href: url, download: page.name.split(/[\\/]/).pop() || "model.gcs" });
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 1000);
}

// ---- tabs and start ---------------------------------------------------------------------------

function showTab(id) {
  for (const b of document.querySelectorAll(".tabs button")) b.classList.toggle("active", b.dataset.tab === id);
  for (const p of document.querySelectorAll(".tab-pane")) p.classList.toggle("active", p.id === id);
}

async function start() {
  for (const b of document.querySelectorAll(".tabs button")) b.addEventListener("click", () => showTab(b.dataset.tab));
  $("editor").addEventListener("input", edited);
  $("compile").addEventListener("click", showCode);
  $("code-close").addEventListener("click", () => $("code-dialog").close());
  $("download-model").addEventListener("click", downloadModel);
  $("drawing").addEventListener("mousemove", trackCursor);
  $("drawing").addEventListener("mouseleave", () => { $("cursor").textContent = ""; });
  $("view").addEventListener("change", () => { page.view = $("view").value; wantSolve(performance.now()); });
  $("sweep-param").addEventListener("change", () => {
    forgetSweepRange();
    syncSweepRange($("sweep-param").value);
    wantSolve(performance.now());
  });
  for (const id of ["sweep-from", "sweep-to", "sweep-steps"]) {
    $(id).addEventListener("change", () => {
      $(id).dataset.edited = "1";
      wantSolve(performance.now());
    });
  }
  setControlsEnabled(false);
  openLive();
  try {
    const response = await fetch("/api/model");
    const model = await response.json();
    if (!response.ok) throw new Error(model.error);
    page.name = model.name;
    $("file-name").textContent = model.name;
    document.title = `gcs serve ${model.name}`;
    $("editor").value = model.text;
  } catch (e) {
    setStatus(`cannot read the model: ${e.message}`, true);
    return;
  }
  await check();
}

start();
