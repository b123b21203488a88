// The operator console's page: draws what the console's System Commander knows (pushed
// over a WebSocket) and sends the operator's commands back as JSON. All JAUS logic is in
// the console (jaus::stock::commander::Station); this page only draws and asks.
"use strict";

const SVG = "http://www.w3.org/2000/svg";
const $ = (id) => document.getElementById(id);

const ocu = {
  view: null,            // the last view
  trails: new Map(),     // subsystem id -> [[x, y], ...]
  poseCounts: new Map(), // subsystem id -> pose_count seen
  selected: null,        // selected subsystem id
  draft: [],             // [{x, y}] waypoints clicked, not sent yet
  mapView: { auto: true, cx: 0, cy: 0, mpp: 0.1 }, // the map's centre (m) and metres per pixel
  layers: { background: null, tiles: null },       // the map's background layers (GET /api/map)
  lastMessage: 0,        // Date.now() of the last WebSocket message
  noticesSeen: 0,
  log: [],
  stats: { latencies: [], draw: [], push: [], frames: 0 }, // pose received by the console -> drawn; time to draw a view (ms)
  socket: null,
};
window.ocu = ocu;

const TRAIL_MAX = 3000;
const LOG_ROWS = 300;
const STALE_LINK_MS = 2000;

// ---- WebSocket -------------------------------------------------------------------------

function connect() {
  const ws = new WebSocket(`ws://${location.host}/ws`);
  ocu.socket = ws;
  ws.onmessage = (ev) => {
    ocu.lastMessage = Date.now();
    let msg;
    try { msg = JSON.parse(ev.data); } catch (e) { return; }
    if (msg.type === "hello") {
      ocu.trails.clear();
      ocu.poseCounts.clear();
      for (const s of msg.view.subsystems || []) {
        ocu.trails.set(s.id, (s.trail || []).slice(-TRAIL_MAX));
        ocu.poseCounts.set(s.id, s.pose_count);
      }
      update(msg.view, []);
    } else if (msg.type === "view") {
      // Console published -> page received, ms (the rest of a pose's latency is the
      // console's own time and the drawing).
      ocu.stats.push.push(Date.now() - msg.published_unix_ms);
      if (ocu.stats.push.length > 10000) ocu.stats.push.shift();
      update(msg.view, msg.log || []);
    } else if (msg.type === "error") {
      localNotice(msg.text);
    }
  };
  ws.onclose = () => { ocu.socket = null; setTimeout(connect, 1000); };
  ws.onerror = () => ws.close();
}

function send(cmd) {
  if (!ocu.socket || ocu.socket.readyState !== WebSocket.OPEN) {
    localNotice("not connected to the console: command not sent");
    return;
  }
  ocu.socket.send(JSON.stringify(cmd));
}

// A notice of the page's own (shown until the next view replaces the list).
const localNotices = [];
function localNotice(text) {
  localNotices.push({ seq: 0, error: true, text: "page: " + text, unix_ms: Date.now() });
  if (localNotices.length > 20) localNotices.shift();
  drawNotices();
}

// ---- View ----------------------------------------------------------------------------

function update(view, log) {
  const t0 = performance.now();
  ocu.view = view;
  const changed = [];
  for (const s of view.subsystems) {
    const seen = ocu.poseCounts.get(s.id) || 0;
    if (s.pose && s.pose_count > seen) {
      const t = ocu.trails.get(s.id) || [];
      t.push([s.pose.x, s.pose.y]);
      if (t.length > TRAIL_MAX) t.splice(0, t.length - TRAIL_MAX);
      ocu.trails.set(s.id, t);
      ocu.poseCounts.set(s.id, s.pose_count);
      changed.push(s.pose.received_unix_ms);
    }
  }
  if (ocu.selected === null || !view.subsystems.some((s) => s.id === ocu.selected)) {
    const v = view.subsystems.find((s) => s.pose) || null;
    ocu.selected = v ? v.id : null;
  }
  drawTree();
  drawMap();
  drawSide();
  drawNotices();
  appendLog(log);
  const drawn = Date.now();
  for (const at of changed) {
    ocu.stats.latencies.push(drawn - at);
    if (ocu.stats.latencies.length > 10000) ocu.stats.latencies.shift();
  }
  ocu.stats.draw.push(performance.now() - t0);
  if (ocu.stats.draw.length > 10000) ocu.stats.draw.shift();
  ocu.stats.frames++;
}

