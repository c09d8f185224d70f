// The lab page: pickers and sliders generated from the catalogue (the JSON `physicskit list
// --json` prints, read from the WebAssembly module), a frame loop stepping the Rust
// integrators, and the views: the scene with trails, a phase-space panel, the energy error
// on a log scale and, for two-degree-of-freedom separable Hamiltonians, a Poincaré section
// that launches orbits where it is clicked. Nothing here names a system or a method, but for
// the one system whose section is shown unasked (SECTION_BY_DEFAULT).
import { load } from "./physicskit.js";

const $ = (id) => document.getElementById(id);
const DTS = [1e-4, 2e-4, 5e-4, 1e-3, 2e-3, 5e-3, 1e-2, 2e-2, 5e-2, 0.1];
const DEFAULT_DT = 1e-3;
const DEFAULT_STEPS = 25;
const TRAIL = 600, PHASE_TRAIL = 4000, ENERGY_POINTS = 3000, MAX_ROWS = 100000;

const app = {
  core: null, catalogue: null, entry: null, lab: null, params: {},
  running: false, trails: [], phase: [], energy: [], rows: [],
  sceneBox: null, phaseBox: null, sectionBox: null, drag: null, frames: 0,
};

// ---------- catalogue-driven controls ----------

function fillSystems() {
  const sel = $("system");
  sel.replaceChildren(...app.catalogue.systems.map((s) => new Option(s.name, s.name)));
}

function sliderRange(p) {
  const d = typeof p.default === "number" ? p.default : null;
  const min = p.range?.min, max = p.range?.max;
  let lo, hi;
  if (min && max) [lo, hi] = [min.value, max.value];
  else if (min) [lo, hi] = [min.value, d !== null && d > min.value ? min.value + 3 * (d - min.value) : min.value + 10];
  else if (max) [lo, hi] = [d !== null && d < max.value ? max.value - 3 * (max.value - d) : max.value - 10, max.value];
  else { const s = Math.max(1, Math.abs(d ?? 1)) * 3; [lo, hi] = [(d ?? 0) - s, (d ?? 0) + s]; }
  // An exclusive bound is not a value: stay a hair inside.
  const span = hi - lo || 1;
  if (min && !min.inclusive) lo += span * 1e-3;
  if (max && !max.inclusive) hi -= span * 1e-3;
  return [lo, hi];
}

function paramControl(p) {
  const div = document.createElement("div");
  div.className = "param";
  const label = document.createElement("label");
  label.textContent = `${p.name}${p.unit ? ` [${p.unit}]` : ""}`;
  label.title = p.help;
  const help = document.createElement("div");
  help.className = "help";
  help.textContent = p.help;
  div.append(label);
  const set = (v) => { if (v === null || v === "") delete app.params[p.name]; else app.params[p.name] = v; rebuildSoon(); };
  if (p.kind === "choice") {
    const sel = document.createElement("select");
    sel.dataset.param = p.name;
    sel.append(...p.choices.map((c) => new Option(c, c)));
    if (p.default !== null) sel.value = p.default;
    sel.onchange = () => set(sel.value);
    label.append(" ", sel);
  } else if (p.kind === "vector") {
    const inp = document.createElement("input");
    inp.type = "text";
    inp.dataset.param = p.name;
    inp.value = Array.isArray(p.default) ? p.default.join(", ") : "";
    inp.placeholder = p.default === null ? "constructor's default" : "";
    inp.onchange = () => {
      const t = inp.value.trim();
      set(t === "" ? null : t.split(/[\s,]+/).filter(Boolean).map(Number));
    };
    label.append(" ", inp);
  } else {
    const num = document.createElement("input");
    num.type = "number";
    num.dataset.param = p.name;
    num.step = p.kind === "integer" ? "1" : "any";
    num.value = p.default ?? "";
    const [lo, hi] = sliderRange(p);
    const slider = document.createElement("input");
    slider.type = "range";
    slider.min = lo; slider.max = hi;
    slider.step = p.kind === "integer" ? 1 : (hi - lo) / 1000;
    slider.value = p.default ?? (lo + hi) / 2;
    slider.setAttribute("aria-label", p.name);
    slider.oninput = () => { num.value = slider.value; set(Number(slider.value)); };
    num.onchange = () => { if (num.value !== "") slider.value = num.value; set(num.value === "" ? null : Number(num.value)); };
    label.append(" ", num);
    div.append(slider);
  }
  div.append(help);
  return div;
}

function fillParams() {
  $("params").replaceChildren(...app.entry.params.map(paramControl));
}

