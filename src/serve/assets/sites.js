// netspec serve: real sites. An OpenStreetMap extract under --root drawn as vector layers
// (what the view shows, asked of the server as the view moves), a box or polygon drawn on it made
// into a site by the server (`netspec site`), the urban methods run on the site with their output
// streamed, and every design beside the real streets at one scale (linked maps, statistics,
// orientation roses, distance to the map). Plain JavaScript over Leaflet; no tiles.
"use strict";

const sites = {
  extract: null, // the extract shown: its path under --root
  site: null, // the site open: its name
  map: null,
  layers: null, // the extract's features in view
  siteLayer: null, // the open site's region and real streets
  shape: null, // the drawn box or polygon (a Leaflet layer)
  ring: null, // the drawn polygon, [lon, lat] points (null for a box)
  excluded: new Set(), // OSM ids of major roads left out
  drawing: null, // "box" or "polygon" while drawing
  featuresDrawn: 0, // feature requests answered (the browser test waits on it)
  minis: [], // the comparison's maps, linked
  syncing: false,
  streams: {}, // run id → EventSource
  compared: 0, // comparisons drawn (the browser test waits on it)
};

const LEVEL_STYLE = { 1: ["#252525", 3.5], 2: ["#d94801", 2.6], 3: ["#2171b5", 1.6], 4: ["#41ab5d", 1.2] };

function siteError(err) {
  $("#site-error").textContent = err ? (err.field ? err.field + ": " : "") + err.message : "";
}

function showTab(which) {
  $("#networks").hidden = which !== "networks";
  $("#compare-view").hidden = which !== "networks";
  $("#sites-view").hidden = which !== "sites";
  $("#tab-networks").classList.toggle("current", which === "networks");
  $("#tab-sites").classList.toggle("current", which === "sites");
  if (which === "sites") {
    ensureMap();
    sites.map.invalidateSize();
    loadExtracts();
  }
}

function ensureMap() {
  if (sites.map) return;
  sites.map = L.map("map", { preferCanvas: true, zoomSnap: 0.25, attributionControl: true });
  sites.map.attributionControl.setPrefix('<a href="/assets/LICENSE-leaflet.txt">Leaflet</a>');
  sites.map.attributionControl.addAttribution("© OpenStreetMap contributors, ODbL");
  sites.map.setView([0, 0], 2);
  sites.map.on("moveend", () => refreshFeatures());
  sites.map.on("mousedown", boxStart);
  sites.map.on("click", polygonClick);
  sites.map.on("dblclick", polygonEnd);
}

// --- extracts and their features --------------------------------------------------------------

async function loadExtracts() {
  const data = await api("GET", "/api/extracts");
  const ul = $("#extracts");
  ul.innerHTML = "";
  for (const e of data.extracts) {
    const li = document.createElement("li");
    li.dataset.path = e.path;
    li.textContent = `${e.path} (${(e.bytes / 1e6).toFixed(2)} MB)`;
    li.classList.toggle("current", e.path === sites.extract);
    li.onclick = () => openExtract(e.path);
    ul.appendChild(li);
  }
  const su = $("#sites");
  su.innerHTML = "";
  for (const name of data.sites) {
    const li = document.createElement("li");
    li.dataset.site = name;
    li.textContent = name;
    li.classList.toggle("current", name === sites.site);
    li.onclick = () => openSite(name);
    su.appendChild(li);
  }
}

async function openExtract(path) {
  siteError(null);
  try {
    const info = await api("GET", "/api/extract?path=" + encodeURIComponent(path));
    sites.extract = path;
    $$("#extracts li").forEach((li) => li.classList.toggle("current", li.dataset.path === path));
    const [w, s, e, n] = info.extent;
    sites.map.fitBounds([[s, w], [n, e]]);
    ["#draw-box", "#draw-polygon", "#make-site"].forEach((id) => ($(id).disabled = false));
    await refreshFeatures();
  } catch (e) {
    siteError(e);
  }
}

function styleOf(f) {
  const p = f.properties;
  if (p.layer === "water") return { color: "#4a90c8", weight: 1, fillColor: "#a6cee3", fillOpacity: 0.7 };
  if (p.layer === "park") return { color: "#66a61e", weight: 1, fillColor: "#b2df8a", fillOpacity: 0.6 };
  if (p.layer === "rail") return { color: "#888", weight: 1, fillColor: "#ccc", fillOpacity: 0.5 };
  const [color, weight] = LEVEL_STYLE[p.level] || ["#999", 1];
  const out = sites.excluded.has(p.osm_id);
  return { color: out ? "#c0392b" : color, weight, dashArray: out ? "6 6" : null, opacity: 0.9 };
}