function selectedView() {
  return ocu.view && ocu.view.subsystems.find((s) => s.id === ocu.selected);
}

function el(tag, attrs, text) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, v);
  if (text !== undefined) e.textContent = text;
  return e;
}

function drawTree() {
  const tree = $("tree");
  tree.replaceChildren();
  for (const s of ocu.view.subsystems) {
    const div = el("div", { class: "tree-ss" + (s.id === ocu.selected ? " selected" : ""), id: `ss-${s.id}` });
    const title = el("div", { class: "title" }, `Subsystem ${s.id}${s.name ? " — " + s.name : ""}`);
    if (s.stale) title.append(el("span", { class: "badge stale" }, "stale"));
    if (s.emergency) title.append(el("span", { class: "badge emergency" }, "EMERGENCY"));
    title.onclick = () => { ocu.selected = s.id; update(ocu.view, []); };
    div.append(title);
    for (const n of s.nodes) {
      div.append(el("div", { class: "tree-node" }, `node ${n.id}${n.name ? " — " + n.name : ""}`));
      for (const c of n.components) {
        const row = el("div", { class: "tree-comp", "data-address": c.address });
        row.append(el("span", {}, `${c.address} ${c.name}`));
        if (c.state) row.append(el("span", { class: "state " + c.state }, c.state));
        if (c.held) row.append(el("span", { class: "held" }, "held"));
        else if (c.keeping !== null && c.keeping !== undefined) row.append(el("span", { class: "ctl" }, "asking…"));
        if (c.controller) row.append(el("span", { class: "ctl" }, `ctl ${c.controller} (auth ${c.controller_authority})`));
        div.append(row);
      }
    }
    tree.append(div);
  }
}

// ---- Map -----------------------------------------------------------------------------
//
// The map's frame is metres east (x) and north (y) of the console's origin; SVG y is
// minus the map's y (north up). The view is a centre and a scale (metres per CSS pixel):
// automatic (it keeps every vehicle, its whole trail, its route, the world-model objects
// and the clicked points in view) until the operator drags or turns the wheel; then it
// stays where the operator put it until "Fit".

function grow(ext, x, y) {
  if (!ext) return [x, y, x, y];
  return [Math.min(ext[0], x), Math.min(ext[1], y), Math.max(ext[2], x), Math.max(ext[3], y)];
}

// What the automatic view keeps in sight: [west, south, east, north], or null.
function contentExtent() {
  let ext = null;
  for (const s of (ocu.view && ocu.view.subsystems) || []) {
    if (s.pose) ext = grow(ext, s.pose.x, s.pose.y);
    for (const p of ocu.trails.get(s.id) || []) ext = grow(ext, p[0], p[1]);
    for (const p of s.route) ext = grow(ext, p[0], p[1]);
    for (const o of s.objects) for (const p of o.points) ext = grow(ext, p[0], p[1]);
  }
  for (const p of ocu.draft) ext = grow(ext, p.x, p.y);
  return ext;
}

function mapSize() {
  const r = $("map").getBoundingClientRect();
  return [Math.max(r.width, 1), Math.max(r.height, 1)];
}