function setControlValues() {
  for (const el of $("params").querySelectorAll("[data-param]")) {
    const v = app.params[el.dataset.param];
    if (v !== undefined) el.value = Array.isArray(v) ? v.join(", ") : v;
  }
}

function fillMethods(keep) {
  const sel = $("method");
  // The lab steps frame by frame, which an adaptive method (dop853: it steps onto the end of a
  // known span) cannot: only the fixed-step methods are offered.
  const fixed = app.entry.methods.filter((m) => !app.catalogue.methods.find((x) => x.name === m)?.adaptive);
  sel.replaceChildren(...fixed.map((m) => new Option(m, m)));
  sel.value = fixed.includes(keep) ? keep : app.entry.default_method;
  describeMethod();
}

function describeMethod() {
  const m = app.catalogue.methods.find((x) => x.name === $("method").value);
  $("method-info").textContent = m ? `order ${m.order}, ${m.symplectic ? "symplectic" : "not symplectic"}, ` +
    `${m.evaluations_per_step} ${m.evaluations} per step — ${m.reference}` : "";
}

// ---------- building and running ----------

let rebuildPending = false;
function rebuildSoon() {
  if (rebuildPending) return;
  rebuildPending = true;
  requestAnimationFrame(() => { rebuildPending = false; rebuild(); });
}

function family() { return app.entry.family; }
function ndof() { const n = app.lab.state().length; return family() === "ode" ? n : n / 2; }
// The Poincaré section panel. A section (q2 = 0, p2 > 0) of the 3-D energy surface is a 2-D
// picture for a separable Hamiltonian of two degrees of freedom, so it is offered (a checkbox)
// for those only; it is on by default only where it is the picture that matters: Hénon–Heiles,
// bounded and chaotic at its energies (islands and a chaotic sea). Elsewhere the reader
// chooses: a Kepler orbit is closed (one crossing, a point; a drifting point when perturbed),
// a projectile crosses once if ever.
const SECTION_BY_DEFAULT = new Set(["henon-heiles"]);
function sectionOffered() { return family() === "hamiltonian" && app.entry.separable && ndof() === 2; }
function hasSection() { return sectionOffered() && $("section-on").checked; }

function stateLabels() {
  const n = app.lab.state().length;
  if (family() === "ode") return Array.from({ length: n }, (_, i) => `y${i + 1}`);
  const k = n / 2, v = family() === "lagrangian" ? "q̇" : "p";
  return [...Array.from({ length: k }, (_, i) => `q${i + 1}`), ...Array.from({ length: k }, (_, i) => `${v}${i + 1}`)];
}

function rebuild(state0 = null) {
  let lab;
  try {
    lab = app.core.build(app.entry.name, app.params);
    if (state0) lab.setState(state0);
  } catch (e) {
    message(e.message);
    return false;
  }
  app.lab?.free();
  app.lab = lab;
  try { lab.setMethod($("method").value); } catch (e) { message(e.message); }
  const labels = stateLabels();
  // The phase panel starts at (q1, p1) for each new system and keeps the reader's choice
  // while the same system is rebuilt.
  const same = app.phaseSystem === app.entry.name;
  app.phaseSystem = app.entry.name;
  if (!same) $("section-on").checked = SECTION_BY_DEFAULT.has(app.entry.name);
  $("section-choice").hidden = !sectionOffered();
  for (const [id, def] of [["phase-x", 0], ["phase-y", family() === "ode" ? 1 : labels.length / 2]]) {
    const sel = $(id), old = sel.value;
    sel.replaceChildren(...labels.map((l, i) => new Option(l, i)));
    sel.value = same && old !== "" && Number(old) < labels.length ? old : Math.min(def, labels.length - 1);
  }
  $("section-figure").hidden = !hasSection();
  if (hasSection()) {
    lab.setSection(1, 0, 1);
    $("section-name").textContent = `${labels[1]} = 0, ${labels[3]} > 0: (${labels[0]}, ${labels[2]})`;
  }
  clearViews();
  message("");
  draw();
  return true;
}

function clearViews() {
  app.trails = []; app.phase = []; app.energy = []; app.rows = [];
  app.sceneBox = null; app.phaseBox = null; app.sectionBox = null; app.frames = 0;
  record();
}

function record() {
  const lab = app.lab, s = lab.state();
  const t = lab.time(), err = lab.energyError();
  const pos = lab.positions();
  if (pos.length) {
    app.trails.push(Array.from(pos));
    if (app.trails.length > TRAIL) app.trails.shift();
  }
  const ix = Number($("phase-x").value), iy = Number($("phase-y").value);
  app.phase.push([s[ix], s[iy]]);
  if (app.phase.length > PHASE_TRAIL) app.phase.shift();
  app.energy.push([t, err]);
  if (app.energy.length > ENERGY_POINTS) app.energy.splice(0, app.energy.length - ENERGY_POINTS / 2);
  app.rows.push([t, lab.energy(), err, ...s]);
  if (app.rows.length > MAX_ROWS) app.rows.shift();
}

