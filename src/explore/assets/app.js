// archstudy explore: the page only gathers the scene from its controls, asks the server,
// and places the figures the server draws (the report's own drawings, as SVG). A click on a
// map is turned into the map's (μ, K) through the plotting frame sent with the figure.
"use strict";

const $ = (id) => document.getElementById(id);
const SCENE_KEYS = ["k", "t_over_r", "mu", "half_angle", "weight", "voussoirs", "shape",
  "eccentricity", "joints", "keystone", "load", "at", "at_x", "lambda"];
const MAP_KEYS = ["k_from", "k_to", "mu_from", "mu_to"];

const ui = {
  inflight: false, pending: false, mapKey: null, mapSeq: 0, mapFrame: null, frames: [], frame: 0,
  playing: true, timer: null, mechTimer: null, runFrames: [], lastScene: null,
};

// --- the scene from the controls, and back -------------------------------------------------

function kFromT(t) { return (2 + t) / (2 - t); }
function tFromK(k) { return 2 * (k - 1) / (k + 1); }

function sceneParams() {
  const p = new URLSearchParams();
  const by = $("thickness-by").value;
  p.set(by, $("k-number").value);
  p.set("mu", $("mu-inf").checked ? "inf" : $("mu-number").value);
  p.set("half_angle", $("half-angle").value);
  p.set("shape", $("shape").value);
  if ($("shape").value === "pointed") p.set("eccentricity", $("eccentricity").value);
  p.set("joints", $("joints").value);
  if ($("keystone").checked) p.set("keystone", "true");
  p.set("weight", $("weight").value);
  if (!$("continuum").checked) p.set("voussoirs", $("voussoirs").value);
  const load = $("load").value;
  p.set("load", load);
  if (load === "point") p.set($("at-by").value, $("at").value);
  if (load !== "self-weight") p.set("lambda", $("lambda").value);
  return p;
}

function mapParams() {
  const p = sceneParams();
  const pairs = [["k_from", "map-k-from"], ["k_to", "map-k-to"], ["mu_from", "map-mu-from"], ["mu_to", "map-mu-to"]];
  for (const [key, id] of pairs) if ($(id).value !== "") p.set(key, $(id).value);
  return p;
}

function setControls(q) {
  const get = (k) => q.get(k);
  if (get("t_over_r") !== null) { $("thickness-by").value = "t_over_r"; $("k-number").value = get("t_over_r"); }
  else if (get("k") !== null) { $("thickness-by").value = "k"; $("k-number").value = get("k"); }
  const mu = get("mu");
  if (mu !== null) {
    $("mu-inf").checked = mu === "inf";
    if (mu !== "inf") $("mu-number").value = mu;
  }
  if (get("half_angle") !== null) $("half-angle").value = get("half_angle");
  if (get("shape") !== null) $("shape").value = get("shape");
  if (get("eccentricity") !== null) $("eccentricity").value = get("eccentricity");
  if (get("joints") !== null) $("joints").value = get("joints");
  $("keystone").checked = get("keystone") === "true";
  if (get("weight") !== null) $("weight").value = get("weight");
  $("continuum").checked = get("voussoirs") === null;
  if (get("voussoirs") !== null) $("voussoirs").value = get("voussoirs");
  if (get("load") !== null) $("load").value = get("load").replace("_", "-");
  if (get("at_x") !== null) { $("at-by").value = "at_x"; $("at").value = get("at_x"); }
  else if (get("at") !== null) { $("at-by").value = "at"; $("at").value = get("at"); }
  if (get("lambda") !== null) $("lambda").value = get("lambda");
  for (const [key, id] of [["k_from", "map-k-from"], ["k_to", "map-k-to"], ["mu_from", "map-mu-from"], ["mu_to", "map-mu-to"]]) {
    if (get(key) !== null) $(id).value = get(key);
  }
  syncControls();
}