// The automatic view: the content (else the background image, else 20 m round the
// origin) with a margin, at least 40 m across.
function autoView(W, H) {
  const bg = ocu.layers.background;
  const ext = contentExtent() || (bg && bg.extent) || [-10, -10, 10, 10];
  const margin = Math.max(5, 0.05 * Math.max(ext[2] - ext[0], ext[3] - ext[1]));
  const w = Math.max(40, ext[2] - ext[0] + 2 * margin), h = Math.max(40, ext[3] - ext[1] + 2 * margin);
  return { cx: (ext[0] + ext[2]) / 2, cy: (ext[1] + ext[3]) / 2, mpp: Math.max(w / W, h / H) };
}

// The view now: [west, south, width, height] in metres, metres per pixel.
function currentView() {
  const [W, H] = mapSize();
  const v = ocu.mapView;
  if (v.auto) Object.assign(v, autoView(W, H));
  const w = W * v.mpp, h = H * v.mpp;
  return [v.cx - w / 2, v.cy - h / 2, w, h, v.mpp];
}

// 1, 2 or 5 times a power of ten, at most `target`.
function roundLength(target) {
  const p = Math.pow(10, Math.floor(Math.log10(target)));
  return Number(([5, 2, 1].map((k) => k * p).find((l) => l <= target) || p).toPrecision(3));
}

function svg(tag, attrs) {
  const e = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, v);
  return e;
}

function drawMap() {
  const map = $("map");
  const [x0, y0, w, h, px] = currentView();
  map.setAttribute("viewBox", `${x0} ${-(y0 + h)} ${w} ${h}`);
  // Strokes and text are sized in screen pixels (style.css: calc(var(--px) * Npx)).
  map.style.setProperty("--px", px);
  map.classList.toggle("stale", !linkUp());
  $("fit").classList.toggle("manual", !ocu.mapView.auto);
  $("view-mode").textContent = ocu.mapView.auto ? "automatic view" : "your view (Fit: automatic)";
  drawTiles(x0, y0, w, h, px);
  const grid = $("grid");
  grid.replaceChildren();
  const step = roundLength(w / 6);
  for (let x = Math.ceil(x0 / step) * step; x <= x0 + w; x += step)
    grid.append(svg("line", { x1: x, x2: x, y1: -(y0 + h), y2: -y0, class: Math.abs(x) < step / 2 ? "grid-axis" : "grid-line" }));
  for (let y = Math.ceil(y0 / step) * step; y <= y0 + h; y += step)
    grid.append(svg("line", { x1: x0, x2: x0 + w, y1: -y, y2: -y, class: Math.abs(y) < step / 2 ? "grid-axis" : "grid-line" }));
  drawScale(x0, y0, w, h, px);
  if (!ocu.view) return;
  const objects = $("objects"), routes = $("routes"), trails = $("trails"), vehicles = $("vehicles");
  objects.replaceChildren(); routes.replaceChildren(); trails.replaceChildren(); vehicles.replaceChildren();
  for (const s of ocu.view.subsystems) {
    for (const o of s.objects) {
      if (o.points.length === 1) {
        objects.append(svg("circle", { cx: o.points[0][0], cy: -o.points[0][1], r: Math.max(o.buffer, 0.3, 3 * px), class: "object", "data-id": o.id }));
      } else {
        objects.append(svg("polygon", { points: o.points.map((p) => `${p[0]},${-p[1]}`).join(" "), class: "object", "data-id": o.id }));
      }
    }
    if (s.route.length) {
      const pts = s.route.map((p) => `${p[0]},${-p[1]}`).join(" ");
      routes.append(svg("polyline", { points: pts, class: "route" }));
      for (const p of s.route) routes.append(svg("circle", { cx: p[0], cy: -p[1], r: Math.max(0.25, 3 * px), class: "route-point" }));
    }
    const t = ocu.trails.get(s.id) || [];
    if (t.length > 1) trails.append(svg("polyline", { points: t.map((p) => `${p[0]},${-p[1]}`).join(" "), class: "trail" }));
    if (s.pose) {
      const cls = ["vehicle"];
      if (s.id === ocu.selected) cls.push("selected");
      if (s.stale) cls.push("stale");
      if (s.emergency) cls.push("emergency");
      const g = svg("g", { id: `vehicle-${s.id}`, class: cls.join(" "), "data-x": s.pose.x.toFixed(3), "data-y": s.pose.y.toFixed(3) });
      const r = Math.max(0.6, 6 * px);
      g.append(svg("circle", { cx: s.pose.x, cy: -s.pose.y, r }));
      if (s.pose.yaw !== null && s.pose.yaw !== undefined) {
        // Yaw 0 is north, clockwise positive.
        const l = 2 * r;
        g.append(svg("line", { x1: s.pose.x, y1: -s.pose.y, x2: s.pose.x + l * Math.sin(s.pose.yaw), y2: -(s.pose.y + l * Math.cos(s.pose.yaw)) }));
      }
      const label = svg("text", { x: s.pose.x + 1.3 * r, y: -s.pose.y - 1.3 * r });
      label.textContent = s.name || `subsystem ${s.id}`;
      g.append(label);
      vehicles.append(g);
    }
  }
  const draft = $("draft");
  draft.replaceChildren();
  const sel = selectedView();
  if (ocu.draft.length) {
    const start = sel && sel.pose ? [[sel.pose.x, sel.pose.y]] : [];
    const pts = start.concat(ocu.draft.map((p) => [p.x, p.y]));
    draft.append(svg("polyline", { points: pts.map((p) => `${p[0]},${-p[1]}`).join(" "), class: "draft" }));
    ocu.draft.forEach((p, i) => {
      draft.append(svg("circle", { cx: p.x, cy: -p.y, r: Math.max(0.35, 4 * px), class: "draft-point" }));
      const t = svg("text", { x: p.x + 6 * px, y: -p.y - 6 * px, class: "label" });
      t.textContent = String(i + 1);
      draft.append(t);
    });
  }
}