function frame() {
  try {
    app.lab.step(Number($("speed").value), Number($("dt").value));
  } catch (e) {
    setRunning(false);
    message(e.message);
    return false;
  }
  app.frames++;
  app.sceneFrozen = false;
  record();
  return true;
}

function setRunning(on) {
  app.running = on;
  $("run").textContent = on ? "Pause" : "Run";
}

function loop() {
  if (app.running && !app.drag) { frame(); draw(); }
  requestAnimationFrame(loop);
}

function message(text) { $("message").textContent = text; }

// ---------- drawing ----------

function grow(box, x, y) {
  if (!Number.isFinite(x) || !Number.isFinite(y)) return box;
  if (!box) return { x0: x, x1: x, y0: y, y1: y };
  return { x0: Math.min(box.x0, x), x1: Math.max(box.x1, x), y0: Math.min(box.y0, y), y1: Math.max(box.y1, y) };
}

// A transform from a box to the canvas, square (equal scales) if `square`, with a margin.
function view(canvas, box, square) {
  const w = canvas.width, h = canvas.height, m = 24;
  let { x0, x1, y0, y1 } = box;
  if (x1 - x0 < 1e-12) { x0 -= 1; x1 += 1; }
  if (y1 - y0 < 1e-12) { y0 -= 1; y1 += 1; }
  let sx = (w - 2 * m) / (x1 - x0), sy = (h - 2 * m) / (y1 - y0);
  if (square) sx = sy = Math.min(sx, sy);
  const cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
  return {
    X: (x) => w / 2 + (x - cx) * sx,
    Y: (y) => h / 2 - (y - cy) * sy,
    inv: (px, py) => [cx + (px - w / 2) / sx, cy - (py - h / 2) / sy],
  };
}

const SWARM_BANDS = 12;

// The view of 3-D points (a top): turned by AZIMUTH about the vertical, then tilted by
// ELEVATION towards the viewer; x across, z up. Returns [screen x, screen y, depth].
const AZIMUTH = 0.6, ELEVATION = 0.35;
function project3([x, y, z]) {
  const ca = Math.cos(AZIMUTH), sa = Math.sin(AZIMUTH), ce = Math.cos(ELEVATION), se = Math.sin(ELEVATION);
  const u = ca * x + sa * y, w = -sa * x + ca * y;
  return [u, ce * z - se * w, ce * w + se * z];
}

// The heavy top: the ground's axes and a unit square of floor, the symmetry axis from the
// pivot to the centre of mass with a disc across it, its shadow on the floor, and the path
// of the axis tip (the nutation loops).
function drawTop(c, ctx, tip) {
  const l = Math.hypot(tip[0], tip[1], tip[2]) || 1;
  app.sceneBox = { x0: -1.3 * l, x1: 1.3 * l, y0: -0.7 * l, y1: 1.3 * l };
  const v = view(c, app.sceneBox, true);
  app.sceneView = v;
  const P = (p) => { const [x, y] = project3(p); return [v.X(x), v.Y(y)]; };
  const line = (a, b) => { ctx.beginPath(); ctx.moveTo(...P(a)); ctx.lineTo(...P(b)); ctx.stroke(); };
  ctx.strokeStyle = "#ccc"; ctx.lineWidth = 1;
  ctx.beginPath();
  for (const [a, b] of [[[-l, -l, 0], [l, -l, 0]], [[l, -l, 0], [l, l, 0]], [[l, l, 0], [-l, l, 0]], [[-l, l, 0], [-l, -l, 0]]]) {
    ctx.moveTo(...P(a)); ctx.lineTo(...P(b));
  }
  ctx.stroke();
  ctx.fillStyle = "#555";
  for (const [axis, name] of [[[l, 0, 0], "x"], [[0, l, 0], "y"], [[0, 0, l], "z"]]) {
    ctx.strokeStyle = "#999"; line([0, 0, 0], axis);
    const [px, py] = P(axis.map((a) => 1.08 * a)); ctx.fillText(name, px - 4, py + 4);
  }
  // The tip's path, fading with age.
  ctx.lineWidth = 1.5;
  for (let k = 1; k < app.trails.length; k++) {
    ctx.strokeStyle = `rgba(40, 90, 200, ${0.1 + 0.7 * k / app.trails.length})`;
    line(app.trails[k - 1], app.trails[k]);
  }
  ctx.setLineDash([4, 4]); ctx.strokeStyle = "#aaa"; line([0, 0, 0], [tip[0], tip[1], 0]); ctx.setLineDash([]);
  ctx.strokeStyle = "#333"; ctx.lineWidth = 3; line([0, 0, 0], tip);
  // The disc: a circle of radius l/2 about the tip, across the axis.
  const a = tip.map((x) => x / l);
  let e1 = [a[1], -a[0], 0];
  const n1 = Math.hypot(...e1);
  e1 = n1 > 1e-9 ? e1.map((x) => x / n1) : [1, 0, 0];
  const e2 = [a[1] * e1[2] - a[2] * e1[1], a[2] * e1[0] - a[0] * e1[2], a[0] * e1[1] - a[1] * e1[0]];
  ctx.beginPath();
  for (let k = 0; k <= 48; k++) {
    const th = (2 * Math.PI * k) / 48, r = 0.5 * l;
    const p = [0, 1, 2].map((i) => tip[i] + r * (Math.cos(th) * e1[i] + Math.sin(th) * e2[i]));
    const [x, y] = P(p);
    if (k) ctx.lineTo(x, y); else ctx.moveTo(x, y);
  }
  ctx.fillStyle = "rgba(192, 57, 43, 0.35)"; ctx.fill();
  ctx.strokeStyle = "#c0392b"; ctx.lineWidth = 2; ctx.stroke();
  ctx.fillStyle = "#333"; ctx.fillRect(v.X(0) - 4, v.Y(0) - 4, 8, 8);
  ctx.lineWidth = 1;
  ctx.fillText("symmetry axis, pivot at the origin; its tip's path: precession and nutation", 8, 20);
}

