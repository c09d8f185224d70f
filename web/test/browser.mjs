// The lab in real headless Chromium (Debian's /usr/bin/chromium, driven by playwright-core;
// no browser download). For every catalogue system it loads the page, runs 4 frames of the
// default setup (default method, dt = 1e-3, 25 steps a frame: the native reference run of
// crates/physicskit-wasm/src/bin/lab_reference.rs) and checks
//   - the energy-error readout against the native run (the text, and the number behind it
//     within the wasm/native bound of node_compare.mjs);
//   - the scene canvas is not blank and changes between frames;
//   - the physics paragraph shown is the catalogue's `physics_text` (hidden when none);
//   - axes on every canvas shown (the tick labels the page drew, which it exposes);
//   - no code in the page's text (a denylist: `::`, `--`, `^`, `thetadot`, "as in the spec",
//     a symbol left as words or with a bare `_` index);
// then: every axis of every system says its unit, as "θ₁ (rad)", or a ratio ("x / l"), or
// (a system the catalogue declares dimensionless) a bare symbol;
// the pendulum swarm's fixed view of where it can reach and its close-up; names of arrows off
// every arrow and each other (the tops); a projectile's frame kept and grown, never shrunk,
// by drags and Reset; every chain of rods dragged by its last bob;
// then: a share link round trip (a dragged start, reopened in a new page, runs to the same
// bits), hostile share links (each opens a valid page and names what it refused), a drag of
// the double pendulum's lower bob within reach and one far out of reach (a reachable pose,
// angles in (−π, π]), three orbits launched on the Hénon–Heiles section (the crossings of all
// three stay, read from the JSON export), Euler's disk ending at its collapse with words, not
// an error, Foucault's swing plane turned by the closed form in time-lapse, the keyboard, the page at 390 px wide (no sideways
// scroll, the scene and Run on the first screen, a chain's strip of masses readable, a floor's
// axis names drawn and clear of its body), and no console errors; a bad method name
// given to the module's build (unknown, HTML, adaptive, refused by the setup) is refused by
// name and the module runs on. Screenshots of every system, desktop and phone, running and
// (every draggable one) after a drag, go to the given directory.
//
// With a rendered gallery's directory (`physicskit gallery --quick --out DIR`), every one of
// its "Open in the lab" links is opened too: nothing refused, the system, method, step and
// parameters it names.
//
//   node web/test/browser.mjs SITE_DIR NATIVE_OUTPUT SCREENSHOT_DIR [GALLERY_DIR]
import { readFileSync, mkdirSync } from "node:fs";
import { join } from "node:path";
import { serve, launch, checks } from "./harness.mjs";

const [site, nativeFile, shots, galleryDir] = process.argv.slice(2);
mkdirSync(shots, { recursive: true });
const native = new Map(readFileSync(nativeFile, "utf8").trim().split("\n")
  .map((l) => JSON.parse(l)).map((r) => [`${r.system} ${r.method}`, r]));
// The page's readout as a physicist writes it (4.263×10⁻¹⁴, −2.500×10³) back in JavaScript's
// notation (4.263e-14, -2.500e+3); any other text as it is.
function readExponent(text) {
  const m = /^(−?\d\.\d+)×10(⁻?[⁰¹²³⁴⁵⁶⁷⁸⁹]+)$/.exec(text);
  if (!m) return text;
  const exp = [...m[2]].map((c) => (c === "⁻" ? "-" : String("⁰¹²³⁴⁵⁶⁷⁸⁹".indexOf(c)))).join("");
  return `${m[1].replace("−", "-")}e${exp.startsWith("-") ? exp : `+${exp}`}`;
}
const num = (hex) => new DataView(new BigUint64Array([BigInt(`0x${hex}`)]).buffer).getFloat64(0, true);

const { server, url } = await serve(site);
const browser = await launch();
const { failures, errors, fail, open } = checks(browser, url);

// Non-white pixels of the scene, and a digest of its pixels, read in the page.
const sceneInk = (page) => page.evaluate(() => {
  const c = document.getElementById("scene");
  const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
  let ink = 0, hash = 0;
  for (let i = 0; i < d.length; i += 4) {
    if (d[i] < 250 || d[i + 1] < 250 || d[i + 2] < 250) ink++;
    hash = (hash * 31 + d[i] + 7 * d[i + 1] + 13 * d[i + 2]) | 0;
  }
  return { ink, hash };
});

const page = await open();
// Tick labels beyond fixed decimals (a step below 10⁻⁶, a value of 10⁵ or more) read as powers
// of ten, 2×10⁻⁷ and 1.5×10⁵ (never 2.0e−7), distinct, and back to the tick values they name.
for (const [lo, hi] of [[0, 3e-7], [-2e-8, 2e-8], [1e5, 3e5], [-4e6, 1e6], [1.2e-9, 1.9e-9]]) {
  const labels = await page.evaluate(([a, b]) => window.physicskitLab.tickLabels(a, b, 5), [lo, hi]);
  const values = labels.map((t) => (t === "0" ? 0 : Number(readExponent(t.startsWith("10") ? `1.0×${t}` : t.replace(/^(−?\d)×/, "$1.0×")))));
  if (labels.length < 2 || new Set(labels).size !== labels.length || labels.some((t) => /e/.test(t))
      || values.some((v, i) => !Number.isFinite(v) || v < lo - (hi - lo) * 1e-9 || v > hi + (hi - lo) * 1e-9 || (i > 0 && v <= values[i - 1]))) {
    fail(`tick labels on [${lo}, ${hi}]: ${JSON.stringify(labels)}`);
  }
}
const systems = await page.evaluate(() => window.physicskitLab.app.catalogue.systems.map((s) => [s.name, s.default_method]));
// Text a person should never meet in the page: code, flags, ASCII powers, notes to developers.
// Symbols left as words or with a bare index ("ω earth", "ω_c") are code-isms too.
const DENYLIST = ["::", "--", "->", "^", "thetadot", "as in the spec", "ω earth", "_"];
const pageText = (p) => p.evaluate(() => {
  const parts = [document.body.innerText];
  for (const o of document.querySelectorAll("option")) parts.push(o.textContent);
  for (const e of document.querySelectorAll("[aria-label], [title], [placeholder]")) {
    parts.push(e.getAttribute("aria-label") ?? "", e.getAttribute("title") ?? "", e.getAttribute("placeholder") ?? "");
  }
  for (const t of Object.values(window.physicskitLab.ticks())) parts.push(t.xLabel, t.yLabel, ...t.x, ...t.y);
  return parts.join("\n");
});
// Axes: every canvas shown has tick labels on both axes (a plot at least two a side).
async function checkAxes(p, name) {
  const { ticks, shown } = await p.evaluate(() => ({
    ticks: window.physicskitLab.ticks(),
    shown: [...document.querySelectorAll("canvas")].filter((c) => c.offsetParent !== null).map((c) => c.id),
  }));
  for (const id of shown) {
    const t = ticks[id], least = id === "scene" ? 1 : 2;
    // A scene along a line (one mass on a spring) has an x axis only.
    const yOk = t?.line || (t && t.y.length >= least && t.yLabel);
    if (!t || t.x.length < least || !yOk || !t.xLabel) fail(`${name}: no axes on the ${id} canvas (${JSON.stringify(t)})`);
  }
}
async function checkWords(p, name) {
  const text = await pageText(p);
  for (const bad of DENYLIST) {
    const at = text.indexOf(bad);
    if (at >= 0) fail(`${name}: the page shows ${JSON.stringify(bad)} in ${JSON.stringify(text.slice(Math.max(0, at - 40), at + 40))}`);
  }
}
const DRAGGABLE = [];
for (let [name, method] of systems) {
  // The native reference's setup (dt = 1e-3, 25 steps a frame), whatever the page's own
  // default step for this system.
  await page.evaluate((n) => { window.physicskitLab.select(n); window.physicskitLab.setStep(1e-3, 25); }, name);
  const before = await sceneInk(page);
  const ok = await page.evaluate(() => window.physicskitLab.runFrames(4));
  // The page runs the catalogue's default method, or the fixed-step one its pace names.
  method = await page.evaluate(() => document.getElementById("method").value);
  const after = await sceneInk(page);
  const readout = await page.locator("#energy-error").textContent();
  const exact = await page.evaluate(() => window.physicskitLab.app.lab.energyError());
  const ref = native.get(`${name} ${method}`);
  if (!ok || !ref || ref.error) { fail(`${name}: run failed or no native reference`); continue; }
  const want = num(ref.energy_error);
  // The readout shows 4 significant digits as a physicist writes them (4.263×10⁻¹⁴, 0 for
  // none); the number behind it must be the native one (bit for bit but for the libm-bound
  // systems, see node_compare.mjs: 1e-14 of the energy).
  if (readExponent(readout) !== (want === 0 ? "0" : want.toExponential(3))) fail(`${name}: readout ${readout}, native ${want.toExponential(3)}`);
  if (Math.abs(exact - want) > 1e-14) fail(`${name}: energy error ${exact} vs native ${want}`);
  // Non-blank: at least 200 inked pixels (a body of radius 10 alone has ~300; an empty
  // canvas with its axis labels ~100 at most).
  if (after.ink < 200) fail(`${name}: scene nearly blank (${after.ink} inked pixels)`);
  // A system at rest (the sine-Gordon chain's zero state) has nothing to move.
  const atRest = await page.evaluate(() => window.physicskitLab.app.lab.state().every((x) => x === 0));
  if (after.hash === before.hash && !atRest) fail(`${name}: scene did not change between frames`);
  // The physics paragraph shown is the catalogue's, with its powers as superscripts (the
  // gallery's text for the system, checked
  // against the rendered gallery in crates/physicskit-viz/tests/gallery.rs), shown only if any.
  const physicsText = await page.evaluate(() => window.physicskitLab.app.entry.physics_text);
  // As the page writes it: a method's name in words, and an index `_x` or `_{x}` lowered
  // (its `_` gone; the denylist checks none is left).
  const physics = physicsText && physicsText.replace(/\b([a-z]{2,})_([a-z]{2,})\b/g, "$1 $2").replace(/_\{([^{}]*)\}/g, "$1").replace(/_/g, "");
  const shown = await page.locator("#about").isVisible() ? await page.locator("#physics").textContent() : null;
  if (shown !== physics) fail(`${name}: physics paragraph ${JSON.stringify(shown)?.slice(0, 60)} vs catalogue ${JSON.stringify(physics)?.slice(0, 60)}`);
  await checkAxes(page, name);
  await checkWords(page, name);
  // Only a body that can be dragged is said to be: no caption of the others says "drag".
  const words = await page.evaluate(() => ({
    draggable: !document.getElementById("drag-hint").hidden,
    text: [...document.querySelectorAll("#views, #caption, #method-info")].map((e) => e.innerText).join("\n"),
  }));
  if (!words.draggable && /\bdrag/i.test(words.text)) fail(`${name}: cannot be dragged, yet the page says ${JSON.stringify(words.text.match(/.{0,40}\bdrag.{0,40}/i)?.[0])}`);
  console.log(`ok ${name} (${method}): energy error ${readout}, ${after.ink} inked pixels, axes, words`);
  // The page's own setup from here (its default step for the system), for the pictures.
  await page.evaluate((n) => window.physicskitLab.select(n), name);
  await page.evaluate(() => window.physicskitLab.runFrames(120));
  await page.screenshot({ path: join(shots, `${name}.png`), fullPage: true });
  if (await page.locator("#drag-hint").isVisible()) DRAGGABLE.push(name);
}