// A scale bar in the lower left corner: a round length near a fifth of the width, drawn
// in the map's own metres (so it is right at every zoom).
function drawScale(x0, y0, w, h, px) {
  const g = $("scale");
  g.replaceChildren();
  const len = roundLength(w / 5);
  const x = x0 + 16 * px, y = -(y0 + 16 * px), tick = 6 * px;
  g.append(svg("rect", { x: x - 4 * px, y: y - 24 * px, width: len + 8 * px, height: 28 * px, class: "scale-back" }));
  g.append(svg("polyline", {
    id: "scale-bar",
    points: `${x},${y - tick} ${x},${y} ${x + len},${y} ${x + len},${y - tick}`,
    class: "scale-bar", "data-metres": len,
  }));
  const t = svg("text", { x: x + 2 * px, y: y - tick - 3 * px, class: "scale-text" });
  t.textContent = len >= 1000 ? `${len / 1000} km` : `${len} m`;
  t.id = "scale-text";
  g.append(t);
  ocu.scale = { metres: len };
}

// Map metres -> client pixels (tests click through it) and back.
ocu.worldToClient = (x, y) => {
  const map = $("map");
  const p = map.createSVGPoint();
  p.x = x; p.y = -y;
  const q = p.matrixTransform(map.getScreenCTM());
  return { x: q.x, y: q.y };
};
function clientToWorld(cx, cy) {
  const map = $("map");
  const p = map.createSVGPoint();
  p.x = cx; p.y = cy;
  const q = p.matrixTransform(map.getScreenCTM().inverse());
  return { x: q.x, y: -q.y };
}

// ---- Zoom and pan ----------------------------------------------------------------------

const MPP_MIN = 0.002, MPP_MAX = 5000;

// Zooms by `factor` (>1: out) about the client point (cx, cy), which stays put.
ocu.zoomAt = (cx, cy, factor) => {
  const v = ocu.mapView;
  currentView();
  const r = $("map").getBoundingClientRect();
  const dx = cx - (r.left + r.width / 2), dy = cy - (r.top + r.height / 2);
  const at = { x: v.cx + dx * v.mpp, y: v.cy - dy * v.mpp };
  const mpp = Math.min(MPP_MAX, Math.max(MPP_MIN, v.mpp * factor));
  Object.assign(v, { auto: false, mpp, cx: at.x - dx * mpp, cy: at.y + dy * mpp });
  drawMap();
};