function project(p) {
  // The 3D positions (a top's axis tip) as drawTop shows them.
  if (p.length === 3) { const [x, y] = project3(p); return [[x, y]]; }
  const out = [];
  for (let i = 0; i + 1 < p.length; i += 2) out.push([p[i], p[i + 1]]);
  return out;
}

function clear(ctx) {
  ctx.fillStyle = "#fff";
  ctx.fillRect(0, 0, ctx.canvas.width, ctx.canvas.height);
}

function font(ctx) {
  ctx.font = `${document.body.classList.contains("large") ? 22 : 14}px system-ui, sans-serif`;
}

function drawScene() {
  const c = $("scene"), ctx = c.getContext("2d");
  clear(ctx); font(ctx);
  const lab = app.lab, pos = lab.positions(), caps = app.entry.capabilities;
  if (pos.length) {
    if (pos.length === 3) { drawTop(c, ctx, pos); return; }
    const bodies = project(pos), linked = family() === "lagrangian";
    let box = grow(app.sceneBox, 0, 0);
    // While a body is dragged, and until the next frame, the view does not move under it.
    if (!app.sceneFrozen || !app.sceneBox) for (const [x, y] of bodies) box = grow(box, x, y);
    app.sceneBox = box;
    const v = view(c, box, true);
    app.sceneView = v;
    // Trails: every body's path, fading with age.
    const paths = app.trails.map(project);
    ctx.lineWidth = 1.5;
    for (let k = 1; k < paths.length; k++) {
      ctx.strokeStyle = `rgba(40, 90, 200, ${0.1 + 0.7 * k / paths.length})`;
      ctx.beginPath();
      paths[k].forEach(([x, y], b) => {
        const [x0, y0] = paths[k - 1][b] ?? [x, y];
        ctx.moveTo(v.X(x0), v.Y(y0)); ctx.lineTo(v.X(x), v.Y(y));
      });
      ctx.stroke();
    }
    ctx.strokeStyle = "#333"; ctx.lineWidth = 3;
    if (linked) {
      ctx.beginPath(); ctx.moveTo(v.X(0), v.Y(0));
      for (const [x, y] of bodies) ctx.lineTo(v.X(x), v.Y(y));
      ctx.stroke();
    }
    ctx.fillStyle = "#333";
    ctx.fillRect(v.X(0) - 4, v.Y(0) - 4, 8, 8);
    bodies.forEach(([x, y], i) => {
      ctx.beginPath(); ctx.arc(v.X(x), v.Y(y), 10, 0, 2 * Math.PI);
      ctx.fillStyle = app.drag?.body === i ? "#e07000" : "#c0392b"; ctx.fill();
    });
  } else if (caps.includes("per_particle_energy") || caps.includes("phase_space_area")) {
    // A swarm: every member as a point of its own (q, p) plane.
    const s = lab.state(), n = s.length / 2;
    let box = app.sceneBox;
    for (let i = 0; i < n; i++) box = grow(box, s[i], s[n + i]);
    app.sceneBox = box;
    const v = view(c, box, false);
    // One path and one fill per colour band (not a fillStyle per member): members keep
    // their hue along the swarm, in SWARM_BANDS steps.
    for (let b = 0; b < SWARM_BANDS; b++) {
      ctx.fillStyle = `hsl(${(300 * b) / SWARM_BANDS}, 70%, 45%)`;
      ctx.beginPath();
      const i1 = Math.round(((b + 1) * n) / SWARM_BANDS);
      for (let i = Math.round((b * n) / SWARM_BANDS); i < i1; i++) ctx.rect(v.X(s[i]) - 1.5, v.Y(s[n + i]) - 1.5, 3, 3);
      ctx.fill();
    }
    ctx.fillStyle = "#333";
    ctx.fillText(`${n} members: angle (across) and momentum (up)`, 8, 20);
  } else if (family() === "ode") {
    // A free rigid body: the angular momentum in the body frame traces the polhode.
    const s = lab.state();
    app.trails.push([s[0] - 0.45 * s[1], s[2] - 0.25 * s[1]]);
    if (app.trails.length > TRAIL) app.trails.shift();
    let box = app.sceneBox;
    for (const [x, y] of app.trails) box = grow(box, x, y);
    app.sceneBox = box = grow(grow(box, 0, 0), 0, 0);
    const v = view(c, box, true);
    ctx.strokeStyle = "#2860c8"; ctx.beginPath();
    app.trails.forEach(([x, y], k) => (k ? ctx.lineTo(v.X(x), v.Y(y)) : ctx.moveTo(v.X(x), v.Y(y))));
    ctx.stroke();
    const [x, y] = app.trails[app.trails.length - 1];
    ctx.strokeStyle = "#c0392b"; ctx.lineWidth = 3;
    ctx.beginPath(); ctx.moveTo(v.X(0), v.Y(0)); ctx.lineTo(v.X(x), v.Y(y)); ctx.stroke();
    ctx.lineWidth = 1; ctx.fillStyle = "#333";
    ctx.fillText("angular momentum in the body frame (its path: the polhode)", 8, 20);
  } else {
    // A chain: each site's displacement, sites left to right.
    const s = lab.state(), n = ndof();
    let box = grow(app.sceneBox, 0, 0);
    for (let i = 0; i < n; i++) box = grow(grow(box, i + 1, s[i]), i + 1, -s[i]);
    app.sceneBox = box = grow(box, n + 1, 0);
    const v = view(c, box, false);
    ctx.strokeStyle = "#999"; ctx.beginPath(); ctx.moveTo(v.X(0), v.Y(0)); ctx.lineTo(v.X(n + 1), v.Y(0)); ctx.stroke();
    ctx.strokeStyle = "#333"; ctx.beginPath(); ctx.moveTo(v.X(0), v.Y(0));
    for (let i = 0; i < n; i++) ctx.lineTo(v.X(i + 1), v.Y(s[i]));
    ctx.lineTo(v.X(n + 1), v.Y(0)); ctx.stroke();
    ctx.fillStyle = "#c0392b";
    const r = n > 60 ? 2 : 5;
    for (let i = 0; i < n; i++) { ctx.beginPath(); ctx.arc(v.X(i + 1), v.Y(s[i]), r, 0, 2 * Math.PI); ctx.fill(); }
    ctx.fillStyle = "#333";
    ctx.fillText(`${n} sites: displacement (up) against site`, 8, 20);
  }
}