// Axis labels are the catalogue's: each system's `presentation` symbols (TeX, read here with a
// converter of this test's own for the symbols these systems use), dotted for velocities or
// p-subscripted for momenta, the initial-state parameters' units, and its unit of time.
{
  const TEX = { "\\theta": "θ", "\\phi": "φ", "\\psi": "ψ" };
  const SUBS = { 1: "₁", 2: "₂", 3: "₃", x: "ₓ" };
  const unicode = (tex) => tex.replace(/\\[a-z]+/g, (m) => TEX[m]).replace(/_\{?([0-9x])\}?/g, (_, c) => SUBS[c]);
  for (const name of ["double-pendulum", "henon-heiles", "heavy-top", "kepler", "foucault-pendulum"]) {
    const got = await page.evaluate((n) => {
      const L = window.physicskitLab;
      L.select(n); L.runFrames(2);
      return { ticks: L.ticks(), entry: L.app.entry, n: L.app.lab.state().length,
        ix: Number(document.getElementById("phase-x").value), iy: Number(document.getElementById("phase-y").value) };
    }, name);
    const { symbols, time_unit: tu } = got.entry.presentation;
    // The initial-state parameters' units, else the presentation's state units.
    const initial = got.entry.params.filter((p) => p.initial_state).map((p) => p.unit_text);
    const starts = initial.length ? initial : got.entry.presentation.state_units ?? [];
    const k = got.n / 2, dot = got.entry.family !== "hamiltonian";
    // A coordinate's symbol, and its velocity's (a dot over the letter, before the index) or
    // momentum's (p with the symbol as its index).
    const q = (i) => unicode(symbols[i]);
    const v = (i) => (dot ? unicode(symbols[i]).replace(/^(\p{L})/u, "$1\u0307") : `p${unicode(`_${symbols[i]}`)}`);
    const unit = (u, i) => { const parts = (u ?? "").split(/,\s*/); return parts.length === k ? parts[i] : parts[0]; };
    const withUnit = (s, u) => (u ? `${s} (${u})` : s);
    const want = (i) => (i < k ? withUnit(q(i), unit(starts[0], i)) : withUnit(v(i - k), unit(starts[1], i - k)));
    const t = got.ticks;
    if (t.phase.xLabel !== want(got.ix) || t.phase.yLabel !== want(got.iy)) fail(`labels ${name}: phase axes ${t.phase.xLabel} / ${t.phase.yLabel}, the catalogue says ${want(got.ix)} / ${want(got.iy)}`);
    const time = tu ? `t (${tu})` : "t";
    if (t.energy.xLabel !== time) fail(`labels ${name}: time axis ${t.energy.xLabel}, the catalogue's unit of time is ${JSON.stringify(tu)}`);
    if (t.section && name === "henon-heiles" && (t.section.xLabel !== want(0) || t.section.yLabel !== want(k))) fail(`labels ${name}: section axes ${t.section.xLabel} / ${t.section.yLabel}`);
    console.log(`ok labels ${name}: ${t.phase.xLabel}, ${t.phase.yLabel}; ${t.energy.xLabel}`);
  }
}

// Every axis says what it measures in: on every canvas shown, of every system (as it opens),
// each axis with tick labels is named "symbol (unit)", or a ratio ("x / l": lengths in units
// of a length of the system's own, as the catalogue's drawing says; "|E − E₀| / |E₀|"), or
// counts sites; a bare symbol only in a system the catalogue declares dimensionless (no unit
// of time), whose caption then says so.
{
  const bad = await page.evaluate((names) => {
    const L = window.physicskitLab, out = [];
    const unit = /^.+ \([^()]+\)$/u, ratio = /^.+ \/ .+$/u;
    for (const n of names) {
      L.select(n); L.runFrames(2);
      const t = L.ticks(), scaled = L.app.entry.presentation.time_unit === "";
      if (scaled && !/dimensionless units/.test(document.getElementById("caption").textContent)) out.push(`${n}: dimensionless, and the caption does not say so`);
      const shown = [...document.querySelectorAll("canvas")].filter((c) => c.offsetParent !== null).map((c) => c.id);
      for (const id of shown) {
        const axes = [["x", t[id]?.x, t[id]?.xLabel], ["y", t[id]?.y, t[id]?.yLabel], ["z", t[id]?.x, t[id]?.zLabel]];
        for (const [axis, ticks, text] of axes) {
          if (!ticks?.length || text === undefined) continue;
          if (unit.test(text) || ratio.test(text) || text === "site" || (scaled && text)) continue;
          out.push(`${n}: ${id} ${axis} axis ${JSON.stringify(text)}`);
        }
      }
    }
    return out;
  }, systems.map(([n]) => n));
  for (const b of bad) fail(`units: ${b}`);
  console.log(`ok units: every axis of every system says its unit, a ratio or (declared) no dimension${bad.length ? ` (but ${bad.length})` : ""}`);
}