$("map").addEventListener("wheel", (ev) => {
  ev.preventDefault();
  const lines = ev.deltaMode === 1 ? 33 : ev.deltaMode === 2 ? 400 : 1;
  ocu.zoomAt(ev.clientX, ev.clientY, Math.exp(Math.max(-500, Math.min(500, ev.deltaY * lines)) * 0.0015));
}, { passive: false });

// Dragging by more than a few pixels pans (and is not a click that adds a waypoint).
let drag = null;
$("map").addEventListener("pointerdown", (ev) => {
  if (ev.button !== 0) return;
  ocu.dragged = false;
  currentView();
  drag = { id: ev.pointerId, x: ev.clientX, y: ev.clientY, cx: ocu.mapView.cx, cy: ocu.mapView.cy, moved: false };
});
$("map").addEventListener("pointermove", (ev) => {
  if (!drag || ev.pointerId !== drag.id) return;
  const dx = ev.clientX - drag.x, dy = ev.clientY - drag.y;
  if (!drag.moved && Math.hypot(dx, dy) < 5) return;
  if (!drag.moved) { drag.moved = true; $("map").setPointerCapture(ev.pointerId); $("map").classList.add("panning"); }
  const v = ocu.mapView;
  Object.assign(v, { auto: false, cx: drag.cx - dx * v.mpp, cy: drag.cy + dy * v.mpp });
  drawMap();
});
function endDrag(ev) {
  if (!drag || ev.pointerId !== drag.id) return;
  ocu.dragged = drag.moved;
  drag = null;
  $("map").classList.remove("panning");
}
$("map").addEventListener("pointerup", endDrag);
$("map").addEventListener("pointercancel", endDrag);
window.addEventListener("resize", () => drawMap());

// ---- Background layers -----------------------------------------------------------------
//
// From the console's command line (nothing by default, no network): an image placed by
// its world file or bounds, and local z/x/y tiles placed by latitude and longitude
// through the console's origin.

function loadLayers() {
  fetch("/api/map").then((r) => (r.ok ? r.json() : null)).then((layers) => {
    if (!layers) return;
    ocu.layers.background = layers.background;
    ocu.layers.tiles = layers.tiles;
    const bg = layers.background;
    if (bg) {
      const img = svg("image", {
        id: "bg-image", x: 0, y: 0, width: bg.width, height: bg.height,
        preserveAspectRatio: "none", transform: `matrix(${bg.matrix.join(" ")})`,
      });
      img.addEventListener("load", () => { ocu.layers.backgroundLoaded = true; });
      img.addEventListener("error", () => localNotice("the background image did not load"));
      img.setAttribute("href", bg.url);
      $("background").replaceChildren(img);
    }
    drawMap();
  }).catch(() => localNotice("the map's layers did not load"));
}

// The console's local frame (as jaus::stock::geo::LocalFrame at elevation 0): metres per
// radian of latitude and of longitude at the origin.
function frameRadii(lat0) {
  const a = 6378137.0, f = 1 / 298.257223563, e2 = f * (2 - f);
  const s = Math.sin(lat0 * Math.PI / 180), w = Math.sqrt(1 - e2 * s * s);
  return { north: a * (1 - e2) / (w * w * w), east: (a / w) * Math.cos(lat0 * Math.PI / 180) };
}

const TILES_MAX = 120;