function drawCurve(canvasId, points, boxKey, square, labels) {
  const c = $(canvasId), ctx = c.getContext("2d");
  clear(ctx); font(ctx);
  let box = app[boxKey];
  for (const [x, y] of points) box = grow(box, x, y);
  app[boxKey] = box;
  if (!box) return null;
  const v = view(c, box, square);
  ctx.strokeStyle = "#2860c8"; ctx.lineWidth = 1.5; ctx.beginPath();
  points.forEach(([x, y], k) => (k ? ctx.lineTo(v.X(x), v.Y(y)) : ctx.moveTo(v.X(x), v.Y(y))));
  ctx.stroke();
  ctx.fillStyle = "#333";
  ctx.fillText(labels[0], c.width - ctx.measureText(labels[0]).width - 8, c.height - 8);
  ctx.fillText(labels[1], 8, 20);
  return v;
}

function drawPhase() {
  const labels = stateLabels();
  drawCurve("phase", app.phase, "phaseBox", false, [labels[$("phase-x").value], labels[$("phase-y").value]]);
}

function drawEnergy() {
  const c = $("energy"), ctx = c.getContext("2d");
  clear(ctx); font(ctx);
  const pts = app.energy.map(([t, e]) => [t, Math.log10(Math.max(e, 1e-17))]);
  let lo = -17, hi = -15;
  for (const [, y] of pts) { if (y > -17) { lo = Math.min(lo === -17 ? y : lo, y); hi = Math.max(hi, y); } }
  lo = Math.floor(Math.min(lo, hi - 1)); hi = Math.ceil(hi);
  const t0 = pts.length ? pts[0][0] : 0, t1 = pts.length ? pts[pts.length - 1][0] : 1;
  const v = view(c, { x0: t0, x1: t1 > t0 ? t1 : t0 + 1, y0: lo, y1: hi }, false);
  ctx.strokeStyle = "#ddd"; ctx.fillStyle = "#555";
  for (let d = lo; d <= hi; d++) {
    ctx.beginPath(); ctx.moveTo(0, v.Y(d)); ctx.lineTo(c.width, v.Y(d)); ctx.stroke();
    ctx.fillText(`1e${d}`, 4, v.Y(d) - 2);
  }
  ctx.strokeStyle = "#c0392b"; ctx.lineWidth = 1.5; ctx.beginPath();
  pts.forEach(([x, y], k) => (k ? ctx.lineTo(v.X(x), v.Y(y)) : ctx.moveTo(v.X(x), v.Y(y))));
  ctx.stroke();
  ctx.fillStyle = "#333";
  ctx.fillText("t", c.width - 16, c.height - 8);
}

