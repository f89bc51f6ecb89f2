// netspec serve: the page. Plain JavaScript; the server checks every edit with netspec's own
// spec code and draws every picture with netspec's own renderer.
"use strict";

const $ = (sel) => document.querySelector(sel);
const $$ = (sel) => Array.from(document.querySelectorAll(sel));

let spec = null; // the spec being edited, as JSON (the server's form of it)
let view = null; // its picture and where its vertices and edges are
let run = null; // the run being watched: {id, source}
let chart = { incumbent: [], bound: [] };
let checks = 0; // checks answered (the browser test waits on it)

async function api(method, url, body) {
  const opts = { method, headers: {} };
  if (body !== undefined) {
    opts.headers["content-type"] = "application/json";
    opts.body = JSON.stringify(body);
  }
  const r = await fetch(url, opts);
  const data = await r.json().catch(() => ({ error: r.statusText }));
  if (!r.ok) {
    const e = new Error(data.error || r.statusText);
    e.field = data.field;
    throw e;
  }
  return data;
}

function getPath(obj, path) {
  return path.split(".").reduce((o, k) => (o == null ? undefined : o[k]), obj);
}

function setPath(obj, path, value) {
  const keys = path.split(".");
  let o = obj;
  for (const k of keys.slice(0, -1)) {
    if (o[k] == null || typeof o[k] !== "object") o[k] = {};
    o = o[k];
  }
  const last = keys[keys.length - 1];
  if (value === undefined) delete o[last];
  else o[last] = value;
}

function showError(err) {
  $$(".field-error").forEach((e) => e.remove());
  $("#error").textContent = "";
  if (!err) return;
  const input = err.field && $$("[data-field]").find((i) => err.field === i.dataset.field || err.field.startsWith(i.dataset.field + ".") || err.field.startsWith(i.dataset.field + "["));
  if (input) {
    const span = document.createElement("span");
    span.className = "field-error";
    span.dataset.for = input.dataset.field;
    span.textContent = err.message;
    input.parentElement.appendChild(span);
  } else {
    $("#error").textContent = (err.field ? err.field + ": " : "") + err.message;
  }
}

// --- the spec list ---------------------------------------------------------------------------

async function loadSpecs() {
  const data = await api("GET", "/api/specs");
  const ul = $("#specs");
  ul.innerHTML = "";
  for (const s of data.specs) {
    const li = document.createElement("li");
    const q = s.source === "example" ? "example=" + encodeURIComponent(s.id) : "path=" + encodeURIComponent(s.id);
    li.dataset.id = s.id;
    li.title = s.description;
    li.innerHTML = `<img loading="lazy" alt=""><span></span>`;
    li.querySelector("img").src = "/api/thumb?" + q;
    li.querySelector("span").textContent = s.source === "example" ? s.name : s.id;
    li.onclick = () => openSpec(q, li);
    ul.appendChild(li);
  }
}

async function openSpec(query, li) {
  try {
    const data = await api("GET", "/api/spec?" + query);
    $$("#specs li").forEach((x) => x.classList.remove("current"));
    if (li) li.classList.add("current");
    setSpec(data);
    resetResult();
  } catch (e) {
    showError(e);
  }
}

async function newSpec() {
  try {
    const body = { width: Number($("#new-width").value), height: Number($("#new-height").value), shape: $("#new-shape").value };
    setSpec(await api("POST", "/api/new", body));
    resetResult();
  } catch (e) {
    showError(e);
  }
}

// --- editing ---------------------------------------------------------------------------------

function setSpec(data) {
  $("#levels").innerHTML = "";
  spec = data.spec;
  view = data.view;
  showError(null);
  $("#spec-name").textContent = "· " + spec.name;
  $("#download").href = "data:application/toml;charset=utf-8," + encodeURIComponent(data.toml);
  $("#download").download = (spec.name || "spec") + ".toml";
  $("#solve").disabled = false;
  fillFields();
  drawSpec();
}

function fillFields() {
  for (const input of $$("[data-field]")) {
    let v = getPath(spec, input.dataset.field);
    if (input.dataset.field === "formulation" && typeof v === "object" && v) v = v.recipe;
    input.value = v == null ? "" : String(v);
  }
  for (const s of $$("[data-slider]")) {
    const v = getPath(spec, s.dataset.slider);
    s.value = typeof v === "number" ? v : 0;
  }
  const level = $("[data-field='rooms.level']").parentElement;
  level.style.display = spec.rooms ? "" : "none";
}