// The pendulum swarm: the scene is the region the swarm can ever reach (each pendulum keeps its
// energy), fixed for the run; the phase panel a close-up that holds the whole swarm, filling at
// least half of it one way, and never zooms back in. Run over a full swing (the default swarm's
// period is about 6.7 s) and check it against the run itself: every member stays in the
// scene's view, and the swarm's own extent over the swing fills most of it (the view is not
// needlessly large).
{
  const r = await page.evaluate(() => {
    const L = window.physicskitLab, out = { boxes: new Set(), escaped: 0, zooms: [], filled: [], outside: 0 };
    L.select("pendulum-swarm");
    let seen = null;
    const wrap = (q) => q - 2 * Math.PI * Math.ceil((q - Math.PI) / (2 * Math.PI));
    for (let f = 0; f < 320; f++) {
      if (!L.runFrames(1)) return null;
      const s = L.app.lab.state(), n = s.length / 2, b = L.app.sceneView.box, c = L.app.closeView;
      out.boxes.add(JSON.stringify(b));
      for (let i = 0; i < n; i++) {
        const q = wrap(s[i]), p = s[n + i];
        if (q < b.x0 || q > b.x1 || p < b.y0 || p > b.y1) out.escaped++;
        seen = seen ? { x0: Math.min(seen.x0, q), x1: Math.max(seen.x1, q), y0: Math.min(seen.y0, p), y1: Math.max(seen.y1, p) } : { x0: q, x1: q, y0: p, y1: p };
      }
      const w = c.swarm, cb = c.box;
      if (w.x0 < cb.x0 || w.x1 > cb.x1 || w.y0 < cb.y0 || w.y1 > cb.y1) out.outside++;
      out.zooms.push(c.zoom);
      out.filled.push(Math.max((w.x1 - w.x0) / (cb.x1 - cb.x0), (w.y1 - w.y0) / (cb.y1 - cb.y0)));
      out.box = b;
    }
    out.seen = seen;
    out.boxes = out.boxes.size;
    out.shown = !document.getElementById("closeup-caption").hidden && document.getElementById("phase-choice").hidden;
    return out;
  });
  if (!r) fail("swarm: the run failed");
  else {
    if (r.boxes !== 1) fail(`swarm: the scene's view changed during the run (${r.boxes} views)`);
    if (r.escaped) fail(`swarm: ${r.escaped} member positions outside the scene's view`);
    // 0.75: the view is the reach with an 8% margin each side, and the swarm's own extent
    // over a swing comes within its box's width (0.05 rad) of the reach.
    const fx = (r.seen.x1 - r.seen.x0) / (r.box.x1 - r.box.x0), fy = (r.seen.y1 - r.seen.y0) / (r.box.y1 - r.box.y0);
    if (!(fx > 0.75 && fy > 0.75)) fail(`swarm: over a swing the swarm fills ${fx.toFixed(2)} × ${fy.toFixed(2)} of the scene's view`);
    if (r.outside) fail(`swarm: the close-up left the swarm out ${r.outside} times`);
    if (r.zooms.some((z, i) => i && z > r.zooms[i - 1])) fail(`swarm: the close-up zoomed back in (${r.zooms.join(", ")})`);
    // Half: the close-up's margin is 0.3 of the swarm's extent each side (1/1.6 of the panel)
    // until the magnification has to stop falling.
    if (!(r.filled[0] >= 0.5)) fail(`swarm: the swarm fills only ${r.filled[0]} of the close-up`);
    if (!r.shown) fail("swarm: the close-up's caption not shown, or the phase choice shown");
    console.log(`ok swarm: scene view fixed over ${r.zooms.length} frames, every member in it, a swing fills ${fx.toFixed(2)} × ${fy.toFixed(2)} of it; close-up ×${r.zooms[0].toPrecision(3)} → ×${r.zooms[r.zooms.length - 1].toPrecision(3)}, the swarm filling ${r.filled[0].toFixed(2)} of it at the start`);
  }
  await page.screenshot({ path: join(shots, "pendulum-swarm-swing.png"), fullPage: true });
}

// Names of arrows never sit on an arrow (theirs or another) or on each other: the Euler top's
// body axes e₁, e₂, e₃ and L, over many orientations, and the heavy top's L. Checked here by
// sampling points along each drawn segment (the page clips segments against boxes).
{
  const draws = await page.evaluate(() => {
    const L = window.physicskitLab, out = [];
    for (const [name, frames, every] of [["euler-top", 40, 15], ["heavy-top", 12, 20]]) {
      L.select(name);
      for (let k = 0; k < frames; k++) { L.runFrames(every); out.push({ name, labels: L.app.sceneLabels }); }
    }
    return out;
  });
  const inside = ([x, y], [l, t, r, b]) => x > l && x < r && y > t && y < b;
  let hits = 0, count = 0;
  for (const { name, labels } of draws) {
    for (const a of labels) {
      count++;
      for (const o of labels) {
        const [x0, y0, x1, y1] = o.seg;
        for (let k = 0; k <= 200; k++) {
          const u = k / 200;
          if (inside([x0 + u * (x1 - x0), y0 + u * (y1 - y0)], a.box)) { hits++; fail(`${name}: the name ${a.text} sits on the arrow of ${o.text}`); break; }
        }
        if (o !== a && a.box[0] < o.box[2] && o.box[0] < a.box[2] && a.box[1] < o.box[3] && o.box[1] < a.box[3]) { hits++; fail(`${name}: the names ${a.text} and ${o.text} overlap`); }
      }
    }
  }
  if (!count) fail("arrow names: none recorded");
  console.log(`ok arrow names: ${count} names over ${draws.length} drawings of the tops, none on an arrow or another name`);
}

// A floor's tick labels and axis names never sit under the body standing on it (the tops,
// Euler's disk, the rolling bodies): over a run, no label drawn meets the box of the body's
// drawing, each floor keeps labels on both edges, and every axis's name (and the heavy top's
// vertical, z) is among the labels drawn.
{
  const bad = await page.evaluate((names) => {
    const L = window.physicskitLab, out = [];
    for (const n of names) {
      L.select(n);
      if (!["top_axis", "contact_spiral", "rolling"].includes(L.app.entry.presentation.drawing.kind)) continue;
      for (let k = 0; k < 8; k++) {
        L.runFrames(15);
        const { avoid, drawn } = L.app.floorLabels, t = L.ticks().scene;
        for (const d of drawn) for (const a of avoid) if (d.box[0] < a[2] && a[0] < d.box[2] && d.box[1] < a[3] && a[1] < d.box[3]) out.push(`${n}: ${d.text} under the body`);
        if (!avoid.length || !t.x.length || !t.y.length) out.push(`${n}: floor ${JSON.stringify(t)}, body ${JSON.stringify(avoid)}`);
        for (const name of [t.xLabel, t.yLabel, t.zLabel]) if (name && !drawn.some((d) => d.text === name)) out.push(`${n}: the axis name ${name} not drawn`);
      }
    }
    return out;
  }, systems.map(([n]) => n));
  for (const b of [...new Set(bad)]) fail(`floor labels: ${b}`);
  console.log("ok floor labels: none under the tops, Euler's disk or the rolling bodies over their runs");
}

// After a drag the scene keeps its frame and grows to take in the new run, never shrinks: the
// projectile dragged while falling (it keeps its momentum, so its new flight is short) is drawn
// at the scale it had, and a drag that starts a longer flight widens the frame to hold it. Reset
// keeps it too.
{
  await page.evaluate(() => { const L = window.physicskitLab; L.select("projectile"); L.runFrames(95); });
  const view = () => page.evaluate(() => {
    const L = window.physicskitLab, v = L.app.sceneView, e = L.app.extent?.pos;
    return { box: { ...L.app.sceneBox }, scale: v.X(1) - v.X(0), flight: e && { ...e }, phase: L.app.phaseBox && { ...L.app.phaseBox } };
  });
  const dragBall = async (dx, dy) => {
    const [b] = await page.evaluate(() => window.physicskitLab.bodiesOnScreen());
    await page.mouse.move(b[0], b[1]); await page.mouse.down();
    await page.mouse.move(b[0] + dx, b[1] + dy, { steps: 4 }); await page.mouse.up();
    await page.evaluate(() => window.physicskitLab.runFrames(2));
  };
  const holds = (a, b) => a.x0 <= b.x0 && a.x1 >= b.x1 && a.y0 <= b.y0 && a.y1 >= b.y1;
  const before = await view();
  await dragBall(-40, 0);
  const short = await view();
  if (!holds(before.box, short.flight)) fail(`projectile drag: the new flight ${JSON.stringify(short.flight)} is not a short one inside the old frame`);
  if (JSON.stringify(short.box) !== JSON.stringify(before.box) || short.scale !== before.scale) fail(`projectile drag: the frame moved from ${JSON.stringify(before.box)} (${before.scale} px/m) to ${JSON.stringify(short.box)} (${short.scale} px/m)`);
  if (before.phase && short.phase && !holds(short.phase, before.phase)) fail("projectile drag: the phase panel's frame shrank");
  await page.screenshot({ path: join(shots, "projectile-dragged-short.png"), fullPage: true });
  // Up near the top of the frame: a longer flight, which the frame grows to hold.
  const top = await page.evaluate(() => { const v = window.physicskitLab.app.sceneView; return document.getElementById("scene").getBoundingClientRect().top + v.Y(0.85 * v.box.y1); });
  const [b0] = await page.evaluate(() => window.physicskitLab.bodiesOnScreen());
  await dragBall(0, top - b0[1]);
  const high = await view();
  if (!holds(high.box, short.box) || !holds(high.box, high.flight)) fail(`projectile drag up: frame ${JSON.stringify(high.box)}, the flight ${JSON.stringify(high.flight)}, the frame before ${JSON.stringify(short.box)}`);
  await page.evaluate(() => window.physicskitLab.restart());
  const reset = await view();
  if (JSON.stringify(reset.box) !== JSON.stringify(high.box)) fail("projectile: Reset changed the frame");
  console.log(`ok projectile drags: a short flight drawn in the frame it had (${before.scale.toFixed(2)} px/m), a higher start grows it to ${JSON.stringify(Object.values(high.box).map((x) => +x.toFixed(1)))}, Reset keeps it`);
  await page.screenshot({ path: join(shots, "projectile-dragged-high.png"), fullPage: true });
}