function drawSection() {
  if (!hasSection()) return;
  const c = $("section"), ctx = c.getContext("2d");
  clear(ctx); font(ctx);
  const x = app.lab.crossings(), n = app.lab.state().length;
  if (!app.sectionBox) {
    // Start from the box the energy allows a harmonic well: |x|, |px| <= sqrt(2|E|).
    const r = Math.sqrt(2 * Math.abs(app.lab.energy0())) * 1.2 || 1;
    app.sectionBox = { x0: -r, x1: r, y0: -r, y1: r };
  }
  for (let i = 0; i < x.length; i += n) app.sectionBox = grow(app.sectionBox, x[i], x[i + 2]);
  const v = view(c, app.sectionBox, false);
  app.sectionView = v;
  ctx.strokeStyle = "#eee";
  ctx.beginPath(); ctx.moveTo(v.X(0), 0); ctx.lineTo(v.X(0), c.height); ctx.moveTo(0, v.Y(0)); ctx.lineTo(c.width, v.Y(0)); ctx.stroke();
  ctx.fillStyle = "#1b4fa0";
  for (let i = 0; i < x.length; i += n) ctx.fillRect(v.X(x[i]) - 1.5, v.Y(x[i + 2]) - 1.5, 3, 3);
  const labels = stateLabels();
  ctx.fillStyle = "#333";
  ctx.fillText(labels[0], c.width - ctx.measureText(labels[0]).width - 8, c.height - 8);
  ctx.fillText(labels[2], 8, 20);
  $("section-energy").textContent = app.lab.energy0().toPrecision(6);
}

function draw() {
  $("time").textContent = app.lab.time().toFixed(3);
  $("energy-error").textContent = app.lab.energyError().toExponential(3);
  drawScene(); drawPhase(); drawEnergy(); drawSection();
}

// ---------- direct manipulation ----------

function canvasPoint(c, ev) {
  const r = c.getBoundingClientRect();
  return [((ev.clientX - r.left) * c.width) / r.width, ((ev.clientY - r.top) * c.height) / r.height];
}

