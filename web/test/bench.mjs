// The lab benchmark in headless Chromium (not a test; benchmarks/README.md records it):
//   - steps per second of the WebAssembly core for the systems of lab_bench.rs, in the same
//     frames (16 steps of 1 ms, default method), to set against the native figures;
//   - whole frames (step and draw all panels) per second of the page itself for the double
//     pendulum at dt = 1e-3 with 16 steps a frame and the 1000-pendulum swarm.
//
//   node web/test/bench.mjs SITE_DIR
import { serve, launch } from "./harness.mjs";

const [site] = process.argv.slice(2);
const { server, url } = await serve(site);
const browser = await launch();
const page = await browser.newPage({ viewport: { width: 1280, height: 900 } });
await page.goto(url);
await page.evaluate(() => window.physicskitLab.ready);
for (const name of ["double-pendulum", "henon-heiles", "pendulum-swarm"]) {
  for (const frame of [16, 10000]) {
    const rate = await page.evaluate(([n, f]) => {
      const lab = window.physicskitLab.app.core.build(n, {});
      lab.step(f, 1e-3);
      const t0 = performance.now();
      let steps = 0;
      while (performance.now() - t0 < 1000) { lab.step(f, 1e-3); steps += f; }
      const rate = steps / ((performance.now() - t0) / 1000);
      lab.free();
      return rate;
    }, [name, frame]);
    console.log(JSON.stringify({ system: name, steps_per_frame: frame, wasm_steps_per_second: Math.round(rate) }));
  }
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