// The heavy top's angular momentum L: its vertical part is conserved (gravity's torque is
// horizontal), so the drawn L, read back, keeps L_z while L itself turns.
{
  const Ls = await page.evaluate(() => {
    const L = window.physicskitLab, out = [];
    L.select("heavy-top");
    for (let i = 0; i < 6; i++) { L.runFrames(40); out.push(L.app.topL); }
    return out;
  });
  const z0 = Ls[0]?.[2];
  // 1e-6 of |L|: the rate ė₃ is a central difference of 1e-6 s (error ~1e-12 |ė₃|), and the
  // run's own L_z drift at dt = 1e-3 over these 1.2 s is far smaller than that.
  const norm = Math.hypot(...(Ls[0] ?? [0, 0, 0]));
  if (!Ls.every((l) => l && Math.abs(l[2] - z0) <= 1e-6 * norm)) fail(`heavy top: L_z drifts: ${Ls.map((l) => l?.[2]).join(", ")}`);
  const turned = Math.hypot(Ls[5][0] - Ls[0][0], Ls[5][1] - Ls[0][1]);
  console.log(`ok heavy top: L_z = ${z0?.toPrecision(8)} kept over 6 draws (|L| ${norm.toPrecision(4)}; its horizontal part moved ${turned.toPrecision(3)})`);
}

// The rolling rattleback opens with the catalogue's fixed pace, whose energy error the
// catalogue bounds (`presentation.pace.energy_error`): run the page's own setup for 10 s of
// motion and read the largest error.
{
  const r = await page.evaluate(() => {
    const L = window.physicskitLab;
    L.select("rolling-rattleback");
    let worst = 0;
    while (L.app.lab.time() < 10) { if (!L.runFrames(1)) return null; worst = Math.max(worst, L.app.lab.energyError()); }
    return { worst, bound: L.app.entry.presentation.pace.energy_error, t: L.app.lab.time(), method: document.getElementById("method").value, dt: document.getElementById("dt").value, steps: document.getElementById("speed").value,
      note: document.getElementById("step-note").textContent };
  });
  if (!r || !(r.worst <= r.bound)) fail(`rolling rattleback: energy error ${r?.worst} over 10 s at its default step`);
  if (!r?.note.includes(r?.dt)) fail(`rolling rattleback: the page does not show its step (${JSON.stringify(r?.note)})`);
  console.log(`ok rolling rattleback: ${r?.method} at dt = ${r?.dt}, ${r?.steps} steps a frame: largest energy error ${r?.worst.toExponential(2)} over ${r?.t.toFixed(2)} s`);
}

// Drag the double pendulum's lower bob 80 px to the left (towards the pivot, within reach): the state must change, the
// velocities be zero (let go from rest), and the bob follow the pointer.
await page.evaluate(() => window.physicskitLab.select("double-pendulum"));
const [, bob] = await page.evaluate(() => window.physicskitLab.bodiesOnScreen());
const q0 = await page.evaluate(() => Array.from(window.physicskitLab.app.lab.state()));
await page.mouse.move(bob[0], bob[1]);
await page.mouse.down();
await page.mouse.move(bob[0] - 40, bob[1], { steps: 4 });
await page.mouse.move(bob[0] - 80, bob[1], { steps: 4 });
await page.mouse.up();
const q1 = await page.evaluate(() => Array.from(window.physicskitLab.app.lab.state()));
const [, bob1] = await page.evaluate(() => window.physicskitLab.bodiesOnScreen());
if (q1[0] === q0[0] && q1[1] === q0[1]) fail("drag: the angles did not change");
if (q1[2] !== 0 || q1[3] !== 0) fail(`drag: velocities ${q1[2]}, ${q1[3]} are not zero`);
// Within 1.5 px of the pointer: the solve converges to 1e-12 of a unit; the rest is the
// whole-pixel rounding of the mouse position and of the drawing.
if (Math.hypot(bob1[0] - bob[0] + 80, bob1[1] - bob[1]) > 1.5) fail(`drag: bob at ${bob1}, pointer at ${[bob[0] - 80, bob[1]]}`);
console.log(`ok drag: angles ${q0.slice(0, 2).map((x) => x.toFixed(3))} -> ${q1.slice(0, 2).map((x) => x.toFixed(3))}`);

// Share link round trip: the dragged start, method and dt, reopened in a new page, runs to
// the same bits.
await page.evaluate(() => { const s = document.getElementById("method"); s.value = "rk4"; s.onchange(); });
const hash = await page.evaluate(() => window.physicskitLab.shareHash());
await page.evaluate(() => window.physicskitLab.runFrames(4));
const first = await page.evaluate(() => [Array.from(window.physicskitLab.app.lab.state()), window.physicskitLab.app.lab.energyError()]);
const page2 = await open(hash);
const opened = await page2.evaluate(() => [window.physicskitLab.app.entry.name, document.getElementById("method").value,
  Array.from(window.physicskitLab.app.lab.initialState())]);
// The page opens running: pause and start the run over before stepping it.
await page2.evaluate(() => { window.physicskitLab.restart(); window.physicskitLab.runFrames(4); });
const second = await page2.evaluate(() => [Array.from(window.physicskitLab.app.lab.state()), window.physicskitLab.app.lab.energyError()]);
if (opened[0] !== "double-pendulum" || opened[1] !== "rk4") fail(`share: opened ${opened[0]} with ${opened[1]}`);
if (JSON.stringify(opened[2]) !== JSON.stringify(q1)) fail("share: initial state differs");
if (JSON.stringify(second) !== JSON.stringify(first)) fail("share: the reopened run differs");
console.log(`ok share link: ${hash.length} characters, reopened run identical`);
await page2.close();

// Drag out of reach: the lower bob pulled to a point farther from the pivot than the two
// rods reach. The pose must be the nearest reachable one: both rods in line, pointing at the
// pointer, the bob at distance l1 + l2 = 2 m (the defaults), angles in (−π, π].
await page.evaluate(() => window.physicskitLab.select("double-pendulum"));
{
  const [, b] = await page.evaluate(() => window.physicskitLab.bodiesOnScreen());
  const box = await page.locator("#scene").boundingBox();
  // The plot's upper-left corner region: about 3 m from the pivot in the 2.4 m-high view.
  const target = [box.x + 70, box.y + 12];
  await page.mouse.move(b[0], b[1]);
  await page.mouse.down();
  await page.mouse.move((b[0] + target[0]) / 2, (b[1] + target[1]) / 2, { steps: 5 });
  await page.mouse.move(target[0], target[1], { steps: 5 });
  const want = await page.evaluate(([x, y]) => window.physicskitLab.sceneAt(x, y), target);
  await page.mouse.up();
  const q = await page.evaluate(() => Array.from(window.physicskitLab.app.lab.state()));
  const pos = await page.evaluate(() => Array.from(window.physicskitLab.app.lab.positions()));
  const reach = Math.hypot(pos[2], pos[3]), dist = Math.hypot(...want);
  if (!(dist > 2.2)) fail(`drag out of reach: the target ${want} is only ${dist} m from the pivot`);
  // The nearest reachable point: the solve stops when a step no longer lowers the distance,
  // which at the stretched pose leaves ~1e-8 of the 2 m (finite-difference Jacobian).
  if (Math.abs(reach - 2) > 1e-6) fail(`drag out of reach: bob ${reach} m from the pivot, not 2 m`);
  const dir = Math.atan2(want[1], want[0]) - Math.atan2(pos[3], pos[2]);
  if (Math.abs(Math.atan2(Math.sin(dir), Math.cos(dir))) > 1e-5) fail(`drag out of reach: bob not towards the pointer (${dir} rad off)`);
  for (const a of q.slice(0, 2)) if (!(a > -Math.PI && a <= Math.PI)) fail(`drag out of reach: angle ${a} outside (−π, π]`);
  if (Math.abs(Math.atan2(Math.sin(q[0] - q[1]), Math.cos(q[0] - q[1]))) > 1e-5) fail(`drag out of reach: rods bent (${q[0]}, ${q[1]})`);
  const link = await page.evaluate(() => window.physicskitLab.shareHash());
  const linkState = new URLSearchParams(link.slice(1)).get("state").split(",").map(Number);
  if (linkState.slice(0, 2).some((a) => !(a > -Math.PI && a <= Math.PI))) fail(`drag out of reach: the link carries ${linkState}`);
  console.log(`ok drag out of reach: angles ${q.slice(0, 2).map((x) => x.toFixed(4))}, bob ${reach.toFixed(9)} m from the pivot`);
  await page.screenshot({ path: join(shots, "double-pendulum-dragged-out-of-reach.png"), fullPage: true });
}

