// The lab in real headless Chromium (Debian's /usr/bin/chromium, driven by playwright-core;
// no browser download). For every catalogue system it loads the page, runs 4 frames of the
// default setup (default method, dt = 1e-3, 25 steps a frame: the native reference run of
// crates/physicskit-wasm/src/bin/lab_reference.rs) and checks
//   - the energy-error readout against the native run (the text, and the number behind it
//     within the wasm/native bound of node_compare.mjs);
//   - the scene canvas is not blank and changes between frames;
//   - the physics paragraph shown is the catalogue's `physics` text (hidden when none);
// then: a share link round trip (a dragged start, reopened in a new page, runs to the same
// bits), one drag of the double pendulum's lower bob, one click on the Hénon–Heiles section,
// and no console errors. Screenshots of three systems go to the given directory.
//
//   node web/test/browser.mjs SITE_DIR NATIVE_OUTPUT SCREENSHOT_DIR
import { readFileSync, mkdirSync } from "node:fs";
import { join } from "node:path";
import { serve, launch } from "./harness.mjs";

const [site, nativeFile, shots] = process.argv.slice(2);
mkdirSync(shots, { recursive: true });
const native = new Map(readFileSync(nativeFile, "utf8").trim().split("\n")
  .map((l) => JSON.parse(l)).map((r) => [`${r.system} ${r.method}`, r]));
const num = (hex) => new DataView(new BigUint64Array([BigInt(`0x${hex}`)]).buffer).getFloat64(0, true);

const { server, url } = await serve(site);
const browser = await launch();
const failures = [];
const fail = (what) => { failures.push(what); console.log(`FAIL ${what}`); };
const errors = [];