function drawTiles(x0, y0, w, h, px) {
  const t = ocu.layers.tiles, origin = ocu.view && ocu.view.origin;
  const layer = $("tiles");
  if (!t || !origin) return;
  const [lat0, lon0] = origin;
  const key = [x0, y0, w, h, lat0, lon0].join(",");
  if (ocu.layers.tilesKey === key) return;
  ocu.layers.tilesKey = key;
  const rad = frameRadii(lat0), D = 180 / Math.PI;
  const lon = (x) => lon0 + (x / rad.east) * D, lat = (y) => lat0 + (y / rad.north) * D;
  const xOf = (lo) => ((lo - lon0) / D) * rad.east, yOf = (la) => ((la - lat0) / D) * rad.north;
  // Web Mercator tiles of 256 pixels: pick the level nearest a tile pixel per screen pixel.
  const want = Math.log2((156543.03392 * Math.cos(lat0 / D)) / px);
  const zooms = t.zooms.filter((z) => z <= Math.round(want));
  let i = zooms.length ? t.zooms.indexOf(zooms[zooms.length - 1]) : 0;
  const span = (z) => {
    const n = 2 ** z, clamp = (v) => Math.min(n - 1, Math.max(0, v));
    const tx = (lo) => clamp(Math.floor(((lo + 180) / 360) * n));
    const ty = (la) => {
      const r = Math.max(-85.0511, Math.min(85.0511, la)) / D;
      return clamp(Math.floor(((1 - Math.log(Math.tan(r) + 1 / Math.cos(r)) / Math.PI) / 2) * n));
    };
    return [tx(lon(x0)), tx(lon(x0 + w)), ty(lat(y0 + h)), ty(lat(y0))];
  };
  let z = t.zooms[i], s = span(z);
  while ((s[1] - s[0] + 1) * (s[3] - s[2] + 1) > TILES_MAX && i > 0) { z = t.zooms[--i]; s = span(z); }
  const wanted = new Set();
  if ((s[1] - s[0] + 1) * (s[3] - s[2] + 1) <= TILES_MAX) {
    const n = 2 ** z;
    const tileLat = (y) => Math.atan(Math.sinh(Math.PI * (1 - (2 * y) / n))) * D;
    for (let x = s[0]; x <= s[1]; x++) {
      for (let y = s[2]; y <= s[3]; y++) {
        const id = `tile-${z}-${x}-${y}`;
        wanted.add(id);
        if (document.getElementById(id)) continue;
        const west = xOf((x / n) * 360 - 180), east = xOf(((x + 1) / n) * 360 - 180);
        const north = yOf(tileLat(y)), south = yOf(tileLat(y + 1));
        const img = svg("image", { id, x: west, y: -north, width: east - west, height: north - south, preserveAspectRatio: "none", class: "tile" });
        img.addEventListener("load", () => img.classList.add("loaded"));
        img.addEventListener("error", () => img.classList.add("missing"));
        img.setAttribute("href", t.url.replace("{z}", z).replace("{x}", x).replace("{y}", y));
        layer.append(img);
      }
    }
  }
  for (const e of [...layer.children]) if (!wanted.has(e.id)) e.remove();
}

// ---- Side panel ------------------------------------------------------------------------

function roleOptions(s) {
  const r = s.roles, out = [];
  if (r.waypoint_driver) out.push(["Global Waypoint Driver", r.waypoint_driver]);
  if (r.path_segment_driver) out.push(["Global Path Segment Driver", r.path_segment_driver]);
  if (r.spooler) out.push(["Mission Spooler", r.spooler]);
  if (r.primitive_driver) out.push(["Primitive Driver", r.primitive_driver]);
  return out;
}

function component(s, address) {
  for (const n of s.nodes) for (const c of n.components) if (c.address === address) return c;
  return null;
}

