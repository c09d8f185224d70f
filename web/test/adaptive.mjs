// The lab's adaptive methods in headless Chromium: taylor chosen from the method menu on Kepler
// and on the double pendulum, where the step control becomes a tolerance (rtol = atol) and the
// facts line gives the order used at it (Taylor's rises as it tightens, dop853's is fixed); the
// run keeps its energy to a bound that follows from the tolerance; the share link carries the
// method and the tolerance and reopens the same run bit for bit; hostile tolerances in a link
// (tol=-1, tol=NaN, a tolerance with a fixed-step method) are refused in the page's one line
// and the page runs at its default; a link from before the tolerance existed opens with nothing
// refused; no console errors.
//
//   node web/test/adaptive.mjs SITE_DIR SCREENSHOT_DIR
import { mkdirSync } from "node:fs";
import { join } from "node:path";
import { serve, launch, checks } from "./harness.mjs";

const [site, shots] = process.argv.slice(2);
mkdirSync(shots, { recursive: true });
const { server, url } = await serve(site);
const browser = await launch();
const { failures, errors, fail, open } = checks(browser, url);

// What the page shows and runs: the step controls, the lab's method, tolerance, state, energy.
const look = (page) => page.evaluate(() => {
  const L = window.physicskitLab, lab = L.app.lab, $ = (id) => document.getElementById(id);
  return {
    system: L.app.entry.name,
    method: $("method").value,
    tolMenu: $("tol").value,
    tolTexts: Array.from($("tol").options, (o) => o.textContent),
    tolShown: !$("tol-row").hidden,
    tolLabel: document.querySelector("label[for=tol]")?.textContent ?? "",
    dtShown: !$("dt").closest(".param").hidden,
    info: $("method-info").textContent,
    tolerance: lab.tolerance(),
    t: lab.time(),
    state: Array.from(lab.state()),
    energyError: lab.energyError(),
    message: $("message").textContent,
    exported: L.exportJson().tol,
    timeUnit: L.app.entry.presentation.time_unit,
    speedLabel: document.querySelector("label[for=speed]").firstChild.textContent.trim(),
  };
});

// FRAMES frames at the page's default output spacing (dt = 1e-3, 25 outputs a frame): 3 s of
// the system's time, a third of the double pendulum's chaotic swings and half a Kepler orbit
// of the catalogue's default (period 2π).
const FRAMES = 120;
// The energy error after the run, relative to |E0|. Taylor's order is chosen so that each
// step's truncation error is about tol relative to the state (`taylor.rs`: s e^{-2p} <= s ε),
// so each step moves the energy by about tol |E0|, and the steps' errors add at worst
// linearly. Over these 3 s Kepler takes 20 internal steps and the double pendulum about 110
// (at tol 1e-6 .. 1e-12, counted natively by integrate's `steps`), so 200 tol bounds the error
// with room (measured natively: at most 1.1 tol, at 1e-6 on the double pendulum); 1e-13
// absolute covers the rounding floor (|E0| of order 1, a few hundred roundings).
const bound = (tol) => 200 * tol + 1e-13;