// Solves positions(q)[body] = target for q by Gauss–Newton with finite differences, from
// the current configuration: a small Levenberg term keeps coordinates the dragged body does
// not depend on where they are (dragging the upper bob leaves the lower rod's angle), and a
// target out of reach ends at the nearest reachable point.
function solveConfiguration(q0, body, target) {
  const q = Array.from(q0), n = q.length;
  const residual = (qq) => {
    const [x, y] = project(app.lab.positionsOf(qq))[body];
    return [x - target[0], y - target[1]];
  };
  for (let it = 0; it < 20; it++) {
    const r = residual(q), J = [];
    for (let j = 0; j < n; j++) {
      const h = 1e-6 * Math.max(1, Math.abs(q[j]));
      const qq = q.slice(); qq[j] += h;
      const rr = residual(qq);
      J.push(rr.map((v, k) => (v - r[k]) / h));
    }
    // Normal equations (J^T J + mu I) dq = -J^T r, solved by Gaussian elimination.
    const A = Array.from({ length: n }, (_, a) => Array.from({ length: n }, (_, b) =>
      J[a].reduce((s, v, k) => s + v * J[b][k], 0) + (a === b ? 1e-9 : 0)));
    const g = Array.from({ length: n }, (_, a) => -J[a].reduce((s, v, k) => s + v * r[k], 0));
    for (let i = 0; i < n; i++) {
      for (let k = i + 1; k < n; k++) {
        const f = A[k][i] / A[i][i];
        for (let j = i; j < n; j++) A[k][j] -= f * A[i][j];
        g[k] -= f * g[i];
      }
    }
    const dq = new Array(n).fill(0);
    for (let i = n - 1; i >= 0; i--) {
      let s = g[i];
      for (let j = i + 1; j < n; j++) s -= A[i][j] * dq[j];
      dq[i] = s / A[i][i];
    }
    if (!dq.every(Number.isFinite)) break;
    dq.forEach((d, j) => (q[j] += d));
    if (Math.hypot(...dq) < 1e-12) break;
  }
  return q;
}

function onScenePointer(ev) {
  const c = $("scene"), v = app.sceneView, pos = app.lab.positions();
  if (!v || !pos.length || pos.length === 3 || family() === "ode") return;
  const [px, py] = canvasPoint(c, ev);
  if (ev.type === "pointerdown") {
    const bodies = project(pos);
    let best = -1, bestD = 30;
    bodies.forEach(([x, y], i) => {
      const d = Math.hypot(v.X(x) - px, v.Y(y) - py);
      if (d < bestD) { best = i; bestD = d; }
    });
    if (best < 0) return;
    c.setPointerCapture(ev.pointerId);
    app.drag = { body: best };
    app.sceneFrozen = true;
  } else if (ev.type === "pointermove" && app.drag) {
    const s = app.lab.state(), n = ndof();
    const q = solveConfiguration(s.slice(0, n), app.drag.body, v.inv(px, py));
    // A pendulum is let go from rest; an orbiting body keeps its momentum.
    const rest = family() === "lagrangian" ? new Array(n).fill(0) : Array.from(s.slice(n));
    try { app.lab.setState([...q, ...rest]); message(""); } catch (e) { message(e.message); }
    // The view stays put while dragging, so the body stays under the pointer.
    const box = app.sceneBox;
    clearViews();
    app.sceneBox = box;
    draw();
  } else if ((ev.type === "pointerup" || ev.type === "pointercancel") && app.drag) {
    app.drag = null;
    const box = app.sceneBox;
    clearViews();
    app.sceneBox = box;
    draw();
  }
}

function onSectionClick(ev) {
  const v = app.sectionView;
  if (!v) return;
  const [x, px] = v.inv(...canvasPoint($("section"), ev));
  try {
    app.lab.launch([[0, x], [2, px], [1, 0]], 3);
    message("");
  } catch (e) {
    message(e.message);
    return;
  }
  const keep = app.sectionBox;
  app.trails = []; app.phase = []; app.energy = []; app.rows = []; app.sceneBox = null; app.phaseBox = null;
  app.sectionBox = keep;
  record();
  draw();
}

// ---------- share link and data ----------

function shareHash() {
  const h = new URLSearchParams();
  h.set("system", app.entry.name);
  h.set("method", $("method").value);
  h.set("dt", $("dt").value);
  h.set("steps", $("speed").value);
  h.set("params", JSON.stringify(app.params));
  // Shortest round-trip decimal of each number: the state comes back bit for bit.
  h.set("state", Array.from(app.lab.initialState()).map(String).join(","));
  return `#${h.toString()}`;
}