// Dragging a chain's mass and a top's axis. While the pointer is down the body is under it (to
// 1.5 px: the whole-pixel mouse position and drawing); let go, the run starts from the dragged
// state, whose energy is the closed form's for that state, and the share link carries it.
const paramsOf = (p) => p.evaluate(() => { const L = window.physicskitLab; return Object.fromEntries(L.app.entry.params.map((q) => [q.name, L.app.params[q.name] ?? q.default])); });
async function dragHandle(pick, dx, dy) {
  const hs = await page.evaluate(() => window.physicskitLab.handlesOnScreen());
  const h = pick(hs);
  await page.mouse.move(h.x, h.y);
  await page.mouse.down();
  await page.mouse.move(h.x + dx / 2, h.y + dy / 2, { steps: 3 });
  await page.mouse.move(h.x + dx, h.y + dy, { steps: 3 });
  const held = (await page.evaluate(() => window.physicskitLab.handlesOnScreen())).find((g) => g.i === h.i && g.how === h.how);
  await page.mouse.up();
  const after = await page.evaluate(() => {
    const L = window.physicskitLab;
    return { state: Array.from(L.app.lab.state()), initial: Array.from(L.app.lab.initialState()), e0: L.app.lab.energy0(), hash: L.shareHash() };
  });
  return { h, held, target: [h.x + dx, h.y + dy], ...after };
}
function checkLink(name, r) {
  const linked = new URLSearchParams(r.hash.slice(1)).get("state").split(",").map(Number);
  if (linked.join() !== r.initial.join() || r.state.join() !== r.initial.join()) fail(`${name}: the link carries ${linked}, the run starts at ${r.initial}, the state is ${r.state}`);
}
{
  // Coupled oscillators (masses between two walls): E = (m/2) Σ q̇ᵢ² + (k/2) Σ (qᵢ₊₁ − qᵢ)², walls q = 0.
  await page.evaluate(() => window.physicskitLab.select("coupled-oscillators"));
  const p = await paramsOf(page);
  const energy = (s) => {
    const n = s.length / 2, q = [0, ...s.slice(0, n), 0];
    let e = 0;
    for (let i = 0; i < n; i++) e += 0.5 * p.m * s[n + i] ** 2;
    for (let i = 0; i + 1 < q.length; i++) e += 0.5 * p.k * (q[i + 1] - q[i]) ** 2;
    return e;
  };
  for (const [how, dx, dy] of [["plot", 0, -25], ["strip", 12, 0]]) {
    const r = await dragHandle((hs) => hs.filter((g) => g.how === how)[1], dx, dy);
    const name = `chain drag (${how})`;
    if (!r.held || Math.hypot(r.held.x - r.target[0], r.held.y - r.target[1]) > 1.5) fail(`${name}: mass ${r.h.i} at ${r.held && [r.held.x, r.held.y]}, pointer at ${r.target}`);
    const n = r.state.length / 2;
    if (r.state[n + r.h.i] !== 0) fail(`${name}: the dragged mass not let go at rest (${r.state[n + r.h.i]})`);
    // Sums of a dozen squares: 1e-13 of the energy is a few roundings.
    if (Math.abs(r.e0 - energy(r.state)) > 1e-13 * Math.abs(energy(r.state))) fail(`${name}: energy ${r.e0}, the closed form ${energy(r.state)}`);
    checkLink(name, r);
    console.log(`ok ${name}: mass ${r.h.i} to ${r.state[r.h.i].toPrecision(6)}, under the pointer, energy ${r.e0.toPrecision(8)} (closed form alike)`);
  }
  // Far beyond the plot: clamped at the plot's edge, 1.1 times the drawing's scale.
  const amp = await page.evaluate(() => window.physicskitLab.app.chainGeom.amp);
  const r = await dragHandle((hs) => hs.filter((g) => g.how === "plot")[2], 0, -2000);
  if (r.state[r.h.i] !== 1.1 * amp) fail(`chain drag out of range: mass at ${r.state[r.h.i]}, the clamp ${1.1 * amp}`);
  await page.screenshot({ path: join(shots, "coupled-oscillators-dragged.png"), fullPage: true });
}
{
  // The heavy top let go with its spin and no precession or nutation rate:
  // E = I₃ ψ̇²/2 + M g l cos θ (Goldstein §5.7 with θ̇ = φ̇ = 0).
  await page.evaluate(() => window.physicskitLab.select("heavy-top"));
  const p = await paramsOf(page);
  const before = await page.evaluate(() => Array.from(window.physicskitLab.app.lab.state()));
  const r = await dragHandle((hs) => hs[0], 40, 25);
  const [phi, theta, psi, dphi, dtheta, dpsi] = r.state;
  if (!r.held || Math.hypot(r.held.x - r.target[0], r.held.y - r.target[1]) > 1.5) fail(`top drag: tip at ${r.held && [r.held.x, r.held.y]}, pointer at ${r.target}`);
  if (dphi !== 0 || dtheta !== 0 || dpsi !== before[5] || psi !== before[2]) fail(`top drag: let go with rates ${[dphi, dtheta, dpsi]}, spin angle ${psi} (was ${before[2]}, spin rate ${before[5]})`);
  if (!(theta >= 0.02 && theta <= Math.PI - 0.02) || !(phi > -Math.PI && phi <= Math.PI)) fail(`top drag: θ = ${theta}, φ = ${phi}`);
  const want = 0.5 * p.I3 * dpsi ** 2 + p.M * p.g * p.l * Math.cos(theta);
  // Two terms: a few roundings.
  if (Math.abs(r.e0 - want) > 1e-13 * Math.abs(want)) fail(`top drag: energy ${r.e0}, the closed form ${want}`);
  checkLink("top drag", r);
  console.log(`ok top drag: axis to θ = ${theta.toFixed(4)}, φ = ${phi.toFixed(4)}, under the pointer, energy ${r.e0.toPrecision(8)} (closed form alike)`);
  await page.screenshot({ path: join(shots, "heavy-top-dragged.png"), fullPage: true });
}

// Drags system `name`'s last body, or a chain's middle mass, or a top's axis, 30 px right and
// 20 px up on page `p`; false if it has nothing on the screen to drag.
async function dragOnce(p, name) {
  await p.evaluate((n) => window.physicskitLab.select(n), name);
  const at = await p.evaluate(() => {
    const L = window.physicskitLab, hs = L.handlesOnScreen();
    if (hs.length) { const h = hs[Math.floor(hs.length / 2)]; return [h.x, h.y]; }
    const b = L.bodiesOnScreen();
    return b[b.length - 1];
  });
  if (!at) return false;
  await p.mouse.move(at[0], at[1]);
  await p.mouse.down();
  await p.mouse.move(at[0] + 30, at[1] - 20, { steps: 4 });
  await p.mouse.up();
  return true;
}

// The Poincaré section is offered only where it has a closed edge on the energy surface (an
// unbounded flight crosses the plane once): every system offering it draws that edge.
{
  const r = await page.evaluate((names) => {
    const L = window.physicskitLab, offered = [], open = [];
    for (const n of names) {
      L.select(n);
      if (document.getElementById("section-choice").hidden) continue;
      const box = document.getElementById("section-on"), was = box.checked;
      if (!was) { box.checked = true; box.onchange(); }
      offered.push(n);
      if (!L.app.boundary) open.push(n);
      if (!was) { box.checked = false; box.onchange(); }
    }
    return { offered, open };
  }, systems.map(([n]) => n));
  if (r.open.length) fail(`section offered without a closed edge: ${r.open.join(", ")}`);
  if (!r.offered.includes("henon-heiles")) fail(`the section is not offered for Hénon–Heiles (offered: ${r.offered.join(", ")})`);
  console.log(`ok section offered for ${r.offered.join(", ")}, each with its closed edge`);
}