function syncControls() {
  const byT = $("thickness-by").value === "t_over_r";
  const v = parseFloat($("k-number").value);
  $("k-range").min = byT ? "0.005" : "1.01";
  $("k-range").max = byT ? "0.667" : "2";
  $("k-range").value = $("k-number").value;
  $("k-other").textContent = Number.isFinite(v) ? (byT ? `K = ${kFromT(v).toFixed(5)}` : `t/R_c = ${tFromK(v).toFixed(5)}`) : "";
  $("mu-range").value = $("mu-number").value;
  $("mu-range").disabled = $("mu-number").disabled = $("mu-inf").checked;
  $("eccentricity").disabled = $("shape").value !== "pointed";
  $("voussoirs").disabled = $("continuum").checked;
  const load = $("load").value;
  $("at-by").disabled = $("at").disabled = load !== "point";
  $("lambda").disabled = load === "self-weight";
  $("at").step = $("at-by").value === "at_x" ? "0.01" : "1";
}

// --- asking the server --------------------------------------------------------------------

async function ask(path, params) {
  const r = await fetch(`${path}?${params.toString()}`);
  let body = null;
  try { body = JSON.parse(await r.text()); } catch (e) { body = null; }
  if (!r.ok || body === null) throw new Error((body && body.error) || `the server answered ${r.status} ${r.statusText}`);
  return body;
}

function showError(e) {
  const box = $("error");
  if (e) { box.textContent = String(e.message || e); box.hidden = false; } else { box.hidden = true; }
}

function archKey(p) {
  const q = new URLSearchParams(p);
  q.delete("k"); q.delete("t_over_r"); q.delete("mu");
  return q.toString();
}

function schedule() {
  syncControls();
  if (ui.inflight) { ui.pending = true; return; }
  update();
}

async function update() {
  ui.inflight = true; ui.pending = false;
  const params = sceneParams();
  history.replaceState(null, "", `?${mapParams().toString()}`);
  $("busy").textContent = "solving…";
  try {
    const v = await ask("/api/scene", params);
    showError(null);
    showScene(v);
    ui.lastScene = params.toString();
    scheduleMechanism(params);
    if (archKey(params) !== ui.mapKey) {
      if (!inWindow()) clearWindow();
      drawMap();
    } else if (!placeMarker()) {
      // The scene left the map: draw the map around it.
      clearWindow();
      drawMap();
    }
  } catch (e) {
    showError(e);
  } finally {
    ui.inflight = false;
    $("busy").textContent = "";
    if (ui.pending) update();
  }
}

const fmt = (x) => (x === null || x === undefined) ? "—" : (Math.abs(x) >= 1e4 || (x !== 0 && Math.abs(x) < 1e-3) ? x.toExponential(4) : (+x.toPrecision(6)).toString());

function criticalRows(v) {
  const f = v.finds || {};
  const rows = [];
  const gap = (s) => s && s.gap ? (s.gap === "gap" ? `gap: collapse at ${fmt(s.collapse_value)}` : s.gap.replace(/_/g, " ")) : "—";
  const add = (name, s, value, mech) => rows.push({ name, value, mech: mech ?? (s && s.mechanism), gap: gap(s), outcome: s && s.outcome });
  if (f.thickness) add("K_c(μ)", f.thickness, f.thickness.k_crit);
  if (f.friction) add("μ_c(K)", f.friction, f.friction.mu_crit);
  if (f.load_factor) add("λ_max", f.load_factor, f.load_factor.load_factor_unbounded ? Infinity : f.load_factor.load_factor);
  if (v.mu_min_at_k !== null && v.mu_min_at_k !== undefined) {
    rows.push({ name: "μ_min(K) (the sliding conditions alone fail below)", value: v.mu_min_at_k, mech: "sliding", gap: "—" });
  }
  if (f.thresholds) {
    const t = f.thresholds;
    rows.push({ name: "K_c at μ = ∞", value: t.k_c_rotational, mech: "rotational", gap: "—" });
    rows.push({ name: "μ of the rotational/mixed bifurcation", value: t.mu_rotational_mixed, mech: "", gap: "—" });
    rows.push({ name: "μ_min (no K stands below)", value: t.mu_min, mech: "sliding", gap: "—" });
    rows.push({ name: "K of the mixed/sliding bifurcation", value: t.k_mixed_sliding, mech: "", gap: "—" });
  }
  return rows;
}