async function refreshFeatures() {
  if (!sites.extract || !sites.map) return;
  const b = sites.map.getBounds();
  const bbox = [b.getWest(), b.getSouth(), b.getEast(), b.getNorth()].map((x) => x.toFixed(6)).join(",");
  try {
    const gj = await api("GET", `/api/extract/features?path=${encodeURIComponent(sites.extract)}&bbox=${bbox}`);
    if (sites.layers) sites.layers.remove();
    sites.layers = L.geoJSON(gj, {
      style: styleOf,
      onEachFeature: (f, layer) => {
        if (f.properties.major) {
          layer.on("click", (ev) => {
            if (sites.drawing) return;
            L.DomEvent.stopPropagation(ev);
            const id = f.properties.osm_id;
            if (sites.excluded.has(id)) sites.excluded.delete(id);
            else sites.excluded.add(id);
            layer.setStyle(styleOf(f));
          });
        }
      },
    }).addTo(sites.map);
    if (sites.shape) sites.shape.bringToFront();
    sites.featuresDrawn += 1;
  } catch (e) {
    siteError(e);
  }
}

// --- drawing a box or a polygon ---------------------------------------------------------------

function startDrawing(kind) {
  sites.drawing = kind;
  sites.ring = kind === "polygon" ? [] : null;
  if (sites.shape) sites.shape.remove();
  sites.shape = null;
  $("#map").classList.add("drawing");
  sites.map.dragging.disable();
  sites.map.doubleClickZoom.disable();
}

function stopDrawing() {
  sites.drawing = null;
  $("#map").classList.remove("drawing");
  sites.map.dragging.enable();
  sites.map.doubleClickZoom.enable();
}

function boxStart(ev) {
  if (sites.drawing !== "box") return;
  const start = ev.latlng;
  const move = (e) => {
    const bounds = L.latLngBounds(start, e.latlng);
    if (sites.shape) sites.shape.setBounds(bounds);
    else sites.shape = L.rectangle(bounds, { color: "#e67e22", weight: 2, fill: false }).addTo(sites.map);
  };
  const up = (e) => {
    sites.map.off("mousemove", move);
    sites.map.off("mouseup", up);
    move(e);
    stopDrawing();
    const b = sites.shape.getBounds();
    $("#site-bbox").value = [b.getWest(), b.getSouth(), b.getEast(), b.getNorth()].map((x) => x.toFixed(6)).join(",");
  };
  sites.map.on("mousemove", move);
  sites.map.on("mouseup", up);
}

function polygonClick(ev) {
  if (sites.drawing !== "polygon") return;
  sites.ring.push([ev.latlng.lng, ev.latlng.lat]);
  const latlngs = sites.ring.map(([x, y]) => [y, x]);
  if (sites.shape) sites.shape.setLatLngs(latlngs);
  else sites.shape = L.polygon(latlngs, { color: "#e67e22", weight: 2, fill: false }).addTo(sites.map);
}

function polygonEnd() {
  if (sites.drawing !== "polygon") return;
  stopDrawing();
  // The double click's second click added the last point twice.
  const r = sites.ring;
  while (r.length > 1 && r[r.length - 1][0] === r[r.length - 2][0] && r[r.length - 1][1] === r[r.length - 2][1]) r.pop();
  $("#site-bbox").value = `polygon of ${r.length} points`;
}

function typedBox() {
  const v = $("#site-bbox").value.split(",").map(Number);
  if (v.length !== 4 || v.some((x) => !Number.isFinite(x))) return;
  sites.ring = null;
  if (sites.shape) sites.shape.remove();
  sites.shape = L.rectangle([[v[1], v[0]], [v[3], v[2]]], { color: "#e67e22", weight: 2, fill: false }).addTo(sites.map);
}