function fieldValue(input) {
  const raw = input.value.trim();
  if (raw === "") return undefined;
  if (input.type === "number") return Number(raw);
  if (input.dataset.kind === "weight") return isNaN(Number(raw)) ? raw : Number(raw);
  return raw;
}

async function edit(path, value) {
  const next = JSON.parse(JSON.stringify(spec));
  setPath(next, path, value);
  await check(next);
}

async function check(next) {
  try {
    const data = await api("POST", "/api/check", { spec: next });
    setSpec(data);
  } catch (e) {
    showError(e);
  }
  checks += 1;
  document.body.dataset.checks = checks;
}

function drawSpec() {
  showPicture(view.svg);
}

// Draws a picture of the spec or a design (the same frame) with the vertices and edges of the
// spec clickable over it.
function showPicture(markup) {
  const pic = $("#picture");
  pic.innerHTML = markup;
  const svg = pic.querySelector("svg");
  if (!svg || !view) return;
  const ns = "http://www.w3.org/2000/svg";
  const g = document.createElementNS(ns, "g");
  view.edges.forEach(([a, b], i) => {
    const l = document.createElementNS(ns, "line");
    l.setAttribute("x1", view.points[a][0]);
    l.setAttribute("y1", view.points[a][1]);
    l.setAttribute("x2", view.points[b][0]);
    l.setAttribute("y2", view.points[b][1]);
    l.setAttribute("class", "hit-e");
    l.dataset.e = i;
    l.onclick = () => clickEdge(a, b);
    g.appendChild(l);
  });
  view.points.forEach(([x, y], v) => {
    const c = document.createElementNS(ns, "circle");
    c.setAttribute("cx", x);
    c.setAttribute("cy", y);
    c.setAttribute("r", 7);
    c.setAttribute("class", "hit-v");
    c.dataset.v = v;
    c.onclick = () => clickVertex(v);
    g.appendChild(c);
  });
  svg.appendChild(g);
}

function toggle(list, item) {
  const key = JSON.stringify(item);
  const i = list.findIndex((x) => JSON.stringify(x) === key);
  if (i >= 0) list.splice(i, 1);
  else list.push(item);
}

function clickVertex(v) {
  const next = JSON.parse(JSON.stringify(spec));
  next.user = next.user || {};
  const mode = $("#click-mode").value;
  if (mode === "sink") toggle((next.sinks.vertices = next.sinks.vertices || []), v);
  if (mode === "obstacle") toggle((next.user.obstacle_vertices = next.user.obstacle_vertices || []), v);
  if (mode === "forced") toggle((next.user.forced_vertices = next.user.forced_vertices || []), v);
  check(next);
}

function clickEdge(a, b) {
  const next = JSON.parse(JSON.stringify(spec));
  next.user = next.user || {};
  const mode = $("#click-mode").value;
  if (mode === "obstacle") toggle((next.user.obstacle_edges = next.user.obstacle_edges || []), [a, b]);
  else if (mode === "forced") toggle((next.user.forced_edges = next.user.forced_edges || []), [a, b]);
  else return;
  check(next);
}

// --- solving ---------------------------------------------------------------------------------

function resetResult() {
  chart = { incumbent: [], bound: [] };
  drawChart();
  for (const id of ["status", "objective", "bound", "gap", "verdict", "metrics"]) $("#" + id).textContent = "-";
  $("#updates").textContent = "0";
  $("#conflicts").textContent = "";
  $("#exports").innerHTML = "";
  $("#result").dataset.state = "none";
}

async function solve() {
  if (!spec) return;
  try {
    const { id } = await api("POST", "/api/solve", { spec });
    resetResult();
    watch(id);
  } catch (e) {
    showError(e);
  }
}