function showScene(v) {
  const s = v.state;
  const regime = s.regime || "—";
  $("regime").textContent = regime;
  $("regime").dataset.regime = regime;
  $("drawn").textContent = `· drawn: ${v.drawn}`;
  const body = $("critical").tBodies[0];
  body.replaceChildren();
  for (const r of criticalRows(v)) {
    const tr = body.insertRow();
    tr.dataset.name = r.name;
    const value = r.value === Infinity ? "unbounded" : (r.value === null || r.value === undefined ? (r.outcome ? r.outcome.replace(/_/g, " ") : "—") : fmt(r.value));
    for (const c of [r.name, value, r.mech || "—", r.gap]) tr.insertCell().textContent = c;
  }
  const joints = $("joints-table").tBodies[0];
  joints.replaceChildren();
  for (const h of v.drawn_joints.hinges) {
    const tr = joints.insertRow();
    tr.dataset.kind = "hinge"; tr.dataset.angle = h.angle_deg; tr.dataset.face = h.face;
    for (const c of ["hinge", fmt(h.angle_deg), h.face]) tr.insertCell().textContent = c;
  }
  for (const j of v.drawn_joints.sliding_joints) {
    const tr = joints.insertRow();
    tr.dataset.kind = "sliding"; tr.dataset.angle = j.angle_deg; tr.dataset.sense = j.sense;
    for (const c of ["sliding joint", fmt(j.angle_deg), j.sense]) tr.insertCell().textContent = c;
  }
  $("state-fig").innerHTML = v.svg.state;
  // No downloads of a figure the arch does not have.
  $("domains-caption").hidden = !v.svg.domains;
  if (v.svg.domains) $("domains-fig").innerHTML = v.svg.domains;
  else {
    const note = document.createElement("p");
    note.className = "hint";
    note.textContent = "Fig. 2 (Hʳ and Hˢ against the joint angle) is the closed form of a circular arch with radial joints under self-weight; this arch or load has no such curves. Its regime and critical values above come from the general route.";
    $("domains-fig").replaceChildren(note);
  }
  $("timing").textContent = `answered in ${v.elapsed_ms.toFixed(1)} ms`;
}

// --- the mechanism, moving ----------------------------------------------------------------

function scheduleMechanism(params) {
  clearTimeout(ui.mechTimer);
  ui.mechTimer = setTimeout(() => loadMechanism(params), 200);
}

async function loadMechanism(params) {
  if (params.toString() !== ui.lastScene) return;
  try {
    const m = await ask("/api/mechanism", params);
    if (params.toString() !== ui.lastScene) return;
    ui.frames = m.frames;
    ui.frame = 0;
    $("mechanism-view").hidden = m.frames.length === 0;
    animate();
  } catch (e) {
    $("mechanism-view").hidden = true;
  }
}

function animate() {
  clearInterval(ui.timer);
  const n = ui.frames.length;
  if (n === 0) return;
  const show = () => { $("mechanism-fig").innerHTML = ui.frames[ui.frame]; };
  show();
  if (!ui.playing) return;
  let step = 1;
  ui.timer = setInterval(() => {
    if (ui.frame + step >= n || ui.frame + step < 0) step = -step;
    ui.frame += step;
    show();
  }, 90);
}

// --- maps -----------------------------------------------------------------------------------

function svgPoint(container, ev) {
  const svg = container.querySelector("svg");
  if (!svg) return null;
  const rect = svg.getBoundingClientRect();
  const vb = svg.viewBox && svg.viewBox.baseVal && svg.viewBox.baseVal.width ? svg.viewBox.baseVal : { width: +svg.getAttribute("width"), height: +svg.getAttribute("height") };
  return { x: (ev.clientX - rect.left) * vb.width / rect.width, y: (ev.clientY - rect.top) * vb.height / rect.height };
}

