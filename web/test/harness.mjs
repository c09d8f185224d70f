// What the browser test and the benchmark share: a static server for the built site on a
// free localhost port, and Debian's Chromium launched headless with the flags this machine
// needs (no sandbox as root; no background networking, whose connections the closed network
// refuses).
import { createServer } from "node:http";
import { readFileSync } from "node:fs";
import { extname, join } from "node:path";
import { chromium } from "playwright-core";

const TYPES = { ".html": "text/html", ".js": "text/javascript", ".css": "text/css", ".wasm": "application/wasm" };

/** Serves `site`; returns the server and the page's address. */
export async function serve(site) {
  const server = createServer((req, res) => {
    const path = join(site, decodeURIComponent(new URL(req.url, "http://x").pathname).replace(/\/$/, "/index.html"));
    try {
      const body = readFileSync(path);
      res.writeHead(200, { "content-type": TYPES[extname(path)] ?? "application/octet-stream" });
      res.end(body);
    } catch {
      res.writeHead(404);
      res.end();
    }
  });
  await new Promise((ok) => server.listen(0, "127.0.0.1", ok));
  return { server, url: `http://127.0.0.1:${server.address().port}/index.html` };
}

/** Launches /usr/bin/chromium headless. */
export function launch() {
  return chromium.launch({
    executablePath: "/usr/bin/chromium",
    args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
      "--disable-background-networking", "--disable-component-update", "--disable-sync"],
  });
}

/**
 * One test run's bookkeeping: `fail(what)` records and prints a failure into `failures`, and
 * `open(hash)` opens the lab at `url + hash` (1280 × 900) once its core is ready, collecting
 * the page's console errors and uncaught exceptions into `errors`.
 */
export function checks(browser, url) {
  const failures = [], errors = [];
  const fail = (what) => { failures.push(what); console.log(`FAIL ${what}`); };
  async function open(hash = "") {
    const page = await browser.newPage({ viewport: { width: 1280, height: 900 } });
    page.on("console", (m) => { if (m.type() === "error") errors.push(m.text()); });
    page.on("pageerror", (e) => errors.push(String(e)));
    await page.goto(url + hash);
    await page.evaluate(() => window.physicskitLab.ready);
    return page;
  }
  return { failures, errors, fail, open };
}
