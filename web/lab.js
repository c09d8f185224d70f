// The lab page: pickers and sliders generated from the catalogue (the JSON `physicskit list
// --json` prints, read from the WebAssembly module; the lab shows its text for people:
// `summary_text`, `note_text`, `label`, `unit_text`, `help_text`, and labels its axes from each
// system's `presentation`: symbols, units, unit of time), a frame loop stepping the
// Rust integrators, and the views, each with axes, ticks and units from a view fixed when a
// run starts: the scene (each kind of body drawn as what it is, with a trail sampled inside
// each frame), a phase-space panel, the energy error on a log scale and, for two-degree-of-
// freedom separable Hamiltonians, a Poincaré section whose launched orbits accumulate.
//
// A share link is untrusted input: every field is checked, what is refused is named in one
// line, and the page always opens the linked system (or the default) with valid values.
import { load } from "./physicskit.js";

const $ = (id) => document.getElementById(id);
const DTS = [1e-4, 2e-4, 5e-4, 1e-3, 2e-3, 5e-3, 1e-2, 2e-2, 5e-2, 0.1];
const DEFAULT_DT = 1e-3;
const DEFAULT_STEPS = 25;
// An adaptive method (dop853, taylor) takes a tolerance (rtol = atol) in place of the step,
// which is then only the output spacing: its steps are chosen to the tolerance. The menu runs
// from 1e-6 (an energy drift one sees over a long run) to 1e-14 (near the rounding floor of
// double precision for these systems); the default is the core's default rtol. A link's
// tolerance must lie in the menu's range.
const TOLS = [1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14];
const DEFAULT_TOL = 1e-10;
const MIN_TOL = TOLS[TOLS.length - 1], MAX_TOL = TOLS[0];
// The step sizes a link may ask for: the menu's range. Outside it a frame either crawls or
// blows up, so a link's dt there is refused rather than offered.
const MIN_DT = DTS[0], MAX_DT = DTS[DTS.length - 1];
// Trail samples per frame: the frame's steps are run in this many pieces (the bits of the
// run do not depend on how its steps are grouped), so a fast orbit draws as a curve.
const SAMPLES_PER_FRAME = 8;
const TRAIL = 2400, PHASE_TRAIL = 6000, ENERGY_POINTS = 3000, MAX_ROWS = 100000;
const TAU = 2 * Math.PI;
// How a system is stepped frame by frame: the catalogue's pace (`presentation.pace`). A
// "fixed" pace is for a system whose default method is adaptive: it opens with that fixed-step
// method, step and steps a frame (1/60 s of motion a frame: real time at 60 frames a second),
// whose energy error the catalogue's tests bound; the adaptive method is in the menu too. A
// "time_lapse" is offered for a system whose effect builds up over hours (Foucault's swing
// plane turns at the Earth's rate): more of the same physics each frame. Other systems open at
// DEFAULT_DT and DEFAULT_STEPS.
function stepDefaults(entry) {
  const p = entry.presentation.pace;
  if (p.kind !== "fixed") return null;
  const bound = scientific(p.energy_error);
  return {
    method: p.method, dt: p.dt, steps: p.steps_per_frame,
    note: `Step: ${p.method} at dt = ${p.dt} s, ${p.steps_per_frame} steps a frame (real time at 60 frames a second), which keeps the energy error below ${bound}; the catalogue's own method, ${entry.default_method}, is in the menu too, at a tolerance instead of a step.`,
  };
}
function timeLapse(entry) {
  const p = entry.presentation.pace;
  if (p.kind !== "time_lapse") return null;
  const perFrame = p.dt * p.steps_per_frame;
  return {
    dt: p.dt, steps: p.steps_per_frame,
    note: `Time-lapse: ${Number(perFrame.toPrecision(6))} s of the system's time each frame, ${Math.round(perFrame * 60)}× real time at 60 frames a second (dt = ${p.dt} s, ${p.steps_per_frame} steps a frame). The physics is unchanged.`,
  };
}
// The system shown when no link names one: the chaotic double pendulum, running on load.
const DEFAULT_SYSTEM = "double-pendulum";

const app = {
  core: null, catalogue: null, entry: null, lab: null, params: {},
  running: false, trails: [], phase: [], energy: [], rows: [],
  sceneBox: null, phaseBox: null, sectionBox: null, boundary: null, drag: null, frames: 0,
  // The tick labels each canvas drew last, for the tests: {x: [..], y: [..], xLabel, yLabel}.
  ticks: {},
  extent: null,
};

// ---------- words ----------

function systemTitle(entry) { return entry.title ?? entry.name; }

function methodTitle(name) { return name.replace(/_/g, " "); }

// The catalogue's words for the state (`presentation`: the coordinates' symbols in TeX, the
// unit of time; the initial-state parameters' units, else `presentation.state_units`), as
// Python's plot labels read them. TeX becomes text in one place, `texRuns`: Greek letters,
// `\dot{..}` as a combining dot, `_{..}` as a subscript run; the canvases draw subscript runs
// lowered in a smaller font, page text uses Unicode subscripts where they exist.
const GREEK = {
  alpha: "α", beta: "β", gamma: "γ", delta: "δ", epsilon: "ε", zeta: "ζ", eta: "η", theta: "θ",
  vartheta: "ϑ", kappa: "κ", lambda: "λ", mu: "μ", nu: "ν", xi: "ξ", pi: "π", rho: "ρ", sigma: "σ",
  tau: "τ", phi: "φ", varphi: "φ", chi: "χ", psi: "ψ", omega: "ω", Gamma: "Γ", Delta: "Δ",
  Theta: "Θ", Lambda: "Λ", Xi: "Ξ", Pi: "Π", Sigma: "Σ", Phi: "Φ", Psi: "Ψ", Omega: "Ω",
};
const SUBSCRIPT = {
  0: "₀", 1: "₁", 2: "₂", 3: "₃", 4: "₄", 5: "₅", 6: "₆", 7: "₇", 8: "₈", 9: "₉", "+": "₊", "-": "₋",
  a: "ₐ", e: "ₑ", h: "ₕ", i: "ᵢ", j: "ⱼ", k: "ₖ", l: "ₗ", m: "ₘ", n: "ₙ", o: "ₒ", p: "ₚ", r: "ᵣ",
  s: "ₛ", t: "ₜ", u: "ᵤ", v: "ᵥ", x: "ₓ", "β": "ᵦ", "γ": "ᵧ", "ρ": "ᵨ", "φ": "ᵩ", "χ": "ᵪ",
};
const DOT = "\u0307";
// TeX (as the catalogue writes symbols) into runs [{text, sub}].
function texRuns(tex) {
  const runs = [];
  const put = (text, sub) => {
    if (!text) return;
    const last = runs[runs.length - 1];
    if (last && last.sub === sub) last.text += text; else runs.push({ text, sub });
  };
  // One group: `{...}`, a command `\name`, or one character; returns [text, next index].
  const group = (s, i) => {
    if (s[i] === "{") {
      let depth = 1, j = i + 1;
      while (j < s.length && depth) { if (s[j] === "{") depth++; else if (s[j] === "}") depth--; j++; }
      return [plain(s.slice(i + 1, j - 1)), j];
    }
    if (s[i] === "\\") {
      const m = /^\\([A-Za-z]+)/.exec(s.slice(i));
      if (m) return command(m[1], s, i + m[0].length);
    }
    return [s[i] ?? "", i + 1];
  };
  const command = (name, s, j) => {
    if (name === "dot" || name === "ddot") {
      const [inner, k] = group(s, j);
      return [inner + (name === "dot" ? DOT : "\u0308"), k];
    }
    return [GREEK[name] ?? name, j];
  };
  const plain = (s) => {
    let out = "";
    for (let i = 0; i < s.length;) { const [t, j] = group(s, i); out += t; i = j; }
    return out;
  };
  for (let i = 0; i < tex.length;) {
    if (tex[i] === "_") { const [t, j] = group(tex, i + 1); put(t, true); i = j; continue; }
    const [t, j] = group(tex, i);
    put(t, false);
    i = j;
  }
  return runs;
}
// Runs as page text: a subscript in Unicode subscripts if each of its characters has one,
// else as it is.
function runsText(runs) {
  return runs.map((r) => (r.sub && [...r.text].every((c) => SUBSCRIPT[c]) ? [...r.text].map((c) => SUBSCRIPT[c]).join("") : r.text)).join("");
}
function texText(tex) { return runsText(texRuns(tex)); }
// The catalogue's text for people (labels, captions, help, the physics paragraph: written for
// people by physicskit-listing's people.rs, which marks every index `_{..}`) into runs: the
// marked indices lowered, the rest as it is. The lab's own captions use the same markup.
function peopleRuns(text) {
  const runs = [];
  let last = 0;
  for (const m of text.matchAll(/_\{([^{}]*)\}/g)) {
    runs.push({ text: text.slice(last, m.index), sub: false }, { text: m[1], sub: true });
    last = m.index + m[0].length;
  }
  runs.push({ text: text.slice(last), sub: false });
  return runs.filter((r) => r.text);
}
// Runs into a page element: text, and `<sub>` for subscripts (built as nodes, never as HTML).
function setRuns(el, runs) {
  el.replaceChildren(...runs.map((r) => { if (!r.sub) return document.createTextNode(r.text); const e = document.createElement("sub"); e.textContent = r.text; return e; }));
}
// The catalogue's unit words for people: powers as superscripts (`kg m^2`, as people.rs does
// for parameter units).
function unitWords(unit) {
  return (unit ?? "").replace(/\^\{?(-?\d+)\}?/g, (_, p) => superscriptInt(p));
}

// A label: TeX symbol and unit; `text` is what the page shows and the tests read.
function label(tex, unit = "") {
  const runs = texRuns(tex);
  if (unit) runs.push({ text: ` (${unit})`, sub: false });
  return { runs, text: runsText(runs) };
}
function plainLabel(text) { return { runs: [{ text, sub: false }], text }; }

function presentation() { return app.entry.presentation; }
// The catalogue's unit of time: "s", "time" (the user's own units, as Kepler's "length"), or
// "" (a dimensionless system, which the caption says once).
function timeUnit() { return presentation().time_unit; }
function timeLabel() { return label("t", timeUnit()); }
// Drawing positions are in metres where the system's lengths are; a body on an orbit is drawn
// at its coordinates, in their unit (Kepler's "length").
function lengthUnit() {
  if (app.entry.params.some((p) => p.unit_text === "m")) return "m";
  return presentation().drawing.kind === "orbit" ? stateUnits()[0] ?? "" : "";
}
// An axis of the drawing's lengths: "x (m)", or "x / l" where the positions are in units of
// a length of the system's own (the catalogue's drawing `scale`: a simple pendulum's rod).
function lengthLabel(sym) {
  const scale = presentation().drawing.scale;
  return scale ? `${sym} / ${texText(scale)}` : withUnit(sym, lengthUnit());
}

// The state's layout: `k` coordinates, then (for a Hamiltonian, a Lagrangian, or an ODE whose
// symbols name half its entries) their momenta or velocities.
function stateLayout() {
  const n = app.lab.state().length, symbols = presentation().symbols ?? [];
  if (family() !== "ode") return { k: n / 2, paired: true, dot: family() === "lagrangian" };
  if (symbols.length && 2 * symbols.length === n) return { k: n / 2, paired: true, dot: true };
  return { k: n, paired: false, dot: false };
}
function symbolOf(i, k) {
  const symbols = presentation().symbols ?? [];
  if (symbols.length >= k && symbols.length) return symbols[i];
  if (symbols.length === 1) return k === 1 ? symbols[0] : `${symbols[0]}_{${i + 1}}`;
  return family() === "ode" ? `y_{${i + 1}}` : k === 1 ? "q" : `q_{${i + 1}}`;
}
// A dotted or momentum symbol: \dot{θ}_1 keeps the index outside the dot.
function momentumOf(sym, dot) {
  const m = /^(.*?)(_\{[^}]*\}|_.)?$/.exec(sym);
  if (dot) return `\\dot{${m[1]}}${m[2] ?? ""}`;
  // An indexed coordinate's momentum takes its index (q₁, p₁); a named one's, its name (pₓ).
  return m[2] ? `p${m[2]}` : `p_{${sym}}`;
}
// Names of the entries of the state layouts the lab draws whose catalogue symbols are empty
// (the catalogue names them only in its notes for the command line): a rigid body's body
// rates and orientation quaternion, a rolling body's contact point after them, the reduced
// rattleback's rates; with their units (the rates' from the initial-state parameter; an entry
// started from other values, such as a steady motion's tilt and precession, has rates in
// radians per its unit of time; the contact point's the system's length). Null for other
// systems.
function layoutNames() {
  if ((presentation().symbols ?? []).length) return null;
  const k = kind(), starts = app.entry.params.filter((p) => p.initial_state);
  const rate = starts[0]?.unit_text ?? (timeUnit() ? `rad/${timeUnit()}` : "");
  if (k === "rigid" || k === "rolling") {
    const names = ["\\omega_1", "\\omega_2", "\\omega_3", "q_w", "q_x", "q_y", "q_z"], units = [rate, rate, rate, "", "", "", ""];
    return k === "rolling" ? { names: [...names, "x", "y"], units: [...units, lengthUnit(), lengthUnit()] } : { names, units };
  }
  if (k === "spinner") return { names: ["n_1", "n_2", "n_3"], units: [rate, rate, rate] };
  return null;
}
// TeX symbols of the state's entries.
function stateSymbols() {
  const named = layoutNames();
  if (named && named.names.length === app.lab.state().length) return named.names;
  const { k, paired, dot } = stateLayout(), q = Array.from({ length: k }, (_, i) => symbolOf(i, k));
  return paired ? [...q, ...q.map((s) => momentumOf(s, dot))] : q;
}
// Units of the state's entries: one initial-state parameter per entry, or one for the
// coordinates and one for the momenta (a unit list `m, rad` names one per coordinate), else
// the presentation's state units.
function stateUnits() {
  const n = app.lab.state().length, { k, paired } = stateLayout(), named = layoutNames();
  if (named && named.units.length === n) return named.units;
  const starts = app.entry.params.filter((p) => p.initial_state);
  if (starts.length === n && starts.every((p) => p.kind !== "vector")) return starts.map((p) => p.unit_text ?? "");
  let units = starts.map((p) => p.unit_text ?? "");
  if (!starts.length && presentation().state_units) units = presentation().state_units.map(unitWords);
  if (!units.length || (!paired && starts.length !== 1)) return new Array(n).fill("");
  const pick = (u, i) => { const parts = (u ?? "").split(/,\s*/); return parts.length === k ? parts[i] : parts.length === 1 ? parts[0] : ""; };
  const q = Array.from({ length: k }, (_, i) => pick(units[0], i));
  return paired ? [...q, ...Array.from({ length: k }, (_, i) => pick(units[1], i))] : q;
}
// Labels of the state's entries for axes ({runs, text}), and their text for the page.
// Kept for the system and state length they were made for: a frame reads two of them, and a
// swarm has thousands.
function stateAxisLabels() {
  const key = `${app.entry.name}/${app.lab.state().length}`;
  if (app.axisLabels?.key !== key) {
    const units = stateUnits();
    app.axisLabels = { key, labels: stateSymbols().map((s, i) => label(s, units[i])) };
  }
  return app.axisLabels.labels;
}
function stateLabels() { return stateSymbols().map(texText); }
function withUnit(name, unit) { return unit ? `${name} (${unit})` : name; }

const SUB = "₀₁₂₃₄₅₆₇₈₉";
function subscript(n) { return String(n).split("").map((d) => SUB[Number(d)]).join(""); }

// ---------- catalogue-driven controls ----------