function watch(id) {
  if (run && run.source) run.source.close();
  const source = new EventSource(`/api/runs/${id}/events`);
  run = { id, source };
  $("#stop").disabled = false;
  $("#result").dataset.state = "queued";
  $("#run-state").textContent = `run ${id}: queued`;
  let updates = 0;
  source.onmessage = (m) => {
    const ev = JSON.parse(m.data);
    if (ev.kind === "started") $("#run-state").textContent = `run ${id}: solving`;
    if (ev.kind === "solving" && ev.live === false)
      $("#run-state").textContent = `run ${id}: solving with ${ev.solver}, which reports its designs only at the end`;
    if (ev.kind === "design") {
      showPicture(ev.svg);
      chart.incumbent.push([ev.t, ev.objective]);
      $("#objective").textContent = ev.objective.toFixed(4);
      updates += 1;
    }
    if (ev.kind === "progress") {
      if (ev.primal != null) chart.incumbent.push([ev.t, ev.primal]);
      if (ev.dual != null) chart.bound.push([ev.t, ev.dual]);
      updates += 1;
    }
    if (ev.kind === "design" || ev.kind === "progress") {
      $("#updates").textContent = String(updates);
      $("#result").dataset.state = "running";
      drawChart();
    }
    if (ev.kind === "done" || ev.kind === "failed") {
      source.close();
      finish(id, ev);
    }
  };
}

function finish(id, ev) {
  $("#stop").disabled = true;
  if (ev.svg) showPicture(ev.svg);
  if (ev.error) showError({ message: ev.error });
  showSummary(ev.summary);
  $("#run-state").textContent = `run ${id}: ${ev.error ? "failed" : "finished"}`;
  showExports(id);
  $("#result").dataset.state = "done";
  loadRuns();
}

function showSummary(s) {
  if (!s) return;
  const num = (v) => (v == null ? "-" : v.toFixed(4));
  $("#status").textContent = s.status;
  $("#objective").textContent = num(s.objective);
  $("#bound").textContent = num(s.bound);
  $("#gap").textContent = s.gap == null ? "-" : (100 * s.gap).toFixed(2) + "%";
  $("#verdict").textContent = s.verdict;
  const m = s.metrics;
  $("#metrics").textContent = m
    ? `${m.edges} edges, length ${m.length.toFixed(2)}, ${m.dead_ends} dead-ends, ${m.junctions_3way} 3-way + ${m.junctions_4way} 4-way, ${m.t_junctions} T, ${m.zigzags} zig-zags, mean travel ${m.mean_travel.toFixed(3)}`
    : "-";
  $("#conflicts").textContent = (s.conflicts || []).join("\n");
  if (s.objective != null && chart.incumbent.length) chart.incumbent.push([s.seconds, s.objective]);
  if (s.bound != null) chart.bound.push([s.seconds, s.bound]);
  drawChart();
}

function showExports(id) {
  const files = ["result.json", "network.svg", "network.png", "network.geojson", "spec.toml", "model.mps", "model.lp"];
  $("#exports").innerHTML = "Export: " + files.map((f) => `<a href="/api/runs/${id}/files/${f}" download="${id}-${f}">${f}</a>`).join(" · ");
}

async function stop() {
  if (run) await api("POST", `/api/runs/${run.id}/stop`).catch(showError);
}

function drawChart() {
  const svg = $("#chart");
  const pts = chart.incumbent.concat(chart.bound);
  if (!pts.length) {
    svg.innerHTML = `<text x="10" y="20" font-size="12" fill="#888">incumbent and bound over time</text>`;
    return;
  }
  const t1 = Math.max(...pts.map((p) => p[0]), 1e-3);
  let lo = Math.min(...pts.map((p) => p[1]));
  let hi = Math.max(...pts.map((p) => p[1]));
  if (hi - lo < 1e-9) { lo -= 1; hi += 1; }
  const x = (t) => 40 + (590 * t) / t1;
  const y = (v) => 135 - (120 * (v - lo)) / (hi - lo);
  const line = (ps, colour) => ps.length ? `<polyline fill="none" stroke="${colour}" stroke-width="2" points="${ps.map((p) => `${x(p[0]).toFixed(1)},${y(p[1]).toFixed(1)}`).join(" ")}"/>` : "";
  svg.innerHTML =
    `<text x="4" y="14" font-size="11">${hi.toFixed(2)}</text><text x="4" y="138" font-size="11">${lo.toFixed(2)}</text>` +
    `<text x="560" y="148" font-size="11">${t1.toFixed(1)} s</text>` +
    `<text x="60" y="14" font-size="11" fill="#c0392b">incumbent</text><text x="140" y="14" font-size="11" fill="#2471a3">bound</text>` +
    line(chart.incumbent, "#c0392b") + line(chart.bound, "#2471a3");
}

// --- runs and comparison ---------------------------------------------------------------------