function valueAt(f, p) {
  if (!f || p.x < f.left || p.x > f.right || p.y < f.top || p.y > f.bottom) return null;
  const x = f.x[0] + (p.x - f.left) / (f.right - f.left) * (f.x[1] - f.x[0]);
  const y = f.y[0] + (f.bottom - p.y) / (f.bottom - f.top) * (f.y[1] - f.y[0]);
  return { x, y: f.log_y ? Math.pow(10, y) : y };
}

function sceneKMu() {
  const v = parseFloat($("k-number").value);
  const k = $("thickness-by").value === "t_over_r" ? kFromT(v) : v;
  const mu = $("mu-inf").checked ? Infinity : parseFloat($("mu-number").value);
  return { k, mu };
}

// True when the map window typed in the inputs holds the scene (or none is typed).
function inWindow() {
  const w = ["map-k-from", "map-k-to", "map-mu-from", "map-mu-to"].map((id) => parseFloat($(id).value));
  if (w.some((x) => !Number.isFinite(x))) return true;
  const { k, mu } = sceneKMu();
  return k >= w[0] && k <= w[1] && (!Number.isFinite(mu) || (mu >= w[2] && mu <= w[3]));
}

function clearWindow() {
  for (const id of ["map-k-from", "map-k-to", "map-mu-from", "map-mu-to"]) $(id).value = "";
}

function placeMarker() {
  const f = ui.mapFrame, m = $("map-marker");
  const svg = $("map-fig").querySelector("svg");
  const { k, mu } = sceneKMu();
  if (!f || !svg) { m.hidden = true; return true; }
  const kInside = k >= f.y[0] && k <= f.y[1];
  // μ = ∞ has no place on the map: the map is kept while K stays inside it.
  if (!Number.isFinite(mu) || mu < f.x[0] || mu > f.x[1] || !kInside) { m.hidden = true; return !Number.isFinite(mu) && kInside; }
  const rect = svg.getBoundingClientRect();
  const box = $("map-fig").getBoundingClientRect();
  const vbw = svg.viewBox.baseVal.width || +svg.getAttribute("width");
  const s = rect.width / vbw;
  const px = f.left + (mu - f.x[0]) / (f.x[1] - f.x[0]) * (f.right - f.left);
  const py = f.bottom - (k - f.y[0]) / (f.y[1] - f.y[0]) * (f.bottom - f.top);
  m.style.left = `${rect.left - box.left + px * s}px`;
  m.style.top = `${rect.top - box.top + py * s}px`;
  m.hidden = false;
  return true;
}

async function drawMap() {
  const params = mapParams();
  ui.mapKey = archKey(sceneParams());
  // Only the latest map asked for is placed, whatever order the answers come in.
  const seq = ++ui.mapSeq;
  $("map-info").textContent = "drawing the map…";
  try {
    const m = await ask("/api/map", params);
    if (seq !== ui.mapSeq) return;
    const marker = $("map-marker");
    $("map-fig").innerHTML = m.svg;
    $("map-fig").appendChild(marker);
    ui.mapFrame = m.frame;
    const w = m.window;
    $("map-k-from").value = w.k[0]; $("map-k-to").value = w.k[1];
    $("map-mu-from").value = w.mu[0]; $("map-mu-to").value = w.mu[1];
    $("map-info").textContent = `${m.points} points, ${m.collapse.length} collapse points and ${m.bifurcations.length} bifurcations located, in ${m.elapsed_ms.toFixed(0)} ms`;
    placeMarker();
  } catch (e) {
    if (seq !== ui.mapSeq) return;
    $("map-info").textContent = `no map: ${e.message} (change the window and redraw)`;
  }
}

function mapClick(ev) {
  const p = svgPoint($("map-fig"), ev);
  const v = p && valueAt(ui.mapFrame, p);
  if (!v) return;
  $("mu-inf").checked = false;
  $("mu-number").value = v.x.toFixed(4);
  if ($("thickness-by").value === "t_over_r") $("k-number").value = tFromK(v.y).toFixed(5);
  else $("k-number").value = v.y.toFixed(4);
  schedule();
}

// --- a finished run -------------------------------------------------------------------------