// Every chain of rods (a drawing of bobs without springs, two bobs or more): its last bob
// dragged towards the pivot, to three quarters of its distance (inside the reach of rods that
// can fold), lands under the pointer and is let go from rest.
{
  const chains = await page.evaluate(() => window.physicskitLab.app.catalogue.systems
    .filter((s) => s.presentation.drawing.kind === "bobs" && !s.presentation.drawing.springs).map((s) => s.name));
  const dragged = [];
  for (const name of chains) {
    const at = await page.evaluate((n) => {
      const L = window.physicskitLab; L.select(n);
      const r = document.getElementById("scene").getBoundingClientRect(), v = L.app.sceneView;
      return { bobs: L.bodiesOnScreen(), pivot: [r.left + v.X(0), r.top + v.Y(0)] };
    }, name);
    if (at.bobs.length < 2) continue;
    const b = at.bobs[at.bobs.length - 1], target = [0, 1].map((i) => at.pivot[i] + 0.75 * (b[i] - at.pivot[i]));
    await page.mouse.move(b[0], b[1]); await page.mouse.down();
    await page.mouse.move((b[0] + target[0]) / 2, (b[1] + target[1]) / 2, { steps: 3 });
    await page.mouse.move(target[0], target[1], { steps: 3 });
    await page.mouse.up();
    const got = await page.evaluate(() => ({ bobs: window.physicskitLab.bodiesOnScreen(), state: Array.from(window.physicskitLab.app.lab.state()) }));
    const last = got.bobs[got.bobs.length - 1], n = got.state.length / 2;
    // 1.5 px: the whole-pixel mouse position and drawing, as for the double pendulum above.
    if (Math.hypot(last[0] - target[0], last[1] - target[1]) > 1.5) fail(`${name}: the last bob at ${last}, the pointer at ${target}`);
    if (got.state.slice(n).some((x) => x !== 0)) fail(`${name}: let go with rates ${got.state.slice(n)}`);
    dragged.push(name);
    await page.screenshot({ path: join(shots, `${name}-last-bob-dragged.png`), fullPage: true });
  }
  if (!dragged.length) fail("no chain of rods dragged by its last bob");
  console.log(`ok last bobs: ${dragged.join(", ")} dragged by their last bob, under the pointer, let go at rest`);
}

// Every draggable system after a drag (then 30 frames run): screenshots to look at, and no
// console error on the way.
for (const name of DRAGGABLE) {
  if (!await dragOnce(page, name)) continue;
  await page.evaluate(() => window.physicskitLab.runFrames(30));
  await page.screenshot({ path: join(shots, `${name}-after-drag.png`), fullPage: true });
}

// Hostile share links: each opens a page with controls, the linked system if it exists (else
// the default), valid values, and one line naming what was refused.
const HOSTILE = [
  ["#system=henon-heiles&params=not-json", "henon-heiles", "parameters"],
  ["#system=double-pendulum&state=NaN,1,2,3", "double-pendulum", "start"],
  ["#system=pendulum-swarm&params=%7B%22n%22%3A1e12%7D", "pendulum-swarm", "“n”"],
  ["#system=double-pendulum&dt=-1", "double-pendulum", "dt"],
  ["#system=no-such-system", "double-pendulum", "no system called"],
  ["#system=double-pendulum&state=0.1,0.2", "double-pendulum", "start"],
  ["#system=double-pendulum&steps=1000000000", "double-pendulum", "steps"],
  ["#system=double-pendulum&method=warp-drive", "double-pendulum", "method"],
  ["#system=kepler&params=%7B%22%3Cimg%20src%3Dx%20onerror%3Dalert(1)%3E%22%3A1%7D", "kepler", "<img src=x"],
];
for (const [hash, system, named] of HOSTILE) {
  const p = await open(hash);
  const got = await p.evaluate(() => {
    const lab = window.physicskitLab.app.lab;
    return {
      system: window.physicskitLab.app.entry.name,
      message: document.getElementById("message").textContent,
      controls: document.querySelectorAll("#params .param").length + document.querySelectorAll("#method option").length,
      dtOptions: [...document.getElementById("dt").options].map((o) => Number(o.value)),
      steps: Number(document.getElementById("speed").value),
      state: Array.from(lab.state()),
      images: document.querySelectorAll("img").length,
    };
  });
  const why = `link ${hash}`;
  if (got.system !== system) fail(`${why}: opened ${got.system}, not ${system}`);
  if (!got.message.includes(named)) fail(`${why}: the message ${JSON.stringify(got.message)} does not name ${named}`);
  if (got.message.split("\n").length !== 1 || !got.message.startsWith("From the link, refused")) fail(`${why}: message ${JSON.stringify(got.message)}`);
  if (got.controls < 2) fail(`${why}: a page without controls`);
  if (got.dtOptions.some((d) => !(d > 0 && Number.isFinite(d)))) fail(`${why}: the dt menu offers ${got.dtOptions}`);
  if (!(got.steps >= 1 && got.steps <= 400)) fail(`${why}: ${got.steps} steps a frame`);
  if (!got.state.every(Number.isFinite)) fail(`${why}: state ${got.state}`);
  if (got.images) fail(`${why}: HTML from the link became ${got.images} image element(s)`);
  // And it runs.
  const ran = await p.evaluate(() => { window.physicskitLab.restart(); return window.physicskitLab.runFrames(3); });
  if (!ran) fail(`${why}: the opened page does not run`);
  console.log(`ok hostile link ${hash.slice(0, 60)}: ${got.message.slice(0, 110)}`);
  await p.close();
}

// A method name from a script call is untrusted too: the module's build and set-method refuse
// an unknown name, HTML, a name in the wrong case and a splitting method on a system with
// drag, each with an Error
// naming the method, and the module runs on (a panic in the WebAssembly would abort it: every
// later call would throw "unreachable").
{
  const r = await page.evaluate(() => {
    const core = window.physicskitLab.app.core, out = [];
    const attempt = (method, f) => { try { f(); out.push({ method, thrown: null }); } catch (e) { out.push({ method, thrown: `${e.constructor.name}: ${e.message}` }); } };
    for (const m of ["warp-drive", "<b>rk4</b>", "RK4"]) attempt(m, () => core.build("double-pendulum", {}, m).free());
    attempt("yoshida4", () => core.build("projectile", { drag_coeff: 0.02 }, "yoshida4").free());
    const lab = core.build("double-pendulum", {}, "rk4");
    attempt("warp-drive", () => lab.setMethod("warp-drive"));
    lab.step(10, 1e-3);
    const ran = Number.isFinite(lab.energyError()) && lab.time() > 0;
    lab.free();
    return { out, ran };
  });
  for (const { method, thrown } of r.out) {
    if (!thrown?.startsWith("Error: ") || !thrown.includes(method)) fail(`method ${method}: ${thrown ?? "not refused"}`);
  }
  if (!r.ran) fail("after the refused methods the module does not run");
  console.log(`ok bad methods refused by name, the module running on: ${r.out.map((o) => o.thrown.slice(7, 60)).join(" | ")}`);
}

// Links in the form the gallery writes (`Ctx::lab_link`: system, method, dt, parameters; no
// steps) open every system with nothing refused, the method and step they name.
{
  const bad = await page.evaluate(() => {
    const L = window.physicskitLab, out = [];
    for (const s of L.app.catalogue.systems) {
      L.select(s.name);
      const m = document.getElementById("method").value;
      const hash = `#system=${s.name}&method=${m}&dt=0.002&params=${encodeURIComponent("{}")}`;
      const clean = L.openHash(hash);
      const got = [L.app.entry.name, document.getElementById("method").value, document.getElementById("dt").value];
      if (!clean || got.join() !== [s.name, m, "0.002"].join()) out.push(`${hash} -> ${got} (${document.getElementById("message").textContent})`);
    }
    return out;
  });
  if (bad.length) fail(`gallery-form links: ${bad.join(" | ")}`);
  console.log("ok gallery-form links: every system opens with its method and step, nothing refused");
}