for (const [system, tol] of [["kepler", "1e-12"], ["double-pendulum", "1e-8"]]) {
  const page = await open(`#system=${system}`);
  await page.selectOption("#method", "taylor");
  await page.selectOption("#tol", tol);
  let got = await look(page);
  if (got.method !== "taylor") fail(`${system}: taylor not chosen (${got.method})`);
  if (!got.tolShown || got.dtShown) fail(`${system} taylor: the step control is not the tolerance (tolerance shown ${got.tolShown}, dt shown ${got.dtShown})`);
  // The menu reads as a physicist writes a tolerance: powers of ten, 10⁻⁶ … 10⁻¹⁴, not
  // 0.000001 or 1e-8.
  if (!got.tolTexts.length || !got.tolTexts.every((t) => /^10⁻[¹²³⁴⁵⁶⁷⁸⁹⁰]+$/.test(t))) fail(`${system}: the tolerance menu reads ${JSON.stringify(got.tolTexts)}`);
  if (!/tolerance/i.test(got.tolLabel) || /step/i.test(got.tolLabel)) fail(`${system}: the tolerance is labelled ${JSON.stringify(got.tolLabel)}`);
  if (!/adaptive/.test(got.info) || !/order \d+/.test(got.info) || /per step per step/.test(got.info)) fail(`${system}: method facts ${JSON.stringify(got.info)}`);
  if (got.tolerance !== Number(tol)) fail(`${system}: the lab runs at ${got.tolerance}, the menu says ${tol}`);
  // The output spacing in the system's unit of time: seconds only where the catalogue says so.
  const spacing = /an output every dt = [\d.e+-]+( s\b)?/.exec(got.info);
  if (!spacing || (got.timeUnit === "s") !== Boolean(spacing[1])) fail(`${system}: the facts line's spacing ${JSON.stringify(spacing?.[0])} for a time unit ${JSON.stringify(got.timeUnit)}`);
  if (got.speedLabel !== "Outputs per frame") fail(`${system} taylor: the frame's count is labelled ${JSON.stringify(got.speedLabel)}`);
  if (got.exported !== got.tolerance) fail(`${system}: the JSON export says tol ${got.exported}, the lab runs at ${got.tolerance}`);
  // The page opens running: from the start, FRAMES frames exactly.
  const ran = await page.evaluate((n) => { window.physicskitLab.restart(); return window.physicskitLab.runFrames(n); }, FRAMES);
  got = await look(page);
  if (!ran || Math.abs(got.t - 3) > 1e-9) fail(`${system} taylor: ran ${ran} to t = ${got.t}`);
  if (!(got.energyError < bound(Number(tol)))) fail(`${system} taylor at ${tol}: energy error ${got.energyError} above ${bound(Number(tol))}`);
  await page.screenshot({ path: join(shots, `adaptive-${system}.png`), fullPage: true });
  console.log(`ok ${system} taylor at tol ${tol}: energy error ${got.energyError.toExponential(2)} at t = ${got.t.toFixed(3)} (bound ${bound(Number(tol)).toExponential(1)}); ${got.info}`);

  // The share link carries the method and the tolerance; it reopens the same run.
  const hash = await page.evaluate(() => window.physicskitLab.shareHash());
  const h = new URLSearchParams(hash.slice(1));
  if (h.get("method") !== "taylor" || h.get("tol") !== tol) fail(`${system}: link ${hash} lacks method=taylor&tol=${tol}`);
  const again = await open(hash);
  let back = await look(again);
  if (back.message !== "") fail(`${system}: its own link refused ${JSON.stringify(back.message)}`);
  if (back.method !== "taylor" || back.tolMenu !== tol || back.tolerance !== Number(tol) || !back.tolShown) {
    fail(`${system}: link reopened as ${back.method} at ${back.tolMenu} (lab ${back.tolerance})`);
  }
  await again.evaluate((n) => { window.physicskitLab.restart(); return window.physicskitLab.runFrames(n); }, FRAMES);
  back = await look(again);
  if (JSON.stringify(back.state) !== JSON.stringify(got.state)) fail(`${system}: the reopened run differs: ${back.state} vs ${got.state}`);
  console.log(`ok ${system} link ${hash.slice(0, 70)}…: reopened with taylor at ${back.tolMenu}, the same run`);

  // Back to a fixed-step method: the step control is the step again, and the link has no tol.
  await page.selectOption("#method", got.system === "kepler" ? "yoshida4" : "rk4");
  const fixed = await look(page);
  const fixedHash = await page.evaluate(() => window.physicskitLab.shareHash());
  if (fixed.speedLabel !== "Steps per frame") fail(`${system} ${fixed.method}: the frame's count is labelled ${JSON.stringify(fixed.speedLabel)}`);
  if (fixed.exported !== undefined) fail(`${system} ${fixed.method}: the JSON export carries a tolerance (${fixed.exported}) for a fixed-step method`);
  if (fixed.tolShown || !fixed.dtShown || fixedHash.includes("tol=")) fail(`${system} ${fixed.method}: tolerance shown ${fixed.tolShown}, dt shown ${fixed.dtShown}, link ${fixedHash}`);
  await page.close();
  await again.close();
}