async function makeSite() {
  siteError(null);
  const body = {
    extract: sites.extract,
    name: $("#site-name").value.trim(),
    holes: $$("[data-hole]").filter((c) => c.checked).map((c) => c.dataset.hole),
    major: $$("[data-major]").filter((c) => c.checked).map((c) => c.dataset.major),
    exclude: Array.from(sites.excluded),
  };
  if (sites.ring && sites.ring.length) body.polygon = sites.ring;
  else {
    const v = $("#site-bbox").value.split(",").map(Number);
    if (v.length !== 4 || v.some((x) => !Number.isFinite(x))) {
      siteError({ field: "bbox", message: "draw a box or a polygon, or type W,S,E,N" });
      return;
    }
    body.bbox = v;
  }
  $("#make-site").disabled = true;
  try {
    const s = await api("POST", "/api/sites", body);
    await loadExtracts();
    await openSite(s.name);
  } catch (e) {
    siteError(e);
  } finally {
    $("#make-site").disabled = false;
  }
}

// --- a site, its runs and its comparison --------------------------------------------------------

async function openSite(name) {
  siteError(null);
  let data;
  try {
    data = await api("GET", "/api/sites/" + encodeURIComponent(name));
  } catch (e) {
    siteError(e);
    return;
  }
  sites.site = name;
  $$("#sites li").forEach((li) => li.classList.toggle("current", li.dataset.site === name));
  $("#site-title").textContent = "Site " + name;
  const props = data.site.features[0].properties;
  $("#site-summary").textContent = `${props.source} · holes: ${props.holes || "none"} · ${props.attribution}`;
  $("#methods").hidden = false;
  if (sites.siteLayer) sites.siteLayer.remove();
  sites.siteLayer = L.layerGroup([
    L.geoJSON(data.site, { style: () => ({ color: "#e67e22", weight: 2, fill: false }) }),
  ]).addTo(sites.map);
  sites.map.fitBounds(L.geoJSON(data.site.features[0]).getBounds());
  showSiteRuns(data.runs || []);
  showComparison(data.compare);
}

function showSiteRuns(runs) {
  const ul = $("#site-runs");
  ul.innerHTML = "";
  for (const r of runs.slice().sort((a, b) => (a.id < b.id ? 1 : -1))) {
    const li = document.createElement("li");
    li.dataset.id = r.id;
    li.dataset.state = r.state;
    li.innerHTML = `<b></b> <span class="state"></span> <button class="cancel">Cancel</button> <button class="resume">Resume</button> <span class="files"></span><span class="last"></span>`;
    li.querySelector("b").textContent = `${r.id} ${r.settings.method}`;
    li.querySelector(".state").textContent = r.state;
    li.querySelector(".last").textContent = r.error || "";
    li.querySelector(".cancel").hidden = !["queued", "running"].includes(r.state);
    li.querySelector(".resume").hidden = ["queued", "running"].includes(r.state);
    li.querySelector(".resume").textContent = r.settings.method === "city" ? "Resume" : "Run again";
    li.querySelector(".cancel").onclick = () => api("POST", `/api/runs/${r.id}/stop`).catch(siteError);
    li.querySelector(".resume").onclick = async () => {
      try {
        await api("POST", `/api/runs/${r.id}/resume`);
        follow(r.id);
      } catch (e) {
        siteError(e);
      }
    };
    const files = { layout: ["layout.json", "layout.geojson"], grow: ["network.json", "network.geojson"], city: ["city.json", "streets.geojson"], traffic: ["comparison.md", "comparison.json"] }[r.settings.method] || [];
    if (r.state === "finished") {
      li.querySelector(".files").innerHTML = files.map((f) => `<a href="/api/runs/${r.id}/out/${f}">${f}</a>`).join(" ");
    }
    ul.appendChild(li);
    if (["queued", "running"].includes(r.state)) follow(r.id);
  }
}

function methodBody(method) {
  const body = { method };
  for (const input of $$(`[data-m^="${method}."]`)) {
    const key = input.dataset.m.split(".")[1];
    if (input.value === "") continue;
    body[key] = input.type === "number" ? Number(input.value) : input.value;
  }
  return body;
}

async function runMethod(method) {
  siteError(null);
  try {
    const r = await api("POST", `/api/sites/${encodeURIComponent(sites.site)}/runs`, methodBody(method));
    await refreshSite();
    follow(r.id);
  } catch (e) {
    siteError(e);
  }
}

async function refreshSite() {
  const data = await api("GET", "/api/sites/" + encodeURIComponent(sites.site));
  showSiteRuns(data.runs || []);
  showComparison(data.compare);
}

