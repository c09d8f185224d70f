// The lab benchmark in headless Chromium (not a test; benchmarks/README.md records it):
//   - steps per second of the WebAssembly core for the systems of lab_bench.rs, in the same
//     frames (16 steps of 1 ms, default method), to set against the native figures;
//   - whole frames (step and draw all panels) per second of the page itself for the double
//     pendulum at dt = 1e-3 with 16 steps a frame and the 1000-pendulum swarm;
//   - the rolling bodies' energy error over 10 s with rk4 at each step, at real time.
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
// The step of the rolling bodies (the catalogue's default method, dop853, is adaptive, which
// a frame-by-frame run cannot take): rk4 at each step with 1/60 s of motion a frame (real time
// at 60 frames a second), 10 s of motion, the largest energy error over it and the time a
// frame's steps take. The page opens each at the largest step whose error stays below 1e-8
// (STEP_DEFAULTS in lab.js).
for (const name of ["rolling-rattleback", "rolling-disk", "rolling-disk-steady"]) {
  for (const dt of [1e-3, 5e-4, 2e-4, 1e-4]) {
    const row = await page.evaluate(([n, step]) => {
      const lab = window.physicskitLab.app.core.build(n, {});
      lab.setMethod("rk4");
      const steps = Math.round(1 / 60 / step);
      let worst = 0, frames = 0;
      const t0 = performance.now();
      while (lab.time() < 10) { lab.step(steps, step); frames++; worst = Math.max(worst, lab.energyError()); }
      const ms = (performance.now() - t0) / frames;
      lab.free();
      return { system: n, method: "rk4", dt: step, steps_per_frame: steps, max_energy_error_10s: Number(worst.toPrecision(3)), ms_per_frame: Number(ms.toFixed(3)) };
    }, [name, dt]);
    console.log(JSON.stringify(row));
  }
}
await browser.close();
server.close();