// The facts line gives the order the method steps at with the chosen tolerance, which the
// page asks of the module (the core's rule, not a copy of it): Taylor's order rises as the
// tolerance tightens, from below its catalogue maximum, and changes with the menu; dop853's is
// its catalogue order at every tolerance. The page before said Taylor's maximum at every
// tolerance.
{
  const page = await open("#system=kepler&method=taylor");
  const catalogue = await page.evaluate(() => Object.fromEntries(
    window.physicskitLab.app.catalogue.methods.map((m) => [m.name, m.order])));
  const tols = await page.evaluate(() => [...document.getElementById("tol").options].map((o) => o.value));
  const loosestFirst = [...tols].sort((a, b) => Number(b) - Number(a));
  for (const method of ["taylor", "dop853"]) {
    await page.selectOption("#method", method);
    const orders = [];
    for (const tol of loosestFirst) {
      await page.selectOption("#tol", tol);
      const { info } = await look(page);
      const order = Number(/^order (\d+)/.exec(info)?.[1]);
      if (!(order >= 2 && order <= catalogue[method])) fail(`${method} at ${tol}: facts line ${JSON.stringify(info)} (catalogue order ${catalogue[method]})`);
      orders.push(order);
    }
    const rises = orders.every((p, i) => i === 0 || p >= orders[i - 1]);
    if (method === "taylor" && (!rises || orders[0] >= orders.at(-1) || orders[0] === catalogue.taylor)) {
      fail(`taylor's order from the loosest to the tightest tolerance: ${orders.join(", ")} (catalogue maximum ${catalogue.taylor})`);
    }
    if (method === "dop853" && !orders.every((p) => p === catalogue.dop853)) fail(`dop853's order over the tolerances: ${orders.join(", ")}`);
    console.log(`ok ${method}'s order over the tolerances ${loosestFirst.join(", ")}: ${orders.join(", ")}`);
  }
  await page.selectOption("#method", "taylor");
  await page.selectOption("#tol", loosestFirst[0]);
  await page.screenshot({ path: join(shots, "adaptive-order.png"), fullPage: true });
  await page.close();
}

// Hostile tolerances: refused in one line naming `tol`, the page opening the linked system with
// the linked method at the default tolerance, and running.
const HOSTILE = [
  "#system=kepler&method=taylor&tol=-1",
  "#system=kepler&method=taylor&tol=NaN",
  "#system=double-pendulum&method=taylor&tol=1e-300",
  "#system=double-pendulum&method=dop853&tol=%3Cb%3E1%3C%2Fb%3E",
  "#system=kepler&method=yoshida4&tol=1e-8",
];
for (const hash of HOSTILE) {
  const p = await open(hash);
  const got = await look(p);
  const why = `link ${hash}`;
  const h = new URLSearchParams(hash.slice(1));
  if (got.system !== h.get("system") || got.method !== h.get("method")) fail(`${why}: opened ${got.system} ${got.method}`);
  if (!got.message.startsWith("From the link, refused") || got.message.split("\n").length !== 1 || !got.message.includes("tol")) {
    fail(`${why}: message ${JSON.stringify(got.message)}`);
  }
  if (got.tolerance !== 1e-10 || got.tolMenu !== "1e-10") fail(`${why}: runs at ${got.tolerance} (menu ${got.tolMenu})`);
  const ran = await p.evaluate(() => { window.physicskitLab.restart(); return window.physicskitLab.runFrames(3); });
  const after = await look(p);
  if (!ran || !after.state.every(Number.isFinite)) fail(`${why}: the opened page does not run`);
  console.log(`ok hostile ${hash}: ${got.message}`);
  await p.close();
}

// Links from before adaptive methods were offered open as they did: nothing refused.
for (const hash of ["#system=kepler&method=yoshida4&dt=0.001&steps=25", "#system=double-pendulum&method=rk4&dt=0.002"]) {
  const p = await open(hash);
  const got = await look(p);
  if (got.message !== "" || got.tolShown || !got.dtShown) fail(`old link ${hash}: ${JSON.stringify(got.message)}, tolerance shown ${got.tolShown}`);
  else console.log(`ok old link ${hash}: opens, nothing refused`);
  await p.close();
}

if (errors.length) fail(`console errors: ${errors.join(" | ")}`);
await browser.close();
server.close();
console.log(failures.length ? `${failures.length} failures` : "lab adaptive test passed");
process.exit(failures.length ? 1 : 0);