function drawSide() {
  const s = selectedView();
  if (!s) { $("veh-name").textContent = "—"; return; }
  $("veh-name").textContent = `${s.id}${s.name ? " — " + s.name : ""}`;
  const states = [];
  for (const n of s.nodes) for (const c of n.components) if (c.state) states.push(c.state);
  const state = s.emergency ? "Emergency" : (component(s, s.roles.waypoint_driver || "") || {}).state || states[0] || "—";
  $("veh-state").textContent = state + (s.stale ? " (stale)" : "");
  $("veh-pos").textContent = s.pose
    ? `${s.pose.latitude.toFixed(6)}, ${s.pose.longitude.toFixed(6)} (${s.pose.x.toFixed(1)} m E, ${s.pose.y.toFixed(1)} m N)`
    : "—";
  $("veh-speed").textContent = s.velocity ? `${s.velocity.speed.toFixed(2)} m/s` : "—";
  $("veh-speed").dataset.speed = s.velocity ? s.velocity.speed : "";
  $("veh-heard").textContent = s.heard_s === null ? "never" : `${s.heard_s.toFixed(1)} s ago`;
  const sel = $("driver");
  const opts = roleOptions(s);
  const key = opts.map((o) => o[1]).join(",");
  if (sel.dataset.key !== key) {
    const keep = sel.value;
    sel.replaceChildren(...opts.map(([name, a]) => el("option", { value: a }, `${name} ${a}`)));
    if (opts.some((o) => o[1] === keep)) sel.value = keep;
    sel.dataset.key = key;
  }
  const c = component(s, sel.value);
  $("driver-control").textContent = !c ? "—" : c.held ? "held" : (c.keeping !== null && c.keeping !== undefined) ? "asking…" : c.controller ? `held by ${c.controller}` : "not held";
  // Which component the line speaks of: a script (or a test) reading it knows it is not
  // the previous selection's.
  $("driver-control").dataset.address = c ? sel.value : "";
  $("mission-status").textContent = s.mission ? `mission ${s.mission.id}: ${s.mission.status || "sent"} (${s.mission.tasks} moves)` : "—";
  const list = $("draft-list");
  list.replaceChildren(...ocu.draft.map((p) => el("li", {}, `${p.x.toFixed(1)} m E, ${p.y.toFixed(1)} m N`)));
}

function drawNotices() {
  const ul = $("notices");
  const all = ((ocu.view && ocu.view.notices) || []).concat(localNotices).sort((a, b) => a.unix_ms - b.unix_ms);
  ul.replaceChildren(...all.slice(-40).reverse().map((n) => el("li", { class: "notice" + (n.error ? " error" : "") }, `${new Date(n.unix_ms).toLocaleTimeString()} ${n.text}`)));
}

function appendLog(entries) {
  if (!entries.length || $("log-pause").checked) return;
  const body = $("log").tBodies[0];
  for (const e of entries) {
    const tr = el("tr", { class: e.dir + (e.error ? " bad" : "") });
    tr.append(el("td", {}, e.seq), el("td", {}, new Date(e.unix_ms).toLocaleTimeString()), el("td", {}, e.dir),
      el("td", {}, e.src), el("td", {}, e.dst), el("td", {}, e.name),
      el("td", { class: "fields" }, e.error ? e.error : JSON.stringify(e.fields)));
    body.prepend(tr);
  }
  while (body.rows.length > LOG_ROWS) body.deleteRow(body.rows.length - 1);
}

// ---- Link ------------------------------------------------------------------------------

function linkUp() {
  return ocu.socket && Date.now() - ocu.lastMessage < STALE_LINK_MS;
}

setInterval(() => {
  const link = $("link");
  if (!ocu.socket) { link.className = "link down"; link.textContent = "console disconnected — data is stale"; }
  else if (!linkUp()) { link.className = "link stale"; link.textContent = "no update for " + ((Date.now() - ocu.lastMessage) / 1000).toFixed(0) + " s — stale"; }
  else {
    const stale = ocu.view && ocu.view.subsystems.filter((s) => s.stale && s.pose).length;
    link.className = stale ? "link stale" : "link up";
    link.textContent = stale ? `live (${stale} vehicle(s) stale)` : "live";
  }
  $("map").classList.toggle("stale", !linkUp());
}, 250);

// ---- Operator actions ------------------------------------------------------------------