function follow(id) {
  if (sites.streams[id]) return;
  const es = new EventSource(`/api/runs/${id}/events`);
  sites.streams[id] = es;
  es.onmessage = (m) => {
    const ev = JSON.parse(m.data);
    const li = $(`#site-runs li[data-id="${id}"]`);
    if (li && ev.kind === "line") li.querySelector(".last").textContent = ev.text;
    if (li && ev.kind === "started") li.querySelector(".state").textContent = "running";
    if (ev.kind === "done" || ev.kind === "failed") {
      es.close();
      delete sites.streams[id];
      refreshSite().catch(siteError);
    }
  };
  es.onerror = () => {
    es.close();
    delete sites.streams[id];
  };
}

function fmt(x, k = 1) {
  return x == null ? "–" : Number(x).toFixed(k);
}

function roseSvg(bins) {
  const r = 70, c = 80;
  const max = Math.max(...bins, 0);
  let paths = "";
  bins.forEach((w, k) => {
    if (w <= 0 || max <= 0) return;
    const rr = r * Math.sqrt(w / max);
    const a0 = ((k - 0.5) * 10 * Math.PI) / 180, a1 = ((k + 0.5) * 10 * Math.PI) / 180;
    const p = (a) => `${(c + rr * Math.sin(a)).toFixed(2)},${(c - rr * Math.cos(a)).toFixed(2)}`;
    paths += `<path d="M${c},${c} L${p(a0)} A${rr.toFixed(2)},${rr.toFixed(2)} 0 0,1 ${p(a1)} Z" fill="#2171b5" fill-opacity="0.8"/>`;
  });
  return `<svg class="rose" width="160" height="160" viewBox="0 0 160 160"><circle cx="${c}" cy="${c}" r="${r}" fill="#f7f7f7" stroke="#ccc"/>${paths}<text x="${c}" y="9" font-size="9" text-anchor="middle">N</text></svg>`;
}

function linkMaps() {
  for (const m of sites.minis) {
    m.on("move", () => {
      if (sites.syncing) return;
      sites.syncing = true;
      for (const o of sites.minis) if (o !== m) o.setView(m.getCenter(), m.getZoom(), { animate: false });
      sites.syncing = false;
    });
  }
}

function showComparison(compare) {
  for (const m of sites.minis) m.remove();
  sites.minis = [];
  const grid = $("#compare-grid");
  grid.innerHTML = "";
  $("#compare-table").innerHTML = "";
  $("#site-exports").innerHTML = "";
  $("#compare-title").hidden = !compare;
  if (!compare) return;
  let bounds = null;
  for (const d of compare.designs) {
    const panel = document.createElement("div");
    panel.className = "panel";
    panel.dataset.label = d.label;
    const s = d.stats;
    const dist = d.distance ? `distance to the map ${fmt(d.distance.mean, 2)}` : "the real streets";
    panel.innerHTML = `<b></b><div class="mini"></div><div class="numbers"></div>`;
    panel.querySelector("b").textContent = d.label;
    panel.querySelector(".numbers").textContent =
      `${fmt(s.street_density_km / 1000)} km/km² · ${fmt(s.clean_intersection_density_km)} intersections/km² · ` +
      `${fmt(s.dead_end_density_km)} dead-ends/km² · φ ${fmt(s.orientation_order, 2)} · ${dist}`;
    panel.insertAdjacentHTML("beforeend", roseSvg(s.orientation_bins));
    grid.appendChild(panel);
    const m = L.map(panel.querySelector(".mini"), { preferCanvas: true, zoomSnap: 0.25, attributionControl: false });
    const layer = L.geoJSON(d.streets, {
      style: (f) => {
        const [color, weight] = LEVEL_STYLE[f.properties.level] || ["#999", 1];
        return { color, weight: weight * 0.6, opacity: 0.9 };
      },
    }).addTo(m);
    const b = layer.getBounds();
    if (b.isValid()) bounds = bounds ? bounds.extend(b) : L.latLngBounds(b.getSouthWest(), b.getNorthEast());
    sites.minis.push(m);
  }
  if (bounds) for (const m of sites.minis) m.fitBounds(bounds, { animate: false });
  linkMaps();
  const cols = [
    ["street km/km²", (d) => fmt(d.stats.street_density_km / 1000)],
    ["intersections /km²", (d) => fmt(d.stats.intersection_density_km)],
    ["clean intersections /km²", (d) => fmt(d.stats.clean_intersection_density_km)],
    ["dead-ends /km²", (d) => fmt(d.stats.dead_end_density_km)],
    ["streets per node", (d) => fmt(d.stats.streets_per_node_avg, 2)],
    ["circuity", (d) => fmt(d.stats.circuity_avg, 3)],
    ["order φ", (d) => fmt(d.stats.orientation_order, 2)],
    ["blocks /km²", (d) => fmt(d.stats.blocks_per_km2)],
    ["block perimeter (m)", (d) => fmt(d.stats.block_perimeter_mean, 0)],
    ["undesirable parcels", (d) => (d.parcels ? `${d.parcels.undesirable} of ${d.parcels.parcels}` : "–")],
    ["distance to the map", (d) => (d.distance ? fmt(d.distance.mean, 2) : "reference")],
    ["SUMO travel time (s)", (d) => (d.traffic ? fmt(d.traffic.travel_time_mean) : "–")],
  ];
  const t = $("#compare-table");
  t.innerHTML = `<tr><th>design</th>${cols.map((c) => `<th>${c[0]}</th>`).join("")}</tr>` +
    compare.designs.map((d) => `<tr data-label="${d.label}"><td>${d.label}</td>${cols.map((c) => `<td>${c[1](d)}</td>`).join("")}</tr>`).join("");
  const site = encodeURIComponent(sites.site);
  $("#site-exports").innerHTML = `Export: <a href="/api/sites/${site}/compare.csv">comparison (CSV)</a> · ` +
    compare.designs.map((d) => `<a href="/api/sites/${site}/designs/${encodeURIComponent(d.label)}.geojson">${d.label}.geojson</a>`).join(" · ");
  sites.compared += 1;
}

