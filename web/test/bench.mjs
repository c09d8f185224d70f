// The lab benchmark in headless Chromium (not a test; benchmarks/README.md records it):
//   - steps per second of the WebAssembly core for the systems of lab_bench.rs, in the same
//     frames (16 steps of 1 ms, default method), to set against the native figures;
//   - whole frames (step and draw all panels) per second of the page itself for the double
//     pendulum at dt = 1e-3 with 16 steps a frame and the 1000-pendulum swarm.
//
//   node web/test/bench.mjs SITE_DIR
import { createServer } from "node:http";
import { readFileSync } from "node:fs";
import { extname, join } from "node:path";
import { chromium } from "playwright-core";

const [site] = process.argv.slice(2);
const types = { ".html": "text/html", ".js": "text/javascript", ".css": "text/css", ".wasm": "application/wasm" };
const server = createServer((req, res) => {
  const path = join(site, new URL(req.url, "http://x").pathname);
  try { const b = readFileSync(path); res.writeHead(200, { "content-type": types[extname(path)] ?? "" }); res.end(b); }
  catch { res.writeHead(404); res.end(); }
});
await new Promise((ok) => server.listen(0, "127.0.0.1", ok));
const browser = await chromium.launch({
  executablePath: "/usr/bin/chromium",
  args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync"],
});
const page = await browser.newPage({ viewport: { width: 1280, height: 900 } });
await page.goto(`http://127.0.0.1:${server.address().port}/index.html`);
await page.evaluate(() => window.physicskitLab.ready);
for (const name of ["double-pendulum", "henon-heiles", "pendulum-swarm"]) {
  const rate = await page.evaluate((n) => {
    const lab = window.physicskitLab.app.core.build(n, {});
    lab.step(16, 1e-3);
    const t0 = performance.now();
    let steps = 0;
    while (performance.now() - t0 < 1000) { lab.step(16, 1e-3); steps += 16; }
    const rate = steps / ((performance.now() - t0) / 1000);
    lab.free();
    return rate;
  }, name);
  console.log(JSON.stringify({ system: name, wasm_steps_per_second: Math.round(rate) }));
}
for (const name of ["double-pendulum", "pendulum-swarm"]) {
  const ms = await page.evaluate((n) => {
    const L = window.physicskitLab;
    L.select(n);
    document.getElementById("speed").value = 16;
    L.runFrames(1);
    const t0 = performance.now();
    let frames = 0;
    while (performance.now() - t0 < 2000) { L.runFrames(1); frames++; }
    return (performance.now() - t0) / frames;
  }, name);
  console.log(JSON.stringify({ system: name, page_ms_per_frame: Number(ms.toFixed(2)), frames_per_second_possible: Math.round(1000 / ms) }));
}
await browser.close();
server.close();