function speed() {
  const v = $("speed").value.trim();
  // Sent as typed when it is not a number: the console says what is wrong.
  return /^[-+]?[0-9]*\.?[0-9]+([eE][-+]?[0-9]+)?$/.test(v) ? Number(v) : v;
}

function needVehicle() {
  const s = selectedView();
  if (!s) localNotice("no vehicle selected");
  return s;
}

$("map").addEventListener("click", (ev) => {
  if (ocu.dragged) { ocu.dragged = false; return; }
  if (!needVehicle()) return;
  const p = clientToWorld(ev.clientX, ev.clientY);
  ocu.draft.push(p);
  drawMap(); drawSide();
});

// Another component chosen: its control line at once, not at the next update.
$("driver").addEventListener("change", () => drawSide());
$("fit").onclick = () => { ocu.mapView.auto = true; drawMap(); };
$("clear-draft").onclick = () => { ocu.draft = []; drawMap(); drawSide(); };
$("take").onclick = () => {
  const a = $("driver").value;
  if (!a) return localNotice("no component to control");
  send({ op: "take", target: a, authority: Number($("authority").value) });
};
$("release").onclick = () => {
  const a = $("driver").value;
  if (a) send({ op: "release", target: a });
};
$("estop-all").onclick = () => {
  for (const s of (ocu.view && ocu.view.subsystems) || []) if (s.pose || s.roles.primitive_driver) send({ op: "emergency", subsystem: s.id });
};
$("clear-all").onclick = () => {
  for (const s of (ocu.view && ocu.view.subsystems) || []) if (s.pose || s.roles.primitive_driver) send({ op: "clear_emergency", subsystem: s.id });
};
$("veh-estop").onclick = () => { const s = needVehicle(); if (s) send({ op: "emergency", subsystem: s.id }); };
$("veh-clear").onclick = () => { const s = needVehicle(); if (s) send({ op: "clear_emergency", subsystem: s.id }); };

function drive(op, driver) {
  if (!needVehicle()) return;
  if (!ocu.draft.length) return localNotice("click the map to add waypoints first");
  if (!driver) return localNotice("this vehicle has no such driver");
  send({ op, driver, speed: speed(), points: ocu.draft.map((p) => ({ x: p.x, y: p.y })) });
  ocu.draft = [];
  drawMap(); drawSide();
}
$("drive").onclick = () => { const s = needVehicle(); if (s) drive("waypoints", s.roles.waypoint_driver); };
$("drive-path").onclick = () => { const s = needVehicle(); if (s) drive("path", s.roles.path_segment_driver); };
$("spool").onclick = () => {
  const s = needVehicle();
  if (!s) return;
  if (!s.roles.spooler || !s.roles.waypoint_driver) return localNotice("this vehicle has no mission spooler or waypoint driver");
  if (!ocu.draft.length) return localNotice("click the map to add the mission's moves first");
  send({ op: "spool", spooler: s.roles.spooler, driver: s.roles.waypoint_driver, speed: speed(), points: ocu.draft.map((p) => ({ x: p.x, y: p.y })) });
  ocu.draft = [];
};
$("obstacle").onclick = () => {
  const s = needVehicle();
  if (!s) return;
  if (!s.roles.world_model) return localNotice("this vehicle has no world model");
  const p = ocu.draft[ocu.draft.length - 1];
  if (!p) return localNotice("click the map where the obstacle is first");
  const radius = Number($("obstacle-radius").value);
  send({ op: "obstacle", world_model: s.roles.world_model, radius, points: [{ x: p.x, y: p.y }] });
  ocu.draft.pop();
  drawMap(); drawSide();
};
for (const [id, action] of [["m-run", "run"], ["m-pause", "pause"], ["m-resume", "resume"], ["m-abort", "abort"]]) {
  $(id).onclick = () => { const s = needVehicle(); if (s && s.roles.spooler) send({ op: "mission", spooler: s.roles.spooler, action }); };
}

loadLayers();
connect();