async function openRun() {
  let run;
  try { run = await ask("/api/run", new URLSearchParams()); } catch (e) { showError(e); return; }
  if (!run.open) return;
  $("run-name").textContent = `run: ${run.name}${run.title ? " — " + run.title : ""} (${run.cases} cases)`;
  if (!run.figure) return;
  $("run-view").hidden = false;
  $("run-fig").innerHTML = run.figure.svg;
  $("run-caption").textContent = run.figure.title + ".";
  ui.runFrames = run.figure.frames;
}

async function runClick(ev) {
  const p = svgPoint($("run-fig"), ev);
  if (!p) return;
  for (let i = 0; i < ui.runFrames.length; i++) {
    const v = valueAt(ui.runFrames[i], p);
    if (!v) continue;
    const q = new URLSearchParams({ panel: i, x: v.x, y: ui.runFrames[i].log_y ? Math.log10(v.y) : v.y });
    try {
      const c = await ask("/api/run/case", q);
      showCase(c);
    } catch (e) { showError(e); }
    return;
  }
}

function showCase(c) {
  const info = $("case-info");
  info.dataset.caseId = c.case_id;
  const s = c.stored || {};
  const parts = [`case ${c.case_id}`, `load case ${s.load_case}`, `K = ${fmt(s.k)}`,
    `μ = ${s.mu === "inf" ? "∞" : fmt(s.mu)}`];
  if (s.regime) parts.push(`stored regime: ${s.regime}`);
  if (s.load_factor !== null && s.load_factor !== undefined) parts.push(`stored λ_max = ${fmt(s.load_factor)}`);
  if (s.k_crit) parts.push(`stored K_c = ${fmt(s.k_crit)}`);
  if (s.mu_crit) parts.push(`stored μ_c = ${fmt(s.mu_crit)}`);
  info.textContent = parts.join(" · ");
  info.dataset.k = s.k; info.dataset.mu = s.mu;
  setControls(new URLSearchParams(c.query));
  schedule();
}

// --- downloads and wiring -------------------------------------------------------------------

function download(ev) {
  ev.preventDefault();
  const a = ev.currentTarget;
  const p = a.dataset.view === "map" ? mapParams() : sceneParams();
  p.set("view", a.dataset.view);
  p.set("format", a.dataset.format);
  window.location.href = `/api/figure?${p.toString()}`;
}

function wire() {
  $("controls").addEventListener("submit", (ev) => ev.preventDefault());
  const onInput = ["k-number", "mu-number", "half-angle", "eccentricity", "voussoirs", "at", "lambda"];
  for (const id of onInput) $(id).addEventListener("input", schedule);
  for (const id of ["thickness-by", "mu-inf", "shape", "joints", "keystone", "weight", "continuum", "load", "at-by"]) {
    $(id).addEventListener("change", () => {
      if (id === "thickness-by") {
        const v = parseFloat($("k-number").value);
        $("k-number").value = ($("thickness-by").value === "t_over_r" ? tFromK(v) : kFromT(v)).toFixed(5);
      }
      schedule();
    });
  }
  $("k-range").addEventListener("input", () => { $("k-number").value = $("k-range").value; schedule(); });
  $("mu-range").addEventListener("input", () => { $("mu-number").value = $("mu-range").value; schedule(); });
  $("map-fig").addEventListener("click", mapClick);
  $("run-fig").addEventListener("click", runClick);
  $("map-redraw").addEventListener("click", () => { ui.mapKey = null; schedule(); });
  $("map-centre").addEventListener("click", () => { clearWindow(); ui.mapKey = null; schedule(); });
  $("play").addEventListener("click", () => {
    ui.playing = !ui.playing;
    $("play").textContent = ui.playing ? "pause" : "play";
    animate();
  });
  for (const a of document.querySelectorAll("a.dl")) a.addEventListener("click", download);
  $("save-study").addEventListener("click", (ev) => {
    ev.preventDefault();
    window.location.href = `/api/study?${mapParams().toString()}`;
  });
  $("share").addEventListener("click", () => navigator.clipboard && navigator.clipboard.writeText(location.href));
  window.addEventListener("resize", placeMarker);
}

wire();
setControls(new URLSearchParams(location.search));
openRun();
schedule();