function fillSystems() {
  $("system").replaceChildren(...app.catalogue.systems.map((s) => new Option(systemTitle(s), s.name)));
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

let controlId = 0;
function paramControl(p) {
  const div = document.createElement("div");
  div.className = "param";
  const id = `param-${controlId++}`;
  const label = document.createElement("label");
  label.htmlFor = id;
  label.className = "param-name";
  setRuns(label, peopleRuns(p.label));
  if (p.unit_text) { const u = document.createElement("span"); u.className = "unit"; u.textContent = ` (${p.unit_text})`; label.append(u); }
  const help = document.createElement("div");
  help.className = "help";
  setRuns(help, peopleRuns(p.help_text ?? ""));
  const row = document.createElement("div");
  row.className = "param-row";
  div.append(label, row, help);
  const set = (v) => { if (v === null || v === "") delete app.params[p.name]; else app.params[p.name] = v; rebuildSoon(); };
  if (p.kind === "choice") {
    const sel = document.createElement("select");
    sel.id = id;
    sel.dataset.param = p.name;
    sel.append(...p.choices.map((c) => new Option(c, c)));
    if (p.default !== null) sel.value = p.default;
    sel.onchange = () => set(sel.value);
    row.append(sel);
  } else if (p.kind === "vector") {
    const inp = document.createElement("input");
    inp.type = "text";
    inp.id = id;
    inp.dataset.param = p.name;
    inp.value = Array.isArray(p.default) ? p.default.join(", ") : "";
    inp.placeholder = p.default === null ? "automatic" : "";
    inp.onchange = () => {
      const t = inp.value.trim();
      set(t === "" ? null : t.split(/[\s,]+/).filter(Boolean).map(Number));
    };
    row.append(inp);
  } else {
    const [lo, hi] = sliderRange(p);
    const slider = document.createElement("input");
    slider.type = "range";
    slider.min = lo; slider.max = hi;
    slider.step = p.kind === "integer" ? 1 : (hi - lo) / 1000;
    slider.value = p.default ?? (lo + hi) / 2;
    slider.setAttribute("aria-label", `${runsText(peopleRuns(p.label))} (slider)`);
    const num = document.createElement("input");
    num.type = "number";
    num.id = id;
    num.dataset.param = p.name;
    num.step = p.kind === "integer" ? "1" : "any";
    num.value = p.default ?? "";
    slider.oninput = () => { num.value = Number(slider.value).toPrecision(4).replace(/\.?0+$/, "").replace(/\.?0+e/, "e"); set(Number(num.value)); };
    num.onchange = () => { if (num.value !== "") slider.value = num.value; set(num.value === "" ? null : Number(num.value)); };
    row.append(slider, num);
  }
  return div;
}

function fillParams() {
  $("params").replaceChildren(...app.entry.params.map(paramControl));
}

function setControlValues() {
  for (const el of $("params").querySelectorAll("[data-param]")) {
    const v = app.params[el.dataset.param];
    if (v !== undefined) {
      el.value = Array.isArray(v) ? v.join(", ") : v;
      const slider = el.parentElement.querySelector("input[type=range]");
      if (slider && !Array.isArray(v)) slider.value = v;
    }
  }
}

// Every method the system takes is offered; an adaptive one (the catalogue's `adaptive`) runs
// at a tolerance, with the step as its output spacing.
function offeredMethods() {
  return app.entry.methods;
}
function isAdaptive(name) { return !!app.catalogue.methods.find((x) => x.name === name)?.adaptive; }
// The tolerance the labs are built and run at (kept by a fixed-step method for the next
// adaptive one).
function tolerance() { return Number($("tol").value) || DEFAULT_TOL; }

function fillMethods(keep) {
  const sel = $("method"), fixed = offeredMethods();
  sel.replaceChildren(...fixed.map((m) => new Option(methodTitle(m), m)));
  sel.value = fixed.includes(keep) ? keep : fixed.includes(app.entry.default_method) ? app.entry.default_method : fixed[0];
  describeMethod();
}

// The step control of the chosen method: the step dt, or for an adaptive method its tolerance
// (the step then only spaces the outputs, and is kept as it was).
function showStepControl() {
  const adaptive = isAdaptive($("method").value);
  $("tol-row").hidden = !adaptive;
  $("dt").closest(".param").hidden = adaptive;
  // An adaptive method takes its own steps: a frame advances this many outputs, dt apart.
  document.querySelector("label[for=speed]").firstChild.textContent = adaptive ? "Outputs per frame " : "Steps per frame ";
}

// The tolerance menu, next to the step's (the page's HTML has the step's only).
function addToleranceControl() {
  const row = document.createElement("div");
  row.className = "param";
  row.id = "tol-row";
  row.hidden = true;
  const label = document.createElement("label");
  label.htmlFor = "tol";
  label.textContent = "Tolerance (rtol = atol)";
  const sel = document.createElement("select");
  sel.id = "tol";
  sel.replaceChildren(...TOLS.map((t) => new Option(scientific(t), String(t))));
  sel.value = String(DEFAULT_TOL);
  row.append(label, sel);
  $("dt").closest(".param").after(row);
}

function describeMethod() {
  showStepControl();
  const m = app.catalogue.methods.find((x) => x.name === $("method").value);
  if (!m) { $("method-info").textContent = ""; $("method-ref").textContent = ""; return; }
  // What is counted, without the catalogue's remarks after it; "per …" where it says per what.
  let what = m.evaluations.split(/[,:;(]/)[0].trim(), per = "per step";
  const at = what.indexOf(" per ");
  if (at >= 0) { per = what.slice(at + 1); what = what.slice(0, at); }
  const ev = m.evaluations_per_step === 1 ? what.replace(/s(?= of |$)/, "") : what;
  // An adaptive method's steps are its own (to the tolerance); dt spaces its outputs.
  const how = m.adaptive ? ` · adaptive: its own steps to the tolerance, an output every dt = ${$("dt").value}${timeUnit() ? ` ${timeUnit()}` : ""}` : "";
  // The order the method steps at: Taylor's follows the tolerance and the system's equations
  // (the core's rule, asked of the module), up to the catalogue's maximum. Parameters the
  // system refuses leave it unknown (the run says why).
  let order = null;
  try {
    order = app.core.methodOrder(app.entry.name, app.params, m.name, tolerance());
  } catch { order = null; }
  const atTol = order === m.order ? "" : ` at this tolerance (at most ${m.order})`;
  const orderText = order === null ? `order up to ${m.order}` : `order ${order}${atTol}`;
  $("method-info").textContent = `${orderText} · ${m.symplectic ? "symplectic" : "not symplectic"}${how} · ` +
    `${m.evaluations_per_step} ${ev} ${per}`;
  $("method-ref").textContent = m.reference;
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
// for those only; it is on from the start where the catalogue says it is the picture that
// matters (`presentation.section_first`: Hénon–Heiles, islands in a chaotic sea).
// Only where the section's edge on the energy surface is closed: an unbounded flight (a
// projectile) crosses the plane once and has no section to show.
function sectionOffered() { return family() === "hamiltonian" && app.entry.separable && ndof() === 2 && app.sectionClosed; }
function hasSection() { return sectionOffered() && $("section-on").checked; }
// The lab's picture of the system: the catalogue's drawing (`presentation.drawing`) and its
// attributes, as the names the drawing code below uses.
function kind() {
  const d = presentation().drawing;
  switch (d.kind) {
    case "bobs": return d.springs ? "spring" : "pendulum";
    case "orbit": return d.ground ? "projectile" : d.central_body ? "orbit" : "bodies";
    case "chain": return "chain";
    case "field": return "sites";
    case "inertia_box": return "rigid";
    case "top_axis": return "top";
    case "contact_spiral": return "disk";
    case "spin": return "spinner";
    case "rolling": return "rolling";
    case "swing": case "swarm": case "hoop": return d.kind;
    default: return "series";
  }
}
function draggable() { return ["projectile", "orbit", "hoop", "spring", "pendulum", "bodies", "chain", "sites", "top"].includes(kind()); }

// Builds the system with the chosen method (some values run only with some methods: a
// projectile with drag is not separable, so the splitting methods refuse it). If the chosen
// method refuses these values, the first offered method that takes them is chosen instead, and
// the page says so.
function buildLab(state0) {
  const chosen = $("method").value;
  let first = null;
  for (const m of [chosen, ...offeredMethods().filter((x) => x !== chosen)]) {
    let lab;
    try {
      lab = app.core.build(app.entry.name, app.params, m, tolerance());
      if (state0) lab.setState(state0);
    } catch (e) {
      lab?.free();
      first ??= e;
      continue;
    }
    if (m !== chosen) {
      fillMethods(m);
      return { lab, note: `${methodTitle(chosen)} cannot run this setup (${first.message}); running with ${methodTitle(m)}.` };
    }
    return { lab, note: null };
  }
  throw first;
}

function rebuild(state0 = null, keepMessage = false) {
  let built;
  try { built = buildLab(state0); } catch (e) { message(e.message); return false; }
  const lab = built.lab;
  app.lab?.free();
  app.lab = lab;
  const labels = stateLabels(), units = stateUnits();
  // The phase panel starts at (q, p) of one site (the middle one of a chain, where a wave or
  // a kink passes) for each new system and keeps the reader's choice while it is rebuilt.
  const same = app.phaseSystem === app.entry.name;
  app.phaseSystem = app.entry.name;
  app.sectionClosed = family() === "hamiltonian" && app.entry.separable && ndof() === 2 && sectionBoundary() !== null;
  if (!same) $("section-on").checked = app.entry.presentation.section_first;
  $("section-choice").hidden = !sectionOffered();
  const { k: kk, paired } = stateLayout(), k = paired ? kk : 0;
  // The site that moves most over the probe run (a chain's wave or kink passes there).
  app.extent = probeExtent();
  let site = 0;
  if (paired && k > 2 && app.extent) {
    for (let i = 1; i < k; i++) if (app.extent.hi[i] - app.extent.lo[i] > app.extent.hi[site] - app.extent.lo[site]) site = i;
  }
  for (const [id, def] of [["phase-x", site], ["phase-y", paired ? k + site : 1]]) {
    const sel = $(id), old = sel.value;
    sel.replaceChildren(...labels.map((l, i) => new Option(withUnit(l, units[i]), i)));
    sel.value = same && old !== "" && Number(old) < labels.length ? old : Math.min(def, labels.length - 1);
  }
  $("section-figure").hidden = !hasSection();
  if (hasSection()) {
    lab.setSection(1, 0, 1);
    const sym = stateSymbols();
    setRuns($("section-name"), [...texRuns(sym[1]), { text: " = 0, ", sub: false }, ...texRuns(sym[3]), { text: " > 0", sub: false }]);
  }
  $("drag-hint").hidden = !draggable();
  // A swarm's phase panel is its close-up (the scene is its phase plane).
  $("phase-choice").hidden = kind() === "swarm";
  $("closeup-caption").hidden = kind() !== "swarm";
  startViews(app.extent);
  if (built.note) message(built.note, "notice");
  else if (!keepMessage) message("");
  draw();
  return true;
}

// A new run: views fixed from the run's own extent. A new system or new parameters fit them
// afresh; a new run of the same setup (`keep`: a drag let go, Reset, another method or step,
// an orbit launched on the section) keeps the frames it had and grows them to take in the new
// run, never shrinking them, so the picture does not jump (a short flight after a drag is
// drawn short, at the scale of the ground and the launcher before).
function startViews(extent = null, keep = false) {
  const scene = app.sceneBox, phase = app.phaseBox, amp = app.chainGeom?.amp;
  clearViews();
  app.extent = extent ?? probeExtent();
  app.sceneBox = sceneBoxFrom(app.extent);
  if (keep && scene) {
    // The kept frame, unless the new run comes within 0.03 of its edges (a body drawn there,
    // 7 px wide, would be cut): then widened to hold the run with the frame's own margin,
    // 0.08 of it (a short run's margin, 0.08 of itself, is too thin for its body).
    const b = sceneBoxFrom(app.extent, 0), W = scene.x1 - scene.x0, H = scene.y1 - scene.y0;
    const inside = !b || (b.x0 >= scene.x0 + 0.03 * W && b.x1 <= scene.x1 - 0.03 * W && b.y0 >= scene.y0 + 0.03 * H && b.y1 <= scene.y1 - 0.03 * H);
    app.sceneBox = inside ? scene : union(scene, { x0: b.x0 - 0.08 * W, x1: b.x1 + 0.08 * W, y0: b.y0 - 0.08 * H, y1: b.y1 + 0.08 * H });
  }
  app.phaseBox = null;
  app.phaseKeep = keep ? phase : null;
  app.ampFloor = keep ? amp : null;
  app.boundary = hasSection() ? sectionBoundary() : null;
  app.sectionBox = app.boundary?.box ?? null;
}

function clearViews() {
  app.trails = []; app.phase = []; app.energy = []; app.rows = [];
  app.startHeight = app.lab.positions()[1];
  app.spinAngle = 0; app.rollingView = null; app.topScale = null; app.swarmReach = null; app.closeScale = null;
  if (app.ended) { app.ended = null; message(""); }
  sceneNote("");
  app.frames = 0;
  record();
}

// The extent of the run ahead: a copy of the lab runs PROBE_STEPS steps, noting the box of the
// drawing positions and of every state entry. The views are set from it once, so they stay put
// while the run goes on (a view that follows the data keeps zooming and drifting).
// The probe's cost is bounded by PROBE_WORK state entries stepped (a 1000-pendulum swarm
// probes 1000 steps, a double pendulum 8000).
const PROBE_STEPS = 8000, PROBE_SAMPLES = 200, PROBE_MAX_STATE = 4096, PROBE_WORK = 2e6;
function probeExtent() {
  const lab = app.lab, s0 = Array.from(lab.state());
  if (s0.length > PROBE_MAX_STATE) return null;
  let probe;
  try {
    probe = app.core.build(app.entry.name, app.params, $("method").value, tolerance());
    probe.setState(s0);
  } catch { probe?.free(); return null; }
  const dt = Number($("dt").value) || DEFAULT_DT;
  const ext = { pos: null, lo: s0.slice(), hi: s0.slice(), samples: [] };
  const note = () => {
    const s = probe.state();
    for (let i = 0; i < s.length; i++) { if (s[i] < ext.lo[i]) ext.lo[i] = s[i]; if (s[i] > ext.hi[i]) ext.hi[i] = s[i]; }
    const p = probe.positions();
    if (p.length === 3) return;
    for (let i = 0; i + 1 < p.length; i += 2) ext.pos = grow(ext.pos, p[i], p[i + 1]);
  };
  note();
  for (let k = 0; k < PROBE_SAMPLES; k++) {
    const steps = Math.max(1, Math.floor(Math.min(PROBE_STEPS, PROBE_WORK / s0.length) / PROBE_SAMPLES));
    try { probe.step(steps, dt); } catch { break; }
    // A projectile's path ends at the ground.
    if (kind() === "projectile" && probe.positions()[1] < 0) break;
    note();
  }
  probe.free();
  return ext;
}

function sceneBoxFrom(ext, margin = 0.08) {
  const pos = app.lab.positions();
  let box = null;
  for (let i = 0; i + 1 < pos.length && pos.length !== 3; i += 2) box = grow(box, pos[i], pos[i + 1]);
  if (ext?.pos) box = grow(grow(box, ext.pos.x0, ext.pos.y0), ext.pos.x1, ext.pos.y1);
  const k = kind();
  if (["pendulum", "spring", "hoop", "orbit", "bodies"].includes(k)) box = grow(box, 0, 0);
  if (k === "pendulum" || k === "hoop") {
    // Pivot-centred, as far as the arms reach: a drag anywhere stays in view.
    const reach = reachOf(pos);
    box = grow(grow(box, -reach, -reach), reach, reach);
  }
  if (k === "projectile") box = grow(box, box ? box.x0 : 0, 0);
  if (!box) return null;
  return pad(box, margin);
}

function reachOf(pos) {
  let r = 0, x = 0, y = 0;
  for (let i = 0; i + 1 < pos.length; i += 2) { r += Math.hypot(pos[i] - x, pos[i + 1] - y); x = pos[i]; y = pos[i + 1]; }
  return r || 1;
}

function pad(b, f) {
  const w = b.x1 - b.x0 || Math.abs(b.x0) || 1, h = b.y1 - b.y0 || Math.abs(b.y0) || 1;
  return { x0: b.x0 - f * w, x1: b.x1 + f * w, y0: b.y0 - f * h, y1: b.y1 + f * h };
}

function record() {
  const lab = app.lab, s = lab.state();
  const t = lab.time(), err = lab.energyError();
  sample();
  app.energy.push([t, err]);
  if (app.energy.length > ENERGY_POINTS) app.energy.splice(0, app.energy.length - ENERGY_POINTS / 2);
  app.rows.push([t, lab.energy(), err, ...s]);
  if (app.rows.length > MAX_ROWS) app.rows.shift();
}

// One trail and phase sample of the current state.
function sample() {
  const lab = app.lab, s = lab.state(), pos = lab.positions();
  if (["swing", "disk", "spinner", "rolling"].includes(kind())) {
    // The state and its time.
    const t = lab.time(), last = app.trails[app.trails.length - 1];
    // The rattleback's drawn heading: its spin n₃ added up over the samples (trapezoids).
    if (kind() === "spinner" && last) app.spinAngle = (app.spinAngle ?? 0) + 0.5 * (last[2] + s[2]) * (t - last[3]);
    app.trails.push(Float64Array.from([...s, t]));
    if (app.trails.length > TRAIL) app.trails.splice(0, app.trails.length - TRAIL);
  } else if (pos.length) {
    app.trails.push(Float64Array.from(pos));
    if (app.trails.length > TRAIL) app.trails.splice(0, app.trails.length - TRAIL);
  } else if (kind() === "rigid") {
    app.trails.push(Float64Array.from(s));
    if (app.trails.length > TRAIL) app.trails.splice(0, app.trails.length - TRAIL);
  }
  const ix = Number($("phase-x").value), iy = Number($("phase-y").value);
  app.phase.push([s[ix], s[iy]]);
  if (app.phase.length > PHASE_TRAIL) app.phase.splice(0, app.phase.length - PHASE_TRAIL);
}

// The steps a model can still take, at most `n`: a model that ends (the reduced Euler's disk,
// whose tilt θ reaches the floor θ_min in finite time) stops there rather than stepping past
// its end, where an implicit solver fails. Above the floor θ θ̇ = −decay rate, so after m steps
// θ² = θ² − 2 × decay rate × m dt (exactly so for the implicit midpoint rule, whose step keeps
// θ² − 2 × decay rate × t); the steps left are those that keep θ at or above the floor.
function stepsLeft(n, dt) {
  if (kind() !== "disk") return n;
  const th = app.lab.state()[0], k = param("decay_rate"), floor = param("theta_floor");
  if (!(th > floor)) return 0;
  if (!(k > 0)) return n;
  return Math.max(0, Math.min(n, Math.floor((th * th - floor * floor) / (2 * k * dt))));
}

// The model's end, once reached: stop, and say so in words (a notice, not an error).
function endOfModel() {
  const th = app.lab.state()[0], t = app.lab.time(), k = param("decay_rate");
  // Where θ would reach zero, from the closed form θ² = θ² − 2 × decay rate × (t′ − t).
  const tf = t + (Math.max(th, 0) ** 2) / (2 * k);
  app.ended = `The disk has come to rest at t ≈ ${tf.toPrecision(3)} s: the model's tilt θ reaches zero in finite time there (its finite-time collapse), and the run ends with it. Reset to spin it again.`;
  setRunning(false);
  message(app.ended, "notice");
  draw();
}

// A projectile thrown from at or above the ground has landed once it is below it: the model
// has no ground (it would fly on through it), the picture has, so the run ends there.
function landed() {
  return kind() === "projectile" && app.startHeight >= 0 && app.lab.positions()[1] < 0;
}
function endOfFlight() {
  app.ended = `The ball has reached the ground at t ≈ ${app.lab.time().toFixed(2)} s, and the run ends there (the model itself has no ground). Reset to throw it again, or drag the ball.`;
  setRunning(false);
  message(app.ended, "notice");
  draw();
}

function frame() {
  const dt = Number($("dt").value), n = stepsLeft(Number($("speed").value), dt);
  if (n === 0) { endOfModel(); return false; }
  if (landed()) { endOfFlight(); return false; }
  try {
    // The frame's steps in pieces, a trail sample after each: the same bits as one call.
    const pieces = Math.min(SAMPLES_PER_FRAME, n);
    let done = 0;
    for (let k = 1; k <= pieces; k++) {
      const upto = Math.round((k * n) / pieces);
      app.lab.step(upto - done, dt);
      done = upto;
      if (landed()) break;
      if (k < pieces) sample();
    }
  } catch (e) {
    setRunning(false);
    message(e.message);
    return false;
  }
  app.frames++;
  record();
  if (stepsLeft(1, dt) === 0) endOfModel();
  else if (landed()) endOfFlight();
  return true;
}

function setRunning(on) {
  app.running = on;
  $("run").textContent = on ? "Pause" : "Run";
  $("run").setAttribute("aria-pressed", String(on));
}

function loop() {
  if (app.running && !app.drag) { frame(); draw(); }
  requestAnimationFrame(loop);
}

// One line of status: an error (refused input, a failed step) unless `kind` is "notice".
function message(text, kind = "error") { const el = $("message"); el.textContent = text; el.classList.toggle("notice", kind === "notice"); }

// ---------- drawing: views and axes ----------

// The smallest box holding both.
function union(a, b) { return grow(grow(a, b.x0, b.y0), b.x1, b.y1); }

function grow(box, x, y) {
  if (!Number.isFinite(x) || !Number.isFinite(y)) return box;
  if (!box) return { x0: x, x1: x, y0: y, y1: y };
  return { x0: Math.min(box.x0, x), x1: Math.max(box.x1, x), y0: Math.min(box.y0, y), y1: Math.max(box.y1, y) };
}

// A canvas sized to its box on screen (device pixels), drawn in CSS pixels.
function surface(id) {
  const c = $(id), ctx = c.getContext("2d");
  const w = c.clientWidth || 640, h = c.clientHeight || 400, dpr = window.devicePixelRatio || 1;
  const W = Math.round(w * dpr), H = Math.round(h * dpr);
  if (c.width !== W || c.height !== H) { c.width = W; c.height = H; }
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  ctx.fillStyle = "#fff";
  ctx.fillRect(0, 0, w, h);
  ctx.font = `${fontSize()}px system-ui, sans-serif`;
  ctx.lineJoin = "round"; ctx.lineCap = "round";
  return { c, ctx, w, h };
}

function fontSize() { return document.body.classList.contains("large") ? 17 : 12; }

// A transform from a box of the data to the plot area (inside the axes' margins, unless `axes`
// is false), with equal scales if `square` (the box then grows about its centre to fill the area).
function plotView(w, h, box, square, axes = true) {
  const f = fontSize();
  // A 3-D scene draws its own floor and labels: it takes the whole canvas.
  const r = axes ? { x0: 4.6 * f + 6, x1: w - 10, y0: 10, y1: h - 2.9 * f - 6 } : { x0: 8, x1: w - 8, y0: 8, y1: h - 8 };
  let { x0, x1, y0, y1 } = box;
  // A coordinate that barely moves gets a span of a millionth of its size (ticks that tell
  // their values apart), one that does not move at all a span of 2.
  const widen = (a, b) => {
    const least = 1e-6 * Math.max(Math.abs(a), Math.abs(b));
    if (b - a >= least && b - a > 1e-300) return [a, b];
    const c = (a + b) / 2, half = least > 0 ? least : 1;
    return [c - half, c + half];
  };
  [x0, x1] = widen(x0, x1);
  [y0, y1] = widen(y0, y1);
  let sx = (r.x1 - r.x0) / (x1 - x0), sy = (r.y1 - r.y0) / (y1 - y0);
  if (square) sx = sy = Math.min(sx, sy);
  const cx = (x0 + x1) / 2, cy = (y0 + y1) / 2, mx = (r.x0 + r.x1) / 2, my = (r.y0 + r.y1) / 2;
  const X = (x) => mx + (x - cx) * sx, Y = (y) => my - (y - cy) * sy;
  const inv = (px, py) => [cx + (px - mx) / sx, cy - (py - my) / sy];
  const [bx0, by1] = inv(r.x0, r.y0), [bx1, by0] = inv(r.x1, r.y1);
  return { X, Y, inv, rect: r, box: { x0: bx0, x1: bx1, y0: by0, y1: by1 } };
}

function niceStep(span, count) {
  const raw = span / count, p = 10 ** Math.floor(Math.log10(raw)), f = raw / p;
  return (f < 1.5 ? 1 : f < 3 ? 2 : f < 7 ? 5 : 10) * p;
}

// Ticks at a nice step, about `count` of them; at least two (a step rounded up to 5 × 10ⁿ can
// leave a single tick in the range, an axis without a scale: then a finer step).
function tickValues(lo, hi, count) {
  let step, out;
  for (let c = count; ; c *= 2) {
    step = niceStep(hi - lo, c);
    out = [];
    for (let k = Math.ceil(lo / step - 1e-9); k * step <= hi + step * 1e-9; k++) out.push(k * step);
    if (out.length >= 2 || c > 64 * count) return { step, values: out };
  }
}

function tickText(x, step) {
  const d = Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
  if (Math.abs(x) < step * 1e-6) x = 0;
  x = Math.round(x / step) * step === 0 ? 0 : x;
  // Fixed decimals while they are few; else a power of ten as a physicist writes it
  // (2×10⁻⁷, 1.5×10⁵), with the mantissa digits down to the step's decade, so ticks differ.
  if (Math.abs(x) >= 1e5 || d > 6) {
    if (x === 0) return "0";
    const k = Math.floor(Math.log10(Math.abs(x)) + 1e-9) - Math.floor(Math.log10(step) + 1e-9);
    return scientific(x, Math.max(0, Math.min(12, k)));
  }
  return x.toFixed(d).replaceAll("-", "−");
}

// An integer (or its digits as a string) in superscript: -12 as ⁻¹².
function superscriptInt(n) {
  const SUP = { "-": "⁻", 0: "⁰", 1: "¹", 2: "²", 3: "³", 4: "⁴", 5: "⁵", 6: "⁶", 7: "⁷", 8: "⁸", 9: "⁹" };
  return String(n).split("").map((c) => SUP[c]).join("");
}
// A number as a physicist writes it in prose: 10⁻⁶, 2.5×10⁻⁸ (not 0.000001 or 2.5e-8);
// `digits` after the point when given (4.263×10⁻¹⁴), else as few as give the number back.
function scientific(x, digits) {
  if (x === 0) return "0";
  if (!Number.isFinite(x)) return String(x);
  const [mant, exp] = (digits === undefined ? x.toExponential() : x.toExponential(digits)).split("e");
  return `${mant === "1" ? "" : `${mant.replace("-", "−")}×`}10${superscriptInt(Number(exp))}`;
}

// Axes on the plot area of `v`: a frame, light grid lines, ticks with labels and the axis
// names. `yTicks` overrides the y ticks ([[value, text], ...]). Records what it drew.
function drawAxes(id, ctx, v, xLabel, yLabel, { yTicks = null, xTicks = null } = {}) {
  const r = v.rect, f = fontSize();
  const xt = xTicks ?? (() => { const t = tickValues(v.box.x0, v.box.x1, Math.max(3, Math.floor((r.x1 - r.x0) / (7 * f)))); return t.values.map((x) => [x, tickText(x, t.step)]); })();
  const yt = yTicks ?? (() => { const t = tickValues(v.box.y0, v.box.y1, Math.max(3, Math.floor((r.y1 - r.y0) / (3.5 * f)))); return t.values.map((y) => [y, tickText(y, t.step)]); })();
  ctx.save();
  ctx.lineWidth = 1;
  ctx.strokeStyle = "#e6e6e6";
  ctx.beginPath();
  for (const [x] of xt) { const px = Math.round(v.X(x)) + 0.5; ctx.moveTo(px, r.y0); ctx.lineTo(px, r.y1); }
  for (const [y] of yt) { const py = Math.round(v.Y(y)) + 0.5; ctx.moveTo(r.x0, py); ctx.lineTo(r.x1, py); }
  ctx.stroke();
  ctx.strokeStyle = "#555";
  ctx.strokeRect(r.x0 + 0.5, r.y0 + 0.5, r.x1 - r.x0 - 1, r.y1 - r.y0 - 1);
  ctx.fillStyle = "#333";
  ctx.textAlign = "center"; ctx.textBaseline = "top";
  ctx.beginPath();
  for (const [x, text] of xt) {
    const px = Math.round(v.X(x)) + 0.5;
    ctx.moveTo(px, r.y1); ctx.lineTo(px, r.y1 + 4);
    // A tick at the plot's right edge: its label moved in to end at the canvas's edge (the
    // plot area stops 10 px short of it).
    ctx.fillText(text, Math.min(px, r.x1 + 9 - ctx.measureText(text).width / 2), r.y1 + 6);
  }
  ctx.textAlign = "right"; ctx.textBaseline = "middle";
  for (const [y, text] of yt) {
    const py = Math.round(v.Y(y)) + 0.5;
    ctx.moveTo(r.x0 - 4, py); ctx.lineTo(r.x0, py);
    ctx.fillText(text, r.x0 - 6, py);
  }
  ctx.stroke();
  const xl = typeof xLabel === "string" ? plainLabel(xLabel) : xLabel, yl = typeof yLabel === "string" ? plainLabel(yLabel) : yLabel;
  ctx.textBaseline = "bottom";
  fillRuns(ctx, xl.runs, (r.x0 + r.x1) / 2, r.y1 + 2.9 * f + 4, "center");
  ctx.translate(f * 0.9, (r.y0 + r.y1) / 2);
  ctx.rotate(-Math.PI / 2);
  ctx.textBaseline = "middle";
  fillRuns(ctx, yl.runs, 0, 0, "center");
  ctx.restore();
  app.ticks[id] = { x: xt.map(([, t]) => t), y: yt.map(([, t]) => t), xLabel: xl.text, yLabel: yl.text };
}

// Text runs ({text, sub}) at (x, y), aligned left, center or right: a subscript run in a
// font 0.72 the size, lowered by a third of the size.
function fillRuns(ctx, runs, x, y, align = "left") {
  ctx.save();
  const size = parseFloat(ctx.font) || fontSize(), family = ctx.font.replace(/^[\d.]+px\s*/, "");
  const fontOf = (sub) => `${sub ? Math.round(size * 0.72) : size}px ${family}`;
  const widths = runs.map((r) => { ctx.font = fontOf(r.sub); return ctx.measureText(r.text).width; });
  const total = widths.reduce((a, b) => a + b, 0);
  let at = align === "center" ? x - total / 2 : align === "right" ? x - total : x;
  ctx.textAlign = "left";
  runs.forEach((r, i) => {
    ctx.font = fontOf(r.sub);
    ctx.fillText(r.text, at, r.sub ? y + size * 0.3 : y);
    at += widths[i];
  });
  ctx.restore();
}

function clip(ctx, v) {
  ctx.save();
  ctx.beginPath();
  ctx.rect(v.rect.x0, v.rect.y0, v.rect.x1 - v.rect.x0, v.rect.y1 - v.rect.y0);
  ctx.clip();
}

function bodiesOf(p) {
  const out = [];
  for (let i = 0; i + 1 < p.length; i += 2) out.push([p[i], p[i + 1]]);
  return out;
}

function massOf(i) {
  const m = app.params[`m${i + 1}`] ?? app.entry.params.find((p) => p.name === `m${i + 1}`)?.default
    ?? app.params.m ?? app.entry.params.find((p) => p.name === "m")?.default ?? 1;
  return Number(m) || 1;
}

// A body's radius in pixels: its area in proportion to its mass (between 6 and 16 px).
function bobRadius(i) {
  const masses = bodiesOf(app.lab.positions()).map((_, k) => massOf(k)), top = Math.max(...masses);
  return Math.max(6, 14 * Math.sqrt(massOf(i) / top));
}

function trailPaths(ctx, v, count, colour = [40, 90, 200]) {
  const T = app.trails, n = T.length;
  if (n < 2) return;
  ctx.lineWidth = 1.6;
  // In 8 bands fading with age: one path per band and body.
  const bands = 8;
  for (let b = 0; b < bands; b++) {
    const k0 = Math.floor((b * (n - 1)) / bands), k1 = Math.floor(((b + 1) * (n - 1)) / bands);
    ctx.strokeStyle = `rgba(${colour.join(",")}, ${0.12 + (0.75 * (b + 1)) / bands})`;
    ctx.beginPath();
    for (let body = 0; body < count; body++) {
      for (let k = k0; k <= k1; k++) {
        const x = v.X(T[k][2 * body]), y = v.Y(T[k][2 * body + 1]);
        if (k === k0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
      }
    }
    ctx.stroke();
  }
}

function pivot(ctx, x, y) {
  ctx.fillStyle = "#333";
  ctx.fillRect(x - 14, y - 3, 28, 3);
  ctx.beginPath(); ctx.arc(x, y, 4, 0, TAU); ctx.fill();
}

function bob(ctx, x, y, r, i) {
  ctx.beginPath(); ctx.arc(x, y, r, 0, TAU);
  ctx.fillStyle = app.drag?.body === i ? "#e07000" : "#c0392b"; ctx.fill();
  ctx.strokeStyle = "#5a1a12"; ctx.lineWidth = 1.2; ctx.stroke();
}

// A coil spring from (x0, y0) to (x1, y1) with `turns` turns of half-width `a` pixels.
function coil(ctx, x0, y0, x1, y1, turns, a) {
  const dx = x1 - x0, dy = y1 - y0, L = Math.hypot(dx, dy) || 1, ux = dx / L, uy = dy / L;
  const lead = Math.min(10, L * 0.15);
  ctx.beginPath(); ctx.moveTo(x0, y0); ctx.lineTo(x0 + ux * lead, y0 + uy * lead);
  const n = turns * 2, body = L - 2 * lead;
  for (let k = 1; k <= n; k++) {
    const s = lead + (body * (k - 0.5)) / n, side = k % 2 ? a : -a;
    ctx.lineTo(x0 + ux * s - uy * side, y0 + uy * s + ux * side);
  }
  ctx.lineTo(x1 - ux * lead, y1 - uy * lead); ctx.lineTo(x1, y1);
  ctx.stroke();
}

function param(name) {
  const v = app.params[name] ?? app.entry.params.find((p) => p.name === name)?.default;
  return typeof v === "number" ? v : NaN;
}

function drawScene() {
  const { ctx, w, h } = surface("scene");
  const k = kind(), pos = app.lab.positions(), L = lengthUnit();
  app.sceneLabels = [];
  if (k === "top") return drawTop(ctx, w, h, Array.from(pos));
  if (k === "rigid") return drawRigid(ctx, w, h);
  if (k === "swarm") return drawSwarm(ctx, w, h);
  if (k === "chain" || k === "sites") return drawChain(ctx, w, h, k);
  if (k === "series") return drawSeries(ctx, w, h);
  if (k === "swing") return drawSwing(ctx, w, h);
  if (k === "disk") return drawTiltedDisk(ctx, w, h);
  if (k === "spinner") return drawSpinner(ctx, w, h, app.lab.state());
  if (k === "rolling") return drawRolling(ctx, w, h);
  if (!app.sceneBox) app.sceneBox = sceneBoxFrom(null) ?? { x0: -1, x1: 1, y0: -1, y1: 1 };
  const v = plotView(w, h, app.sceneBox, true);
  app.sceneView = v;
  drawAxes("scene", ctx, v, lengthLabel("x"), lengthLabel("y"));
  clip(ctx, v);
  const bodies = bodiesOf(pos);
  if (k === "projectile") {
    // The ground, the path so far, its apex and where it meets the ground (the range).
    ctx.fillStyle = "#e9e2cf"; ctx.fillRect(v.rect.x0, v.Y(0), v.rect.x1 - v.rect.x0, v.rect.y1 - v.Y(0));
    ctx.strokeStyle = "#8a7a50"; ctx.lineWidth = 1.5; ctx.beginPath(); ctx.moveTo(v.rect.x0, v.Y(0)); ctx.lineTo(v.rect.x1, v.Y(0)); ctx.stroke();
    trailPaths(ctx, v, 1);
    let apex = null, land = null;
    for (let i = 0; i < app.trails.length; i++) {
      const [x, y] = app.trails[i];
      if (!apex || y > apex[1]) apex = [x, y];
      if (i && !land && y < 0 && app.trails[i - 1][1] >= 0) {
        const [xa, ya] = app.trails[i - 1];
        land = [xa + ((x - xa) * ya) / (ya - y), 0];
      }
    }
    ctx.fillStyle = "#333"; ctx.textAlign = "center";
    if (apex && apex[1] > app.trails[0][1] + 1e-9 && app.trails[app.trails.length - 1][1] < apex[1]) {
      ctx.beginPath(); ctx.arc(v.X(apex[0]), v.Y(apex[1]), 3, 0, TAU); ctx.fill();
      labelInside(ctx, v, `apex ${apex[1].toFixed(2)} ${L}`, v.X(apex[0]), v.Y(apex[1]) - 8);
    }
    if (land) {
      ctx.beginPath(); ctx.moveTo(v.X(land[0]), v.Y(0) - 6); ctx.lineTo(v.X(land[0]), v.Y(0) + 6); ctx.stroke();
      // Under the ground, to the left of the mark if the ball has gone on past it.
      const range = `range ${(land[0] - app.trails[0][0]).toFixed(2)} ${L}`, past = bodies[0]?.[0] > land[0];
      labelInside(ctx, v, range, v.X(land[0]) + (past ? -8 : 0), v.Y(0) + 18, past ? "right" : "center");
    }
    bodies.forEach(([x, y], i) => bob(ctx, v.X(x), v.Y(y), 7, i));
  } else if (k === "orbit") {
    // The focus (the attracting centre), the orbit traced so far, the body, and the
    // Laplace–Runge–Lenz vector (towards the perihelion; constant for a pure 1/r potential).
    trailPaths(ctx, v, 1);
    ctx.fillStyle = "#e0a800"; ctx.beginPath(); ctx.arc(v.X(0), v.Y(0), 7, 0, TAU); ctx.fill();
    const s = app.lab.state(), [x, y, px, py] = s, r = Math.hypot(x, y);
    const mu = param("mu"), kk = param("k");
    const m = Number.isFinite(mu) ? mu : 1, kc = Number.isFinite(kk) ? kk : 1;
    const Lz = x * py - y * px;
    const A = [py * Lz - m * kc * x / r, -px * Lz - m * kc * y / r];
    const e = Math.hypot(...A) / (m * kc);
    if (e > 1e-3 && e < 1) {
      const rp = (Lz * Lz) / (m * kc * (1 + e)), ux = A[0] / Math.hypot(...A), uy = A[1] / Math.hypot(...A);
      arrow(ctx, v.X(0), v.Y(0), v.X(rp * ux), v.Y(rp * uy), "#1e7d32");
      // Beyond the arrow's tip, on the side it points to; where the plot's edge leaves no room
      // there, beside the tip on the side away from the shaft (above a tip pointing up).
      ctx.fillStyle = "#1e7d32";
      const tx = v.X(rp * ux), ty = v.Y(rp * uy), room = ux < 0 ? tx - 6 - v.rect.x0 : v.rect.x1 - tx - 6;
      const fits = room >= ctx.measureText("LRL vector").width + 3;
      labelInside(ctx, v, "LRL vector", tx + (ux < 0 ? -6 : 6), fits ? ty - 6 : uy >= 0 ? ty - 10 : ty + fontSize() + 8, ux < 0 ? "right" : "left");
    }
    bodies.forEach(([bx, by], i) => bob(ctx, v.X(bx), v.Y(by), 7, i));
  } else if (k === "hoop") {
    // The hoop seen from the side while it turns at Ω about its vertical diameter: an ellipse
    // of half-width R |cos Ωt|; the bead rides on it.
    const R = param("R"), W = param("omega"), t = app.lab.time(), c = Math.cos(W * t);
    const [bx, by] = bodies[0];
    ctx.strokeStyle = "#666"; ctx.lineWidth = 3;
    ctx.beginPath(); ctx.ellipse(v.X(0), v.Y(0), Math.max(1, Math.abs(R * c) * (v.X(1) - v.X(0))), R * (v.X(1) - v.X(0)), 0, 0, TAU); ctx.stroke();
    ctx.setLineDash([5, 5]); ctx.lineWidth = 1; ctx.beginPath(); ctx.moveTo(v.X(0), v.Y(-1.08 * R)); ctx.lineTo(v.X(0), v.Y(1.08 * R)); ctx.stroke(); ctx.setLineDash([]);
    bob(ctx, v.X(bx * c), v.Y(by), 8, 0);
    ctx.fillStyle = "#333"; ctx.textAlign = "left";
    ctx.fillText(`Ω t = ${((W * t) % TAU).toFixed(2)} rad`, v.rect.x0 + 8, v.rect.y0 + 16);
  } else {
    // Pendulums: the path of each bob, the pivot, rods (a coil for a spring), bobs by mass.
    // Free bodies (a particle in a potential): the path and the body.
    trailPaths(ctx, v, bodies.length);
    if (k === "bodies") { bodies.forEach(([x, y], i) => bob(ctx, v.X(x), v.Y(y), 8, i)); ctx.restore(); return; }
    ctx.strokeStyle = "#333"; ctx.lineWidth = 3;
    let [x0, y0] = [v.X(0), v.Y(0)];
    bodies.forEach(([x, y]) => {
      if (k === "spring") { ctx.lineWidth = 1.8; coil(ctx, x0, y0, v.X(x), v.Y(y), 12, 7); }
      else { ctx.beginPath(); ctx.moveTo(x0, y0); ctx.lineTo(v.X(x), v.Y(y)); ctx.stroke(); }
      [x0, y0] = [v.X(x), v.Y(y)];
    });
    pivot(ctx, v.X(0), v.Y(0));
    // Bobs no wider than 0.3 of the shortest rod on the screen (three rods on a phone are short),
    // so neighbours never cover each other or the rod between them.
    let rod = Infinity, [px, py] = [0, 0];
    if (k === "pendulum") for (const [x, y] of bodies) { rod = Math.min(rod, Math.hypot(v.X(x) - v.X(px), v.Y(y) - v.Y(py))); [px, py] = [x, y]; }
    // What was drawn, for the tests: each bob's centre and radius on the canvas.
    app.bobsDrawn = bodies.map(([x, y], i) => ({ x: v.X(x), y: v.Y(y), r: Math.min(bobRadius(i), Math.max(4, 0.3 * rod)) }));
    for (const [i, b] of app.bobsDrawn.entries()) bob(ctx, b.x, b.y, b.r, i);
  }
  ctx.restore();
}

// A label in the plot area of `v`: at (x, y) as aligned, moved in to stay whole inside the
// area (a label at a body near the edge, the projectile's range, Kepler's LRL vector, is never
// cut by the frame). `y` is the text's baseline.
function labelInside(ctx, v, text, x, y, align = "center") {
  const r = v.rect, wd = ctx.measureText(text).width, f = fontSize();
  let left = align === "center" ? x - wd / 2 : align === "right" ? x - wd : x;
  left = Math.max(r.x0 + 3, Math.min(left, r.x1 - 3 - wd));
  const base = Math.max(r.y0 + f + 2, Math.min(y, r.y1 - 4));
  ctx.save(); ctx.textAlign = "left"; ctx.textBaseline = "alphabetic"; ctx.fillText(text, left, base); ctx.restore();
}

function arrow(ctx, x0, y0, x1, y1, colour) {
  const a = Math.atan2(y1 - y0, x1 - x0);
  ctx.strokeStyle = colour; ctx.fillStyle = colour; ctx.lineWidth = 2;
  ctx.beginPath(); ctx.moveTo(x0, y0); ctx.lineTo(x1, y1); ctx.stroke();
  ctx.beginPath(); ctx.moveTo(x1, y1);
  ctx.lineTo(x1 - 9 * Math.cos(a - 0.4), y1 - 9 * Math.sin(a - 0.4));
  ctx.lineTo(x1 - 9 * Math.cos(a + 0.4), y1 - 9 * Math.sin(a + 0.4));
  ctx.fill();
}

// True if the segment [x0, y0, x1, y1] meets the box [left, top, right, bottom]
// (Liang–Barsky clipping).
function segmentMeetsBox([x0, y0, x1, y1], [l, t, r, b]) {
  let u0 = 0, u1 = 1;
  const dx = x1 - x0, dy = y1 - y0;
  for (const [p, q] of [[-dx, x0 - l], [dx, r - x0], [-dy, y0 - t], [dy, b - y0]]) {
    if (p === 0) { if (q < 0) return false; continue; }
    const u = q / p;
    if (p < 0) { if (u > u1) return false; u0 = Math.max(u0, u); } else { if (u < u0) return false; u1 = Math.min(u1, u); }
  }
  return u0 <= u1;
}
// Names of arrows ({text, seg: [x0, y0, x1, y1] from tail to tip, colour}): each placed beyond
// its tip along the arrow, at the first distance and angle off it (0, ±30°, ±60°, ...) where
// its box meets no arrow and no name placed before; the box's corner nearest the arrow keeps
// a gap from the tip, so a name never sits on what it names. Returns what was drawn
// ({text, box, seg}), for the tests. `others`: more segments to keep clear of.
function arrowLabels(ctx, arrows, others = []) {
  const f = fontSize(), placed = [];
  ctx.save(); ctx.textAlign = "center"; ctx.textBaseline = "middle";
  for (const a of arrows) {
    const [x0, y0, x1, y1] = a.seg, len = Math.hypot(x1 - x0, y1 - y0);
    // An arrow seen end-on has no direction on the screen: its name goes above its tip.
    const base = len > 1 ? Math.atan2(y1 - y0, x1 - x0) : -Math.PI / 2;
    const hw = ctx.measureText(a.text).width / 2 + 2, hh = f / 2 + 1;
    let best = null;
    search: for (const gap of [4, 10, 18]) {
      for (const turn of [0, 0.5, -0.5, 1, -1, 1.6, -1.6, 2.3, -2.3]) {
        const th = base + turn, dx = Math.cos(th), dy = Math.sin(th);
        const d = gap + hw * Math.abs(dx) + hh * Math.abs(dy), cx = x1 + d * dx, cy = y1 + d * dy;
        const box = [cx - hw, cy - hh, cx + hw, cy + hh];
        const clear = [...arrows.map((o) => o.seg), ...others].every((sg) => !segmentMeetsBox(sg, box)) &&
          placed.every((p) => box[2] <= p.box[0] || p.box[2] <= box[0] || box[3] <= p.box[1] || p.box[3] <= box[1]);
        if (!best) best = { cx, cy, box };
        if (clear) { best = { cx, cy, box }; break search; }
      }
    }
    ctx.fillStyle = a.colour;
    ctx.fillText(a.text, best.cx, best.cy);
    placed.push({ text: a.text, box: best.box, seg: a.seg });
  }
  ctx.restore();
  return placed;
}

// The view of 3-D points: turned by AZIMUTH about the vertical, tilted by ELEVATION towards
// the viewer, seen in perspective from DISTANCE (in units of the body's size). Returns
// [screen x, screen y, depth].
const AZIMUTH = 0.6, ELEVATION = 0.35, DISTANCE = 6;
function project3([x, y, z], size = 1, elevation = ELEVATION) {
  const ca = Math.cos(AZIMUTH), sa = Math.sin(AZIMUTH), ce = Math.cos(elevation), se = Math.sin(elevation);
  const u = ca * x + sa * y, w = -sa * x + ca * y;
  const depth = ce * w + se * z, f = DISTANCE / (DISTANCE + depth / size);
  return [u * f, (ce * z - se * w) * f, depth];
}

// The heavy top in perspective: the floor with its axes (ticks in metres), the symmetry
// axis from the pivot to the centre of mass with a disc across it, its shadow, and the path
// of the axis tip (precession and nutation).
// A 3-D floor's labels (centred, hanging from the point): on a narrow canvas the two edges'
// labels meet at the near corner and the axis names sit on the middle ticks, so a label that
// would overlap one already drawn is left out (draw the axis names first, then the ticks).
// Returns put(text, [x, y]), true if drawn. `avoid`: boxes [left, top, right, bottom] of the
// body drawn over the floor, whose labels would sit on it.
function labelPlacer(ctx, avoid = []) {
  const drawn = [...avoid], f = fontSize();
  // For the tests: the body's boxes and the labels drawn.
  app.floorLabels = { avoid, drawn: [] };
  const put = (text, [px, py]) => {
    const half = ctx.measureText(text).width / 2 + 2, b = [px - half, py - 1, px + half, py + f + 1];
    if (drawn.some((d) => b[0] < d[2] && d[0] < b[2] && b[1] < d[3] && d[1] < b[3])) return false;
    drawn.push(b);
    app.floorLabels.drawn.push({ text, box: b });
    ctx.fillText(text, px, py);
    return true;
  };
  // An axis's name is never left out: the first of `spots` where it is clear; if none, the
  // first, where the tests see it under the body.
  put.first = (text, spots) => {
    if (spots.some((at) => put(text, at))) return;
    const half = ctx.measureText(text).width / 2 + 2, [px, py] = spots[0];
    ctx.fillText(text, px, py);
    app.floorLabels.drawn.push({ text, box: [px - half, py - 1, px + half, py + f + 1] });
  };
  return put;
}
// Spots for a floor axis's name: at `at(0)`, then along its edge both ways by `step`.
function alongEdge(at, step) { return [0, 1, -1, 2, -2, 3, -3].map((k) => at(k * step)); }

function drawTop(ctx, w, h, tip) {
  const l = Math.hypot(tip[0], tip[1], tip[2]) || 1;
  app.topLength = l;
  const v = plotView(w, h, { x0: -1.3 * l, x1: 1.3 * l, y0: -0.9 * l, y1: 1.3 * l }, true, false);
  app.sceneView = v;
  const P = (p) => { const [x, y] = project3(p, l); return [v.X(x), v.Y(y)]; };
  const line = (a, b) => { ctx.beginPath(); ctx.moveTo(...P(a)); ctx.lineTo(...P(b)); ctx.stroke(); };
  // The floor: a grid with tick labels along two edges.
  const t = tickValues(-l, l, 4);
  ctx.strokeStyle = "#ddd"; ctx.lineWidth = 1;
  for (const g of t.values) { line([g, -l, 0], [g, l, 0]); line([-l, g, 0], [l, g, 0]); }
  ctx.fillStyle = "#555"; ctx.textAlign = "center"; ctx.textBaseline = "top";
  const xs = t.values.map((g) => tickText(g, t.step)), ys = xs.slice();
  // The top (the disc round its tip, radius l/2, and its axis from the pivot) stands over the
  // floor: a label it would cover is left out. The body's boxes: the disc's (whatever its
  // turn), and six along the axis (a label beside a standing top's axis is clear of it).
  let disc = null;
  for (let k = 0; k < 24; k++) {
    const th = (TAU * k) / 24, c = [Math.cos(th), Math.sin(th)];
    for (const d of [[c[0], c[1], 0], [c[0], 0, c[1]], [0, c[0], c[1]]]) disc = grow(disc, ...P(tip.map((x, i) => x + 0.5 * l * d[i])));
  }
  const body = [[disc.x0, disc.y0, disc.x1, disc.y1]];
  for (let k = 0; k < 6; k++) {
    const [ax, ay] = P(tip.map((x) => (x * k) / 6)), [bx, by] = P(tip.map((x) => (x * (k + 1)) / 6));
    body.push([Math.min(ax, bx) - 4, Math.min(ay, by) - 4, Math.max(ax, bx) + 4, Math.max(ay, by) + 4]);
  }
  const put = labelPlacer(ctx, body);
  put.first(lengthLabel("x"), alongEdge((g) => P([g, -l * 1.3, 0]), 0.3 * l));
  put.first(lengthLabel("y"), alongEdge((g) => P([l * 1.35, g, 0]), 0.3 * l));
  // The vertical's name at its top, or, where the top's disc stands there, the first place
  // beside the vertical (lower and lower, right then left) clear of the disc and the labels.
  const zText = lengthLabel("z"), zHalf = ctx.measureText(zText).width / 2 + 6, f = fontSize();
  const [zx, zy] = P([0, 0, 1.15 * l]), spots = [];
  for (let y = zy - f - 3; y > 1 && spots.length < 4; y -= f) spots.push([zx, y]);
  for (let k = 0; k < 8; k++) { const [, y] = P([0, 0, (1 - 0.12 * k) * l]); spots.push([zx + zHalf, y], [zx - zHalf, y]); }
  put.first(zText, spots.length ? spots : [[zx, zy]]);
  const xShown = xs.filter((x, i) => put(x, P([t.values[i], -l * 1.08, 0])));
  const yShown = ys.filter((y, i) => put(y, P([l * 1.1, t.values[i], 0])));
  app.ticks.scene = { x: xShown, y: yShown, xLabel: lengthLabel("x"), yLabel: lengthLabel("y"), zLabel: zText };
  ctx.strokeStyle = "#999"; line([0, 0, 0], [0, 0, 1.15 * l]);
  ctx.textBaseline = "alphabetic";
  ctx.lineWidth = 1.5;
  const T = app.trails;
  for (let k = 1; k < T.length; k++) {
    ctx.strokeStyle = `rgba(40, 90, 200, ${0.1 + (0.7 * k) / T.length})`;
    line(T[k - 1], T[k]);
  }
  ctx.setLineDash([4, 4]); ctx.strokeStyle = "#aaa"; line([0, 0, 0], [tip[0], tip[1], 0]); ctx.setLineDash([]);
  ctx.strokeStyle = "#333"; ctx.lineWidth = 3; line([0, 0, 0], tip);
  const a = tip.map((x) => x / l);
  let e1 = [a[1], -a[0], 0];
  const n1 = Math.hypot(...e1);
  e1 = n1 > 1e-9 ? e1.map((x) => x / n1) : [1, 0, 0];
  const e2 = [a[1] * e1[2] - a[2] * e1[1], a[2] * e1[0] - a[0] * e1[2], a[0] * e1[1] - a[1] * e1[0]];
  ctx.beginPath();
  for (let k = 0; k <= 48; k++) {
    const th = (TAU * k) / 48, r = 0.5 * l;
    const [x, y] = P([0, 1, 2].map((i) => tip[i] + r * (Math.cos(th) * e1[i] + Math.sin(th) * e2[i])));
    if (k) ctx.lineTo(x, y); else ctx.moveTo(x, y);
  }
  ctx.fillStyle = "rgba(192, 57, 43, 0.35)"; ctx.fill();
  ctx.strokeStyle = "#c0392b"; ctx.lineWidth = 2; ctx.stroke();
  const Lv = topMomentum(tip);
  app.topL = Lv;
  if (Lv) {
    // Drawn to a scale fixed when the run starts: the start's |L| is 1.2 arm lengths.
    const Ln = Math.hypot(...Lv);
    if (!app.topScale) app.topScale = (1.2 * l) / (Ln || 1);
    const [x0, y0] = P([0, 0, 0]), end = Lv.map((x) => x * app.topScale), [x1, y1] = P(end);
    arrow(ctx, x0, y0, x1, y1, "#e07000");
    app.sceneLabels = arrowLabels(ctx, [{ text: "L", seg: [x0, y0, x1, y1], colour: "#e07000" }], [[x0, y0, ...P(tip)], [x0, y0, ...P([0, 0, 1.15 * l])]]);
    sceneNote(`The top's axis (black) with its disc, the path of its tip (blue), and its angular momentum about the pivot L (orange, |L| = ${Ln.toPrecision(4)} kg m²/s): gravity's torque turns L about the vertical, keeping its vertical part.`);
  }
  const [ox, oy] = P([0, 0, 0]);
  ctx.fillStyle = "#333"; ctx.beginPath(); ctx.arc(ox, oy, 4, 0, TAU); ctx.fill();
}

// The heavy symmetric top's angular momentum about the pivot, L = I₁ e₃ × ė₃ + I₃ ω₃ e₃: the
// axis e₃ (the drawn tip over l) turning at e₃ × ė₃, and the spin ω₃ = ω · e₃ = ψ̇ + φ̇ (ẑ · e₃)
// about it (the angles named by the catalogue's symbols). ė₃ is a central difference of the
// drawn tip along the velocity (1e-6 of a second: the tip is smooth, so the difference is
// good to ~1e-12 of |ė₃|, far below a pixel).
function topMomentum(tip) {
  const s = Array.from(app.lab.state()), n = s.length / 2, sym = presentation().symbols ?? [];
  const iphi = sym.indexOf("\\phi"), ipsi = sym.indexOf("\\psi"), l = param("l"), I1 = param("I1"), I3 = param("I3");
  if (iphi < 0 || ipsi < 0 || !(Math.abs(l) > 0) || !Number.isFinite(I1) || !Number.isFinite(I3)) return null;
  const e3 = tip.map((x) => x / l), eps = 1e-6;
  const at = (sign) => Array.from(app.lab.positionsOf(s.slice(0, n).map((q, i) => q + sign * eps * s[n + i])));
  const up = at(1), down = at(-1);
  if (up.length !== 3 || down.length !== 3) return null;
  const de3 = up.map((x, i) => (x - down[i]) / (2 * eps * l));
  const w3 = s[n + ipsi] + s[n + iphi] * e3[2];
  const cr = [e3[1] * de3[2] - e3[2] * de3[1], e3[2] * de3[0] - e3[0] * de3[2], e3[0] * de3[1] - e3[1] * de3[0]];
  return [0, 1, 2].map((i) => I1 * cr[i] + I3 * w3 * e3[i]);
}

// Rotates `v` by the unit quaternion [w, x, y, z].
function rotate([w, x, y, z], v) {
  const [a, b, c] = v;
  const tx = 2 * (y * c - z * b), ty = 2 * (z * a - x * c), tz = 2 * (x * b - y * a);
  return [a + w * tx + (y * tz - z * ty), b + w * ty + (z * tx - x * tz), c + w * tz + (x * ty - y * tx)];
}

// The free rigid body (state: body angular velocity ω, then the orientation quaternion): a
// box with the proportions of its inertia ellipsoid, its body axes, and the angular momentum
// L = I ω turned into the space frame (fixed in space: no torque).
function drawRigid(ctx, w, h) {
  const s = app.lab.state(), q = s.slice(3, 7), I = [param("I1"), param("I2"), param("I3")].map((x) => (Number.isFinite(x) ? x : 1));
  const v = plotView(w, h, { x0: -1.6, x1: 1.6, y0: -1.4, y1: 1.4 }, true, false);
  app.sceneView = v;
  // Half-sides of the uniform box with these principal moments: I1 ∝ b² + c², ...
  const sum = I[0] + I[1] + I[2];
  let half = [0, 1, 2].map((i) => Math.sqrt(Math.max(1e-3, sum / 2 - I[i])));
  const big = Math.max(...half); half = half.map((x) => (0.7 * x) / big);
  const P = (p) => { const [x, y] = project3(p, 1.2); return [v.X(x), v.Y(y)]; };
  const corners = [];
  for (const sx of [-1, 1]) for (const sy of [-1, 1]) for (const sz of [-1, 1]) corners.push(rotate(q, [sx * half[0], sy * half[1], sz * half[2]]));
  ctx.strokeStyle = "#7a2a1e"; ctx.fillStyle = "rgba(192, 57, 43, 0.12)"; ctx.lineWidth = 1.5;
  ctx.beginPath();
  for (let i = 0; i < 8; i++) for (let j = i + 1; j < 8; j++) {
    if ([1, 2, 4].includes(i ^ j)) { ctx.moveTo(...P(corners[i])); ctx.lineTo(...P(corners[j])); }
  }
  ctx.stroke();
  const colours = ["#c0392b", "#1e7d32", "#2860c8"], [ox, oy] = P([0, 0, 0]), arrows = [];
  for (let i = 0; i < 3; i++) {
    const e = [0, 0, 0]; e[i] = 1.05;
    const [x1, y1] = P(rotate(q, e));
    arrows.push({ text: `e${subscript(i + 1)}`, seg: [ox, oy, x1, y1], colour: colours[i] });
  }
  const Lb = [I[0] * s[0], I[1] * s[1], I[2] * s[2]], Ls = rotate(q, Lb), Ln = Math.hypot(...Ls) || 1;
  const [lx, ly] = P(Ls.map((x) => (1.35 * x) / Ln));
  arrows.push({ text: "L", seg: [ox, oy, lx, ly], colour: "#e07000" });
  for (const a of arrows) arrow(ctx, ...a.seg, a.colour);
  // Each name beyond its arrow's tip, clear of every arrow and of the names placed before.
  app.sceneLabels = arrowLabels(ctx, arrows);
  // The path of the tip of body axis 3, fading with age.
  ctx.lineWidth = 1;
  const T = app.trails;
  for (let k = 1; k < T.length; k++) {
    ctx.strokeStyle = `rgba(40, 90, 200, ${0.05 + (0.5 * k) / T.length})`;
    const a = rotate(T[k - 1].slice(3, 7), [0, 0, 1.05]), b = rotate(T[k].slice(3, 7), [0, 0, 1.05]);
    ctx.beginPath(); ctx.moveTo(...P(a)); ctx.lineTo(...P(b)); ctx.stroke();
  }
  sceneNote(`The body's axes e₁, e₂, e₃ turn; its angular momentum L (orange, |L| = ${Ln.toPrecision(4)} kg m²/s) stays fixed in space (no torque). Blue: the path of the tip of e₃.`);
  // No axes in space: the scene's scale is its two magnitudes, |ω| and |L|.
  app.ticks.scene = {
    x: [Math.hypot(s[0], s[1], s[2]).toPrecision(4)], xLabel: `|ω| (${stateUnits()[0]})`,
    y: [Ln.toPrecision(4)], yLabel: "|L| (kg m²/s)",
  };
}

// A swarm of pendulums: every member a point of the (angle, momentum) plane, coloured by its
// energy, with the separatrix p = ±2 √(g/l) cos(θ/2) between swinging and turning.
// Each pendulum keeps its energy E = p²/2 − (g/l) cos θ, so it stays on its own contour for
// good: the region the swarm can ever reach, the union of its members' contours, is known
// when the run starts. The scene shows that region, fixed for the run (the swarm never leaves
// it), with the contours of the lowest and highest energies between which the filament
// winds; the phase panel is a close-up that follows the swarm (a dashed frame in the scene).
// Colours from the lowest energy to the highest (plasma's scale without its pale yellow end,
// which white paper hides).
const SWARM_COLOURS = ["#0d0887", "#41049d", "#6a00a8", "#8f0da4", "#b12a90", "#cc4778", "#e16462", "#f2844b", "#fca636"];
function swarmG() { const g = param("g_over_l"); return Number.isFinite(g) && g > 0 ? g : 1; }
function swarmEnergy(q, p, g) { return 0.5 * p * p - g * Math.cos(q); }
const wrapQ = (q) => q - TAU * Math.ceil((q - Math.PI) / TAU);
// The box of the contours of every member (a swinging one: |θ| ≤ arccos(−E/g), |p| ≤
// √(2(E + g)); a turning one: all angles, p of its sign between √(2(E − g)) and √(2(E + g))),
// the lowest and highest energies, and the members by colour (their energy's place between).
function swarmReach() {
  const s = app.lab.state(), n = s.length / 2, g = swarmG(), energies = new Float64Array(n);
  let box = null, lo = Infinity, hi = -Infinity;
  for (let i = 0; i < n; i++) {
    const q = s[i], p = s[n + i], E = swarmEnergy(q, p, g);
    energies[i] = E;
    lo = Math.min(lo, E); hi = Math.max(hi, E);
    if (E < g) {
      const qa = Math.acos(Math.max(-1, Math.min(1, -E / g))), pa = Math.sqrt(Math.max(0, 2 * (E + g)));
      box = grow(grow(box, -qa, -pa), qa, pa);
    } else {
      const sign = p < 0 ? -1 : 1;
      box = grow(grow(box, -Math.PI, sign * Math.sqrt(2 * (E - g))), Math.PI, sign * Math.sqrt(2 * (E + g)));
    }
  }
  if (!box) return null;
  const bands = SWARM_COLOURS.map(() => []), span = hi - lo;
  energies.forEach((E, i) => bands[span > 0 ? Math.min(bands.length - 1, Math.floor(((E - lo) / span) * bands.length)) : 0].push(i));
  // A swarm at rest at the bottom has no extent: a span of a fifth of the separatrix's
  // height round it, so its axes have a scale.
  return { box: atLeast(pad(box, 0.08), [0.4, 0.8 * Math.sqrt(g)]), lo, hi, g, bands };
}
// The contour of energy E as polylines (one for a swinging orbit, two for a turning one).
function energyContour(E, g) {
  const pOf = (q) => Math.sqrt(Math.max(0, 2 * (E + g * Math.cos(q))));
  const N = 160, out = [];
  if (E < g) {
    const qa = Math.acos(Math.max(-1, Math.min(1, -E / g))), top = [], bottom = [];
    // Points crowd at the turning points, where the contour turns.
    for (let k = 0; k <= N; k++) { const q = -qa * Math.cos((Math.PI * k) / N); top.push([q, pOf(q)]); bottom.push([q, -pOf(q)]); }
    out.push([...top, ...bottom.reverse()]);
  } else {
    for (const sign of [1, -1]) out.push(Array.from({ length: N + 1 }, (_, k) => { const q = -Math.PI + (TAU * k) / N; return [q, sign * pOf(q)]; }));
  }
  return out;
}
// The members as points, in their energy's colour; `at(θ)` places an angle in the view.
function swarmPoints(ctx, v, s, n, at) {
  if (!app.swarmReach) app.swarmReach = swarmReach();
  // A few pendulums as dots that show; thousands as points that leave the filament's shape.
  const d = n <= 50 ? 6 : n <= 500 ? 4 : 3;
  app.swarmReach?.bands.forEach((members, b) => {
    ctx.fillStyle = SWARM_COLOURS[b];
    ctx.beginPath();
    for (const i of members) ctx.rect(v.X(at(s[i])) - d / 2, v.Y(s[n + i]) - d / 2, d, d);
    ctx.fill();
  });
}
function swarmLabels() {
  const sym = presentation().symbols?.[0] ?? "q", units = stateUnits(), { dot } = stateLayout(), n = app.lab.state().length / 2;
  return [label(sym, units[0]), label(momentumOf(sym, dot), units[n])];
}
function drawSwarm(ctx, w, h) {
  const s = app.lab.state(), n = s.length / 2;
  if (!app.swarmReach) app.swarmReach = swarmReach();
  const reach = app.swarmReach, g = reach?.g ?? swarmG();
  const v = plotView(w, h, reach?.box ?? { x0: -Math.PI, x1: Math.PI, y0: -3 * Math.sqrt(g), y1: 3 * Math.sqrt(g) }, false);
  app.sceneView = v;
  // Multiples of π/2 where the view spans more than π, else ordinary ticks.
  const piTicks = v.box.x1 - v.box.x0 > Math.PI
    ? [[-Math.PI, "−π"], [-Math.PI / 2, "−π/2"], [0, "0"], [Math.PI / 2, "π/2"], [Math.PI, "π"]].filter(([x]) => x >= v.box.x0 - 1e-9 && x <= v.box.x1 + 1e-9)
    : null;
  const [xl, yl] = swarmLabels();
  drawAxes("scene", ctx, v, xl, yl, { xTicks: piTicks });
  clip(ctx, v);
  // The band the swarm winds in: its lowest and highest energies' contours.
  if (reach) {
    ctx.strokeStyle = "#b9b9b9"; ctx.lineWidth = 1;
    for (const E of reach.hi - reach.lo > 1e-12 * Math.abs(reach.hi) ? [reach.lo, reach.hi] : [reach.hi]) {
      for (const line of energyContour(E, g)) { ctx.beginPath(); line.forEach(([q, p], k) => (k ? ctx.lineTo(v.X(q), v.Y(p)) : ctx.moveTo(v.X(q), v.Y(p)))); ctx.stroke(); }
    }
  }
  ctx.strokeStyle = "#777"; ctx.setLineDash([6, 4]); ctx.lineWidth = 1.2;
  for (const line of energyContour(g, g)) { ctx.beginPath(); line.forEach(([q, p], k) => (k ? ctx.lineTo(v.X(q), v.Y(p)) : ctx.moveTo(v.X(q), v.Y(p)))); ctx.stroke(); }
  ctx.setLineDash([]);
  swarmPoints(ctx, v, s, n, wrapQ);
  // The close-up's frame (the phase panel), drawn where the swarm is (and a turn of 2π
  // either side, for a swarm across θ = ±π).
  const cu = swarmCloseUp();
  if (cu) {
    ctx.strokeStyle = "#333"; ctx.lineWidth = 1; ctx.setLineDash([4, 3]);
    const c = wrapQ((cu.box.x0 + cu.box.x1) / 2) - (cu.box.x0 + cu.box.x1) / 2;
    for (const d of [c - TAU, c, c + TAU]) ctx.strokeRect(v.X(cu.box.x0 + d), v.Y(cu.box.y1), v.X(cu.box.x1 + d) - v.X(cu.box.x0 + d), v.Y(cu.box.y0) - v.Y(cu.box.y1));
    ctx.setLineDash([]);
  }
  const inView = energyContour(g, g).some((line) => line.some(([q, p]) => q >= v.box.x0 && q <= v.box.x1 && p >= v.box.y0 && p <= v.box.y1));
  sceneNote(`${n} pendulums, each a point of the phase plane, coloured by its energy (dark blue the lowest, orange the highest). Each keeps its energy, so the swarm stays between the grey contours of its lowest and highest energies: the view is that band, fixed for the run. ` +
    `${inView ? "Dashed: the separatrix between swinging and turning over. " : ""}The dashed frame is the close-up below${cu ? `, ×${cu.zoom.toPrecision(2)}` : ""}.`);
  ctx.restore();
}

// The close-up of the swarm in the phase panel: the swarm's extent (angles taken about their
// circular mean, so a swarm across θ = ±π stays in one piece) with a margin, centred on it, at
// the scene's ratio of scales (shapes as in the scene, magnified). The magnification only falls
// during a run (the frame grows as the swarm stretches and folds, never zooms back in), and
// starts again with the run.
const CLOSE_MARGIN = 0.3;
function swarmCloseUp() {
  const sv = app.sceneView, c = $("phase");
  if (!sv || kind() !== "swarm") return null;
  const s = app.lab.state(), n = s.length / 2;
  let cs = 0, sn = 0;
  for (let i = 0; i < n; i++) { cs += Math.cos(s[i]); sn += Math.sin(s[i]); }
  const mean = Math.atan2(sn, cs);
  let box = null;
  for (let i = 0; i < n; i++) box = grow(box, mean + wrapQ(s[i] - mean), s[n + i]);
  if (!box) return null;
  const g = swarmG();
  // Spans a hair above nothing (a swarm of one, or at rest): a hundredth of the scene's.
  const sw = Math.max(box.x1 - box.x0, 1e-2 * (sv.box.x1 - sv.box.x0)), sh = Math.max(box.y1 - box.y0, 1e-2 * (sv.box.y1 - sv.box.y0));
  const pv = plotView(c.clientWidth || 640, c.clientHeight || 400, { x0: 0, x1: 1, y0: 0, y1: 1 }, false);
  const rw = pv.rect.x1 - pv.rect.x0, rh = pv.rect.y1 - pv.rect.y0;
  const sx = (sv.rect.x1 - sv.rect.x0) / (sv.box.x1 - sv.box.x0), sy = (sv.rect.y1 - sv.rect.y0) / (sv.box.y1 - sv.box.y0);
  // Pixels per radian in the close-up: the swarm and its margin fit both ways at the scene's
  // ratio of scales; never more than before in this run, never less than the scene's.
  let k = Math.min(rw / ((1 + 2 * CLOSE_MARGIN) * sw), (rh / ((1 + 2 * CLOSE_MARGIN) * sh)) * (sx / sy));
  if (app.closeScale) k = Math.min(k, app.closeScale);
  k = Math.max(k, sx * Math.min(1, rw / (sv.rect.x1 - sv.rect.x0)));
  app.closeScale = k;
  const ky = k * (sy / sx), cx = (box.x0 + box.x1) / 2, cy = (box.y0 + box.y1) / 2;
  return { box: { x0: cx - rw / (2 * k), x1: cx + rw / (2 * k), y0: cy - rh / (2 * ky), y1: cy + rh / (2 * ky) }, zoom: k / sx, swarm: box };
}
function drawSwarmCloseUp() {
  const { ctx, w, h } = surface("phase");
  const cu = swarmCloseUp();
  if (!cu) return;
  const v = plotView(w, h, cu.box, false);
  app.closeView = { box: v.box, swarm: cu.swarm, zoom: cu.zoom };
  const [xl, yl] = swarmLabels();
  drawAxes("phase", ctx, v, xl, yl);
  clip(ctx, v);
  const s = app.lab.state(), n = s.length / 2, mid = (cu.box.x0 + cu.box.x1) / 2;
  swarmPoints(ctx, v, s, n, (q) => mid + wrapQ(q - mid));
  ctx.restore();
  const note = `Close-up of the swarm (the dashed frame above), magnified ×${cu.zoom.toPrecision(2)}: it stretches and folds, and its area stays the same (Liouville's theorem).`;
  if ($("closeup-caption").textContent !== note) $("closeup-caption").textContent = note;
}

// A chain: masses on springs drawn along a line (each displaced by its coordinate, to scale
// with the spacing), walls at fixed ends, and below, each site's displacement against the
// site with axes. Sine–Gordon: only the sites on a line with their displacement (an angle).
// The least spacing of the masses on a chain's strip, in CSS pixels: springs of three coils
// between masses 7 px wide, as readable projected as on a phone.
const STRIP_GAP = 22;
function drawChain(ctx, w, h, k) {
  const s = app.lab.state(), n = ndof(), ring = presentation().drawing.ends === "periodic";
  const unit = stateUnits()[0], sym = presentation().symbols?.[0] ?? "q";
  let amp = 0;
  if (app.extent) for (let i = 0; i < n; i++) amp = Math.max(amp, Math.abs(app.extent.lo[i]), Math.abs(app.extent.hi[i]));
  for (let i = 0; i < n; i++) amp = Math.max(amp, Math.abs(s[i]));
  amp = amp || 1;
  // A new run of the same setup keeps the scale it had (it may grow).
  amp = Math.max(amp, app.ampFloor ?? 0);
  // While a mass is dragged the drawing keeps its scale, so the mass stays under the pointer.
  if (app.drag?.chain) amp = app.drag.amp;
  if (n === 1 && k === "chain") {
    drawOneMass(ctx, w, h, s[0], amp, label(sym, unit));
    app.chainGeom = { one: true, v: app.sceneView, amp };
    return;
  }
  const top = k === "chain" ? Math.min(110, h * 0.32) : 0;
  const v = plotView(w, h - top, { x0: 0.5, x1: n + 0.5, y0: -1.1 * amp, y1: 1.1 * amp }, false);
  ctx.save(); ctx.translate(0, top);
  drawAxes("scene", ctx, v, "site", label(sym, unit));
  clip(ctx, v);
  // On a narrow canvas (a phone) a strip of every mass would be too dense to read: it shows
  // the chain's middle, masses at least STRIP_GAP px apart, marked on the plot by a band.
  const count = k === "chain" ? Math.min(n, Math.max(3, Math.floor((v.rect.x1 - v.rect.x0) / STRIP_GAP) - 1)) : n;
  const first = Math.floor((n - count) / 2), last = first + count - 1;
  if (count < n) { ctx.fillStyle = "rgba(192, 57, 43, 0.1)"; ctx.fillRect(v.X(first + 0.5), v.rect.y0, v.X(last + 1.5) - v.X(first + 0.5), v.rect.y1 - v.rect.y0); }
  ctx.strokeStyle = "#999"; ctx.lineWidth = 1; ctx.beginPath(); ctx.moveTo(v.rect.x0, v.Y(0)); ctx.lineTo(v.rect.x1, v.Y(0)); ctx.stroke();
  ctx.strokeStyle = "#2860c8"; ctx.lineWidth = 1.5; ctx.beginPath();
  for (let i = 0; i < n; i++) (i ? ctx.lineTo(v.X(i + 1), v.Y(s[i])) : ctx.moveTo(v.X(i + 1), v.Y(s[i])));
  ctx.stroke();
  ctx.fillStyle = "#c0392b";
  // Dots no wider than 0.6 of their spacing (32 sites on a phone are 9 px apart).
  const r = n > 60 ? 1.8 : Math.min(4, 0.3 * (v.X(2) - v.X(1)));
  for (let i = 0; i < n; i++) { ctx.beginPath(); ctx.arc(v.X(i + 1), v.Y(s[i]), r, 0, TAU); ctx.fill(); }
  ctx.restore(); ctx.restore();
  app.chainGeom = { v, top, amp, strip: false };
  if (k !== "chain") {
    // A chain at rest (its default start) has nothing to show until a site is moved.
    const rest = Array.from(s).every((x) => x === 0);
    sceneNote(`${n} sites: each one's ${texText(sym)} against its place in the chain${rest ? ". All at rest: drag a site up or down to start a wave" : ""}.`);
    return;
  }
  // The masses on their springs, displacements to scale: a displacement of `amp` moves a
  // mass 0.3 of the spacing, so neighbours' centres stay 0.4 of it apart, and a mass is at
  // most 0.36 of it wide (at least 5 px), so neighbours do not overlap. A window of the
  // chain (`first` to `last`) goes on at both sides: springs to the strip's edges, in grey.
  const whole = count === n;
  const x0 = v.rect.x0, x1 = v.rect.x1, y = top * 0.55, gap = (x1 - x0) / (count + 1), gain = (0.3 * gap) / amp;
  const X = (i) => x0 + gap * (i - first + 1) + gain * s[i];
  Object.assign(app.chainGeom, { strip: true, x0, gap, gain, y, first, count });
  ctx.strokeStyle = whole ? "#555" : "#aaa"; ctx.lineWidth = 1.2;
  const half = Math.max(2.5, Math.min(8, 0.18 * gap));
  if (!ring || !whole) {
    if (whole) { ctx.fillStyle = "#bbb"; ctx.fillRect(x0 - 8, y - 18, 8, 36); ctx.fillRect(x1, y - 18, 8, 36); }
    coil(ctx, x0, y, X(first) - half, y, 5, 4);
    coil(ctx, X(last) + half, y, x1, y, 5, 4);
  }
  ctx.strokeStyle = "#555";
  for (let i = first; i < last; i++) coil(ctx, X(i) + half, y, X(i + 1) - half, y, Math.max(2, Math.min(6, Math.round(gap / 8))), Math.min(4, half * 0.6));
  if (ring && whole) {
    // The ring's closing spring, from the last mass back round to the first, drawn as a
    // loop under the strip.
    const drop = Math.min(0.35 * top, 3 * half + 10);
    ctx.beginPath(); ctx.moveTo(X(n - 1) + half, y);
    ctx.bezierCurveTo(x1 + 0.6 * gap, y, x1 + 0.6 * gap, y + drop, (x0 + x1) / 2, y + drop);
    ctx.bezierCurveTo(x0 - 0.6 * gap, y + drop, x0 - 0.6 * gap, y, X(0) - half, y);
    ctx.setLineDash([4, 3]); ctx.stroke(); ctx.setLineDash([]);
  }
  ctx.fillStyle = "#c0392b";
  for (let i = first; i <= last; i++) ctx.fillRect(X(i) - half, y - half, 2 * half, 2 * half);
  const strip = whole ? `${n} masses on springs${ring ? " (a ring: the last is joined to the first, dashed)" : ", fixed walls at both ends"}`
    : `masses ${first + 1} to ${last + 1} of the ${n} on springs (the band below; the chain goes on at both sides)`;
  sceneNote(`Above: ${strip}, displacements to scale. Below: each mass's displacement against its place in the chain.`);
}

// One mass on a spring from a wall, seen from the side, its displacement x to scale on the
// axis (0: the spring's rest length), with the run's extent as a faint band.
function drawOneMass(ctx, w, h, x, amp, xLabel) {
  const v = plotView(w, h, { x0: -2.3 * amp, x1: 1.25 * amp, y0: -amp, y1: amp }, false);
  app.sceneView = v;
  drawAxes("scene", ctx, v, xLabel, "", { yTicks: [[0, ""]] });
  // A line, not a plane: the scene has no y axis (the tests read `line`).
  app.ticks.scene = { ...app.ticks.scene, y: [], yLabel: "", line: true };
  clip(ctx, v);
  const y = v.Y(0), half = Math.min(22, (v.rect.y1 - v.rect.y0) / 5), wall = v.X(-2.2 * amp);
  if (app.extent) { ctx.fillStyle = "rgba(40, 90, 200, 0.1)"; ctx.fillRect(v.X(app.extent.lo[0]), y - 1.6 * half, v.X(app.extent.hi[0]) - v.X(app.extent.lo[0]), 3.2 * half); }
  ctx.fillStyle = "#bbb"; ctx.fillRect(wall - 10, y - 2 * half, 10, 4 * half);
  ctx.strokeStyle = "#999"; ctx.setLineDash([5, 4]); ctx.beginPath(); ctx.moveTo(v.X(0), y - 2 * half); ctx.lineTo(v.X(0), y + 2 * half); ctx.stroke(); ctx.setLineDash([]);
  ctx.strokeStyle = "#555"; ctx.lineWidth = 1.6;
  coil(ctx, wall, y, v.X(x) - half, y, 12, half * 0.45);
  ctx.fillStyle = "#c0392b"; ctx.fillRect(v.X(x) - half, y - half, 2 * half, 2 * half);
  ctx.strokeStyle = "#5a1a12"; ctx.lineWidth = 1.2; ctx.strokeRect(v.X(x) - half, y - half, 2 * half, 2 * half);
  ctx.restore();
  sceneNote("A mass on a spring, seen from the side: its displacement from the spring's rest length (dashed) to scale; the band is the range of the run.");
}

// A system with nothing to draw as bodies (a reduced model's ODE): each state entry against
// time, over the recorded run, in a colour of its own.
function drawSeries(ctx, w, h) {
  const rows = app.rows, labels = stateLabels(), n = labels.length;
  let box = app.sceneBox;
  if (!box && app.extent) box = pad({ x0: 0, x1: 1, y0: Math.min(...app.extent.lo), y1: Math.max(...app.extent.hi) }, 0.05);
  for (const r of rows) for (let i = 0; i < n; i++) box = grow(box, r[0], r[3 + i]);
  const t1 = rows.length ? rows[rows.length - 1][0] : 1;
  box = { ...box, x0: 0, x1: Math.max(t1, 1e-9) };
  app.sceneBox = { ...box };
  const v = plotView(w, h, box, false);
  app.sceneView = v;
  drawAxes("scene", ctx, v, timeLabel(), `state: ${labels.join(", ")}`);
  clip(ctx, v);
  for (let i = 0; i < n; i++) {
    ctx.strokeStyle = orbitColour(i); ctx.lineWidth = 1.5; ctx.beginPath();
    rows.forEach((r, k) => (k ? ctx.lineTo(v.X(r[0]), v.Y(r[3 + i])) : ctx.moveTo(v.X(r[0]), v.Y(r[3 + i]))));
    ctx.stroke();
  }
  ctx.restore();
}

// ---------- the newest bodies: Foucault's swing, Euler's disk, rattlebacks, rolling bodies ----------

// A caption under the scene, in the page's text (it wraps on a phone; a canvas line would be
// cut): what the picture shows and its live numbers.
// The scene's caption, in people's symbols (peopleRuns: `Ω_{⊕}` shows as Ω with ⊕ lowered).
// A note under the scene; a number's sign is a minus sign (−2.883), not a hyphen.
function sceneNote(text) {
  text = text.replace(/(^|[\s(=,])-(?=\d)/g, "$1−");
  const el = $("scene-note");
  if (el.dataset.text !== text) { el.dataset.text = text; setRuns(el, peopleRuns(text)); }
}

// A floor grid in perspective with tick labels in metres along two edges, centred at
// (cx, cy) with half-width `half`; records the scene's ticks for the tests.
// `avoid`: boxes of the body over the floor, where no tick label goes.
function drawFloor(ctx, P, cx, cy, half, avoid = []) {
  const tx = tickValues(cx - half, cx + half, 4), ty = tickValues(cy - half, cy + half, 4);
  const line = (a, b) => { ctx.beginPath(); ctx.moveTo(...P(a)); ctx.lineTo(...P(b)); ctx.stroke(); };
  ctx.strokeStyle = "#ddd"; ctx.lineWidth = 1;
  for (const g of tx.values) line([g, cy - half, 0], [g, cy + half, 0]);
  for (const g of ty.values) line([cx - half, g, 0], [cx + half, g, 0]);
  ctx.fillStyle = "#555"; ctx.textAlign = "center"; ctx.textBaseline = "top";
  const xs = tx.values.map((g) => tickText(g, tx.step)), ys = ty.values.map((g) => tickText(g, ty.step));
  const put = labelPlacer(ctx, avoid);
  put.first(lengthLabel("x"), alongEdge((g) => P([cx + g, cy - half * 1.32, 0]), 0.3 * half));
  put.first(lengthLabel("y"), alongEdge((g) => P([cx + half * 1.38, cy + g, 0]), 0.3 * half));
  const xShown = xs.filter((x, i) => put(x, P([tx.values[i], cy - half * 1.1, 0])));
  const yShown = ys.filter((y, i) => put(y, P([cx + half * 1.12, ty.values[i], 0])));
  ctx.textBaseline = "alphabetic";
  app.ticks.scene = { x: xShown, y: yShown, xLabel: lengthLabel("x"), yLabel: lengthLabel("y") };
}

// A curved arrow round the vertical through `centre` (radius `r` in metres): the sense and
// size of a spin about the vertical. `spin` > 0 turns anticlockwise seen from above.
function spinArrow(ctx, P, centre, r, spin, colour, reference) {
  if (!(Math.abs(spin) > 1e-9)) return;
  // The arc's length in proportion to the spin against `reference` (the run's starting spin).
  const sweep = (0.25 + 1.3 * Math.PI * Math.min(1, Math.abs(spin) / Math.max(Math.abs(reference) || 0, Math.abs(spin)))) * Math.sign(spin), pts = [];
  for (let k = 0; k <= 40; k++) { const a = (sweep * k) / 40; pts.push(P([centre[0] + r * Math.cos(a), centre[1] + r * Math.sin(a), centre[2]])); }
  ctx.strokeStyle = colour; ctx.lineWidth = 2.2; ctx.beginPath();
  pts.forEach(([x, y], k) => (k ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
  ctx.stroke();
  const [x1, y1] = pts[pts.length - 1], [x0, y0] = pts[pts.length - 3];
  arrow(ctx, x0, y0, x1, y1, colour);
}

// Foucault's pendulum seen from above: the bob's path (a rosette), the swing plane it started
// in (dashed) and where it swings now (the line through its farthest recent point), the bob,
// and the turn of the plane beside the Earth's: −Ω_⊕ sin(latitude) t.
function drawSwing(ctx, w, h) {
  const s = app.lab.state(), units = stateUnits(), T = app.trails;
  let amp = Math.hypot(s[0], s[1]);
  if (app.extent) for (const i of [0, 1]) amp = Math.max(amp, Math.abs(app.extent.lo[i]), Math.abs(app.extent.hi[i]));
  amp = 1.15 * (amp || 1);
  const v = plotView(w, h, { x0: -amp, x1: amp, y0: -amp, y1: amp }, true);
  app.sceneView = v;
  const labels = stateSymbols();
  drawAxes("scene", ctx, v, label(`${labels[0]}`, units[0]), label(`${labels[1]}`, units[1]));
  clip(ctx, v);
  ctx.fillStyle = "#777"; ctx.textAlign = "center"; ctx.textBaseline = "middle";
  ctx.fillText("N", v.X(0), v.rect.y0 + 12); ctx.fillText("E", v.rect.x1 - 10, v.Y(0));
  const s0 = app.lab.initialState();
  const a0 = Math.hypot(s0[0], s0[1]) > 0 ? Math.atan2(s0[1], s0[0]) : Math.atan2(s0[3], s0[2]);
  ctx.setLineDash([6, 5]); ctx.strokeStyle = "#999"; ctx.lineWidth = 1.2;
  ctx.beginPath(); ctx.moveTo(v.X(-amp * Math.cos(a0)), v.Y(-amp * Math.sin(a0))); ctx.lineTo(v.X(amp * Math.cos(a0)), v.Y(amp * Math.sin(a0))); ctx.stroke();
  ctx.setLineDash([]);
  ctx.lineWidth = 1.3;
  const n = T.length;
  for (let b = 0; b < 8 && n > 1; b++) {
    const k0 = Math.floor((b * (n - 1)) / 8), k1 = Math.floor(((b + 1) * (n - 1)) / 8);
    ctx.strokeStyle = `rgba(40, 90, 200, ${0.15 + (0.7 * (b + 1)) / 8})`;
    ctx.beginPath();
    for (let k = k0; k <= k1; k++) (k === k0 ? ctx.moveTo(v.X(T[k][0]), v.Y(T[k][1])) : ctx.lineTo(v.X(T[k][0]), v.Y(T[k][1])));
    ctx.stroke();
  }
  // The swing plane now: the farthest point of the last swing (a period's samples).
  const omega0 = Math.sqrt(param("g") / param("length")), lat = (param("latitude_deg") * Math.PI) / 180;
  const omegaZ = param("omega_earth") * Math.sin(lat), period = TAU / omega0;
  let far = null;
  for (let k = n - 1; k >= 0 && T[n - 1][4] - T[k][4] <= period; k--) if (!far || Math.hypot(T[k][0], T[k][1]) > Math.hypot(far[0], far[1])) far = T[k];
  ctx.strokeStyle = "#1e7d32"; ctx.lineWidth = 2;
  let turned = null;
  if (far && Math.hypot(far[0], far[1]) > 0) {
    const a = Math.atan2(far[1], far[0]);
    ctx.beginPath(); ctx.moveTo(v.X(-amp * Math.cos(a)), v.Y(-amp * Math.sin(a))); ctx.lineTo(v.X(amp * Math.cos(a)), v.Y(amp * Math.sin(a))); ctx.stroke();
    // A plane's direction is defined modulo π: the turn in (−90°, 90°].
    turned = ((a - a0 + Math.PI / 2) % Math.PI + Math.PI) % Math.PI - Math.PI / 2;
  }
  // For the tests: the measured turn (rad), the time of the sample it was measured at, and Ω⊕ sin(latitude).
  app.swingTurn = { turned, at: far ? far[4] : null, omegaZ };
  ctx.fillStyle = "#333"; ctx.beginPath(); ctx.arc(v.X(0), v.Y(0), 3, 0, TAU); ctx.fill();
  bob(ctx, v.X(s[0]), v.Y(s[1]), 8, 0);
  ctx.restore();
  // The closed form at the time of the sample the turn was measured at (up to a swing ago).
  const t = turned === null ? app.lab.time() : far[4], deg = (x) => `${((x * 180) / Math.PI).toFixed(3)}°`.replace("-", "−");
  const day = Math.abs(omegaZ) > 0 ? `; a full turn takes ${(TAU / Math.abs(omegaZ) / 3600).toPrecision(3)} h` : "";
  sceneNote(`Seen from above: the bob's path, the swing plane it started in (dashed) and its plane now (green)` +
    `${turned === null ? "" : `, turned ${deg(turned)} at t = ${t.toFixed(1)} s`}. The Earth's rotation Ω_{⊕} turns it by −Ω_{⊕} sin(latitude) t = ${deg(-omegaZ * t)}${day}.`);
}

// Euler's disk (the reduced model: inclination θ and the contact point's azimuth φ): the
// disk in perspective, tilted θ from the table and touching it at azimuth φ from below its
// centre, with the contact point's path on the table (it spirals out to the rim's radius as
// the disk flattens). Lengths in units of the disk's radius (the model has none).
function drawTiltedDisk(ctx, w, h) {
  const s = app.lab.state(), [th, ph] = s;
  const v = plotView(w, h, { x0: -1.8, x1: 1.8, y0: -1.0, y1: 1.2 }, true, false);
  app.sceneView = v;
  const P = (p) => { const [x, y] = project3(p, 1.6, 0.55); return [v.X(x), v.Y(y)]; };
  const t = tickValues(-1, 1, 4), line = (a, b) => { ctx.beginPath(); ctx.moveTo(...P(a)); ctx.lineTo(...P(b)); ctx.stroke(); };
  ctx.strokeStyle = "#ddd"; ctx.lineWidth = 1;
  for (const g of t.values) { line([g, -1.2, 0], [g, 1.2, 0]); line([-1.2, g, 0], [1.2, g, 0]); }
  ctx.fillStyle = "#555"; ctx.textAlign = "center"; ctx.textBaseline = "top";
  const xs = t.values.map((g) => tickText(g, t.step));
  // The disk (its rim and its shadow) lies over the floor: a tick label it would cover is left out.
  const c = [0, 0, Math.sin(th)], er = [-Math.cos(th) * Math.cos(ph), -Math.cos(th) * Math.sin(ph), Math.sin(th)], et = [-Math.sin(ph), Math.cos(ph), 0];
  const rim = (a) => [0, 1, 2].map((i) => c[i] + Math.cos(a) * er[i] + Math.sin(a) * et[i]);
  let disk = null;
  for (let k = 0; k < 32; k++) { const p = rim((TAU * k) / 32); disk = grow(grow(disk, ...P(p)), ...P([p[0], p[1], 0])); }
  const put = labelPlacer(ctx, [[disk.x0, disk.y0, disk.x1, disk.y1]]);
  // Lengths in units of the disk's radius R (drawn 1: the reduced model has no size).
  put.first("x / R", alongEdge((g) => P([g, -1.6, 0]), 0.3));
  put.first("y / R", alongEdge((g) => P([1.62, g, 0]), 0.3));
  const xShown = xs.filter((x, i) => put(x, P([t.values[i], -1.3, 0])));
  const yShown = xs.filter((y, i) => put(y, P([1.32, t.values[i], 0])));
  ctx.textBaseline = "alphabetic";
  app.ticks.scene = { x: xShown, y: yShown, xLabel: "x / R", yLabel: "y / R" };
  const contact = (a, b) => [Math.cos(a) * Math.cos(b), Math.cos(a) * Math.sin(b), 0];
  // The contact point's path so far.
  const T = app.trails;
  ctx.lineWidth = 1.5;
  for (let k = 1; k < T.length; k++) {
    ctx.strokeStyle = `rgba(40, 90, 200, ${0.1 + (0.7 * k) / T.length})`;
    line(contact(T[k - 1][0], T[k - 1][1]), contact(T[k][0], T[k][1]));
  }
  // Its shadow, straight below.
  ctx.fillStyle = "rgba(0, 0, 0, 0.08)"; ctx.beginPath();
  for (let k = 0; k <= 64; k++) { const p = rim((TAU * k) / 64); const [x, y] = P([p[0], p[1], 0]); k ? ctx.lineTo(x, y) : ctx.moveTo(x, y); }
  ctx.fill();
  ctx.beginPath();
  for (let k = 0; k <= 64; k++) { const [x, y] = P(rim((TAU * k) / 64)); k ? ctx.lineTo(x, y) : ctx.moveTo(x, y); }
  ctx.fillStyle = "rgba(160, 165, 175, 0.55)"; ctx.fill();
  ctx.strokeStyle = "#555"; ctx.lineWidth = 2; ctx.stroke();
  ctx.strokeStyle = "#888"; ctx.lineWidth = 1; line(c, rim(Math.PI));
  const [px, py] = P(contact(th, ph));
  ctx.fillStyle = "#c0392b"; ctx.beginPath(); ctx.arc(px, py, 5, 0, TAU); ctx.fill();
  const rate = param("precession_const") / Math.max(th, param("theta_floor"));
  // The model's collapse: θ θ' = −decay rate, so θ reaches 0 at θ₀² / (2 decay rate).
  const th0 = app.lab.initialState()[0], tf = (th0 * th0) / (2 * param("decay_rate"));
  sceneNote(`${app.ended ? "At rest. " : ""}The disk tilted θ = ${th.toFixed(3)} rad from the table; its contact point (red) runs round at φ̇ = ${rate.toPrecision(3)} rad/s, ` +
    `faster as the disk flattens, which it does at t = θ₀² / (2 × decay rate) = ${tf.toPrecision(3)} s, where the model ends ` +
    `(lengths in units of the disk's radius R; the reduced model has no size).`);
}

// The rattleback's rates in a body: an ellipsoid seen in perspective, turned about the
// vertical by its spin (the angle ∫ n₃ dt, added up over the drawn samples) and rocked in
// proportion to the rocking rates n₁, n₂; a curved arrow shows the sense and size of the spin.
// Proportions of a typical rattleback (the reduced model has no shape).
function drawSpinner(ctx, w, h, s) {
  // The body left of the rates' bars and their scale (drawRateBars: three bars 2.2 font sizes
  // apart, their axis's labels about 4.5 font sizes to its left).
  const v = plotView(w - (11.1 * fontSize() + 10), h, { x0: -1.4, x1: 1.4, y0: -0.8, y1: 1.0 }, true, false);
  app.sceneView = v;
  const P = (p) => { const [x, y] = project3(p, 1.4, 0.55); return [v.X(x), v.Y(y)]; };
  const line = (a, b) => { ctx.beginPath(); ctx.moveTo(...P(a)); ctx.lineTo(...P(b)); ctx.stroke(); };
  ctx.strokeStyle = "#ddd"; ctx.lineWidth = 1;
  for (let g = -1; g <= 1.001; g += 0.5) { line([g, -1, 0], [g, 1, 0]); line([-1, g, 0], [1, g, 0]); }
  const nmax = Math.max(1e-9, ...(app.extent ? [0, 1].map((i) => Math.max(Math.abs(app.extent.lo[i]), Math.abs(app.extent.hi[i]))) : [1]));
  const roll = (0.25 * s[0]) / nmax, pitch = (0.25 * s[1]) / nmax, yaw = app.spinAngle ?? 0;
  // Body axes turned: yaw about z, then small rocking about the body's x and y.
  const R = (p) => {
    let [x, y, z] = p;
    [y, z] = [y * Math.cos(roll) - z * Math.sin(roll), y * Math.sin(roll) + z * Math.cos(roll)];
    [x, z] = [x * Math.cos(pitch) + z * Math.sin(pitch), -x * Math.sin(pitch) + z * Math.cos(pitch)];
    return [x * Math.cos(yaw) - y * Math.sin(yaw), x * Math.sin(yaw) + y * Math.cos(yaw), z + 0.12];
  };
  const semi = [1, 0.3, 0.12];
  ctx.lineWidth = 1.2;
  const ring = (f, colour) => {
    ctx.strokeStyle = colour; ctx.beginPath();
    for (let k = 0; k <= 64; k++) { const [x, y] = P(R(f((TAU * k) / 64))); k ? ctx.lineTo(x, y) : ctx.moveTo(x, y); }
    ctx.stroke();
  };
  ctx.fillStyle = "rgba(192, 57, 43, 0.25)"; ctx.beginPath();
  for (let k = 0; k <= 64; k++) { const a = (TAU * k) / 64, [x, y] = P(R([semi[0] * Math.cos(a), semi[1] * Math.sin(a), 0])); k ? ctx.lineTo(x, y) : ctx.moveTo(x, y); }
  ctx.fill();
  ring((a) => [semi[0] * Math.cos(a), semi[1] * Math.sin(a), 0], "#7a2a1e");
  ring((a) => [semi[0] * Math.cos(a), 0, semi[2] * Math.sin(a)], "#c0392b");
  ring((a) => [0, semi[1] * Math.cos(a), semi[2] * Math.sin(a)], "#c0392b");
  ctx.strokeStyle = "#7a2a1e"; ctx.lineWidth = 2.5; line(R([-semi[0], 0, 0]), R([semi[0], 0, 0]));
  spinArrow(ctx, P, [0, 0, 0.12], 1.15, s[2], "#1f5fbf", app.lab.initialState()[2]);
  app.ticks.scene = { x: [`n₁ = ${s[0].toPrecision(3)}`, `n₂ = ${s[1].toPrecision(3)}`], y: [`n₃ = ${s[2].toPrecision(3)}`], xLabel: "rocking rates n₁, n₂ (rad/s)", yLabel: "spin n₃ (rad/s)" };
  drawRateBars(ctx, w, h, s, nmax);
  sceneNote(`A rattleback's rates: the spin n₃ = ${s[2].toFixed(3)} rad/s (blue arrow: its sense seen from above; it turns the body), ` +
    `rocking n₁ = ${s[0].toFixed(3)}, n₂ = ${s[1].toFixed(3)} rad/s (the tilt, exaggerated). The reduced model has no shape: the body is drawn in a rattleback's proportions.`);
}

// Bars of the three rates, to the right of the body: the spin's reversal is the blue bar
// crossing zero.
function drawRateBars(ctx, w, h, s, nmax) {
  const f = fontSize(), x0 = w - 3 * 2.2 * f - 10, y0 = 14 + f, y1 = h - 2 * f, mid = (y0 + y1) / 2;
  const top = Math.max(nmax, Math.abs(app.lab.initialState()[2]) || 1, Math.abs(s[2]));
  ctx.strokeStyle = "#999"; ctx.lineWidth = 1; ctx.beginPath(); ctx.moveTo(x0 - 4, mid); ctx.lineTo(w - 6, mid); ctx.stroke();
  // Their scale: an axis on the left with ticks in rad/s.
  const Y = (r) => mid - ((y1 - y0) / 2) * (r / top), t = tickValues(-top, top, 4), ax = x0 - 8;
  ctx.strokeStyle = "#555"; ctx.beginPath(); ctx.moveTo(ax, y0); ctx.lineTo(ax, y1);
  ctx.fillStyle = "#333"; ctx.textAlign = "right"; ctx.textBaseline = "middle";
  for (const r of t.values) { ctx.moveTo(ax - 4, Y(r)); ctx.lineTo(ax, Y(r)); ctx.fillText(tickText(r, t.step), ax - 6, Y(r)); }
  ctx.stroke();
  ctx.textAlign = "center"; ctx.textBaseline = "bottom";
  ctx.fillText("rad/s", ax, y0 - 4);
  ["n₁", "n₂", "n₃"].forEach((name, i) => {
    const x = x0 + i * 2.2 * f, hgt = ((y1 - y0) / 2) * (s[i] / top);
    ctx.fillStyle = i === 2 ? "#1f5fbf" : "#c0392b";
    ctx.fillRect(x, Math.min(mid, mid - hgt), 1.4 * f, Math.abs(hgt));
    ctx.fillStyle = "#333"; ctx.textAlign = "center"; ctx.textBaseline = "top";
    ctx.fillText(name, x + 0.7 * f, y1 + 4);
  });
  ctx.textBaseline = "alphabetic";
}

// Quaternion [w, x, y, z] (any norm) to the rows of its rotation matrix, normalised.
function rotationRows(q) {
  const [w, x, y, z] = q, n = w * w + x * x + y * y + z * z, k = 2 / n;
  return [
    [1 - k * (y * y + z * z), k * (x * y - w * z), k * (x * z + w * y)],
    [k * (x * y + w * z), 1 - k * (x * x + z * z), k * (y * z - w * x)],
    [k * (x * z - w * y), k * (y * z + w * x), 1 - k * (x * x + y * y)],
  ];
}
const mulRows = (R, p) => R.map((row) => row[0] * p[0] + row[1] * p[1] + row[2] * p[2]);

// The rolling bodies' shape: the vector from the centre of mass to the contact point in the
// body frame for the upward vertical γ seen from the body, and points of the body's outline.
// (The same geometry as the catalogue's systems: an ellipsoid of semi-axes a, b, c whose
// centre is h above the centre of mass, or a thin disk's rim of radius a.)
function rollingShape() {
  if (presentation().drawing.shape === "ellipsoid") {
    const a = param("a"), b = param("b"), c = param("c"), hh = param("h"), A = [a * a, b * b, c * c];
    return {
      size: a,
      contact(g) { const ag = [A[0] * g[0], A[1] * g[1], A[2] * g[2]], s = Math.sqrt(ag[0] * g[0] + ag[1] * g[1] + ag[2] * g[2]); return [-ag[0] / s, -ag[1] / s, -ag[2] / s + hh]; },
      rings: [
        (t) => [a * Math.cos(t), b * Math.sin(t), hh],
        (t) => [a * Math.cos(t), 0, hh + c * Math.sin(t)],
        (t) => [0, b * Math.cos(t), hh + c * Math.sin(t)],
      ],
      outline: (t) => [a * Math.cos(t), b * Math.sin(t), hh],
      mark: [[-a, 0, hh], [a, 0, hh]],
    };
  }
  const a = param("a");
  return {
    size: a,
    contact(g) { const n = Math.hypot(g[0], g[1]) || 1; return [(-a * g[0]) / n, (-a * g[1]) / n, 0]; },
    rings: [(t) => [a * Math.cos(t), a * Math.sin(t), 0]],
    outline: (t) => [a * Math.cos(t), a * Math.sin(t), 0],
    mark: [[0, 0, 0], [a, 0, 0]],
  };
}

// A body rolling on the plane: the floor with ticks in metres, the contact point's path on it
// (fading), the body in perspective at its orientation with a mark that shows its turning,
// the contact point, and the spin about the vertical (ω · ẑ) as a curved arrow; the spin
// against time in the caption's numbers.
const RATTLEBACK_PATH = 30 * SAMPLES_PER_FRAME;
function drawRolling(ctx, w, h) {
  const s = app.lab.state(), shape = rollingShape(), T = app.trails;
  const R = rotationRows(s.slice(3, 7)), gamma = [R[2][0], R[2][1], R[2][2]];
  const r = shape.contact(gamma), rw = mulRows(R, r), cm = [s[7] - rw[0], s[8] - rw[1], -rw[2]];
  const world = (p) => { const q = mulRows(R, p); return [cm[0] + q[0], cm[1] + q[1], cm[2] + q[2]]; };
  // The view: centred on the run's contact path (the probe's extent), wide enough for the body.
  if (!app.rollingView) {
    const e = app.extent, lo = e ? [e.lo[7], e.lo[8]] : [s[7], s[8]], hi = e ? [e.hi[7], e.hi[8]] : [s[7], s[8]];
    const half = Math.max(1.25 * shape.size, 0.6 * Math.max(hi[0] - lo[0], hi[1] - lo[1]) + 1.1 * shape.size);
    app.rollingView = { cx: (lo[0] + hi[0]) / 2, cy: (lo[1] + hi[1]) / 2, half };
  }
  // It widens (never narrows) when the body rolls out of it.
  const away = Math.max(Math.abs(s[7] - app.rollingView.cx), Math.abs(s[8] - app.rollingView.cy)) + shape.size;
  if (away > app.rollingView.half) app.rollingView.half = 1.3 * away;
  const { cx, cy, half } = app.rollingView;
  // The box of the projected floor with its labels, and room above it for the body.
  let box = null;
  for (const [x, y, z] of [[-1.2, -1.2, 0], [-1.2, 1.2, 0], [1.2, -1.2, 0], [1.2, 1.2, 0], [0, 0, 0.5]]) {
    const [px, py] = project3([x * half, y * half, z * half], half, 0.6);
    box = grow(box, px, py);
  }
  const v = plotView(w, h, pad(box, 0.03), true, false);
  app.sceneView = v;
  const P = (p) => { const [x, y] = project3([p[0] - cx, p[1] - cy, p[2]], half, 0.6); return [v.X(x), v.Y(y)]; };
  // The body and its spin arrow stand over the floor: no tick label under them.
  let body = null;
  for (let k = 0; k < 36; k++) {
    const a = (TAU * k) / 36;
    for (const f of [shape.outline, ...shape.rings]) body = grow(body, ...P(world(f(a))));
    body = grow(body, ...P([cm[0] + 1.2 * shape.size * Math.cos(a), cm[1] + 1.2 * shape.size * Math.sin(a), cm[2]]));
  }
  drawFloor(ctx, P, cx, cy, half, [[body.x0, body.y0, body.x1, body.y1]]);
  ctx.lineWidth = 1.2;
  // The rattleback's contact point rocks to and fro ~100 times a second: its whole path is a
  // dense tangle, so only its recent stretch is drawn, fading out (RATTLEBACK_PATH samples:
  // 30 frames, half a second of motion at real time). The disks' path is a clean curve: all of it.
  const first = presentation().drawing.shape === "ellipsoid" ? Math.max(1, T.length - RATTLEBACK_PATH) : 1, shown = T.length - first + 1;
  for (let k = first; k < T.length; k++) {
    ctx.strokeStyle = `rgba(30, 125, 50, ${0.08 + (0.6 * (k - first + 1)) / shown})`;
    ctx.beginPath(); ctx.moveTo(...P([T[k - 1][7], T[k - 1][8], 0])); ctx.lineTo(...P([T[k][7], T[k][8], 0])); ctx.stroke();
  }
  // The shadow, the body's outline filled, its rings and its mark.
  const N = 72, path = (f) => { ctx.beginPath(); for (let k = 0; k <= N; k++) { const [x, y] = f((TAU * k) / N); k ? ctx.lineTo(x, y) : ctx.moveTo(x, y); } };
  ctx.fillStyle = "rgba(0, 0, 0, 0.1)";
  path((t) => { const p = world(shape.outline(t)); return P([p[0], p[1], 0]); }); ctx.fill();
  ctx.fillStyle = "rgba(192, 57, 43, 0.3)";
  path((t) => P(world(shape.outline(t)))); ctx.fill();
  ctx.lineWidth = 1.4;
  shape.rings.forEach((f, i) => { ctx.strokeStyle = i ? "#c0392b" : "#7a2a1e"; path((t) => P(world(f(t)))); ctx.stroke(); });
  ctx.strokeStyle = "#333"; ctx.lineWidth = 2.5;
  ctx.beginPath(); ctx.moveTo(...P(world(shape.mark[0]))); ctx.lineTo(...P(world(shape.mark[1]))); ctx.stroke();
  const [px, py] = P([s[7], s[8], 0]);
  ctx.fillStyle = "#1e7d32"; ctx.beginPath(); ctx.arc(px, py, 4.5, 0, TAU); ctx.fill();
  const spin = s[0] * gamma[0] + s[1] * gamma[1] + s[2] * gamma[2];
  const s0 = app.lab.initialState(), g0 = rotationRows(s0.slice(3, 7))[2];
  spinArrow(ctx, P, [cm[0], cm[1], cm[2]], 1.15 * shape.size, spin, "#1f5fbf", s0[0] * g0[0] + s0[1] * g0[1] + s0[2] * g0[2]);
  const tilt = Math.acos(Math.max(-1, Math.min(1, R[2][2])));
  const ellipsoid = presentation().drawing.shape === "ellipsoid", what = ellipsoid ? "The ellipsoid" : "The disk";
  sceneNote(`${what} rolling without slipping; green: the contact point and its path on the table. ` +
    `Spin about the vertical ω·ẑ = ${spin.toFixed(3)} rad/s (blue arrow, seen from above${ellipsoid ? "; a reversal crosses zero" : ""}), ` +
    `${ellipsoid ? "tilt" : "normal"} ${((tilt * 180) / Math.PI).toFixed(1)}° from the vertical.`);
}

function drawCurve(id, points, boxKey, labels, least = [0, 0]) {
  const { ctx, w, h } = surface(id);
  let box = app[boxKey];
  // The view: the probe run's extent of these coordinates, widened only when the run leaves
  // it (never narrowed mid-run).
  if (!box && app.extent && points.length) {
    const ix = Number($("phase-x").value), iy = Number($("phase-y").value);
    box = pad({ x0: app.extent.lo[ix], x1: app.extent.hi[ix], y0: app.extent.lo[iy], y1: app.extent.hi[iy] }, 0.08);
    if (app.phaseKeep) box = union(box, app.phaseKeep);
  }
  let outside = false;
  for (const [x, y] of points) if (box && (x < box.x0 || x > box.x1 || y < box.y0 || y > box.y1)) { outside = true; break; }
  if (!box || outside) { for (const [x, y] of points) box = grow(box, x, y); if (box && outside) box = pad(box, 0.1); }
  if (box) box = atLeast(box, least);
  app[boxKey] = box;
  if (!box) return null;
  const v = plotView(w, h, box, false);
  drawAxes(id, ctx, v, labels[0], labels[1]);
  clip(ctx, v);
  ctx.strokeStyle = "#2860c8"; ctx.lineWidth = 1.3; ctx.beginPath();
  points.forEach(([x, y], k) => (k ? ctx.lineTo(v.X(x), v.Y(y)) : ctx.moveTo(v.X(x), v.Y(y))));
  ctx.stroke();
  const last = points[points.length - 1];
  if (last) { ctx.fillStyle = "#c0392b"; ctx.beginPath(); ctx.arc(v.X(last[0]), v.Y(last[1]), 3.5, 0, TAU); ctx.fill(); }
  ctx.restore();
  return v;
}

// A box widened about its centre to spans of at least `least` ([x, y]).
function atLeast(box, [sx, sy]) {
  const widen = (a, b, span) => (b - a >= span ? [a, b] : [(a + b) / 2 - span / 2, (a + b) / 2 + span / 2]);
  const [x0, x1] = widen(box.x0, box.x1, sx), [y0, y1] = widen(box.y0, box.y1, sy);
  return { x0, x1, y0, y1 };
}

// The scale of state entry `i`: the largest magnitude over the probe run and now of the
// entries of its kind (all coordinates, or all momenta or velocities).
function entryScale(i) {
  const s = app.lab.state(), { k, paired } = stateLayout();
  const [a, b] = paired ? (i < k ? [0, k] : [k, 2 * k]) : [0, s.length];
  let m = 0;
  for (let j = a; j < b; j++) m = Math.max(m, Math.abs(s[j]), Math.abs(app.extent?.lo[j] ?? 0), Math.abs(app.extent?.hi[j] ?? 0));
  return m;
}

// The least span of the phase panel along entry `i`: an entry that keeps still next to the
// others of its kind (it moves less than STILL of their scale over the probe run: a sine-Gordon
// site the wave has not reached, at 1e-236) is shown on their scale, resting at its value, not
// magnified into ticks at 1e-235; any other keeps its own span.
const STILL = 1e-6;
function phaseLeast(i) {
  const scale = entryScale(i), lo = app.extent?.lo[i], hi = app.extent?.hi[i];
  return lo !== undefined && hi - lo < STILL * scale ? scale : 0;
}

function drawPhase() {
  if (kind() === "swarm") return drawSwarmCloseUp();
  const labels = stateAxisLabels(), ix = $("phase-x").value, iy = $("phase-y").value;
  drawCurve("phase", app.phase, "phaseBox", [labels[ix], labels[iy]], [phaseLeast(Number(ix)), phaseLeast(Number(iy))]);
}

function drawEnergy() {
  const { ctx, w, h } = surface("energy");
  const pts = app.energy.map(([t, e]) => [t, Math.log10(Math.max(e, 1e-17))]);
  let lo = Infinity, hi = -Infinity;
  for (const [, y] of pts) if (y > -17) { lo = Math.min(lo, y); hi = Math.max(hi, y); }
  if (!Number.isFinite(lo)) { lo = -17; hi = -15; }
  lo = Math.floor(lo); hi = Math.max(Math.ceil(hi), lo + 2);
  // At least ten frames' time: a fresh run's axis is not a sliver.
  const least = 10 * Number($("dt").value) * Number($("speed").value);
  const t0 = 0, t1 = Math.max(pts.length ? pts[pts.length - 1][0] : 0, least || 1);
  const v = plotView(w, h, { x0: t0, x1: t1 > t0 ? t1 : t0 + 1, y0: lo, y1: hi }, false);
  // Decades, labelled 10⁻ⁿ, thinned to fit the height.
  const every = Math.max(1, Math.ceil((hi - lo) / Math.max(2, Math.floor((v.rect.y1 - v.rect.y0) / (2.2 * fontSize())))));
  const yTicks = [];
  for (let d = lo; d <= hi; d++) if ((d - lo) % every === 0) yTicks.push([d, `10${superscriptInt(d)}`]);
  drawAxes("energy", ctx, v, timeLabel(), "|E − E₀| / |E₀|", { yTicks });
  clip(ctx, v);
  ctx.strokeStyle = "#c0392b"; ctx.lineWidth = 1.5; ctx.beginPath();
  pts.forEach(([x, y], k) => (k ? ctx.lineTo(v.X(x), v.Y(y)) : ctx.moveTo(v.X(x), v.Y(y))));
  ctx.stroke();
  ctx.restore();
}

// The edge of the section on the energy surface: the points (q1, p1) with q2 = 0, p2 = 0 at
// the run's energy, traced with the lab's own energy function by bisection in p1 at each q1;
// its extent is the section's view. `null` where the edge is not closed (an unbounded orbit).
const BOUNDARY_POINTS = 160;
function sectionBoundary() {
  const lab = app.lab, E = lab.energy0();
  const H = (x, px) => { try { return lab.energyOf([x, 0, px, 0]) - E; } catch { return NaN; } };
  const scale = Math.sqrt(2 * Math.abs(E)) || 1;
  const x00 = lab.initialState()[0];
  const start = H(x00, 0) <= 0 ? x00 : 0;
  if (!(H(start, 0) <= 0)) return null;
  const edge = (dir) => {
    let inside = start, step = scale / 50, out = null;
    for (let k = 0; k < 400 && out === null; k++) {
      const x = inside + dir * step;
      if (!(H(x, 0) <= 0)) out = x; else { inside = x; step *= 1.1; }
    }
    if (out === null) return null;
    for (let k = 0; k < 60; k++) { const m = (inside + out) / 2; if (H(m, 0) <= 0) inside = m; else out = m; }
    return inside;
  };
  const xl = edge(-1), xr = edge(1);
  if (xl === null || xr === null) return null;
  const pAt = (x, sign) => {
    let lo = 0, hi = scale;
    for (let k = 0; k < 60 && H(x, sign * hi) <= 0; k++) hi *= 2;
    if (!(H(x, sign * hi) > 0)) return NaN;
    for (let k = 0; k < 60; k++) { const m = (lo + hi) / 2; if (H(x, sign * m) <= 0) lo = m; else hi = m; }
    return sign * lo;
  };
  const upper = [], lower = [];
  for (let k = 0; k <= BOUNDARY_POINTS; k++) {
    // Points crowd at the ends, where the edge turns.
    const x = xl + ((xr - xl) * (1 - Math.cos((Math.PI * k) / BOUNDARY_POINTS))) / 2;
    upper.push([x, pAt(x, 1)]); lower.push([x, pAt(x, -1)]);
  }
  const curve = [...upper, ...lower.reverse()].filter(([, p]) => Number.isFinite(p));
  let box = null;
  for (const [x, p] of curve) box = grow(box, x, p);
  return box ? { curve, box: pad(box, 0.06) } : null;
}

// A colour of its own for each orbit: hues a golden angle apart.
function orbitColour(k) { return `hsl(${(k * 137.508) % 360}, 70%, 40%)`; }

function drawSection() {
  if (!hasSection()) return;
  const { ctx, w, h } = surface("section");
  const x = app.lab.crossings(), orbits = app.lab.crossingOrbits(), n = app.lab.state().length;
  if (!app.sectionBox) {
    const r = Math.sqrt(2 * Math.abs(app.lab.energy0())) * 1.2 || 1;
    app.sectionBox = { x0: -r, x1: r, y0: -r, y1: r };
  }
  // Without a closed edge the view widens to take in crossings outside it.
  if (!app.boundary) for (let i = 0; i < x.length; i += n) app.sectionBox = grow(app.sectionBox, x[i], x[i + 2]);
  const v = plotView(w, h, app.sectionBox, false);
  app.sectionView = v;
  const labels = stateAxisLabels();
  drawAxes("section", ctx, v, labels[0], labels[2]);
  clip(ctx, v);
  if (app.boundary) {
    ctx.strokeStyle = "#444"; ctx.lineWidth = 1.5; ctx.beginPath();
    app.boundary.curve.forEach(([bx, bp], k) => (k ? ctx.lineTo(v.X(bx), v.Y(bp)) : ctx.moveTo(v.X(bx), v.Y(bp))));
    ctx.closePath(); ctx.stroke();
  }
  // One path per run of crossings of one orbit (they come in orbit order).
  let i = 0;
  const count = orbits.length, ids = [];
  while (i < count) {
    const o = orbits[i];
    if (!ids.includes(o)) ids.push(o);
    ctx.fillStyle = orbitColour(ids.indexOf(o));
    ctx.beginPath();
    for (; i < count && orbits[i] === o; i++) ctx.rect(v.X(x[i * n]) - 2.25, v.Y(x[i * n + 2]) - 2.25, 4.5, 4.5);
    ctx.fill();
  }
  ctx.restore();
  $("section-energy").textContent = app.lab.energy0().toPrecision(6);
  $("section-count").textContent = `${ids.length} orbit${ids.length === 1 ? "" : "s"}, ${count} crossings`;
}

function draw() {
  // The readout names seconds only: "4.50 time" would read as a word.
  const tu = timeUnit() === "s" ? "s" : "";
  $("time").textContent = `${app.lab.time().toFixed(2)}${tu ? ` ${tu}` : ""}`;
  $("energy-error").textContent = scientific(app.lab.energyError(), 3);
  drawScene(); drawPhase(); if (!$("energy-figure").hidden) drawEnergy(); drawSection();
}

// ---------- direct manipulation ----------

function canvasPoint(c, ev) {
  const r = c.getBoundingClientRect();
  return [ev.clientX - r.left, ev.clientY - r.top];
}

// Into (−π, π].
function wrapAngle(x) { return x - TAU * Math.ceil((x - Math.PI) / TAU); }

// The coordinates that are angles: a turn of 2π leaves every drawn position where it was.
function angleCoordinates(q) {
  const p0 = app.lab.positionsOf(q);
  return q.map((_, j) => {
    const qq = Array.from(q); qq[j] += TAU;
    const p = app.lab.positionsOf(qq);
    // 1e-9 of the size: a turn of 2π costs a few roundings of sin and cos.
    return p.length === p0.length && p.every((x, i) => Math.abs(x - p0[i]) <= 1e-9 * (1 + Math.abs(p0[i])));
  });
}

// The pose whose dragged body is nearest the pointer: Levenberg–Marquardt on |positions(q)
// [body] − target|² with finite-difference Jacobians, from the current pose, each step
// accepted only if it brings the body nearer, angles wrapped into (−π, π]. Within reach the
// body lands on the pointer; out of reach, at the nearest reachable point (arms stretched
// towards the pointer), never at a wound-up or bent pose.
// `where(q)` is the dragged point of pose q, in the target's coordinates.
function solveConfiguration(q0, where, target, angles) {
  let q = Array.from(q0).map((x, j) => (angles[j] ? wrapAngle(x) : x));
  const n = q.length;
  const residual = (qq) => {
    const [x, y] = where(qq);
    return [x - target[0], y - target[1]];
  };
  const cost = (r) => r[0] * r[0] + r[1] * r[1];
  let r = residual(q), c = cost(r), mu = 1e-3;
  for (let it = 0; it < 100 && c > 1e-26; it++) {
    const J = [];
    for (let j = 0; j < n; j++) {
      const hh = 1e-7 * Math.max(1, Math.abs(q[j]));
      const qq = q.slice(); qq[j] += hh;
      const rr = residual(qq);
      J.push(rr.map((v, k) => (v - r[k]) / hh));
    }
    const JTJ = Array.from({ length: n }, (_, a) => Array.from({ length: n }, (_, b) => J[a][0] * J[b][0] + J[a][1] * J[b][1]));
    const g = Array.from({ length: n }, (_, a) => -(J[a][0] * r[0] + J[a][1] * r[1]));
    let improved = false;
    for (let tries = 0; tries < 30 && !improved; tries++) {
      const A = JTJ.map((row, a) => row.map((x, b) => x + (a === b ? mu * (1 + JTJ[a][a]) : 0)));
      const dq = solveLinear(A, g.slice());
      if (!dq) { mu *= 10; continue; }
      const qn = q.map((x, j) => (angles[j] ? wrapAngle(x + dq[j]) : x + dq[j]));
      const rn = residual(qn), cn = cost(rn);
      if (cn < c) { q = qn; r = rn; mu = Math.max(mu / 5, 1e-12); improved = c - cn > 1e-30; c = cn; if (!improved) break; }
      else mu *= 5;
    }
    if (!improved) break;
  }
  return q;
}

function solveLinear(A, b) {
  const n = b.length;
  for (let i = 0; i < n; i++) {
    let p = i;
    for (let k = i + 1; k < n; k++) if (Math.abs(A[k][i]) > Math.abs(A[p][i])) p = k;
    [A[i], A[p]] = [A[p], A[i]]; [b[i], b[p]] = [b[p], b[i]];
    if (!(Math.abs(A[i][i]) > 1e-300)) return null;
    for (let k = i + 1; k < n; k++) {
      const f = A[k][i] / A[i][i];
      for (let j = i; j < n; j++) A[k][j] -= f * A[i][j];
      b[k] -= f * b[i];
    }
  }
  const x = new Array(n).fill(0);
  for (let i = n - 1; i >= 0; i--) {
    let s = b[i];
    for (let j = i + 1; j < n; j++) s -= A[i][j] * x[j];
    x[i] = s / A[i][i];
  }
  return x.every(Number.isFinite) ? x : null;
}

// A chain's masses are dragged along their line, one at a time: in the strip of masses on
// springs sideways, in the displacement plot up and down, the one mass on a spring sideways.
// The displacement is clamped to the drawing's scale fixed when the drag starts (1.1 times the
// run's largest displacement: the plot's edge; in the strip 0.44 of the spacing, so neighbours
// never cross). The dragged mass is let go at rest; the others keep their momenta.
const CHAIN_REACH = 1.1;
function chainHandles() {
  const g = app.chainGeom, s = app.lab.state(), n = ndof(), out = [];
  if (!g) return out;
  for (let i = 0; i < n; i++) {
    if (g.one) { out.push({ i, how: "one", x: g.v.X(s[0]), y: g.v.Y(0) }); break; }
    out.push({ i, how: "plot", x: g.v.X(i + 1), y: g.top + g.v.Y(s[i]) });
    if (g.strip && i >= g.first && i < g.first + g.count) out.push({ i, how: "strip", x: g.x0 + g.gap * (i - g.first + 1) + g.gain * s[i], y: g.y });
  }
  return out;
}
function chainDisplacement(d, px, py) {
  const g = app.chainGeom, i = d.i;
  const x = d.how === "plot" ? g.v.inv(px, py - g.top)[1] : d.how === "one" ? g.v.inv(px, py)[0] : (px - g.x0 - g.gap * (i - g.first + 1)) / g.gain;
  return Math.max(-CHAIN_REACH * d.amp, Math.min(CHAIN_REACH * d.amp, x));
}

// A top is dragged by its axis: the pointer on the drawn top picks the direction of the
// symmetry axis (tilt θ and azimuth φ; the spin angle ψ stays), the point of the sphere of the
// axis's length whose projection is under the pointer (out of the sphere's outline, the
// nearest point of the outline). θ is kept TOP_TILT away from the vertical both ways, where the
// Euler angles lock. The top is let go with its spin ψ̇ and no precession or nutation rate.
const TOP_TILT = 0.02;
function topPoint(q) {
  const [x, y] = project3(app.lab.positionsOf(q), app.topLength);
  return [x, y];
}
function topAngles(q) {
  const sym = presentation().symbols ?? [], ith = sym.indexOf("\\theta"), iphi = sym.indexOf("\\phi");
  if (ith < 0 || iphi < 0) return q;
  // The same axis with θ ≥ 0: (φ, −θ) is (φ + π, θ).
  if (q[ith] < 0) { q[ith] = -q[ith]; q[iphi] = wrapAngle(q[iphi] + Math.PI); }
  q[ith] = Math.max(TOP_TILT, Math.min(Math.PI - TOP_TILT, q[ith]));
  return q;
}

function onScenePointer(ev) {
  const c = $("scene"), v = app.sceneView, pos = app.lab.positions(), k = kind();
  if (!draggable()) return;
  const [px, py] = canvasPoint(c, ev);
  if (k === "chain" || k === "sites") return onChainPointer(ev, c, px, py);
  if (!v) return;
  if (k === "top") return onTopPointer(ev, c, px, py, v);
  if (ev.type === "pointerdown") {
    const bodies = bodiesOf(pos);
    let best = -1, bestD = 30;
    bodies.forEach(([x, y], i) => {
      const bx = kind() === "hoop" ? x * Math.cos(param("omega") * app.lab.time()) : x;
      const d = Math.hypot(v.X(bx) - px, v.Y(y) - py);
      if (d < bestD) { best = i; bestD = d; }
    });
    if (best < 0) return;
    c.setPointerCapture?.(ev.pointerId);
    const n = ndof();
    app.drag = { body: best, angles: angleCoordinates(Array.from(app.lab.state().slice(0, n))) };
    ev.preventDefault();
  } else if (ev.type === "pointermove" && app.drag) {
    const s = app.lab.state(), n = ndof(), target = v.inv(px, py);
    // The hoop is drawn turned by Ωt: the bead's place on it is the pointer's x over cos Ωt.
    if (kind() === "hoop") { const c = Math.cos(param("omega") * app.lab.time()); if (Math.abs(c) > 0.2) target[0] /= c; }
    const body = app.drag.body;
    const q = solveConfiguration(s.slice(0, n), (qq) => bodiesOf(app.lab.positionsOf(qq))[body], target, app.drag.angles);
    // A pendulum is let go from rest; an orbiting body keeps its momentum.
    const rest = family() === "lagrangian" ? new Array(n).fill(0) : Array.from(s.slice(n));
    try { app.lab.setState([...q, ...rest]); message(""); } catch (e) { message(e.message); }
    // The view stays put while dragging, so the body stays under the pointer.
    clearViews();
    draw();
  } else if ((ev.type === "pointerup" || ev.type === "pointercancel") && app.drag) {
    endDrag();
  }
}

// The end of a drag: the new run's views, in the frames the drag was made in (grown to take
// in the new run).
function endDrag() {
  app.drag = null;
  startViews(null, true);
  draw();
}

function onChainPointer(ev, c, px, py) {
  if (ev.type === "pointerdown") {
    let best = null, bestD = 30;
    for (const hd of chainHandles()) {
      const d = Math.hypot(hd.x - px, hd.y - py);
      if (d < bestD) { best = hd; bestD = d; }
    }
    if (!best) return;
    c.setPointerCapture?.(ev.pointerId);
    app.drag = { chain: true, i: best.i, how: best.how, amp: app.chainGeom.amp };
    ev.preventDefault();
  } else if (ev.type === "pointermove" && app.drag?.chain) {
    const s = Array.from(app.lab.state()), n = ndof();
    s[app.drag.i] = chainDisplacement(app.drag, px, py);
    if (s.length === 2 * n) s[n + app.drag.i] = 0;
    try { app.lab.setState(s); message(""); } catch (e) { message(e.message); }
    clearViews();
    draw();
  } else if ((ev.type === "pointerup" || ev.type === "pointercancel") && app.drag) {
    endDrag();
  }
}

function onTopPointer(ev, c, px, py, v) {
  if (ev.type === "pointerdown") {
    const [x, y] = project3(Array.from(app.lab.positions()), app.topLength);
    if (Math.hypot(v.X(x) - px, v.Y(y) - py) > 30) return;
    c.setPointerCapture?.(ev.pointerId);
    app.drag = { top: true, angles: angleCoordinates(Array.from(app.lab.state().slice(0, ndof()))) };
    ev.preventDefault();
  } else if (ev.type === "pointermove" && app.drag?.top) {
    const s = Array.from(app.lab.state()), n = ndof(), sym = presentation().symbols ?? [];
    const q = topAngles(solveConfiguration(s.slice(0, n), topPoint, v.inv(px, py), app.drag.angles));
    // Let go with its spin: ψ̇ kept, the other rates zero.
    const rates = s.slice(n).map((x, j) => (sym[j] === "\\psi" ? x : 0));
    try { app.lab.setState([...q, ...rates]); message(""); } catch (e) { message(e.message); }
    clearViews();
    draw();
  } else if ((ev.type === "pointerup" || ev.type === "pointercancel") && app.drag) {
    endDrag();
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
  // The section's orbits accumulate, so only the other views start again (in their frames).
  startViews(null, true);
  draw();
}

// ---------- share link and data ----------

function shareHash() {
  const h = new URLSearchParams();
  h.set("system", app.entry.name);
  h.set("method", $("method").value);
  h.set("dt", $("dt").value);
  if (isAdaptive($("method").value)) h.set("tol", $("tol").value);
  h.set("steps", $("speed").value);
  h.set("params", JSON.stringify(app.params));
  if ($("timelapse").checked) h.set("timelapse", "1");
  // Shortest round-trip decimal of each number: the state comes back bit for bit.
  h.set("state", Array.from(app.lab.initialState()).map(String).join(","));
  return `#${h.toString()}`;
}

function quoted(text) {
  const t = String(text);
  return `“${t.length > 40 ? `${t.slice(0, 40)}…` : t}”`;
}

// Opens a share link. Every field is checked; a refused one is named in one line and left
// at its default. The linked system opens if it exists (else the default, said so).
function applyHash(hash) {
  let h;
  try { h = new URLSearchParams(hash.replace(/^#/, "")); } catch { h = new URLSearchParams(); }
  const refused = [];
  const fallback = app.catalogue.systems.find((s) => s.name === DEFAULT_SYSTEM) ?? app.catalogue.systems[0];
  let entry = app.catalogue.systems.find((s) => s.name === h.get("system"));
  if (!entry) {
    if (h.has("system")) refused.push(`no system called ${quoted(h.get("system"))}, so ${systemTitle(fallback).toLowerCase()} opened`);
    entry = fallback;
  }
  // The method first: some parameter values run only with some methods (a projectile with
  // drag refuses the splitting methods), so the parameters are tried with the link's method.
  const offered = entry.methods;
  let method = h.get("method");
  if (method !== null && !offered.includes(method)) {
    refused.push(`method ${quoted(method)} (not one this system runs in the lab)`);
    method = null;
  }
  // Parameters: all together if the system builds with them (a vector and the length that
  // goes with it only build together); otherwise kept one by one, each only if the system
  // builds with it, the others refused by name.
  let params = {};
  const raw = h.get("params");
  if (raw !== null && raw !== "") {
    let parsed;
    try { parsed = JSON.parse(raw); } catch { refused.push("the parameters (not readable)"); }
    if (parsed !== undefined && (parsed === null || typeof parsed !== "object" || Array.isArray(parsed))) {
      refused.push("the parameters (not a set of named values)");
    } else if (parsed !== undefined) {
      let together = false;
      try { app.core.build(entry.name, parsed, method).free(); params = { ...parsed }; together = true; } catch { /* one by one below */ }
      if (!together) {
        for (const [k, val] of Object.entries(parsed)) {
          const trial = { ...params, [k]: val };
          try { app.core.build(entry.name, trial, method).free(); params = trial; } catch (e) { refused.push(`${quoted(k)}: ${e.message}`); }
        }
      }
    }
  }
  selectSystem(entry.name, params, false);
  if (method !== null) fillMethods(method);
  const dtText = h.get("dt");
  if (dtText !== null) {
    const dt = Number(dtText);
    if (dtText.trim() !== "" && Number.isFinite(dt) && dt >= MIN_DT && dt <= MAX_DT) {
      if (![...$("dt").options].some((o) => Number(o.value) === dt)) $("dt").append(new Option(String(dt), String(dt)));
      $("dt").value = String(dt);
    } else refused.push(`dt = ${quoted(dtText)} (a step from ${MIN_DT} to ${MAX_DT})`);
  }
  // The tolerance of an adaptive method (a link from before adaptive methods has none: the
  // default).
  const tolText = h.get("tol");
  if (tolText !== null) {
    const tol = Number(tolText);
    if (!isAdaptive($("method").value)) {
      refused.push(`tol = ${quoted(tolText)} (${methodTitle($("method").value)} takes a step, not a tolerance)`);
    } else if (tolText.trim() !== "" && Number.isFinite(tol) && tol >= MIN_TOL && tol <= MAX_TOL) {
      if (![...$("tol").options].some((o) => Number(o.value) === tol)) $("tol").append(new Option(String(tol), String(tol)));
      $("tol").value = String(tol);
    } else refused.push(`tol = ${quoted(tolText)} (a tolerance from ${scientific(MIN_TOL)} to ${scientific(MAX_TOL)})`);
  }
  describeMethod(); // the facts line shows the link's step and the order at its tolerance
  const stepsText = h.get("steps");
  if (stepsText !== null) {
    const n = Number(stepsText), max = Number($("speed").max);
    if (Number.isInteger(n) && n >= 1 && n <= max) { $("speed").value = n; $("speed-out").textContent = n; }
    else refused.push(`steps = ${quoted(stepsText)} (a whole number from 1 to ${max})`);
  }
  // A time-lapse link (the box ticked, or, from before the link said so, the time-lapse's own
  // step and steps a frame) opens with the box ticked and its note; its dt and steps stay the
  // link's.
  const tl = timeLapse(entry);
  if (tl && (h.get("timelapse") === "1" || (Number(dtText) === tl.dt && Number(stepsText) === tl.steps))) {
    $("timelapse").checked = true;
    $("step-note").textContent = tl.note;
  }
  let state = null;
  const stateText = h.get("state");
  if (stateText !== null && stateText !== "") {
    const values = stateText.split(",").map((x) => (x.trim() === "" ? NaN : Number(x)));
    if (!values.every(Number.isFinite)) refused.push(`the start (${quoted(stateText)} holds a value that is not a finite number)`);
    else state = values;
  }
  if (!rebuild(state, true)) {
    refused.push(`the start (${$("message").textContent})`);
    rebuild(null, true);
  }
  message(refused.length ? `From the link, refused: ${refused.join("; ")}.` : "");
  return refused.length === 0;
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

// The run as JSON: setup, the recorded rows and, with a section, every crossing with the
// number of the orbit it belongs to.
function exportData() {
  const { columns, rows } = runData();
  const out = {
    system: app.entry.name, params: app.params, method: $("method").value, dt: Number($("dt").value),
    initial_state: Array.from(app.lab.initialState()), columns, rows,
  };
  // An adaptive method's run is set by its tolerance (rtol = atol); dt is its output spacing.
  if (isAdaptive(out.method)) out.tol = app.lab.tolerance();
  if (hasSection()) {
    const x = Array.from(app.lab.crossings()), o = Array.from(app.lab.crossingOrbits()), n = app.lab.state().length;
    out.section = {
      coordinate: 1, value: 0, energy: app.lab.energy0(), columns: stateLabels(),
      crossings: o.map((orbit, i) => ({ orbit, state: x.slice(i * n, (i + 1) * n) })),
    };
  }
  return out;
}

// ---------- wiring ----------

function selectSystem(name, params = {}, build = true) {
  app.entry = app.catalogue.systems.find((s) => s.name === name);
  // The last chain's drawing geometry (its drag handles) goes with it.
  app.chainGeom = null;
  $("system").value = name;
  app.params = { ...params };
  // A dimensionless system (no unit of time in the catalogue) says so once, here: its axes
  // carry bare symbols.
  const scaled = app.entry.presentation.time_unit === "" ? " All quantities are in dimensionless units." : "";
  setRuns($("caption"), peopleRuns(`${app.entry.summary_text}.${app.entry.note_text ? ` ${app.entry.note_text[0].toUpperCase()}${app.entry.note_text.slice(1)}.` : ""}${scaled}`));
  // The physics paragraph: the gallery's text for this system, from the catalogue JSON.
  setRuns($("physics"), peopleRuns(app.entry.physics_text ?? app.entry.physics ?? ""));
  $("about").hidden = !app.entry.physics;
  fillParams();
  setControlValues();
  // A new system starts from its own default method (the catalogue's) and the lab's step.
  const step = stepDefaults(app.entry);
  fillMethods(step?.method ?? null);
  setStep(step?.dt ?? DEFAULT_DT, step?.steps ?? DEFAULT_STEPS);
  $("tol").value = String(DEFAULT_TOL);
  $("step-note").textContent = step?.note ?? "";
  $("timelapse-choice").hidden = !timeLapse(app.entry);
  // A reduced model whose `energy` is dissipated or is no energy has no energy error to show.
  $("energy-figure").hidden = !app.entry.presentation.energy_conserved;
  $("phase").closest("figure").classList.toggle("wide", !app.entry.presentation.energy_conserved);
  $("timelapse").checked = false;
  if (build) rebuild();
}

// The time-lapse on or off: its step and steps a frame, or the system's own; the run restarts.
function setTimeLapse(on) {
  const tl = timeLapse(app.entry), step = stepDefaults(app.entry);
  $("timelapse").checked = on && !!tl;
  if (on && tl) setStep(tl.dt, tl.steps); else setStep(step?.dt ?? DEFAULT_DT, step?.steps ?? DEFAULT_STEPS);
  $("step-note").textContent = (on ? tl?.note : step?.note) ?? "";
  restartRun();
}

function setStep(dt, steps) {
  if (![...$("dt").options].some((o) => Number(o.value) === dt)) $("dt").append(new Option(String(dt), String(dt)));
  $("dt").value = String(dt);
  $("speed").value = steps;
  $("speed-out").textContent = steps;
}

function restartRun() { app.lab.reset(); startViews(null, true); draw(); }

async function main() {
  const bytes = await (await fetch("physicskit_wasm.wasm")).arrayBuffer();
  app.core = await load(bytes);
  app.catalogue = app.core.catalogue();
  fillSystems();
  $("dt").replaceChildren(...DTS.map((d) => new Option(String(d), String(d))));
  $("dt").value = String(DEFAULT_DT);
  addToleranceControl();
  $("speed").value = DEFAULT_STEPS;
  $("speed-out").textContent = DEFAULT_STEPS;
  $("system").onchange = () => selectSystem($("system").value);
  $("method").onchange = () => {
    describeMethod();
    try { app.lab.setTolerance(tolerance()); app.lab.setMethod($("method").value); restartRun(); } catch (e) { message(e.message); }
  };
  $("dt").onchange = () => { describeMethod(); restartRun(); };
  $("tol").onchange = () => {
    describeMethod();
    try { app.lab.setTolerance(tolerance()); restartRun(); } catch (e) { message(e.message); }
  };
  $("timelapse").onchange = () => setTimeLapse($("timelapse").checked);
  $("speed").oninput = () => { $("speed-out").textContent = $("speed").value; };
  $("run").onclick = () => setRunning(!app.running);
  $("step").onclick = () => { setRunning(false); frame(); draw(); };
  $("reset").onclick = () => restartRun();
  $("share").onclick = async () => {
    const url = `${location.href.split("#")[0]}${shareHash()}`;
    history.replaceState(null, "", url);
    try { await navigator.clipboard.writeText(url); message("Link copied (also in the address bar)."); } catch { message("Link in the address bar."); }
  };
  $("csv").onclick = () => {
    const { columns, rows } = runData();
    download(`${app.entry.name}.csv`, [columns.join(","), ...rows.map((r) => r.join(","))].join("\n") + "\n", "text/csv");
  };
  $("json").onclick = () => download(`${app.entry.name}.json`, JSON.stringify(exportData()), "application/json");
  $("large").onchange = () => { document.body.classList.toggle("large", $("large").checked); draw(); };
  $("phase-x").onchange = $("phase-y").onchange = () => { app.phase = []; app.phaseBox = null; app.phaseKeep = null; sample(); draw(); };
  $("section-clear").onclick = () => { app.lab.clearCrossings(); draw(); };
  $("section-on").onchange = () => rebuild(Array.from(app.lab.initialState()));
  for (const t of ["pointerdown", "pointermove", "pointerup", "pointercancel"]) $("scene").addEventListener(t, onScenePointer);
  $("section").addEventListener("click", onSectionClick);
  // Space runs and pauses, unless a control that takes typing or space has the focus.
  document.addEventListener("keydown", (ev) => {
    const tag = ev.target?.tagName;
    if (ev.code === "Space" && !["INPUT", "SELECT", "TEXTAREA", "BUTTON", "SUMMARY"].includes(tag)) {
      ev.preventDefault();
      setRunning(!app.running);
    }
  });
  new ResizeObserver(() => { if (app.lab) draw(); }).observe($("views"));
  if (location.hash) applyHash(location.hash);
  else selectSystem((app.catalogue.systems.find((s) => s.name === DEFAULT_SYSTEM) ?? app.catalogue.systems[0]).name);
  // The page opens running.
  setRunning(true);
  requestAnimationFrame(loop);
}

// For the browser test and the benchmark: the page's own state and a way to step it.
window.physicskitLab = {
  app,
  ready: main().catch((e) => { message(`Could not start: ${e.message}`); throw e; }),
  select: (name) => { setRunning(false); selectSystem(name); },
  pause: () => setRunning(false),
  restart: () => { setRunning(false); restartRun(); },
  setStep: (dt, steps) => setStep(dt, steps),
  setTimeLapse: (on) => { setRunning(false); setTimeLapse(on); },
  runFrames: (n) => { setRunning(false); for (let i = 0; i < n; i++) if (!frame()) return false; draw(); return true; },
  shareHash: () => shareHash(),
  openHash: (hash) => { setRunning(false); return applyHash(hash); },
  exportJson: () => JSON.parse(JSON.stringify(exportData())),
  ticks: () => JSON.parse(JSON.stringify(app.ticks)),
  tickLabels: (lo, hi, count) => { const t = tickValues(lo, hi, count); return t.values.map((x) => tickText(x, t.step)); },
  bodiesOnScreen: () => {
    const c = $("scene"), r = c.getBoundingClientRect(), v = app.sceneView;
    return bodiesOf(app.lab.positions()).map(([x, y]) => [r.left + v.X(x), r.top + v.Y(y)]);
  },
  // The grab points of a chain's masses ({i, how, x, y}) or a top's axis tip, on the screen.
  handlesOnScreen: () => {
    const r = $("scene").getBoundingClientRect();
    if (kind() === "top") {
      const [x, y] = project3(Array.from(app.lab.positions()), app.topLength);
      return [{ i: 0, how: "tip", x: r.left + app.sceneView.X(x), y: r.top + app.sceneView.Y(y) }];
    }
    if (kind() !== "chain" && kind() !== "sites") return [];
    return chainHandles().map((hd) => ({ ...hd, x: r.left + hd.x, y: r.top + hd.y }));
  },
  sceneAt: (clientX, clientY) => {
    const r = $("scene").getBoundingClientRect();
    return app.sceneView.inv(clientX - r.left, clientY - r.top);
  },
  sectionToScreen: (x, px) => {
    const r = $("section").getBoundingClientRect(), v = app.sectionView;
    return [r.left + v.X(x), r.top + v.Y(px)];
  },
};