async function loadRuns() {
  const data = await api("GET", "/api/runs");
  const ul = $("#runs");
  ul.innerHTML = "";
  // Runs of a site's urban methods are listed with their site (sites.js).
  for (const r of data.runs.slice().reverse().filter((r) => !(r.settings && r.settings.kind === "urban"))) {
    const li = document.createElement("li");
    li.dataset.id = r.id;
    const obj = r.summary && r.summary.objective != null ? r.summary.objective.toFixed(4) : "-";
    li.innerHTML = `<input type="checkbox"> <a></a>`;
    li.querySelector("input").value = r.id;
    li.querySelector("a").textContent = `${r.id} ${r.name} · ${r.state} · ${obj}`;
    li.querySelector("a").onclick = () => showRun(r);
    ul.appendChild(li);
  }
}

function showRun(r) {
  resetResult();
  $("#picture").innerHTML = `<img alt="run ${r.id}" src="/api/runs/${r.id}/files/network.svg">`;
  showSummary(r.summary);
  showExports(r.id);
  $("#run-state").textContent = `run ${r.id}: ${r.state}`;
}

async function compare() {
  const ids = $$("#runs input:checked").map((i) => i.value);
  try {
    const data = await api("GET", "/api/compare?ids=" + ids.join(","));
    const view = $("#compare-view");
    const imgs = data.runs.map((r) => `<figure><img alt="" src="/api/runs/${r.id}/files/network.svg"><figcaption>${r.id}</figcaption></figure>`).join("");
    const head = `<tr><th></th>${data.runs.map((r) => `<th>${r.id}</th>`).join("")}</tr>`;
    const rows = data.rows.map((row) => `<tr>${row.map((c, i) => (i ? `<td></td>` : `<th></th>`)).join("")}</tr>`).join("");
    view.innerHTML = `<h2>Compare</h2><div class="side">${imgs}</div><table>${head}${rows}</table>`;
    // Cell text set as text, never markup.
    const trs = view.querySelectorAll("table tr");
    data.rows.forEach((row, i) => row.forEach((c, j) => (trs[i + 1].children[j].textContent = c)));
    view.scrollIntoView();
  } catch (e) {
    showError(e);
  }
}

// --- city, traffic, layout, field and grow outputs (kind: path) ------------------------------

async function loadOutputs() {
  const data = await api("GET", "/api/outputs");
  const ul = $("#outputs");
  ul.innerHTML = "";
  for (const o of data.outputs) {
    const li = document.createElement("li");
    li.dataset.path = o.path;
    li.innerHTML = "<a></a>";
    li.querySelector("a").textContent = `${o.kind}: ${o.path}`;
    li.querySelector("a").onclick = () => showOutput(o);
    ul.appendChild(li);
  }
}

// A city picture (streets by level, each level toggled), a traffic picture (streets coloured
// by volume, travel times, a comparison) or any other output's picture (layout, field, grow),
// as its command drew it.
async function showOutput(o) {
  const r = await fetch("/api/output?path=" + encodeURIComponent(o.path));
  if (!r.ok) return showError(await r.json());
  view = null;
  $("#picture").innerHTML = await r.text();
  const levels = $("#levels");
  levels.innerHTML = "";
  const present = new Set($$("#picture [data-level]").map((e) => e.dataset.level));
  for (const level of Array.from(present).sort()) {
    const label = document.createElement("label");
    label.innerHTML = `<input type="checkbox" checked data-level-toggle="${level}"> level ${level}`;
    label.querySelector("input").onchange = (e) => {
      for (const el of $$(`#picture [data-level="${level}"]`)) el.style.display = e.target.checked ? "" : "none";
    };
    levels.appendChild(label);
  }
}

// --- wiring ----------------------------------------------------------------------------------

for (const input of $$("[data-field]")) {
  input.addEventListener("change", () => edit(input.dataset.field, fieldValue(input)));
}
for (const s of $$("[data-slider]")) {
  s.addEventListener("change", () => edit(s.dataset.slider, Number(s.value)));
}
$("#new").onclick = newSpec;
$("#solve").onclick = solve;
$("#stop").onclick = stop;
$("#save").onclick = async () => {
  try {
    const r = await api("POST", "/api/save", { path: $("#save-path").value, spec });
    $("#saved").textContent = "saved " + r.saved;
    loadSpecs();
  } catch (e) {
    showError(e);
  }
};
$("#compare").onclick = compare;
drawChart();
loadSpecs();
loadRuns();
loadOutputs();