// --- uploads ------------------------------------------------------------------------------------

/// A GeoJSON file is read here, as the region (its first Polygon's outline); an extract is sent.
async function upload(file) {
  if (file.name.endsWith(".geojson") || file.name.endsWith(".json")) {
    try {
      const gj = JSON.parse(await file.text());
      const feats = gj.type === "FeatureCollection" ? gj.features : [gj.type === "Feature" ? gj : { geometry: gj }];
      const poly = feats.map((f) => f.geometry).find((g) => g && g.type === "Polygon");
      if (!poly) throw Object.assign(new Error(`${file.name} has no Polygon to take as the region`), { field: "upload" });
      sites.ring = poly.coordinates[0].slice(0, -1);
      if (sites.shape) sites.shape.remove();
      sites.shape = L.polygon(sites.ring.map(([x, y]) => [y, x]), { color: "#e67e22", weight: 2, fill: false }).addTo(sites.map);
      sites.map.fitBounds(sites.shape.getBounds());
      $("#site-bbox").value = `polygon of ${sites.ring.length} points (${file.name})`;
    } catch (e) {
      siteError(e.field ? e : { field: "upload", message: `${file.name}: ${e.message}` });
    }
    return;
  }
  $("#upload-state").textContent = `sending ${file.name} (${(file.size / 1e6).toFixed(1)} MB)…`;
  try {
    const r = await fetch("/api/upload?name=" + encodeURIComponent(file.name), { method: "POST", body: file });
    const data = await r.json().catch(() => ({ error: r.statusText }));
    if (!r.ok) throw Object.assign(new Error(data.error || r.statusText), { field: data.field });
    $("#upload-state").textContent = `kept as ${data.path}`;
    await loadExtracts();
    if (!data.path.endsWith(".geojson")) await openExtract(data.path);
  } catch (e) {
    $("#upload-state").textContent = "";
    siteError(e);
  }
}

// --- wiring -------------------------------------------------------------------------------------

$("#tab-networks").onclick = () => showTab("networks");
$("#tab-sites").onclick = () => showTab("sites");
$("#draw-box").onclick = () => startDrawing("box");
$("#draw-polygon").onclick = () => startDrawing("polygon");
$("#site-bbox").addEventListener("change", typedBox);
$("#make-site").onclick = makeSite;
$("#upload").addEventListener("change", (e) => e.target.files[0] && upload(e.target.files[0]));
for (const b of $$("[data-method]")) b.onclick = () => runMethod(b.dataset.method);
if (location.hash === "#sites") showTab("sites");