function applyHash(hash) {
  const h = new URLSearchParams(hash.replace(/^#/, ""));
  const entry = app.catalogue.systems.find((s) => s.name === h.get("system"));
  if (!entry) return false;
  selectSystem(entry.name, JSON.parse(h.get("params") || "{}"), false);
  if (h.get("method")) fillMethods(h.get("method"));
  if (h.get("dt")) {
    const dt = Number(h.get("dt"));
    if (![...$("dt").options].some((o) => Number(o.value) === dt)) $("dt").append(new Option(String(dt), String(dt)));
    $("dt").value = String(dt);
  }
  if (h.get("steps")) { $("speed").value = h.get("steps"); $("speed-out").textContent = $("speed").value; }
  const state = h.get("state") ? h.get("state").split(",").map(Number) : null;
  return rebuild(state);
}

function download(name, text, type) {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(new Blob([text], { type }));
  a.download = name;
  a.click();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}

function runData() {
  const columns = ["t", "energy", "energy_error", ...stateLabels()];
  return { columns, rows: app.rows };
}

// ---------- wiring ----------

function selectSystem(name, params = {}, build = true) {
  app.entry = app.catalogue.systems.find((s) => s.name === name);
  $("system").value = name;
  app.params = { ...params };
  const note = app.entry.note ? ` ${app.entry.note}` : "";
  $("caption").textContent = `${app.entry.summary}.${note}`;
  // The physics paragraph: the gallery's text for this system, from the catalogue JSON.
  $("physics").textContent = app.entry.physics ?? "";
  $("about").hidden = !app.entry.physics;
  fillParams();
  setControlValues();
  // A new system starts from its own default method (the catalogue's).
  fillMethods(null);
  if (build) rebuild();
}

async function main() {
  const bytes = await (await fetch("physicskit_wasm.wasm")).arrayBuffer();
  app.core = await load(bytes);
  app.catalogue = app.core.catalogue();
  fillSystems();
  $("dt").replaceChildren(...DTS.map((d) => new Option(String(d), String(d))));
  $("dt").value = String(DEFAULT_DT);
  $("speed").value = DEFAULT_STEPS;
  $("speed-out").textContent = DEFAULT_STEPS;
  $("system").onchange = () => selectSystem($("system").value);
  $("method").onchange = () => {
    describeMethod();
    try { app.lab.setMethod($("method").value); app.lab.reset(); clearViews(); draw(); } catch (e) { message(e.message); }
  };
  $("dt").onchange = () => { app.lab.reset(); clearViews(); draw(); };
  $("speed").oninput = () => { $("speed-out").textContent = $("speed").value; };
  $("run").onclick = () => setRunning(!app.running);
  $("step").onclick = () => { setRunning(false); frame(); draw(); };
  $("reset").onclick = () => { app.lab.reset(); clearViews(); draw(); };
  $("share").onclick = async () => {
    const url = `${location.href.split("#")[0]}${shareHash()}`;
    history.replaceState(null, "", url);
    try { await navigator.clipboard.writeText(url); message("Link copied (also in the address bar)."); } catch { message("Link in the address bar."); }
  };
  $("csv").onclick = () => {
    const { columns, rows } = runData();
    download(`${app.entry.name}.csv`, [columns.join(","), ...rows.map((r) => r.join(","))].join("\n") + "\n", "text/csv");
  };
  $("json").onclick = () => {
    const { columns, rows } = runData();
    download(`${app.entry.name}.json`, JSON.stringify({ system: app.entry.name, params: app.params,
      method: $("method").value, dt: Number($("dt").value), initial_state: Array.from(app.lab.initialState()),
      columns, rows }), "application/json");
  };
  $("large").onchange = () => { document.body.classList.toggle("large", $("large").checked); draw(); };
  $("phase-x").onchange = $("phase-y").onchange = () => { app.phase = []; app.phaseBox = null; record(); draw(); };
  $("section-clear").onclick = () => { app.lab.clearCrossings(); draw(); };
  $("section-on").onchange = () => rebuild(Array.from(app.lab.state()));
  for (const t of ["pointerdown", "pointermove", "pointerup", "pointercancel"]) $("scene").addEventListener(t, onScenePointer);
  $("section").addEventListener("click", onSectionClick);
  if (!(location.hash && applyHash(location.hash))) selectSystem(app.catalogue.systems[0].name);
  requestAnimationFrame(loop);
}

// For the browser test and the benchmark: the page's own state and a way to step it.
window.physicskitLab = {
  app,
  ready: main().catch((e) => { message(`Could not start: ${e.message}`); throw e; }),
  select: (name) => { setRunning(false); selectSystem(name); },
  runFrames: (n) => { setRunning(false); for (let i = 0; i < n; i++) if (!frame()) return false; draw(); return true; },
  shareHash: () => shareHash(),
  openHash: (hash) => { setRunning(false); return applyHash(hash); },
  bodiesOnScreen: () => {
    const c = $("scene"), r = c.getBoundingClientRect(), v = app.sceneView;
    return project(app.lab.positions()).map(([x, y]) => [r.left + (v.X(x) * r.width) / c.width, r.top + (v.Y(y) * r.height) / c.height]);
  },
  sectionToScreen: (x, px) => {
    const c = $("section"), r = c.getBoundingClientRect(), v = app.sectionView;
    return [r.left + (v.X(x) * r.width) / c.width, r.top + (v.Y(px) * r.height) / c.height];
  },
};