async function open(hash = "") {
  const page = await browser.newPage({ viewport: { width: 1280, height: 900 } });
  page.on("console", (m) => { if (m.type() === "error") errors.push(m.text()); });
  page.on("pageerror", (e) => errors.push(String(e)));
  await page.goto(url + hash);
  await page.evaluate(() => window.physicskitLab.ready);
  return page;
}

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
const systems = await page.evaluate(() => window.physicskitLab.app.catalogue.systems.map((s) => [s.name, s.default_method]));
const SHOTS = ["double-pendulum", "henon-heiles", "pendulum-swarm", "heavy-top"];
for (const [name, method] of systems) {
  await page.evaluate((n) => window.physicskitLab.select(n), name);
  const before = await sceneInk(page);
  const ok = await page.evaluate(() => window.physicskitLab.runFrames(4));
  const after = await sceneInk(page);
  const readout = await page.locator("#energy-error").textContent();
  const exact = await page.evaluate(() => window.physicskitLab.app.lab.energyError());
  const ref = native.get(`${name} ${method}`);
  if (!ok || !ref || ref.error) { fail(`${name}: run failed or no native reference`); continue; }
  const want = num(ref.energy_error);
  // The readout shows 4 significant digits; the number behind it must be the native one
  // (bit for bit but for the libm-bound systems, see node_compare.mjs: 1e-14 of the energy).
  if (readout !== want.toExponential(3)) fail(`${name}: readout ${readout}, native ${want.toExponential(3)}`);
  if (Math.abs(exact - want) > 1e-14) fail(`${name}: energy error ${exact} vs native ${want}`);
  // Non-blank: at least 200 inked pixels (a body of radius 10 alone has ~300; an empty
  // canvas with its axis labels ~100 at most).
  if (after.ink < 200) fail(`${name}: scene nearly blank (${after.ink} inked pixels)`);
  // A system at rest (the sine-Gordon chain's zero state) has nothing to move.
  const atRest = await page.evaluate(() => window.physicskitLab.app.lab.state().every((x) => x === 0));
  if (after.hash === before.hash && !atRest) fail(`${name}: scene did not change between frames`);
  // The physics paragraph shown is the catalogue's (the gallery's text for the system, checked
  // against the rendered gallery in crates/physicskit-viz/tests/gallery.rs), shown only if any.
  const physics = await page.evaluate(() => window.physicskitLab.app.entry.physics);
  const shown = await page.locator("#about").isVisible() ? await page.locator("#physics").textContent() : null;
  if (shown !== physics) fail(`${name}: physics paragraph ${JSON.stringify(shown)?.slice(0, 60)} vs catalogue ${JSON.stringify(physics)?.slice(0, 60)}`);
  console.log(`ok ${name} (${method}): energy error ${readout}, ${after.ink} inked pixels`);
  if (SHOTS.includes(name)) {
    await page.evaluate(() => window.physicskitLab.runFrames(120));
    await page.screenshot({ path: join(shots, `${name}.png`), fullPage: true });
  }
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
await page2.evaluate(() => window.physicskitLab.runFrames(4));
const second = await page2.evaluate(() => [Array.from(window.physicskitLab.app.lab.state()), window.physicskitLab.app.lab.energyError()]);
if (opened[0] !== "double-pendulum" || opened[1] !== "rk4") fail(`share: opened ${opened[0]} with ${opened[1]}`);
if (JSON.stringify(opened[2]) !== JSON.stringify(q1)) fail("share: initial state differs");
if (JSON.stringify(second) !== JSON.stringify(first)) fail("share: the reopened run differs");
console.log(`ok share link: ${hash.length} characters, reopened run identical`);
await page2.close();

// Hénon–Heiles: a click on the section at (x, px) = (0.1, 0) launches an orbit there at the
// same energy (y = 0, py > 0 solved), and its crossings accumulate.
await page.evaluate(() => window.physicskitLab.select("henon-heiles"));
const e0 = await page.evaluate(() => window.physicskitLab.app.lab.energy0());
const [cx, cy] = await page.evaluate(() => window.physicskitLab.sectionToScreen(0.1, 0.0));
await page.mouse.click(cx, cy);
const s = await page.evaluate(() => Array.from(window.physicskitLab.app.lab.state()));
const [lx, ly] = await page.evaluate(([x, px]) => window.physicskitLab.sectionToScreen(x, px), [s[0], s[2]]);
// The orbit starts where the click was, to a screen pixel (the mouse position is whole CSS
// pixels); y exactly on the section, py > 0 (the section's direction).
if (Math.hypot(lx - cx, ly - cy) > 1 || s[1] !== 0 || !(s[3] > 0)) fail(`section: launched at ${s}, on screen ${[lx, ly]} vs click ${[cx, cy]}`);
const e1 = await page.evaluate(() => window.physicskitLab.app.lab.energy());
// The solved py puts the energy on E0 to the last bits of the bisection.
if (Math.abs(e1 - e0) > 1e-14) fail(`section: energy ${e1} vs ${e0}`);
// 200 frames of 400 steps of 1e-3: 80 time units, about 12 periods of the x oscillation
// (2 pi), so about a dozen upward crossings of y = 0.
await page.evaluate(() => { document.getElementById("speed").value = 400; window.physicskitLab.runFrames(200); });
const crossings = await page.evaluate(() => window.physicskitLab.app.lab.crossings().length / 4);
if (crossings < 5) fail(`section: ${crossings} crossings after 80 time units`);
console.log(`ok section click: launched at x = ${s[0].toFixed(4)}, px = ${s[2].toFixed(4)}, ${crossings} crossings`);
await page.screenshot({ path: join(shots, "henon-heiles-section.png"), fullPage: true });

// A phone-sized screen with the large-text option: one column, nothing wider than the screen.
const phone = await browser.newPage({ viewport: { width: 390, height: 844 } });
phone.on("pageerror", (e) => errors.push(String(e)));
await phone.goto(`${url}#system=double-pendulum`);
await phone.evaluate(() => window.physicskitLab.ready);
await phone.evaluate(() => { document.getElementById("large").click(); window.physicskitLab.runFrames(60); });
const overflow = await phone.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
if (overflow > 0) fail(`phone: the page is ${overflow} px wider than the screen`);
await phone.screenshot({ path: join(shots, "phone-double-pendulum.png"), fullPage: true });
console.log(`ok phone layout (${overflow} px overflow)`);

if (errors.length) fail(`console errors: ${errors.join(" | ")}`);
await browser.close();
server.close();
console.log(failures.length ? `${failures.length} failures` : "lab browser test passed");
process.exit(failures.length ? 1 : 0);