// Every "Open in the lab" link of a rendered gallery (GALLERY_DIR/index.html, given as the
// fourth argument) opens its system with its method, step and every parameter, nothing
// refused: the page's links are read from the HTML as the gallery wrote them.
if (galleryDir) {
  const html = readFileSync(join(galleryDir, "index.html"), "utf8");
  const hrefs = [...new Set([...html.matchAll(/href="([^"]*#[^"]*)"/g)].map((m) => m[1].replace(/&amp;/g, "&").replace(/&quot;/g, "\"")))]
    .filter((h) => new URLSearchParams(h.split("#")[1]).has("system"));
  if (!hrefs.length) fail(`gallery links: none in ${galleryDir}/index.html`);
  const bad = await page.evaluate((hashes) => {
    const L = window.physicskitLab, out = [];
    for (const hash of hashes) {
      const h = new URLSearchParams(hash.slice(1)), params = JSON.parse(h.get("params") ?? "{}");
      const clean = L.openHash(hash);
      const kept = Object.entries(params).every(([k, v]) => JSON.stringify(L.app.params[k]) === JSON.stringify(v));
      const got = [L.app.entry.name, document.getElementById("method").value, Number(document.getElementById("dt").value)];
      const want = [h.get("system"), h.get("method"), Number(h.get("dt"))];
      // And it runs a frame with them.
      const ran = clean && L.runFrames(1);
      if (!clean || !kept || !ran || got.join() !== want.join()) out.push(`${want.join()} -> ${got.join()}${ran ? "" : " (does not run)"}: ${document.getElementById("message").textContent}`);
    }
    return out;
  }, hrefs.map((h) => `#${h.split("#")[1]}`));
  for (const b of bad) fail(`gallery link ${b}`);
  console.log(`ok gallery links: ${hrefs.length - bad.length} of ${hrefs.length} open with their system, method, step and parameters, nothing refused`);
}

// A link made in time-lapse opens in time-lapse: the box ticked, its step and steps a frame.
{
  const r = await page.evaluate(() => {
    const L = window.physicskitLab;
    L.select("foucault-pendulum");
    L.setTimeLapse(true);
    const hash = L.shareHash(), dt = document.getElementById("dt").value, steps = document.getElementById("speed").value;
    L.select("double-pendulum");
    const clean = L.openHash(hash);
    return { hash, clean, ticked: document.getElementById("timelapse").checked, same: [dt, steps].join() === [document.getElementById("dt").value, document.getElementById("speed").value].join(),
      note: document.getElementById("step-note").textContent };
  });
  if (!r.clean || !r.ticked || !r.same || !/time-lapse/i.test(r.note)) fail(`time-lapse link: ${JSON.stringify(r)}`);
  console.log("ok time-lapse link: opens with the time-lapse ticked, its step and steps a frame");
}

// Parameters that only build together (a start of another length and the size that goes
// with it) open together: nothing refused, every value kept.
{
  const links = [
    ["coupled-oscillators", { n: 5, q0: [0.1, -0.2, 0.15, 0.0, 0.05], qdot0: [0, 0, 0, 0, 0] }],
    ["toda", { q0: [0, 0, 0, 0], p0: [1.0, 0.0, -0.5, -0.5] }],
  ];
  const bad = await page.evaluate((links) => {
    const L = window.physicskitLab, out = [];
    for (const [system, params] of links) {
      const clean = L.openHash(`#system=${system}&params=${encodeURIComponent(JSON.stringify(params))}`);
      const kept = Object.entries(params).every(([k, v]) => JSON.stringify(L.app.params[k]) === JSON.stringify(v));
      if (!clean || L.app.entry.name !== system || !kept) {
        out.push(`${system}: ${document.getElementById("message").textContent} kept ${JSON.stringify(L.app.params)}`);
      }
    }
    return out;
  }, links);
  if (bad.length) fail(`parameters that build together: ${bad.join(" | ")}`);
  console.log("ok links whose parameters build only together open with all of them");
}

// Hénon–Heiles: three clicks on the section launch three orbits at the same energy (y = 0,
// py > 0 solved); each runs 80 time units. The crossings of all three stay, each orbit with
// its own number, read from the JSON export.
await page.evaluate(() => window.physicskitLab.select("henon-heiles"));
const e0 = await page.evaluate(() => window.physicskitLab.app.lab.energy0());
const clicks = [[0.1, 0.0], [-0.2, 0.05], [0.0, 0.25]];
for (const [k, [x, px]] of clicks.entries()) {
  await page.locator("#section").scrollIntoViewIfNeeded();
  const [cx, cy] = await page.evaluate(([a, b]) => window.physicskitLab.sectionToScreen(a, b), [x, px]);
  await page.mouse.click(cx, cy);
  const s = await page.evaluate(() => Array.from(window.physicskitLab.app.lab.state()));
  const [lx, ly] = await page.evaluate(([a, b]) => window.physicskitLab.sectionToScreen(a, b), [s[0], s[2]]);
  // The orbit starts where the click was, to a screen pixel (the mouse position is whole CSS
  // pixels, truncated: under √2 px off); y exactly on the section, py > 0 (the section's
  // direction).
  if (Math.hypot(lx - cx, ly - cy) > 1.5 || s[1] !== 0 || !(s[3] > 0)) fail(`section click ${k}: launched at ${s}, on screen ${[lx, ly]} vs click ${[cx, cy]}`);
  const e1 = await page.evaluate(() => window.physicskitLab.app.lab.energy());
  // The solved py puts the energy on E0 to the last bits of the bisection.
  if (Math.abs(e1 - e0) > 1e-14) fail(`section click ${k}: energy ${e1} vs ${e0}`);
  // 200 frames of 400 steps of 1e-3: 80 time units, about 12 periods of the x oscillation
  // (2 pi), so about a dozen upward crossings of y = 0.
  await page.evaluate(() => { document.getElementById("speed").value = 400; window.physicskitLab.runFrames(200); });
}
{
  const section = await page.evaluate(() => window.physicskitLab.exportJson().section);
  const byOrbit = new Map();
  for (const c of section?.crossings ?? []) byOrbit.set(c.orbit, [...(byOrbit.get(c.orbit) ?? []), c.state]);
  if (byOrbit.size !== 3) fail(`section: ${byOrbit.size} orbits in the export after three clicks`);
  for (const [orbit, states] of byOrbit) {
    if (states.length < 5) fail(`section: orbit ${orbit} kept ${states.length} crossings`);
    // On the section (Hénon's step lands on y = 0 to rounding), upwards.
    if (states.some((st) => Math.abs(st[1]) > 1e-12 || !(st[3] > 0))) fail(`section: orbit ${orbit} has a crossing off the section`);
  }
  if (section && Math.abs(section.energy - e0) > 0) fail(`section: energy ${section.energy} vs ${e0}`);
  console.log(`ok section: ${byOrbit.size} orbits kept, ${[...byOrbit.values()].map((v) => v.length).join(" + ")} crossings`);
  await page.screenshot({ path: join(shots, "henon-heiles-section.png"), fullPage: true });
  await page.click("#section-clear");
  const left = await page.evaluate(() => window.physicskitLab.exportJson().section.crossings.length);
  if (left !== 0) fail(`section: ${left} crossings after Clear`);
}

// The reduced Euler's disk ends at its finite-time collapse (its tilt θ reaches the floor):
// run well past it and the page stops there, at the last step that keeps θ above the floor,
// saying so in words (a notice, not an error), with the closed form's collapse time
// θ₀² / (2 × decay rate).
{
  const r = await page.evaluate(() => {
    const L = window.physicskitLab;
    L.select("eulers-disk");
    const p = Object.fromEntries(L.app.entry.params.map((q) => [q.name, L.app.params[q.name] ?? q.default]));
    const dt = Number(document.getElementById("dt").value), steps = Number(document.getElementById("speed").value);
    // Twice the frames the collapse takes.
    const frames = Math.ceil((2 * p.theta0 ** 2) / (2 * p.decay_rate) / (dt * steps));
    const ran = L.runFrames(frames);
    const m = document.getElementById("message");
    return { p, dt, ran, t: L.app.lab.time(), theta: L.app.lab.state()[0], running: L.app.running,
      text: m.textContent, notice: m.classList.contains("notice"), shown: getComputedStyle(m).color };
  });
  const tf = r.p.theta0 ** 2 / (2 * r.p.decay_rate);
  // The last step: θ² = θ₀² − 2 k t ≥ floor², so t is within one step of the collapse (the
  // floor, 1e-3 rad, moves it by floor² / 2k = 1e-5 s).
  if (r.ran || r.running) fail("Euler's disk: the run did not stop at the model's end");
  if (!(r.theta >= r.p.theta_floor) || !(r.t <= tf && r.t > tf - 2 * r.dt)) fail(`Euler's disk: stopped at t = ${r.t}, θ = ${r.theta}; the collapse is at ${tf}`);
  const said = /come to rest at t ≈ ([0-9.]+) s/.exec(r.text);
  // Three significant digits, as the page writes it.
  if (!said || Number(said[1]) !== Number(tf.toPrecision(3))) fail(`Euler's disk: the page says ${JSON.stringify(r.text)}, the collapse is at ${tf.toPrecision(3)} s`);
  if (!r.notice || /error|converge|reduce dt/i.test(r.text)) fail(`Euler's disk: an error shown at the end: ${JSON.stringify(r.text)}`);
  // Reset starts it again, the notice gone.
  const again = await page.evaluate(() => { const L = window.physicskitLab; L.restart(); const ok = L.runFrames(2); return { ok, text: document.getElementById("message").textContent }; });
  if (!again.ok || again.text) fail(`Euler's disk: after a reset ${JSON.stringify(again)}`);
  console.log(`ok Euler's disk: stops at t = ${r.t} (θ = ${r.theta.toPrecision(3)}), collapse ${tf} s, says ${JSON.stringify(said?.[0])}`);
}

// Foucault's pendulum in time-lapse: after an hour of the pendulum's time (a minute of
// frames) its swing plane has turned visibly, by the closed form −Ω⊕ sin(latitude) t.
{
  const r = await page.evaluate(() => {
    const L = window.physicskitLab;
    L.select("foucault-pendulum");
    L.setTimeLapse(true);
    const perFrame = Number(document.getElementById("dt").value) * Number(document.getElementById("speed").value);
    const frames = Math.ceil(3600 / perFrame);
    const ran = L.runFrames(frames);
    return { ran, frames, perFrame, t: L.app.lab.time(), turn: L.app.swingTurn, note: document.getElementById("step-note").textContent,
      label: [...document.querySelectorAll("#params label")].find((l) => l.htmlFor === document.querySelector("[data-param=omega_earth]")?.id)?.innerHTML };
  });
  const deg = (x) => (x * 180) / Math.PI;
  const want = -r.turn.omegaZ * r.turn.at;
  if (!r.ran || !(r.frames <= 3600) || !/time-lapse/i.test(r.note)) fail(`Foucault time-lapse: ${JSON.stringify(r)}`);
  // Visible: more than 5° (Paris turns 11.3° an hour).
  if (!(Math.abs(deg(r.turn.turned)) > 5)) fail(`Foucault time-lapse: turned ${deg(r.turn.turned)}° after ${r.t} s`);
  // 0.01°: the turn is read from the trail sample farthest out in the last swing, within half a
  // sample spacing (0.5 s) of the swing's end, where the rosette's thin ellipse (width/length
  // Ω⊕ sin(latitude) / ω₀ ≈ 1.4e-4) bends its direction by under 0.002°; the integration's
  // error at dt = 0.02 s is far smaller.
  if (Math.abs(deg(r.turn.turned - want)) > 0.01) fail(`Foucault time-lapse: turned ${deg(r.turn.turned)}°, the closed form ${deg(want)}°`);
  // Ω⊕ as a physicist writes it: Ω with ⊕ as a subscript.
  if (!r.label?.startsWith("Ω<sub>⊕</sub>")) fail(`Foucault: the Earth's rate labelled ${JSON.stringify(r.label)}`);
  console.log(`ok Foucault time-lapse: turned ${deg(r.turn.turned).toFixed(4)}° at t = ${r.turn.at} s, closed form ${deg(want).toFixed(4)}° (${r.frames} frames of ${r.perFrame} s)`);
}

// The keyboard: space runs and pauses the page.
{
  await page.evaluate(() => { window.physicskitLab.pause(); document.activeElement?.blur(); });
  await page.keyboard.press("Space");
  const on = await page.evaluate(() => window.physicskitLab.app.running);
  await page.keyboard.press("Space");
  const off = await page.evaluate(() => window.physicskitLab.app.running);
  if (!on || off) fail(`keyboard: space gave running ${on}, then ${off}`);
  const unlabelled = await page.evaluate(() => [...document.querySelectorAll("input, select, button")].filter((e) => e.offsetParent !== null &&
    !(e.labels?.length || e.getAttribute("aria-label") || (e.tagName === "BUTTON" && e.textContent.trim()))).map((e) => e.id || e.outerHTML.slice(0, 60)));
  if (unlabelled.length) fail(`controls without a label: ${unlabelled.join(", ")}`);
  console.log("ok keyboard: space runs and pauses; every control has a label");
}

// A phone-sized screen (390 px): one column, nothing wider than the screen, the scene and the
// Run button on the first screen; with the large-text option too. Every system is shown.
const phone = await browser.newPage({ viewport: { width: 390, height: 844 } });
phone.on("pageerror", (e) => errors.push(String(e)));
await phone.goto(url);
await phone.evaluate(() => window.physicskitLab.ready);
for (const [name] of systems) {
  await phone.evaluate((n) => { window.physicskitLab.select(n); window.physicskitLab.runFrames(60); }, name);
  const m = await phone.evaluate(() => ({
    overflow: document.documentElement.scrollWidth - window.innerWidth,
    scene: document.getElementById("scene").getBoundingClientRect().bottom,
    run: document.getElementById("run").getBoundingClientRect().bottom,
    height: window.innerHeight,
  }));
  if (m.overflow > 0) fail(`phone ${name}: the page is ${m.overflow} px wider than the screen`);
  // No caption cut: every text block shown is as wide as its content (but the labels kept for
  // screen readers only, clipped on purpose).
  const cut = await phone.evaluate(() => [...document.querySelectorAll("figcaption, p, label, legend, h1, h2, .hint, .clock")]
    .filter((e) => e.offsetParent !== null && !e.classList.contains("sr-only") && e.scrollWidth > e.clientWidth + 1).map((e) => `${e.id || e.tagName}: ${e.textContent.slice(0, 50)}`));
  if (cut.length) fail(`phone ${name}: text cut at 390 px: ${cut.join(" | ")}`);
  if (m.scene > m.height || m.run > m.height) fail(`phone ${name}: scene ends at ${m.scene} px, Run at ${m.run} px, screen ${m.height} px`);
  // A chain of rods: neighbouring bobs (and the first and the pivot) never cover each other.
  const bobs = await phone.evaluate(() => { const L = window.physicskitLab, d = L.app.entry.presentation.drawing; return d.kind === "bobs" && !d.springs ? [{ x: L.app.sceneView.X(0), y: L.app.sceneView.Y(0), r: 0 }, ...L.app.bobsDrawn] : []; });
  for (let i = 1; i < bobs.length; i++) {
    if (Math.hypot(bobs[i].x - bobs[i - 1].x, bobs[i].y - bobs[i - 1].y) < bobs[i].r + bobs[i - 1].r) fail(`phone ${name}: bob ${i} covers ${i > 1 ? `bob ${i - 1}` : "the pivot"} (${JSON.stringify(bobs.slice(i - 1, i + 1))})`);
  }
  // A chain's strip of masses on springs stays readable: neighbours at least 20 px apart (where
  // all do not fit, a window of the chain), each mass on the screen inside the strip.
  const strip = await phone.evaluate(() => {
    const L = window.physicskitLab, g = L.app.chainGeom;
    if (!g?.strip) return null;
    const r = document.getElementById("scene").getBoundingClientRect();
    return { gap: g.gap, count: g.count, xs: L.handlesOnScreen().filter((h) => h.how === "strip").map((h) => h.x - r.left), x0: g.x0, x1: g.v.rect.x1 };
  });
  // 20 px: a mass 7 px wide and a spring of two coils between neighbours.
  if (strip && !(strip.gap >= 20)) fail(`phone ${name}: the strip's masses ${strip.gap.toFixed(1)} px apart`);
  if (strip && (strip.xs.length !== strip.count || strip.xs.some((x) => x < strip.x0 || x > strip.x1))) fail(`phone ${name}: strip masses at ${strip.xs.map((x) => x.toFixed(0))}, the strip ${strip.x0}–${strip.x1} px`);
  // On the narrow floor too: no label under the body, every axis's name drawn.
  const under = await phone.evaluate(() => {
    const L = window.physicskitLab, f = L.app.floorLabels, t = L.ticks().scene, out = [];
    if (!["top_axis", "contact_spiral", "rolling"].includes(L.app.entry.presentation.drawing.kind)) return out;
    for (const d of f.drawn) for (const a of f.avoid) if (d.box[0] < a[2] && a[0] < d.box[2] && d.box[1] < a[3] && a[1] < d.box[3]) out.push(`${d.text} under the body`);
    for (const axis of [t.xLabel, t.yLabel, t.zLabel]) if (axis && !f.drawn.some((d) => d.text === axis)) out.push(`the axis name ${axis} not drawn`);
    return out;
  });
  for (const u of new Set(under)) fail(`phone ${name}: ${u}`);
  await phone.screenshot({ path: join(shots, `phone-${name}.png`) });
}
// Every draggable system dragged on the phone too (as on the desktop, then 30 frames):
// screenshots to look at, the start moved, the page still no wider than the screen.
for (const name of DRAGGABLE) {
  const before = await phone.evaluate((n) => { window.physicskitLab.select(n); return Array.from(window.physicskitLab.app.lab.initialState()); }, name);
  if (!await dragOnce(phone, name)) { fail(`phone ${name}: nothing to drag on the screen`); continue; }
  const after = await phone.evaluate(() => Array.from(window.physicskitLab.app.lab.initialState()));
  if (after.join() === before.join()) fail(`phone ${name}: a drag did not move the start`);
  await phone.evaluate(() => window.physicskitLab.runFrames(30));
  const wide = await phone.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
  if (wide > 0) fail(`phone ${name}: after a drag the page is ${wide} px wider than the screen`);
  await phone.screenshot({ path: join(shots, `phone-${name}-after-drag.png`) });
}
console.log(`ok phone drags: ${DRAGGABLE.length} draggable systems dragged at 390 px`);
await phone.evaluate(() => { document.getElementById("large").click(); window.physicskitLab.select("double-pendulum"); window.physicskitLab.runFrames(60); });
const overflow = await phone.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
if (overflow > 0) fail(`phone (large text): the page is ${overflow} px wider than the screen`);
await phone.screenshot({ path: join(shots, "phone-double-pendulum-large.png"), fullPage: true });
console.log(`ok phone layout: every system at 390 px, no overflow, scene and Run on the first screen`);

if (errors.length) fail(`console errors: ${errors.join(" | ")}`);
await browser.close();
server.close();
console.log(failures.length ? `${failures.length} failures` : "lab browser test passed");
process.exit(failures.length ? 1 : 0);
